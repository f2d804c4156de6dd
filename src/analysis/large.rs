//! Sweeps of large rotors: the checked modal reduction with no dense matrix of the rotor's size.
//!
//! [`super::reduction`] reduces a sweep on the lowest undamped modes and checks it against the
//! full model, but holds the full model dense: its modes by a full symmetric eigensolve
//! (`O(n^3)`) and its poles through a dense factor of `Z(sigma)` (`O(n^3)`), so that a sweep's
//! cost grows with the cube of the mesh. Here every step is linear in the mesh: the lowest modes
//! by shift-invert Lanczos on the sparse `(K, M)` ([`ModalBasis::lowest`]), their static
//! corrections by a sparse Cholesky factor of `K`, the projections by sparse products, and the
//! full model's poles in the disc the check reads by shift-invert Arnoldi through a sparse LU
//! of `Z(sigma)` ([`crate::damping::large`]). The reduced model is small and dense as before;
//! the basis widens by half until the check passes (the same check, [`TOLERANCE`] relative).
//!
//! Used for bounded sweeps of the viscous and hysteretic models (whose full model is the rotor's
//! own second-order system) where the full model has more than [`SPARSE_FROM`] coordinates and
//! no Guyan reduction (the parse decides, `model::task`); below that the dense path is as fast.
//! The answer's reduction says which was used.
//!
//! [`SPARSE_FROM`]: crate::model::limits::SPARSE_FROM

use super::AnalysisError;
use super::nearest;
use super::reduction::{
    Criterion, Reduced, Reduction, TOLERANCE, both_ways, checked_speeds, compared_at, distance,
    with_supports,
};
use crate::damping::dampers::ModalDampers;
use crate::damping::{DampedModel, DampingError, ModelKind, large};
use crate::fem::modal::{ModalBasis, ModalError};
use crate::linalg::{LinalgError, arnoldi, c64};
use crate::model::damping::DampingModel;
use crate::model::limits::SPARSE_ARNOLDI;
use crate::system::{Layout, RotorSystem};

/// Full states from which a run-up or a Level I screen reduces without its dense full model:
/// below, the dense model costs little and the check's Krylov space (at most half the state)
/// has no room (a Jeffcott rotor's Lanczos run does not converge).
pub const SPARSE_FROM_STATES: usize = 100;

/// Whether `system` under `damping` reduces without its dense full model (run-ups, Level I):
/// the viscous and hysteretic models (the rotor's own second-order system, sparse) of at least
/// [`SPARSE_FROM_STATES`] states.
pub fn sparse_applies(system: &RotorSystem, damping: &DampingModel) -> bool {
    matches!(damping, DampingModel::Viscous | DampingModel::Hysteretic)
        && 2 * full_size(system) >= SPARSE_FROM_STATES
        && !fitted(system)
}

/// Whether a support carries Maxwell branches fitted to a table over whirl frequency: the
/// sparse full model has no internal coordinates for them, so such a rotor is solved dense.
pub fn fitted(system: &RotorSystem) -> bool {
    system.supports.iter().any(|p| p.support.branches.is_some())
}

/// Coordinates `N` of the full second-order model.
pub fn full_size(system: &RotorSystem) -> usize {
    system.layout().size(system.n())
}

/// The equivalent or nonviscous model's dampers of a rotor held sparse for an analysis bounded
/// by `bound` (`damping::dampers`), `None` for the other models.
pub fn dampers(
    system: &RotorSystem,
    damping: &DampingModel,
    bound: f64,
) -> Result<Option<ModalDampers>, AnalysisError> {
    ModalDampers::new(system, damping, bound)
        .map_err(|e| AnalysisError::Damping(DampingError::Modal(e)))
}

/// Why a large rotor's sweep could not be reduced: the dense full model is no fallback there.
fn not_reduced(states: usize, max_states: usize) -> AnalysisError {
    AnalysisError::Damping(DampingError::Unsolvable(format!(
        "no modal reduction of this rotor ({states} states) with at most half its states and \
         at most {max_states} (WHIRL_MAX_STATES) passed the check against the full model, and \
         a rotor this large is not solved dense: lower `max_frequency`"
    )))
}

