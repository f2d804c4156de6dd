//! Modal reduction of a sweep below a frequency bound, checked against the full model.
//!
//! A Campbell diagram up to a bound `w_b` needs only the poles below it. Projected on its
//! lowest undamped nonrotating modes, `q = Phi_m eta` (a Rayleigh-Ritz reduction, see
//! [`ModalBasis::reduce`]), the rotor keeps every matrix, rotating and nonrotating apart, and
//! every damping model builds on it unchanged; the state shrinks from `2n + p` to `2m + p`
//! and each eigenproblem by `((2n + p) / (2m + p))^3`.
//!
//! The basis is the modes with `w_k <= 2 w_b` (at least 4) and their static corrections
//! ([`ModalBasis::augmented`]), plus the static responses to unit loads where supports and
//! nonrotating dampers act (heavily damped supports pin the damped modes there, which free
//! modes span poorly) and, for a time response, where the loads act; the band widens by half until the check passes: at the
//! fastest speed of the sweep (where the gyroscopic coupling of the neglected modes is
//! largest) every full-model eigenvalue in the box `|Re s|, |Im s| <= w_b` has a reduced one
//! within [`TOLERANCE`] relative, and the other way round. The measured error is reported.
//! Reduction is used only where it at least halves the state.
//!
//! [`ModalBasis::reduce`]: crate::fem::modal::ModalBasis::reduce
//! [`ModalBasis::augmented`]: crate::fem::modal::ModalBasis::augmented

use super::AnalysisError;
use super::nearest::Wanted;
use crate::damping::{DampedModel, ModelKind};
use crate::fem::modal::ModalBasis;
use crate::linalg::{self, LinalgError, c64};
use crate::model::damping::DampingModel;
use crate::system::{Layout, RotorSystem};

/// Largest relative eigenvalue change allowed by the reduction of a sweep, at the check speed.
pub const TOLERANCE: f64 = 1e-6;

/// Largest change of a pole relative to its decay rate (or to a thousandth of its modulus,
/// if larger) allowed by the reduction of a time response: a forced response near a pole
/// moves by about that fraction. The state matrix of a full model itself carries round-off
/// of `eps w_max^2` relative to its poles (4e-6 for heavily damped poles of a 100-element
/// shaft whose rotations reach 1e6 rad/s), below which no relative check can pass.
pub const RESPONSE_TOLERANCE: f64 = 1e-3;

/// How a reduced model is compared with the full one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Criterion {
    /// `|s - s_full| / |s_full|` (sweeps: what the Campbell diagram shows).
    Relative(f64),
    /// `|s - s_full| / max(|Re s_full|, 1e-3 |s_full|)` (time responses).
    Response(f64),
}

/// How a sweep was reduced.
#[derive(Debug, Clone, PartialEq)]
pub struct Reduction {
    /// Undamped modes retained.
    pub modes: usize,
    /// Size of the basis: the modes and their independent static corrections.
    pub vectors: usize,
    /// State size of each reduced eigenproblem.
    pub states: usize,
    /// State size of the full model.
    pub full_states: usize,
    /// Natural frequency of the highest retained mode, rad/s.
    pub band: f64,
    /// The speed at which the reduced poles were checked against the full ones.
    pub checked_speed: f64,
    /// Every speed checked (`checked_speed` first): with supports that change with the speed,
    /// also the sweep's lowest and middle speeds.
    pub checked_speeds: Vec<f64>,
    /// Largest relative distance between a checked pole and its counterpart.
    pub max_relative_error: f64,
    /// Whether the full model was held sparse (`analysis::large`).
    pub sparse: bool,
    /// For a sweep, the poles it reported outside the checked box, refined on the full model
    /// ([`super::refine`]).
    pub outside: Option<Outside>,
    /// The equivalent or nonviscous model held sparse: the modes with dampers and the highest
    /// one's natural frequency, rad/s (`damping::dampers`).
    pub dampers: Option<(usize, f64)>,
}

