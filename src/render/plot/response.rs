//! The time response (whirl amplitude against time, and the orbits y against x of each node)
//! and the unbalance response as a Bode plot (amplitude over phase against speed).

use super::svg::{Anchor, Axis, INK, Panel, Stroke, Svg, extent, length_unit, spread, text_width};
use super::{COLOURS, Err, RPM, stride};
use crate::model::api::{TimeResponseResponse, UnbalanceResponseResponse};

/// Whirl amplitude `|x + i y|` of each node against time (left) and the orbits, y against x
/// at equal scales (right).
pub fn time(r: &TimeResponseResponse) -> Result<String, Err> {
    if !r.elements.is_empty() {
        return super::shaft_loads::time(r);
    }
    let mut svg = Svg::new(1200, 560).nondimensional(r.nondimensional);
    let amps: Vec<Vec<f64>> = r
        .nodes
        .iter()
        .map(|n| n.x.iter().zip(&n.y).map(|(x, y)| x.hypot(*y)).collect())
        .collect();
    let max = extent(amps.iter().flatten().copied()).map_or(0.0, |e| e.1);
    let (k, unit) = length_unit(max);
    let (t0, t1) = extent(r.time.iter().copied()).unwrap_or((0.0, 1.0));
    let a1 = if max > 0.0 { max * k * 1.05 } else { 1.0 };
    svg.caption((380.0, 24.0), "Time response: whirl amplitude");
    let p = svg.panel(
        [84.0, 50.0, 690.0, 480.0],
        Axis::lin(t0, t1),
        Axis::lin(0.0, a1),
    );
    svg.axes(
        &p,
        "time [s]",
        &format!("whirl amplitude |x + i y| [{unit}]"),
    );
    let mut key = vec![];
    for (j, (n, a)) in r.nodes.iter().zip(&amps).enumerate() {
        let color = COLOURS[j % COLOURS.len()];
        let pts: Vec<(f64, f64)> = r.time.iter().zip(a).map(|(t, a)| (*t, a * k)).collect();
        let pts: Vec<(f64, f64)> = stride(&pts).collect();
        svg.path(
            &p,
            &pts,
            Stroke::solid(color, 1.5),
            &format!("amplitude node-{}", n.node),
        );
        key.push((format!("node {}", n.node), color, None));
    }
    svg.key_in(&p, &key);

    // Orbits: a square area, equal scales on x and y.
    let reach = r
        .nodes
        .iter()
        .flat_map(|n| n.x.iter().chain(&n.y))
        .filter(|v| v.is_finite())
        .fold(0.0f64, |m, v| m.max(v.abs()));
    let (ko, unit_o) = length_unit(reach);
    let e = if reach > 0.0 { reach * ko * 1.08 } else { 1.0 };
    svg.caption((975.0, 24.0), "Orbits");
    let o = svg.panel(
        [790.0, 70.0, 1160.0, 440.0],
        Axis::lin(-e, e),
        Axis::lin(-e, e),
    );
    svg.axes(&o, &format!("x [{unit_o}]"), &format!("y [{unit_o}]"));
    let cross = Stroke::solid("#BBBBBB", 1.0);
    svg.path(&o, &[(-e, 0.0), (e, 0.0)], cross, "");
    svg.path(&o, &[(0.0, -e), (0.0, e)], cross, "");
    for (j, n) in r.nodes.iter().enumerate() {
        let color = COLOURS[j % COLOURS.len()];
        let pts: Vec<(f64, f64)> =
            n.x.iter()
                .zip(&n.y)
                .map(|(x, y)| (x * ko, y * ko))
                .collect();
        let pts: Vec<(f64, f64)> = stride(&pts).collect();
        let faint = Stroke {
            opacity: 0.3,
            ..Stroke::solid(color, 0.8)
        };
        svg.path(&o, &pts, faint, &format!("orbit node-{}", n.node));
        let tail = &pts[pts.len() - pts.len().div_ceil(10)..];
        let name = format!("orbit-end node-{}", n.node);
        svg.path(&o, tail, Stroke::solid(color, 1.6), &name);
        if let Some(last) = pts.last().filter(|q| q.0.is_finite() && q.1.is_finite()) {
            svg.circle_px(o.px(*last), 3.5, color, INK);
        }
    }
    svg.text(
        (975.0, 500.0),
        "faint: the whole history; bold: its last tenth; dot: the end",
        12.0,
        Anchor::Middle,
        INK,
    );
    Ok(svg.finish())
}