/// The checked reduced model of a sweep over `speeds` below `bound` (see the module docs).
pub fn reduce_for_sweep(
    system: &RotorSystem,
    damping: &DampingModel,
    dampers: Option<&ModalDampers>,
    speeds: &[f64],
    bound: f64,
    max_states: usize,
) -> Result<(DampedModel, Reduction), AnalysisError> {
    let check = Check {
        speeds: checked_speeds(system, speeds),
        bound,
        criterion: Criterion::Relative(TOLERANCE),
    };
    match reduce(
        system,
        damping,
        dampers,
        lowest(system, 4, |_| bound)?,
        &check,
        &[],
        max_states,
    )? {
        Some(r) => Ok((r.model, r.info)),
        None => Err(not_reduced(2 * full_size(system), max_states)),
    }
}

/// What a reduction is checked for: every full-model pole in the box `|Re s|, |Im s| <= bound`
/// at each of `speeds` (the first reported) reproduced as `criterion` asks, both ways.
pub struct Check {
    pub speeds: Vec<f64>,
    pub bound: f64,
    pub criterion: Criterion,
}

/// At least the lowest `count` undamped modes by Lanczos, and every one with `w <= 2 bound` and
/// the first past it, the bound from the frequencies found (a run-up's and a Level I screen's
/// band follows from the lowest modes: one Lanczos run finds them and the band).
pub fn lowest(
    system: &RotorSystem,
    count: usize,
    bound: impl Fn(&[f64]) -> f64,
) -> Result<ModalBasis, AnalysisError> {
    ModalBasis::lowest(system, |w2| {
        let omega: Vec<f64> = w2.iter().map(|w| w.sqrt()).collect();
        omega.len() >= count && omega.last().is_some_and(|&l| l > 2.0 * bound(&omega))
    })
    .map_err(|e| AnalysisError::Damping(DampingError::Modal(e)))
}

/// The sparse counterpart of [`super::reduction::reduce_checked`]: from `basis` (the lowest
/// modes, extended by Lanczos as needed), the modes with `w <= 2 bound` (at least 4), their
/// static corrections and those of unit loads on `loads` and where the supports act, widened by
/// half until `check` passes; `None` when no basis of at most half the states and `max_states`
/// does.
pub fn reduce(
    system: &RotorSystem,
    damping: &DampingModel,
    dampers: Option<&ModalDampers>,
    basis: ModalBasis,
    check: &Check,
    loads: &[usize],
    max_states: usize,
) -> Result<Option<Reduced>, AnalysisError> {
    let mut widening = Widening::new(system, damping, dampers, basis, check, loads, max_states)?;
    let exact = exact_poles(system, damping, dampers, check)?;
    widening.first_passing(&exact)
}

/// The full model's poles that `check` compares with, at each of its speeds: every one within
/// 1.5 times its bound. They do not depend on the basis (a run-up finds them on a second thread
/// while it integrates its first candidate).
pub fn exact_poles(
    system: &RotorSystem,
    damping: &DampingModel,
    dampers: Option<&ModalDampers>,
    check: &Check,
) -> Result<Vec<Split>, AnalysisError> {
    check
        .speeds
        .iter()
        .map(|&w| full_split(system, damping, dampers, w, 1.5 * check.bound))
        .collect()
}

/// A model's eigenvalues at one speed as a check compares them: its rotor poles, and the
/// others (the nonviscous model's internal poles; none for the other models).
#[derive(Debug, Clone, Default)]
pub struct Split {
    pub rotor: Vec<c64>,
    pub others: Vec<c64>,
}

impl Split {
    /// The largest relative distance, as `criterion` measures it, from a rotor pole of either
    /// set in the box `|Re s|, |Im s| <= bound` to the nearest eigenvalue of the other
    /// (rotor or internal: a heavily damped pole that is half in the branches may be a rotor
    /// pole of one model and an internal one of the other, and the eigenvalue is what must
    /// agree). Without internal poles, [`both_ways`].
    pub fn distance(&self, other: &Split, bound: f64, criterion: Criterion) -> f64 {
        if self.others.is_empty() && other.others.is_empty() {
            return both_ways(&self.rotor, &other.rotor, bound, criterion);
        }
        let all = |s: &Split| -> Vec<c64> { s.rotor.iter().chain(&s.others).copied().collect() };
        let inside = |v: &[c64]| -> Vec<c64> {
            v.iter()
                .copied()
                .filter(|s| s.re.abs() <= bound && s.im.abs() <= bound)
                .collect()
        };
        distance(&inside(&self.rotor), &all(other), criterion).max(distance(
            &inside(&other.rotor),
            &all(self),
            criterion,
        ))
    }
}

