//! The stability threshold: on the full dense model, on a reduction of a rotor held sparse,
//! or on the poles consistent with their own frequency (supports over whirl frequency, dense
//! or held sparse).

use super::models::{assemble, damping_error, rigid_body};
use super::{Analysis, Outcome, RunError};
use crate::analysis::control::Control;
use crate::analysis::{AnalysisError, campbell_whirl, stability, stability_large};
use crate::damping::DampedModel;
use crate::model::task::StabilityTask;

impl Analysis for StabilityTask {
    /// The threshold of `model` over `speeds`; `held`: the box and state limit of a rotor held
    /// sparse.
    fn run(&self, control: &Control) -> Result<Outcome, RunError> {
        let StabilityTask {
            model,
            speeds,
            held,
        } = self;
        let (speeds, held) = (speeds.as_slice(), *held);
        let system = assemble(model)?;
        let outcome = |(threshold, max_decay_rate), held| Outcome::Stability {
            threshold,
            speeds: speeds.to_vec(),
            max_decay_rate,
            held,
        };
        if system.frequency_dependent() {
            // The consistent poles in the box of a rotor held sparse, every pole of a dense one.
            let bound = held.map_or(f64::INFINITY, |(b, _)| b);
            let at =
                campbell_whirl::consistent_poles(&system, &model.damping, bound, held.is_some());
            let curve = stability::curve_of(&at, speeds, control)
                .map_err(|e| rigid_body(e, &model.rotor))?;
            return Ok(outcome(curve, held.map(|(b, _)| (b, None))));
        }
        if let Some((bound, max_states)) = held {
            let r = stability_large::stability_large(
                &system,
                &model.damping,
                speeds,
                bound,
                max_states,
                control,
            )
            .map_err(|e| match e {
                AnalysisError::Damping(e) => damping_error(e, &model.rotor),
                e => e.into(),
            })?;
            let curve = (r.threshold.clone(), r.max_decay_rate.clone());
            return Ok(outcome(curve, Some((bound, Some(Box::new(r))))));
        }
        let damped = DampedModel::build(&system, &model.damping)
            .map_err(|e| damping_error(e, &model.rotor))?;
        let curve = stability::stability_curve(&damped, speeds, control)?;
        Ok(outcome(curve, None))
    }
}
