//! Campbell diagram and decay-rate plot: every rotor branch over a sweep of spin speeds, the
//! forward critical speeds and the threshold of instability.

use super::AnalysisError;
use super::control::Control;
use super::criticals::{self, Critical};
use super::poles::{self, Whirl};
use super::reduction::{Reduction, reduce_for_sweep};
use super::stability::{Threshold, sweep, threshold};
use super::tracking::{Ambiguity, Tracker};
use crate::damping::dampers::ModalDampers;
use crate::damping::{DampedModel, ModelKind};
use crate::linalg::{self, c64};
use crate::model::damping::DampingModel;
use crate::system::{Layout, RotorSystem};

/// One branch over the sweep: one mode, whatever its whirl does.
#[derive(Debug, Clone)]
pub struct Branch {
    /// Mode number: forward and backward branches of one mode share it (1F, 1B), numbered by
    /// |frequency| where they start.
    pub mode: usize,
    /// The direction of most of its poles.
    pub whirl: Whirl,
    /// The pole at each speed as `/v1/modal` reports it; `None` where the model defines none
    /// for this mode.
    pub poles: Vec<Option<c64>>,
    /// Its whirl ratio at each speed (+1 forward circular, -1 backward, 0 planar).
    pub whirl_ratio: Vec<Option<f64>>,
    /// Its shape where it starts (for pairing forward and backward branches).
    pub shape: Vec<c64>,
}

impl Branch {
    /// `-2 pi sigma / |omega|` at each speed; `None` where undefined or not oscillating.
    pub fn log_decrement(&self) -> Vec<Option<f64>> {
        self.poles
            .iter()
            .map(|p| p.and_then(poles::log_decrement))
            .collect()
    }

    /// `-sigma / |s|` at each speed.
    pub fn damping_ratio(&self) -> Vec<Option<f64>> {
        self.poles
            .iter()
            .map(|p| p.map(poles::damping_ratio))
            .collect()
    }

    /// Its first defined speed (index), |frequency| there (0 for a pole that does not
    /// oscillate, [`poles::NON_OSCILLATING`]: its frequency is round-off) and |s| there.
    fn start(&self) -> (usize, f64, f64) {
        let i = self.poles.iter().position(Option::is_some).unwrap_or(0);
        let s = self.poles[i].unwrap_or_default();
        let oscillates = s.im.abs() > poles::NON_OSCILLATING * s.norm();
        (i, if oscillates { s.im.abs() } else { 0.0 }, s.norm())
    }
}

#[derive(Debug, Clone)]
pub struct CampbellResult {
    pub speeds: Vec<f64>,
    /// The oscillating branches, by mode, forward before backward.
    pub branches: Vec<Branch>,
    /// Branches of poles overdamped at every speed ([`poles::OVERDAMPED`]: real at rest), by
    /// decay rate where they start; `mode` is 0.
    pub overdamped: Vec<Branch>,
    /// Every crossing of a branch with the 1x line, refined, by speed.
    pub criticals: Vec<Critical>,
    /// The forward crossings that are not critically damped, ascending.
    pub critical_speeds: Vec<f64>,
    pub threshold: Option<Threshold>,
    /// The modal reduction the sweep ran on, if any (see [`campbell_below`]).
    pub reduction: Option<Reduction>,
    /// Hand-overs between two branches that the tracking could not tell apart (veering, or a
    /// crossing with similar shapes): speed index and branch indices.
    pub ambiguities: Vec<Ambiguity>,
    /// A torsional or axial train's interference diagram.
    pub interference: Option<super::excitation::Interference>,
}

/// Which branches a Campbell diagram reports.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Keep {
    /// Those whose |frequency| (|s| for overdamped ones) is at most this at some speed.
    pub below: f64,
    /// Of those, the `n` of lowest |frequency| at their first speed.
    pub lowest: Option<usize>,
}

impl Keep {
    pub const ALL: Keep = Keep {
        below: f64::INFINITY,
        lowest: None,
    };
}

/// Crossing refinements counted in the progress (most sweeps need fewer).
const CRITICAL_WORK: u64 = 40;

/// Every branch of `model` over `speeds`.
pub fn campbell(
    model: &DampedModel,
    speeds: &[f64],
    control: &Control,
) -> Result<CampbellResult, AnalysisError> {
    campbell_kept(model, speeds, Keep::ALL, control)
}