/// [`reduce`]'s candidates, each basis half as wide again as the last.
pub struct Widening<'a> {
    system: &'a RotorSystem,
    damping: &'a DampingModel,
    dampers: Option<&'a ModalDampers>,
    check: &'a Check,
    basis: ModalBasis,
    loads: Vec<usize>,
    /// Modes of the next candidate.
    m: usize,
    max_states: usize,
}

impl<'a> Widening<'a> {
    pub fn new(
        system: &'a RotorSystem,
        damping: &'a DampingModel,
        dampers: Option<&'a ModalDampers>,
        mut basis: ModalBasis,
        check: &'a Check,
        loads: &[usize],
        max_states: usize,
    ) -> Result<Self, AnalysisError> {
        let bound = check.bound;
        let band = |w: f64| w <= 2.0 * bound;
        // Every mode in the band, and one past it (a basis found for a narrower band).
        if basis.omega.last().is_none_or(|&w| band(w)) {
            basis = lowest(system, basis.len() + 1, |_| bound)?;
        }
        let m = basis.omega.iter().filter(|&&w| band(w)).count().max(4);
        Ok(Widening {
            system,
            damping,
            dampers,
            check,
            basis,
            loads: with_supports(system, loads),
            m,
            max_states,
        })
    }

    /// The next candidate, its `info` still without the check's error ([`judge`] fills it);
    /// `None` once a candidate would not halve the state or would pass `max_states`.
    pub fn candidate(&mut self) -> Result<Option<Reduced>, AnalysisError> {
        let (system, m, bound) = (self.system, self.m, self.check.bound);
        if self.basis.len() < m + 1 {
            self.basis = lowest(system, m + 1, |_| bound)?;
        }
        let sub = self
            .basis
            .augmented_with(system, m, &self.loads)
            .map_err(|e: ModalError| AnalysisError::Damping(DampingError::Modal(e)))?;
        let reduced = sub.reduce(system);
        let model = match self.dampers {
            Some(d) => DampedModel::projected(&reduced, system, self.damping, d, &sub.phi)?,
            None => DampedModel::build(&reduced, self.damping)?,
        };
        let full_states = 2 * full_size(system) + self.dampers.map_or(0, |d| d.internal());
        if 2 * model.states() > full_states || model.states() > self.max_states {
            return Ok(None);
        }
        self.m = (3 * m).div_ceil(2);
        let info = Reduction {
            modes: m,
            vectors: sub.len(),
            states: model.states(),
            full_states,
            band: self.basis.omega[m - 1],
            checked_speed: self.check.speeds[0],
            checked_speeds: self.check.speeds.clone(),
            max_relative_error: f64::NAN,
            sparse: true,
            outside: None,
            dampers: self.dampers.map(|d| (d.modes(), d.band())),
        };
        Ok(Some(Reduced {
            system: reduced,
            model,
            basis: sub,
            info,
        }))
    }

    /// The first of the remaining candidates that passes the check against the full model's
    /// poles `exact` (from [`exact_poles`]), or `None`.
    pub fn first_passing(&mut self, exact: &[Split]) -> Result<Option<Reduced>, AnalysisError> {
        let mut exact = exact.to_vec();
        let mut closed = false;
        while let Some(candidate) = self.candidate()? {
            let approx = compared(&candidate.model, self.check)?;
            // A full-model pole no candidate value is near may be the Arnoldi's own error (a
            // pole far from its shift, of a non-normal model: 1.7e-6 on a heavily damped pole
            // of the train's nonviscous model at the disc's edge): closed by shift-invert at
            // itself, once, before the candidate is judged.
            if !closed && self.dampers.is_some() {
                closed = true;
                self.close_unmatched(&mut exact, &approx)?;
            }
            if let Some(r) = accept(candidate, &exact, &approx, self.check) {
                return Ok(Some(r));
            }
        }
        Ok(None)
    }

