//! SVG plots of the audit analyses (API 684 / API 617): the undamped critical speed map, static
//! deflection and bending moment, the Level I screen, the frequency response (Bode), the
//! unbalance response with its peaks, and a sketch of the rotor ([`rotor_sketch`], in
//! `plot_audit/sketch.rs`). Same style as [`super::plot`]: SVG text, the viewer renders the
//! fonts, so label sizes are estimated.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::plot::{PALETTE, RPM, SHADE, range, runs};
use crate::model::api::{
    CriticalSpeedMapResponse, FrequencyResponseResponse, Level1Response, StaticResponse,
    UnbalanceResponseResponse,
};

mod sketch;
pub use sketch::rotor_sketch;
pub(crate) use sketch::support_stiffness;

type Err = Box<dyn std::error::Error>;
type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;

const FONT: &str = "sans-serif";
/// Colour of the frame around every plotting area (tests find the area by it).
pub(crate) const FRAME: RGBColor = RGBColor(80, 80, 80);
const GRID: RGBColor = RGBColor(238, 238, 238);
const INK: RGBColor = RGBColor(30, 30, 30);
const FAIL: RGBColor = RGBColor(200, 20, 20);
/// Tick labels, axis titles, annotations: plotters' sizes (the SVG font size is 1/1.24 of it).
const TICK: u32 = 15;
const DESC: u32 = 16;
const NOTE: u32 = 15;

/// A box in pixels: `[x0, y0, x1, y1]`.
pub(crate) type Rect = [i32; 4];

/// Estimated box of `text` at plotters font `size` (width ~0.62 em per character).
pub(crate) fn text_box(text: &str, size: u32) -> (i32, i32) {
    let em = f64::from(size) / 1.24;
    (
        (0.62 * em * text.chars().count() as f64).ceil() as i32,
        (1.25 * em).ceil() as i32,
    )
}

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
    /// Without room, the nearest spot inside `bounds`.
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
        let mut first = None;
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
                continue;
            }
            if far {
                self.block_path(&[at, n]);
            }
            self.taken.push(r);
            self.texts.push(r);
            return (r[0], r[1]);
        }
        let r = first.unwrap_or([x + 7, y - h - 4, x + 7 + w, y - 4]);
        self.taken.push(r);
        self.texts.push(r);
        (r[0], r[1])
    }
}

/// The point of `r` nearest to `p`.
fn nearest(p: (i32, i32), r: &Rect) -> (i32, i32) {
    (p.0.clamp(r[0], r[2]), p.1.clamp(r[1], r[3]))
}

/// Text at a pixel position of the root area.
pub(crate) fn text(
    root: &Area<'_>,
    s: &str,
    at: (i32, i32),
    size: u32,
    color: RGBColor,
    pos: (HPos, VPos),
) -> Result<(), Err> {
    let style = (FONT, size)
        .into_font()
        .color(&color)
        .pos(Pos::new(pos.0, pos.1));
    root.draw(&Text::new(s.to_string(), at, style))?;
    Ok(())
}

/// A label placed by `labels` near the pixel `at`, joined to it by a thin line when moved away.
fn label(
    root: &Area<'_>,
    labels: &mut Labels,
    s: &str,
    at: (i32, i32),
    color: RGBColor,
    left: bool,
) -> Result<(), Err> {
    let (x, y) = labels.place(at, s, NOTE, left);
    let (w, h) = text_box(s, NOTE);
    let near = nearest(at, &[x, y, x + w, y + h]);
    if (near.0 - at.0).abs() + (near.1 - at.1).abs() > 10 {
        let (dx, dy) = (f64::from(near.0 - at.0), f64::from(near.1 - at.1));
        let r = 6.0 / dx.hypot(dy);
        let from = (at.0 + (dx * r) as i32, at.1 + (dy * r) as i32);
        root.draw(&PathElement::new(
            vec![from, near],
            color.mix(0.8).stroke_width(1),
        ))?;
    }
    text(root, s, (x, y), NOTE, color, (HPos::Left, VPos::Top))
}

/// A boxed key of line styles (`dashed`) at the top-right corner `at`; returns its box.
fn key(root: &Area<'_>, at: (i32, i32), entries: &[(String, RGBColor, bool)]) -> Result<Rect, Err> {
    let w = entries
        .iter()
        .map(|e| text_box(&e.0, NOTE).0)
        .max()
        .unwrap_or(0)
        + 44;
    let line = text_box("x", NOTE).1 + 4;
    let r = [at.0 - w, at.1, at.0, at.1 + 8 + line * entries.len() as i32];
    root.draw(&Rectangle::new(
        [(r[0], r[1]), (r[2], r[3])],
        WHITE.mix(0.9).filled(),
    ))?;
    root.draw(&Rectangle::new(
        [(r[0], r[1]), (r[2], r[3])],
        FRAME.stroke_width(1),
    ))?;
    for (k, (s, c, dashed)) in entries.iter().enumerate() {
        let y = r[1] + 4 + line * k as i32 + line / 2;
        let pts = if *dashed {
            vec![
                vec![(r[0] + 6, y), (r[0] + 14, y)],
                vec![(r[0] + 20, y), (r[0] + 30, y)],
            ]
        } else {
            vec![vec![(r[0] + 6, y), (r[0] + 30, y)]]
        };
        for p in pts {
            root.draw(&PathElement::new(p, c.stroke_width(2)))?;
        }
        text(
            root,
            s,
            (r[0] + 36, y),
            NOTE,
            INK,
            (HPos::Left, VPos::Center),
        )?;
    }
    Ok(r)
}

