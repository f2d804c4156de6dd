//! Which analyses read a support over whirl frequency, and under which damping models.

use super::{CriticalMapTask, DampingTask, StaticTask, TimeTask};
use super::{Task, TaskKind};
use crate::model::damping::DampingModel;
use crate::model::error::Invalid;

impl Task {
    /// Supports over whirl frequency are read by every analysis: the modal analysis, Campbell
    /// diagram, stability threshold and Level I and II with poles consistent with their own
    /// frequency; the harmonic responses at the excitation frequency; the static deflection at
    /// 0; the critical speed map synchronously (each under the viscous and hysteretic models:
    /// the others are refused naming the first one's `frequencies`); the time response and the
    /// damping matrices through their fit.
    pub(crate) fn whirl_read(&self) -> Result<(), Invalid> {
        let supports: &[crate::model::supports::GeneralSupport] = match &self.kind {
            TaskKind::CriticalMap(CriticalMapTask { rotor, .. }) => rotor.general_supports(),
            TaskKind::Static(StaticTask { .. }) | TaskKind::Report(_) => return Ok(()),
            _ => self.model().map_or(&[], |m| m.rotor.general_supports()),
        };
        let Some(first) = supports.iter().find(|s| s.frequency_dependent()) else {
            return Ok(());
        };
        // The time domain and the damping matrices carry it by its Maxwell fit
        // (`damping/whirl_fit.rs`), under every model that has a time-domain form.
        if matches!(
            self.kind,
            TaskKind::Time(TimeTask { .. }) | TaskKind::Damping(DampingTask { .. })
        ) {
            return match supports.iter().find(|s| s.ross()) {
                Some(r) => Err(Invalid::one(
                    format!("{}.interpolation", r.path()),
                    "a table on ROSS's curves is scheduled on one model, which a support over \
                     whirl frequency cannot join in the time domain: use \"linear\"",
                )),
                None => Ok(()),
            };
        }
        // Every other analysis reads it (modal, Campbell, stability, Level I and II, the
        // harmonic responses, the critical speed map), under the models below.
        let path = format!("{}.frequencies", first.path());
        match self.model().map(|m| &m.damping) {
            Some(DampingModel::Viscous | DampingModel::Hysteretic) | None => Ok(()),
            Some(d) => Err(Invalid::one(
                path,
                format!(
                    "a support whose coefficients depend on the whirl frequency is read by the \
                     viscous and hysteretic models so far, not by the {} model",
                    d.name()
                ),
            )),
        }
    }
}

impl super::Model {
    /// Floating point work of fitting its supports over whirl frequency for the time domain
    /// (`damping/whirl_fit.rs`): at each speed of its tables, least squares over four samples
    /// per frequency with up to 18 columns, for each of 4 coefficients and each of up to 16
    /// branch counts, about 10 active-set passes each.
    pub(crate) fn fit_work(&self) -> f64 {
        let per_speed: f64 = self
            .rotor
            .general_supports()
            .iter()
            .filter_map(|s| s.grid())
            .map(|g| 8.0 * g.frequencies.len() as f64 * 18.0 * 18.0 * 4.0 * 16.0 * 10.0)
            .sum();
        // The speeds of every table, where the state model is realized.
        per_speed * self.size().points as f64
    }
}