/// The branches of `model` over `speeds` that `keep` asks for, their critical speeds (refined
/// on `model`) and the threshold.
pub fn campbell_kept(
    model: &DampedModel,
    speeds: &[f64],
    keep: Keep,
    control: &Control,
) -> Result<CampbellResult, AnalysisError> {
    control.expect(super::stability::work(speeds.len()) + CRITICAL_WORK);
    let mut tracker = Tracker::new(2 * model.rotor_dofs());
    let summaries = sweep(model, speeds, control, |set| tracker.push(set))?;
    let (branches, overdamped, ambiguities) =
        branches_of(tracker, model.layout == Layout::Doubled, keep);
    let curves: Vec<criticals::Curve> = branches
        .iter()
        .map(|b| criticals::Curve {
            mode: b.mode,
            poles: &b.poles,
            whirl_ratio: &b.whirl_ratio,
        })
        .collect();
    let criticals = criticals::criticals(model, speeds, &curves, control)?;
    control.advance(CRITICAL_WORK);
    let critical_speeds = forward_criticals(&criticals);
    let threshold = threshold(model, &summaries, control)?;
    control.advance(super::stability::work(0));
    Ok(CampbellResult {
        speeds: speeds.to_vec(),
        branches,
        overdamped,
        criticals,
        critical_speeds,
        threshold,
        reduction: None,
        ambiguities,
        interference: None,
    })
}

/// The tracker's branches as a Campbell diagram reports them: oscillating ones numbered by mode
/// and kept as `keep` asks, the overdamped ones apart, and the ambiguous hand-overs between
/// the branches kept.
pub(super) fn branches_of(
    tracker: Tracker,
    doubled: bool,
    keep: Keep,
) -> (Vec<Branch>, Vec<Branch>, Vec<Ambiguity>) {
    let (tracks, ambiguities) = tracker.finish();
    let mut all: Vec<(Branch, usize)> = vec![];
    let mut overdamped = vec![];
    for (i, t) in tracks.into_iter().enumerate() {
        let defined = t.values.iter().flatten().count();
        if defined == 0 {
            continue;
        }
        let forward = t.values.iter().flatten().filter(|s| s.im >= 0.0).count();
        let oscillating = t.values.iter().flatten().any(|&s| !poles::overdamped(s));
        let b = Branch {
            mode: 0,
            whirl: if 2 * forward >= defined {
                Whirl::Forward
            } else {
                Whirl::Backward
            },
            poles: t.values,
            whirl_ratio: t.ratios,
            shape: t.shape,
        };
        if oscillating {
            all.push((b, i));
        } else {
            overdamped.push(b);
        }
    }
    number_modes(&mut all, doubled);
    // Ambiguities between reported branches, in their indices.
    let mut kept = keep_branches(all, keep);
    let index = |track: usize| kept.iter().position(|(_, t)| *t == track);
    let ambiguities = ambiguities
        .into_iter()
        .filter_map(|a| {
            let (x, y) = (index(a.branches.0)?, index(a.branches.1)?);
            Some(Ambiguity {
                speed: a.speed,
                branches: (x.min(y), x.max(y)),
            })
        })
        .collect();
    let branches: Vec<Branch> = kept.drain(..).map(|(b, _)| b).collect();
    overdamped.retain(|b| b.poles.iter().flatten().any(|s| s.norm() <= keep.below));
    overdamped.sort_by(|a, b| {
        let first = |b: &Branch| b.poles.iter().flatten().next().map_or(0.0, |s| s.re);
        first(b).total_cmp(&first(a))
    });
    (branches, overdamped, ambiguities)
}

/// The speeds of the forward crossings that are not critically damped, ascending.
pub fn forward_criticals(c: &[Critical]) -> Vec<f64> {
    let mut out: Vec<f64> = c
        .iter()
        .filter(|c| c.whirl == Whirl::Forward && !c.critically_damped())
        .map(|c| c.speed)
        .collect();
    out.sort_by(f64::total_cmp);
    out.dedup();
    out
}

/// The Campbell diagram of the branches `keep` asks for, on a modal reduction of the rotor
/// below `keep.below` where one is checked to hold (`reduce`; see [`super::reduction`]), else
/// on `full`. The threshold is that of the model solved: with a reduction, of the poles the
/// retained modes carry.
pub fn campbell_below(
    system: &RotorSystem,
    damping: &DampingModel,
    full: &DampedModel,
    speeds: &[f64],
    keep: Keep,
    reduce: bool,
    control: &Control,
) -> Result<CampbellResult, AnalysisError> {
    let reduced = if reduce {
        reduce_for_sweep(system, damping, full, speeds, keep.below)?
    } else {
        None
    };
    match reduced {
        Some((model, reduction)) => {
            let mut r = campbell_kept(&model, speeds, keep, control)?;
            r.reduction = Some(reduction);
            Ok(r)
        }
        None => campbell_kept(full, speeds, keep, control),
    }
}

