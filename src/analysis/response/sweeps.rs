//! The harmonic sweeps: an unbalance response over spin speeds and a frequency response at one
//! speed, each on a reduction checked at its band's edges and again at its largest response.

use super::{Full, Probe, Responses};
use crate::analysis::AnalysisError;
use crate::analysis::audit::frequency::{Harmonic, Orbit};
use crate::analysis::control::Control;
use crate::analysis::unbalance::SteadyUnbalance;
use crate::linalg::c64;
use crate::model::damping::DampingModel;
use crate::system::RotorSystem;
use rayon::prelude::*;

/// The force of `unbalances` at spin speed `w` on a rotor of `n` coordinates.
pub fn unbalance_force(unbalances: &[SteadyUnbalance], n: usize, w: f64) -> Harmonic {
    let zero = c64::new(0.0, 0.0);
    let mut force = Harmonic {
        forward: vec![zero; n],
        backward: vec![zero; n],
    };
    for u in unbalances {
        force.forward[u.dof] += c64::from_polar(u.amount * w * w, u.phase);
    }
    force
}

/// The synchronous response to `unbalances` at `out` over `speeds`, on a checked reduction
/// (if `reduce`): at the lowest and highest nonzero speed, then at the speed of the largest
/// response. Returns the orbits per speed and the model solved (for peak refinement).
#[allow(clippy::too_many_arguments)]
pub fn unbalance_sweep<'a>(
    system: &'a RotorSystem,
    damping: &DampingModel,
    full: impl Into<Full<'a>>,
    speeds: &[f64],
    unbalances: &[SteadyUnbalance],
    out: &[usize],
    reduce: bool,
    control: &Control,
) -> Result<(Vec<Vec<Orbit>>, Responses<'a>), AnalysisError> {
    let n = system.n();
    control.expect(speeds.len() as u64);
    let at = |r: &Responses, w: f64| r.orbits(w, w, &unbalance_force(unbalances, n, w), out);
    let probe_at = |points: Vec<f64>| {
        move |r: &Responses| -> Result<Vec<Orbit>, AnalysisError> {
            let per: Vec<Vec<Orbit>> = points
                .par_iter()
                .map(|&w| at(r, w))
                .collect::<Result<_, _>>()?;
            Ok(per.concat())
        }
    };
    let mut dofs: Vec<usize> = unbalances.iter().map(|u| u.dof).collect();
    dofs.extend(out);
    let bound = speeds.iter().fold(0.0, |a: f64, b| a.max(b.abs()));
    let nonzero: Vec<f64> = speeds.iter().copied().filter(|w| *w != 0.0).collect();
    let edges = edges(&nonzero);
    let sweep = |model: &Responses| -> Result<Vec<Vec<Orbit>>, AnalysisError> {
        speeds
            .par_iter()
            .map(|&w| {
                control.check()?;
                let o = at(model, w)?;
                control.advance(1);
                Ok(o)
            })
            .collect()
    };
    let grid = Grid {
        reduce,
        bound,
        dofs: &dofs,
        forces: unbalances.len(),
        edges,
    };
    grid.swept(
        system,
        damping,
        full.into(),
        &|p| Box::new(probe_at(p)),
        sweep,
        |r| largest(speeds, r),
    )
}

/// What a harmonic sweep is checked over: the largest frequency, the loaded and observed
/// degrees of freedom (the first `forces` of `dofs` loaded), and the band's edges.
struct Grid<'d> {
    reduce: bool,
    bound: f64,
    dofs: &'d [usize],
    forces: usize,
    edges: Vec<f64>,
}

