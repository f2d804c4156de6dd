//! Steady harmonic response at a fixed spin speed: the non-synchronous transfer function.
//!
//! A nonrotating force on the translations `r = x + i y` at frequency `omega > 0` has a
//! forward and a backward circular part, `f_r(t) = F e^{i omega t} + G e^{-i omega t}` (a force
//! `cos(omega t)` along the angle `theta` has `F = G = e^{i theta} / 2`). The response of the
//! rotor spun at `Omega` is `r(t) = a e^{i omega t} + conj(b) e^{-i omega t}`:
//!
//! - in the coordinates `r` (isotropic supports) the two parts do not couple: `a` solves
//!   `D(omega) a = F` and `conj b` solves `D(-omega) conj b = G`;
//! - in the doubled coordinates `(r, conj r)` one solve at `+omega` gives both, with `F` on the
//!   `r` rows and `conj G` on the `conj r` rows (the conjugate equation at `+omega`).
//!
//! `D(lambda) = -lambda^2 M + i lambda (C_n + C_r) + lambda Omega S G + K - i Omega S C_r`
//! plus the damping model: the state matrix `A(Omega)` for the linear models
//! (`(i lambda - A) Z = B f`), and for the hysteretic model `i sgn(lambda) K''_n` and
//! `i sgn(lambda - Omega) K''_r` on the `r` rows, `i sgn(lambda + Omega) K''_r` on the `conj r`
//! rows (there the rotor sees `-lambda - Omega`, conjugated). The hysteretic model is the
//! frequency-domain model, so it is exact here; `sgn 0 = 0` at `lambda = Omega` (see
//! `unbalance`).
//!
//! Then `x(t) = Re(X e^{i omega t})`, `y(t) = Re(Y e^{i omega t})` with `X = a + b`,
//! `Y = -i (a - b)`.

use crate::analysis::AnalysisError;
use crate::analysis::control::Control;
use crate::damping::harmonic::Physical;
use crate::damping::{DampedModel, ModelKind};
use crate::linalg::{self, CMat, c64};
pub use crate::model::loads::Excitation;
use crate::system::{Layout, Realized, RotorSystem};
use rayon::prelude::*;
use std::sync::Arc;

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

/// The force: its forward and backward circular parts on each complex coordinate.
#[derive(Debug, Clone, PartialEq)]
pub struct Harmonic {
    pub forward: Vec<c64>,
    pub backward: Vec<c64>,
}

// `Excitation` is part of the validated request (`model::loads`); its force is solved for here.
impl Excitation {
    /// The unit force on degree of freedom `dof` of `n`.
    pub fn at(self, dof: usize, n: usize) -> Harmonic {
        let zero = c64::new(0.0, 0.0);
        let mut h = Harmonic {
            forward: vec![zero; n],
            backward: vec![zero; n],
        };
        match self {
            Excitation::Direction(t) => {
                h.forward[dof] = c64::from_polar(0.5, t);
                h.backward[dof] = c64::from_polar(0.5, t);
            }
            Excitation::Forward => h.forward[dof] = c64::new(1.0, 0.0),
            Excitation::Backward => h.backward[dof] = c64::new(1.0, 0.0),
        }
        h
    }
}

/// The rotor at one spin speed, with what every excitation frequency shares: the
/// second-order matrices (linear models with constant coefficients, `damping::harmonic`), the
/// state matrix `A(Omega)` (tabulated supports) or the realized rotor with its spun gyroscopic
/// and circulatory matrices (hysteretic).
pub(crate) struct Steady {
    n: usize,
    speed: f64,
    layout: Layout,
    parts: Parts,
}

enum Parts {
    Physical(Arc<Physical>),
    /// `A(Omega)` and the realized mass.
    Linear {
        a: CMat,
        mass: CMat,
    },
    Hysteretic {
        r: Box<Realized>,
        sg: CMat,
        scr: CMat,
    },
}

impl Steady {
    pub(crate) fn at(system: &RotorSystem, model: &DampedModel, speed: f64) -> Self {
        let parts = match &model.kind {
            ModelKind::Linear(state) => match state.physical() {
                Some(p) => Parts::Physical(p.clone()),
                None => Parts::Linear {
                    a: state.at(speed),
                    mass: Realized::at(system, speed).mass,
                },
            },
            ModelKind::Hysteretic(_) => {
                let r = Realized::at(system, speed);
                Parts::Hysteretic {
                    sg: r.spun(&r.gyroscopic),
                    scr: r.spun(&r.damping_rotating),
                    r: Box::new(r),
                }
            }
        };
        Steady {
            n: system.n(),
            speed,
            layout: system.layout(),
            parts,
        }
    }