/// `[lo, hi]` of the positive finite values, widened by `pad` decades; empty: `[1, 10]`.
pub(crate) fn log_range(values: impl Iterator<Item = f64>, pad: f64) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite() && *v > 0.0)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    if !lo.is_finite() {
        return (1.0, 10.0);
    }
    let (lo, hi) = if hi > lo * 1.0001 {
        (lo, hi)
    } else {
        (lo / 3.0, hi * 3.0)
    };
    let f = 10f64.powf(pad * (hi / lo).log10().max(1.0));
    (lo / f, hi * f)
}

/// A log axis tick: plain from 0.01 to 10000, else `1e6`, `2e6`-style.
pub(crate) fn log_tick(v: f64) -> String {
    if !v.is_finite() || v <= 0.0 {
        return String::new();
    }
    let e = v.log10().floor();
    let m = v / 10f64.powf(e);
    let (e, m) = if m > 9.9999 { (e + 1.0, 1.0) } else { (e, m) };
    if (-2.0..5.0).contains(&e) {
        format!("{}", (v * 100.0).round() / 100.0)
    } else {
        format!("{m:.0}e{e}")
    }
}

/// Tick labels of a linear axis spanning `span`: as many decimals as its steps need.
pub(crate) fn lin_tick(span: f64) -> impl Fn(&f64) -> String {
    let step = (span.abs() / 8.0).max(f64::MIN_POSITIVE);
    let decimals = (-step.log10().floor()).clamp(0.0, 8.0) as usize;
    move |v: &f64| {
        if v.abs() < step * 1e-6 {
            "0".into()
        } else {
            format!("{v:.decimals$}")
        }
    }
}

/// Labels at 2 and 5 times the powers of ten of a log y axis `[lo, hi]` over `area`, left or
/// right of it (plotters labels the powers only), when it spans at most three decades.
fn log_minor_labels(
    root: &Area<'_>,
    area: Rect,
    (lo, hi): (f64, f64),
    right: bool,
) -> Result<(), Err> {
    if !(lo > 0.0 && hi > lo && (hi / lo).log10() <= 3.0) {
        return Ok(());
    }
    let y = |v: f64| {
        area[3] - ((v / lo).ln() / (hi / lo).ln() * f64::from(area[3] - area[1])).round() as i32
    };
    let mut e = lo.log10().floor();
    while 10f64.powf(e) <= hi {
        for m in [2.0, 5.0] {
            let v = m * 10f64.powf(e);
            if (lo..=hi).contains(&v) {
                let (x, tick, pos) = if right {
                    (
                        area[2] + 10,
                        (area[2], area[2] + 5),
                        (HPos::Left, VPos::Center),
                    )
                } else {
                    (
                        area[0] - 10,
                        (area[0] - 5, area[0]),
                        (HPos::Right, VPos::Center),
                    )
                };
                root.draw(&PathElement::new(
                    vec![(tick.0, y(v)), (tick.1, y(v))],
                    BLACK.stroke_width(1),
                ))?;
                text(root, &log_tick(v), (x, y(v)), TICK, BLACK, pos)?;
            }
        }
        e += 1.0;
    }
    Ok(())
}

/// The pixels of a line drawn on `chart`.
fn pixels<X: Ranged<ValueType = f64>, Y: Ranged<ValueType = f64>>(
    chart: &ChartContext<'_, SVGBackend<'_>, Cartesian2d<X, Y>>,
    pts: &[(f64, f64)],
) -> Vec<(i32, i32)> {
    pts.iter().map(|p| chart.backend_coord(p)).collect()
}

