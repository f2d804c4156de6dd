//! Poles at one spin speed, and the undamped nonrotating natural frequencies.
//!
//! Every pole of the model ([`modal`]), or those in the box `|Re s|, |Im s| <= bound`
//! ([`modal_bounded`]; a rotor held sparse only so, [`modal_large`]: the box's poles of the
//! full model by shift-invert Arnoldi through sparse factors of `Z(sigma)`, in a disc of radius
//! `sqrt 2 bound` that holds the box, each closed by shift-invert at itself, and the natural
//! frequencies below the bound by Lanczos on the sparse `(K, M)`; exact, with no dense matrix
//! of the rotor's size and no reduction).

use super::AnalysisError;
use super::large;
use super::poles::{PoleSet, poles_at, rotor_set};
use super::refine::{Full, nearest_pole};
use crate::damping::dampers::ModalDampers;
use crate::damping::{DampedModel, DampingError};
use crate::linalg::{LinalgError, c64};
use crate::model::damping::DampingModel;
use crate::system::{Dof, Layout, RotorSystem};
use rayon::prelude::*;

/// Result of a modal analysis.
#[derive(Debug, Clone)]
pub struct ModalResult {
    pub poles: PoleSet,
    /// On supports over whirl frequency: each rotor pole's residual at the frequency it reads
    /// them at ([`super::consistent`]), in the order of `poles.rotor`.
    pub consistency: Option<Consistency>,
    /// Undamped nonrotating natural frequencies, rad/s, ascending.
    pub natural_frequencies: Vec<f64>,
    /// Size of the first-order eigenproblem.
    pub states: usize,
    /// What each entry of a pole's shape is.
    pub dofs: Vec<Dof>,
}

pub fn modal(
    system: &RotorSystem,
    model: &DampedModel,
    speed: f64,
) -> Result<ModalResult, AnalysisError> {
    Ok(ModalResult {
        poles: poles_at(model, speed)?,
        consistency: None,
        natural_frequencies: model.basis.omega.clone(),
        states: model.states(),
        dofs: system.dofs.clone(),
    })
}

/// Whether the pole `s` is in the box `|Re s|, |Im s| <= bound`.
pub fn in_box(s: c64, bound: f64) -> bool {
    s.re.abs() <= bound && s.im.abs() <= bound
}

/// [`modal`] keeping the poles in the box `|Re s|, |Im s| <= bound` and the natural
/// frequencies up to `bound` (every one for an infinite bound). `missing_poles` still counts
/// the whole model's.
pub fn modal_bounded(
    system: &RotorSystem,
    model: &DampedModel,
    speed: f64,
    bound: f64,
) -> Result<ModalResult, AnalysisError> {
    let mut r = modal(system, model, speed)?;
    r.poles.rotor.retain(|p| in_box(p.s, bound));
    r.poles.internal.retain(|p| in_box(p.s, bound));
    r.natural_frequencies.retain(|&w| w <= bound);
    Ok(r)
}

/// The poles of a rotor held sparse in the box `|Re s|, |Im s| <= bound` at `speed`, and its
/// natural frequencies up to `bound` (module docs); the equivalent and nonviscous models with
/// their dampers up to 16 times `bound` (`damping::dampers`).
pub fn modal_large(
    system: &RotorSystem,
    damping: &DampingModel,
    speed: f64,
    bound: f64,
) -> Result<ModalResult, AnalysisError> {
    let dampers = large::dampers(system, damping, bound)?;
    let poles = large_poles(system, damping, dampers.as_ref(), speed, bound)?;
    let basis = large::lowest(system, 1, |_| bound)?;
    Ok(ModalResult {
        poles,
        consistency: None,
        natural_frequencies: basis.omega.into_iter().filter(|&w| w <= bound).collect(),
        states: 2 * large::full_size(system),
        dofs: system.dofs.clone(),
    })
}

/// [`modal_large`]'s poles alone, under `dampers` found once for the systems that share them
/// (API 617's cross-coupling changes no damper: Level II's configurations).
pub fn large_poles(
    system: &RotorSystem,
    damping: &DampingModel,
    dampers: Option<&ModalDampers>,
    speed: f64,
    bound: f64,
) -> Result<PoleSet, AnalysisError> {
    let radius = std::f64::consts::SQRT_2 * bound;
    let pairs =
        large::full_modes(system, damping, dampers, speed, radius).map_err(|e| match e {
            AnalysisError::Linalg(LinalgError::NoConvergence) => {
                AnalysisError::Damping(DampingError::Unsolvable(format!(
                    "the poles within {radius:.6e} rad/s of the origin did not converge in the \
                 Arnoldi space a rotor held sparse is solved in (about 100 poles): lower \
                 `max_frequency`"
                )))
            }
            e => e,
        })?;
    // Each closed by shift-invert at itself: Arnoldi about one shift places a non-normal
    // model's poles far from it to about 1e-8 only (the doubled model's on cross-coupled
    // bearings, `tests/it/modal_large.rs`), a factor at the pole to round-off.
    let full = Full::Sparse {
        system,
        damping,
        dampers,
    };
    let pairs: Vec<(c64, Vec<c64>)> = pairs
        .into_par_iter()
        .map(|(s, x)| Ok((nearest_pole(full, speed, s)?.unwrap_or(s), x)))
        .collect::<Result<Vec<_>, AnalysisError>>()?
        .into_iter()
        .filter(|(s, _)| in_box(*s, bound))
        .collect();
    Ok(rotor_set(speed, pairs, system.layout() == Layout::Doubled))
}

