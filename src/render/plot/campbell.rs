//! The Campbell diagram (|frequency| against speed, the 1x and 2x lines, critical speeds)
//! over its decay-rate panel (the stability plot, largest decay rate against speed, in
//! `stability.rs`).

use super::svg::{Anchor, Axis, INK, Panel, Stroke, Svg, extent, sig, spread, text_width};
use super::{COLOURS, Err, RPM, SHADE_HEX, clip, runs};
use crate::model::api::Whirl as ApiWhirl;
use crate::model::api::{Branch, CampbellResponse, CriticalSpeed, Whirl};

pub(super) const W: f64 = 960.0;
pub(super) const LEFT: f64 = 84.0;
pub(super) const RIGHT: f64 = W - 64.0;
pub(super) const RED: &str = "#C81414";
const SYNC: &str = "#555555";

/// Colour of mode `mode` (1-based).
fn colour(mode: usize) -> &'static str {
    COLOURS[(mode.max(1) - 1) % COLOURS.len()]
}

/// Dashes of a whirl direction: forward solid, backward dashed, internal dotted.
fn dash(w: Whirl) -> Option<&'static str> {
    match w {
        Whirl::Forward => None,
        Whirl::Backward => Some("9 5"),
        Whirl::Internal => Some("2 4"),
    }
}

fn tag(b: &Branch) -> String {
    let w = match b.whirl {
        Whirl::Forward => "F",
        Whirl::Backward => "B",
        Whirl::Internal => "I",
    };
    format!("{}{w}", b.mode)
}

/// Each branch's label: its mode and whirl, with `a`, `b`, ... where several branches share
/// them (the two members of an anisotropic pair whirling the same way), in branch order.
fn tags(branches: &[Branch]) -> Vec<String> {
    let plain: Vec<String> = branches.iter().map(tag).collect();
    plain
        .iter()
        .enumerate()
        .map(|(i, t)| {
            let same = |j: &usize| plain[*j] == *t;
            if (0..plain.len()).filter(same).count() < 2 {
                return t.clone();
            }
            let k = (0..i).filter(same).count();
            let letter = char::from_u32('a' as u32 + (k % 26) as u32).unwrap_or('?');
            format!("{t}{letter}")
        })
        .collect()
}

/// The y range of decay rates: zero included, padded. A peak far above the stable part
/// (beyond the threshold) would flatten it: then the range stops at `1.5 |lowest|` and the
/// third value is the clipped maximum.
pub fn decay_range(values: impl IntoIterator<Item = f64>) -> (f64, f64, Option<f64>) {
    let Some((lo, hi)) = extent(values) else {
        return (-1.0, 1.0, None);
    };
    let (lo, hi) = (lo.min(0.0), hi.max(0.0));
    let (top, clipped) = if lo < 0.0 && hi > 3.0 * -lo {
        (1.5 * -lo, Some(hi))
    } else {
        (hi, None)
    };
    let span = (top - lo).max(1e-12);
    (lo - 0.06 * span, top + 0.06 * span, clipped)
}

/// The bottom of the decay-rate axis when heavily damped modes (a seal's, an overdamped
/// pair's) would flatten the lightly damped ones that matter: four times the median negative
/// decay rate, when the lowest is more than twice that; with the lowest, for the note.
fn light_floor(values: &[f64]) -> Option<(f64, f64)> {
    let mut neg: Vec<f64> = values
        .iter()
        .copied()
        .filter(|v| v.is_finite() && *v < 0.0)
        .collect();
    if neg.len() < 4 {
        return None;
    }
    neg.sort_by(f64::total_cmp);
    let floor = 4.0 * neg[neg.len() / 2];
    (neg[0] < 2.0 * floor).then_some((floor, neg[0]))
}

/// Campbell diagram (|frequency| against speed) over the decay-rate plot.
pub fn campbell(c: &CampbellResponse) -> Result<String, Err> {
    campbell_with(c, None)
}

/// Mode labels at the ends of the branches, spread apart, right of `p`'s last point.
fn end_labels(svg: &mut Svg, p: &Panel, ends: Vec<((f64, f64), String, &str)>) {
    let ends: Vec<_> = ends.into_iter().filter(|e| p.contains(e.0)).collect();
    let px: Vec<(f64, f64)> = ends.iter().map(|e| p.px(e.0)).collect();
    let ys: Vec<f64> = px.iter().map(|q| q.1 + 4.0).collect();
    let ys = spread(&ys, 13.0, p.rect[1] + 8.0, p.rect[3] + 4.0);
    for ((q, y), (_, s, color)) in px.iter().zip(ys).zip(&ends) {
        svg.text((q.0 + 5.0, y), s, 12.0, Anchor::Start, color);
    }
}