    /// Each rotor pole of `exact` in the box farther than the tolerance from every value of
    /// `approx`, replaced by the full model's eigenvalue nearest it (shift-invert at itself).
    fn close_unmatched(&self, exact: &mut [Split], approx: &[Split]) -> Result<(), AnalysisError> {
        let check = self.check;
        let tolerance = match check.criterion {
            Criterion::Relative(t) | Criterion::Response(t) => t,
        };
        for ((e, a), &speed) in exact.iter_mut().zip(approx).zip(&check.speeds) {
            let problems = large::problems(
                self.system,
                self.damping,
                self.dampers.map(|d| d.at(self.system, speed)),
                speed,
            );
            let Some(problems) = problems else {
                continue;
            };
            let all: Vec<c64> = a.rotor.iter().chain(&a.others).copied().collect();
            for s in e.rotor.iter_mut() {
                let inside = s.re.abs() <= check.bound && s.im.abs() <= check.bound;
                if !inside || distance(&[*s], &all, check.criterion) <= tolerance {
                    continue;
                }
                let mut best = *s;
                let mut distance = f64::INFINITY;
                for p in problems.iter().filter(|p| p.consistent(*s, speed)) {
                    let op = p.shift_invert(*s)?;
                    let found = arnoldi::nearest_from(
                        op.states(),
                        |b| op.solve(b),
                        *s,
                        1e-3 * s.norm(),
                        nearest::TOLERANCE,
                        (12, 1),
                        60.min(op.states() / 2),
                    )?;
                    for t in found.map(|f| f.values).unwrap_or_default() {
                        if (t - *s).norm() < distance {
                            (best, distance) = (t, (t - *s).norm());
                        }
                    }
                }
                *s = best;
            }
        }
        Ok(())
    }
}

/// `candidate` with its error in its `info` if it reproduces the full model's poles `exact`
/// (from [`exact_poles`]) as `check` asks, both ways; else `None`.
pub fn judge(
    candidate: Reduced,
    exact: &[Split],
    check: &Check,
) -> Result<Option<Reduced>, AnalysisError> {
    let approx = compared(&candidate.model, check)?;
    Ok(accept(candidate, exact, &approx, check))
}

/// The poles of a candidate's `model` that `check` compares, at each of its speeds.
pub fn compared(model: &DampedModel, check: &Check) -> Result<Vec<Split>, AnalysisError> {
    check
        .speeds
        .iter()
        .map(|&w| compared_split(model, w))
        .collect()
}

/// [`compared_at`] with the internal poles apart (those of a model with internal coordinates).
fn compared_split(model: &DampedModel, speed: f64) -> Result<Split, AnalysisError> {
    let rotor = compared_at(model, speed)?;
    let others = match &model.kind {
        ModelKind::Linear(m) if m.p() > 0 => {
            let set = super::poles::poles_at(model, speed)?;
            let mut out: Vec<c64> = set.internal.iter().map(|p| p.s).collect();
            if model.layout == Layout::Doubled {
                out.extend(set.internal.iter().map(|p| p.s.conj()));
            }
            out
        }
        _ => vec![],
    };
    Ok(Split { rotor, others })
}

/// [`judge`] with the candidate's poles `approx` (from [`compared`]) already found.
pub fn accept(
    mut candidate: Reduced,
    exact: &[Split],
    approx: &[Split],
    check: &Check,
) -> Option<Reduced> {
    let error = exact
        .iter()
        .zip(approx)
        .map(|(e, a)| e.distance(a, check.bound, check.criterion))
        .fold(0.0, f64::max);
    let tolerance = match check.criterion {
        Criterion::Relative(t) | Criterion::Response(t) => t,
    };
    (error <= tolerance).then(|| {
        candidate.info.max_relative_error = error;
        candidate
    })
}