/// A boxed block of lines of text in a free corner of `labels`' bounds.
fn note_box(root: &Area<'_>, labels: &mut Labels, lines: &[String]) -> Result<(), Err> {
    if lines.is_empty() {
        return Ok(());
    }
    let w = lines.iter().map(|l| text_box(l, NOTE).0).max().unwrap_or(0) + 16;
    let h = text_box("x", NOTE).1 + 2;
    let at = labels.corner(w, 8 + h * lines.len() as i32);
    let r = [at.0, at.1, at.0 + w, at.1 + 8 + h * lines.len() as i32];
    root.draw(&Rectangle::new(
        [(r[0], r[1]), (r[2], r[3])],
        WHITE.mix(0.92).filled(),
    ))?;
    root.draw(&Rectangle::new(
        [(r[0], r[1]), (r[2], r[3])],
        FRAME.stroke_width(1),
    ))?;
    for (k, l) in lines.iter().enumerate() {
        text(
            root,
            l,
            (r[0] + 8, r[1] + 5 + h * k as i32),
            NOTE,
            INK,
            (HPos::Left, VPos::Top),
        )?;
    }
    Ok(())
}

/// Pixel box of a chart's plotting area, framed.
fn frame<X: Ranged, Y: Ranged>(
    root: &Area<'_>,
    chart: &ChartContext<'_, SVGBackend<'_>, Cartesian2d<X, Y>>,
) -> Result<Rect, Err> {
    let (xr, yr) = chart.plotting_area().get_pixel_range();
    let r = [xr.start, yr.start, xr.end, yr.end];
    root.draw(&Rectangle::new(
        [(r[0], r[1]), (r[2], r[3])],
        FRAME.stroke_width(1),
    ))?;
    Ok(r)
}

/// A length unit for values up to `max` m: `(factor, name)`.
fn length_unit(max: f64) -> (f64, &'static str) {
    if max < 1e-3 {
        (1e6, "µm")
    } else {
        (1e3, "mm")
    }
}

/// Undamped critical speed map: natural frequency against support stiffness, log-log.
pub fn critical_speed_map(c: &CriticalSpeedMapResponse) -> Result<String, Err> {
    critical_speed_map_with(c, None)
}

/// [`critical_speed_map`] with the operating speeds `shade = [min, max]` (rad/s) shaded.
pub fn critical_speed_map_with(
    c: &CriticalSpeedMapResponse,
    shade: Option<[f64; 2]>,
) -> Result<String, Err> {
    let ok = |v: f64| v.is_finite() && v > 0.0;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (960, 680)).into_drawing_area();
        root.fill(&WHITE)?;
        let ks = c
            .stiffness
            .iter()
            .copied()
            .chain(c.intersections.iter().map(|i| i.stiffness));
        let (k0, k1) = log_range(ks, 0.0);
        let fs = c.frequencies.iter().flatten().copied();
        let fs = fs
            .chain(c.intersections.iter().map(|i| i.frequency))
            .chain(shade.into_iter().flatten());
        let (f0, f1) = log_range(fs, 0.06);
        let mut chart = ChartBuilder::on(&root)
            .caption("Undamped critical speed map", (FONT, 22))
            .margin(14)
            .x_label_area_size(52)
            .y_label_area_size(80)
            .right_y_label_area_size(86)
            .build_cartesian_2d((k0..k1).log_scale(), (f0..f1).log_scale())?
            .set_secondary_coord((k0..k1).log_scale(), (f0 * RPM..f1 * RPM).log_scale());
        chart
            .configure_mesh()
            .x_desc("support stiffness [N/m]")
            .y_desc("natural frequency [rad/s]")
            .x_label_formatter(&|v| log_tick(*v))
            .y_label_formatter(&|v| log_tick(*v))
            .label_style((FONT, TICK))
            .axis_desc_style((FONT, DESC))
            .light_line_style(GRID)
            .draw()?;
        chart
            .configure_secondary_axes()
            .y_desc("natural frequency [rpm]")
            .y_label_formatter(&|v| log_tick(*v))
            .label_style((FONT, TICK))
            .axis_desc_style((FONT, DESC))
            .x_labels(0)
            .draw()?;
        let area = frame(&root, &chart)?;
        log_minor_labels(&root, area, (f0, f1), false)?;
        log_minor_labels(&root, area, (f0 * RPM, f1 * RPM), true)?;
        let mut labels = Labels::new(area);
        if let Some([lo, hi]) = shade.filter(|s| ok(s[0]) && ok(s[1]) && s[1] > s[0]) {
            let (lo, hi) = (lo.max(f0), hi.min(f1));
            chart.draw_series(std::iter::once(Rectangle::new(
                [(k0, lo), (k1, hi)],
                SHADE.filled(),
            )))?;
            let at = chart.backend_coord(&(k0, hi));
            let s = "operating range";
            let (w, h) = text_box(s, NOTE);
            labels.block([at.0, at.1, at.0 + w + 12, at.1 + h + 6]);
            text(
                &root,
                s,
                (at.0 + 6, at.1 + 3),
                NOTE,
                INK,
                (HPos::Left, VPos::Top),
            )?;
        }
        for (m, ys) in c.frequencies.iter().enumerate() {
            let color = PALETTE[m % PALETTE.len()];
            let pts: Vec<(f64, f64)> = c
                .stiffness
                .iter()
                .zip(ys)
                .filter(|(k, f)| ok(**k) && ok(**f))
                .map(|(k, f)| (*k, *f))
                .collect();
            chart.draw_series(LineSeries::new(pts.iter().copied(), color.stroke_width(2)))?;
            labels.block_path(&pixels(&chart, &pts));
            if let Some(end) = pts.last() {
                let at = chart.backend_coord(end);
                let s = format!("mode {}", m + 1);
                let (w, h) = text_box(&s, NOTE);
                let (x, y) = (at.0 - w - 6, at.1 - h - 3);
                labels.block([x, y, x + w, y + h]);
                text(&root, &s, (x, y), NOTE, color, (HPos::Left, VPos::Top))?;
            }
        }
        // One marker per distinct point (two supports often meet a mode at the same place).
        let mut seen: Vec<(f64, f64)> = vec![];
        let mut points = vec![];
        for i in &c.intersections {
            let (k, f) = (i.stiffness, i.frequency);
            let inside = ok(k) && ok(f) && (k0..=k1).contains(&k) && (f0..=f1).contains(&f);
            if inside
                && !seen
                    .iter()
                    .any(|(a, b)| (a / k).ln().abs() < 1e-3 && (b / f).ln().abs() < 1e-3)
            {
                seen.push((k, f));
                points.push((k, f, PALETTE[(i.mode.max(1) - 1) % PALETTE.len()]));
            }
        }
        for &(k, f, color) in &points {
            let at = chart.backend_coord(&(k, f));
            labels.block([at.0 - 6, at.1 - 6, at.0 + 6, at.1 + 6]);
            chart.draw_series([
                Circle::new((k, f), 6, color.filled()),
                Circle::new((k, f), 6, INK.stroke_width(1)),
            ])?;
        }
        for &(k, f, color) in &points {
            let at = chart.backend_coord(&(k, f));
            let s = format!("{f:.1} rad/s ({:.0} rpm)", f * RPM);
            label(&root, &mut labels, &s, at, color, false)?;
        }
        root.present()?;
    }
    Ok(svg)
}

