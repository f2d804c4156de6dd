//! Poles at one spin speed, and the undamped nonrotating natural frequencies.

use super::AnalysisError;
use super::poles::{PoleSet, poles_at};
use crate::damping::DampedModel;
use crate::linalg;
use crate::system::RotorSystem;

/// Result of a modal analysis.
#[derive(Debug, Clone)]
pub struct ModalResult {
    pub poles: PoleSet,
    /// Undamped nonrotating natural frequencies, rad/s, ascending.
    pub natural_frequencies: Vec<f64>,
    /// Size of the first-order eigenproblem.
    pub states: usize,
}

pub fn modal(
    system: &RotorSystem,
    model: &DampedModel,
    speed: f64,
) -> Result<ModalResult, AnalysisError> {
    Ok(ModalResult {
        poles: poles_at(model, speed)?,
        natural_frequencies: natural_frequencies(system)?,
        states: model.states(),
    })
}

/// `sqrt` of the eigenvalues of `(K, M)`; a rigid-body mode gives 0.
pub fn natural_frequencies(system: &RotorSystem) -> Result<Vec<f64>, AnalysisError> {
    let modes = linalg::symmetric_modes(&system.stiffness(), &system.mass)?;
    Ok(modes
        .omega_squared
        .iter()
        .map(|w2| w2.max(0.0).sqrt())
        .collect())
}