impl Grid<'_> {
    /// The sweep on a reduction checked at the band's edges (or on the full model), and, when
    /// the largest response lies elsewhere, the check repeated there and the sweep again if
    /// that widened the basis: the unbalance and frequency responses alike.
    fn swept<'a, 'p, T>(
        &self,
        system: &'a RotorSystem,
        damping: &DampingModel,
        full: Full<'a>,
        probe_at: &dyn Fn(Vec<f64>) -> Box<Probe<'p>>,
        sweep: impl Fn(&Responses<'a>) -> Result<T, AnalysisError>,
        peak: impl Fn(&T) -> Option<f64>,
    ) -> Result<(T, Responses<'a>), AnalysisError> {
        let (bound, mut dofs, edges) = (self.bound, self.dofs, &self.edges);
        let mut model = if self.reduce && !edges.is_empty() && matches!(full, Full::Dense(_)) {
            let probe = probe_at(edges.clone());
            let mut model = Responses::checked(system, damping, full, bound, dofs, edges, &*probe)?;
            // The outputs' static responses can keep every basis from halving the state
            // (outputs at every node): the outputs are then read off a basis corrected at the
            // loads and supports only (an output error of first order in the basis error, not
            // second), under the same check.
            let forces = &dofs[..self.forces.min(dofs.len())];
            if model.reduced.is_none() && forces.len() < dofs.len() {
                let fewer =
                    Responses::checked(system, damping, full, bound, forces, edges, &*probe)?;
                if fewer.reduced.is_some() {
                    (model, dofs) = (fewer, forces);
                }
            }
            model
        } else {
            Responses::full(system, full)
        };
        let mut response = sweep(&model)?;
        if let Some(at) = peak(&response)
            && model.reduced.is_some()
            && !edges.contains(&at)
        {
            let mut points = edges.clone();
            points.push(at);
            let before = model.reduction().map(|r| r.modes);
            model = model.rechecked(damping, bound, dofs, &[at], &*probe_at(points))?;
            if model.reduction().map(|r| r.modes) != before {
                response = sweep(&model)?;
            }
        }
        Ok((response, model))
    }
}

/// The first and last of `points` (once if they are one).
fn edges(points: &[f64]) -> Vec<f64> {
    let mut e: Vec<f64> = points
        .first()
        .into_iter()
        .chain(points.last())
        .copied()
        .collect();
    e.dedup();
    e
}

/// The point of the largest orbit (semi-major axis) at any output.
fn largest(points: &[f64], response: &[Vec<Orbit>]) -> Option<f64> {
    points
        .iter()
        .zip(response)
        .map(|(&w, o)| (w, o.iter().map(|o| o.major()).fold(0.0, f64::max)))
        .filter(|(_, a)| *a > 0.0)
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(w, _)| w)
}

/// The orbit at `output` per unit `force` at each of `frequencies`, the rotor spun at
/// `speed`, on a checked reduction (if `reduce`): at the lowest and highest frequency, then
/// at the largest response.
#[allow(clippy::too_many_arguments)]
pub fn frequency_sweep<'a>(
    system: &'a RotorSystem,
    damping: &DampingModel,
    full: impl Into<Full<'a>>,
    speed: f64,
    force: &Harmonic,
    output: usize,
    frequencies: &[f64],
    reduce: bool,
    control: &Control,
) -> Result<(Vec<Orbit>, Responses<'a>), AnalysisError> {
    control.expect(frequencies.len() as u64);
    let probe_at = |points: Vec<f64>| {
        move |r: &Responses| -> Result<Vec<Orbit>, AnalysisError> {
            let at = r.at(speed);
            let per: Vec<Vec<Orbit>> = points
                .par_iter()
                .map(|&w| at.orbits(w, force, &[output]))
                .collect::<Result<_, _>>()?;
            Ok(per.concat())
        }
    };
    let mut dofs: Vec<usize> = (0..force.forward.len())
        .filter(|&i| force.forward[i].norm() != 0.0 || force.backward[i].norm() != 0.0)
        .collect();
    dofs.push(output);
    let bound = frequencies.iter().fold(0.0, |a: f64, b| a.max(b.abs()));
    let edges = edges(frequencies);
    let sweep = |model: &Responses| -> Result<Vec<Orbit>, AnalysisError> {
        let at = model.at(speed);
        frequencies
            .par_iter()
            .map(|&w| {
                control.check()?;
                let o = at.orbits(w, force, &[output])?;
                control.advance(1);
                Ok(o[0])
            })
            .collect()
    };
    let grid = Grid {
        reduce,
        bound,
        dofs: &dofs,
        forces: dofs.len() - 1,
        edges,
    };
    grid.swept(
        system,
        damping,
        full.into(),
        &|p| Box::new(probe_at(p)),
        sweep,
        |r| {
            let per: Vec<Vec<Orbit>> = r.iter().map(|o| vec![*o]).collect();
            largest(frequencies, &per)
        },
    )
}