    /// `Z` of `D(lambda) Z = rhs` on the model's coordinates (`rhs` of the model's physical
    /// size: `n`, or `2n` doubled).
    fn solve(&self, lambda: f64, rhs: &[c64]) -> Result<Vec<c64>, AnalysisError> {
        let speed = self.speed;
        let big = match self.layout {
            Layout::Single => self.n,
            Layout::Doubled => 2 * self.n,
        };
        let zero = c64::new(0.0, 0.0);
        let i1 = c64::new(0.0, 1.0);
        match &self.parts {
            Parts::Physical(physical) => {
                let lhs = physical.dynamic_stiffness(speed, i1 * lambda);
                let b = CMat::from_fn(big, 1, |i, _| rhs[i]);
                let z = linalg::solve_complex(&lhs, &b)?;
                Ok((0..big).map(|i| z[(i, 0)]).collect())
            }
            Parts::Linear { a, mass } => {
                let size = a.nrows();
                let lhs = CMat::from_fn(size, size, |i, j| {
                    let diag = if i == j { i1 * lambda } else { zero };
                    diag - a[(i, j)]
                });
                let fm = CMat::from_fn(big, 1, |i, _| rhs[i]);
                let minv_f = linalg::mass_solve(mass, &fm)?;
                let b = CMat::from_fn(size, 1, |i, _| if i < big { minv_f[(i, 0)] } else { zero });
                let z = linalg::solve_complex(&lhs, &b)?;
                Ok((0..big).map(|i| z[(big + i, 0)]).collect())
            }
            Parts::Hysteretic { r, sg, scr } => {
                let sgn = crate::damping::hysteretic::sign;
                let s_n = sgn(lambda);
                let lhs = CMat::from_fn(big, big, |a, b| {
                    let s_r = if r.spin[a] > 0.0 {
                        sgn(lambda - speed)
                    } else {
                        sgn(lambda + speed)
                    };
                    r.mass[(a, b)] * (-lambda * lambda)
                        + (r.damping_nonrotating[(a, b)] + r.damping_rotating[(a, b)])
                            * (i1 * lambda)
                        + sg[(a, b)] * (lambda * speed)
                        + r.stiffness[(a, b)]
                        - scr[(a, b)] * (i1 * speed)
                        + r.loss_nonrotating[(a, b)] * (i1 * s_n)
                        + r.loss_rotating[(a, b)] * (i1 * s_r)
                });
                let b = CMat::from_fn(big, 1, |i, _| rhs[i]);
                let z = linalg::solve_complex(&lhs, &b)?;
                Ok((0..big).map(|i| z[(i, 0)]).collect())
            }
        }
    }

    /// The steady orbit of every degree of freedom in `out` under `force` at `omega`.
    pub(crate) fn orbits(
        &self,
        omega: f64,
        force: &Harmonic,
        out: &[usize],
    ) -> Result<Vec<Orbit>, AnalysisError> {
        let (a, b) = self.amplitudes(omega, force)?;
        Ok(out.iter().map(|&d| Orbit { a: a[d], b: b[d] }).collect())
    }

    /// The forward and backward amplitudes `(a, b)` of every degree of freedom under `force`
    /// at `omega`.
    pub(crate) fn amplitudes(
        &self,
        omega: f64,
        force: &Harmonic,
    ) -> Result<(Vec<c64>, Vec<c64>), AnalysisError> {
        amplitudes(self.n, self.layout, omega, force, |l, rhs| {
            self.solve(l, rhs)
        })
    }
}

