//! Time responses: on a checked reduction where one passes, else on the full dense model; a
//! rotor held sparse only on a reduction.

use super::models::damping_error;
use super::{Analysis, Outcome, RunError};
use crate::analysis::control::Control;
use crate::analysis::time;
use crate::damping::DampedModel;
use crate::model::Invalid;
use crate::model::rotor::Rotor;
use crate::model::task::TimeTask;

/// Why a large rotor's time response failed: it is integrated on a checked reduction only.
const NOT_REDUCED: &str = "no modal reduction of this rotor passed the check against its full \
    model (every pole in the band within 1e-3 of its decay rate), and a rotor this large is not \
    integrated on its full model: use fewer elements";

impl Analysis for TimeTask {
    fn run(&self, control: &Control) -> Result<Outcome, RunError> {
        let TimeTask {
            model,
            spec,
            sparse,
        } = self;
        let (system, fits) = super::time_fit::fitted(model, spec, !*sparse, control)?;
        // A train on its modes apart from its rigid motion (dense: a train held sparse is
        // integrated on a checked reduction, without the machines' torques).
        let dense = !*sparse && !system.frequency_dependent();
        if let (Rotor::Train(t), true) = (&model.rotor, dense) {
            let r = super::time_train::solve(&system, t, model, spec, control)?;
            return Ok(Outcome::Time(r, None, fits));
        }
        if !spec.generated.is_empty() {
            let field = match spec.generated.motor {
                Some(_) => "motor_start",
                None => "short_circuit",
            };
            return Err(RunError::Invalid(Invalid::one(
                field,
                "a machine's torques are applied to a train solved on all its modes: this one \
                 is too large (or has supports over whirl frequency); use fewer elements",
            )));
        }
        let reduced = time::reduced::solve_sparse(
            &system,
            &model.damping,
            spec,
            spec.reduce,
            *sparse,
            control,
        )?;
        if let Some((r, reduction)) = reduced {
            return Ok(Outcome::Time(r, Some(reduction), fits));
        }
        if *sparse {
            if let Some(f) = fits.fits.first() {
                return Err(RunError::Invalid(Invalid::one(
                    format!("{}.frequencies", f.path),
                    "a rotor held sparse has no internal coordinates for the branches a \
                     support over whirl frequency is fitted with, and is not integrated \
                     on its full model: use fewer elements",
                )));
            }
            return Err(RunError::Unsolvable(NOT_REDUCED.into()));
        }
        let damped = DampedModel::build(&system, &model.damping)
            .map_err(|e| damping_error(e, &model.rotor))?;
        let (r, reduction) =
            time::reduced::solve(&system, &model.damping, &damped, spec, spec.reduce, control)?;
        Ok(Outcome::Time(r, reduction, fits))
    }
}
