//! The damping model's matrices (and the fits of supports over whirl frequency) for a user's own
//! integrator.

use super::models::{damping_error, fitted};
use super::{Analysis, Outcome, RunError};
use crate::analysis::control::Control;
use crate::damping::report::{self, ReportError};
use crate::model::Invalid;
use crate::model::task::DampingTask;

impl Analysis for DampingTask {
    fn run(&self, control: &Control) -> Result<Outcome, RunError> {
        let DampingTask {
            model,
            state_form,
            band,
            max_deviation,
            max_states,
            speed,
        } = self;
        let (system, fits) = fitted(model, &[*speed], control)?;
        let options = report::Options {
            state_form: *state_form,
            band: *band,
            max_deviation: *max_deviation,
            max_states: *max_states,
            speed: *speed,
        };
        let r = report::matrices(&system, &model.damping, &options).map_err(|e| match e {
            ReportError::Damping(e) => damping_error(e, &model.rotor),
            e @ ReportError::Unreachable { .. } => {
                RunError::Invalid(Invalid::one("fit.max_deviation", e.to_string()))
            }
            e @ ReportError::NonFinite => RunError::Unsolvable(e.to_string()),
            e @ ReportError::TooLarge { .. } => {
                RunError::Invalid(Invalid::one("damping", e.to_string()))
            }
        })?;
        Ok(Outcome::Damping {
            matrices: Box::new(r),
            model: model.damping.name(),
            fits,
        })
    }
}
