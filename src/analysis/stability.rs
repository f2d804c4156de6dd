//! Threshold of instability: the lowest spin speed of a range at which a pole has a positive
//! decay rate.
//!
//! The growth `g(Omega) = max_poles (sigma - 1e-10 |s|)` is evaluated on the grid; the first grid
//! interval where it turns positive brackets the threshold (the margin keeps round-off on an
//! undamped rotor from counting as instability). The crossing of `max sigma` itself is then
//! refined, when the bracket allows it, so the margin does not bias the result, by a bracketing
//! root finder (Illinois false position with forced bisection) to a relative width of
//! [`TOLERANCE`]. The bracket is kept, so it also converges onto a jump: the hysteretic model's
//! step at a critical speed is exactly such a jump.

use super::AnalysisError;
use super::control::Control;
use super::poles::{Pole, PoleSet, poles_at};
use crate::damping::DampedModel;
use crate::model::limits::BATCH_PER_THREAD;
use rayon::prelude::*;

/// Relative width of the final bracket (the API promises 1e-6).
pub const TOLERANCE: f64 = 1e-10;

/// The threshold and the pole that becomes unstable there.
#[derive(Debug, Clone)]
pub struct Threshold {
    pub speed: f64,
    pub pole: Pole,
    /// Rank of the pole by |frequency| within its whirl, from 1.
    pub mode: usize,
}

/// What a sweep keeps of each speed: enough to bracket a threshold.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Summary {
    pub speed: f64,
    /// `max (sigma - margin |s|)`: > 0 iff a pole is unstable.
    pub growth: f64,
    pub max_decay_rate: f64,
}

impl Summary {
    fn of(set: &PoleSet) -> Self {
        Summary {
            speed: set.speed,
            growth: set.growth(),
            max_decay_rate: set.max_decay_rate(),
        }
    }
}

/// Pole sets over a grid of speeds, solved in parallel a batch at a time and handed to
/// `visit` in order of speed (one unit of progress per speed). Only a batch of pole sets is
/// alive at once, so the memory of a sweep grows with its speeds only through what `visit`
/// keeps.
pub fn sweep(
    model: &DampedModel,
    speeds: &[f64],
    control: &Control,
    visit: impl FnMut(&PoleSet),
) -> Result<Vec<Summary>, AnalysisError> {
    sweep_of(&|w| Ok(poles_at(model, w)?), speeds, control, visit)
}

/// The poles a search reads at a speed: a model's every pole, or those of a bounded one.
pub trait Poles: Fn(f64) -> Result<PoleSet, AnalysisError> + Sync {}
impl<F: Fn(f64) -> Result<PoleSet, AnalysisError> + Sync> Poles for F {}

/// [`sweep`] of the poles `at` gives.
pub fn sweep_of(
    at: &impl Poles,
    speeds: &[f64],
    control: &Control,
    mut visit: impl FnMut(&PoleSet),
) -> Result<Vec<Summary>, AnalysisError> {
    let batch = BATCH_PER_THREAD * rayon::current_num_threads().max(1);
    let mut out = Vec::with_capacity(speeds.len());
    for chunk in speeds.chunks(batch) {
        let sets: Vec<PoleSet> = chunk
            .par_iter()
            .map(|&w| {
                control.check()?;
                let set = at(w)?;
                control.advance(1);
                Ok(set)
            })
            .collect::<Result<_, AnalysisError>>()?;
        for set in &sets {
            out.push(Summary::of(set));
            visit(set);
        }
    }
    Ok(out)
}

/// Refinement evaluations counted in the progress (most searches need fewer).
const REFINEMENT_WORK: u64 = 40;

/// Work units of a stability search over `n` grid speeds: the grid and the refinement.
pub fn work(n: usize) -> u64 {
    n as u64 + REFINEMENT_WORK
}

/// Threshold over the range of `speeds`, the grid only bracketing it.
pub fn stability(
    model: &DampedModel,
    speeds: &[f64],
    control: &Control,
) -> Result<Option<Threshold>, AnalysisError> {
    stability_curve(model, speeds, control).map(|(t, _)| t)
}

