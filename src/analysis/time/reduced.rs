//! Time responses along a speed profile on a checked modal reduction.
//!
//! A run-up or a blade loss excites the rotor at the spin speed and below, but an implicit
//! integrator on the full model also follows every stiff, lightly damped high mode that the
//! error control sees. On `q = Phi eta`, with `Phi` the undamped modes up to twice the band
//! and the static corrections of the coupling forces and of the loads themselves
//! ([`ModalBasis::augmented_with`]: the quasi-static response of every dropped mode to each
//! load), the state is a few tens of entries and its fastest poles are a few times the band.
//! The basis is the one a bounded Campbell sweep uses, checked the same way
//! ([`super::super::reduction::reduce`]) but for what a forced response needs: at the fastest
//! speed of the profile, every pole of the full model within the band (every rotor pole, when
//! the model has Maxwell branches) is reproduced within 1e-3 of its decay rate (a response
//! near a pole moves by that fraction), and the other way round.
//! The band is twice the fastest speed (at least 1.5 times the first natural frequency); the
//! answer reports the reduction, and the full model is integrated where none passes.
//!
//! The reduced state is integrated by [`super::exponential`] (ETD-RK4 on stages of frozen
//! speed: every pole exact, the step held by the spin speed of the loads and the drift's
//! coupling, output samples inside a step by its dense output); TR-BDF2 only where a stage's
//! state matrix cannot be diagonalised. Checked against the full model at tolerance 1e-8 in
//! `tests/it/runup_reduction.rs`: the reduction moves the response by 4.3e-6 to 2.8e-5 of its
//! peak.
//!
//! [`ModalBasis::augmented_with`]: crate::fem::modal::ModalBasis::augmented_with

use super::{
    Coordinates, TimeError, TimeResult, TimeSpec, solve_exponential, solve_in, time_response,
    translation,
};
use crate::analysis::control::Control;
use crate::analysis::large::{self, Check};
use crate::analysis::reduction::{Criterion, RESPONSE_TOLERANCE, Reduced, Reduction, reduce};
use crate::damping::{DampedModel, ModelKind};
use crate::model::damping::DampingModel;
use crate::system::RotorSystem;

/// The state entries of a reduced model `[v, x, y]` that belong to Ritz modes at most `cutoff`
/// (velocities and displacements; branches by the mode they serve, every branch of dampers
/// `projected` from the full rotor's modes, which are not the Ritz modes).
fn slow_entries(model: &DampedModel, omega: &[f64], cutoff: f64, projected: bool) -> Vec<bool> {
    let ModelKind::Linear(state) = &model.kind else {
        return vec![true; model.states()];
    };
    let n = state.n();
    // In doubled coordinates `(eta, conj eta)` each Ritz vector appears twice.
    let m = omega.len().max(1);
    let slow = |k: usize| omega.get(k % m).is_none_or(|&w| w <= cutoff);
    let mut out: Vec<bool> = (0..2 * n).map(|i| slow(i % n)).collect();
    out.extend(state.branches().mode.iter().map(|&k| projected || slow(k)));
    out
}

/// The time response of `spec`: on a checked reduction where the speed varies and one is
/// allowed and passes, else on `full` (exact at constant speed).
pub fn solve(
    system: &RotorSystem,
    damping: &DampingModel,
    full: &DampedModel,
    spec: &TimeSpec,
    allow: bool,
    control: &Control,
) -> Result<(TimeResult, Option<Reduction>), TimeError> {
    if allow && spec.speed.constant().is_none() {
        let first = full.basis.omega.first().copied().unwrap_or(0.0);
        let (bound, fastest, loads) = band(system, spec, first);
        let criterion = Criterion::Response(RESPONSE_TOLERANCE);
        if let Ok(Some(r)) = reduce(system, damping, full, fastest, bound, &loads, criterion) {
            let out = integrate(system, &r, bound, spec, control)?;
            return Ok((out, Some(r.info)));
        }
    }
    Ok((time_response(system, full, spec, false, control)?, None))
}

