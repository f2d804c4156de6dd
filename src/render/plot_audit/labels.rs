//! Greedy placement of annotations so they overlap neither each other nor the lines drawn.

use super::{Rect, text_box};
use crate::render::plot::svg::spread;

/// Markers further apart than this (pixels) get their callouts in separate columns.
const CLUSTER_GAP: i32 = 160;

fn overlaps(a: &Rect, b: &Rect) -> bool {
    a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3]
}

/// Greedy placement of text labels: each goes to the first spot around its anchor, nearest
/// first, that overlaps no earlier label or blocked box and stays inside `bounds`; where the
/// curves leave no such spot, to the nearest one straight above or below that overlaps no
/// label or marker (over a curve), joined to its anchor by a leader.
pub(crate) struct Labels {
    bounds: Rect,
    /// Labels, markers and keys: nothing is placed over them.
    taken: Vec<Rect>,
    /// The curves, in small boxes: avoided while there is room elsewhere.
    curves: Vec<Rect>,
    /// The labels placed (leader lines must not cross them).
    texts: Vec<Rect>,
}

impl Labels {
    pub(crate) fn new(bounds: Rect) -> Self {
        Labels {
            bounds,
            taken: vec![],
            curves: vec![],
            texts: vec![],
        }
    }

    pub(crate) fn block(&mut self, r: Rect) {
        self.taken.push(r);
    }

    /// Takes `r` if it is inside the bounds and free.
    pub(crate) fn take(&mut self, r: Rect) -> bool {
        let b = self.bounds;
        let inside = r[0] >= b[0] && r[1] >= b[1] && r[2] <= b[2] && r[3] <= b[3];
        let free = inside && self.free(&r);
        if free {
            self.taken.push(r);
            self.texts.push(r);
        }
        free
    }

    /// Top-left corner for a `w` x `h` box in the first free corner of `bounds` (bottom-left,
    /// top-right, bottom-right, top-left), else bottom-left; the box is taken.
    pub(crate) fn corner(&mut self, w: i32, h: i32) -> (i32, i32) {
        let [x0, y0, x1, y1] = self.bounds;
        let spots = [
            (x0 + 8, y1 - 8 - h),
            (x1 - 8 - w, y0 + 8),
            (x1 - 8 - w, y1 - 8 - h),
            (x0 + 8, y0 + 8),
        ];
        let free = |p: &(i32, i32)| self.free(&[p.0, p.1, p.0 + w, p.1 + h]);
        let p = spots.iter().copied().find(free).unwrap_or(spots[0]);
        self.taken.push([p.0, p.1, p.0 + w, p.1 + h]);
        p
    }

    /// Blocks a drawn line: small boxes every few pixels along it.
    pub(crate) fn block_path(&mut self, path: &[(i32, i32)]) {
        for p in path.windows(2) {
            let (dx, dy) = (p[1].0 - p[0].0, p[1].1 - p[0].1);
            let n = (dx.abs().max(dy.abs()) / 4).clamp(1, 2000);
            for k in 0..=n {
                let (x, y) = (p[0].0 + dx * k / n, p[0].1 + dy * k / n);
                self.curves.push([x - 2, y - 2, x + 2, y + 2]);
            }
        }
    }

