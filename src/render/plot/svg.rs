//! A small SVG writer for the analysis plots: sub-pixel paths, `stroke-dasharray` dashes,
//! segments clipped to their plotting area, nice ticks (1, 2, 5 x 10^k) with as many decimals as the step
//! needs. Every plotting area is a `<rect>` framed in [`FRAME`] carrying its axis ranges as
//! `data-x="lo hi"`, `data-y="lo hi"` and `data-scale="lin|log"` (x, y), so a reader of the
//! SVG can map its paths back to data.

use std::fmt::Write;

pub use super::axis::{Axis, extent, length_unit, nice_step, sig, tick_label};

/// Colour of the frame around every plotting area.
pub(crate) const FRAME: &str = "#505050";
pub(crate) const GRID: &str = "#EBEBEB";
pub(crate) const INK: &str = "#1E1E1E";
pub(crate) const FONT: &str = "sans-serif";

/// XML text escaping.
pub fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// A plotting area in pixels `[x0, y0, x1, y1]` (y down) with its axes.
#[derive(Clone, Debug)]
pub struct Panel {
    pub rect: [f64; 4],
    pub x: Axis,
    pub y: Axis,
}

impl Panel {
    /// Pixel position of the data point `(x, y)`.
    pub fn px(&self, (x, y): (f64, f64)) -> (f64, f64) {
        let [x0, y0, x1, y1] = self.rect;
        (
            x0 + self.x.frac(x) * (x1 - x0),
            y1 - self.y.frac(y) * (y1 - y0),
        )
    }

    /// The data point at pixel `(px, py)` (the inverse of [`Panel::px`]).
    pub fn data(&self, (px, py): (f64, f64)) -> (f64, f64) {
        let [x0, y0, x1, y1] = self.rect;
        (
            self.x.value((px - x0) / (x1 - x0)),
            self.y.value((y1 - py) / (y1 - y0)),
        )
    }

    pub fn contains(&self, (x, y): (f64, f64)) -> bool {
        let t = (self.x.frac(x), self.y.frac(y));
        (-1e-9..=1.0 + 1e-9).contains(&t.0) && (-1e-9..=1.0 + 1e-9).contains(&t.1)
    }
}

/// Stroke of a line: colour, width, dashes (`stroke-dasharray`), opacity.
#[derive(Clone, Copy)]
pub struct Stroke<'a> {
    pub color: &'a str,
    pub width: f64,
    pub dash: Option<&'a str>,
    pub opacity: f64,
}

impl<'a> Stroke<'a> {
    pub fn solid(color: &'a str, width: f64) -> Self {
        Stroke {
            color,
            width,
            dash: None,
            opacity: 1.0,
        }
    }

    pub fn dashed(color: &'a str, width: f64, dash: &'a str) -> Self {
        Stroke {
            dash: Some(dash),
            ..Stroke::solid(color, width)
        }
    }

    fn attrs(&self) -> String {
        let mut s = format!(
            "fill=\"none\" stroke=\"{}\" stroke-width=\"{}\" stroke-linejoin=\"round\"",
            self.color, self.width
        );
        if let Some(d) = self.dash {
            let _ = write!(s, " stroke-dasharray=\"{d}\"");
        }
        if self.opacity < 1.0 {
            let _ = write!(s, " stroke-opacity=\"{}\"", self.opacity);
        }
        s
    }
}

/// Where a text sits relative to its point.
#[derive(Clone, Copy, PartialEq)]
pub enum Anchor {
    Start,
    Middle,
    End,
}

/// An SVG document being written.
pub struct Svg {
    out: String,
    /// Pixels covered by lines and text so far (where a key should not go).
    drawn: Vec<(f64, f64)>,
    /// The paper's nondimensional rotor: axis titles and speeds name no physical unit.
    nondimensional: bool,
}

impl Svg {
    pub fn new(w: u32, h: u32) -> Self {
        let mut out = String::new();
        let _ = write!(
            out,
            "<svg width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\" \
             xmlns=\"http://www.w3.org/2000/svg\" font-family=\"{FONT}\">\n\
             <rect x=\"0\" y=\"0\" width=\"{w}\" height=\"{h}\" fill=\"#FFFFFF\"/>\n"
        );
        Svg {
            out,
            drawn: vec![],
            nondimensional: false,
        }
    }

