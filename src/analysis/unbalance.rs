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
pub use super::audit::frequency::Orbit;
use super::audit::frequency::{Harmonic, harmonic};
use super::control::Control;
use crate::damping::DampedModel;
use crate::linalg::c64;
use crate::system::RotorSystem;
use rayon::prelude::*;

/// An unbalance for the steady response.
#[derive(Debug, Clone, PartialEq)]
pub struct SteadyUnbalance {
    pub dof: usize,
    pub amount: f64,
    pub phase: f64,
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
            let zero = c64::new(0.0, 0.0);
            let mut force = Harmonic {
                forward: vec![zero; n],
                backward: vec![zero; n],
            };
            for u in unbalances {
                force.forward[u.dof] += c64::from_polar(u.amount * w * w, u.phase);
            }
            let orbits = harmonic(system, model, w, w, &force, out)?;
            control.advance(1);
            Ok(orbits)
        })
        .collect()
}
