//! TR-BDF2 for `z' = A(Omega(t)) z + b(t)`: L-stable, second order, one LU for both stages.
//!
//! With `gamma = 2 - sqrt 2` and `d = gamma / 2 = 1 - 1/sqrt 2`, a step of length `h` is a
//! trapezoidal stage to `t + gamma h`, `(I - d h A) z_g = z_n + d h (f_n + b_g)`, then a BDF2
//! stage, `(I - d h A) z_1 = (z_g - (1 - gamma)^2 z_n) / (gamma (2 - gamma)) + d h b_1`. The local
//! error estimate (Bank et al. 1985) `2 k h (f_n / gamma - f_g / (gamma (1 - gamma)) +
//! f_1 / (1 - gamma))`, `k = (-3 gamma^2 + 4 gamma - 2) / (12 (2 - gamma))`, is filtered
//! through `(I - d h A)^-1` so that stiff, decayed components do not shrink the step. Steps land
//! on every breakpoint of the loads and the speed law; outputs between steps come from the cubic
//! Hermite interpolant. The LU of `I - d h A` is kept while `h` is unchanged; when the speed
//! moves, the stages are solved by iterative refinement on it and refactored only when that
//! stops converging.

use super::{Forcing, Method, TimeError, TimeResult, TimeSpec, observed};
use crate::analysis::control::Control;
use crate::damping::state::StateModel;
use crate::linalg::{CMat, ComplexLu, c64};

const GAMMA: f64 = 2.0 - std::f64::consts::SQRT_2;
const D: f64 = 1.0 - std::f64::consts::FRAC_1_SQRT_2;

struct Factor {
    lu: ComplexLu,
    h: f64,
    omega: f64,
}

/// `A(Omega) x` (through the supports' table, if any).
fn apply(state: &StateModel, omega: f64, x: &[c64]) -> Vec<c64> {
    state.apply(omega, x)
}

fn norm_inf(x: &[c64]) -> f64 {
    x.iter().map(|v| v.norm()).fold(0.0, f64::max)
}

/// Solves `(I - d h A(omega)) x = rhs` with the kept factor, refining to `tol` relative
/// (refactored when needed).
fn stage_solve(
    state: &StateModel,
    factor: &mut Option<Factor>,
    h: f64,
    omega: f64,
    rhs: &[c64],
    tol: f64,
) -> Vec<c64> {
    let build = |w: f64| {
        let a = state.at(w);
        let n = a.nrows();
        let m = CMat::from_fn(n, n, |i, j| {
            let id = if i == j { 1.0 } else { 0.0 };
            c64::new(id, 0.0) - a[(i, j)] * (D * h)
        });
        Factor {
            lu: ComplexLu::new(&m),
            h,
            omega: w,
        }
    };
    if factor.as_ref().is_none_or(|f| f.h != h) {
        *factor = Some(build(omega));
    }
    for attempt in 0..2 {
        let f = factor.as_ref().expect("built");
        let mut x = rhs.to_vec();
        f.lu.solve_in_place(&mut x);
        if f.omega == omega {
            return x;
        }
        // Refinement: r = rhs - (x - d h A(omega) x).
        for _ in 0..12 {
            let ax = apply(state, omega, &x);
            let mut r: Vec<c64> = (0..x.len())
                .map(|i| rhs[i] - x[i] + ax[i] * (D * h))
                .collect();
            f.lu.solve_in_place(&mut r);
            for (xi, ri) in x.iter_mut().zip(&r) {
                *xi += ri;
            }
            if norm_inf(&r) <= tol * norm_inf(&x).max(f64::MIN_POSITIVE) {
                return x;
            }
        }
        if attempt == 0 {
            *factor = Some(build(omega));
        }
    }
    let f = factor.as_ref().expect("built");
    let mut x = rhs.to_vec();
    f.lu.solve_in_place(&mut x);
    x
}