/// Pieces of a branch where its whirl is one way, each extended to the next piece's first
/// point (so the line is unbroken where the whirl changes): `(backward, points)`.
fn whirl_pieces(xs: &[f64], b: &Branch, ys: &[Option<f64>]) -> Vec<(bool, Vec<(f64, f64)>)> {
    let mut out: Vec<(bool, Vec<(f64, f64)>)> = vec![];
    let mut open = false;
    for ((x, y), f) in xs.iter().zip(ys).zip(&b.frequency) {
        match (y, f) {
            (Some(y), Some(f)) if y.is_finite() => {
                let back = *f < 0.0;
                let pt = (*x, *y);
                match out.last_mut() {
                    Some((w, run)) if open && *w == back => run.push(pt),
                    Some((_, run)) if open => {
                        run.push(pt);
                        out.push((back, vec![pt]));
                    }
                    _ => out.push((back, vec![pt])),
                }
                open = true;
            }
            _ => open = false,
        }
    }
    out
}

/// Branches on `p`, the values of each by `values`, dashed where they whirl backward; returns
/// the label at each branch's end.
fn branches<'a>(
    svg: &mut Svg,
    p: &Panel,
    c: &'a CampbellResponse,
    values: impl Fn(&Branch) -> Vec<Option<f64>>,
) -> Vec<((f64, f64), String, &'a str)> {
    let mut ends = vec![];
    for (b, tag) in c.branches.iter().zip(tags(&c.branches)) {
        let color = colour(b.mode);
        let pieces = whirl_pieces(&c.speeds, b, &values(b));
        for (back, run) in &pieces {
            let w = if *back {
                Whirl::Backward
            } else {
                Whirl::Forward
            };
            let stroke = Stroke {
                dash: dash(w),
                ..Stroke::solid(color, 2.0)
            };
            svg.path(p, run, stroke, &format!("branch mode-{tag}"));
        }
        if let Some(last) = pieces.last().and_then(|r| r.1.last()) {
            ends.push((*last, tag, color));
        }
    }
    ends
}

/// Where a branch's pole oscillates: not overdamped (`|omega| > 0.01 |sigma|`, as the
/// analysis classifies poles). A branch overdamped at low speeds (a heavily damped seal's
/// mode) is drawn on the Campbell diagram only where it whirls.
fn oscillating(b: &Branch) -> Vec<bool> {
    b.frequency
        .iter()
        .zip(&b.decay_rate)
        .map(|(f, s)| match (f, s) {
            (Some(f), Some(s)) => !(*s < 0.0 && f.abs() <= 0.01 * -s),
            _ => true,
        })
        .collect()
}

/// The overdamped poles' decay rates on `p`, thin, grey and dotted.
fn overdamped(svg: &mut Svg, p: &Panel, c: &CampbellResponse) {
    for o in &c.overdamped {
        for run in runs(&c.speeds, &o.decay_rate) {
            let st = Stroke::dashed(SYNC, 1.0, "1 3");
            svg.path(p, &run, st, "overdamped");
        }
    }
}

/// The y range of log decrements: 0 to the largest, clipped like [`decay_range`] when a
/// heavily damped mode would flatten the lightly damped ones that matter.
fn log_dec_range(values: &[f64]) -> (f64, f64, Option<f64>) {
    let mut v: Vec<f64> = values.iter().copied().filter(|x| x.is_finite()).collect();
    if v.is_empty() {
        return (0.0, 1.0, None);
    }
    v.sort_by(f64::total_cmp);
    let (lo, hi) = (v[0].min(0.0), v[v.len() - 1].max(0.2));
    // The lightly damped modes: below the median's three times (at least API 617's 0.1 shown).
    let typical = (3.0 * v[v.len() / 2]).max(0.3);
    let (top, clipped) = if hi > 2.0 * typical {
        (typical, Some(hi))
    } else {
        (hi, None)
    };
    let span = top - lo;
    (lo - 0.04 * span, top + 0.06 * span, clipped)
}

