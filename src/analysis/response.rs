//! Harmonic responses (unbalance, frequency response) on a checked modal reduction.
//!
//! A steady response up to a frequency `w_b` is carried by the modes below it; the modes above
//! respond quasi-statically. Projected on the lowest undamped modes with `w_k <= 2 w_b`, their
//! static corrections (gyroscopic, damping and loss couplings, as for the Campbell diagram) and
//! the static responses to unit loads where the forces act, where the supports and
//! nonrotating dampers act, and at the outputs (residual flexibility: the forcing and the
//! observation are then exact at zero frequency, and the output error is second order in the
//! basis error), each frequency costs one solve of the reduced size instead of the full one.
//!
//! The reduction is checked, not assumed: at the band's edges (the lowest and highest loaded
//! frequency) the reduced response at every output is compared with the full model's, and
//! after the sweep again at its largest response (where a pole's error is amplified most);
//! the band widens by half until the largest difference is within [`TOLERANCE`] of the largest
//! response compared, or the full model is solved when no basis at least halves the state.
//! What was solved is reported ([`ResponseReduction`]). Where the outputs' static responses
//! keep every basis from halving the state (outputs at every node), the outputs are read off a
//! basis corrected at the loads and supports only, under the same check.
//!
//! A large rotor's viscous or hysteretic model held sparse ([`Full::Sparse`]) is not reduced:
//! each frequency is one sparse factor of `Z(i omega)`, exact and linear in the mesh. So is a
//! rotor on supports over whirl frequency (`model::supports::grid`), whatever its size: each
//! frequency reads them at itself, which no reduction built once holds.

use super::AnalysisError;
use super::audit::frequency::{self, Harmonic, Orbit, Steady};
use super::reduction::with_supports;
use crate::damping::dampers::ModalDampers;
use crate::damping::{DampedModel, large};
use crate::fem::modal::ModalBasis;
use crate::linalg::sparse::LuPattern;
use crate::linalg::{RMat, c64};
use crate::model::damping::DampingModel;
use crate::system::RotorSystem;

mod sweeps;

pub use sweeps::{frequency_sweep, unbalance_force, unbalance_sweep};

/// Largest difference between the reduced and the full response allowed at a checked
/// frequency, relative to the largest response there: ten times below the 1e-6 the reduced
/// response is held to everywhere between the checked points (tests/it/response.rs).
pub const TOLERANCE: f64 = 1e-7;

/// How a harmonic response was reduced.
#[derive(Debug, Clone, PartialEq)]
pub struct ResponseReduction {
    /// Undamped modes retained.
    pub modes: usize,
    /// Size of the basis: the modes and their independent static corrections.
    pub vectors: usize,
    /// State size of each reduced solve (the second-order size for the hysteretic model).
    pub states: usize,
    /// State size of the full model.
    pub full_states: usize,
    /// Natural frequency of the highest retained mode, rad/s.
    pub band: f64,
    /// The frequencies (spin speeds for an unbalance response) at which the reduced response
    /// was compared with the full one.
    pub checked: Vec<f64>,
    /// Largest difference found there, relative to the largest response compared.
    pub max_relative_error: f64,
}

/// A rotor's harmonic responses: on a checked reduction, or on the full model.
pub struct Responses<'a> {
    system: &'a RotorSystem,
    full: Full<'a>,
    reduced: Option<Reduced>,
}

