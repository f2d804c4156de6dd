//! A train's torsional or axial time response: its vibration apart from its rigid motion, and
//! the load every element carries.
//!
//! A free train (nothing holds its turning, or without a thrust bearing its sliding) has a
//! rigid mode `r` (`K r = 0`, `r^T M r = 1`); a net torque turns it ever faster, and the
//! state matrix has a double zero that no modal superposition can diagonalise. With `Phi` the
//! other undamped modes, `q = r eta + Phi y`: `Phi^T M r = 0` and `K r = 0` (and `C r = 0` where
//! no damping reaches ground), so
//!
//! ```text
//! eta'' = r^T f(t),      Phi^T M Phi y'' + Phi^T C Phi y' + Phi^T K Phi y = Phi^T f(t)
//! ```
//!
//! The rigid part is integrated in closed form (tables and short circuits) or is the motor's
//! run-up itself (its inertia `J = 1 / r_m^2` referred to the motor's node `m`, the load's shaft
//! turning `r_l / r_m` times as fast); the vibration `y` is solved on the complete basis of the
//! other modes, exactly as the train's own coordinates would be. Each node's `x` is `Phi y`,
//! its motion relative to the rigid one, and each element's load `t_e . x` (the rigid motion
//! twists nothing).

use std::sync::Arc;

use super::RunError;
use super::models::damping_error;
use crate::analysis::control::Control;
use crate::analysis::shaft_loads;
use crate::analysis::time::{self, Coordinates, TimeResult, TimeSpec, TrainHistory};
use crate::damping::DampedModel;
use crate::fem::modal::ModalBasis;
use crate::model::Invalid;
use crate::model::loads::{Source, SpeedLaw, Torque};
use crate::model::task::Model;
use crate::model::train::TrainRotor;
use crate::system::RotorSystem;

/// The response of `spec` on the train `t` assembled as `system`.
pub fn solve(
    system: &RotorSystem,
    t: &TrainRotor,
    model: &Model,
    spec: &TimeSpec,
    control: &Control,
) -> Result<TimeResult, RunError> {
    let basis = ModalBasis::of(system).map_err(|e| RunError::Unsolvable(e.to_string()))?;
    let rigid: Vec<usize> = (0..basis.len())
        .filter(|&k| basis.omega[k] == 0.0)
        .collect();
    if rigid.len() > 1 {
        return Err(RunError::Invalid(Invalid::one(
            "rotor.shaft",
            format!(
                "the train is in {} pieces that nothing joins (a coupling or mesh without \
                 stiffness along this motion): each would turn on its own; give the joining \
                 element its stiffness, or analyse the pieces apart",
                rigid.len()
            ),
        )));
    }
    let r: Option<Vec<f64>> = rigid
        .first()
        .map(|&k| (0..system.n()).map(|i| basis.phi[(i, k)]).collect());
    let dof = |node: usize| time::translation(system, node);
    // Every node solved (the element loads need them all); the speed is no part of it.
    let mut solved_spec = TimeSpec {
        speed: SpeedLaw::Constant(0.0),
        nodes: (0..system.n()).collect(),
        ..spec.clone()
    };
    let mut run_up = None;
    if let Some(m) = solved_spec.generated.motor.take() {
        let Some(r) = &r else {
            return Err(RunError::Invalid(Invalid::one(
                "motor_start",
                "the train is held in place: a motor's start-up needs a train free to turn",
            )));
        };
        let (rm, rl) = (r[dof(m.node)], r[dof(m.load_node)]);
        let up = Arc::new(m.run_up(1.0 / (rm * rm), rl / rm, spec.duration));
        solved_spec.generated.torques.extend([
            Torque {
                node: m.node,
                source: Source::AirGap(up.clone()),
            },
            Torque {
                node: m.load_node,
                source: Source::Load(up.clone()),
            },
        ]);
        run_up = Some((up, rm));
    }
    // The rigid mode is the lowest (the basis is ascending): the elastic ones are the rest.
    let from = rigid.len();
    let elastic = ModalBasis {
        omega: basis.omega[from..].to_vec(),
        phi: basis.phi.subcols(from, basis.len() - from).to_owned(),
    };
    let reduced = elastic.reduce(system);
    let damped =
        DampedModel::build(&reduced, &model.damping).map_err(|e| damping_error(e, &model.rotor))?;
    let c = Coordinates {
        physical: system,
        solved: &reduced,
        basis: Some(&elastic.phi),
        slow: None,
    };
    let mut out = if solved_spec.generated.torques.is_empty() {
        time::solve_in(&c, &damped, &solved_spec, false, control)?
    } else {
        time::solve_exponential(&c, &damped, &solved_spec, control)?
    };
    let mut warnings = vec![];
    let rigid_motion = r.as_ref().map(|r| {
        let c_r = system.damping_nonrotating.mul_vec(r);
        if r.iter().zip(&c_r).map(|(a, b)| a * b).sum::<f64>() > 0.0 {
            warnings.push(
                "damping to ground (mass-proportional Rayleigh damping) resists the train's \
                 rigid motion: it is left out of the rigid motion and of the vibration it \
                 drives"
                    .to_string(),
            );
        }
        rigid_history(r, &solved_spec, &out.time, run_up.as_ref(), &dof)
    });
    let elements = shaft_loads::histories(t, &out.nodes);
    out.nodes.retain(|(n, _)| spec.nodes.contains(n));
    out.train = Some(Box::new(TrainHistory {
        rigid: rigid_motion,
        elements,
        warnings,
    }));
    Ok(out)
}

/// The first node's rigid position and rate at `times`: `r_0 eta`, `eta'' = r^T f`.
fn rigid_history(
    r: &[f64],
    spec: &TimeSpec,
    times: &[f64],
    run_up: Option<&(Arc<crate::model::torque::RunUp>, f64)>,
    dof: &dyn Fn(usize) -> usize,
) -> (Vec<f64>, Vec<f64>) {
    let r0 = r[dof(0)];
    // Each force as steps and ramps, weighted by the rigid mode at its node: once, not per time.
    let pieces: Vec<(f64, f64, f64)> = spec
        .forces
        .iter()
        .flat_map(|f| {
            let w = r[dof(f.node)];
            let sr = f.history.steps_and_ramps();
            sr.into_iter()
                .map(move |(tk, jump, ramp)| (tk, w * jump, w * ramp))
        })
        .collect();
    times
        .iter()
        .map(|&t| {
            // (eta', eta).
            let (mut v, mut p) = (0.0, 0.0);
            for &(tk, jump, ramp) in &pieces {
                let tau = t - tk;
                if tau > 0.0 {
                    v += jump * tau + ramp * tau * tau / 2.0;
                    p += jump * tau * tau / 2.0 + ramp * tau.powi(3) / 6.0;
                }
            }
            for g in &spec.generated.torques {
                if let Source::Fault(s) = &g.source {
                    let (i1, i2) = s.integrals(t);
                    v += r[dof(g.node)] * i1;
                    p += r[dof(g.node)] * i2;
                }
            }
            if let Some((up, rm)) = run_up {
                let (angle, speed) = up.angle(t);
                v += speed / rm;
                p += angle / rm;
            }
            (r0 * p, r0 * v)
        })
        .unzip()
}
