//! The torsional (or axial) interference diagram: a train's natural frequencies against its
//! excitations, and API 684's separation margins.
//!
//! A torsional or axial system is real: its poles come in conjugate pairs, one mode each, so
//! its Campbell diagram keeps the branches of positive frequency. The excitations are orders
//! `k` of each shaft's speed, `omega = k n Omega` for a shaft turning `n` times as fast as the
//! reference one, and fixed frequencies (the electrical line frequency `f_L` and `2 f_L` of a
//! motor or generator). A branch crosses an order where `|omega(Omega)| = k n Omega`: bracketed
//! on the sweep's grid and refined on the model like the 1x critical speeds
//! (`criticals::crossings`). For a natural frequency that does not move with speed the
//! crossing is `omega_n / (k n)`.
//!
//! API 684 asks each torsional natural frequency to lie at least 10% from every excitation
//! frequency over the operating range `[min, max]`: for an order, with `f_n = k n Omega_c`, the
//! margin is `1 - Omega_c / min` below the range and `Omega_c / max - 1` above it (the distance
//! relative to the excitation frequency at the range's end), negative inside it; for a fixed
//! frequency `f`, `|f_n - f| / f` at the worst speed of the range.

use super::AnalysisError;
use super::campbell::CampbellResult;
use super::control::Control;
use super::criticals::{self, Curve};
pub use super::excitation::{Crossing, Interference, MARGIN};
use super::poles::{self, Whirl};
use crate::damping::DampedModel;
use crate::linalg::c64;
pub use crate::model::train::{Line, Spec};

/// Poles of `|s|` below this fraction of the largest are a free train's rigid turning (or
/// sliding): a double pole at 0 that an eigensolver returns as `sqrt(eps)`-sized round-off.
pub const RIGID: f64 = 1e-6;

/// Keeps one branch per mode (those of positive frequency; the conjugates are the same
/// motion) and none for a free train's rigid motion, with the 1x criticals and hand-overs
/// that concern them; the threshold is then that of the branches kept.
///
/// `scale`: a lower bound of the system's highest natural frequency
/// (`fem::modal::frequency_scale`); `modes`: how many modes to keep, the lowest.
pub fn real_modes(r: &mut CampbellResult, scale: f64, modes: Option<usize>) {
    let largest = r
        .branches
        .iter()
        .flat_map(|b| b.poles.iter().flatten())
        .map(|s| s.norm())
        .fold(scale, f64::max);
    let rigid = |b: &super::campbell::Branch| {
        b.poles
            .iter()
            .flatten()
            .all(|s| s.norm() <= RIGID * largest)
    };
    let keep: Vec<bool> = r
        .branches
        .iter()
        .map(|b| b.whirl != Whirl::Backward && !rigid(b))
        .collect();
    r.overdamped.retain(|b| {
        !b.poles
            .iter()
            .flatten()
            .all(|s| s.norm() <= RIGID * largest)
    });
    let mut index = vec![None; keep.len()];
    let mut next = 0;
    for (i, &k) in keep.iter().enumerate() {
        if k && modes.is_none_or(|m| next < m) {
            index[i] = Some(next);
            next += 1;
        }
    }
    let keep: Vec<bool> = index.iter().map(Option::is_some).collect();
    let mut i = 0;
    r.branches.retain(|_| {
        i += 1;
        keep[i - 1]
    });
    r.criticals.retain_mut(|c| match index[c.branch] {
        Some(j) => {
            c.branch = j;
            true
        }
        None => false,
    });
    r.ambiguities
        .retain_mut(|a| match (index[a.branches.0], index[a.branches.1]) {
            (Some(x), Some(y)) => {
                a.branches = (x, y);
                true
            }
            _ => false,
        });
    // Modes numbered from 1 again, the rigid motion left out.
    let numbers: Vec<usize> = r.branches.iter().map(|b| b.mode).collect();
    let renumber = |m: usize| numbers.iter().position(|&x| x == m).map_or(m, |i| i + 1);
    for c in &mut r.criticals {
        c.mode = renumber(c.mode);
    }
    for b in &mut r.branches {
        b.mode = renumber(b.mode);
    }
    // The threshold of the modes kept: a rigid motion's round-off is not an instability.
    if r.threshold
        .as_ref()
        .is_some_and(|t| t.pole.s.norm() <= RIGID * largest)
    {
        r.threshold = first_growing(r);
    }
}

