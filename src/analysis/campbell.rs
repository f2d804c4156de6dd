//! Campbell diagram and decay-rate plot: every rotor branch over a sweep of spin speeds, the
//! forward critical speeds and the threshold of instability.

use super::AnalysisError;
use super::control::Control;
use super::poles::Whirl;
use super::reduction::{Reduction, reduce_for_sweep};
use super::stability::{Threshold, sweep, threshold};
use super::tracking::Tracker;
use crate::damping::{DampedModel, ModelKind};
use crate::linalg::{self, c64};
use crate::model::damping::DampingModel;
use crate::system::{Layout, RotorSystem};

/// One branch over the sweep.
#[derive(Debug, Clone)]
pub struct Branch {
    /// 1 = lowest |frequency| at its first speed, per whirl direction.
    pub mode: usize,
    pub whirl: Whirl,
    /// The pole at each speed; `None` where the model defines none for this mode.
    pub poles: Vec<Option<c64>>,
}

#[derive(Debug, Clone)]
pub struct CampbellResult {
    pub speeds: Vec<f64>,
    pub branches: Vec<Branch>,
    /// Forward branches crossing `omega = Omega`, interpolated, ascending.
    pub critical_speeds: Vec<f64>,
    pub threshold: Option<Threshold>,
    /// The modal reduction the sweep ran on, if any (see [`campbell_below`]).
    pub reduction: Option<Reduction>,
}

pub fn campbell(
    model: &DampedModel,
    speeds: &[f64],
    control: &Control,
) -> Result<CampbellResult, AnalysisError> {
    control.expect(super::stability::work(speeds.len()));
    let mut tracker = Tracker::new(2 * model.rotor_dofs());
    let summaries = sweep(model, speeds, control, |set| tracker.push(set))?;
    let tracks = tracker.finish();
    let mut branches: Vec<Branch> = tracks
        .into_iter()
        .filter(|t| t.values.iter().any(Option::is_some))
        .map(|t| {
            // A branch's whirl is the direction of most of its defined poles.
            let defined = t.values.iter().flatten().count();
            let forward = t.values.iter().flatten().filter(|s| s.im >= 0.0).count();
            Branch {
                mode: 0,
                whirl: if 2 * forward >= defined {
                    Whirl::Forward
                } else {
                    Whirl::Backward
                },
                poles: t.values,
            }
        })
        .collect();
    number_modes(&mut branches);
    let critical_speeds = critical_speeds(speeds, &branches);
    let threshold = threshold(model, &summaries, control)?;
    control.advance(super::stability::work(0));
    Ok(CampbellResult {
        speeds: speeds.to_vec(),
        branches,
        critical_speeds,
        threshold,
        reduction: None,
    })
}

/// The Campbell diagram of the branches below `bound` (`f64::INFINITY`: all), on a modal
/// reduction of the rotor where one is checked to hold (`reduce`; see [`super::reduction`]),
/// else on `full`. The threshold is that of the model solved: with a reduction, of the poles
/// the retained modes carry.
pub fn campbell_below(
    system: &RotorSystem,
    damping: &DampingModel,
    full: &DampedModel,
    speeds: &[f64],
    bound: f64,
    reduce: bool,
    control: &Control,
) -> Result<CampbellResult, AnalysisError> {
    let reduced = if reduce {
        reduce_for_sweep(system, damping, full, speeds, bound)?
    } else {
        None
    };
    let mut r = match reduced {
        Some((model, reduction)) => {
            let mut r = campbell(&model, speeds, control)?;
            r.reduction = Some(reduction);
            r
        }
        None => campbell(full, speeds, control)?,
    };
    r.keep_below(bound);
    Ok(r)
}

