//! Harmonic responses: the steady unbalance response over speeds (with its refined peaks) and
//! the non-synchronous frequency response at one speed.

use super::models::{assemble, harmonic_model};
use super::{Analysis, Outcome, RunError};
use crate::analysis::AnalysisError;
use crate::analysis::audit::peaks;
use crate::analysis::control::Control;
use crate::analysis::response;
use crate::analysis::shaft_loads;
use crate::analysis::time;
use crate::analysis::unbalance::SteadyUnbalance;
use crate::linalg::c64;
use crate::model::rotor::Rotor;
use crate::model::task::{FrequencyTask, UnbalanceTask};
use rayon::prelude::*;

impl Analysis for UnbalanceTask {
    fn run(&self, control: &Control) -> Result<Outcome, RunError> {
        let UnbalanceTask {
            model,
            speeds,
            unbalances,
            nodes,
            range,
            reduce,
            sparse,
        } = self;
        let system = assemble(model)?;
        let top = speeds
            .as_slice()
            .iter()
            .fold(0.0, |a: f64, w| a.max(w.abs()));
        let owned = harmonic_model(*sparse, &system, model, top)?;
        let full = owned.full();
        let dof = |n: usize| time::translation(&system, n);
        let loads: Vec<SteadyUnbalance> = unbalances
            .iter()
            .map(|&(n, amount, phase)| SteadyUnbalance {
                dof: dof(n),
                amount,
                phase,
            })
            .collect();
        let dofs: Vec<usize> = nodes.iter().map(|&n| dof(n)).collect();
        let grid = speeds.as_slice();
        let (response, solved) = response::unbalance_sweep(
            &system,
            &model.damping,
            full,
            grid,
            &loads,
            &dofs,
            *reduce,
            control,
        )?;
        // Refinement costs at most about two sweeps more; further peaks are interpolated.
        let mut budget = 2 * grid.len() + 2 * peaks::SOLVES_PER_PEAK;
        let n = system.n();
        let peaks = dofs
            .iter()
            .enumerate()
            .map(|(k, &d)| {
                let amp: Vec<f64> = response.iter().map(|o| o[k].major()).collect();
                let mut eval = |w: f64| -> Result<f64, AnalysisError> {
                    control.check()?;
                    let force = response::unbalance_force(&loads, n, w);
                    Ok(solved.orbits(w, w, &force, &[d])?[0].major())
                };
                peaks::peaks(grid, &amp, &mut eval, &mut budget)
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Outcome::Unbalance {
            speeds: grid.to_vec(),
            nodes: nodes.clone(),
            response,
            peaks,
            range: *range,
            model: model.damping.name(),
            reduction: solved.reduction().cloned(),
            sparse: *sparse || system.frequency_dependent(),
        })
    }
}

impl Analysis for FrequencyTask {
    fn run(&self, control: &Control) -> Result<Outcome, RunError> {
        let FrequencyTask {
            model,
            speed,
            input,
            output,
            frequencies,
            reduce,
            sparse,
        } = self;
        let system = assemble(model)?;
        let top = frequencies
            .iter()
            .fold(speed.abs(), |a: f64, w| a.max(w.abs()));
        let owned = harmonic_model(*sparse, &system, model, top)?;
        let full = owned.full();
        let dof = |n: usize| time::translation(&system, n);
        let force = input.1.at(dof(input.0), system.n());
        // A train's element loads need every node: its full model, which is small.
        let train = match &model.rotor {
            Rotor::Train(t) => Some(t),
            _ => None,
        };
        let (response, solved) = response::frequency_sweep(
            &system,
            &model.damping,
            full,
            *speed,
            &force,
            dof(*output),
            frequencies,
            *reduce && train.is_none(),
            control,
        )?;
        let elements = match train {
            Some(t) => {
                let at = solved.at(*speed);
                let every: Vec<usize> = (0..system.n()).collect();
                let x = frequencies
                    .par_iter()
                    .map(|&w| {
                        let o = at.orbits(w, &force, &every)?;
                        Ok(o.iter().map(|o| o.xy()[0]).collect())
                    })
                    .collect::<Result<Vec<Vec<c64>>, AnalysisError>>()?;
                shaft_loads::responses(t, &x)
            }
            None => vec![],
        };
        Ok(Outcome::Frequency {
            speed: *speed,
            input: *input,
            output: *output,
            frequencies: frequencies.clone(),
            response,
            model: model.damping.name(),
            reduction: solved.reduction().cloned(),
            sparse: *sparse || system.frequency_dependent(),
            elements,
        })
    }
}
