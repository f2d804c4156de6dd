//! Greedy placement of annotations so they overlap neither each other nor the lines drawn.

use super::{Rect, text_box};

fn overlaps(a: &Rect, b: &Rect) -> bool {
    a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3]
}

/// Greedy placement of text labels: each goes to the first spot around its anchor, nearest
/// first, that overlaps no earlier label or blocked box and stays inside `bounds`.
pub(crate) struct Labels {
    bounds: Rect,
    taken: Vec<Rect>,
    /// The labels placed (leader lines must not cross them).
    texts: Vec<Rect>,
}

impl Labels {
    pub(crate) fn new(bounds: Rect) -> Self {
        Labels {
            bounds,
            taken: vec![],
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
        let free = inside && !self.taken.iter().any(|t| overlaps(t, &r));
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
        let free = |p: &(i32, i32)| {
            let r = [p.0, p.1, p.0 + w, p.1 + h];
            !self.taken.iter().any(|t| overlaps(t, &r))
        };
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
                self.taken.push([x - 2, y - 2, x + 2, y + 2]);
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
            if self.taken.iter().any(|t| overlaps(t, &r)) {
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
            .or(first)
            .unwrap_or([x + 7, y - h - 4, x + 7 + w, y - 4]);
        self.taken.push(r);
        self.texts.push(r);
        (r[0], r[1])
    }
}

/// The point of `r` nearest to `p`.
pub(super) fn nearest(p: (i32, i32), r: &Rect) -> (i32, i32) {
    (p.0.clamp(r[0], r[2]), p.1.clamp(r[1], r[3]))
}