/// [`campbell`] with the operating speeds `shade = [min, max]` (rad/s) shaded.
pub fn campbell_with(c: &CampbellResponse, shade: Option<[f64; 2]>) -> Result<String, Err> {
    let mut svg = Svg::new(W as u32, 1370).nondimensional(c.nondimensional);
    let (x0, x1) = extent(c.speeds.iter().copied()).unwrap_or((0.0, 1.0));
    let x = Axis::lin(x0, x1);
    let freqs = c
        .branches
        .iter()
        .flat_map(|b| b.frequency.iter().flatten().map(|f| f.abs()));
    let f_hi = extent(freqs).map_or(1.0, |e| e.1.max(0.0));
    let f_hi = if f_hi > 0.0 { f_hi * 1.05 } else { 1.0 };
    let rates = c
        .branches
        .iter()
        .flat_map(|b| b.decay_rate.iter().flatten().copied())
        .chain(
            c.overdamped
                .iter()
                .flat_map(|o| o.decay_rate.iter().flatten().copied())
                .filter(|_| c.overdamped.len() < 2 * c.branches.len().max(1)),
        );
    let rates: Vec<f64> = rates.collect();
    let (d_lo, d_hi, clipped) = decay_range(rates.iter().copied());
    let floor = light_floor(&rates);
    let d_lo = floor.map_or(d_lo, |(f, _)| f - 0.04 * (d_hi - f));
    let shade = clip(shade, x.lo, x.hi);

    svg.caption((W / 2.0, 24.0), "Campbell diagram");
    let top = svg.panel([LEFT, 84.0, RIGHT, 460.0], x, Axis::lin(0.0, f_hi));
    if let Some((lo, hi)) = shade {
        band(&mut svg, &top, (lo, hi));
    }
    svg.axes(&top, "spin speed [rad/s]", "whirl frequency |ω| [rad/s]");
    svg.top_axis(&top, RPM, "spin speed [rpm]");
    sync_lines(&mut svg, &top);
    let ends = branches(&mut svg, &top, c, |b| {
        b.frequency
            .iter()
            .zip(oscillating(b))
            .map(|(f, o)| f.filter(|_| o).map(f64::abs))
            .collect()
    });
    end_labels(&mut svg, &top, ends);
    if let Some(t) = c.threshold.filter(|t| x.lo <= *t && *t <= x.hi) {
        svg.path(
            &top,
            &[(t, 0.0), (t, f_hi)],
            Stroke::solid(RED, 2.0),
            "threshold",
        );
    }
    criticals(&mut svg, &top, c);
    let mut key: Vec<(String, &str, Option<&str>)> = vec![
        ("forward whirl".into(), INK, None),
        ("backward whirl".into(), INK, Some("9 5")),
        ("1x, 2x (synchronous)".into(), SYNC, Some("1 0")),
    ];
    if c.branches.iter().any(|b| b.whirl == Whirl::Internal) {
        key.push(("internal".into(), INK, Some("2 4")));
    }
    let shown = |w: ApiWhirl, damped: bool| {
        c.criticals
            .iter()
            .any(|x| x.whirl == w && x.critically_damped == damped)
    };
    if shown(ApiWhirl::Forward, false) {
        key.push(("critical speed, forward".into(), INK, Some("dot")));
    }
    if shown(ApiWhirl::Backward, false) {
        key.push(("critical speed, backward".into(), INK, Some("ring")));
    }
    if c.criticals.iter().any(|x| x.critically_damped) {
        key.push((
            "critically damped crossing (AF < 2.5)".into(),
            SYNC,
            Some("small"),
        ));
    }
    if !c.overdamped.is_empty() {
        key.push(("overdamped poles".into(), SYNC, Some("1 3")));
    }
    if shade.is_some() {
        key.push(("operating range".into(), SHADE_HEX, Some("shade")));
    }
    if let Some(t) = c.threshold {
        key.push((format!("threshold {}", svg.speed_label(t)), RED, None));
    }
    let rows = svg.key_rows(((LEFT + RIGHT) / 2.0, 514.0), RIGHT - LEFT, &key);
    let dy = rows - 17.0;

    svg.caption((W / 2.0, 560.0 + dy), "Decay-rate plot");
    let bottom = svg.panel(
        [LEFT, 578.0 + dy, RIGHT, 890.0 + dy],
        x,
        Axis::lin(d_lo, d_hi),
    );
    if let Some((lo, hi)) = shade {
        band(&mut svg, &bottom, (lo, hi));
    }
    svg.axes(
        &bottom,
        "spin speed [rad/s]",
        "decay rate σ [1/s]  (> 0 unstable)",
    );
    svg.path(
        &bottom,
        &[(x.lo, 0.0), (x.hi, 0.0)],
        Stroke::solid(INK, 1.0),
        "zero",
    );
    for x in c.criticals.iter().filter(|x| !x.critically_damped) {
        let st = Stroke::dashed(SYNC, 1.0, "4 4");
        svg.path(&bottom, &[(x.speed, d_lo), (x.speed, d_hi)], st, "critical");
    }
    overdamped(&mut svg, &bottom, c);
    let ends = branches(&mut svg, &bottom, c, |b| b.decay_rate.clone());
    end_labels(&mut svg, &bottom, ends);
    if let Some(t) = c.threshold.filter(|t| x.lo <= *t && *t <= x.hi) {
        svg.path(
            &bottom,
            &[(t, d_lo), (t, d_hi)],
            Stroke::solid(RED, 2.0),
            "threshold",
        );
        let (px, py) = bottom.px((t, d_hi));
        // Left of the line, or right of it where the left edge would cut it.
        let label = format!("threshold {}", svg.speed_label(t));
        let (x, anchor) = if px - 6.0 - text_width(&label, 12.0) >= bottom.rect[0] {
            (px - 6.0, Anchor::End)
        } else {
            (px + 6.0, Anchor::Start)
        };
        svg.text((x, py + 16.0), &label, 12.0, anchor, RED);
    }
    if let Some(m) = clipped {
        clipped_note(&mut svg, &bottom, m, 6.0);
    }
    if let Some((f, lowest)) = floor {
        let s = format!(
            "axis clipped at σ = {} 1/s to show the lightly damped modes (lowest σ: {} 1/s; \
             every mode's log decrement below)",
            sig(f, 2),
            sig(lowest, 3)
        );
        svg.text(
            (bottom.rect[0] + 6.0, bottom.rect[3] - 8.0),
            &s,
            12.0,
            Anchor::Start,
            RED,
        );
    }

    // Log decrement: how engineers read stability margins off a Campbell diagram.
    let decs: Vec<f64> = c
        .branches
        .iter()
        .flat_map(|b| b.log_decrement.iter().flatten().copied())
        .collect();
    let (l_lo, l_hi, l_clipped) = log_dec_range(&decs);
    let y0 = 968.0 + dy;
    svg.caption((W / 2.0, y0), "Logarithmic decrement");
    let third = svg.panel(
        [LEFT, y0 + 18.0, RIGHT, y0 + 320.0],
        x,
        Axis::lin(l_lo, l_hi),
    );
    if let Some((lo, hi)) = shade {
        band(&mut svg, &third, (lo, hi));
    }
    svg.axes(&third, "spin speed [rad/s]", "log decrement δ = −2πσ/|ω|");
    if l_lo <= 0.1 && 0.1 <= l_hi {
        svg.path(
            &third,
            &[(x.lo, 0.1), (x.hi, 0.1)],
            Stroke::dashed(RED, 1.0, "6 4"),
            "api617-minimum",
        );
        let (px, py) = third.px((x.lo, 0.1));
        svg.text(
            (px + 6.0, py - 5.0),
            "δ = 0.1 (API 617 minimum)",
            11.0,
            Anchor::Start,
            RED,
        );
    }
    let ends = branches(&mut svg, &third, c, |b| {
        b.log_decrement
            .iter()
            .zip(oscillating(b))
            .map(|(v, o)| v.filter(|v| o && *v <= l_hi))
            .collect()
    });
    end_labels(&mut svg, &third, ends);
    if let Some(m) = l_clipped {
        let s = format!(
            "axis clipped at δ = {} (largest δ: {})",
            sig(l_hi, 2),
            sig(m, 3)
        );
        svg.text(
            (third.rect[2], third.rect[1] - 6.0),
            &s,
            12.0,
            Anchor::End,
            RED,
        );
    }
    Ok(svg.finish())
}