/// The forward and backward amplitudes `(a, b)` of the `n` degrees of freedom of a rotor in
/// `layout` under `force` at `omega`, from `solve(lambda, rhs)`, the solution `Z` of
/// `D(lambda) Z = rhs` (see the module docs).
pub(crate) fn amplitudes(
    n: usize,
    layout: Layout,
    omega: f64,
    force: &Harmonic,
    solve: impl Fn(f64, &[c64]) -> Result<Vec<c64>, AnalysisError>,
) -> Result<(Vec<c64>, Vec<c64>), AnalysisError> {
    let zero = c64::new(0.0, 0.0);
    let any = |v: &[c64]| v.iter().any(|x| *x != zero);
    Ok(match layout {
        Layout::Doubled => {
            let rhs: Vec<c64> = force
                .forward
                .iter()
                .copied()
                .chain(force.backward.iter().map(|g| g.conj()))
                .collect();
            let z = solve(omega, &rhs)?;
            (z[..n].to_vec(), z[n..2 * n].to_vec())
        }
        Layout::Single => {
            let a = if any(&force.forward) {
                solve(omega, &force.forward)?
            } else {
                vec![zero; n]
            };
            let b = if any(&force.backward) {
                // `conj b` solves the equation at `-omega`.
                solve(-omega, &force.backward)?
                    .iter()
                    .map(|c| c.conj())
                    .collect()
            } else {
                vec![zero; n]
            };
            (a, b)
        }
    })
}

/// The steady orbit of every degree of freedom in `out` under `force` at `omega` (> 0, or 0
/// for a static load), the rotor spun at `speed`.
pub fn harmonic(
    system: &RotorSystem,
    model: &DampedModel,
    speed: f64,
    omega: f64,
    force: &Harmonic,
    out: &[usize],
) -> Result<Vec<Orbit>, AnalysisError> {
    Steady::at(system, model, speed).orbits(omega, force, out)
}

/// The orbit at `output` per unit force at `input` at each of `frequencies`.
pub fn frequency_response(
    system: &RotorSystem,
    model: &DampedModel,
    speed: f64,
    input: (usize, Excitation),
    output: usize,
    frequencies: &[f64],
    control: &Control,
) -> Result<Vec<Orbit>, AnalysisError> {
    let force = input.1.at(input.0, system.n());
    // The spun matrices once: only the excitation frequency changes.
    let steady = Steady::at(system, model, speed);
    control.expect(frequencies.len() as u64);
    frequencies
        .par_iter()
        .map(|&w| {
            control.check()?;
            let o = steady.orbits(w, &force, &[output])?;
            control.advance(1);
            Ok(o[0])
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::api::{DampingInput, JeffcottInput, NonviscousInput};
    use crate::model::damping::DampingModel;
    use crate::model::rotor::Jeffcott;

    /// The second-order solve equals the whole first-order system's,
    /// `(i lambda I - A) [v; x; y] = [M^-1 f; 0; 0]`, on a model with internal coordinates
    /// (a nonviscous Jeffcott rotor: m = 2 kg, k = 8 N/m, loss factors 0.02 / 0.05).
    #[test]
    fn second_order_solve_is_the_first_order_one() {
        let input = JeffcottInput {
            mass: 2.0,
            stiffness: 8.0,
            loss_factor_rotating: 0.02,
            loss_factor_nonrotating: 0.05,
            damping_rotating: 0.1,
            damping_nonrotating: 0.3,
        };
        let system = RotorSystem::jeffcott(&Jeffcott::parse(&input, "rotor").unwrap());
        let damping = DampingInput::Nonviscous(NonviscousInput::default());
        let model = DampingModel::parse(&damping, Some(system.n())).unwrap();
        let full = DampedModel::build(&system, &model).unwrap();
        let ModelKind::Linear(state) = &full.kind else {
            panic!("the nonviscous model is linear")
        };
        assert!(state.p() > 0);
        let speed = 1.3;
        let steady = Steady::at(&system, &full, speed);
        assert!(matches!(steady.parts, Parts::Physical(_)));
        let a = state.at(speed);
        let (size, big) = (a.nrows(), system.n());
        let f = [c64::new(0.7, -0.2)];
        let minv_f = f[0] / 2.0;
        for lambda in [0.4, 1.9, 2.2, -1.5] {
            let z = steady.solve(lambda, &f).unwrap();
            let lhs = CMat::from_fn(size, size, |i, j| {
                let diag = if i == j {
                    c64::new(0.0, lambda)
                } else {
                    c64::new(0.0, 0.0)
                };
                diag - a[(i, j)]
            });
            let b = CMat::from_fn(
                size,
                1,
                |i, _| if i < big { minv_f } else { c64::new(0.0, 0.0) },
            );
            let whole = linalg::solve_complex(&lhs, &b).unwrap();
            let x = whole[(big, 0)];
            assert!(
                (z[0] - x).norm() <= 1e-13 * x.norm(),
                "{lambda}: {:?} vs {x:?}",
                z[0]
            );
        }
    }
}