/// The first speed of the grid where a kept branch grows (interpolated to where its decay rate
/// crosses 0).
fn first_growing(r: &CampbellResult) -> Option<super::stability::Threshold> {
    let mut best: Option<(f64, c64, usize)> = None;
    for b in &r.branches {
        let pts: Vec<(f64, c64)> = r
            .speeds
            .iter()
            .zip(&b.poles)
            .filter_map(|(&w, p)| p.map(|p| (w, p)))
            .collect();
        // The stability analysis's margin: round-off on an undamped pole is not growth.
        let grows = |s: &c64| s.re - super::stability::TOLERANCE * s.norm() > 0.0;
        let Some(i) = pts.iter().position(|(_, s)| grows(s)) else {
            continue;
        };
        let at = match i {
            0 => pts[0],
            _ => {
                let ((w0, s0), (w1, s1)) = (pts[i - 1], pts[i]);
                let t = s0.re / (s0.re - s1.re);
                (w0 + (w1 - w0) * t, s0 + (s1 - s0) * t)
            }
        };
        if best.is_none_or(|(w, _, _)| at.0 < w) {
            best = Some((at.0, at.1, b.mode));
        }
    }
    best.map(|(speed, s, mode)| super::stability::Threshold {
        speed,
        pole: super::poles::Pole {
            s,
            whirl: Whirl::Forward,
            shape: vec![],
            whirl_ratio: 1.0,
        },
        mode,
    })
}

