//! SVG plots of analysis results, written directly as SVG (`plot/svg.rs`, its axes in `plot/axis.rs`: sub-pixel paths,
//! real dashes, clip paths; the viewer renders the text). The plots: `plot/campbell.rs`
//! (Campbell diagram with its decay-rate panel, stability), `plot/response.rs` (time response
//! with its orbits, unbalance response as a Bode plot), `plot/modes.rs` (mode shapes of a
//! modal answer). Here the helpers shared with [`super::plot_audit`].

use plotters::style::{RGBAColor, RGBColor};

pub mod axis;
mod campbell;
mod interference;
mod modes;
mod response;
mod shaft_loads;
mod stability;
mod study;
pub mod svg;

pub use campbell::{campbell, campbell_with, decay_range};
pub use interference::interference;
pub use modes::{modal, modal_plotted};
pub use response::{time, unbalance};
pub use stability::{stability, stability_with};
pub use study::study;

pub use crate::model::speeds::RPM;
pub(crate) const PALETTE: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(23, 190, 207),
];
/// [`PALETTE`] as SVG colours, then four more for plots with more lines.
pub(crate) const COLOURS: [&str; 10] = [
    "#1F77B4", "#D62728", "#2CA02C", "#9467BD", "#FF7F0E", "#17BECF", "#8C564B", "#E377C2",
    "#7F7F7F", "#BCBD22",
];

/// Fill of a shaded operating range.
pub(crate) const SHADE: RGBAColor = RGBAColor(255, 170, 40, 0.22);
pub(crate) const SHADE_HEX: &str = "#FFAA28";

type Err = Box<dyn std::error::Error>;

/// `[lo, hi]` of finite values, padded; a flat or empty set gets a unit range.
pub(crate) fn range(values: impl Iterator<Item = f64>, pad: f64) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    let span = if hi > lo { hi - lo } else { lo.abs().max(1.0) };
    (lo - pad * span, hi + pad * span)
}

/// Runs of consecutive defined points (a `null` breaks the line).
pub(crate) fn runs(xs: &[f64], ys: &[Option<f64>]) -> Vec<Vec<(f64, f64)>> {
    let mut out = vec![vec![]];
    for (x, y) in xs.iter().zip(ys) {
        match y {
            Some(y) if y.is_finite() => out.last_mut().expect("non-empty").push((*x, *y)),
            _ => {
                if !out.last().expect("non-empty").is_empty() {
                    out.push(vec![]);
                }
            }
        }
    }
    out.retain(|r| !r.is_empty());
    out
}

/// `[lo, hi]` clipped to `[x0, x1]`, if they overlap.
pub(crate) fn clip(shade: Option<[f64; 2]>, x0: f64, x1: f64) -> Option<(f64, f64)> {
    let [lo, hi] = shade?;
    let (lo, hi) = (lo.min(hi).max(x0), hi.max(lo).min(x1));
    (lo.is_finite() && hi.is_finite() && hi > lo).then_some((lo, hi))
}

/// `"123.4 rad/s (1178 rpm)"`, the decimals fitting the size of `w`.
pub(crate) fn speed_label(w: f64) -> String {
    speed_label_in(w, false)
}

/// [`speed_label`], or on a nondimensional plot `"Ω* = 1.00"` (Ω / sqrt(k/m)).
pub(crate) fn speed_label_in(w: f64, nondimensional: bool) -> String {
    let d = if w.abs() >= 100.0 {
        1
    } else if w.abs() >= 1.0 {
        2
    } else {
        3
    };
    if nondimensional {
        return format!("Ω* = {w:.d$}");
    }
    if w == 0.0 {
        return "0 rad/s (0 rpm)".into();
    }
    let rpm = w * RPM;
    let rd = if rpm.abs() >= 100.0 { 0 } else { 2 };
    format!("{w:.d$} rad/s ({rpm:.rd$} rpm)")
}

/// An axis title of a nondimensional plot: each quantity over its scale (`spin speed Ω* =
/// Ω/√(k/m)`), no physical unit left.
pub(crate) fn unit_free(desc: &str) -> String {
    desc.replace("spin speed [rad/s]", "spin speed Ω* = Ω/√(k/m)")
        .replace("|ω| [rad/s]", "|ω*| = |ω|/√(k/m)")
        .replace("σ [1/s]", "σ* = σ/√(k/m)")
        .replace("time [s]", "time t* = t·√(k/m)")
        .replace(" [rad/s]", " [–]")
        .replace(" [1/s]", " [–]")
}

/// At most this many points per line (evenly strided; more do not show at this size).
const MAX_POINTS: usize = 6000;

pub(crate) fn stride<T: Copy>(v: &[T]) -> impl Iterator<Item = T> + '_ {
    let step = v.len().div_ceil(MAX_POINTS).max(1);
    v.iter().copied().step_by(step)
}
