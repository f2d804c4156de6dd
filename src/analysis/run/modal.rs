//! Poles at one speed: on the dense model (bounded or not), held sparse, or consistent with
//! their own frequency on supports over whirl frequency.

use super::models::{assemble, damping_error, rigid_body};
use super::{Analysis, Outcome, RunError};
use crate::analysis::AnalysisError;
use crate::analysis::control::Control;
use crate::analysis::modal;
use crate::damping::DampedModel;
use crate::model::task::ModalTask;

impl Analysis for ModalTask {
    fn run(&self, _control: &Control) -> Result<Outcome, RunError> {
        let ModalTask {
            model,
            speed,
            max_frequency,
            sparse,
        } = self;
        let system = assemble(model)?;
        if system.frequency_dependent() {
            return modal::modal_consistent(
                &system,
                &model.damping,
                *speed,
                *max_frequency,
                *sparse,
            )
            .map(Outcome::Modal)
            .map_err(|e| rigid_body(e, &model.rotor));
        }
        if *sparse {
            return modal::modal_large(&system, &model.damping, *speed, *max_frequency)
                .map(Outcome::Modal)
                .map_err(|e| match e {
                    AnalysisError::Damping(e) => damping_error(e, &model.rotor),
                    e => e.into(),
                });
        }
        let damped = DampedModel::build(&system, &model.damping)
            .map_err(|e| damping_error(e, &model.rotor))?;
        let r = modal::modal_bounded(&system, &damped, *speed, *max_frequency)?;
        Ok(Outcome::Modal(r))
    }
}