/// Static deflection (µm or mm) with the support reactions over the bending moment, along the
/// shaft.
pub fn static_deflection(s: &StaticResponse) -> Result<String, Err> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (960, 820)).into_drawing_area();
        root.fill(&WHITE)?;
        let (top, bottom) = root.split_vertically(450);
        let xs = s
            .nodes
            .iter()
            .map(|n| n.position)
            .chain(s.stations.iter().map(|t| t.position));
        let (x0, x1) = range(xs, 0.02);
        let max = s
            .nodes
            .iter()
            .map(|n| n.deflection.abs())
            .filter(|v| v.is_finite())
            .fold(0.0, f64::max);
        let (scale, unit) = length_unit(max);
        let ds = s.nodes.iter().map(|n| n.deflection * scale).chain([0.0]);
        let (y0, y1) = range(ds, 0.18);
        let caption = format!("Static deflection under gravity (weight {:.1} N)", s.weight);
        let mut chart = ChartBuilder::on(&top)
            .caption(caption, (FONT, 22))
            .margin(14)
            .x_label_area_size(48)
            .y_label_area_size(84)
            .build_cartesian_2d(x0..x1, y0..y1)?;
        chart
            .configure_mesh()
            .x_desc("axial position [m]")
            .y_desc(format!("deflection y [{unit}]"))
            .x_label_formatter(&lin_tick(x1 - x0))
            .y_label_formatter(&lin_tick(y1 - y0))
            .label_style((FONT, TICK))
            .axis_desc_style((FONT, DESC))
            .light_line_style(GRID)
            .draw()?;
        let area = frame(&root, &chart)?;
        chart.draw_series(LineSeries::new(
            [(x0, 0.0), (x1, 0.0)],
            INK.mix(0.6).stroke_width(1),
        ))?;
        let pts: Vec<(f64, f64)> = s
            .nodes
            .iter()
            .filter(|n| n.position.is_finite() && n.deflection.is_finite())
            .map(|n| (n.position, n.deflection * scale))
            .collect();
        chart.draw_series(LineSeries::new(
            pts.iter().copied(),
            PALETTE[0].stroke_width(2),
        ))?;
        chart.draw_series(pts.iter().map(|p| Circle::new(*p, 3, PALETTE[0].filled())))?;
        let mut labels = Labels::new(area);
        labels.block_path(&pixels(&chart, &pts));
        if let Some(p) = pts.iter().min_by(|a, b| a.1.total_cmp(&b.1)) {
            let at = chart.backend_coord(p);
            let s = format!("max {:.1} {unit} at {:.3} m", p.1.abs(), p.0);
            label(&root, &mut labels, &s, at, PALETTE[0], false)?;
        }
        for r in &s.supports {
            let Some(n) = s.nodes.iter().find(|n| n.node == r.node) else {
                continue;
            };
            if !(n.position.is_finite() && n.deflection.is_finite() && r.reaction.is_finite()) {
                continue;
            }
            let p = (n.position, n.deflection * scale);
            let at = chart.backend_coord(&p);
            let tri = vec![at, (at.0 - 8, at.1 + 15), (at.0 + 8, at.1 + 15)];
            root.draw(&Polygon::new(tri, PALETTE[1].filled()))?;
            labels.block([at.0 - 8, at.1, at.0 + 8, at.1 + 15]);
            let mut s = format!("R{} = {:.1} N (node {})", r.support, r.reaction, r.node);
            if r.reaction_x.is_finite() && r.reaction_x.abs() > 1e-6 * r.reaction.abs().max(1.0) {
                s = format!(
                    "R{} = {:.1} N, x {:.1} N (node {})",
                    r.support, r.reaction, r.reaction_x, r.node
                );
            }
            // Centred under the support when there is room.
            let (w, h) = text_box(&s, NOTE);
            let r = [at.0 - w / 2, at.1 + 19, at.0 + w / 2, at.1 + 19 + h];
            if labels.take(r) {
                text(
                    &root,
                    &s,
                    (r[0], r[1]),
                    NOTE,
                    PALETTE[1],
                    (HPos::Left, VPos::Top),
                )?;
            } else {
                let left = p.0 > (x0 + x1) / 2.0;
                label(&root, &mut labels, &s, (at.0, at.1 + 15), PALETTE[1], left)?;
            }
        }

        let ms: Vec<(f64, f64)> = s
            .stations
            .iter()
            .filter(|t| t.position.is_finite() && t.bending_moment.is_finite())
            .map(|t| (t.position, t.bending_moment))
            .collect();
        let (m0, m1) = range(ms.iter().map(|p| p.1).chain([0.0]), 0.15);
        let mut chart = ChartBuilder::on(&bottom)
            .caption("Bending moment", (FONT, 22))
            .margin(14)
            .x_label_area_size(48)
            .y_label_area_size(84)
            .build_cartesian_2d(x0..x1, m0..m1)?;
        chart
            .configure_mesh()
            .x_desc("axial position [m]")
            .y_desc("bending moment [N m]")
            .x_label_formatter(&lin_tick(x1 - x0))
            .y_label_formatter(&lin_tick(m1 - m0))
            .label_style((FONT, TICK))
            .axis_desc_style((FONT, DESC))
            .light_line_style(GRID)
            .draw()?;
        let area = frame(&root, &chart)?;
        chart.draw_series(LineSeries::new(
            [(x0, 0.0), (x1, 0.0)],
            INK.mix(0.6).stroke_width(1),
        ))?;
        chart.draw_series(LineSeries::new(
            ms.iter().copied(),
            PALETTE[2].stroke_width(2),
        ))?;
        if let Some(p) = ms.iter().max_by(|a, b| a.1.abs().total_cmp(&b.1.abs())) {
            let at = chart.backend_coord(p);
            let mut labels = Labels::new(area);
            labels.block_path(&pixels(&chart, &ms));
            let s = format!("|M| max {:.1} N m at {:.3} m", p.1.abs(), p.0);
            chart.draw_series([Circle::new(*p, 4, PALETTE[2].filled())])?;
            label(&root, &mut labels, &s, at, PALETTE[2], false)?;
        }
        root.present()?;
    }
    Ok(svg)
}