    /// Top-left corner for `text` near `at`: the nearest free spot, right of it first unless
    /// `left`, whose leader line crosses no other label; the box and the leader are taken.
    /// Without one, the nearest free spot; without room, the nearest spot inside `bounds`.
    pub(crate) fn place(
        &mut self,
        at: (i32, i32),
        text: &str,
        size: u32,
        left: bool,
    ) -> (i32, i32) {
        let (w, h) = text_box(text, size);
        let (x, y) = at;
        let mut spots = vec![];
        for step in 0..14 {
            let d = 4 + step * (h / 2 + 2);
            for (k, px) in [x + 7, x - 7 - w, x - w / 2].into_iter().enumerate() {
                let side = if k == 2 {
                    2
                } else {
                    i32::from((k == 1) != left)
                };
                for shift in [0, 50, 100, 160] {
                    let px = if k == 1 { px - shift } else { px + shift };
                    spots.push(([px, y - d - h, px + w, y - d], side));
                    spots.push(([px, y + d, px + w, y + d + h], side));
                }
            }
        }
        spots.sort_by_key(|(r, side)| {
            let n = nearest(at, r);
            ((n.0 - x).abs() + (n.1 - y).abs()) / 10 * 4 + side
        });
        let b = self.bounds;
        let inside = |r: &Rect| r[0] >= b[0] && r[1] >= b[1] && r[2] <= b[2] && r[3] <= b[3];
        // Fallbacks: the nearest free spot whose leader crosses a label, the nearest spot.
        let (mut first, mut crossing) = (None, None);
        for (r, _) in spots.into_iter().filter(|(r, _)| inside(r)) {
            first.get_or_insert(r);
            if !self.free(&r) {
                continue;
            }
            let n = nearest(at, &r);
            let far = (n.0 - x).abs() + (n.1 - y).abs() > 10;
            let steps = ((n.0 - x).abs().max((n.1 - y).abs()) / 3).max(1);
            let crosses = far
                && (0..=steps).any(|k| {
                    let p = (x + (n.0 - x) * k / steps, y + (n.1 - y) * k / steps);
                    self.texts.iter().any(|t| {
                        t[0] - 2 <= p.0 && p.0 <= t[2] + 2 && t[1] - 2 <= p.1 && p.1 <= t[3] + 2
                    })
                });
            if crosses {
                crossing.get_or_insert(r);
                continue;
            }
            if far {
                self.block_path(&[at, n]);
            }
            self.taken.push(r);
            self.texts.push(r);
            return (r[0], r[1]);
        }
        let r = crossing
            .or_else(|| self.stacked(at, (w, h), left))
            .or(first)
            .unwrap_or([x + 7, y - h - 4, x + 7 + w, y - 4]);
        self.taken.push(r);
        self.texts.push(r);
        (r[0], r[1])
    }

    /// Boxes for the callouts of markers `at` (`sizes` each), laid out as columns of
    /// labels: the markers grouped where they lie within [`CLUSTER_GAP`] of each other
    /// across (a group taller than the plot split), each group's labels in one column, in the
    /// order of their markers from top to bottom and each as near its marker's height as the
    /// others leave room for (a greedy vertical de-overlap). The column goes as near the group
    /// as it meets no label or marker, right of it first; it may cross the curves (the
    /// callouts are drawn on a white ground). A label its column has no room for goes to the
    /// nearest free spot straight above or below its marker. Every box is taken.
    pub(crate) fn columns(&mut self, at: &[(i32, i32)], sizes: &[(i32, i32)]) -> Vec<Rect> {
        let b = self.bounds;
        let mut order: Vec<usize> = (0..at.len()).collect();
        order.sort_by_key(|&i| at[i].0);
        let mut groups: Vec<Vec<usize>> = vec![];
        let mut height = 0;
        for i in order {
            let h = sizes[i].1 + 2;
            match groups.last_mut() {
                Some(g)
                    if at[i].0 - at[g[g.len() - 1]].0 <= CLUSTER_GAP
                        && height + h <= b[3] - b[1] - 4 =>
                {
                    g.push(i);
                    height += h;
                }
                _ => {
                    groups.push(vec![i]);
                    height = h;
                }
            }
        }
        let mut out: Vec<Option<Rect>> = vec![None; at.len()];
        // Right to left: a group on the right has least room, those on the left the plot.
        for mut g in groups.into_iter().rev() {
            g.sort_by_key(|&i| at[i].1);
            let w = g.iter().map(|&i| sizes[i].0).max().unwrap_or(0);
            let h = g.iter().map(|&i| sizes[i].1).max().unwrap_or(0);
            let ys: Vec<f64> = g.iter().map(|&i| f64::from(at[i].1 - h / 2)).collect();
            let ys = spread(
                &ys,
                f64::from(h + 2),
                f64::from(b[1] + 2),
                f64::from(b[3] - 2 - h),
            );
            let column = |x: i32| -> Vec<Rect> {
                g.iter()
                    .zip(&ys)
                    .map(|(&i, &y)| [x, y as i32, x + sizes[i].0, y as i32 + sizes[i].1])
                    .collect()
            };
            let clashes = |r: &[Rect]| {
                r.iter()
                    .filter(|q| self.taken.iter().any(|t| overlaps(t, q)))
                    .count()
            };
            // Right of the group, then left of it, nearest first.
            let x_hi = g.iter().map(|&i| at[i].0).max().unwrap_or(0) + 14;
            let x_lo = g.iter().map(|&i| at[i].0).min().unwrap_or(0) - 14 - w;
            let right = (x_hi.max(b[0] + 2)..=b[2] - 2 - w)
                .step_by(6)
                .map(|x| (x - x_hi, x));
            let left = (b[0] + 2..=x_lo.min(b[2] - 2 - w)).rev().step_by(6);
            let left = left.map(|x| (x_lo - x + 3, x));
            let best = right
                .chain(left)
                .map(|(d, x)| (clashes(&column(x)), d, x))
                .min();
            let Some((_, _, x)) = best else { continue };
            for (&i, r) in g.iter().zip(column(x)) {
                if !self.taken.iter().any(|t| overlaps(t, &r)) {
                    self.taken.push(r);
                    self.texts.push(r);
                    out[i] = Some(r);
                }
            }
        }
        (0..at.len())
            .map(|i| {
                out[i].unwrap_or_else(|| {
                    let (w, h) = sizes[i];
                    let r = self.stacked(at[i], (w, h), false).unwrap_or([
                        at[i].0 + 9,
                        at[i].1 - h / 2,
                        at[i].0 + 9 + w,
                        at[i].1 + h - h / 2,
                    ]);
                    self.taken.push(r);
                    self.texts.push(r);
                    r
                })
            })
            .collect()
    }