/// What refining the poles outside the checked box did.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Outside {
    /// Poles reported outside the box `|Re s|, |Im s| <= bound` (over every speed, and the
    /// crossings' poles).
    pub poles: usize,
    /// Of those, replaced by the full model's eigenvalue nearest them.
    pub refined: usize,
    /// Of those, removed: no full-model eigenvalue within 25 % of them.
    pub removed: usize,
    /// Largest `|s_full - s_reduced| / |s_full|` of a refined pole.
    pub largest_change: f64,
}

/// The reduced model for a sweep over `speeds` with poles wanted below `bound`, or `None` when
/// no reduction at least halves the state and passes the check (then solve `full`).
pub fn reduce_for_sweep(
    system: &RotorSystem,
    damping: &DampingModel,
    full: &DampedModel,
    speeds: &[f64],
    bound: f64,
) -> Result<Option<(DampedModel, Reduction)>, AnalysisError> {
    if speeds.is_empty() {
        return Ok(None);
    }
    let checked = checked_speeds(system, speeds);
    Ok(reduce_checked(
        system,
        damping,
        full,
        &checked,
        bound,
        &[],
        Criterion::Relative(TOLERANCE),
    )?
    .map(|r| (r.model, r.info)))
}

/// The speeds a sweep's reduction is checked at: the fastest (where the gyroscopic coupling of
/// the neglected modes is largest) first. The basis is the rotor's at rest with static
/// corrections where the supports act; when the supports change with the speed, one speed's
/// check does not vouch for the others (a tabulated rotor's poles drifted to 4e-6 in the middle
/// of a sweep checked to 5e-7 at its top): the lowest and the middle speed are checked too.
pub fn checked_speeds(system: &RotorSystem, speeds: &[f64]) -> Vec<f64> {
    let top = speeds
        .iter()
        .cloned()
        .fold(0.0, |a: f64, b| if b.abs() > a.abs() { b } else { a });
    let mut checked = vec![top];
    if system.speed_dependent() && !speeds.is_empty() {
        let mut sorted = speeds.to_vec();
        sorted.sort_by(f64::total_cmp);
        for w in [sorted[0], sorted[sorted.len() / 2]] {
            if !checked.contains(&w) {
                checked.push(w);
            }
        }
    }
    checked
}

/// A checked reduction: the rotor in the coordinates of its basis (`q = phi eta`), its damped
/// model, the basis and what was checked.
pub struct Reduced {
    pub system: RotorSystem,
    pub model: DampedModel,
    pub basis: ModalBasis,
    pub info: Reduction,
}

/// The lowest undamped modes with `w <= 2 bound` (at least 4), their static corrections and
/// those of unit loads on `loads`, widened until every full-model pole in the box
/// `|Re s|, |Im s| <= bound` at `checked_speed` is reproduced within [`TOLERANCE`] (and the
/// other way round); `None` if no such basis at least halves the state.
pub fn reduce(
    system: &RotorSystem,
    damping: &DampingModel,
    full: &DampedModel,
    checked_speed: f64,
    bound: f64,
    loads: &[usize],
    criterion: Criterion,
) -> Result<Option<Reduced>, AnalysisError> {
    reduce_checked(
        system,
        damping,
        full,
        &[checked_speed],
        bound,
        loads,
        criterion,
    )
}

