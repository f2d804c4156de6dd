//! Harmonic responses: the steady unbalance response over speeds (with its refined peaks) and
//! the non-synchronous frequency response at one speed.

use super::models::{assemble, harmonic_model};
use super::{Analysis, Outcome, RunError};
use crate::analysis::AnalysisError;
use crate::analysis::audit::frequency::Orbit;
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
        // A train's element loads need every node: its full model (small), each frequency
        // solved once for all of them, the output among them.
        let (response, reduction, elements) = match &model.rotor {
            Rotor::Train(t) => {
                let held = response::Responses::full(&system, full);
                let at = held.at(*speed);
                let every: Vec<usize> = (0..system.n()).collect();
                control.expect(frequencies.len() as u64);
                let orbits = frequencies
                    .par_iter()
                    .map(|&w| {
                        control.check()?;
                        let o = at.orbits(w, &force, &every)?;
                        control.advance(1);
                        Ok(o)
                    })
                    .collect::<Result<Vec<Vec<Orbit>>, AnalysisError>>()?;
                let x: Vec<Vec<c64>> = (orbits.iter())
                    .map(|o| o.iter().map(|o| o.xy()[0]).collect())
                    .collect();
                let response = orbits.iter().map(|o| o[dof(*output)]).collect();
                (response, None, shaft_loads::responses(t, &x))
            }
            _ => {
                let (response, solved) = response::frequency_sweep(
                    &system,
                    &model.damping,
                    full,
                    *speed,
                    &force,
                    dof(*output),
                    frequencies,
                    *reduce,
                    control,
                )?;
                (response, solved.reduction().cloned(), vec![])
            }
        };
        Ok(Outcome::Frequency {
            speed: *speed,
            input: *input,
            output: *output,
            frequencies: frequencies.clone(),
            response,
            model: model.damping.name(),
            reduction,
            sparse: *sparse || system.frequency_dependent(),
            elements,
        })
    }
}