/// A cross-coupling unit for values up to `max` N/m: `(divisor, name)`.
pub(crate) fn stiffness_unit(max: f64) -> (f64, &'static str) {
    if max >= 1e6 {
        (1e6, "MN/m")
    } else if max >= 1e3 {
        (1e3, "kN/m")
    } else {
        (1.0, "N/m")
    }
}

/// API 617 Level I screen: log decrement of the first forward mode against cross-coupling.
pub fn level1(l: &Level1Response) -> Result<String, Err> {
    let fin = |v: &Option<f64>| v.filter(|x| x.is_finite());
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (960, 600)).into_drawing_area();
        root.fill(&WHITE)?;
        let qmax = l
            .cross_coupling
            .iter()
            .copied()
            .filter(|q| q.is_finite())
            .fold(0.0, f64::max);
        // q0 and q_A widen the axis unless far beyond the curve (then they are only named).
        let near = |q: Option<f64>| fin(&q).filter(|q| *q <= 2.0 * qmax.max(f64::MIN_POSITIVE));
        let extra = [near(l.q0), near(l.qa)].into_iter().flatten();
        let (q_lo, q_hi) = range(l.cross_coupling.iter().copied().chain(extra), 0.0);
        let (div, unit) = stiffness_unit(q_hi.abs().max(q_lo.abs()));
        let (x0, x1) = (q_lo / div, q_hi / div);
        let ds = l
            .log_decrement
            .iter()
            .chain([&l.log_decrement_0, &l.log_decrement_at_qa]);
        let (y0, y1) = range(ds.filter_map(fin).chain([0.0, 0.1]), 0.1);
        let caption = format!(
            "API 617 Level I screen at {:.0} rpm ({})",
            l.speed * RPM,
            l.model
        );
        let mut chart = ChartBuilder::on(&root)
            .caption(caption, (FONT, 22))
            .margin(14)
            .margin_right(30)
            .x_label_area_size(52)
            .y_label_area_size(80)
            .build_cartesian_2d(x0..x1, y0..y1)?;
        let unit_name = if unit == "MN/m" { "MN/m = kN/mm" } else { unit };
        chart
            .configure_mesh()
            .x_desc(format!("cross-coupled stiffness q [{unit_name}]"))
            .y_desc("log decrement δ, first forward mode")
            .x_label_formatter(&lin_tick(x1 - x0))
            .y_label_formatter(&lin_tick(y1 - y0))
            .label_style((FONT, TICK))
            .axis_desc_style((FONT, DESC))
            .light_line_style(GRID)
            .draw()?;
        let area = frame(&root, &chart)?;
        let mut labels = Labels::new(area);
        let qs: Vec<f64> = l.cross_coupling.iter().map(|q| q / div).collect();
        chart.draw_series(LineSeries::new([(x0, 0.0), (x1, 0.0)], INK.stroke_width(1)))?;
        chart.draw_series(DashedLineSeries::new(
            [(x0, 0.1), (x1, 0.1)],
            8,
            6,
            FAIL.stroke_width(2),
        ))?;
        let curves = runs(&qs, &l.log_decrement);
        for run in &curves {
            chart.draw_series(LineSeries::new(
                run.iter().copied(),
                PALETTE[0].stroke_width(2),
            ))?;
            chart.draw_series(run.iter().map(|p| Circle::new(*p, 3, PALETTE[0].filled())))?;
            labels.block_path(&pixels(&chart, run));
        }
        let at = chart.backend_coord(&(x1, 0.1));
        let s = "API 617 minimum δ = 0.1";
        let (w, h) = text_box(s, NOTE);
        let spot = (at.0 - w - 6, at.1 - h - 2);
        labels.block([spot.0, spot.1, spot.0 + w, spot.1 + h]);
        text(&root, s, spot, NOTE, FAIL, (HPos::Left, VPos::Top))?;
        let mut notes = vec![];
        if let Some(qa) = fin(&l.qa) {
            let x = qa / div;
            let name = format!("q_A = {:.3} {unit}", x);
            if (x0..=x1).contains(&x) {
                let c = PALETTE[4];
                chart.draw_series(LineSeries::new([(x, y0), (x, y1)], c.stroke_width(2)))?;
                labels.block_path(&pixels(&chart, &[(x, y0), (x, y1)]));
                let at = chart.backend_coord(&(x, y1));
                let (w, h) = text_box(&name, NOTE);
                let (px, py) = if at.0 + 6 + w < area[2] {
                    (at.0 + 6, at.1 + 4)
                } else {
                    (at.0 - 6 - w, at.1 + 4)
                };
                labels.block([px, py, px + w, py + h]);
                text(&root, &name, (px, py), NOTE, c, (HPos::Left, VPos::Top))?;
                if let Some(d) = fin(&l.log_decrement_at_qa) {
                    chart.draw_series([Circle::new((x, d), 5, c.filled())])?;
                    let at = chart.backend_coord(&(x, d));
                    label(
                        &root,
                        &mut labels,
                        &format!("δ(q_A) = {d:.3}"),
                        at,
                        c,
                        false,
                    )?;
                }
            } else {
                notes.push(name);
            }
        }
        if let Some(q0) = fin(&l.q0) {
            let x = q0 / div;
            let name = format!("q0 = {:.3} {unit}", x);
            if (x0..=x1).contains(&x) {
                chart.draw_series([Circle::new((x, 0.0), 6, FAIL.filled())])?;
                let at = chart.backend_coord(&(x, 0.0));
                label(&root, &mut labels, &name, at, FAIL, false)?;
            } else {
                notes.push(format!("{name} (beyond the plot)"));
            }
        } else {
            notes.push("q0: stable over the range searched".into());
        }
        if let Some(r) = fin(&l.ratio) {
            notes.push(format!("q0 / q_A = {r:.2}"));
        }
        if let Some(p) = l.passes {
            notes.push(if p {
                "Level I: passes".into()
            } else {
                "Level I: Level II required".into()
            });
        }
        note_box(&root, &mut labels, &notes)?;
        root.present()?;
    }
    Ok(svg)
}

