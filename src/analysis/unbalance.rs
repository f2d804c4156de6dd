//! Steady synchronous response to unbalance against spin speed.
//!
//! Unbalances `m e` at phases `phi` load `F = m e Omega^2 e^{i phi} e^{i Omega t}`; the steady
//! response is `q = Q e^{i Omega t}` with, in state form, `(i Omega I - A(Omega)) Z = B F`, one
//! complex solve per speed. Its translations describe circular forward orbits of radius `|Q|`.
//!
//! In synchronous whirl the rotor material sees a frequency `omega - Omega = 0`. The rotating
//! viscous and equivalent damping then do no work (`C_r (q' - i Omega q) = 0`), nor do the
//! nonviscous branches (a Maxwell branch carries no static load). The hysteretic model is
//! undefined there (`sgn 0`); it is evaluated with `sgn 0 = 0`, the limit the other models
//! share: only the nonrotating loss `i K''_n` acts.

use super::AnalysisError;
use super::control::Control;
use crate::damping::{DampedModel, ModelKind};
use crate::linalg::{self, CMat, c64};
use crate::system::RotorSystem;
use rayon::prelude::*;

/// An unbalance for the steady response.
#[derive(Debug, Clone, PartialEq)]
pub struct SteadyUnbalance {
    pub dof: usize,
    pub amount: f64,
    pub phase: f64,
}

/// Complex amplitude `Q` of each requested degree of freedom at each speed.
pub fn unbalance_response(
    system: &RotorSystem,
    model: &DampedModel,
    speeds: &[f64],
    unbalances: &[SteadyUnbalance],
    out: &[usize],
    control: &Control,
) -> Result<Vec<Vec<c64>>, AnalysisError> {
    let n = system.n();
    control.expect(speeds.len() as u64);
    speeds
        .par_iter()
        .map(|&w| {
            control.check()?;
            let mut f = vec![c64::new(0.0, 0.0); n];
            for u in unbalances {
                f[u.dof] += c64::from_polar(u.amount * w * w, u.phase);
            }
            let q = match &model.kind {
                ModelKind::Linear(state) => {
                    let size = state.size();
                    let a = state.at(w);
                    let lhs = CMat::from_fn(size, size, |i, j| {
                        let diag = if i == j {
                            c64::new(0.0, w)
                        } else {
                            c64::new(0.0, 0.0)
                        };
                        diag - a[(i, j)]
                    });
                    let fm = CMat::from_fn(n, 1, |i, _| f[i]);
                    let minv_f = linalg::spd_solve(&system.mass, &fm)?;
                    let rhs = CMat::from_fn(size, 1, |i, _| {
                        if i < n {
                            minv_f[(i, 0)]
                        } else {
                            c64::new(0.0, 0.0)
                        }
                    });
                    let z = linalg::solve_complex(&lhs, &rhs)?;
                    (0..n).map(|i| z[(n + i, 0)]).collect::<Vec<_>>()
                }
                ModelKind::Hysteretic(_) => {
                    // -Omega^2 M + i Omega (C_n + C_r - i Omega G) + K - i Omega C_r + i sgn(Omega) K''_n
                    let k = system.stiffness();
                    let s = if w > 0.0 { 1.0 } else { 0.0 };
                    let lhs = CMat::from_fn(n, n, |i, j| {
                        let re = -w * w * system.mass[(i, j)]
                            + w * w * system.gyroscopic[(i, j)]
                            + k[(i, j)];
                        let im = w * system.damping_nonrotating[(i, j)]
                            + s * system.hysteretic_nonrotating[(i, j)];
                        c64::new(re, im)
                    });
                    let rhs = CMat::from_fn(n, 1, |i, _| f[i]);
                    let z = linalg::solve_complex(&lhs, &rhs)?;
                    (0..n).map(|i| z[(i, 0)]).collect()
                }
            };
            control.advance(1);
            Ok(out.iter().map(|&d| q[d]).collect())
        })
        .collect()
}