/// How the poles of a rotor on supports over whirl frequency were made consistent.
#[derive(Debug, Clone, PartialEq)]
pub struct Consistency {
    /// Per rotor pole, its residual ([`super::consistent`]).
    pub residuals: Vec<f64>,
    /// Poles of the synchronous reading with no consistent pole near them (none found, or the
    /// steps did not settle): not reported.
    pub lost: usize,
    /// Poles of the synchronous reading that continued to a pole already found.
    pub merged: usize,
    /// Eigensolves, in all.
    pub solves: usize,
}

/// The poles of a rotor on supports over whirl frequency at `speed` (in the box of `bound`),
/// each consistent with the frequency it reads them at, continued from those of the rotor read
/// synchronously (frequency = `speed`; dense, or held sparse where `sparse`). The natural
/// frequencies are the synchronous reading's at rest.
pub fn modal_consistent(
    system: &RotorSystem,
    damping: &DampingModel,
    speed: f64,
    bound: f64,
    sparse: bool,
) -> Result<ModalResult, AnalysisError> {
    let synchronous = system.read(speed, speed);
    let start = match sparse {
        true => modal_large(&synchronous, damping, speed, bound)?,
        false => {
            let model = DampedModel::build(&synchronous, damping)?;
            modal_bounded(&synchronous, &model, speed, bound)?
        }
    };
    let found: Vec<Option<super::consistent::Consistent>> = start
        .poles
        .rotor
        .par_iter()
        .map(|p| super::consistent::consistent(system, damping, speed, p.s))
        .collect::<Result<_, _>>()?;
    let doubled = system.layout() == Layout::Doubled;
    let same = |k: &super::consistent::Consistent, c: &super::consistent::Consistent| {
        (k.s - c.s).norm() <= 1e-8 * c.s.norm()
            || (doubled && (k.s - c.s.conj()).norm() <= 1e-8 * c.s.norm())
    };
    let (mut kept, mut lost, mut merged, mut solves) = (vec![], 0, 0, 0);
    let mut missed = vec![];
    for c in found {
        let Some(c) = c else {
            lost += 1;
            continue;
        };
        solves += c.solves;
        if kept.iter().any(|k| same(k, &c)) {
            merged += 1;
            missed.push(c.s);
            continue;
        }
        kept.push(c);
    }
    // Each continuation that ended on a pole already found missed one: continued from the
    // eigenvalues beside that pole (`consistent::neighbours`) until one ends on a new pole.
    for around in missed {
        let near = super::consistent::neighbours(system, damping, speed, around)?;
        for t in near {
            let known = |k: &super::consistent::Consistent| {
                let d = (k.s - t).norm();
                let d = if doubled {
                    d.min((k.s.conj() - t).norm())
                } else {
                    d
                };
                d <= 1e-6 * t.norm()
            };
            if kept.iter().any(known) {
                continue;
            }
            let Some(c) = super::consistent::consistent(system, damping, speed, t)? else {
                continue;
            };
            solves += c.solves;
            if !kept.iter().any(|k| same(k, &c)) {
                kept.push(c);
                merged -= 1;
                break;
            }
        }
    }
    kept.retain(|c| in_box(c.s, bound));
    // Doubled: each pole with its mirror, as the full model has them, for the set to choose.
    let mut pairs = vec![];
    for c in &kept {
        pairs.push((c.s, c.shape.clone()));
        if doubled {
            pairs.push((c.s.conj(), super::poles::mirror_shape(&c.shape)));
        }
    }
    let poles = rotor_set(speed, pairs, doubled);
    let residuals = poles
        .rotor
        .iter()
        .map(|p| {
            // The set keeps each pole's value (or its mirror's): the nearest is it.
            let d = |c: &&super::consistent::Consistent| {
                (c.s - p.s).norm().min((c.s.conj() - p.s).norm())
            };
            kept.iter()
                .min_by(|a, b| d(a).total_cmp(&d(b)))
                .map_or(0.0, |c| c.residual)
        })
        .collect();
    Ok(ModalResult {
        poles,
        consistency: Some(Consistency {
            residuals,
            lost,
            merged,
            solves,
        }),
        natural_frequencies: start.natural_frequencies,
        states: start.states,
        dofs: system.dofs.clone(),
    })
}
