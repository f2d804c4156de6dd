//! The torsional (or axial) interference diagram: each mode's natural frequency against the
//! reference shaft's speed, the excitation lines (orders of each shaft's speed, fixed line
//! frequencies), the operating range and the crossings, marked red where API 684's 10%
//! separation fails; below it, each mode's log decrement.

use super::campbell::{LEFT, RED, RIGHT, W, band};
use super::svg::{Anchor, Axis, INK, Stroke, Svg, extent, spread};
use super::{COLOURS, Err, RPM, clip, runs};
use crate::model::api::{CampbellResponse, Motion};

const LINE: &str = "#555555";

fn colour(mode: usize) -> &'static str {
    COLOURS[(mode.max(1) - 1) % COLOURS.len()]
}

/// The interference diagram of a torsional or axial sweep (its answer in rad/s).
pub fn interference(c: &CampbellResponse) -> Result<String, Err> {
    let i = c.interference.as_ref().ok_or("no interference diagram")?;
    let what = match c.motion {
        Motion::Axial => "Axial",
        _ => "Torsional",
    };
    let mut svg = Svg::new(W as u32, 1000);
    let (x0, x1) = extent(c.speeds.iter().copied()).unwrap_or((0.0, 1.0));
    let x = Axis::lin(x0, x1);
    // Up to the highest excitation over the sweep, with room above it.
    let excite = i
        .excitations
        .iter()
        .map(|e| e.frequency.unwrap_or(e.slope * x1))
        .fold(0.0, f64::max);
    let lowest = c
        .branches
        .iter()
        .filter_map(|b| b.frequency.iter().flatten().copied().reduce(f64::min))
        .fold(f64::INFINITY, f64::min);
    let f_hi = (1.3 * excite).max(if lowest.is_finite() {
        1.2 * lowest
    } else {
        1.0
    });
    svg.caption((W / 2.0, 24.0), &format!("{what} interference diagram"));
    let top = svg.panel([LEFT, 84.0, RIGHT, 520.0], x, Axis::lin(0.0, f_hi));
    let range = clip(Some(i.operating_range), x.lo, x.hi);
    if let Some(r) = range {
        band(&mut svg, &top, r);
    }
    svg.axes(&top, "reference shaft speed [rad/s]", "frequency [rad/s]");
    svg.top_axis(&top, RPM, "reference shaft speed [rpm]");
    // Excitations: orders as lines from the origin, fixed frequencies flat.
    let mut tags = vec![];
    for (e, ex) in i.excitations.iter().enumerate() {
        let (pts, dash) = match ex.frequency {
            Some(f) => (vec![(x.lo, f), (x.hi, f)], "7 4"),
            None => {
                let t1 = x.hi.min(f_hi / ex.slope);
                (vec![(x.lo, ex.slope * x.lo), (t1, ex.slope * t1)], "2 3")
            }
        };
        svg.path(&top, &pts, Stroke::dashed(LINE, 1.2, dash), "excitation");
        let end = pts[1];
        if top.contains(end) || end.1 <= f_hi {
            tags.push((top.px(end), i.label(e)));
        }
    }
    // At the right edge, spread apart; elsewhere (a line leaving through the top) beside it.
    let (edge, inside): (Vec<_>, Vec<_>) = tags.into_iter().partition(|t| t.0.0 >= RIGHT - 2.0);
    for ((px, py), s) in inside {
        svg.text((px + 4.0, py + 12.0), &s, 11.0, Anchor::Start, LINE);
    }
    let ys: Vec<f64> = edge.iter().map(|t| t.0.1 - 4.0).collect();
    let ys = spread(&ys, 12.0, top.rect[1] + 8.0, top.rect[3] - 4.0);
    for ((_, s), y) in edge.iter().zip(ys) {
        svg.text((RIGHT - 4.0, y), s, 11.0, Anchor::End, LINE);
    }
    // Natural frequencies.
    let mut ends = vec![];
    for b in &c.branches {
        let f: Vec<Option<f64>> = b.frequency.iter().map(|f| f.map(f64::abs)).collect();
        for run in runs(&c.speeds, &f) {
            svg.path(&top, &run, Stroke::solid(colour(b.mode), 2.0), "mode");
            if let Some(last) = run.last().filter(|p| top.contains(**p)) {
                ends.push((top.px(*last), format!("mode {}", b.mode), colour(b.mode)));
            }
        }
    }
    let ys: Vec<f64> = ends.iter().map(|e| e.0.1 + 4.0).collect();
    let ys = spread(&ys, 13.0, top.rect[1] + 8.0, top.rect[3] + 4.0);
    for (e, y) in ends.iter().zip(ys) {
        svg.text((e.0.0 + 5.0, y), &e.1, 12.0, Anchor::Start, e.2);
    }
    // Crossings.
    let (mut fail, mut pass) = (false, false);
    for cr in &i.criticals {
        let Some(speed) = cr.speed else { continue };
        if !top.contains((speed, cr.frequency)) {
            continue;
        }
        let color = if cr.passes { INK } else { RED };
        fail |= !cr.passes;
        pass |= cr.passes;
        svg.circle_px(top.px((speed, cr.frequency)), 5.0, color, "#FFFFFF");
    }
    let mut key: Vec<(String, &str, Option<&str>)> = vec![
        ("natural frequency".into(), INK, None),
        ("order of a shaft's speed".into(), LINE, Some("2 3")),
    ];
    if i.excitations.iter().any(|e| e.frequency.is_some()) {
        key.push(("line frequency".into(), LINE, Some("7 4")));
    }
    if pass {
        key.push(("crossing, margin >= 10%".into(), INK, Some("dot")));
    }
    if fail {
        key.push(("crossing, margin < 10% (API 684)".into(), RED, Some("dot")));
    }
    if range.is_some() {
        key.push(("operating range".into(), super::SHADE_HEX, Some("shade")));
    }
    let rows = svg.key_rows(((LEFT + RIGHT) / 2.0, 574.0), RIGHT - LEFT, &key);
    let dy = rows - 17.0;
    // The worst margin of each mode, as a table of text.
    let y0 = 624.0 + dy;
    svg.caption((W / 2.0, y0), "Separation margins (API 684: at least 10%)");
    let mut y = y0 + 28.0;
    let mut modes: Vec<usize> = i.criticals.iter().map(|c| c.mode).collect();
    modes.sort_unstable();
    modes.dedup();
    for m in modes.iter().take(12) {
        let worst = i.nearest(*m).expect("a mode with a crossing");
        let s = format!(
            "mode {m}: {} — closest: {}{}, margin {:.1}%",
            svg.frequency_label(worst.frequency),
            i.label(worst.excitation),
            worst
                .speed
                .map_or(String::new(), |w| format!(", crossing at {w:.1} rad/s")),
            100.0 * worst.margin
        );
        let color = if worst.passes { INK } else { RED };
        svg.text((LEFT, y), &s, 13.0, Anchor::Start, color);
        y += 20.0;
    }
    Ok(svg.finish())
}
