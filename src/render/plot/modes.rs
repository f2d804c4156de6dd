//! Mode shapes of a modal answer along the shaft: the lowest rotor poles that carry a shape.

use super::svg::{Anchor, Axis, INK, Stroke, Svg, extent, nice_step, spread};
use super::{COLOURS, Err, speed_label};
use crate::model::api::{ModalResponse, Pole, Whirl};

/// Modes drawn at most.
pub const MODES: usize = 6;

/// The lowest (by |frequency|) rotor poles with a shape of at least two nodes.
fn shaped(m: &ModalResponse) -> Vec<&Pole> {
    let mut v: Vec<&Pole> = m
        .poles
        .iter()
        .filter(|p| p.whirl != Whirl::Internal && p.frequency.is_finite())
        .filter(|p| p.shape.as_ref().is_some_and(|s| s.len() >= 2))
        .collect();
    v.sort_by(|a, b| a.frequency.abs().total_cmp(&b.frequency.abs()));
    v.truncate(MODES);
    v
}

/// Whether [`modal`] draws `m`: some rotor pole has a shape along a shaft.
pub fn modal_plotted(m: &ModalResponse) -> bool {
    !shaped(m).is_empty()
}

/// The real part of the mode shape (the translation `x + i y` of each node, largest 1) of
/// the lowest [`MODES`] rotor poles against node number, each labelled with its frequency and
/// whirl direction (forward solid, backward dashed); `None` when no pole has a shape along
/// a shaft (a Jeffcott rotor's single node).
pub fn modal(m: &ModalResponse) -> Result<Option<String>, Err> {
    let poles = shaped(m);
    if poles.is_empty() {
        return Ok(None);
    }
    let nodes = poles
        .iter()
        .flat_map(|p| p.shape.iter().flatten().map(|d| d.node as f64));
    let (n0, n1) = extent(nodes).unwrap_or((0.0, 1.0));
    let values = poles
        .iter()
        .flat_map(|p| p.shape.iter().flatten().map(|d| d.re));
    let (lo, hi) = extent(values).unwrap_or((-1.0, 1.0));
    let (lo, hi) = (lo.min(0.0).min(-0.1) - 0.08, hi.max(1.0) + 0.08);
    let mut svg = Svg::new(960, 600);
    svg.caption(
        (480.0, 24.0),
        &format!("Mode shapes at Ω = {}", speed_label(m.speed)),
    );
    let pad = ((n1 - n0) * 0.02).max(0.2);
    let p = svg.panel(
        [84.0, 50.0, 880.0, 470.0],
        Axis::lin(n0 - pad, n1 + pad).with_step(nice_step((n1 - n0) / 10.0).max(1.0)),
        Axis::lin(lo, hi),
    );
    svg.axes(&p, "node", "mode shape Re(x + i y), largest = 1");
    svg.path(
        &p,
        &[(p.x.lo, 0.0), (p.x.hi, 0.0)],
        Stroke::solid(INK, 1.0),
        "zero",
    );
    let mut key = vec![];
    let mut ends = vec![];
    let mut counts = (0, 0);
    for pole in &poles {
        let forward = pole.whirl == Whirl::Forward;
        // Mode numbers counted per whirl direction, as in the Campbell diagram.
        let mode = if forward {
            counts.0 += 1;
            counts.0
        } else {
            counts.1 += 1;
            counts.1
        };
        let tag = format!("{mode}{}", if forward { "F" } else { "B" });
        let color = COLOURS[(mode - 1) % COLOURS.len()];
        let stroke = Stroke {
            dash: (!forward).then_some("9 5"),
            ..Stroke::solid(color, 2.0)
        };
        let mut pts: Vec<(f64, f64)> = pole
            .shape
            .iter()
            .flatten()
            .map(|d| (d.node as f64, d.re))
            .collect();
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        svg.path(&p, &pts, stroke, &format!("shape mode-{tag}"));
        // Markers at the nodes while they stay apart.
        for q in pts.iter().filter(|_| pts.len() <= 30) {
            if q.1.is_finite() {
                svg.circle_px(p.px(*q), 2.5, color, color);
            }
        }
        let whirl = if forward { "forward" } else { "backward" };
        let mut s = format!("{tag}: {}, {whirl}", speed_label(pole.frequency.abs()));
        if let Some(d) = pole.log_decrement.filter(|d| d.is_finite()) {
            s += &format!(", δ = {d:.3}");
        }
        key.push((s, color, stroke.dash));
        if let Some(last) = pts.last() {
            ends.push((p.px(*last), tag, color));
        }
    }
    let ys: Vec<f64> = ends.iter().map(|e| e.0.1 + 4.0).collect();
    let ys = spread(&ys, 13.0, p.rect[1] + 8.0, p.rect[3]);
    for (e, y) in ends.iter().zip(ys) {
        svg.text((p.rect[2] + 6.0, y), &e.1, 12.0, Anchor::Start, e.2);
    }
    svg.key((84.0, 520.0), &key[..key.len().min(3)]);
    if key.len() > 3 {
        svg.key((500.0, 520.0), &key[3..]);
    }
    Ok(Some(svg.finish()))
}