/// [`solve`]'s reduction without the dense full model: for the viscous and hysteretic models
/// (and the equivalent and nonviscous models of a rotor `held` sparse, their dampers on the
/// full rotor's lowest modes and projected on the reduction), the lowest modes by Lanczos and the check through sparse factors (as [`large::reduce`]), so
/// a run-up costs no dense matrix of the rotor's size (on a 113-element cross-coupled rotor the
/// dense full model's build and check took 84 of 103 ms). The check's full-model poles are
/// found on a second thread while the first candidate is integrated: on `benches/
/// forced_ross.py`'s four rotors the run-up took 14.3 / 7.6 / 11.0 / 12.0 ms over HTTP with
/// the two in turn, 12.2 / 6.4 / 8.0 / 8.4 ms side by side, the same answer to the bit. `None`
/// where it does not apply or no reduction passes: then build the full model and [`solve`].
/// A rotor `held` sparse (past the dense limits) is reduced at a constant speed too (then
/// solved exactly on the reduction), where a small one is solved exactly on its full model: a
/// load that changes smoothly within the band is reproduced as a run-up is, but one that jumps
/// rings every mode above the band at about its static deflection, which the static
/// corrections do not hold (`tests/it/time_large.rs`: 2.5e-3 of the peak at the loaded node
/// after a sudden release, 4.2e-5 for the same blow released over its rise time).
pub fn solve_sparse(
    system: &RotorSystem,
    damping: &DampingModel,
    spec: &TimeSpec,
    allow: bool,
    held: bool,
    control: &Control,
) -> Result<Option<(TimeResult, Reduction)>, TimeError> {
    let varying = spec.speed.constant().is_none();
    // The equivalent and nonviscous models of a rotor held sparse too: their dampers on the
    // full rotor's lowest modes, the reduction carrying them projected.
    let damped = held && damping.on_modes() && !large::fitted(system);
    if !(allow && (large::sparse_applies(system, damping) || damped) && (varying || held)) {
        return Ok(None);
    }
    // The lowest modes and the band they set, in one Lanczos run. A rotor it refuses is
    // refused by the dense path too, with its message.
    let Ok(basis) = large::lowest(system, 4, |omega| bound_of(spec, omega[0])) else {
        return Ok(None);
    };
    let first = basis.omega.first().copied().unwrap_or(0.0);
    let (bound, fastest, loads) = band(system, spec, first);
    let check = Check {
        speeds: vec![fastest],
        bound,
        criterion: Criterion::Response(RESPONSE_TOLERANCE),
    };
    let Ok(dampers) = large::dampers(system, damping, bound) else {
        return Ok(None);
    };
    let dampers = dampers.as_ref();
    let Ok(mut widening) =
        large::Widening::new(system, damping, dampers, basis, &check, &loads, usize::MAX)
    else {
        return Ok(None);
    };
    // The check's full-model poles (shift-invert Arnoldi) do not depend on the basis: found
    // beside the first candidate's build and integration, which is kept if it passes (the
    // first passed on every rotor of `benches/`; the two halves take comparable time there,
    // 20-40% of the run-up each). On the pool's threads (`rayon::join`), not a thread of its
    // own: a new thread's first product reserves its own scratch (twice the L3 cache each).
    let check = &check;
    let (exact, first) = rayon::join(
        || large::exact_poles(system, damping, dampers, check),
        || {
            widening.candidate().map(|c| {
                c.map(|c| {
                    let out = integrate(system, &c, bound, spec, control);
                    (c, out)
                })
            })
        },
    );
    let (Ok(exact), Ok(Some((candidate, out)))) = (exact, first) else {
        return Ok(None);
    };
    // The candidate's own poles, for the comparison.
    let Ok(approx) = large::compared(&candidate.model, check) else {
        return Ok(None);
    };
    if let Some(r) = large::accept(candidate, &exact, &approx, check) {
        return Ok(Some((out?, r.info)));
    }
    // The first candidate failed: wider ones, integrated once one passes.
    match widening.first_passing(&exact) {
        Ok(Some(r)) => Ok(Some((integrate(system, &r, bound, spec, control)?, r.info))),
        _ => Ok(None),
    }
}

/// The band `(bound, fastest speed, load coordinates)` of `spec`: twice the fastest speed, at
/// least 1.5 times the first natural frequency `first`.
fn band(system: &RotorSystem, spec: &TimeSpec, first: f64) -> (f64, f64, Vec<usize>) {
    let (_, fastest) = spec.speed.range(spec.duration);
    let bound = bound_of(spec, first);
    let loads: Vec<usize> = spec
        .forces
        .iter()
        .map(|f| f.node)
        .chain(spec.unbalances.iter().map(|u| u.node))
        .map(|node| translation(system, node))
        .collect();
    (bound, fastest, loads)
}

/// Twice the fastest speed of `spec`, at least 1.5 times the first natural frequency `first`.
fn bound_of(spec: &TimeSpec, first: f64) -> f64 {
    let (_, fastest) = spec.speed.range(spec.duration);
    (2.0 * fastest).max(1.5 * first)
}

/// The response of `spec` integrated on the reduction `r` of band `bound`.
fn integrate(
    system: &RotorSystem,
    r: &Reduced,
    bound: f64,
    spec: &TimeSpec,
    control: &Control,
) -> Result<TimeResult, TimeError> {
    let c = Coordinates {
        physical: system,
        solved: &r.system,
        basis: Some(&r.basis.phi),
        slow: Some(slow_entries(
            &r.model,
            &r.basis.omega,
            2.0 * bound,
            r.info.dampers.is_some(),
        )),
    };
    // At a constant speed (a rotor held sparse) the reduced model is solved exactly, as a
    // small rotor's full model is.
    match spec.speed.constant() {
        Some(_) => solve_in(&c, &r.model, spec, false, control),
        None => solve_exponential(&c, &r.model, spec, control),
    }
}