    /// Speeds, frequencies and decay rates in units of sqrt(k/m), times in sqrt(m/k) (the
    /// nondimensional Jeffcott rotor): axis titles and speed labels say so, without rad/s,
    /// 1/s, s or rpm, and there is no rpm axis.
    pub fn nondimensional(mut self, on: bool) -> Self {
        self.nondimensional = on;
        self
    }

    /// A speed `w` as the plot labels it: `"123.4 rad/s (1178 rpm)"`, or `"Ω* = 1.00"`.
    pub fn speed_label(&self, w: f64) -> String {
        super::speed_label_in(w, self.nondimensional)
    }

    /// A whirl frequency `f` in a key: `"ω = 123.4 rad/s"`, or `"ω* = 1.00"`.
    pub fn frequency_label(&self, f: f64) -> String {
        if self.nondimensional {
            format!("ω* = {f:.2}")
        } else {
            format!("ω = {f:.1} rad/s")
        }
    }

    pub fn finish(mut self) -> String {
        self.out.push_str("</svg>\n");
        self.out
    }

    /// A plotting area (not yet drawn: see [`Svg::axes`]); lines drawn on it are clipped to it.
    pub fn panel(&mut self, rect: [f64; 4], x: Axis, y: Axis) -> Panel {
        Panel { rect, x, y }
    }

    /// Grid, frame, ticks and axis titles of `p`.
    pub fn axes(&mut self, p: &Panel, x_desc: &str, y_desc: &str) {
        let [x0, y0, x1, y1] = p.rect;
        let (x_desc, y_desc) = if self.nondimensional {
            (super::unit_free(x_desc), super::unit_free(y_desc))
        } else {
            (x_desc.to_string(), y_desc.to_string())
        };
        for (v, label) in p.x.ticks(8) {
            let (x, _) = p.px((v, p.y.lo));
            self.line_px(&[(x, y0), (x, y1)], Stroke::solid(GRID, 1.0));
            self.line_px(&[(x, y1), (x, y1 + 5.0)], Stroke::solid(INK, 1.0));
            self.text((x, y1 + 19.0), &label, 12.0, Anchor::Middle, INK);
        }
        for (v, label) in p.y.ticks(6) {
            let (_, y) = p.px((p.x.lo, v));
            self.line_px(&[(x0, y), (x1, y)], Stroke::solid(GRID, 1.0));
            self.line_px(&[(x0 - 5.0, y), (x0, y)], Stroke::solid(INK, 1.0));
            self.text((x0 - 8.0, y + 4.0), &label, 12.0, Anchor::End, INK);
        }
        let scale = |a: &Axis| if a.log { "log" } else { "lin" };
        let _ = writeln!(
            self.out,
            "<rect x=\"{x0:.2}\" y=\"{y0:.2}\" width=\"{:.2}\" height=\"{:.2}\" fill=\"none\" \
             stroke=\"{FRAME}\" stroke-width=\"1\" data-x=\"{} {}\" data-y=\"{} {}\" \
             data-scale=\"{} {}\"/>",
            x1 - x0,
            y1 - y0,
            p.x.lo,
            p.x.hi,
            p.y.lo,
            p.y.hi,
            scale(&p.x),
            scale(&p.y)
        );
        self.text(
            ((x0 + x1) / 2.0, y1 + 38.0),
            &x_desc,
            13.0,
            Anchor::Middle,
            INK,
        );
        self.text_rotated((x0 - 58.0, (y0 + y1) / 2.0), &y_desc, 13.0);
    }

    /// A second x axis on top of `p` in units `factor` times its own (rpm of rad/s); none on
    /// a nondimensional plot.
    pub fn top_axis(&mut self, p: &Panel, factor: f64, desc: &str) {
        if self.nondimensional {
            return;
        }
        let [x0, y0, x1, _] = p.rect;
        let a = Axis::lin(p.x.lo * factor, p.x.hi * factor);
        for (v, label) in a.ticks(8) {
            let x = x0 + a.frac(v) * (x1 - x0);
            self.line_px(&[(x, y0 - 5.0), (x, y0)], Stroke::solid(INK, 1.0));
            self.text((x, y0 - 9.0), &label, 12.0, Anchor::Middle, INK);
        }
        self.text(
            ((x0 + x1) / 2.0, y0 - 27.0),
            desc,
            13.0,
            Anchor::Middle,
            INK,
        );
    }