/// The operating range shaded over the whole height of `p`.
pub(super) fn band(svg: &mut Svg, p: &Panel, (lo, hi): (f64, f64)) {
    let (a, _) = p.px((lo, p.y.lo));
    let (b, _) = p.px((hi, p.y.lo));
    svg.rect_px([a, p.rect[1], b, p.rect[3]], SHADE_HEX, 0.22, None);
    svg.text(
        (b - 4.0, p.rect[3] - 6.0),
        "operating range",
        11.0,
        Anchor::End,
        INK,
    );
}

/// Note of a clipped decay-rate axis, `above` pixels over `p`, right-aligned.
pub(super) fn clipped_note(svg: &mut Svg, p: &Panel, max: f64, above: f64) {
    let s = format!(
        "axis clipped at σ = {} 1/s (largest σ: {} 1/s)",
        sig(p.y.hi, 2),
        sig(max, 3)
    );
    svg.text((p.rect[2], p.rect[1] - above), &s, 12.0, Anchor::End, RED);
}

/// The lines ω = Ω and ω = 2Ω, clipped to `p` analytically (they start at the origin).
fn sync_lines(svg: &mut Svg, p: &Panel) {
    for (k, name) in [(1.0, "1x"), (2.0, "2x")] {
        let t0 = p.x.lo.max(p.y.lo / k);
        let t1 = p.x.hi.min(p.y.hi / k);
        if t1 <= t0 {
            continue;
        }
        let st = if k == 1.0 {
            Stroke::solid(SYNC, 1.5)
        } else {
            Stroke {
                opacity: 0.7,
                ..Stroke::dashed(SYNC, 1.0, "2 3")
            }
        };
        svg.path(
            p,
            &[(t0, k * t0), (t1, k * t1)],
            st,
            &format!("sync-{name}"),
        );
        let (px, py) = p.px((t1, k * t1));
        let (dx, dy) = if t1 >= p.x.hi {
            (-4.0, -6.0)
        } else {
            (6.0, 12.0)
        };
        let anchor = if t1 >= p.x.hi {
            Anchor::End
        } else {
            Anchor::Start
        };
        svg.text((px + dx, py + dy), name, 12.0, anchor, SYNC);
    }
}