/// The full model of a harmonic response.
#[derive(Clone, Copy)]
pub enum Full<'a> {
    /// Dense, with the modal basis a reduction is drawn from.
    Dense(&'a DampedModel),
    /// The viscous or hysteretic model of a large rotor, held sparse: each frequency one
    /// sparse factor of `Z(i omega)` ([`large::Parts::steady`]), exact and linear in the
    /// mesh, so never reduced.
    Sparse(&'a Held),
}

/// A large rotor's damping model (viscous, hysteretic, or the equivalent and nonviscous
/// models' dampers on its lowest modes) and the pattern of its dynamic stiffness, analysed once.
pub struct Held {
    hysteretic: bool,
    pattern: LuPattern,
    dampers: Option<Box<ModalDampers>>,
}

impl Held {
    /// The model of responses up to `bound` rad/s (the equivalent and nonviscous models'
    /// dampers on the modes up to 16 times it, `damping::dampers`).
    pub fn new(
        system: &RotorSystem,
        damping: &DampingModel,
        bound: f64,
    ) -> Result<Self, AnalysisError> {
        let hysteretic = matches!(damping, DampingModel::Hysteretic);
        Ok(Held {
            hysteretic,
            pattern: large::parts_of(system, hysteretic, 0.0).pattern()?,
            dampers: super::large::dampers(system, damping, bound)?.map(Box::new),
        })
    }
}

/// What a [`Full`] borrows: a dense model, or a large rotor's [`Held`].
pub enum Owned {
    Dense(DampedModel),
    Sparse(Held),
}

impl Owned {
    pub fn full(&self) -> Full<'_> {
        match self {
            Owned::Dense(d) => Full::Dense(d),
            Owned::Sparse(h) => Full::Sparse(h),
        }
    }
}

impl<'a> From<&'a DampedModel> for Full<'a> {
    fn from(model: &'a DampedModel) -> Self {
        Full::Dense(model)
    }
}

struct Reduced {
    system: RotorSystem,
    model: DampedModel,
    /// The basis, `q = phi eta`.
    phi: RMat,
    info: ResponseReduction,
}

/// Orbits at the check points, flattened, from a model.
pub type Probe<'p> = dyn Fn(&Responses) -> Result<Vec<Orbit>, AnalysisError> + Sync + 'p;

impl<'a> Responses<'a> {
    /// The full model.
    pub fn full(system: &'a RotorSystem, full: impl Into<Full<'a>>) -> Self {
        Responses {
            system,
            full: full.into(),
            reduced: None,
        }
    }

    /// What was reduced; `None` on the full model.
    pub fn reduction(&self) -> Option<&ResponseReduction> {
        self.reduced.as_ref().map(|r| &r.info)
    }

