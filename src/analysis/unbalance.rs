//! Steady synchronous response to unbalance against spin speed.
//!
//! Unbalances `m e` at phases `phi` load `F = m e Omega^2 e^{i phi} e^{i Omega t}` on `r`; the
//! steady response is `q = Q e^{i Omega t}` with, in state form, `(i Omega I - A(Omega)) Z = B F`,
//! one complex solve per speed. In doubled coordinates the `conj r` rows are unloaded at this
//! frequency (their load is the conjugate, at `-Omega`, which gives the conjugate solution),
//! and a node's `r` and `conj r` amplitudes `a` and `b` make the elliptical orbit
//! `r(t) = a e^{i Omega t} + conj(b) e^{-i Omega t}`: `x(t) = Re(X e^{i Omega t})`,
//! `y(t) = Re(Y e^{i Omega t})` with `X = a + b`, `Y = -i (a - b)` (ROSS's complex amplitudes),
//! semi-axes `|a| + |b|` and `||a| - |b||`. On isotropic supports `b = 0`: a circle.
//!
//! In synchronous whirl the rotor material sees a frequency `omega - Omega = 0`. The rotating
//! viscous and equivalent damping then do no work (`C_r (q' - i Omega q) = 0`), nor do the
//! nonviscous branches (a Maxwell branch carries no static load). The hysteretic model is
//! undefined there (`sgn 0`); it is evaluated with `sgn 0 = 0`, the limit the other models
//! share: only the nonrotating loss `i K''_n` acts (and, on doubled coordinates' backward part,
//! which the rotor sees at `2 Omega`, the rotating loss too).

use super::AnalysisError;
use super::control::Control;
use crate::damping::{DampedModel, ModelKind};
use crate::linalg::{self, CMat, c64};
use crate::system::{Realized, RotorSystem};
use rayon::prelude::*;

/// An unbalance for the steady response.
#[derive(Debug, Clone, PartialEq)]
pub struct SteadyUnbalance {
    pub dof: usize,
    pub amount: f64,
    pub phase: f64,
}

/// A node's steady orbit: `r(t) = a e^{i Omega t} + conj(b) e^{-i Omega t}`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Orbit {
    pub a: c64,
    pub b: c64,
}

impl Orbit {
    /// `[X, Y]`: `x(t) = Re(X e^{i Omega t})`, `y(t) = Re(Y e^{i Omega t})`.
    pub fn xy(&self) -> [c64; 2] {
        [self.a + self.b, c64::new(0.0, -1.0) * (self.a - self.b)]
    }

    /// Semi-major axis.
    pub fn major(&self) -> f64 {
        self.a.norm() + self.b.norm()
    }

    /// Semi-minor axis.
    pub fn minor(&self) -> f64 {
        (self.a.norm() - self.b.norm()).abs()
    }
}

/// The orbit of each requested degree of freedom at each speed.
pub fn unbalance_response(
    system: &RotorSystem,
    model: &DampedModel,
    speeds: &[f64],
    unbalances: &[SteadyUnbalance],
    out: &[usize],
    control: &Control,
) -> Result<Vec<Vec<Orbit>>, AnalysisError> {
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
            let r = Realized::at(system, w);
            let big = r.size();
            let q: Vec<c64> = match &model.kind {
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
                    let fm =
                        CMat::from_fn(big, 1, |i, _| if i < n { f[i] } else { c64::new(0.0, 0.0) });
                    let minv_f = linalg::mass_solve(&r.mass, &fm)?;
                    let rhs = CMat::from_fn(size, 1, |i, _| {
                        if i < big {
                            minv_f[(i, 0)]
                        } else {
                            c64::new(0.0, 0.0)
                        }
                    });
                    let z = linalg::solve_complex(&lhs, &rhs)?;
                    (0..big).map(|i| z[(big + i, 0)]).collect()
                }
                ModelKind::Hysteretic(_) => {
                    // -W^2 M + i W (C_n + C_r) + W^2 S G + K - i W S C_r + i sgn(W) K''_n
                    // + i diag(sgn(W - W) = 0 on r, sgn(2 W) on conj r) K''_r.
                    let sg = r.spun(&r.gyroscopic);
                    let scr = r.spun(&r.damping_rotating);
                    let s = if w > 0.0 { 1.0 } else { 0.0 };
                    let i1 = c64::new(0.0, 1.0);
                    let lhs = CMat::from_fn(big, big, |a, b| {
                        let rot = if r.spin[a] > 0.0 { 0.0 } else { s };
                        r.mass[(a, b)] * (-w * w)
                            + (r.damping_nonrotating[(a, b)] + r.damping_rotating[(a, b)])
                                * (i1 * w)
                            + sg[(a, b)] * (w * w)
                            + r.stiffness[(a, b)]
                            - scr[(a, b)] * (i1 * w)
                            + r.loss_nonrotating[(a, b)] * (i1 * s)
                            + r.loss_rotating[(a, b)] * (i1 * rot)
                    });
                    let rhs =
                        CMat::from_fn(big, 1, |i, _| if i < n { f[i] } else { c64::new(0.0, 0.0) });
                    let z = linalg::solve_complex(&lhs, &rhs)?;
                    (0..big).map(|i| z[(i, 0)]).collect()
                }
            };
            control.advance(1);
            Ok(out
                .iter()
                .map(|&d| Orbit {
                    a: q[d],
                    b: if big > n {
                        q[n + d]
                    } else {
                        c64::new(0.0, 0.0)
                    },
                })
                .collect())
        })
        .collect()
}
