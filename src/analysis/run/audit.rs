//! The audit's single analyses: the undamped critical speed map, the static deflection, and
//! API 617's Level I screen (with Level II when the machine's data are given).

use super::models::{assemble, rigid_body};
use super::{Analysis, Outcome, RunError};
use crate::analysis::AnalysisError;
use crate::analysis::audit::critical_map;
use crate::analysis::audit::level1_reduced;
use crate::analysis::audit::level2;
use crate::analysis::audit::statics::{self, Held};
use crate::analysis::control::Control;
use crate::analysis::time;
use crate::model::task::{CriticalMapTask, Level1Task, StaticTask};
use crate::model::{Invalid, rotor::Rotor};

impl Analysis for CriticalMapTask {
    fn run(&self, control: &Control) -> Result<Outcome, RunError> {
        let CriticalMapTask {
            rotor,
            stiffness,
            modes,
        } = self;
        Ok(Outcome::CriticalMap {
            map: critical_map::critical_speed_map(rotor, stiffness, *modes, control)?,
            stiffness: stiffness.clone(),
        })
    }
}

impl Analysis for StaticTask {
    fn run(&self, _control: &Control) -> Result<Outcome, RunError> {
        let StaticTask {
            rotor,
            gravity,
            rigid,
            speed,
        } = self;
        let held = if *rigid {
            Held::Rigid
        } else {
            Held::Elastic { speed: *speed }
        };
        let result = statics::static_deflection(rotor, *gravity, held).map_err(|e| match e {
            AnalysisError::Linalg(_) => RunError::Invalid(Invalid::one(
                "rotor.supports",
                "the supports do not hold the shaft (its stiffness matrix is singular)",
            )),
            e => e.into(),
        })?;
        Ok(Outcome::Static {
            result,
            gravity: *gravity,
            rigid: *rigid,
        })
    }
}

impl Analysis for Level1Task {
    fn run(&self, control: &Control) -> Result<Outcome, RunError> {
        let Level1Task {
            model,
            speed,
            at,
            qs,
            qa,
            density,
            extra,
            reduce,
            sparse,
        } = self;
        let system = assemble(model)?;
        let placing: Vec<(usize, f64)> = at
            .iter()
            .map(|&(n, w)| (time::translation(&system, n), w))
            .collect();
        let screened = level1_reduced::level1_reduced(
            &system,
            &model.damping,
            *speed,
            &placing,
            qs,
            21,
            *qa,
            *reduce,
            *sparse,
            control,
        )
        .map_err(|e| rigid_body(e, &model.rotor))?;
        let (qs, result, qa) = (screened.qs, screened.result, screened.qa);
        let reduction = screened.reduction;
        let rigid = match &model.rotor {
            Rotor::Beam(b) => Some(critical_map::rigid_first(b)?),
            _ => None,
        };
        let level2 = match qa {
            Some((q, _)) => {
                control.check().map_err(|_| RunError::Cancelled)?;
                let more: Vec<(usize, f64)> = extra
                    .iter()
                    .map(|&(n, q)| (time::translation(&system, n), q))
                    .collect();
                Some(level2::level2(
                    &system,
                    &model.damping,
                    *speed,
                    &placing,
                    q,
                    &more,
                    *sparse,
                )?)
            }
            None => None,
        };
        Ok(Outcome::Level1 {
            speed: *speed,
            at: at.clone(),
            qs,
            result,
            qa,
            rigid,
            density: *density,
            level2,
            model: model.damping.name(),
            reduction,
        })
    }
}
