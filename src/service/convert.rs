//! Domain results to wire types.

use crate::analysis::campbell::CampbellResult;
use crate::analysis::modal::ModalResult;
use crate::analysis::poles::{self, PoleSet};
use crate::analysis::stability::Threshold;
use crate::model::api;

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
    }
}

fn pole_list(set: &PoleSet) -> Vec<api::Pole> {
    set.all().map(pole).collect()
}

pub fn modal(r: &ModalResult) -> api::ModalResponse {
    api::ModalResponse {
        speed: r.poles.speed,
        poles: pole_list(&r.poles),
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
