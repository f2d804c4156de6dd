//! Poles at one spin speed, and the undamped nonrotating natural frequencies.

use super::AnalysisError;
use super::poles::{PoleSet, poles_at};
use crate::damping::DampedModel;
use crate::system::{Dof, RotorSystem};

/// Result of a modal analysis.
#[derive(Debug, Clone)]
pub struct ModalResult {
    pub poles: PoleSet,
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
        natural_frequencies: model.basis.omega.clone(),
        states: model.states(),
        dofs: system.dofs.clone(),
    })
}
