//! The Campbell sweep: branches tracked over speeds, dense (on a checked reduction where it
//! pays), held sparse, or consistent with their own frequency; the poles a reduction's check did
//! not cover refined on the full model.

use super::models::{assemble, damping_error, rigid_body};
use super::{Analysis, Outcome, RunError};
use crate::analysis::AnalysisError;
use crate::analysis::campbell;
use crate::analysis::campbell_whirl;
use crate::analysis::control::Control;
use crate::analysis::interference;
use crate::analysis::refine;
use crate::damping::DampedModel;
use crate::model::task::CampbellTask;

impl Analysis for CampbellTask {
    fn run(&self, control: &Control) -> Result<Outcome, RunError> {
        let CampbellTask {
            model,
            speeds,
            max_frequency,
            modes,
            reduce,
            sparse,
            max_states,
            interference,
        } = self;
        if let Some(spec) = interference {
            return train(self, spec, control);
        }
        let speeds = speeds.as_slice();
        let system = assemble(model)?;
        if system.frequency_dependent() {
            let keep = campbell::Keep {
                below: *max_frequency,
                lowest: *modes,
            };
            return campbell_whirl::campbell_consistent(
                &system,
                &model.damping,
                speeds,
                keep,
                *sparse,
                control,
            )
            .map(Outcome::Campbell)
            .map_err(|e| rigid_body(e, &model.rotor));
        }
        if *sparse {
            let keep = campbell::Keep {
                below: *max_frequency,
                lowest: None,
            };
            let dampers = crate::analysis::large::dampers(&system, &model.damping, *max_frequency)?;
            let dampers = dampers.as_ref();
            let r = campbell::campbell_large(
                &system,
                &model.damping,
                dampers,
                speeds,
                keep,
                *max_states,
                control,
            );
            return match r.and_then(|mut r| {
                let full = refine::Full::Sparse {
                    system: &system,
                    damping: &model.damping,
                    dampers,
                };
                refine::outside_box(&mut r, full, *max_frequency)?;
                Ok(r)
            }) {
                Ok(r) => Ok(Outcome::Campbell(r)),
                Err(AnalysisError::Damping(e)) => Err(damping_error(e, &model.rotor)),
                Err(e) => Err(e.into()),
            };
        }
        let damped = DampedModel::build(&system, &model.damping)
            .map_err(|e| damping_error(e, &model.rotor))?;
        let bound = match modes {
            Some(n) => campbell::lowest_bound(&damped, speeds[0], *n)?.min(*max_frequency),
            None => *max_frequency,
        };
        let keep = campbell::Keep {
            below: bound,
            lowest: *modes,
        };
        let mut r = campbell::campbell_below(
            &system,
            &model.damping,
            &damped,
            speeds,
            keep,
            *reduce,
            control,
        )?;
        // The poles the reduction's check did not cover, on the full model.
        let full = refine::Full::of(&system, &model.damping, &damped);
        refine::outside_box(&mut r, full, bound)?;
        Ok(Outcome::Campbell(r))
    }
}

/// A train's torsional or axial sweep: one branch per mode, and the interference diagram
/// refined on the model (interpolated on supports over whirl frequency).
fn train(
    task: &CampbellTask,
    spec: &interference::Spec,
    control: &Control,
) -> Result<Outcome, RunError> {
    let model = &task.model;
    let speeds = task.speeds.as_slice();
    let system = assemble(model)?;
    // Each mode is a conjugate pair, and a free train's rigid motion one more.
    let keep = campbell::Keep {
        below: task.max_frequency,
        lowest: task.modes.map(|m| 2 * m + 2),
    };
    let (mut r, damped) = if system.frequency_dependent() {
        let r = campbell_whirl::campbell_consistent(
            &system,
            &model.damping,
            speeds,
            keep,
            false,
            control,
        )
        .map_err(|e| rigid_body(e, &model.rotor))?;
        (r, None)
    } else {
        let damped = DampedModel::build(&system, &model.damping)
            .map_err(|e| damping_error(e, &model.rotor))?;
        let r = campbell::campbell_below(
            &system,
            &model.damping,
            &damped,
            speeds,
            keep,
            false,
            control,
        )?;
        (r, Some(damped))
    };
    let scale = crate::fem::modal::frequency_scale(&system);
    interference::real_modes(&mut r, scale, task.modes);
    r.interference = Some(interference::interference(
        &r,
        damped.as_ref(),
        spec,
        control,
    )?);
    Ok(Outcome::Campbell(r))
}