    /// The reduction for responses below `bound` (rad/s) with forces and outputs on `dofs`,
    /// checked by `probe` at `checked` (the orbits at those points): the first basis whose
    /// probe is within [`TOLERANCE`] of the full model's; the full model if none at least
    /// halves the state (or `reduce` is false), or if it is held sparse.
    pub fn checked(
        system: &'a RotorSystem,
        damping: &DampingModel,
        full: impl Into<Full<'a>>,
        bound: f64,
        dofs: &[usize],
        checked: &[f64],
        probe: &Probe,
    ) -> Result<Self, AnalysisError> {
        match full.into() {
            Full::Dense(full) => {
                Self::widened(system, damping, full, bound, dofs, checked, probe, 0)
            }
            sparse => Ok(Self::full(system, sparse)),
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn widened(
        system: &'a RotorSystem,
        damping: &DampingModel,
        full: &'a DampedModel,
        bound: f64,
        dofs: &[usize],
        checked: &[f64],
        probe: &Probe,
        at_least: usize,
    ) -> Result<Self, AnalysisError> {
        let n = system.n();
        let whole = Self::full(system, full);
        if !(bound.is_finite() && bound > 0.0) {
            return Ok(whole);
        }
        let basis = &full.basis;
        let mut m = basis
            .omega
            .iter()
            .filter(|&&w| w <= 2.0 * bound)
            .count()
            .max(4)
            .max(at_least);
        let loads = with_supports(system, dofs);
        let candidate = |m: usize| -> Option<(ModalBasis, RotorSystem, DampedModel)> {
            let sub = basis.augmented_formed(system, m, &loads).ok()?;
            let reduced = sub.reduce(system);
            let model = DampedModel::build(&reduced, damping).ok()?;
            (2 * model.states() <= full.states()).then_some((sub, reduced, model))
        };
        if m >= n {
            return Ok(whole);
        }
        let (exact, first) = rayon::join(|| probe(&whole), || candidate(m));
        let exact = exact?;
        let scale = exact
            .iter()
            .map(|o| o.a.norm() + o.b.norm())
            .fold(0.0, f64::max);
        let mut current = first;
        // Widening the basis shrinks a truncation error; where two widenings in a row do not
        // halve it, the difference is a floor of the reduced model's round-off, not truncation
        // (held-out soft, heavily damped cross-coupled rotor on a basis with a tracked `K v`,
        // `ModalBasis::augmented_formed`: 1.71e-7 at 4 modes, 1.75e-7 at 6, 1.83e-7 at 9), and
        // no wider basis will pass: the full model is solved without trying them.
        let (mut best, mut stalled) = (f64::INFINITY, 0);
        while let Some((sub, reduced, model)) = current {
            let states = model.states();
            let mut r = Responses {
                system,
                full: Full::Dense(full),
                reduced: Some(Reduced {
                    system: reduced,
                    model,
                    phi: sub.phi.clone(),
                    info: ResponseReduction {
                        modes: m,
                        vectors: sub.len(),
                        states,
                        full_states: full.states(),
                        band: basis.omega[m - 1],
                        checked: checked.to_vec(),
                        max_relative_error: 0.0,
                    },
                }),
            };
            let approx = probe(&r)?;
            let error = difference(&exact, &approx, scale);
            if error <= TOLERANCE {
                if let Some(red) = r.reduced.as_mut() {
                    red.info.max_relative_error = error;
                }
                return Ok(r);
            }
            stalled = if error > 0.5 * best { stalled + 1 } else { 0 };
            best = best.min(error);
            if stalled >= 2 {
                break;
            }
            m = (3 * m).div_ceil(2);
            current = if m < n { candidate(m) } else { None };
        }
        Ok(whole)
    }

    /// This reduction checked again at `more` points (`probe` covering the old and new
    /// ones), widened from its band if that fails.
    pub fn rechecked(
        self,
        damping: &DampingModel,
        bound: f64,
        dofs: &[usize],
        more: &[f64],
        probe: &Probe,
    ) -> Result<Self, AnalysisError> {
        let (Some(r), Full::Dense(full)) = (&self.reduced, self.full) else {
            return Ok(self);
        };
        let mut checked = r.info.checked.clone();
        checked.extend(more);
        let whole = Self::full(self.system, full);
        let (exact, approx) = rayon::join(|| probe(&whole), || probe(&self));
        let (exact, approx) = (exact?, approx?);
        let scale = exact
            .iter()
            .map(|o| o.a.norm() + o.b.norm())
            .fold(0.0, f64::max);
        let error = difference(&exact, &approx, scale);
        if error <= TOLERANCE {
            let mut s = self;
            if let Some(red) = s.reduced.as_mut() {
                red.info.checked = checked;
                red.info.max_relative_error = red.info.max_relative_error.max(error);
            }
            return Ok(s);
        }
        let at_least = (3 * r.info.modes).div_ceil(2);
        Self::widened(
            self.system,
            damping,
            full,
            bound,
            dofs,
            &checked,
            probe,
            at_least,
        )
    }

    /// The model's state at `speed`, shared by every frequency solved there.
    pub fn at(&self, speed: f64) -> At<'_> {
        let dense = |steady| Solver::Dense(Box::new(steady));
        match (&self.reduced, self.full) {
            (Some(r), _) => At {
                solver: dense(Steady::at(&r.system, &r.model, speed)),
                phi: Some(&r.phi),
            },
            (None, Full::Dense(full)) => At {
                solver: dense(Steady::at(self.system, full, speed)),
                phi: None,
            },
            (None, Full::Sparse(held)) => At {
                solver: Solver::Sparse {
                    pattern: &held.pattern,
                    hysteretic: held.hysteretic,
                    parts: large::parts_of(self.system, held.hysteretic, speed),
                    terms: held.dampers.as_ref().map(|d| d.at(self.system, speed)),
                    speed,
                    system: self.system,
                },
                phi: None,
            },
        }
    }

    /// The steady orbit of every degree of freedom in `out` under `force` at `omega`, the
    /// rotor spun at `speed`.
    pub fn orbits(
        &self,
        speed: f64,
        omega: f64,
        force: &Harmonic,
        out: &[usize],
    ) -> Result<Vec<Orbit>, AnalysisError> {
        self.at(speed).orbits(omega, force, out)
    }
}

/// A model at one spin speed.
pub struct At<'r> {
    solver: Solver<'r>,
    phi: Option<&'r RMat>,
}

