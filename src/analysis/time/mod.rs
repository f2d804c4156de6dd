//! Time response: `z' = A(Omega(t)) z + B F(t)`, `z = [v, x, y]`, from rest.
//!
//! Loads, in complex coordinates on node translations:
//! - nonrotating forces `F(t) e^{i direction}`, `F` piecewise linear;
//! - unbalances `m e (Omega^2 - i Omega') e^{i (theta(t) + phase)}` from their `from` time, with
//!   `theta = int_0^t Omega` (the centrifugal force and the angular-acceleration term).
//!
//! At constant speed the system is linear time-invariant and [`exact`] solves it in closed form
//! from one eigendecomposition (modal superposition: piecewise-linear forces and harmonic
//! unbalance have exact modal responses), sampled at the output times. With a varying speed,
//! [`implicit`] integrates with TR-BDF2: L-stable, so the internal poles of the nonviscous
//! model (down to -3e4 1/s in Example 1) cost no accuracy and no tiny steps.
//! The hysteretic model is defined for harmonic motion only and has no time response.

pub mod exact;
pub mod implicit;

use super::control::{Cancelled, Control};
use crate::damping::state::StateModel;
use crate::damping::{DampedModel, ModelKind};
use crate::linalg::{self, CMat, LinalgError, c64};
pub use crate::model::loads::{SpeedLaw, TimeSpec};
use crate::system::{DofKind, RotorSystem};
use crate::system::{Layout, Realized};

/// How the response was computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    Exact,
    Implicit,
}

/// Complex displacement `x + i y` of each reported node at the output times.
#[derive(Debug, Clone)]
pub struct TimeResult {
    pub time: Vec<f64>,
    pub nodes: Vec<(usize, Vec<c64>)>,
    pub method: Method,
    pub steps: usize,
    pub states: usize,
}

#[derive(Debug, Clone, PartialEq)]
pub enum TimeError {
    /// The hysteretic model has no time-domain form.
    Hysteretic,
    Linalg(LinalgError),
    /// The integration needed more steps than allowed.
    TooManySteps(usize),
    /// The step size fell below round-off.
    StepTooSmall(f64),
    /// The response left floating point range (an unstable rotor over a long time).
    Overflow,
    Cancelled,
}

impl std::fmt::Display for TimeError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Hysteretic => write!(
                f,
                "the hysteretic model is defined for harmonic motion only and cannot be \
                 integrated in time; use `nonviscous` (its time-domain model) or `equivalent`"
            ),
            Self::Linalg(e) => write!(f, "{e}"),
            Self::TooManySteps(n) => write!(
                f,
                "the integration needs more than {n} steps (WHIRL_MAX_STEPS): shorten the \
                 duration or loosen the tolerance"
            ),
            Self::StepTooSmall(t) => write!(f, "the step size fell below round-off at t = {t} s"),
            Self::Cancelled => write!(f, "cancelled"),
            Self::Overflow => write!(
                f,
                "the response grows beyond floating point range (the rotor is unstable at this \
                 speed): shorten the duration"
            ),
        }
    }
}

impl From<Cancelled> for TimeError {
    fn from(_: Cancelled) -> Self {
        Self::Cancelled
    }
}

impl From<LinalgError> for TimeError {
    fn from(e: LinalgError) -> Self {
        Self::Linalg(e)
    }
}

/// The loads as a right-hand side `b(t) = [M^-1 F(t); 0; 0]`. In doubled coordinates the
/// `conj r` rows carry the conjugate loads: a force `F e^{i theta}` there is `F e^{-i theta}`,
/// and an unbalance whirls the other way.
pub struct Forcing<'a> {
    spec: &'a TimeSpec,
    /// Degree of freedom of each force, then of each unbalance.
    force_dofs: Vec<usize>,
    unbalance_dofs: Vec<usize>,
    /// `M^-1`, `N x N`.
    m_inv: CMat,
    /// Rotor degrees of freedom `n` when doubled (`N = 2n`).
    doubled: Option<usize>,
    size: usize,
}

impl<'a> Forcing<'a> {
    pub fn new(system: &RotorSystem, spec: &'a TimeSpec, size: usize) -> Result<Self, LinalgError> {
        let r = Realized::at(system, spec.speed.omega(0.0));
        let big = r.size();
        let identity = CMat::from_fn(big, big, |i, j| {
            c64::new(if i == j { 1.0 } else { 0.0 }, 0.0)
        });
        Ok(Forcing {
            spec,
            force_dofs: spec
                .forces
                .iter()
                .map(|f| translation(system, f.node))
                .collect(),
            unbalance_dofs: spec
                .unbalances
                .iter()
                .map(|u| translation(system, u.node))
                .collect(),
            m_inv: linalg::mass_solve(&r.mass, &identity)?,
            doubled: (r.layout == Layout::Doubled).then_some(system.n()),
            size,
        })
    }