    /// Whether `r` overlaps nothing drawn (labels, markers, curves).
    fn free(&self, r: &Rect) -> bool {
        !self
            .taken
            .iter()
            .chain(&self.curves)
            .any(|t| overlaps(t, r))
    }

    /// A `w` x `h` box beside `at` (right of it first unless `left`) moved straight up or
    /// down, nearest first, to the first place inside `bounds` that overlaps no label or
    /// marker; curves may run under it. With no such place on either side, the free place
    /// nearest to `at` anywhere in `bounds`; None when there is none.
    fn stacked(&self, at: (i32, i32), (w, h): (i32, i32), left: bool) -> Option<Rect> {
        let b = self.bounds;
        let fits = |x: &i32| *x >= b[0] && *x + w <= b[2];
        let (right, other) = (at.0 + 9, at.0 - 9 - w);
        let sides = if left { [other, right] } else { [right, other] };
        for x in sides.into_iter().filter(fits) {
            if let Some((_, r)) = self.free_column(x, (w, h), at.1) {
                return Some(r);
            }
        }
        (b[0]..=b[2] - w)
            .step_by(6)
            .filter_map(|x| {
                let dx = (x - right).abs().min((x - other).abs());
                self.free_column(x, (w, h), at.1)
                    .map(|(dy, r)| (dx + dy, r))
            })
            .min_by_key(|(d, _)| *d)
            .map(|(_, r)| r)
    }

    /// The free `w` x `h` box at `x` whose middle is nearest to the height `y` (and that
    /// distance), overlapping no label or marker, inside `bounds`.
    fn free_column(&self, x: i32, (w, h): (i32, i32), y: i32) -> Option<(i32, Rect)> {
        let b = self.bounds;
        let mut best: Option<(i32, Rect)> = None;
        let mut top = b[1];
        while top + h <= b[3] {
            let r = [x, top, x + w, top + h];
            match self.taken.iter().find(|t| overlaps(t, &r)) {
                // Past what is in the way.
                Some(t) => top = top.max(t[3] + 1),
                None => {
                    let d = (top + h / 2 - y).abs();
                    if best.is_none_or(|(e, _)| d < e) {
                        best = Some((d, r));
                    }
                    if top + h / 2 >= y {
                        // Every place further down is further away.
                        break;
                    }
                    top += 1;
                }
            }
        }
        best
    }
}

/// The point of `r` nearest to `p`.
pub(super) fn nearest(p: (i32, i32), r: &Rect) -> (i32, i32) {
    (p.0.clamp(r[0], r[2]), p.1.clamp(r[1], r[3]))
}
