//! Exact response at constant speed by modal superposition.
//!
//! `A = V diag(lambda) V^-1` once; in modal coordinates `xi = V^-1 z` each equation
//! `xi' = lambda xi + g(t)` has a closed-form solution for the loads we have. Every force
//! history is a sum of steps and ramps starting at its breakpoints, and for `tau = t - t_k`:
//! step `tau phi1(lambda tau)`, ramp `tau^2 phi2(lambda tau)` with `phi1(z) = (e^z - 1)/z`,
//! `phi2(z) = (e^z - 1 - z)/z^2`. An unbalance `m e Omega^2 e^{i (Omega t + phase)}` from `t0`
//! gives `e^{i Omega t0} tau e^{i Omega tau} phi1((lambda - i Omega) tau)`, which stays exact
//! at resonance. The results are sampled at the output times; no time stepping at all.

use super::{Forcing, Method, TimeError, TimeResult, TimeSpec};
use rayon::prelude::*;

use crate::analysis::control::{Cancelled, Control};
use crate::damping::state::StateModel;
use crate::linalg::{self, CMat, c64};

pub use crate::linalg::{phi1, phi2};

pub fn solve(
    state: &StateModel,
    omega: f64,
    forcing: &Forcing,
    spec: &TimeSpec,
    out: &[Vec<(usize, f64)>],
    control: &Control,
) -> Result<TimeResult, TimeError> {
    let e = linalg::eigen(&state.at(omega))?;
    let size = state.size();
    // One right-hand side per load: unit force in its direction; unit unbalance at its phase,
    // once per direction of whirl it drives (two in doubled coordinates).
    let super::LoadColumns { cols, whirls } = forcing.columns();
    let rhs = CMat::from_fn(size, cols.len(), |i, j| cols[j][i]);
    let g = linalg::solve_complex(&e.vectors, &rhs)?;
    super::check_modal(&e.vectors, &g, &rhs)?;
    // Every force as steps and ramps: (force index, t_k, jump, slope change).
    let pieces: Vec<(usize, f64, f64, f64)> = spec
        .forces
        .iter()
        .enumerate()
        .flat_map(|(fi, f)| {
            f.history
                .steps_and_ramps()
                .into_iter()
                .map(move |(tk, jump, dslope)| (fi, tk, jump, dslope))
        })
        .collect();
    let vrows = super::output_rows(&e.vectors, out, state.n());
    let times = spec.output_times();
    let chunks: Vec<(usize, usize)> = (0..times.len())
        .step_by(CHUNK)
        .map(|i0| (i0, (i0 + CHUNK).min(times.len())))
        .collect();
    let model = Modal {
        lambda: &e.values,
        g: &g,
        pieces: &pieces,
        whirls: &whirls,
        omega,
        dt: spec.output_interval,
        spec,
        vrows: &vrows,
    };
    let parts: Vec<Vec<Vec<c64>>> = chunks
        .par_iter()
        .map(|&(i0, i1)| {
            control.check()?;
            let part = model.chunk(i0, i1);
            control.advance((i1 - i0) as u64);
            Ok(part)
        })
        .collect::<Result<_, Cancelled>>()?;
    let mut histories = vec![Vec::with_capacity(times.len()); out.len()];
    for part in parts {
        for (h, p) in histories.iter_mut().zip(part) {
            h.extend(p);
        }
    }
    Ok(TimeResult {
        time: times,
        nodes: spec.nodes.iter().cloned().zip(histories).collect(),
        method: Method::Exact,
        steps: 0,
        states: size,
        train: None,
    })
}

/// Output samples per parallel chunk: each chunk starts its exponentials afresh.
const CHUNK: usize = 512;

