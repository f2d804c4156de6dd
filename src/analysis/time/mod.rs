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

pub mod conjugate;
mod etd;
pub mod exact;
pub mod exponential;
pub mod fit_poles;
pub mod implicit;
pub mod reduced;

use super::control::{Cancelled, Control};
use crate::damping::{DampedModel, ModelKind};
use crate::linalg::{self, CMat, LinalgError, RMat, c64};
pub use crate::model::loads::{SpeedLaw, TimeSpec};
use crate::system::RotorSystem;
use crate::system::{Layout, Realized};

/// How the response was computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    Exact,
    Implicit,
    /// ETD-RK4 on a small state ([`exponential`]).
    Exponential,
}

/// Complex displacement `x + i y` of each reported node at the output times.
#[derive(Debug, Clone)]
pub struct TimeResult {
    pub time: Vec<f64>,
    pub nodes: Vec<(usize, Vec<c64>)>,
    pub method: Method,
    pub steps: usize,
    pub states: usize,
    /// A torsional or axial response's rigid motion and element loads.
    pub train: Option<Box<TrainHistory>>,
}

/// What a torsional or axial response adds: the rigid motion of a free train (the first
/// node's position and rate at each output time) and each element's load history.
#[derive(Debug, Clone, Default)]
pub struct TrainHistory {
    pub rigid: Option<(Vec<f64>, Vec<f64>)>,
    pub elements: Vec<crate::analysis::shaft_loads::ElementHistory>,
    pub warnings: Vec<String>,
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

/// The coordinates a time response is solved in, and how the physical ones map to them:
/// the rotor's own (`q`), or a modal reduction `q = Phi eta` (loads projected by `Phi^T`,
/// outputs recovered by `Phi`).
pub struct Coordinates<'a> {
    /// The system as assembled (its nodes and translations).
    pub physical: &'a RotorSystem,
    /// The system solved.
    pub solved: &'a RotorSystem,
    /// `Phi` when reduced.
    pub basis: Option<&'a RMat>,
    /// The state entries whose error the integrator controls (all when `None`).
    pub slow: Option<Vec<bool>>,
}

impl Coordinates<'_> {
    /// The shape of a unit load on a node's translation in the solved coordinates (before
    /// `M^-1`; the `conj r` half is added by [`Forcing`]).
    fn load(&self, node: usize) -> Vec<f64> {
        let d = translation(self.physical, node);
        match self.basis {
            None => (0..self.solved.n())
                .map(|i| if i == d { 1.0 } else { 0.0 })
                .collect(),
            Some(phi) => (0..phi.ncols()).map(|k| phi[(d, k)]).collect(),
        }
    }

    /// Weights over the solved displacements that give a node's translation.
    pub fn observe(&self, node: usize) -> Vec<(usize, f64)> {
        let d = translation(self.physical, node);
        match self.basis {
            None => vec![(d, 1.0)],
            Some(phi) => (0..phi.ncols()).map(|k| (k, phi[(d, k)])).collect(),
        }
    }
}

/// The loads as a right-hand side `b(t) = [M^-1 F(t); 0; 0]`. In doubled coordinates the
/// `conj r` rows carry the conjugate loads: a force `F e^{i theta}` there is `F e^{-i theta}`,
/// and an unbalance whirls the other way.
pub struct Forcing<'a> {
    spec: &'a TimeSpec,
    /// Shape of each force, each generated torque, then of each unbalance, in the solved
    /// coordinates.
    force_shapes: Vec<Vec<f64>>,
    torque_shapes: Vec<Vec<f64>>,
    unbalance_shapes: Vec<Vec<f64>>,
    /// `M^-1`, `N x N`.
    m_inv: CMat,
    /// Rotor degrees of freedom `n` when doubled (`N = 2n`).
    doubled: Option<usize>,
    size: usize,
}

