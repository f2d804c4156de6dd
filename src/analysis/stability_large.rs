//! The threshold of instability of a rotor held sparse (the viscous and hysteretic models of
//! a beam rotor past 600 coordinates), over the poles in the box `|Re s|, |Im s| <= bound`.
//!
//! Every pole of a large rotor is not asked for (nor meaningful: a fine mesh's highest modes
//! carry its round-off), so the search is bounded as the Campbell diagram is. The grid and its
//! bracket are searched on a modal reduction checked through sparse factors against the full
//! model's poles in the box ([`super::large::reduce_for_sweep`]: each within 1e-6 of its
//! modulus), which places a crossing only to `1e-6 |s|` over the decay rate's slope; the
//! crossing is then closed on the full model, by the secant on the decay rate of the full
//! model's pole nearest the reduced one (shift-invert Arnoldi through a sparse factor of
//! `Z(s)` at each step, [`super::refine::nearest_pole`]), kept inside the grid's bracket.

use super::AnalysisError;
use super::control::Control;
use super::modal::in_box;
use super::poles::poles_at;
use super::reduction::Reduction;
use super::refine::{Full, nearest_pole};
use super::stability::{Threshold, curve_of};
use crate::linalg::c64;
use crate::model::damping::DampingModel;
use crate::system::RotorSystem;

/// The threshold of a rotor held sparse, over the poles in the box `|Re s|, |Im s| <= bound`.
#[derive(Debug, Clone)]
pub struct Bounded {
    pub threshold: Option<Threshold>,
    /// Largest decay rate in the box at each grid speed, on the reduction.
    pub max_decay_rate: Vec<f64>,
    /// The checked reduction the grid was searched on.
    pub reduction: Reduction,
    /// Whether the threshold was closed on the full model (else it is the reduction's: the
    /// range's start, a jump of the hysteretic model, or a crossing the secant lost).
    pub closed: bool,
}

/// The threshold of a rotor held sparse over `speeds`, the poles in the box `|Re s|, |Im s|
/// <= bound` considered, on a reduction of at most `max_states` states (module docs).
pub fn stability_large(
    system: &RotorSystem,
    damping: &DampingModel,
    speeds: &[f64],
    bound: f64,
    max_states: usize,
    control: &Control,
) -> Result<Bounded, AnalysisError> {
    let dampers = super::large::dampers(system, damping, bound)?;
    let dampers = dampers.as_ref();
    let (reduced, reduction) =
        super::large::reduce_for_sweep(system, damping, dampers, speeds, bound, max_states)?;
    let at = |w: f64| {
        Ok(poles_at(&reduced, w).map(|mut set| {
            set.rotor.retain(|p| in_box(p.s, bound));
            set.internal.retain(|p| in_box(p.s, bound));
            set
        })?)
    };
    let (threshold, max_decay_rate) = curve_of(&at, speeds, control)?;
    let full = Full::Sparse {
        system,
        damping,
        dampers,
    };
    let (threshold, closed) = match threshold {
        Some(t) if t.speed > speeds[0] => {
            // The grid interval holding the reduced threshold bounds the secant.
            let hi = speeds
                .iter()
                .copied()
                .find(|&w| w >= t.speed)
                .unwrap_or(t.speed);
            let lo = speeds
                .iter()
                .copied()
                .rfind(|&w| w < t.speed)
                .unwrap_or(speeds[0]);
            match close(full, &t, lo, hi)? {
                Some((speed, s)) => {
                    let mut pole = t.pole.clone();
                    pole.s = s;
                    (
                        Some(Threshold {
                            speed,
                            pole,
                            mode: t.mode,
                        }),
                        true,
                    )
                }
                None => (Some(t), false),
            }
        }
        t => (t, false),
    };
    Ok(Bounded {
        threshold,
        max_decay_rate,
        reduction,
        closed,
    })
}

/// Relative step at which the secant on the full model stops: the pole's decay rate is found
/// to round-off (about 1e-13 of its modulus), which a slow crossing turns into a wider spread
/// of speeds than [`super::stability::TOLERANCE`]; the API promises 1e-6.
const CLOSED: f64 = 1e-9;

/// The speed in `[lo, hi]` where the decay rate of the full model's pole continuing `t`'s
/// crosses zero, and that pole, by the secant method; `None` where the pole is lost, the
/// iterate leaves the interval, or it does not converge (a jump, not a crossing).
fn close(full: Full, t: &Threshold, lo: f64, hi: f64) -> Result<Option<(f64, c64)>, AnalysisError> {
    let follow = |w: f64, s: c64| nearest_pole(full, w, s);
    let Some(s0) = follow(t.speed, t.pole.s)? else {
        return Ok(None);
    };
    let step = 1e-6 * (hi - lo).max(t.speed * 1e-3);
    let w1 = if t.speed + step <= hi {
        t.speed + step
    } else {
        t.speed - step
    };
    let Some(s1) = follow(w1, s0)? else {
        return Ok(None);
    };
    let (mut a, mut b) = ((t.speed, s0), (w1, s1));
    for _ in 0..30 {
        let (da, db) = (a.1.re, b.1.re);
        if db == da {
            return Ok(None);
        }
        let w = b.0 - db * (b.0 - a.0) / (db - da);
        if !(w >= lo && w <= hi) {
            return Ok(None);
        }
        let Some(s) = follow(w, b.1)? else {
            return Ok(None);
        };
        if (w - b.0).abs() <= CLOSED * w.abs() || s.re == 0.0 {
            return Ok(Some((w, s)));
        }
        (a, b) = (b, (w, s));
    }
    Ok(None)
}