/// [`campbell_below`] for a large rotor: the reduction and its check held sparse
/// ([`super::large`]); no dense full model to fall back on.
pub fn campbell_large(
    system: &RotorSystem,
    damping: &DampingModel,
    dampers: Option<&ModalDampers>,
    speeds: &[f64],
    keep: Keep,
    max_states: usize,
    control: &Control,
) -> Result<CampbellResult, AnalysisError> {
    let (model, reduction) =
        super::large::reduce_for_sweep(system, damping, dampers, speeds, keep.below, max_states)?;
    let mut r = campbell_kept(&model, speeds, keep, control)?;
    r.reduction = Some(reduction);
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

/// The branches `keep` asks for (mode numbers unchanged), each with its track index.
fn keep_branches(mut all: Vec<(Branch, usize)>, keep: Keep) -> Vec<(Branch, usize)> {
    if keep.below.is_finite() {
        all.retain(|(b, _)| b.poles.iter().flatten().any(|s| s.im.abs() <= keep.below));
    }
    if let Some(n) = keep.lowest {
        let mut order: Vec<usize> = (0..all.len()).collect();
        order.sort_by(|&a, &b| by_start(&all[a].0, &all[b].0));
        let mut kept = vec![false; all.len()];
        for &i in order.iter().take(n) {
            kept[i] = true;
        }
        let mut k = kept.into_iter();
        all.retain(|_| k.next().unwrap_or(false));
    }
    all
}

/// Branches by where they start: their first defined speed, then |frequency| there, then |s|
/// (the order modes are numbered in, and the lowest kept). Real poles at rest (ROSS's
/// compressor) are ordered by |s|, not by their frequencies' round-off.
fn by_start(a: &Branch, b: &Branch) -> std::cmp::Ordering {
    let ((ia, fa, sa), (ib, fb, sb)) = (a.start(), b.start());
    ia.cmp(&ib).then(fa.total_cmp(&fb)).then(sa.total_cmp(&sb))
}

/// The amplitude of each coordinate of a shape, whichever member of a mirror pair it is
/// (`sqrt(|a|^2 + |b|^2)` of the halves when doubled): what the two branches of one mode share.
fn profile(shape: &[c64], doubled: bool) -> Vec<c64> {
    if doubled {
        let h = shape.len() / 2;
        (0..h)
            .map(|i| c64::new((shape[i].norm_sqr() + shape[h + i].norm_sqr()).sqrt(), 0.0))
            .collect()
    } else {
        shape.iter().map(|z| c64::new(z.norm(), 0.0)).collect()
    }
}

/// Largest pairing cost of two branches of the same mode: `1 - MAC` of their amplitude
/// profiles plus their frequency difference where both are first defined, relative to |s|.
const PAIR_GATE: f64 = 0.5;

/// Mode numbers: the two branches of each mode are paired (forward and backward on isotropic
/// supports; the two members of an anisotropic pair, which may whirl the same way), cheapest
/// pair first on the similarity of their amplitude profiles and frequencies where both start;
/// pairs and unpaired branches are numbered by where they start. Branches ordered by mode,
/// forward before backward.
fn number_modes(branches: &mut [(Branch, usize)], doubled: bool) {
    let n = branches.len();
    let profiles: Vec<Vec<c64>> = branches
        .iter()
        .map(|(b, _)| profile(&b.shape, doubled))
        .collect();
    let refs: Vec<&[c64]> = profiles.iter().map(|p| &p[..]).collect();
    let macs = linalg::mac_matrix(&refs, &refs);
    let mut pairs: Vec<(f64, usize, usize)> = vec![];
    for i in 0..n {
        for j in i + 1..n {
            let cost = (1.0 - macs[i][j]) + frequency_gap(&branches[i].0, &branches[j].0);
            if cost <= PAIR_GATE {
                pairs.push((cost, i, j));
            }
        }
    }
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut partner: Vec<Option<usize>> = vec![None; n];
    for (_, i, j) in pairs {
        if partner[i].is_none() && partner[j].is_none() {
            partner[i] = Some(j);
            partner[j] = Some(i);
        }
    }
    // A pair is numbered by the member that starts first (ties: the first index).
    let first = |i: usize, p: usize| by_start(&branches[i].0, &branches[p].0).then(i.cmp(&p));
    let mut leaders: Vec<usize> = (0..n)
        .filter(|&i| partner[i].is_none_or(|p| first(i, p).is_lt()))
        .collect();
    leaders.sort_by(|&a, &b| by_start(&branches[a].0, &branches[b].0));
    for (k, &i) in leaders.iter().enumerate() {
        branches[i].0.mode = k + 1;
        if let Some(p) = partner[i] {
            branches[p].0.mode = k + 1;
        }
    }
    branches.sort_by(|(a, _), (b, _)| {
        (a.mode, a.whirl != Whirl::Forward)
            .cmp(&(b.mode, b.whirl != Whirl::Forward))
            .then(by_start(a, b))
    });
}

/// |frequency| difference of two branches at the first speed both are defined, relative to
/// the poles' modulus (1 if never together). Not to the frequencies themselves: real poles
/// (overdamped, ROSS's compressor at rest) carry frequencies of round-off, 1e-9 rad/s of
/// poles of 1e3 1/s, whose ratio is noise and paired its branches by chance.
fn frequency_gap(a: &Branch, b: &Branch) -> f64 {
    a.poles
        .iter()
        .zip(&b.poles)
        .find_map(|(x, y)| match (x, y) {
            (Some(x), Some(y)) => {
                let size = x.norm().max(y.norm()).max(f64::MIN_POSITIVE);
                Some((x.im.abs() - y.im.abs()).abs() / size)
            }
            _ => None,
        })
        .unwrap_or(1.0)
}