/// [`reduce`] checked at each of `checked` (the first reported as `checked_speed`).
pub fn reduce_checked(
    system: &RotorSystem,
    damping: &DampingModel,
    full: &DampedModel,
    checked: &[f64],
    bound: f64,
    loads: &[usize],
    criterion: Criterion,
) -> Result<Option<Reduced>, AnalysisError> {
    let n = system.n();
    let checked_speed = checked[0];
    if !bound.is_finite() {
        return Ok(None);
    }
    let basis = &full.basis;
    let mut m = basis
        .omega
        .iter()
        .filter(|&&w| w <= 2.0 * bound)
        .count()
        .max(4);
    // The static response to a unit load where the supports act: with heavy support damping
    // the damped modes pivot about the supports, which the free modes alone span poorly; for
    // supports in the general form it also spans their anisotropy and cross-coupling.
    let loads = &with_supports(system, loads)[..];
    // A basis of `m` modes, its reduced model and the poles it gives; `None` if it cannot be
    // built (which only means no reduction) or does not at least halve the state.
    let candidate = |m: usize| -> Option<(ModalBasis, RotorSystem, DampedModel, Vec<Vec<c64>>)> {
        let sub = basis.augmented_with(system, m, loads).ok()?;
        let reduced = sub.reduce(system);
        let model = DampedModel::build(&reduced, damping).ok()?;
        if 2 * model.states() > full.states() {
            return None;
        }
        let approx = checked
            .iter()
            .map(|&w| compared_at(&model, w))
            .collect::<Result<_, _>>()
            .ok()?;
        Some((sub, reduced, model, approx))
    };
    if m >= n {
        return Ok(None);
    }
    // The full model's poles (the one large solve) and the first basis at once.
    let (exact, mut next) = rayon::join(
        || -> Result<Vec<Vec<c64>>, LinalgError> {
            checked
                .iter()
                .map(|&w| full_compared(full, w, bound))
                .collect()
        },
        || candidate(m),
    );
    let Some(first) = next.take() else {
        return Ok(None);
    };
    let exact = exact?;
    let tolerance = match criterion {
        Criterion::Relative(t) | Criterion::Response(t) => t,
    };
    let mut current = Some(first);
    while let Some((sub, reduced, model, approx)) = current {
        let error = exact
            .iter()
            .zip(&approx)
            .map(|(e, a)| both_ways(e, a, bound, criterion))
            .fold(0.0, f64::max);
        if error <= tolerance {
            let info = Reduction {
                modes: m,
                vectors: sub.len(),
                states: model.states(),
                full_states: full.states(),
                band: basis.omega[m - 1],
                checked_speed,
                checked_speeds: checked.to_vec(),
                max_relative_error: error,
                sparse: false,
                outside: None,
                dampers: None,
            };
            return Ok(Some(Reduced {
                system: reduced,
                model,
                basis: sub,
                info,
            }));
        }
        m = (3 * m).div_ceil(2);
        current = if m < n { candidate(m) } else { None };
    }
    Ok(None)
}

/// Largest relative distance between the poles of `full` and of `reduced` at `speed`, both
/// ways, over those in the box `|Re s|, |Im s| <= bound` (the check [`reduce`] makes, for a
/// model that changed after it: Level I's cross-coupling). Eigenvalues only (with vectors
/// where rotor poles are told from internal ones); the full model's by shift-invert Arnoldi
/// where that is cheaper than the dense solve.
pub fn band_error(
    full: &DampedModel,
    reduced: &DampedModel,
    speed: f64,
    bound: f64,
) -> Result<f64, LinalgError> {
    let criterion = Criterion::Relative(TOLERANCE);
    let (exact, approx) = rayon::join(
        || full_compared(full, speed, bound),
        || compared_at(reduced, speed),
    );
    Ok(both_ways(&exact?, &approx?, bound, criterion))
}

/// Largest distance from a pole of either set in the box `|Re s|, |Im s| <= bound` to the
/// nearest of the other set, as `criterion` measures it.
pub(super) fn both_ways(exact: &[c64], approx: &[c64], bound: f64, criterion: Criterion) -> f64 {
    let inside = |v: &[c64]| -> Vec<c64> {
        v.iter()
            .cloned()
            .filter(|s| s.re.abs() <= bound && s.im.abs() <= bound)
            .collect()
    };
    distance(&inside(exact), approx, criterion).max(distance(&inside(approx), exact, criterion))
}