/// The crossings and margins of every branch of `r` (one per mode, [`real_modes`]) with the
/// lines of `spec`, refined on `model` where there is one (else interpolated on the grid).
pub fn interference(
    r: &CampbellResult,
    model: Option<&DampedModel>,
    spec: &Spec,
    control: &Control,
) -> Result<Interference, AnalysisError> {
    let [lo, hi] = spec.range;
    let speeds = &r.speeds;
    let mut out = vec![];
    for (li, line) in spec.lines.iter().enumerate() {
        match *line {
            Line::Order { .. } => {
                let slope = line.slope();
                let found = match model {
                    Some(m) => {
                        let curves: Vec<Curve> = r
                            .branches
                            .iter()
                            .map(|b| Curve {
                                mode: b.mode,
                                poles: &b.poles,
                                whirl_ratio: &b.whirl_ratio,
                            })
                            .collect();
                        criticals::crossings(m, speeds, &curves, slope, control)?
                            .into_iter()
                            .map(|c| (c.mode, c.speed, c.pole))
                            .collect()
                    }
                    None => interpolated(r, slope),
                };
                let margin = |speed: f64| {
                    if speed < lo {
                        1.0 - speed / lo
                    } else if speed > hi {
                        speed / hi - 1.0
                    } else {
                        -(speed / lo - 1.0).min(1.0 - speed / hi)
                    }
                };
                for &(mode, speed, pole) in &found {
                    out.push(Crossing {
                        line: li,
                        mode,
                        speed: Some(speed),
                        frequency: pole.im.abs(),
                        damping_ratio: poles::damping_ratio(pole),
                        margin: margin(speed),
                        beyond_sweep: false,
                    });
                }
                // A mode that crosses this order beyond the sweep: where, from its pole at the
                // sweep's speed nearest the operating range.
                let middle = 0.5 * (lo + hi);
                for b in &r.branches {
                    if found.iter().any(|f| f.0 == b.mode) {
                        continue;
                    }
                    let near = speeds
                        .iter()
                        .zip(&b.poles)
                        .filter_map(|(&w, p)| p.map(|p| (w, p)))
                        .min_by(|a, b| (a.0 - middle).abs().total_cmp(&(b.0 - middle).abs()));
                    if let Some((_, p)) = near.filter(|(_, p)| p.im.abs() > 0.0) {
                        let speed = p.im.abs() / slope;
                        out.push(Crossing {
                            line: li,
                            mode: b.mode,
                            speed: Some(speed),
                            frequency: p.im.abs(),
                            damping_ratio: poles::damping_ratio(p),
                            margin: margin(speed),
                            beyond_sweep: true,
                        });
                    }
                }
            }
            Line::Fixed { frequency: f, .. } => {
                for b in &r.branches {
                    // The worst speed of the operating range: the grid's points in it and its
                    // ends, interpolated between the grid's points either side (a range
                    // between two points, or a single speed, has no point of its own).
                    let inside = speeds
                        .iter()
                        .zip(&b.poles)
                        .filter(|(w, _)| **w >= lo * (1.0 - 1e-12) && **w <= hi * (1.0 + 1e-12))
                        .filter_map(|(_, p)| *p);
                    let ends = [lo, hi]
                        .into_iter()
                        .filter_map(|w| at_speed(speeds, &b.poles, w));
                    let worst = inside
                        .chain(ends)
                        .min_by(|a, b| (a.im.abs() - f).abs().total_cmp(&(b.im.abs() - f).abs()));
                    if let Some(p) = worst {
                        out.push(Crossing {
                            line: li,
                            mode: b.mode,
                            speed: None,
                            frequency: p.im.abs(),
                            damping_ratio: poles::damping_ratio(p),
                            margin: (p.im.abs() - f).abs() / f,
                            beyond_sweep: false,
                        });
                    }
                }
            }
        }
    }
    out.sort_by(|a, b| {
        a.speed
            .unwrap_or(f64::INFINITY)
            .total_cmp(&b.speed.unwrap_or(f64::INFINITY))
            .then(a.mode.cmp(&b.mode))
            .then(a.line.cmp(&b.line))
    });
    Ok(Interference {
        spec: spec.clone(),
        crossings: out,
    })
}

/// A branch's pole at speed `w` inside the grid, linear between the grid's points either side.
fn at_speed(speeds: &[f64], poles: &[Option<c64>], w: f64) -> Option<c64> {
    let k = speeds.partition_point(|&s| s < w);
    if k == 0 || k >= speeds.len() {
        return (speeds.get(k) == Some(&w)).then_some(poles[k]).flatten();
    }
    let (a, b) = (poles[k - 1]?, poles[k]?);
    let t = (w - speeds[k - 1]) / (speeds[k] - speeds[k - 1]);
    Some(a + (b - a) * t)
}

/// Crossings interpolated linearly between the grid's points (a sweep without one model to
/// refine on: supports over whirl frequency, solved consistently at each speed).
fn interpolated(r: &CampbellResult, slope: f64) -> Vec<(usize, f64, c64)> {
    let mut out = vec![];
    for b in &r.branches {
        let pts: Vec<(f64, c64)> = r
            .speeds
            .iter()
            .zip(&b.poles)
            .filter_map(|(&w, p)| p.map(|p| (w, p)))
            .collect();
        let g = |(w, s): (f64, c64)| s.im.abs() - slope * w;
        for pair in pts.windows(2) {
            let (p, q) = (pair[0], pair[1]);
            let (gp, gq) = (g(p), g(q));
            if gp * gq < 0.0 || (gq == 0.0 && q.0 > 0.0) {
                let t = gp / (gp - gq);
                out.push((b.mode, p.0 + (q.0 - p.0) * t, p.1 + (q.1 - p.1) * t));
            }
        }
    }
    out
}
