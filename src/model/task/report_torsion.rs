//! The report's torsional section planned as tasks: the torsional interference diagram over the
//! report's speeds and, with a motor's start-up or a generator's short circuit, its transient.

use super::Task;
use crate::model::api::{
    DampingInput, InterferenceInput, Motion, NonviscousInput, ReportRequest, SpeedsInput,
    SweepRequest, TimeResponseRequest, TorsionInput,
};
use crate::model::error::Invalid;
use crate::model::limits::Limits;

/// The torsional section's tasks.
#[derive(Debug, Clone)]
pub struct TorsionPlan {
    /// `/v1/campbell` with `motion: torsional` and its interference diagram.
    pub campbell: Task,
    /// `/v1/time-response` of the transient.
    pub transient: Option<Task>,
}

impl TorsionPlan {
    pub fn tasks(&self) -> Vec<&Task> {
        let mut all = vec![&self.campbell];
        all.extend(&self.transient);
        all
    }
}

/// Errors of a part under `torsion`, its own paths kept (`rotor...` stays `rotor...`).
fn under_torsion(mut e: Invalid) -> Invalid {
    e.prefix_paths(|p| {
        if p.starts_with("rotor") {
            p.to_string()
        } else {
            format!("torsion.{p}")
        }
    });
    e
}

impl ReportRequest {
    /// The torsional section's plan, when asked for: over `speeds` (rad/s unless their unit
    /// says), margins from the operating range `(lo, hi)` rad/s.
    pub(super) fn torsion_plan(
        &self,
        t: &TorsionInput,
        speeds: &SpeedsInput,
        (lo, hi): (f64, f64),
        limits: &Limits,
    ) -> Result<TorsionPlan, Invalid> {
        // The operating range in the sweep's unit.
        let unit = speeds.unit();
        let range = [unit.from_rad_s(lo), unit.from_rad_s(hi)];
        let campbell = SweepRequest {
            rotor: self.rotor.clone(),
            damping: self.damping.clone(),
            speeds: speeds.clone(),
            max_frequency: None,
            modes: None,
            modal_reduction: None,
            output_unit: None,
            motion: Motion::Torsional,
            interference: Some(InterferenceInput {
                orders: t.orders.clone(),
                line_frequency: t.line_frequency,
                operating_range: Some(range),
            }),
        }
        .parse_campbell(limits)
        .map_err(under_torsion)?;
        let transient = if t.motor_start.is_some() || t.short_circuit.is_some() {
            let Some(duration) = t.duration else {
                return Err(Invalid::one(
                    "torsion.duration",
                    "the transient's length, s, is needed with a motor start or short circuit",
                ));
            };
            let damping = t.damping.clone().unwrap_or(match &self.damping {
                DampingInput::Hysteretic(_) => DampingInput::Nonviscous(NonviscousInput::default()),
                d => d.clone(),
            });
            let request = TimeResponseRequest {
                rotor: self.rotor.clone(),
                damping,
                speed: None,
                speed_profile: None,
                forces: vec![],
                unbalances: vec![],
                duration,
                output_interval: t.output_interval.unwrap_or(duration / 2000.0),
                nodes: Some(vec![0]),
                tolerance: None,
                modal_reduction: None,
                motion: Motion::Torsional,
                motor_start: t.motor_start.clone(),
                short_circuit: t.short_circuit.clone(),
            };
            Some(request.parse(limits).map_err(under_torsion)?)
        } else {
            None
        };
        Ok(TorsionPlan {
            campbell,
            transient,
        })
    }
}
