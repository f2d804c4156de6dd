//! SVG plots of the audit analyses (API 684 / API 617): the undamped critical speed map, static
//! deflection and bending moment, the Level I screen, the frequency response (Bode), the
//! unbalance response with its peaks, and a sketch of the rotor. Same style as
//! [`super::plot`]: SVG text, the viewer renders the fonts, so label sizes are estimated and
//! [`Labels`] keeps annotations apart.
//!
//! Here the shared helpers; the plots in `plot_audit/`: `map.rs` (critical speed map, static
//! deflection), `response.rs` (Level I, frequency response, unbalance), `sketch.rs` (rotor).

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::plot::axis::length_unit;
use super::plot::{PALETTE, RPM, SHADE, clip, range, runs};
use crate::model::api::{
    CriticalSpeedMapResponse, FrequencyResponseResponse, Level1Response, StaticResponse,
    UnbalanceResponseResponse,
};

mod labels;
mod map;
mod response;
mod shape;
mod sketch;

pub(crate) use labels::Labels;
use labels::nearest;
pub use map::{critical_speed_map, critical_speed_map_with, static_deflection};
pub use response::{frequency_response, level1, unbalance_bode, unbalance_with};
pub use shape::mode_shapes;
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
    leader(root, at, &[x, y, x + w, y + h], 6.0, color)?;
    text(root, s, (x, y), NOTE, color, (HPos::Left, VPos::Top))
}

/// A thin line from `gap` pixels off the marker `at` to the nearest point of the label's box
/// `b`, when the label is not beside the marker.
fn leader(root: &Area<'_>, at: (i32, i32), b: &Rect, gap: f64, color: RGBColor) -> Result<(), Err> {
    let near = nearest(at, b);
    if (near.0 - at.0).abs() + (near.1 - at.1).abs() > 10 {
        let (dx, dy) = (f64::from(near.0 - at.0), f64::from(near.1 - at.1));
        let k = gap / dx.hypot(dy);
        let from = (at.0 + (dx * k) as i32, at.1 + (dy * k) as i32);
        root.draw(&PathElement::new(
            vec![from, near],
            color.mix(0.8).stroke_width(1),
        ))?;
    }
    Ok(())
}

/// A callout `s` in the box `r` on a white ground (it may lie across a curve), joined to its
/// marker `at` by a thin line from the marker's edge when it is not beside it.
fn callout(root: &Area<'_>, s: &str, at: (i32, i32), r: Rect, color: RGBColor) -> Result<(), Err> {
    // The ground as wide as the glyphs (DejaVu Sans: ~0.54 em a character, the box allows
    // 0.62), so that it hides no more of a curve than the text does.
    let w = (f64::from(r[2] - r[0]) * 0.9) as i32;
    root.draw(&Rectangle::new(
        [(r[0] - 2, r[1]), (r[0] + w + 2, r[3])],
        WHITE.mix(0.8).filled(),
    ))?;
    leader(root, at, &r, 7.0, color)?;
    text(root, s, (r[0], r[1]), NOTE, color, (HPos::Left, VPos::Top))
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

/// Label count of a log axis `[lo, hi]` that makes plotters label the powers of ten only (and
/// draw light lines at their multiples).
pub(crate) fn log_labels(lo: f64, hi: f64) -> usize {
    let decades = (hi / lo).log10();
    if decades.is_finite() {
        decades.floor().max(1.0) as usize + 1
    } else {
        2
    }
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

/// The operating range shaded over the data box `[from, to]` of `chart`, named inside its
/// top-left corner (the name's box kept free in `labels`).
fn operating_range<X: Ranged<ValueType = f64>, Y: Ranged<ValueType = f64>>(
    root: &Area<'_>,
    chart: &mut ChartContext<'_, SVGBackend<'_>, Cartesian2d<X, Y>>,
    labels: &mut Labels,
    from: (f64, f64),
    to: (f64, f64),
) -> Result<(), Err> {
    chart.draw_series([Rectangle::new([from, to], SHADE.filled())])?;
    let at = chart.backend_coord(&(from.0.min(to.0), from.1.max(to.1)));
    let s = "operating range";
    let (w, h) = text_box(s, NOTE);
    labels.block([at.0, at.1, at.0 + w + 12, at.1 + h + 6]);
    text(
        root,
        s,
        (at.0 + 6, at.1 + 3),
        NOTE,
        INK,
        (HPos::Left, VPos::Top),
    )
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_read_well() {
        assert_eq!(log_tick(1e6), "1e6");
        assert_eq!(log_tick(2e6), "2e6");
        assert_eq!(log_tick(2000.0), "2000");
        assert_eq!(log_tick(10000.0), "10000");
        assert_eq!(log_tick(5e-6), "5e-6");
        assert_eq!(log_tick(0.05), "0.05");
        assert_eq!(log_tick(f64::NAN), "");
        assert_eq!(lin_tick(600.0)(&-100.0), "-100");
        assert_eq!(lin_tick(1.5)(&0.2), "0.2");
        assert_eq!(lin_tick(1.3)(&-1e-17), "0");
        assert_eq!(log_labels(50.0, 5000.0), 3);
    }

    #[test]
    fn labels_keep_apart_and_inside() {
        let bounds = [0, 0, 600, 400];
        let mut labels = Labels::new(bounds);
        labels.block_path(&[(0, 200), (600, 200)]);
        let mut boxes: Vec<Rect> = vec![];
        for k in 0..12 {
            let s = format!("label number {k}");
            let (x, y) = labels.place((300, 200), &s, NOTE, k % 2 == 0);
            let (w, h) = text_box(&s, NOTE);
            let r = [x, y, x + w, y + h];
            assert!(
                r[0] >= 0 && r[1] >= 0 && r[2] <= 600 && r[3] <= 400,
                "{r:?}"
            );
            assert!(!(r[1] < 202 && r[3] > 198), "{r:?} on the line");
            assert!(boxes.iter().all(|b| !overlaps_for_test(b, &r)), "{r:?}");
            boxes.push(r);
        }
    }

    fn overlaps_for_test(a: &Rect, b: &Rect) -> bool {
        a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3]
    }
}
