//! Mode shapes of a modal answer along the shaft: the lowest rotor poles that carry a shape,
//! over a sketch of the rotor.

use super::svg::{Anchor, Axis, FRAME, INK, Panel, Stroke, Svg, extent, nice_step, spread};
use super::{COLOURS, Err, speed_label};
use crate::model::api::{ModalResponse, NodeDisplacement, Pole, ShaftLayout, Whirl};

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

/// Points drawn per element between two nodes that keep their rotations.
const PER_ELEMENT: usize = 12;

/// The mode shape's real part along the shaft: `(position, value)` at the nodes, and between
/// two consecutive nodes with slopes the element's cubic Hermite shape functions of both
/// ends' translations and slopes (the beam element's own interpolation; a coupling's nodes
/// joined straight); without a layout, against node number, the nodes joined straight.
fn curve(pole: &Pole, shaft: Option<&ShaftLayout>) -> Vec<(f64, f64)> {
    let mut nodes: Vec<&NodeDisplacement> = pole.shape.iter().flatten().collect();
    nodes.sort_by_key(|d| d.node);
    let Some(shaft) = shaft else {
        return nodes.iter().map(|d| (d.node as f64, d.re)).collect();
    };
    let z = |d: &NodeDisplacement| shaft.positions.get(d.node).copied();
    let mut out: Vec<(f64, f64)> = vec![];
    for (k, d) in nodes.iter().enumerate() {
        let Some(z0) = z(d) else { continue };
        // Across a coupling (a spring, not a beam) the nodes are joined straight.
        let next = nodes
            .get(k + 1)
            .filter(|e| e.node == d.node + 1 && !shaft.couplings.contains(&d.node));
        match (next, d.slope, next.and_then(|e| e.slope)) {
            (Some(e), Some(s0), Some(s1)) if z(e).is_some() => {
                let l = z(e).unwrap_or(z0) - z0;
                for i in 0..PER_ELEMENT {
                    let x = i as f64 / PER_ELEMENT as f64;
                    let h = [
                        1.0 - 3.0 * x * x + 2.0 * x * x * x,
                        l * (x - 2.0 * x * x + x * x * x),
                        3.0 * x * x - 2.0 * x * x * x,
                        l * (x * x * x - x * x),
                    ];
                    let v = d.re * h[0] + s0[0] * h[1] + e.re * h[2] + s1[0] * h[3];
                    out.push((z0 + x * l, v));
                }
            }
            _ => out.push((z0, d.re)),
        }
    }
    out
}

/// The rotor in a strip `r` (pixels) over the plot, on the plot's x axis: the shaft as a
/// line, couplings as amber blocks on it, disks as blocks, bearings as triangles, seals as
/// small squares.
fn schematic(svg: &mut Svg, p: &Panel, r: [f64; 4], shaft: &ShaftLayout) {
    let mid = (r[1] + r[3]) / 2.0;
    let x = |z: f64| p.px((z, p.y.lo)).0;
    let (z0, z1) = (
        shaft.positions.first().copied().unwrap_or(0.0),
        shaft.positions.last().copied().unwrap_or(0.0),
    );
    svg.rect_px(
        [x(z0), mid - 2.5, x(z1), mid + 2.5],
        "#9AA0A6",
        1.0,
        Some(FRAME),
    );
    // Couplings: a gap in the shaft bridged by a flanged block.
    for &n in &shaft.couplings {
        if let (Some(&a), Some(&b)) = (shaft.positions.get(n), shaft.positions.get(n + 1)) {
            svg.rect_px(
                [x(a), mid - 6.0, x(b), mid + 6.0],
                "#E2A85C",
                1.0,
                Some("#965F1E"),
            );
        }
    }
    for &n in &shaft.disks {
        if let Some(&z) = shaft.positions.get(n) {
            svg.rect_px(
                [x(z) - 4.0, r[1] + 2.0, x(z) + 4.0, r[3] - 2.0],
                "#5F6B7A",
                1.0,
                None,
            );
        }
    }
    for &n in &shaft.bearings {
        if let Some(&z) = shaft.positions.get(n) {
            let (a, t) = (x(z), mid + 3.0);
            svg.raw(&format!(
                "<path d=\"M{a:.2},{t:.2} L{:.2},{:.2} L{:.2},{:.2} Z\" fill=\"#C81414\"/>\n",
                a - 7.0,
                t + 12.0,
                a + 7.0,
                t + 12.0
            ));
            // Where the bearing is, across the plot.
            svg.line_px(
                &[(a, p.rect[1]), (a, p.rect[3])],
                Stroke::dashed("#C81414", 1.0, "2 4"),
            );
        }
    }
    for &n in &shaft.seals {
        if let Some(&z) = shaft.positions.get(n) {
            svg.rect_px(
                [x(z) - 4.0, mid + 3.0, x(z) + 4.0, mid + 11.0],
                "#FF7F0E",
                1.0,
                Some(INK),
            );
        }
    }
}