/// Whether the amplitudes call for a log axis: the peak is more than 30 times the median
/// (positive values), so a linear axis would flatten everything off resonance.
pub(crate) fn wants_log(values: &[f64]) -> bool {
    let mut v: Vec<f64> = values
        .iter()
        .copied()
        .filter(|v| v.is_finite() && *v > 0.0)
        .collect();
    if v.len() < 3 {
        return false;
    }
    v.sort_by(f64::total_cmp);
    v[v.len() - 1] > 30.0 * v[v.len() / 2]
}

/// Unwrapped phase in degrees.
fn unwrap_deg(phase: &[f64]) -> Vec<f64> {
    let mut out = Vec::with_capacity(phase.len());
    let mut offset = 0.0;
    let mut prev: Option<f64> = None;
    for &p in phase {
        if !p.is_finite() {
            out.push(f64::NAN);
            continue;
        }
        if let Some(q) = prev {
            let d = p + offset - q;
            offset -= (d / std::f64::consts::TAU).round() * std::f64::consts::TAU;
        }
        let v = p + offset;
        prev = Some(v);
        out.push(v.to_degrees());
    }
    out
}

/// Bode plot of the unbalance response: the semi-major axis of each node's orbit (zero to
/// peak; the radius of a circular orbit) on a linear axis, or a log one when the peak is over
/// 30 times the median; below it the phase of the forward whirl, unwrapped, in degrees. The
/// peaks are marked with their speed.
pub fn unbalance(r: &UnbalanceResponseResponse) -> Result<String, Err> {
    let mut svg = Svg::new(960, 880).nondimensional(r.nondimensional);
    let (x0, x1) = extent(r.speeds.iter().copied()).unwrap_or((0.0, 1.0));
    let x = Axis::lin(x0, x1);
    let all: Vec<f64> = r
        .nodes
        .iter()
        .flat_map(|n| n.amplitude.iter().copied())
        .collect();
    let peaks = r
        .nodes
        .iter()
        .flat_map(|n| n.peaks.iter().map(|p| p.amplitude));
    let max = extent(all.iter().copied().chain(peaks)).map_or(0.0, |e| e.1);
    let (k, unit) = length_unit(max);
    let log = wants_log(&all);
    let y = if log {
        let lo = all
            .iter()
            .copied()
            .filter(|v| v.is_finite() && *v > 0.0)
            .fold(f64::INFINITY, f64::min);
        // At most five decades below the peak.
        let lo = (lo * k).max(max * k * 1e-5);
        Axis::log(10f64.powf((lo).log10().floor()), max * k * 1.5)
    } else {
        Axis::lin(0.0, if max > 0.0 { max * k * 1.08 } else { 1.0 })
    };
    svg.caption((480.0, 24.0), "Unbalance response (Bode plot)");
    let p = svg.panel([84.0, 84.0, 896.0, 480.0], x, y);
    let scale = if log { ", log scale" } else { "" };
    svg.axes(
        &p,
        "spin speed [rad/s]",
        &format!("semi-major axis of the orbit, 0-pk [{unit}]{scale}"),
    );
    svg.top_axis(&p, RPM, "spin speed [rpm]");
    let mut key = vec![];
    let mut marks = vec![];
    for (j, n) in r.nodes.iter().enumerate() {
        let color = COLOURS[j % COLOURS.len()];
        let mut pts: Vec<(f64, f64)> = r
            .speeds
            .iter()
            .zip(&n.amplitude)
            .map(|(s, a)| (*s, a * k))
            .collect();
        // The refined peaks are points of the curve too (a sharp one falls between the
        // grid's speeds).
        for pk in n
            .peaks
            .iter()
            .filter(|p| p.speed.is_finite() && p.amplitude.is_finite())
        {
            let at = pts.partition_point(|q| q.0 < pk.speed);
            pts.insert(at, (pk.speed, pk.amplitude * k));
        }
        svg.path(
            &p,
            &pts,
            Stroke::solid(color, 2.0),
            &format!("amplitude node-{}", n.node),
        );
        key.push((format!("node {}", n.node), color, None));
        for pk in &n.peaks {
            let q = (pk.speed, pk.amplitude * k);
            if q.0.is_finite() && q.1.is_finite() && p.contains(q) {
                marks.push((p.px(q), color, pk.speed));
            }
        }
    }
    peak_marks(&mut svg, &p, marks);
    svg.key_in(&p, &key);

    let phases: Vec<Vec<f64>> = r.nodes.iter().map(|n| unwrap_deg(&n.phase)).collect();
    let (lo, hi) = extent(phases.iter().flatten().copied()).unwrap_or((-180.0, 0.0));
    let (lo, hi) = ((lo / 90.0).floor() * 90.0, (hi / 90.0).ceil() * 90.0);
    let (lo, hi) = if hi - lo < 90.0 {
        (lo - 45.0, hi + 45.0)
    } else {
        (lo, hi)
    };
    let step = if hi - lo > 720.0 {
        180.0
    } else if hi - lo > 180.0 {
        90.0
    } else {
        45.0
    };
    let q = svg.panel(
        [84.0, 560.0, 896.0, 820.0],
        x,
        Axis::lin(lo, hi).with_step(step),
    );
    svg.axes(&q, "spin speed [rad/s]", "phase of the forward whirl [°]");
    for (j, (n, ph)) in r.nodes.iter().zip(&phases).enumerate() {
        let color = COLOURS[j % COLOURS.len()];
        let pts: Vec<(f64, f64)> = r.speeds.iter().copied().zip(ph.iter().copied()).collect();
        svg.path(
            &q,
            &pts,
            Stroke::solid(color, 2.0),
            &format!("phase node-{}", n.node),
        );
    }
    svg.text(
        (480.0, 548.0),
        "phase of the forward whirl relative to the unbalance at phase 0, unwrapped",
        12.0,
        Anchor::Middle,
        INK,
    );
    Ok(svg.finish())
}