/// Bode plot of the frequency response: amplitude (m/N, log) over phase (degrees).
pub fn frequency_response(r: &FrequencyResponseResponse) -> Result<String, Err> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (960, 820)).into_drawing_area();
        root.fill(&WHITE)?;
        let (top, bottom) = root.split_vertically(470);
        let (x0, x1) = range(r.frequencies.iter().copied(), 0.0);
        let (a0, a1) = log_range(r.amplitude.iter().copied(), 0.05);
        let caption = format!(
            "Frequency response: node {} → node {} at {:.0} rpm ({})",
            r.input_node,
            r.output_node,
            r.speed * RPM,
            r.model
        );
        let mut chart = ChartBuilder::on(&top)
            .caption(caption, (FONT, 22))
            .margin(14)
            .x_label_area_size(48)
            .y_label_area_size(84)
            .top_x_label_area_size(44)
            .build_cartesian_2d(x0..x1, (a0..a1).log_scale())?
            .set_secondary_coord(x0 * RPM..x1 * RPM, 0.0..1.0);
        chart
            .configure_mesh()
            .x_desc("excitation frequency ω [rad/s]")
            .y_desc("amplitude [m/N]")
            .x_label_formatter(&|v| format!("{v:.0}"))
            .y_label_formatter(&|v| log_tick(*v))
            .label_style((FONT, TICK))
            .axis_desc_style((FONT, DESC))
            .light_line_style(GRID)
            .draw()?;
        chart
            .configure_secondary_axes()
            .x_desc("excitation frequency [cpm]")
            .x_label_formatter(&|v| format!("{v:.0}"))
            .label_style((FONT, TICK))
            .axis_desc_style((FONT, DESC))
            .y_labels(0)
            .draw()?;
        let area = frame(&root, &chart)?;
        log_minor_labels(&root, area, (a0, a1), false)?;
        let ok = |(f, a): &(f64, f64)| f.is_finite() && a.is_finite() && *a > 0.0;
        let pts = r
            .frequencies
            .iter()
            .copied()
            .zip(r.amplitude.iter().copied());
        chart.draw_series(LineSeries::new(pts.filter(ok), PALETTE[0].stroke_width(2)))?;

        let mut chart = ChartBuilder::on(&bottom)
            .margin(14)
            .x_label_area_size(48)
            .y_label_area_size(84)
            .build_cartesian_2d(x0..x1, -180.0..180.0)?;
        chart
            .configure_mesh()
            .x_desc("excitation frequency ω [rad/s]")
            .y_desc("phase [deg]")
            .x_label_formatter(&|v| format!("{v:.0}"))
            .y_labels(0)
            .label_style((FONT, TICK))
            .axis_desc_style((FONT, DESC))
            .light_line_style(GRID)
            .draw()?;
        // Grid every 45 degrees, labelled every 90.
        for k in -4..=4 {
            let d = f64::from(k) * 45.0;
            let c = if k % 2 == 0 {
                RGBColor(200, 200, 200)
            } else {
                GRID
            };
            chart.draw_series(LineSeries::new([(x0, d), (x1, d)], c.stroke_width(1)))?;
            if k % 2 == 0 {
                let at = chart.backend_coord(&(x0, d));
                root.draw(&PathElement::new(
                    vec![(at.0 - 5, at.1), at],
                    BLACK.stroke_width(1),
                ))?;
                text(
                    &root,
                    &format!("{d:.0}"),
                    (at.0 - 10, at.1),
                    TICK,
                    BLACK,
                    (HPos::Right, VPos::Center),
                )?;
            }
        }
        frame(&root, &chart)?;
        // Wrapped to (-180, 180]; a wrap breaks the line.
        let mut run: Vec<(f64, f64)> = vec![];
        for (f, p) in r.frequencies.iter().zip(&r.phase) {
            if !(f.is_finite() && p.is_finite()) {
                chart.draw_series(LineSeries::new(
                    std::mem::take(&mut run),
                    PALETTE[1].stroke_width(2),
                ))?;
                continue;
            }
            let d = -((-p.to_degrees() + 180.0).rem_euclid(360.0) - 180.0);
            if run.last().is_some_and(|l| (l.1 - d).abs() > 180.0) {
                chart.draw_series(LineSeries::new(
                    std::mem::take(&mut run),
                    PALETTE[1].stroke_width(2),
                ))?;
            }
            run.push((*f, d));
        }
        chart.draw_series(LineSeries::new(run, PALETTE[1].stroke_width(2)))?;
        root.present()?;
    }
    Ok(svg)
}