impl<'a> Forcing<'a> {
    pub fn new(c: &Coordinates, spec: &'a TimeSpec, size: usize) -> Result<Self, LinalgError> {
        let r = Realized::at(c.solved, spec.speed.omega(0.0));
        let big = r.size();
        let identity = CMat::from_fn(big, big, |i, j| {
            c64::new(if i == j { 1.0 } else { 0.0 }, 0.0)
        });
        Ok(Forcing {
            spec,
            force_shapes: spec.forces.iter().map(|f| c.load(f.node)).collect(),
            torque_shapes: (spec.generated.torques.iter())
                .map(|t| c.load(t.node))
                .collect(),
            unbalance_shapes: spec.unbalances.iter().map(|u| c.load(u.node)).collect(),
            m_inv: linalg::mass_solve(&r.mass, &identity)?,
            doubled: (r.layout == Layout::Doubled).then_some(c.solved.n()),
            size,
        })
    }

    /// `M^-1 f` for the load `value` times `shape` (and its conjugate on `conj r`).
    fn add_load(&self, shape: &[f64], value: c64, f: &mut [c64]) {
        for (i, &w) in shape.iter().enumerate() {
            if w != 0.0 {
                f[i] += value * w;
                if let Some(n) = self.doubled {
                    f[n + i] += value.conj() * w;
                }
            }
        }
    }

    /// `M^-1 f` over the state.
    fn apply_m_inv(&self, f: &[c64]) -> Vec<c64> {
        let n = self.m_inv.nrows();
        let mut b = vec![c64::new(0.0, 0.0); self.size];
        for (j, &fj) in f.iter().enumerate() {
            if fj.re != 0.0 || fj.im != 0.0 {
                for (i, bi) in b.iter_mut().enumerate().take(n) {
                    *bi += self.m_inv[(i, j)] * fj;
                }
            }
        }
        b
    }

    /// `b(t)`; `left`: the limit just before `t` (at the end of a step landing on a jump).
    pub fn b(&self, t: f64, left: bool) -> Vec<c64> {
        let mut f = vec![c64::new(0.0, 0.0); self.m_inv.nrows()];
        for (force, shape) in self.spec.forces.iter().zip(&self.force_shapes) {
            let v = if left {
                force.history.left_value(t)
            } else {
                force.history.value(t)
            };
            self.add_load(shape, c64::from_polar(v, force.direction), &mut f);
        }
        for (torque, shape) in self.spec.generated.torques.iter().zip(&self.torque_shapes) {
            self.add_load(shape, c64::new(torque.value(t, left), 0.0), &mut f);
        }
        let sp = &self.spec.speed;
        for (u, shape) in self.spec.unbalances.iter().zip(&self.unbalance_shapes) {
            let on = if left { t > u.from } else { t >= u.from };
            if on {
                let (w, a) = (sp.omega(t), sp.accel(t, left));
                let rot = c64::from_polar(1.0, sp.angle(t) + u.phase);
                self.add_load(shape, c64::new(w * w, -a) * rot * u.amount, &mut f);
            }
        }
        self.apply_m_inv(&f)
    }

    /// `B` of the unit force `k` in its direction (both rows when doubled).
    pub fn force_column(&self, k: usize) -> Vec<c64> {
        let dir = c64::from_polar(1.0, self.spec.forces[k].direction);
        self.unit_column(&self.force_shapes[k], dir)
    }

    /// `M^-1` of a unit load `value` on `shape`.
    fn unit_column(&self, shape: &[f64], value: c64) -> Vec<c64> {
        let mut f = vec![c64::new(0.0, 0.0); self.m_inv.nrows()];
        self.add_load(shape, value, &mut f);
        self.apply_m_inv(&f)
    }

    /// `B` of the unit unbalance `k` at its phase: one column per direction of whirl it
    /// drives, with that direction (+1 on `r`, -1 on `conj r`).
    pub fn unbalance_columns(&self, k: usize) -> Vec<(Vec<c64>, f64)> {
        let shape = &self.unbalance_shapes[k];
        let phase = c64::from_polar(1.0, self.spec.unbalances[k].phase);
        let n = self.m_inv.nrows();
        let mut f = vec![c64::new(0.0, 0.0); n];
        for (i, &w) in shape.iter().enumerate() {
            f[i] += phase * w;
        }
        let mut out = vec![(self.apply_m_inv(&f), 1.0)];
        if let Some(h) = self.doubled {
            let mut g = vec![c64::new(0.0, 0.0); n];
            for (i, &w) in shape.iter().enumerate() {
                g[h + i] += phase.conj() * w;
            }
            out.push((self.apply_m_inv(&g), -1.0));
        }
        out
    }