/// A ring at each peak, labelled with its speed: one label for the peaks of several nodes at
/// the same speed (on the highest), right of its ring or left where the plot ends, moved apart
/// with a leader line to its ring when moved.
fn peak_marks(svg: &mut Svg, p: &Panel, mut marks: Vec<((f64, f64), &str, f64)>) {
    marks.sort_by(|a, b| a.0.0.total_cmp(&b.0.0));
    marks.dedup_by(|a, b| (a.0.0 - b.0.0).abs() < 2.0 && (a.0.1 - b.0.1).abs() < 2.0);
    for m in &marks {
        svg.circle_px(m.0, 5.0, m.1, INK);
    }
    let mut named: Vec<usize> = vec![];
    for (k, m) in marks.iter().enumerate() {
        match named.last_mut() {
            Some(j) if (marks[*j].2 - m.2).abs() <= 5e-3 * m.2.abs() => {
                if m.0.1 < marks[*j].0.1 {
                    *j = k;
                }
            }
            _ => named.push(k),
        }
    }
    let ys: Vec<f64> = named.iter().map(|&k| marks[k].0.1 - 10.0).collect();
    let ys = spread(&ys, 15.0, p.rect[1] + 12.0, p.rect[3] - 4.0);
    for (&k, y) in named.iter().zip(ys) {
        let ((x0, y0), _, speed) = marks[k];
        let s = format!("peak {}", svg.speed_label(speed));
        // Clear of every ring beside the label's line, not only its own (two nodes' peaks a
        // few pixels apart otherwise put one's ring inside the other's label).
        let beside: Vec<f64> = marks
            .iter()
            .filter(|m| (m.0.0 - x0).abs() < 16.0 && (m.0.1 - (y - 4.0)).abs() < 12.0)
            .map(|m| m.0.0)
            .chain([x0])
            .collect();
        let (lo, hi) = beside
            .iter()
            .fold((x0, x0), |(lo, hi), &x| (lo.min(x), hi.max(x)));
        let right = hi + 9.0 + text_width(&s, 12.0) <= p.rect[2] - 2.0;
        let (x, anchor) = if right {
            (hi + 9.0, Anchor::Start)
        } else {
            (lo - 9.0, Anchor::End)
        };
        if (y - (y0 - 10.0)).abs() > 6.0 {
            svg.line_px(&[(x0, y0), (x, y - 4.0)], Stroke::solid(INK, 0.8));
        }
        svg.text((x, y), &s, 12.0, anchor, INK);
    }
}
