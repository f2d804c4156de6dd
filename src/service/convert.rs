//! Domain results to wire types.

use crate::analysis::campbell::CampbellResult;
use crate::analysis::modal::ModalResult;
use crate::analysis::poles;
use crate::analysis::stability::Threshold;
use crate::linalg::c64;
use crate::model::api;
use crate::system::{Dof, DofKind};

pub fn whirl(w: poles::Whirl) -> api::Whirl {
    match w {
        poles::Whirl::Forward => api::Whirl::Forward,
        poles::Whirl::Backward => api::Whirl::Backward,
        poles::Whirl::Internal => api::Whirl::Internal,
    }
}

pub fn pole(p: &poles::Pole) -> api::Pole {
    api::Pole {
        decay_rate: p.decay_rate(),
        frequency: p.frequency(),
        whirl: whirl(p.whirl),
        damping_ratio: p.damping_ratio(),
        log_decrement: p.log_decrement(),
        shape: None,
    }
}

/// The translations of a mode shape, the largest scaled to 1 (real).
fn translations(p: &poles::Pole, dofs: &[Dof]) -> Vec<api::NodeDisplacement> {
    let t: Vec<(usize, c64)> = dofs
        .iter()
        .zip(&p.shape)
        .filter(|(d, _)| d.kind == DofKind::Translation)
        .map(|(d, x)| (d.node, *x))
        .collect();
    let big = t
        .iter()
        .map(|(_, x)| *x)
        .max_by(|a, b| a.norm().total_cmp(&b.norm()))
        .unwrap_or(c64::new(1.0, 0.0));
    let scale = if big.norm() > 0.0 {
        1.0 / big
    } else {
        c64::new(1.0, 0.0)
    };
    t.into_iter()
        .map(|(node, x)| {
            let v = x * scale;
            api::NodeDisplacement {
                node,
                re: v.re,
                im: v.im,
            }
        })
        .collect()
}

pub fn modal(r: &ModalResult) -> api::ModalResponse {
    let mut poles: Vec<api::Pole> = r
        .poles
        .rotor
        .iter()
        .map(|p| {
            let mut out = pole(p);
            out.shape = Some(translations(p, &r.dofs));
            out
        })
        .collect();
    poles.extend(r.poles.internal.iter().map(pole));
    api::ModalResponse {
        speed: r.poles.speed,
        poles,
        natural_frequencies: r.natural_frequencies.clone(),
        states: r.states,
        missing_poles: r.poles.missing(),
    }
}

pub fn campbell(r: &CampbellResult) -> api::CampbellResponse {
    api::CampbellResponse {
        speeds: r.speeds.clone(),
        branches: r
            .branches
            .iter()
            .map(|b| api::Branch {
                mode: b.mode,
                whirl: whirl(b.whirl),
                frequency: b.poles.iter().map(|p| p.map(|s| s.im)).collect(),
                decay_rate: b.poles.iter().map(|p| p.map(|s| s.re)).collect(),
            })
            .collect(),
        critical_speeds: r.critical_speeds.clone(),
        threshold: r.threshold.as_ref().map(|t| t.speed),
    }
}

pub fn stability(t: Option<&Threshold>, range: [f64; 2]) -> api::StabilityResponse {
    api::StabilityResponse {
        threshold: t.map(|t| t.speed),
        mode: t.map(|t| t.mode),
        whirl: t.map(|t| whirl(t.pole.whirl)),
        frequency: t.map(|t| t.pole.frequency()),
        range,
    }
}