/// `loads` with the coordinates where supports and nonrotating dampers act, sorted, once each:
/// where a reduction's basis carries the static responses to unit loads.
pub fn with_supports(system: &RotorSystem, loads: &[usize]) -> Vec<usize> {
    let mut loads = loads.to_vec();
    for p in &system.supports {
        loads.extend(p.at.weights().iter().map(|&(d, _)| d));
    }
    for a in [&system.damping_nonrotating, &system.hysteretic_nonrotating] {
        loads.extend(a.entries().filter(|e| e.2 != 0.0).map(|e| e.0));
    }
    loads.sort_unstable();
    loads.dedup();
    loads
}

/// Largest distance from a value in `from` to the nearest in `to`, as `criterion` measures it.
pub(super) fn distance(from: &[c64], to: &[c64], criterion: Criterion) -> f64 {
    from.iter()
        .map(|s| {
            let nearest = to
                .iter()
                .map(|t| (s - t).norm())
                .fold(f64::INFINITY, f64::min);
            let scale = match criterion {
                Criterion::Relative(_) => s.norm(),
                Criterion::Response(_) => s.re.abs().max(1e-3 * s.norm()),
            };
            nearest / scale.max(f64::MIN_POSITIVE)
        })
        .fold(0.0, f64::max)
}

/// The poles compared at `speed`: every eigenvalue, but for a model with internal coordinates
/// (the nonviscous model's Maxwell branches) its rotor poles only, which are all any analysis
/// reports. The full model's branches sit on every mode, and those of modes far above the
/// band relax within it (a branch centred on `w_k` has a rate `w_k / 10`); a reduction carries
/// those modes quasi-statically through its static corrections, so their internal poles have
/// no counterpart, while their effect on the rotor poles is compared. Comparing the rotor poles
/// also lets the full model's be found by shift-invert Arnoldi: its internal poles include
/// ill-conditioned ones only the dense solve places to 1e-7 (a 1616-state model's rotor poles
/// in 0.4 s instead of 5.8, `tests/it/nearest.rs`).
pub(super) fn compared_at(model: &DampedModel, speed: f64) -> Result<Vec<c64>, LinalgError> {
    match &model.kind {
        // A support's fitted branches are poles of the support, compared like the rotor's.
        ModelKind::Linear(m) if m.branches().modelled() => {
            let rotor = super::poles::poles_at(model, speed)?.rotor;
            let mut out: Vec<c64> = rotor.iter().map(|p| p.s).collect();
            // Doubled, each pole was kept once of its mirror pair `(s, conj s)`; the full
            // model's are compared as found (both), so both sides carry both.
            if model.layout == Layout::Doubled {
                out.extend(rotor.iter().map(|p| p.s.conj()));
            }
            Ok(out)
        }
        _ => eigenvalues_at(model, speed),
    }
}

/// The full model's poles as [`compared_at`] gives them, those in a disc covering the box
/// `|Re s|, |Im s| <= bound` (all the check reads: a pole outside it is no nearer to one inside
/// than the disc's edge), by shift-invert Arnoldi where that is cheaper than the dense solve.
fn full_compared(model: &DampedModel, speed: f64, bound: f64) -> Result<Vec<c64>, LinalgError> {
    let wanted = match &model.kind {
        ModelKind::Linear(m) if m.branches().modelled() => Wanted::Rotor,
        _ => Wanted::All,
    };
    match super::nearest::poles_within(model, speed, 1.5 * bound, wanted)? {
        Some(poles) => Ok(poles),
        None => compared_at(model, speed),
    }
}

/// Every eigenvalue of the model at `speed` (for the hysteretic model, the consistent roots).
fn eigenvalues_at(model: &DampedModel, speed: f64) -> Result<Vec<c64>, LinalgError> {
    match &model.kind {
        ModelKind::Linear(m) => linalg::eigenvalues(&m.at(speed)),
        ModelKind::Hysteretic(signed) => {
            let mut out = vec![];
            for sm in signed {
                out.extend(
                    linalg::eigenvalues(&sm.model.at(speed))?
                        .into_iter()
                        .filter(|&s| sm.consistent(s, speed)),
                );
            }
            Ok(out)
        }
    }
}