    /// `M^-1 f` for a load vector with a few nonzero entries.
    fn apply_m_inv(&self, f: &[(usize, c64)]) -> Vec<c64> {
        let n = self.m_inv.nrows();
        let mut b = vec![c64::new(0.0, 0.0); self.size];
        for &(j, fj) in f {
            if fj.re != 0.0 || fj.im != 0.0 {
                for (i, bi) in b.iter_mut().enumerate().take(n) {
                    *bi += self.m_inv[(i, j)] * fj;
                }
            }
        }
        b
    }

    /// A load `value` on the translation `dof` (and its conjugate on `conj r`).
    fn load(&self, dof: usize, value: c64, out: &mut Vec<(usize, c64)>) {
        out.push((dof, value));
        if let Some(n) = self.doubled {
            out.push((n + dof, value.conj()));
        }
    }

    /// `b(t)`; `left`: the limit just before `t` (at the end of a step landing on a jump).
    pub fn b(&self, t: f64, left: bool) -> Vec<c64> {
        let mut f = vec![];
        for (force, &dof) in self.spec.forces.iter().zip(&self.force_dofs) {
            let v = if left {
                force.history.left_value(t)
            } else {
                force.history.value(t)
            };
            self.load(dof, c64::from_polar(v, force.direction), &mut f);
        }
        let sp = &self.spec.speed;
        for (u, &dof) in self.spec.unbalances.iter().zip(&self.unbalance_dofs) {
            let on = if left { t > u.from } else { t >= u.from };
            if on {
                let (w, a) = (sp.omega(t), sp.accel(t, left));
                let rot = c64::from_polar(1.0, sp.angle(t) + u.phase);
                self.load(dof, c64::new(w * w, -a) * rot * u.amount, &mut f);
            }
        }
        self.apply_m_inv(&f)
    }

    /// `B` of a unit force on `dof` in the direction `angle` (both rows when doubled).
    pub fn force_column(&self, dof: usize, angle: f64) -> Vec<c64> {
        let mut f = vec![];
        self.load(dof, c64::from_polar(1.0, angle), &mut f);
        self.apply_m_inv(&f)
    }

    /// `B` of a unit unbalance on `dof` at `phase`: one column per direction of whirl it
    /// drives, with that direction (+1 on `r`, -1 on `conj r`).
    pub fn unbalance_columns(&self, dof: usize, phase: f64) -> Vec<(Vec<c64>, f64)> {
        let mut out = vec![(self.apply_m_inv(&[(dof, c64::from_polar(1.0, phase))]), 1.0)];
        if let Some(n) = self.doubled {
            out.push((
                self.apply_m_inv(&[(n + dof, c64::from_polar(1.0, -phase))]),
                -1.0,
            ));
        }
        out
    }

    /// Times where a load or the speed law changes value or slope.
    pub fn breakpoints(&self) -> Vec<f64> {
        let mut t: Vec<f64> = vec![];
        for f in &self.spec.forces {
            t.extend(f.history.breakpoints());
        }
        t.extend(self.spec.unbalances.iter().map(|u| u.from));
        if let SpeedLaw::Profile(p) = &self.spec.speed {
            t.extend(p.breakpoints());
        }
        t.retain(|&x| x > 0.0 && x < self.spec.duration);
        t.sort_by(f64::total_cmp);
        t.dedup();
        t
    }
}

/// The translation degree of freedom of a node (validated to exist).
pub fn translation(system: &RotorSystem, node: usize) -> usize {
    system
        .dofs
        .iter()
        .position(|d| d.node == node && d.kind == DofKind::Translation)
        .expect("validated: every reported or loaded node has a translation")
}

/// Time response of `model` (exact at constant speed unless `implicit` is forced).
/// Progress is counted in output samples; the exact method checks for cancellation between
/// samples, the implicit one every few steps.
pub fn time_response(
    system: &RotorSystem,
    model: &DampedModel,
    spec: &TimeSpec,
    force_implicit: bool,
    control: &Control,
) -> Result<TimeResult, TimeError> {
    control.expect(spec.output_times().len() as u64);
    let ModelKind::Linear(state) = &model.kind else {
        return Err(TimeError::Hysteretic);
    };
    let forcing = Forcing::new(system, spec, state.size())?;
    let out: Vec<usize> = spec.nodes.iter().map(|&n| translation(system, n)).collect();
    if let (Some(w), false) = (spec.speed.constant(), force_implicit) {
        match exact::solve(state, w, &forcing, spec, &out, control) {
            Ok(r) => return finite(r),
            Err(TimeError::Cancelled) => return Err(TimeError::Cancelled),
            Err(_) => {} // a nearly defective state matrix: integrate instead
        }
    }
    finite(implicit::solve(state, &forcing, spec, &out, control)?)
}

/// No NaN or infinity leaves: an overflowing response is an error with its reason.
fn finite(r: TimeResult) -> Result<TimeResult, TimeError> {
    let ok = r
        .nodes
        .iter()
        .all(|(_, h)| h.iter().all(|z| z.re.is_finite() && z.im.is_finite()));
    if ok { Ok(r) } else { Err(TimeError::Overflow) }
}

/// Displacement rows of the reported degrees of freedom in the state.
fn rows(state: &StateModel, out: &[usize]) -> Vec<usize> {
    out.iter().map(|d| state.n() + d).collect()
}