    pub fn caption(&mut self, at: (f64, f64), s: &str) {
        self.text_sized(at, s, 18.0, Anchor::Middle, INK, "bold");
    }

    /// A polyline of data points clipped to `p`; non-finite points break it.
    pub fn path(&mut self, p: &Panel, pts: &[(f64, f64)], stroke: Stroke<'_>, class: &str) {
        let px: Vec<Option<(f64, f64)>> = pts
            .iter()
            .map(|&(x, y)| {
                let ok = x.is_finite()
                    && y.is_finite()
                    && (!p.x.log || x > 0.0)
                    && (!p.y.log || y > 0.0);
                ok.then(|| p.px((x, y)))
            })
            .collect();
        let mut d = String::new();
        let mut pen: Option<(f64, f64)> = None;
        let single = px.len() == 1;
        for k in 0..px.len() {
            let (a, b) = match (px[k], px.get(k + 1).copied().flatten()) {
                (Some(a), Some(b)) => (a, b),
                (Some(a), None) if single => (a, a),
                _ => {
                    pen = None;
                    continue;
                }
            };
            let Some((a, b)) = clip_segment(a, b, p.rect) else {
                pen = None;
                continue;
            };
            let joined = pen.is_some_and(|q| (q.0 - a.0).abs() < 1e-9 && (q.1 - a.1).abs() < 1e-9);
            if !joined {
                let _ = write!(d, "M{:.2},{:.2} ", a.0, a.1);
                self.drawn.push(a);
            }
            let _ = write!(d, "L{:.2},{:.2} ", b.0, b.1);
            let n = ((b.0 - a.0).hypot(b.1 - a.1) / 8.0).min(200.0) as usize;
            for k in 1..=n {
                let t = k as f64 / n as f64;
                self.drawn
                    .push((a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1)));
            }
            // A clipped end leaves the area: the next segment starts anew.
            pen = Some(b).filter(|_| px.get(k + 1).copied().flatten() == Some(b));
        }
        if d.is_empty() {
            return;
        }
        let class = if class.is_empty() {
            String::new()
        } else {
            format!(" class=\"{class}\"")
        };
        let _ = writeln!(
            self.out,
            "<path{class} d=\"{}\" {}/>",
            d.trim_end(),
            stroke.attrs()
        );
    }

    /// A polyline in pixels, unclipped.
    pub fn line_px(&mut self, pts: &[(f64, f64)], stroke: Stroke<'_>) {
        let d: Vec<String> = pts
            .iter()
            .enumerate()
            .map(|(k, (x, y))| format!("{}{x:.2},{y:.2}", if k == 0 { "M" } else { "L" }))
            .collect();
        let _ = writeln!(self.out, "<path d=\"{}\" {}/>", d.join(" "), stroke.attrs());
    }

    /// A filled rectangle in pixels, `opacity` its fill's.
    pub fn rect_px(&mut self, r: [f64; 4], fill: &str, opacity: f64, stroke: Option<&str>) {
        let [x0, y0, x1, y1] = r;
        let stroke = stroke.map_or(String::new(), |s| {
            format!(" stroke=\"{s}\" stroke-width=\"1\"")
        });
        let _ = writeln!(
            self.out,
            "<rect x=\"{:.2}\" y=\"{:.2}\" width=\"{:.2}\" height=\"{:.2}\" fill=\"{fill}\" \
             opacity=\"{opacity}\"{stroke}/>",
            x0.min(x1),
            y0.min(y1),
            (x1 - x0).abs(),
            (y1 - y0).abs()
        );
    }

    pub fn circle_px(&mut self, (x, y): (f64, f64), r: f64, fill: &str, stroke: &str) {
        let _ = writeln!(
            self.out,
            "<circle cx=\"{x:.2}\" cy=\"{y:.2}\" r=\"{r}\" fill=\"{fill}\" stroke=\"{stroke}\" \
             stroke-width=\"1\"/>"
        );
    }

    /// Text with a white halo (readable over lines).
    pub fn text(&mut self, at: (f64, f64), s: &str, size: f64, anchor: Anchor, color: &str) {
        self.text_sized(at, s, size, anchor, color, "normal");
    }

    fn text_sized(
        &mut self,
        (x, y): (f64, f64),
        s: &str,
        size: f64,
        anchor: Anchor,
        color: &str,
        weight: &str,
    ) {
        let w = text_width(s, size);
        let x0 = match anchor {
            Anchor::Start => x,
            Anchor::Middle => x - w / 2.0,
            Anchor::End => x - w,
        };
        let mut t = 0.0;
        while t <= w {
            self.drawn.push((x0 + t, y - size * 0.35));
            t += 6.0;
        }
        let anchor = match anchor {
            Anchor::Start => "start",
            Anchor::Middle => "middle",
            Anchor::End => "end",
        };
        let _ = writeln!(
            self.out,
            "<text x=\"{x:.2}\" y=\"{y:.2}\" font-size=\"{size}\" font-weight=\"{weight}\" \
             text-anchor=\"{anchor}\" fill=\"{color}\" stroke=\"#FFFFFF\" stroke-width=\"3\" \
             stroke-opacity=\"0.85\" paint-order=\"stroke\">{}</text>",
            escape(s)
        );
    }

    fn text_rotated(&mut self, (x, y): (f64, f64), s: &str, size: f64) {
        let _ = writeln!(
            self.out,
            "<text x=\"{x:.2}\" y=\"{y:.2}\" font-size=\"{size}\" text-anchor=\"middle\" \
             fill=\"{INK}\" transform=\"rotate(-90 {x:.2} {y:.2})\">{}</text>",
            escape(s)
        );
    }

    /// A boxed key at the top-left corner `at`: text, colour, dashes (a `None` colour: a
    /// shaded swatch, a colour with `"dot"`, `"ring"` or `"small"`: a marker).
    pub fn key(&mut self, at: (f64, f64), entries: &[(String, &str, Option<&str>)]) {
        if entries.is_empty() {
            return;
        }
        let (w, h) = key_size(entries);
        self.rect_px(
            [at.0, at.1, at.0 + w, at.1 + h],
            "#FFFFFF",
            0.9,
            Some(FRAME),
        );
        for (k, (s, color, dash)) in entries.iter().enumerate() {
            let y = at.1 + 13.0 + 17.0 * k as f64;
            match *dash {
                Some("shade") => self.rect_px(
                    [at.0 + 6.0, y - 5.0, at.0 + 34.0, y + 5.0],
                    color,
                    0.22,
                    None,
                ),
                Some("dot") => self.circle_px((at.0 + 20.0, y), 4.0, color, INK),
                Some("ring") => self.circle_px((at.0 + 20.0, y), 4.0, "#FFFFFF", color),
                Some("small") => self.circle_px((at.0 + 20.0, y), 3.0, "#FFFFFF", color),
                _ => {
                    let mut st = Stroke::solid(color, 2.0);
                    st.dash = *dash;
                    self.line_px(&[(at.0 + 6.0, y), (at.0 + 34.0, y)], st);
                }
            }
            self.text((at.0 + 40.0, y + 4.0), s, 12.0, Anchor::Start, INK);
        }
    }

    /// An unboxed key in rows centred on `x`, starting at the height `y`, wrapped at `width`;
    /// returns the height used.
    pub fn key_rows(
        &mut self,
        (x, y): (f64, f64),
        width: f64,
        entries: &[(String, &str, Option<&str>)],
    ) -> f64 {
        let size = |e: &(String, &str, Option<&str>)| text_width(&e.0, 12.0) + 58.0;
        let mut rows: Vec<Vec<&(String, &str, Option<&str>)>> = vec![vec![]];
        let mut used = 0.0;
        for e in entries {
            if used + size(e) > width && !rows.last().is_some_and(Vec::is_empty) {
                rows.push(vec![]);
                used = 0.0;
            }
            used += size(e);
            rows.last_mut().expect("a row").push(e);
        }
        for (k, row) in rows.iter().enumerate() {
            let total: f64 = row.iter().map(|e| size(e)).sum();
            let mut at = x - total / 2.0;
            let yk = y + 17.0 * k as f64;
            for (s, color, dash) in row.iter().map(|e| (&e.0, e.1, e.2)) {
                match dash {
                    Some("shade") => {
                        self.rect_px([at, yk - 5.0, at + 28.0, yk + 5.0], color, 0.22, None)
                    }
                    Some("dot") => self.circle_px((at + 14.0, yk), 4.0, color, INK),
                    Some("ring") => self.circle_px((at + 14.0, yk), 4.0, "#FFFFFF", color),
                    Some("small") => self.circle_px((at + 14.0, yk), 3.0, "#FFFFFF", color),
                    _ => {
                        let mut st = Stroke::solid(color, 2.0);
                        st.dash = dash;
                        self.line_px(&[(at, yk), (at + 28.0, yk)], st);
                    }
                }
                self.text((at + 34.0, yk + 4.0), s, 12.0, Anchor::Start, INK);
                at += size(&(s.clone(), color, dash));
            }
        }
        17.0 * rows.len() as f64
    }

    /// [`Svg::key`] in the corner of `p` (or halfway down a side) that the fewest lines and
    /// texts drawn so far cross.
    pub fn key_in(&mut self, p: &Panel, entries: &[(String, &str, Option<&str>)]) {
        if entries.is_empty() {
            return;
        }
        let (w, h) = key_size(entries);
        let [x0, y0, x1, y1] = p.rect;
        let (l, r) = (x0 + 8.0, x1 - 8.0 - w);
        let (t, b, m) = (y0 + 8.0, y1 - 8.0 - h, (y0 + y1 - h) / 2.0);
        let spots = [
            (l, t),
            (r, t),
            (r, b),
            (l, b),
            (l, m),
            (r, m),
            ((x0 + x1 - w) / 2.0, t),
        ];
        let cost = |at: &(f64, f64)| {
            self.drawn
                .iter()
                .filter(|q| {
                    q.0 >= at.0 - 2.0
                        && q.0 <= at.0 + w + 2.0
                        && q.1 >= at.1 - 2.0
                        && q.1 <= at.1 + h + 2.0
                })
                .count()
        };
        let best = spots
            .iter()
            .enumerate()
            .min_by_key(|(k, at)| (cost(at), *k))
            .map_or((l, t), |(_, at)| *at);
        self.key(best, entries);
    }

    /// Raw SVG.
    pub fn raw(&mut self, s: &str) {
        self.out.push_str(s);
    }
}