/// The real part of the mode shape (the translation `x + i y` of each node, largest 1) of
/// the lowest [`MODES`] rotor poles along the shaft (the rotor drawn above: disks, bearings,
/// seals), interpolated by the elements' shape functions; against node number for a rotor
/// given as matrices. Each labelled with its frequency and whirl direction (forward solid,
/// backward dashed); `None` when no pole has a shape along a shaft (a Jeffcott rotor's
/// single node).
pub fn modal(m: &ModalResponse) -> Result<Option<String>, Err> {
    let poles = shaped(m);
    if poles.is_empty() {
        return Ok(None);
    }
    let shaft = m.shaft.as_ref().filter(|s| s.positions.len() >= 2);
    let curves: Vec<Vec<(f64, f64)>> = poles.iter().map(|p| curve(p, shaft)).collect();
    let (n0, n1) = match shaft {
        Some(s) => extent(s.positions.iter().copied()),
        None => extent(curves.iter().flatten().map(|q| q.0)),
    }
    .unwrap_or((0.0, 1.0));
    let (lo, hi) = extent(curves.iter().flatten().map(|q| q.1)).unwrap_or((-1.0, 1.0));
    let (lo, hi) = (lo.min(0.0).min(-0.1) - 0.08, hi.max(1.0) + 0.08);
    let mut svg = Svg::new(960, 660);
    svg.caption(
        (480.0, 24.0),
        &format!("Mode shapes at Ω = {}", speed_label(m.speed)),
    );
    let top = if shaft.is_some() { 96.0 } else { 50.0 };
    let (x_axis, x_desc) = match shaft {
        Some(_) => {
            let pad = (n1 - n0) * 0.02;
            (Axis::lin(n0 - pad, n1 + pad), "axial position [m]")
        }
        None => {
            let pad = ((n1 - n0) * 0.02).max(0.2);
            (
                Axis::lin(n0 - pad, n1 + pad).with_step(nice_step((n1 - n0) / 10.0).max(1.0)),
                "node",
            )
        }
    };
    let p = svg.panel([84.0, top, 880.0, 500.0], x_axis, Axis::lin(lo, hi));
    svg.axes(&p, x_desc, "mode shape Re(x + i y), largest = 1");
    if let Some(s) = shaft {
        schematic(&mut svg, &p, [84.0, 44.0, 880.0, 86.0], s);
    }
    svg.path(
        &p,
        &[(p.x.lo, 0.0), (p.x.hi, 0.0)],
        Stroke::solid(INK, 1.0),
        "zero",
    );
    let mut key = vec![];
    let mut ends = vec![];
    let mut counts = (0, 0);
    for (pole, pts) in poles.iter().zip(&curves) {
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
        svg.path(&p, pts, stroke, &format!("shape mode-{tag}"));
        // Markers at the nodes while they stay apart.
        let mut nodes: Vec<(f64, f64)> = pole
            .shape
            .iter()
            .flatten()
            .filter_map(|d| {
                let x = match shaft {
                    Some(s) => *s.positions.get(d.node)?,
                    None => d.node as f64,
                };
                Some((x, d.re))
            })
            .collect();
        nodes.sort_by(|a, b| a.0.total_cmp(&b.0));
        for q in nodes.iter().filter(|_| nodes.len() <= 30) {
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
    svg.key((84.0, 560.0), &key[..key.len().min(3)]);
    if key.len() > 3 {
        svg.key((500.0, 560.0), &key[3..]);
    }
    Ok(Some(svg.finish()))
}