/// `N_c = ... rpm, AF = ..., SM = ...% (req ...%)` of a peak.
pub(crate) fn peak_label(p: &crate::model::api::ResponsePeak) -> String {
    let fin = |v: Option<f64>| v.filter(|x| x.is_finite());
    let mut s = format!("N_c = {:.0} rpm", p.speed * RPM);
    match fin(p.amplification_factor) {
        Some(af) => s += &format!(", AF = {af:.1}"),
        None => s += ", AF = n/a",
    }
    if let Some(sm) = fin(p.separation_margin) {
        s += &format!(", SM = {sm:.1}%");
        match fin(p.required_margin) {
            Some(req) => s += &format!(" (req {req:.1}%)"),
            None => s += " (none req)",
        }
    }
    s
}

/// Orbit radius of each node against speed, each peak marked with its critical speed,
/// amplification factor and separation margin; the operating speeds `shade` shaded.
pub fn unbalance_with(
    r: &UnbalanceResponseResponse,
    shade: Option<[f64; 2]>,
) -> Result<String, Err> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (960, 600)).into_drawing_area();
        root.fill(&WHITE)?;
        let (x0, x1) = range(r.speeds.iter().copied(), 0.0);
        let max = r
            .nodes
            .iter()
            .flat_map(|n| &n.amplitude)
            .copied()
            .filter(|v| v.is_finite())
            .fold(0.0, f64::max);
        let (scale, unit) = length_unit(max);
        let (_, a1) = range([0.0, max * scale].into_iter(), 0.0);
        let a1 = a1 * 1.3;
        let mut chart = ChartBuilder::on(&root)
            .caption("Unbalance response", (FONT, 22))
            .margin(14)
            .x_label_area_size(48)
            .y_label_area_size(84)
            .top_x_label_area_size(44)
            .build_cartesian_2d(x0..x1, 0.0..a1)?
            .set_secondary_coord(x0 * RPM..x1 * RPM, 0.0..a1);
        chart
            .configure_mesh()
            .x_desc("spin speed [rad/s]")
            .y_desc(format!("orbit radius [{unit}]"))
            .x_label_formatter(&|v| format!("{v:.0}"))
            .y_label_formatter(&lin_tick(a1))
            .label_style((FONT, TICK))
            .axis_desc_style((FONT, DESC))
            .light_line_style(GRID)
            .draw()?;
        chart
            .configure_secondary_axes()
            .x_desc("spin speed [rpm]")
            .x_label_formatter(&|v| format!("{v:.0}"))
            .label_style((FONT, TICK))
            .axis_desc_style((FONT, DESC))
            .y_labels(0)
            .draw()?;
        let area = frame(&root, &chart)?;
        let mut labels = Labels::new(area);
        let mut entries = vec![];
        if let Some([lo, hi]) = shade {
            let (lo, hi) = (lo.max(x0), hi.min(x1));
            if lo.is_finite() && hi.is_finite() && hi > lo {
                chart.draw_series([Rectangle::new([(lo, 0.0), (hi, a1)], SHADE.filled())])?;
                let at = chart.backend_coord(&(lo, a1));
                let s = "operating range";
                let (w, h) = text_box(s, NOTE);
                labels.block([at.0, at.1, at.0 + w + 8, at.1 + h + 6]);
                text(
                    &root,
                    s,
                    (at.0 + 4, at.1 + 4),
                    NOTE,
                    INK,
                    (HPos::Left, VPos::Top),
                )?;
            }
        }
        for (k, n) in r.nodes.iter().enumerate() {
            let color = PALETTE[k % PALETTE.len()];
            let pts = r
                .speeds
                .iter()
                .zip(&n.amplitude)
                .filter(|(s, a)| s.is_finite() && a.is_finite());
            let pts: Vec<(f64, f64)> = pts.map(|(s, a)| (*s, a * scale)).collect();
            labels.block_path(&pixels(&chart, &pts));
            chart.draw_series(LineSeries::new(pts, color.stroke_width(2)))?;
            entries.push((format!("node {}", n.node), color, false));
        }
        let key_box = key(&root, (area[2] - 8, area[1] + 8), &entries)?;
        labels.block(key_box);
        let many = r.nodes.iter().filter(|n| !n.peaks.is_empty()).count() > 1;
        let mut marks = vec![];
        for (k, n) in r.nodes.iter().enumerate() {
            for p in &n.peaks {
                let pt = (p.speed, p.amplitude * scale);
                if !(pt.0.is_finite() && pt.1.is_finite() && (x0..=x1).contains(&pt.0)) {
                    continue;
                }
                let color = PALETTE[k % PALETTE.len()];
                chart.draw_series([
                    Circle::new(pt, 5, color.filled()),
                    Circle::new(pt, 5, INK.stroke_width(1)),
                ])?;
                let at = chart.backend_coord(&pt);
                labels.block([at.0 - 5, at.1 - 5, at.0 + 5, at.1 + 5]);
                let mut s = peak_label(p);
                if many {
                    s = format!("node {}: {s}", n.node);
                }
                let ink = if p.passes == Some(false) { FAIL } else { INK };
                marks.push((at, s, ink));
            }
        }
        marks.sort_by_key(|m| m.0.1);
        for (at, s, ink) in marks {
            let left = at.0 > (area[0] + area[2]) / 2;
            label(&root, &mut labels, &s, at, ink, left)?;
        }
        root.present()?;
    }
    Ok(svg)
}