    /// The loads as fixed columns and coefficients, `b(t) = sum_j c_j(t) B_j`: the unit force
    /// `k` in its direction, the unit generated torques, then each unbalance's whirls
    /// ([`Self::unbalance_columns`]).
    pub fn columns(&self) -> LoadColumns {
        let mut cols: Vec<Vec<c64>> = (0..self.spec.forces.len())
            .map(|k| self.force_column(k))
            .collect();
        let one = c64::new(1.0, 0.0);
        cols.extend(self.torque_shapes.iter().map(|s| self.unit_column(s, one)));
        let mut whirls = vec![];
        for u in 0..self.spec.unbalances.len() {
            for (col, sense) in self.unbalance_columns(u) {
                whirls.push((u, cols.len(), sense));
                cols.push(col);
            }
        }
        LoadColumns { cols, whirls }
    }

    /// `c_j(t)` of [`Self::columns`] (`left`: the limit just before `t`), into `c`.
    pub fn coefficients(&self, columns: &LoadColumns, t: f64, left: bool, c: &mut [c64]) {
        for (ck, force) in c.iter_mut().zip(&self.spec.forces) {
            let v = if left {
                force.history.left_value(t)
            } else {
                force.history.value(t)
            };
            *ck = c64::new(v, 0.0);
        }
        let forces = self.spec.forces.len();
        for (k, torque) in self.spec.generated.torques.iter().enumerate() {
            c[forces + k] = c64::new(torque.value(t, left), 0.0);
        }
        let sp = &self.spec.speed;
        let (w, a, angle) = (sp.omega(t), sp.accel(t, left), sp.angle(t));
        for &(u, col, sense) in &columns.whirls {
            let ub = &self.spec.unbalances[u];
            let on = if left { t > ub.from } else { t >= ub.from };
            // m e (Omega^2 - i Omega') e^{i theta}, conjugated on the `conj r` rows.
            c[col] = if on {
                c64::new(w * w, -sense * a) * c64::from_polar(ub.amount, sense * angle)
            } else {
                c64::new(0.0, 0.0)
            };
        }
    }

    /// Times where a load or the speed law changes value or slope.
    pub fn breakpoints(&self) -> Vec<f64> {
        let mut t: Vec<f64> = vec![];
        for f in &self.spec.forces {
            t.extend(f.history.breakpoints());
        }
        t.extend(self.spec.unbalances.iter().map(|u| u.from));
        t.extend(
            self.spec
                .generated
                .torques
                .iter()
                .filter_map(|g| g.breakpoints()),
        );
        if let SpeedLaw::Profile(p) = &self.spec.speed {
            t.extend(p.breakpoints());
        }
        t.retain(|&x| x > 0.0 && x < self.spec.duration);
        t.sort_by(f64::total_cmp);
        t.dedup();
        t
    }
}

/// The loads of a [`Forcing`] as columns: `cols[j]` is `B_j`; `whirls` holds
/// `(unbalance, column, sense)`, the unbalance driving whirl at `sense Omega` through that column.
pub struct LoadColumns {
    pub cols: Vec<Vec<c64>>,
    pub whirls: Vec<(usize, usize, f64)>,
}

/// The degree of freedom a load at a node acts on (validated to exist): its translation, or its
/// twist or axial displacement in a torsional or axial system.
pub fn translation(system: &RotorSystem, node: usize) -> usize {
    system
        .translation(node)
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
    let c = Coordinates {
        physical: system,
        solved: system,
        basis: None,
        slow: None,
    };
    solve_in(&c, model, spec, force_implicit, control)
}