/// [`super::reduction::band_error`] for a full model held sparse: the largest relative distance
/// between the poles of `system` and of `reduced` at `speed`, both ways, over those in the box
/// `|Re s|, |Im s| <= bound`.
pub fn band_error(
    system: &RotorSystem,
    damping: &DampingModel,
    dampers: Option<&ModalDampers>,
    reduced: &DampedModel,
    speed: f64,
    bound: f64,
) -> Result<f64, AnalysisError> {
    let exact = full_split(system, damping, dampers, speed, 1.5 * bound)?;
    let approx = compared_split(reduced, speed)?;
    Ok(exact.distance(&approx, bound, Criterion::Relative(TOLERANCE)))
}

/// Every pole of the full model at `speed` within `radius` of the origin (for the hysteretic
/// model, the consistent roots of its four problems), by shift-invert Arnoldi through sparse
/// factors.
pub fn full_poles(
    system: &RotorSystem,
    damping: &DampingModel,
    dampers: Option<&ModalDampers>,
    speed: f64,
    radius: f64,
) -> Result<Vec<c64>, AnalysisError> {
    Ok(full_modes(system, damping, dampers, speed, radius)?
        .into_iter()
        .map(|(s, _)| s)
        .collect())
}

/// [`full_poles`] and the full model's other eigenvalues in the disc (the nonviscous model's
/// internal poles).
pub fn full_split(
    system: &RotorSystem,
    damping: &DampingModel,
    dampers: Option<&ModalDampers>,
    speed: f64,
    radius: f64,
) -> Result<Split, AnalysisError> {
    let mut out = Split::default();
    for (s, _, rotor) in full_eigen(system, damping, dampers, speed, radius)? {
        match rotor {
            true => out.rotor.push(s),
            false => out.others.push(s),
        }
    }
    Ok(out)
}

/// [`full_poles`] with each pole's shape on the coordinates (the displacement half of its
/// first-order eigenvector, unscaled).
pub fn full_modes(
    system: &RotorSystem,
    damping: &DampingModel,
    dampers: Option<&ModalDampers>,
    speed: f64,
    radius: f64,
) -> Result<Vec<(c64, Vec<c64>)>, AnalysisError> {
    Ok(full_eigen(system, damping, dampers, speed, radius)?
        .into_iter()
        .filter(|e| e.2)
        .map(|(s, x, _)| (s, x))
        .collect())
}

/// Every eigenvalue of the full model within `radius` (consistent ones, hysteretic), with its
/// shape and whether it is a rotor pole (most of its energy in the rotor, not the branches).
fn full_eigen(
    system: &RotorSystem,
    damping: &DampingModel,
    dampers: Option<&ModalDampers>,
    speed: f64,
    radius: f64,
) -> Result<Vec<(c64, Vec<c64>, bool)>, AnalysisError> {
    let problems = large::problems(system, damping, dampers.map(|d| d.at(system, speed)), speed)
        .ok_or_else(|| {
            AnalysisError::Damping(DampingError::Unsolvable(
                "the equivalent and nonviscous models of a large rotor have no sparse form".into(),
            ))
        })?;
    // Off both axes, as `nearest` shifts (rigid-body poles at 0, mirror pairs on the real axis).
    let sigma = c64::new(0.0113, 0.0137) * (radius / 1.5);
    let mut out = vec![];
    for p in &problems {
        let op = p.shift_invert(sigma)?;
        let size = op.states();
        let found = arnoldi::nearest(
            size,
            |b| op.solve(b),
            sigma,
            radius,
            nearest::TOLERANCE,
            // The nonviscous model's internal poles (on the negative real axis, moved by
            // `i Omega` for rotating branches) share the disc with the rotor's.
            (size / 2).min(SPARSE_ARNOLDI + p.internal()),
        )?
        .ok_or(AnalysisError::Linalg(LinalgError::NoConvergence))?;
        let n = op.coordinates();
        out.extend(
            found
                .values
                .into_iter()
                .zip(found.vectors)
                .filter(|(s, _)| p.consistent(*s, speed))
                .map(|(s, z)| {
                    let rotor = p.internal() == 0 || p.rotor_fraction(&z) >= 0.5;
                    (s, z[n..2 * n].to_vec(), rotor)
                }),
        );
    }
    Ok(out)
}