/// The threshold and the largest decay rate at each grid speed.
pub fn stability_curve(
    model: &DampedModel,
    speeds: &[f64],
    control: &Control,
) -> Result<(Option<Threshold>, Vec<f64>), AnalysisError> {
    curve_of(&|w| Ok(poles_at(model, w)?), speeds, control)
}

/// [`stability_curve`] of the poles `at` gives.
pub fn curve_of(
    at: &impl Poles,
    speeds: &[f64],
    control: &Control,
) -> Result<(Option<Threshold>, Vec<f64>), AnalysisError> {
    control.expect(work(speeds.len()));
    let summaries = sweep_of(at, speeds, control, |_| {})?;
    let t = threshold_of(at, &summaries, control)?;
    control.advance(REFINEMENT_WORK);
    Ok((t, summaries.iter().map(|s| s.max_decay_rate).collect()))
}

/// Threshold from the summaries of a grid (as a Campbell sweep has them).
pub fn threshold(
    model: &DampedModel,
    grid: &[Summary],
    control: &Control,
) -> Result<Option<Threshold>, AnalysisError> {
    threshold_of(&|w| Ok(poles_at(model, w)?), grid, control)
}

/// [`threshold`] of the poles `at` gives.
pub fn threshold_of(
    poles_at: &impl Poles,
    grid: &[Summary],
    control: &Control,
) -> Result<Option<Threshold>, AnalysisError> {
    let Some(first) = grid.iter().position(|s| s.growth > 0.0) else {
        return Ok(None);
    };
    let at = |w: f64| -> Result<Threshold, AnalysisError> {
        control.check()?;
        Ok(describe(&poles_at(w)?))
    };
    if first == 0 {
        return at(grid[0].speed).map(Some);
    }
    // A grid point within round-off of the crossing (sigma > 0 by less than the margin) is the
    // threshold itself.
    if grid[first - 1].max_decay_rate > 0.0 {
        return at(grid[first - 1].speed).map(Some);
    }
    // Refine the pure decay rate where it brackets too, else the margined growth.
    let pure = grid[first].max_decay_rate > 0.0;
    let f = |s: &Summary| if pure { s.max_decay_rate } else { s.growth };
    let (mut lo, mut glo) = (grid[first - 1].speed, f(&grid[first - 1]));
    let mut hi_set: Option<PoleSet> = None;
    let (mut hi, mut ghi) = (grid[first].speed, f(&grid[first]));
    // Illinois: halve the retained end's value when the same end is kept twice.
    let mut kept_side = 0i8;
    let mut iterations = 0;
    while hi - lo > TOLERANCE * hi.abs().max(f64::MIN_POSITIVE) && iterations < 200 {
        iterations += 1;
        let width = hi - lo;
        let mut x = if iterations % 3 == 0 || !(ghi - glo).is_finite() || ghi == glo {
            0.5 * (lo + hi)
        } else {
            hi - ghi * (hi - lo) / (ghi - glo)
        };
        // Stay strictly inside the bracket.
        if !(x > lo && x < hi) {
            x = 0.5 * (lo + hi);
        }
        control.check()?;
        let set = poles_at(x)?;
        let g = f(&Summary::of(&set));
        if g > 0.0 {
            hi = x;
            ghi = g;
            hi_set = Some(set);
            if kept_side == -1 {
                glo *= 0.5;
            }
            kept_side = -1;
        } else {
            lo = x;
            glo = g;
            if kept_side == 1 {
                ghi *= 0.5;
            }
            kept_side = 1;
        }
        debug_assert!(hi - lo < width);
    }
    match hi_set {
        Some(set) => Ok(Some(describe(&set))),
        None => at(hi).map(Some),
    }
}

fn describe(set: &PoleSet) -> Threshold {
    let pole = set
        .least_stable()
        .cloned()
        .expect("an unstable set has a pole");
    Threshold {
        speed: set.speed,
        mode: set.mode_number(&pole),
        pole,
    }
}