/// Time response in the coordinates `c` (the rotor's own, or a reduction of it).
pub fn solve_in(
    c: &Coordinates,
    model: &DampedModel,
    spec: &TimeSpec,
    force_implicit: bool,
    control: &Control,
) -> Result<TimeResult, TimeError> {
    control.expect(spec.output_times().len() as u64);
    let ModelKind::Linear(state) = &model.kind else {
        return Err(TimeError::Hysteretic);
    };
    let forcing = Forcing::new(c, spec, state.size())?;
    let out: Vec<Vec<(usize, f64)>> = spec.nodes.iter().map(|&n| c.observe(n)).collect();
    // Generated torques are not piecewise linear: stepped, not superposed.
    let exact = !force_implicit && spec.generated.torques.is_empty();
    if let (Some(w), true) = (spec.speed.constant(), exact) {
        match exact::solve(state, w, &forcing, spec, &out, control) {
            Ok(r) => return finite(r),
            Err(TimeError::Cancelled) => return Err(TimeError::Cancelled),
            Err(_) => {} // a nearly defective state matrix: integrate instead
        }
    }
    finite(implicit::solve(
        state,
        &forcing,
        spec,
        &out,
        c.slow.as_deref(),
        control,
    )?)
}

/// A varying speed on a small state in the coordinates `c`: the exponential integrator, or
/// TR-BDF2 where a stage's state matrix is too near defective to diagonalise.
pub fn solve_exponential(
    c: &Coordinates,
    model: &DampedModel,
    spec: &TimeSpec,
    control: &Control,
) -> Result<TimeResult, TimeError> {
    let ModelKind::Linear(state) = &model.kind else {
        return Err(TimeError::Hysteretic);
    };
    control.expect(spec.output_times().len() as u64);
    let forcing = Forcing::new(c, spec, state.size())?;
    let out: Vec<Vec<(usize, f64)>> = spec.nodes.iter().map(|&n| c.observe(n)).collect();
    // Doubled coordinates without internal ones or scheduled supports: one of each conjugate
    // pair of modal coordinates is integrated (`conjugate`).
    let pairing = match (model.layout, state.p(), state.schedule()) {
        (Layout::Doubled, 0, None) => conjugate::Pairing::doubled(state.n(), state.size()),
        _ => None,
    };
    match exponential::solve(state, &forcing, spec, &out, pairing.as_ref(), control) {
        Err(TimeError::Linalg(_)) => solve_in(c, model, spec, true, control),
        r => finite(r?),
    }
}

/// Errs where `V g = b` does not hold to 1e-9 of `b`: a state matrix too near defective for
/// its modal coordinates `g = V^-1 b` to mean anything (the caller integrates instead).
fn check_modal(v: &CMat, g: &CMat, b: &CMat) -> Result<(), TimeError> {
    let back = v * g;
    let (mut res, mut scale) = (0.0f64, 0.0f64);
    for i in 0..b.nrows() {
        for j in 0..b.ncols() {
            res = res.max((back[(i, j)] - b[(i, j)]).norm());
            scale = scale.max(b[(i, j)].norm());
        }
    }
    if res.is_nan() || res > 1e-9 * scale {
        return Err(TimeError::Linalg(LinalgError::NonFinite));
    }
    Ok(())
}

/// The rows of the eigenvectors `V` that give each output (weights `out` over the
/// displacements, rows `n..2n` of the state).
fn output_rows(v: &CMat, out: &[Vec<(usize, f64)>], n: usize) -> Vec<Vec<c64>> {
    out.iter()
        .map(|w| {
            (0..v.ncols())
                .map(|k| w.iter().map(|&(d, a)| v[(n + d, k)] * a).sum())
                .collect()
        })
        .collect()
}

/// The output of observation `w` from a state `z` (displacements at `n..2n`).
fn observed(w: &[(usize, f64)], z: &[c64], n: usize) -> c64 {
    w.iter().map(|&(k, a)| z[n + k] * a).sum()
}

/// No NaN or infinity leaves: an overflowing response is an error with its reason.
fn finite(r: TimeResult) -> Result<TimeResult, TimeError> {
    let ok = r
        .nodes
        .iter()
        .all(|(_, h)| h.iter().all(|z| z.re.is_finite() && z.im.is_finite()));
    if ok { Ok(r) } else { Err(TimeError::Overflow) }
}
