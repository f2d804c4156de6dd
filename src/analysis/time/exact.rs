//! Exact response at constant speed by modal superposition.
//!
//! `A = V diag(lambda) V^-1` once; in modal coordinates `xi = V^-1 z` each equation
//! `xi' = lambda xi + g(t)` has a closed-form solution for the loads we have. Every force
//! history is a sum of steps and ramps starting at its breakpoints, and for `tau = t - t_k`:
//! step `tau phi1(lambda tau)`, ramp `tau^2 phi2(lambda tau)` with `phi1(z) = (e^z - 1)/z`,
//! `phi2(z) = (e^z - 1 - z)/z^2`. An unbalance `m e Omega^2 e^{i (Omega t + phase)}` from `t0`
//! gives `e^{i Omega t0} tau e^{i Omega tau} phi1((lambda - i Omega) tau)`, which stays exact
//! at resonance. The results are sampled at the output times; no time stepping at all.

use super::{Forcing, Method, TimeError, TimeResult, TimeSpec, rows};
use crate::analysis::control::Control;
use crate::damping::state::StateModel;
use crate::linalg::{self, CMat, LinalgError, c64};

/// `(e^z - 1)/z`, accurate near 0.
pub fn phi1(z: c64) -> c64 {
    if z.norm() < 0.1 {
        let (mut term, mut sum) = (c64::new(1.0, 0.0), c64::new(1.0, 0.0));
        for k in 2..14 {
            term = term * z / k as f64;
            sum += term;
        }
        sum
    } else {
        (z.exp() - 1.0) / z
    }
}

/// `(e^z - 1 - z)/z^2`, accurate near 0.
pub fn phi2(z: c64) -> c64 {
    if z.norm() < 0.1 {
        let (mut term, mut sum) = (c64::new(0.5, 0.0), c64::new(0.5, 0.0));
        for k in 3..16 {
            term = term * z / k as f64;
            sum += term;
        }
        sum
    } else {
        (phi1(z) - 1.0) / z
    }
}

pub fn solve(
    state: &StateModel,
    omega: f64,
    forcing: &Forcing,
    spec: &TimeSpec,
    out: &[usize],
    control: &Control,
) -> Result<TimeResult, TimeError> {
    let e = linalg::eigen(&state.at(omega))?;
    let size = state.size();
    // One right-hand side per load: unit force in its direction, unit unbalance at its phase.
    let mut cols: Vec<Vec<c64>> = vec![];
    for (f, &dof) in spec.forces.iter().zip(&forcing.force_dofs) {
        let dir = c64::from_polar(1.0, f.direction);
        cols.push(forcing.unit(dof).iter().map(|b| b * dir).collect());
    }
    for (u, &dof) in spec.unbalances.iter().zip(&forcing.unbalance_dofs) {
        let ph = c64::from_polar(1.0, u.phase);
        cols.push(forcing.unit(dof).iter().map(|b| b * ph).collect());
    }
    let rhs = CMat::from_fn(size, cols.len(), |i, j| cols[j][i]);
    let g = linalg::solve_complex(&e.vectors, &rhs)?;
    // A nearly defective A makes V^-1 meaningless: fall back to integrating.
    let back = &e.vectors * &g;
    let (mut res, mut scale) = (0.0f64, 0.0f64);
    for i in 0..size {
        for j in 0..cols.len() {
            res = res.max((back[(i, j)] - rhs[(i, j)]).norm());
            scale = scale.max(rhs[(i, j)].norm());
        }
    }
    if res > 1e-9 * scale.max(f64::MIN_POSITIVE) {
        return Err(TimeError::Linalg(LinalgError::NonFinite));
    }
    let pieces: Vec<Vec<(f64, f64, f64)>> = spec
        .forces
        .iter()
        .map(|f| f.history.steps_and_ramps())
        .collect();
    let out_rows = rows(state, out);
    let times = spec.output_times();
    let lambda = &e.values;
    let nf = spec.forces.len();
    let mut histories = vec![vec![c64::new(0.0, 0.0); times.len()]; out.len()];
    let mut xi = vec![c64::new(0.0, 0.0); size];
    let iw = c64::new(0.0, omega);
    for (ti, &t) in times.iter().enumerate() {
        if ti.is_multiple_of(64) {
            control.check()?;
            control.advance(64.min((times.len() - ti) as u64));
        }
        for (k, xk) in xi.iter_mut().enumerate() {
            let l = lambda[k];
            let mut acc = c64::new(0.0, 0.0);
            for (fi, ps) in pieces.iter().enumerate() {
                let mut r = c64::new(0.0, 0.0);
                for &(tk, jump, dslope) in ps {
                    let tau = t - tk;
                    if tau > 0.0 {
                        if jump != 0.0 {
                            r += jump * tau * phi1(l * tau);
                        }
                        if dslope != 0.0 {
                            r += dslope * tau * tau * phi2(l * tau);
                        }
                    }
                }
                acc += g[(k, fi)] * r;
            }
            for (ui, u) in spec.unbalances.iter().enumerate() {
                let tau = t - u.from;
                if tau > 0.0 {
                    let r = c64::from_polar(u.amount * omega * omega, omega * u.from)
                        * tau
                        * (iw * tau).exp()
                        * phi1((l - iw) * tau);
                    acc += g[(k, nf + ui)] * r;
                }
            }
            *xk = acc;
        }
        for (h, &row) in histories.iter_mut().zip(&out_rows) {
            h[ti] = (0..size).map(|k| e.vectors[(row, k)] * xi[k]).sum();
        }
    }
    Ok(TimeResult {
        time: times,
        nodes: spec.nodes.iter().cloned().zip(histories).collect(),
        method: Method::Exact,
        steps: 0,
        states: size,
    })
}