enum Solver<'r> {
    Dense(Box<Steady>),
    Sparse {
        /// At `speed`; for supports over whirl frequency rebuilt at each frequency solved.
        parts: large::Parts,
        hysteretic: bool,
        pattern: &'r LuPattern,
        terms: Option<std::sync::Arc<large::Terms>>,
        speed: f64,
        system: &'r RotorSystem,
    },
}

impl At<'_> {
    /// The steady orbit of every degree of freedom in `out` (physical coordinates) under
    /// `force` (physical coordinates) at `omega`.
    pub fn orbits(
        &self,
        omega: f64,
        force: &Harmonic,
        out: &[usize],
    ) -> Result<Vec<Orbit>, AnalysisError> {
        let Some(phi) = self.phi else {
            let (a, b) = self.amplitudes(omega, force)?;
            return Ok(out.iter().map(|&d| Orbit { a: a[d], b: b[d] }).collect());
        };
        let k = phi.ncols();
        // `Phi^T f`, over the loaded coordinates only.
        let project = |f: &[c64]| -> Vec<c64> {
            let mut out = vec![c64::new(0.0, 0.0); k];
            for (i, fi) in f.iter().enumerate().filter(|(_, f)| f.norm() != 0.0) {
                for (j, o) in out.iter_mut().enumerate() {
                    *o += fi * phi[(i, j)];
                }
            }
            out
        };
        let reduced = Harmonic {
            forward: project(&force.forward),
            backward: project(&force.backward),
        };
        let (a, b) = self.amplitudes(omega, &reduced)?;
        let row = |d: usize, v: &[c64]| -> c64 { (0..k).map(|j| v[j] * phi[(d, j)]).sum() };
        Ok(out
            .iter()
            .map(|&d| Orbit {
                a: row(d, &a),
                b: row(d, &b),
            })
            .collect())
    }
}

impl At<'_> {
    /// The forward and backward amplitudes of every coordinate solved (modal on a reduction).
    fn amplitudes(
        &self,
        omega: f64,
        force: &Harmonic,
    ) -> Result<(Vec<c64>, Vec<c64>), AnalysisError> {
        match &self.solver {
            Solver::Dense(steady) => steady.amplitudes(omega, force),
            Solver::Sparse {
                parts,
                hysteretic,
                pattern,
                terms,
                speed,
                system,
            } => frequency::amplitudes(system.n(), system.layout(), omega, force, |l, rhs| {
                // Supports over whirl frequency read at the excitation's (exact: a harmonic
                // response whirls at the frequency it is driven at).
                let read;
                let parts = match system.frequency_dependent() {
                    true => {
                        read = large::parts_read(system, *hysteretic, *speed, Some(l));
                        &read
                    }
                    false => parts,
                };
                Ok(parts.steady(pattern, l, *speed, rhs, terms.as_ref())?)
            }),
        }
    }
}

/// Largest `|a - a'| + |b - b'|` over the orbits, relative to `scale`.
fn difference(exact: &[Orbit], approx: &[Orbit], scale: f64) -> f64 {
    if exact.len() != approx.len() {
        return f64::INFINITY;
    }
    let worst = exact
        .iter()
        .zip(approx)
        .map(|(e, a)| (e.a - a.a).norm() + (e.b - a.b).norm())
        .fold(0.0, f64::max);
    if worst == 0.0 {
        0.0
    } else {
        worst / scale.max(f64::MIN_POSITIVE)
    }
}