/// The diagonalised system and its loads, evaluated over a range of output samples.
struct Modal<'a> {
    lambda: &'a [c64],
    /// `V^-1 B`: modal participation of each force, then each unbalance's whirls.
    g: &'a CMat,
    pieces: &'a [(usize, f64, f64, f64)],
    /// `(unbalance, column of g, sense)`: each unbalance whirls at `sense Omega`.
    whirls: &'a [(usize, usize, f64)],
    omega: f64,
    dt: f64,
    spec: &'a TimeSpec,
    /// Rows of `V` of the output coordinates.
    vrows: &'a [Vec<c64>],
}

impl Modal<'_> {
    /// Outputs at samples `i0..i1` (`t_i = i dt`). The exponentials `e^{lambda tau}` advance by
    /// one multiplication per sample; the closed forms divide by `lambda` (or
    /// `lambda - i Omega`) only where `|z tau| >= 0.1`, and use `phi1`, `phi2` below, so
    /// nothing cancels.
    fn chunk(&self, i0: usize, i1: usize) -> Vec<Vec<c64>> {
        let size = self.lambda.len();
        let step: Vec<c64> = self.lambda.iter().map(|l| (l * self.dt).exp()).collect();
        let mut e_piece = vec![vec![c64::new(0.0, 0.0); size]; self.pieces.len()];
        let mut started_piece = vec![false; self.pieces.len()];
        let unbalances = &self.spec.unbalances;
        let mut e_unb = vec![vec![c64::new(0.0, 0.0); size]; self.whirls.len()];
        let mut w_unb = vec![c64::new(0.0, 0.0); self.whirls.len()];
        let mut started_unb = vec![false; self.whirls.len()];
        let mut acc = vec![c64::new(0.0, 0.0); size];
        let mut out = vec![Vec::with_capacity(i1 - i0); self.vrows.len()];
        for i in i0..i1 {
            let t = i as f64 * self.dt;
            acc.iter_mut().for_each(|a| *a = c64::new(0.0, 0.0));
            for (p, &(fi, tk, jump, dslope)) in self.pieces.iter().enumerate() {
                let tau = t - tk;
                if tau <= 0.0 {
                    continue;
                }
                let fresh = !started_piece[p];
                started_piece[p] = true;
                for k in 0..size {
                    let l = self.lambda[k];
                    let ek = &mut e_piece[p][k];
                    *ek = if fresh {
                        (l * tau).exp()
                    } else {
                        *ek * step[k]
                    };
                    let z = l * tau;
                    let r = if z.norm() < 0.1 {
                        jump * tau * phi1(z) + dslope * tau * tau * phi2(z)
                    } else {
                        let one = (*ek - 1.0) / l;
                        jump * one + dslope * (one - tau) / l
                    };
                    acc[k] += self.g[(k, fi)] * r;
                }
            }
            for (h, &(u, col, sense)) in self.whirls.iter().enumerate() {
                let ub = &unbalances[u];
                let tau = t - ub.from;
                if tau <= 0.0 {
                    continue;
                }
                let omega = sense * self.omega;
                let fresh = !started_unb[h];
                started_unb[h] = true;
                w_unb[h] = if fresh {
                    c64::from_polar(1.0, omega * tau)
                } else {
                    w_unb[h] * c64::from_polar(1.0, omega * self.dt)
                };
                let w = w_unb[h];
                let iw = c64::new(0.0, omega);
                let amp = c64::from_polar(ub.amount * self.omega * self.omega, omega * ub.from);
                for k in 0..size {
                    let l = self.lambda[k];
                    let ek = &mut e_unb[h][k];
                    *ek = if fresh {
                        (l * tau).exp()
                    } else {
                        *ek * step[k]
                    };
                    let z = l - iw;
                    // tau e^{i w tau} phi1(z tau) = (e^{lambda tau} - e^{i w tau}) / z
                    let r = if (z * tau).norm() < 0.1 {
                        tau * w * phi1(z * tau)
                    } else {
                        (*ek - w) / z
                    };
                    acc[k] += self.g[(k, col)] * amp * r;
                }
            }
            for (o, row) in out.iter_mut().zip(self.vrows) {
                o.push(row.iter().zip(&acc).map(|(v, a)| v * a).sum());
            }
        }
        out
    }
}