/// A mark at each crossing of a branch with the 1x line: forward critical speeds as filled
/// dots, backward ones as rings, each labelled in rad/s and rpm; critically damped
/// crossings (AF < 2.5: no separation margin needed) small, grey and unlabelled.
fn criticals(svg: &mut Svg, p: &Panel, c: &CampbellResponse) {
    let inside: Vec<&CriticalSpeed> = c
        .criticals
        .iter()
        .filter(|x| x.speed.is_finite() && p.contains((x.speed, x.speed)))
        .collect();
    for x in inside.iter().filter(|x| x.critically_damped) {
        svg.circle_px(p.px((x.speed, x.speed)), 3.0, "#FFFFFF", SYNC);
    }
    let marked: Vec<&&CriticalSpeed> = inside.iter().filter(|x| !x.critically_damped).collect();
    for x in &marked {
        let q = p.px((x.speed, x.speed));
        if x.whirl == ApiWhirl::Backward {
            svg.circle_px(q, 5.0, "#FFFFFF", INK);
        } else {
            svg.circle_px(q, 5.0, INK, "#FFFFFF");
        }
    }
    // Crossings at the same printed speed (a forward and a backward branch crossing 1x
    // together, as an isotropic Jeffcott rotor's do) share one label naming both.
    let mut groups: Vec<Vec<&&CriticalSpeed>> = vec![];
    for x in &marked {
        match groups.last_mut() {
            Some(g) if svg.speed_label(g[0].speed) == svg.speed_label(x.speed) => g.push(x),
            _ => groups.push(vec![x]),
        }
    }
    let pts: Vec<(f64, f64)> = groups
        .iter()
        .map(|g| p.px((g[0].speed, g[0].speed)))
        .collect();
    let ys: Vec<f64> = pts.iter().map(|q| q.1 + 16.0).collect();
    let ys = spread(&ys, 15.0, p.rect[1] + 12.0, p.rect[3] - 4.0);
    for ((q, y), g) in pts.iter().zip(ys).zip(&groups) {
        let mut s = svg.speed_label(g[0].speed);
        let (f, b) = (
            g.iter().any(|x| x.whirl != ApiWhirl::Backward),
            g.iter().any(|x| x.whirl == ApiWhirl::Backward),
        );
        if f && b {
            s += ", forward and backward";
        } else if g.len() > 1 {
            s += &format!(", {} crossings", g.len());
        }
        let right = q.0 + 10.0 + text_width(&s, 12.0) < p.rect[2];
        let (x, anchor) = if right {
            (q.0 + 8.0, Anchor::Start)
        } else {
            (q.0 - 8.0, Anchor::End)
        };
        svg.text((x, y), &s, 12.0, anchor, INK);
    }
}