/// A bound that keeps the `n` rotor branches of lowest |frequency| at `speed` (`modes: n`):
/// just above the n-th |frequency| of the full model there, with room for a reduced model's
/// poles (within [`super::reduction::TOLERANCE`] of the full ones) to stay below it.
pub fn lowest_bound(full: &DampedModel, speed: f64, n: usize) -> Result<f64, AnalysisError> {
    let mut freqs: Vec<f64> = match &full.kind {
        // No internal coordinates and no mirror pairs: every eigenvalue is a rotor pole, and
        // the values alone (a third of the work of values and vectors) give the bound.
        ModelKind::Linear(m)
            if full.layout != Layout::Doubled && m.size() == 2 * full.rotor_dofs() =>
        {
            linalg::eigenvalues(&m.at(speed))?
                .iter()
                .map(|s| s.im.abs())
                .collect()
        }
        _ => super::poles::poles_at(full, speed)?
            .rotor
            .iter()
            .map(|p| p.s.im.abs())
            .collect(),
    };
    freqs.sort_by(f64::total_cmp);
    Ok(match freqs.get(n.saturating_sub(1)) {
        Some(&f) => f * (1.0 + 1e-4) + f64::MIN_POSITIVE,
        None => f64::INFINITY,
    })
}

impl CampbellResult {
    /// Keeps the `n` branches of lowest |frequency| at their first defined speed (mode numbers
    /// unchanged), and the critical speeds of those.
    pub fn keep_lowest(&mut self, n: usize) {
        let mut order: Vec<usize> = (0..self.branches.len()).collect();
        order.sort_by(|&a, &b| by_start(&self.branches[a], &self.branches[b]));
        let mut keep = vec![false; self.branches.len()];
        for &i in order.iter().take(n) {
            keep[i] = true;
        }
        let mut k = keep.into_iter();
        self.branches.retain(|_| k.next().unwrap_or(false));
        self.critical_speeds = critical_speeds(&self.speeds, &self.branches);
    }

    /// Keeps the branches whose |frequency| at their first defined speed is at most `bound`
    /// (mode numbers unchanged), and the critical speeds of those.
    pub fn keep_below(&mut self, bound: f64) {
        if bound.is_infinite() {
            return;
        }
        self.branches.retain(|b| {
            b.poles
                .iter()
                .flatten()
                .next()
                .is_some_and(|s| s.im.abs() <= bound)
        });
        self.critical_speeds = critical_speeds(&self.speeds, &self.branches);
    }
}

/// Branches by where they start: their first defined speed, then |frequency| there (the
/// order modes are numbered in, and the lowest kept).
fn by_start(a: &Branch, b: &Branch) -> std::cmp::Ordering {
    let start = |b: &Branch| {
        let i = b.poles.iter().position(Option::is_some).unwrap_or(0);
        (i, b.poles[i].map_or(0.0, |s| s.im.abs()))
    };
    let ((ia, fa), (ib, fb)) = (start(a), start(b));
    ia.cmp(&ib).then(fa.total_cmp(&fb))
}

/// Modes numbered per whirl by |frequency| at the branch's first defined speed; branches
/// ordered by mode, forward before backward.
fn number_modes(branches: &mut [Branch]) {
    for whirl in [Whirl::Forward, Whirl::Backward] {
        let mut idx: Vec<usize> = (0..branches.len())
            .filter(|&i| branches[i].whirl == whirl)
            .collect();
        idx.sort_by(|&a, &b| by_start(&branches[a], &branches[b]));
        for (k, i) in idx.into_iter().enumerate() {
            branches[i].mode = k + 1;
        }
    }
    branches.sort_by_key(|b| (b.mode, b.whirl != Whirl::Forward));
}

/// Where `omega - Omega` changes sign along a forward branch (across undefined gaps too).
fn critical_speeds(speeds: &[f64], branches: &[Branch]) -> Vec<f64> {
    let mut out = vec![];
    for b in branches.iter().filter(|b| b.whirl == Whirl::Forward) {
        let pts: Vec<(f64, f64)> = speeds
            .iter()
            .zip(&b.poles)
            .filter_map(|(&w, p)| p.map(|s| (w, s.im - w)))
            .collect();
        for pair in pts.windows(2) {
            let ((w0, f0), (w1, f1)) = (pair[0], pair[1]);
            if f0 == 0.0 {
                out.push(w0);
            } else if f0 * f1 < 0.0 {
                out.push(w0 + (w1 - w0) * f0 / (f0 - f1));
            }
        }
        if let Some(&(w, f)) = pts.last()
            && f == 0.0
        {
            out.push(w);
        }
    }
    out.sort_by(f64::total_cmp);
    out.dedup();
    out
}
