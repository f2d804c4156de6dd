//! A torsional (or axial) time response: the torque (axial force) in the most loaded element of
//! each shaft against time, and the train's speed (its rigid motion's rate) beside it.

use super::svg::{Axis, Stroke, Svg, extent};
use super::{COLOURS, Err, RPM, stride};
use crate::model::api::{ElementLoadHistory, Motion, TimeResponseResponse};

/// The most loaded element of each shaft: the runs of elements with a section (stress) between
/// couplings and meshes.
fn per_shaft(elements: &[ElementLoadHistory]) -> Vec<(usize, &ElementLoadHistory)> {
    let mut out: Vec<(usize, &ElementLoadHistory)> = vec![];
    let mut shaft = 0;
    let mut open = false;
    for e in elements {
        if e.peak_stress.is_none() {
            if open {
                shaft += 1;
            }
            open = false;
            continue;
        }
        open = true;
        match out.last_mut() {
            Some((s, best)) if *s == shaft => {
                if e.peak > best.peak {
                    *best = e;
                }
            }
            _ => out.push((shaft, e)),
        }
    }
    if out.is_empty() {
        // Couplings and meshes only: the most loaded of them.
        if let Some(e) = elements.iter().max_by(|a, b| a.peak.total_cmp(&b.peak)) {
            out.push((0, e));
        }
    }
    out
}

/// `(scale, unit)` of a load of magnitude `max`.
fn load_unit(max: f64, axial: bool) -> (f64, &'static str) {
    match (max >= 1e4, axial) {
        (true, false) => (1e-3, "kN m"),
        (false, false) => (1.0, "N m"),
        (true, true) => (1e-3, "kN"),
        (false, true) => (1.0, "N"),
    }
}

/// Element loads against time (left) and the train's speed (right, where it turns freely).
pub fn time(r: &TimeResponseResponse) -> Result<String, Err> {
    let axial = r.motion == Motion::Axial;
    let mut svg = Svg::new(1200, 560);
    let (t0, t1) = extent(r.time.iter().copied()).unwrap_or((0.0, 1.0));
    let shown = per_shaft(&r.elements);
    let max = shown.iter().map(|(_, e)| e.peak).fold(0.0, f64::max);
    let (k, unit) = load_unit(max, axial);
    let a = if max > 0.0 { max * k * 1.08 } else { 1.0 };
    let what = if axial { "axial force" } else { "torque" };
    let right = r.rigid_motion.is_some();
    let width = if right { 760.0 } else { 1160.0 };
    svg.caption(
        ((84.0 + width) / 2.0, 24.0),
        &format!("Shaft {what}: the most loaded element of each shaft"),
    );
    let p = svg.panel(
        [84.0, 50.0, width, 480.0],
        Axis::lin(t0, t1),
        Axis::lin(-a, a),
    );
    svg.axes(&p, "time [s]", &format!("{what} [{unit}]"));
    svg.path(
        &p,
        &[(t0, 0.0), (t1, 0.0)],
        Stroke::solid("#BBBBBB", 1.0),
        "",
    );
    let mut key = vec![];
    for (j, (shaft, e)) in shown.iter().enumerate() {
        let color = COLOURS[j % COLOURS.len()];
        let pts: Vec<(f64, f64)> = r
            .time
            .iter()
            .zip(&e.load)
            .map(|(t, v)| (*t, v * k))
            .collect();
        let pts: Vec<(f64, f64)> = stride(&pts).collect();
        svg.path(
            &p,
            &pts,
            Stroke::solid(color, 1.2),
            &format!("load element-{}", e.element),
        );
        let stress = e
            .peak_stress
            .map(|s| format!(", {:.1} MPa", s / 1e6))
            .unwrap_or_default();
        key.push((
            format!(
                "shaft {}: element {} (nodes {}-{}), peak {:.3} {unit}{stress}",
                shaft + 1,
                e.element,
                e.nodes[0],
                e.nodes[1],
                e.peak * k
            ),
            color,
            None,
        ));
    }
    svg.key_in(&p, &key);
    if let Some(m) = &r.rigid_motion {
        let (rate, unit) = if axial { (1.0, "m/s") } else { (RPM, "rpm") };
        let (lo, hi) = extent(m.rate.iter().map(|v| v * rate)).unwrap_or((0.0, 1.0));
        let (lo, hi) = (lo.min(0.0), if hi > lo { hi * 1.05 } else { lo + 1.0 });
        svg.caption((990.0, 24.0), "The train's rigid motion");
        let q = svg.panel(
            [860.0, 50.0, 1160.0, 480.0],
            Axis::lin(t0, t1),
            Axis::lin(lo, hi),
        );
        let name = if axial {
            "first node's axial speed"
        } else {
            "first shaft's speed"
        };
        svg.axes(&q, "time [s]", &format!("{name} [{unit}]"));
        let pts: Vec<(f64, f64)> = r
            .time
            .iter()
            .zip(&m.rate)
            .map(|(t, v)| (*t, v * rate))
            .collect();
        let pts: Vec<(f64, f64)> = stride(&pts).collect();
        svg.path(&q, &pts, Stroke::solid(COLOURS[0], 1.6), "rigid-rate");
    }
    Ok(svg.finish())
}