/// The part of the segment `a`-`b` inside `r` (Liang-Barsky), if any.
fn clip_segment(a: (f64, f64), b: (f64, f64), r: [f64; 4]) -> Option<((f64, f64), (f64, f64))> {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    let eps = 1e-7;
    for (p, q) in [
        (-dx, a.0 - r[0] + eps),
        (dx, r[2] - a.0 + eps),
        (-dy, a.1 - r[1] + eps),
        (dy, r[3] - a.1 + eps),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let t = q / p;
            if p < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
        }
    }
    if t0 > t1 {
        return None;
    }
    let at = |t: f64| (a.0 + t * dx, a.1 + t * dy);
    Some((
        if t0 > 0.0 { at(t0) } else { a },
        if t1 < 1.0 { at(t1) } else { b },
    ))
}

/// Width and height of a key.
fn key_size(entries: &[(String, &str, Option<&str>)]) -> (f64, f64) {
    let w = entries
        .iter()
        .map(|e| text_width(&e.0, 12.0))
        .fold(0.0, f64::max)
        + 48.0;
    (w, 8.0 + 17.0 * entries.len() as f64)
}

/// Estimated width of `s` at font `size` px.
pub fn text_width(s: &str, size: f64) -> f64 {
    0.58 * size * s.chars().count() as f64
}

/// Moves the positions `ys` (pixels, any order) apart by at least `gap`, keeping them in
/// `[lo, hi]` where they fit; returns them in the original order.
pub fn spread(ys: &[f64], gap: f64, lo: f64, hi: f64) -> Vec<f64> {
    let mut idx: Vec<usize> = (0..ys.len()).collect();
    idx.sort_by(|&a, &b| ys[a].total_cmp(&ys[b]));
    let mut out = ys.to_vec();
    let mut prev = f64::NEG_INFINITY;
    for &i in &idx {
        out[i] = out[i].max(prev + gap).max(lo);
        prev = out[i];
    }
    let mut next = f64::INFINITY;
    for &i in idx.iter().rev() {
        out[i] = out[i].min(next - gap).min(hi);
        next = out[i];
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spread_keeps_gaps() {
        let y = spread(&[10.0, 11.0, 12.0, 100.0], 10.0, 0.0, 200.0);
        assert!(y[1] - y[0] >= 10.0 - 1e-9 && y[2] - y[1] >= 10.0 - 1e-9);
        assert_eq!(y[3], 100.0);
    }
}