/// Integrates from rest. `slow`: the state entries the error is controlled on (all when
/// `None`); on a modal reduction, the fast static corrections ride quasi-statically (the
/// scheme is L-stable) and are left out, or their ringing would hold the step.
pub fn solve(
    state: &StateModel,
    forcing: &Forcing,
    spec: &TimeSpec,
    out: &[Vec<(usize, f64)>],
    slow: Option<&[bool]>,
    control: &Control,
) -> Result<TimeResult, TimeError> {
    let size = state.size();
    let controlled: Vec<usize> = (0..size).filter(|&i| slow.is_none_or(|s| s[i])).collect();
    let times = spec.output_times();
    let n = state.n();
    let mut histories = vec![vec![c64::new(0.0, 0.0); times.len()]; out.len()];
    let breaks = forcing.breakpoints();
    let speed = |t: f64| spec.speed.omega(t);
    let rtol = spec.tolerance;
    // Stage equations solved well below the step's own error: more is wasted work.
    let solve_tol = (1e-3 * rtol).max(1e-14);
    let k_err = (-3.0 * GAMMA * GAMMA + 4.0 * GAMMA - 2.0) / (12.0 * (2.0 - GAMMA));

    let mut t = 0.0;
    let mut z = vec![c64::new(0.0, 0.0); size];
    let mut f_n: Vec<c64> = forcing.b(0.0, false);
    let mut h = (spec.output_interval).min(spec.duration) * 0.1;
    let mut factor: Option<Factor> = None;
    let mut next_out = 1; // sample 0 is the state at rest
    let mut next_break = 0;
    let mut steps = 0usize;
    let mut peak = 0.0f64;
    while t < spec.duration * (1.0 - 1e-14) {
        if steps >= spec.max_steps {
            return Err(TimeError::TooManySteps(spec.max_steps));
        }
        if steps.is_multiple_of(64) {
            control.check()?;
        }
        while next_break < breaks.len() && breaks[next_break] <= t * (1.0 + 1e-14) {
            next_break += 1;
        }
        let limit = breaks.get(next_break).copied().unwrap_or(spec.duration);
        let landing = t + h >= limit * (1.0 - 1e-12);
        let step = if landing { limit - t } else { h };
        let (tg, t1) = (t + GAMMA * step, t + step);
        // Stage 1: trapezoid to t + gamma h.
        let bg = forcing.b(tg, false);
        let rhs: Vec<c64> = (0..size)
            .map(|i| z[i] + (f_n[i] + bg[i]) * (D * step))
            .collect();
        let zg = stage_solve(state, &mut factor, step, speed(tg), &rhs, solve_tol);
        let fg: Vec<c64> = (0..size)
            .map(|i| (zg[i] - z[i]) / (D * step) - f_n[i])
            .collect();
        // Stage 2: BDF2 to t + h (loads from the left if the step ends on a jump).
        let b1 = forcing.b(t1, landing);
        let c = 1.0 / (GAMMA * (2.0 - GAMMA));
        let r: Vec<c64> = (0..size)
            .map(|i| (zg[i] - z[i] * (1.0 - GAMMA).powi(2)) * c)
            .collect();
        let rhs: Vec<c64> = (0..size).map(|i| r[i] + b1[i] * (D * step)).collect();
        let z1 = stage_solve(state, &mut factor, step, speed(t1), &rhs, solve_tol);
        let f1: Vec<c64> = (0..size).map(|i| (z1[i] - r[i]) / (D * step)).collect();
        // Error estimate, filtered.
        let mut e: Vec<c64> = (0..size)
            .map(|i| {
                (f_n[i] / GAMMA - fg[i] / (GAMMA * (1.0 - GAMMA)) + f1[i] / (1.0 - GAMMA))
                    * (2.0 * k_err * step)
            })
            .collect();
        e = stage_solve(state, &mut factor, step, speed(t1), &e, 1e-2);
        peak = peak.max(norm_inf(&z1));
        let atol = rtol * 1e-3 * peak;
        let err = if peak == 0.0 {
            0.0
        } else {
            let s: f64 = controlled
                .iter()
                .map(|&i| {
                    let sc = atol + rtol * z[i].norm().max(z1[i].norm());
                    (e[i].norm() / sc).powi(2)
                })
                .sum();
            (s / controlled.len().max(1) as f64).sqrt()
        };
        let ratio = if err == 0.0 {
            2.0
        } else {
            (0.9 * err.powf(-1.0 / 3.0)).clamp(0.2, 2.0)
        };
        if err <= 1.0 {
            // Outputs in (t, t1]: cubic Hermite on the displacement rows (x' = v exactly).
            while next_out < times.len() && times[next_out] <= t1 * (1.0 + 1e-13) {
                let th = ((times[next_out] - t) / step).clamp(0.0, 1.0);
                let (h00, h10) = (
                    2.0 * th.powi(3) - 3.0 * th * th + 1.0,
                    th.powi(3) - 2.0 * th * th + th,
                );
                let (h01, h11) = (-2.0 * th.powi(3) + 3.0 * th * th, th.powi(3) - th * th);
                for (hist, w) in histories.iter_mut().zip(out) {
                    hist[next_out] = observed(w, &z, n) * h00
                        + observed(w, &f_n, n) * (h10 * step)
                        + observed(w, &z1, n) * h01
                        + observed(w, &f1, n) * (h11 * step);
                }
                next_out += 1;
                control.advance(1);
            }
            t = t1;
            z = z1;
            steps += 1;
            f_n = if landing {
                // Restart after a jump with the loads from the right.
                let mut f = apply(state, speed(t), &z);
                for (fi, bi) in f.iter_mut().zip(forcing.b(t, false)) {
                    *fi += bi;
                }
                f
            } else {
                f1
            };
            // Keep h (and its LU) unless the change is worth a refactorisation.
            if !(1.0..1.5).contains(&ratio) {
                h *= ratio;
            }
        } else {
            h = step * ratio.min(0.9);
        }
        if h < 1e-14 * t.max(1e-3) {
            return Err(TimeError::StepTooSmall(t));
        }
    }
    Ok(TimeResult {
        time: times,
        nodes: spec.nodes.iter().cloned().zip(histories).collect(),
        method: Method::Implicit,
        steps,
        states: size,
        train: None,
    })
}
