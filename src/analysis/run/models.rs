//! The rotor assembled and its damping model built for a task, with the errors of both as a
//! task reports them.

use super::RunError;
use crate::analysis::AnalysisError;
use crate::analysis::control::Control;
use crate::analysis::response;
use crate::damping::whirl_fit::{self, FitOptions, SupportFit};
use crate::damping::{DampedModel, DampingError};
use crate::fem::modal::ModalError;
use crate::model::task::Model;
use crate::model::{Invalid, rotor::Rotor};
use crate::system::RotorSystem;

/// A rigid-body rotor is an invalid input (its supports, or its stiffness); anything else is a
/// model the analysis cannot solve.
pub(super) fn damping_error(e: DampingError, rotor: &Rotor) -> RunError {
    match e {
        DampingError::Modal(ModalError::RigidBody { .. }) => {
            let path = match rotor {
                Rotor::Beam(_) => "rotor.supports",
                _ => "rotor.stiffness",
            };
            RunError::Invalid(Invalid::one(path, e.to_string()))
        }
        other => RunError::Unsolvable(other.to_string()),
    }
}

pub(super) fn assemble(model: &Model) -> Result<RotorSystem, RunError> {
    RotorSystem::assemble(&model.rotor)
        .map_err(|e| RunError::Unsolvable(format!("the rotor cannot be assembled: {e}")))
}

/// The rotor assembled with its supports over whirl frequency fitted by Maxwell branches (how
/// the time domain and the damping matrices read them), held to their tables at the whirl
/// frequencies `anchors`, and how well each was fitted.
pub(super) fn fitted(
    model: &Model,
    anchors: &[f64],
    control: &Control,
) -> Result<(RotorSystem, Vec<SupportFit>), RunError> {
    let system = assemble(model)?;
    if !system.frequency_dependent() {
        return Ok((system, vec![]));
    }
    fit(&system, model, anchors, control)
}

/// [`fitted`] of an assembled `system` with supports over whirl frequency.
pub(super) fn fit(
    system: &RotorSystem,
    model: &Model,
    anchors: &[f64],
    control: &Control,
) -> Result<(RotorSystem, Vec<SupportFit>), RunError> {
    let options = FitOptions {
        anchors: anchors.to_vec(),
        ..FitOptions::default()
    };
    whirl_fit::fit(system, &options, &|| control.is_cancelled())
        .map_err(|e| damping_error(e, &model.rotor))?
        .ok_or(RunError::Cancelled)
}

/// Assembles the rotor and builds its damping model.
pub fn build(model: &Model) -> Result<(RotorSystem, DampedModel), RunError> {
    let system = assemble(model)?;
    let damped =
        DampedModel::build(&system, &model.damping).map_err(|e| damping_error(e, &model.rotor))?;
    Ok((system, damped))
}

/// A harmonic response's full model: the damping model built dense, or where the rotor is held
/// sparse (or stands on supports over whirl frequency, read at each frequency solved) the
/// pattern of its dynamic stiffness.
pub(super) fn harmonic_model(
    sparse: bool,
    system: &RotorSystem,
    model: &Model,
    bound: f64,
) -> Result<response::Owned, RunError> {
    Ok(match sparse || system.frequency_dependent() {
        true => response::Owned::Sparse(
            response::Held::new(system, &model.damping, bound).map_err(|e| match e {
                AnalysisError::Damping(e) => damping_error(e, &model.rotor),
                e => e.into(),
            })?,
        ),
        false => response::Owned::Dense(
            DampedModel::build(system, &model.damping)
                .map_err(|e| damping_error(e, &model.rotor))?,
        ),
    })
}

/// A damping model that cannot be built because the rotor floats is an invalid input.
pub(super) fn rigid_body(e: AnalysisError, rotor: &Rotor) -> RunError {
    match e {
        AnalysisError::Damping(d) => damping_error(d, rotor),
        e => e.into(),
    }
}
