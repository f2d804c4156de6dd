//! An exponential integrator (ETD-RK4, Cox & Matthews 2002) for `z' = A(Omega(t)) z + b(t)`
//! on a small state: a run-up on a checked modal reduction.
//!
//! Time is cut into stages on which the speed is frozen for the linear part: with
//! `A_k = A(Omega_k) = V diag(lambda) V^-1` (`Omega_k` the speed at the stage's middle) and
//! `w = V^-1 z`,
//!
//! `w' = lambda w + N(t, w)`, `N = V^-1 (A(Omega(t)) - A_k) V w + V^-1 b(t)`.
//!
//! Every pole, however stiff or lightly damped, is then integrated exactly (`e^{lambda h}`),
//! and the step is held only by what `N` carries: the loads, which turn at the spin speed, and
//! the drift of the speed over the stage, a small coupling. Within a table segment
//! `A(w) = F0 + w F1 + w^2 F2` (see [`StateModel::speed_terms`]), so
//! `A(Omega) - A_k = (Omega - Omega_k) F1 + (Omega^2 - Omega_k^2) F2`; where `F1`, `F2` act on
//! few rows (the velocity rows of a viscous model), their modal forms are kept as the product
//! of two thin factors.
//!
//! One step of length `h` (all products elementwise in `lambda`, `z = lambda h`):
//! `a = e^{z/2} w + h/2 phi1(z/2) N(w, t)`, `b = e^{z/2} w + h/2 phi1(z/2) N(a, t + h/2)`,
//! `c = e^{z/2} a + h/2 phi1(z/2) (2 N(b, t + h/2) - N(w, t))`,
//! `w1 = e^z w + h [(phi1 - 3 phi2 + 4 phi3) N_w + (2 phi2 - 4 phi3) (N_a + N_b)
//! + (4 phi3 - phi2) N_c]`. Fourth order for the loads; exact for loads linear in time.
//!
//! In doubled coordinates (supports that are anisotropic or cross-coupled) a real motion's
//! modal coordinates pair as complex conjugates: the stage's eigenproblem is solved in real
//! form and one of each pair is integrated, the drift's product in real arithmetic
//! ([`super::conjugate`]; half the work of the complex state, to round-off the same answer).
//!
//! Steps land on every breakpoint of the loads, of the speed law and of the supports' table
//! (stages end there) and on the run's end (loads from the left); a step spans as many output
//! intervals as the step bound allows, the outputs inside by the dense output
//! ([`super::etd`]: `N` on the step as the quadratic through its values at the start, middle
//! and end, integrated exactly to each output; fourth order like the step, with `N` at the
//! middle taken from the scheme's own continuous extension and at the end from the new
//! state). The step is `h <= theta / max |Omega|` with `theta` from the tolerance (see
//! [`step_bound`]), and on each stage no longer than `theta` over the drift's coupling
//! (`Stage::step_bound`).

use super::conjugate::{Halves, Pairing};
use super::etd::{Coefficients, Dense, dense_at};
use super::{Forcing, Method, TimeError, TimeResult, TimeSpec};
use crate::analysis::control::Control;
use crate::damping::schedule::ModalSchedule;
use crate::damping::state::StateModel;
use crate::linalg::{self, CMat, RMat, c64};

/// The largest step for tolerance `tol`, over the fastest spin speed `w`: the loads turn by
/// `theta` radians a step ([`crate::model::loads::step_angle`], which the request's step
/// estimate uses too). ETD-RK4's error on a harmonic load goes as `theta^4`; `theta = 0.2`
/// at `tol = 1e-6` keeps the response within about `tol` of its peak (`tests/it/exponential.rs`:
/// 1.05e-6 from the closed form at constant speed, 1.0e-9 at `tol = 1e-9`).
pub fn step_bound(tol: f64, w: f64) -> f64 {
    crate::model::loads::step_angle(tol) / w.max(f64::MIN_POSITIVE)
}

/// `V^-1 F V` for the drift of the speed, applied as `y += f (V^-1 F V) x`: whole, as the
/// product of two thin factors where `F` has few rows that are not zero (the velocity rows of
/// a viscous model; the internal rows of a nonviscous one also turn with the speed), or, where
/// one of each conjugate pair is kept, in real arithmetic: with `w = u + i v` the kept
/// coordinates, `C_a w + C_b conj w = (C_a + C_b) u + i (C_a - C_b) v`, one real product of
/// twice the kept size (half the work of the complex product with every coordinate).
enum Coupling {
    Whole(CMat),
    /// `right`: `F`'s rows times `V` (`r x m`); `left`: the kept rows of `V^-1` at those rows.
    Thin {
        right: CMat,
        left: CMat,
    },
    /// `[Re y; Im y] = [[Re P, -Im Q], [Im P, Re Q]] [u; v]`.
    Paired(RMat),
}

/// Room for the products of [`Coupling::add_apply`].
#[derive(Default)]
struct Scratch {
    c: Vec<c64>,
    x: Vec<f64>,
    y: Vec<f64>,
}

impl Coupling {
    /// From `V^-1` (the kept rows), `F`, `V` and the kept coordinates.
    fn new(vinv: &CMat, f: &CMat, v: &CMat, halves: &Halves) -> Self {
        let (h, m) = (vinv.nrows(), f.nrows());
        let rows: Vec<usize> = (0..m)
            .filter(|&i| (0..m).any(|j| f[(i, j)] != c64::new(0.0, 0.0)))
            .collect();
        let f_rows = CMat::from_fn(rows.len(), m, |k, j| f[(rows[k], j)]);
        let fv = &f_rows * v;
        let left = CMat::from_fn(h, rows.len(), |i, k| vinv[(i, rows[k])]);
        if h < m {
            let whole = &left * &fv;
            let (mut p, mut q) = (CMat::zeros(h, h), CMat::zeros(h, h));
            for (j, &(k, conj)) in halves.full.iter().enumerate() {
                let sign = if conj { -1.0 } else { 1.0 };
                for i in 0..h {
                    p[(i, k)] += whole[(i, j)];
                    q[(i, k)] += whole[(i, j)] * sign;
                }
            }
            Coupling::Paired(RMat::from_fn(2 * h, 2 * h, |i, j| match (i < h, j < h) {
                (true, true) => p[(i, j)].re,
                (true, false) => -q[(i, j - h)].im,
                (false, true) => p[(i - h, j)].im,
                (false, false) => q[(i - h, j - h)].re,
            }))
        } else if rows.len() * (m + h) < h * m {
            Coupling::Thin { right: fv, left }
        } else {
            Coupling::Whole(&left * &fv)
        }
    }

    /// A bound on the product's norm (Frobenius norms).
    fn norm(&self) -> f64 {
        match self {
            Coupling::Whole(c) => c.norm_l2(),
            Coupling::Thin { right, left } => right.norm_l2() * left.norm_l2(),
            Coupling::Paired(r) => r.norm_l2(),
        }
    }

    /// `y += f C x`, `w` the kept coordinates and `full` all of them.
    fn add_apply(&self, w: &[c64], full: &[c64], f: f64, y: &mut [c64], s: &mut Scratch) {
        let fc = c64::new(f, 0.0);
        match self {
            Coupling::Whole(c) => linalg::add_matvec(y, c, full, fc),
            Coupling::Thin { right, left } => {
                s.c.clear();
                s.c.resize(right.nrows(), c64::new(0.0, 0.0));
                linalg::add_matvec(&mut s.c, right, full, fc);
                linalg::add_matvec(y, left, &s.c, c64::new(1.0, 0.0));
            }
            Coupling::Paired(r) => {
                let h = w.len();
                s.x.clear();
                s.x.extend(w.iter().map(|z| z.re));
                s.x.extend(w.iter().map(|z| z.im));
                s.y.clear();
                s.y.resize(2 * h, 0.0);
                linalg::add_matvec(&mut s.y, r, &s.x, f);
                for (i, yi) in y.iter_mut().enumerate() {
                    *yi += c64::new(s.y[i], s.y[h + i]);
                }
            }
        }
    }
}

/// One stage: the modal form of `A_k` and everything `N` needs in it, for the modal
/// coordinates integrated (`halves`: all, or one of each conjugate pair in doubled coordinates).
struct Stage<'a> {
    omega: f64,
    /// The eigenvalues of the kept coordinates.
    lambda: Vec<c64>,
    halves: Halves,
    v: CMat,
    /// The kept rows of `V^-1`.
    vinv: CMat,
    f1: Coupling,
    f2: Option<Coupling>,
    /// Supports on ROSS's curves: their change from the stage's speed.
    scheduled: Option<ModalSchedule<'a>>,
    /// `V^-1 B`, one column per load column.
    g: CMat,
    /// Rows of `V` of the outputs.
    rows: Vec<Vec<c64>>,
}

impl<'a> Stage<'a> {
    fn new(
        state: &'a StateModel,
        omega: f64,
        columns: &[Vec<c64>],
        out: &[Vec<(usize, f64)>],
        pairing: Option<&Pairing>,
    ) -> Result<Self, TimeError> {
        let (f1, f2) = state.speed_terms(omega);
        let size = state.size();
        let a = state.at(omega);
        let (e, halves) = match pairing.and_then(|p| p.eigen(&a)) {
            Some(r) => r?,
            None => (linalg::eigen(&a)?, Halves::all(size)),
        };
        let identity = CMat::from_fn(size, size, |i, j| {
            c64::new(if i == j { 1.0 } else { 0.0 }, 0.0)
        });
        let vinv = linalg::solve_complex(&e.vectors, &identity)?;
        let b = CMat::from_fn(size, columns.len(), |i, j| columns[j][i]);
        let g = &vinv * &b;
        super::check_modal(&e.vectors, &g, &b)?;
        let rows = super::output_rows(&e.vectors, out, state.n());
        let kept = &halves.kept;
        let vinv = CMat::from_fn(kept.len(), size, |k, j| vinv[(kept[k], j)]);
        let g = CMat::from_fn(kept.len(), g.ncols(), |k, j| g[(kept[k], j)]);
        Ok(Stage {
            omega,
            f1: Coupling::new(&vinv, &f1, &e.vectors, &halves),
            f2: f2
                .as_ref()
                .map(|f| Coupling::new(&vinv, f, &e.vectors, &halves)),
            scheduled: state.schedule().map(|s| s.modal(&vinv, &e.vectors, omega)),
            g,
            lambda: kept.iter().map(|&j| e.values[j]).collect(),
            halves,
            v: e.vectors,
            vinv,
            rows,
        })
    }
}

impl Stage<'_> {
    /// One output sample of the kept modal coordinates `w` on every output (`full`: room for
    /// all the modal coordinates).
    fn record(&self, w: &[c64], full: &mut [c64], histories: &mut [Vec<c64>]) {
        self.halves.expand(w, full);
        for (hist, row) in histories.iter_mut().zip(&self.rows) {
            hist.push(row.iter().zip(full.iter()).map(|(r, x)| r * x).sum());
        }
    }

    /// The step on this stage (grid points `span`): `h_loads`, the loads' bound, and no longer
    /// than the drift's coupling allows, `h |Omega - Omega_k| |C| <= theta` (the same angle:
    /// `N` carries the coupling as it carries the loads). On `benches/forced_ross.py`'s soft
    /// heavy cross-coupled rotor sampled every 1 ms, the run-up moved 5.6e-6 of its peak from
    /// a 20x finer step on the loads' bound alone, 1.3e-6 with this one.
    fn step_bound(
        &self,
        span: &[(f64, bool)],
        omega: impl Fn(f64) -> f64,
        h_loads: f64,
        tol: f64,
    ) -> f64 {
        let (mut d1, mut d2) = (0.0f64, 0.0f64);
        for &(t, _) in span {
            let w = omega(t);
            d1 = d1.max((w - self.omega).abs());
            d2 = d2.max((w * w - self.omega * self.omega).abs());
        }
        let rate = d1 * self.f1.norm() + self.f2.as_ref().map_or(0.0, |f| d2 * f.norm());
        h_loads.min(crate::model::loads::step_angle(tol) / rate.max(f64::MIN_POSITIVE))
    }
}

/// Integrates from rest; `out`: the weights of each output over the displacements.
pub fn solve(
    state: &StateModel,
    forcing: &Forcing,
    spec: &TimeSpec,
    out: &[Vec<(usize, f64)>],
    pairing: Option<&Pairing>,
    control: &Control,
) -> Result<TimeResult, TimeError> {
    let size = state.size();
    let times = spec.output_times();
    let columns = forcing.columns();
    let sp = &spec.speed;
    let (lo, hi) = sp.range(spec.duration);
    // The loads turn at the spin speed (unbalances) or at a generated torque's frequency.
    let fastest = lo.abs().max(hi.abs()).max(spec.generated.fastest());
    let h_max = step_bound(spec.tolerance, fastest);
    let hard = hard_breaks(state, forcing, spec);
    // The grid the steps land on: every output time and every breakpoint.
    let mut grid: Vec<(f64, bool)> = times.iter().map(|&t| (t, false)).collect();
    grid.extend(hard.iter().map(|&t| (t, true)));
    grid.sort_by(|a, b| a.0.total_cmp(&b.0).then(b.1.cmp(&a.1)));
    grid.dedup_by(|b, a| {
        let same = (b.0 - a.0).abs() <= 1e-12 * spec.duration;
        a.1 |= same && b.1;
        same
    });
    // The run ends at `duration`: its last step takes the loads there from the left (from the
    // right, a speed law's acceleration has ended, and with it an unbalance's `-i a Omega'`).
    if let Some(last) = grid.last_mut() {
        last.1 = true;
    }
    // A stage: at most this many steps (its eigensolve costs a few steps' work per state),
    // and a speed drift of at most 5% of the fastest speed where the supports change with the
    // speed (their change rides in `N`: at 20% a run-up on ROSS's interpolated fluid-film
    // tables moved 3.7e-6 of its peak against 7.9e-7 at 5%), 50% where only the gyroscopic
    // and rotating-damping terms do: `h |dOmega| |G| / |M|` stays below the step angle, and
    // three run-ups of `benches/forced_ross.py`'s rotors moved 4.8e-8, 4.1e-9 and 2.3e-9 of
    // their peaks from the 5% stages (4.8e-8, 4.1e-9, 5.6e-10 at 20%; Example 1's nonviscous
    // run-up 2.6e-7 at 20% or 5%, `tests/it/exponential.rs`). Output intervals longer than that
    // are cut, so that stages can end inside them.
    let steps_per_stage = 16 * size.max(8);
    let constant = state.schedule().is_none() && state.table_speeds().is_empty();
    let drift = if constant { 0.5 } else { 0.05 } * lo.abs().max(hi.abs());
    let grid = refine(
        &grid,
        |t| sp.omega(t),
        drift,
        steps_per_stage as f64 * h_max,
    );
    let mut histories = vec![Vec::with_capacity(times.len()); out.len()];
    for h in histories.iter_mut() {
        h.push(c64::new(0.0, 0.0)); // at rest
    }
    let mut next_out = 1;
    let mut z = vec![c64::new(0.0, 0.0); size];
    let mut steps = 0usize;
    let mut coefficients: Vec<(f64, Coefficients)> = vec![];
    let zeros = |len: usize| vec![c64::new(0.0, 0.0); len];
    let (mut c0, mut cm, mut c1) = (
        zeros(columns.cols.len()),
        zeros(columns.cols.len()),
        zeros(columns.cols.len()),
    );
    let (mut nw, mut na, mut nb, mut nc) = (vec![], vec![], vec![], vec![]);
    // The dense output's: `N` at a step's middle and end, the state at its start.
    let (mut nm, mut n1, mut w_start) = (vec![], vec![], vec![]);
    let mut dense: Vec<(f64, f64, Dense)> = vec![];
    let is_output = |x: f64, next: usize| {
        times
            .get(next)
            .is_some_and(|&to| (to - x).abs() <= 1e-12 * spec.duration)
    };
    let (mut a, mut b, mut cc) = (vec![], vec![], vec![]);
    let mut full = zeros(size);
    let mut tmp = Scratch::default();
    // The loads at a step's start are those at the last step's end (taken from the right),
    // across output times and stages: `c0` holds them at `c0_at`.
    let mut c0_at = f64::NAN;
    let mut g0 = 0;
    while g0 + 1 < grid.len() {
        control.check()?;
        // The stage: grid points g0..=g1, up to the next breakpoint.
        let (t0, w0) = (grid[g0].0, sp.omega(grid[g0].0));
        let mut g1 = g0 + 1;
        let mut count = substeps(grid[g1].0 - t0, h_max);
        while g1 + 1 < grid.len()
            && !grid[g1].1
            && count + substeps(grid[g1 + 1].0 - grid[g1].0, h_max) <= steps_per_stage
            && (sp.omega(grid[g1 + 1].0) - w0).abs() <= drift
        {
            count += substeps(grid[g1 + 1].0 - grid[g1].0, h_max);
            g1 += 1;
        }
        let omega = sp.omega(0.5 * (t0 + grid[g1].0));
        let stage = Stage::new(state, omega, &columns.cols, out, pairing)?;
        let h_max = stage.step_bound(&grid[g0..=g1], |t| sp.omega(t), h_max, spec.tolerance);
        coefficients.clear();
        dense.clear();
        // The kept modal coordinates (all, or one of each conjugate pair).
        let kept = stage.lambda.len();
        for buffer in [
            &mut nw,
            &mut na,
            &mut nb,
            &mut nc,
            &mut a,
            &mut b,
            &mut cc,
            &mut nm,
            &mut n1,
            &mut w_start,
        ] {
            buffer.clear();
            buffer.resize(kept, c64::new(0.0, 0.0));
        }
        let mut w: Vec<c64> = (0..kept)
            .map(|i| (0..size).map(|j| stage.vinv[(i, j)] * z[j]).sum())
            .collect();
        // `N(w)` at speed `om` with the loads' coefficients `c`, into `y` (`full`: room for
        // the full modal coordinates).
        let n_into =
            |w: &[c64], om: f64, c: &[c64], y: &mut [c64], tmp: &mut Scratch, full: &mut [c64]| {
                y.fill(c64::new(0.0, 0.0));
                stage.halves.expand(w, full);
                stage.f1.add_apply(w, full, om - stage.omega, y, tmp);
                if let Some(s) = &stage.scheduled {
                    s.add_apply(om, full, y);
                }
                if let Some(f2) = &stage.f2 {
                    f2.add_apply(w, full, om * om - stage.omega * stage.omega, y, tmp);
                }
                for (j, &cj) in c.iter().enumerate() {
                    if cj != c64::new(0.0, 0.0) {
                        for (yi, gi) in y.iter_mut().zip(stage.g.col(j).iter()) {
                            *yi += gi * cj;
                        }
                    }
                }
            };
        // `N(w)` at a step's start, when the last step left it (`N(t1, w1)` of a dense step).
        let mut nw_ready = false;
        let mut g = g0;
        while g < g1 {
            // One step across as many output intervals as the step bound allows (the outputs
            // inside by the dense output), else substeps of one interval.
            let ta = grid[g].0;
            let mut e = g + 1;
            while e < g1 && !grid[e].1 && grid[e + 1].0 - ta <= h_max * (1.0 + 1e-12) {
                e += 1;
            }
            let tb = grid[e].0;
            let k = substeps(tb - ta, h_max);
            let h = (tb - ta) / k as f64;
            // Output intervals differ in their last bits; a step within 1e-10 of one already
            // made reuses its coefficients (the state then lands within 1e-10 h of `tb`).
            let at = match coefficients
                .iter()
                .position(|(hh, _)| (hh - h).abs() <= 1e-10 * h)
            {
                Some(i) => i,
                None => {
                    coefficients.push((h, Coefficients::new(&stage.lambda, h)));
                    coefficients.len() - 1
                }
            };
            let co = &coefficients[at].1;
            let inside = e > g + 1 && (g + 1..e).any(|i| is_output(grid[i].0, next_out));
            for j in 0..k {
                let t = ta + j as f64 * h;
                let last = j + 1 == k;
                let t1 = if last { tb } else { t + h };
                // At the end of a step landing on a jump, the loads from the left.
                let left = last && grid[e].1;
                if c0_at != t {
                    forcing.coefficients(&columns, t, false, &mut c0);
                }
                let tm = t + 0.5 * h;
                forcing.coefficients(&columns, tm, false, &mut cm);
                forcing.coefficients(&columns, t1, left, &mut c1);
                let (om0, omm, om1) = (sp.omega(t), sp.omega(tm), sp.omega(t1));
                if !nw_ready {
                    n_into(&w, om0, &c0, &mut nw, &mut tmp, &mut full);
                }
                nw_ready = false;
                for i in 0..kept {
                    a[i] = co.e_half[i] * w[i] + co.p_half[i] * nw[i];
                }
                n_into(&a, omm, &cm, &mut na, &mut tmp, &mut full);
                for i in 0..kept {
                    b[i] = co.e_half[i] * w[i] + co.p_half[i] * na[i];
                }
                n_into(&b, omm, &cm, &mut nb, &mut tmp, &mut full);
                for i in 0..kept {
                    cc[i] = co.e_half[i] * a[i] + co.p_half[i] * (nb[i] * 2.0 - nw[i]);
                }
                n_into(&cc, om1, &c1, &mut nc, &mut tmp, &mut full);
                if inside {
                    w_start.clone_from(&w);
                }
                for i in 0..kept {
                    w[i] = co.e[i] * w[i]
                        + co.b1[i] * nw[i]
                        + co.b2[i] * (na[i] + nb[i])
                        + co.b4[i] * nc[i];
                }
                if inside {
                    // `N` at the step's middle from the scheme's own continuous extension,
                    // at its end from `w1`: the quadratic through `N(t, w)`, these two, is
                    // `N` to third order, so the outputs inside are fourth order like `w1`.
                    let half = dense_at(&mut dense, &stage.lambda, h, 0.5);
                    for i in 0..kept {
                        a[i] = half.e[i] * w_start[i]
                            + half.c0[i] * nw[i]
                            + half.cm[i] * 0.5 * (na[i] + nb[i])
                            + half.c1[i] * nc[i];
                    }
                    n_into(&a, omm, &cm, &mut nm, &mut tmp, &mut full);
                    n_into(&w, om1, &c1, &mut n1, &mut tmp, &mut full);
                    for &(ti, _) in &grid[g + 1..e] {
                        if !is_output(ti, next_out) {
                            continue;
                        }
                        let d = dense_at(&mut dense, &stage.lambda, h, (ti - t) / h);
                        for q in 0..kept {
                            b[q] = d.e[q] * w_start[q]
                                + d.c0[q] * nw[q]
                                + d.cm[q] * nm[q]
                                + d.c1[q] * n1[q];
                        }
                        stage.record(&b, &mut full, &mut histories);
                        next_out += 1;
                        control.advance(1);
                    }
                    if !left {
                        std::mem::swap(&mut nw, &mut n1);
                        nw_ready = true;
                    }
                }
                if !left {
                    std::mem::swap(&mut c0, &mut c1);
                    c0_at = t1;
                }
                steps += 1;
            }
            if is_output(tb, next_out) {
                stage.record(&w, &mut full, &mut histories);
                next_out += 1;
                control.advance(1);
            }
            if steps > spec.max_steps {
                return Err(TimeError::TooManySteps(spec.max_steps));
            }
            g = e;
        }
        stage.halves.expand(&w, &mut full);
        for (i, zi) in z.iter_mut().enumerate() {
            *zi = (0..size).map(|k| stage.v[(i, k)] * full[k]).sum();
        }
        if z.iter().any(|x| !(x.re.is_finite() && x.im.is_finite())) {
            return Err(TimeError::Overflow);
        }
        g0 = g1;
    }
    debug_assert!(histories.iter().all(|h| h.len() == times.len()));
    Ok(TimeResult {
        time: times,
        nodes: spec.nodes.iter().cloned().zip(histories).collect(),
        method: Method::Exponential,
        steps,
        states: size,
        train: None,
    })
}

/// `grid` with points added inside each interval (not outputs, not breakpoints) so that none
/// spans more than `drift` of speed (linear between grid points) or `span` of time.
fn refine(
    grid: &[(f64, bool)],
    omega: impl Fn(f64) -> f64,
    drift: f64,
    span: f64,
) -> Vec<(f64, bool)> {
    let mut out = Vec::with_capacity(grid.len());
    for pair in grid.windows(2) {
        let ((ta, _), (tb, _)) = (pair[0], pair[1]);
        out.push(pair[0]);
        let by_speed = if drift > 0.0 {
            ((omega(tb) - omega(ta)).abs() / drift).ceil()
        } else {
            1.0
        };
        let pieces = by_speed.max(((tb - ta) / span).ceil()).max(1.0) as usize;
        out.extend((1..pieces).map(|k| (ta + (tb - ta) * k as f64 / pieces as f64, false)));
    }
    out.extend(grid.last().copied());
    out
}

fn substeps(span: f64, h_max: f64) -> usize {
    ((span / h_max) * (1.0 - 1e-12)).ceil().max(1.0) as usize
}

/// Where a load or the speed law breaks, and where the speed crosses a table speed of the
/// supports (the state matrix's form changes there), inside `(0, duration)`.
fn hard_breaks(state: &StateModel, forcing: &Forcing, spec: &TimeSpec) -> Vec<f64> {
    let mut t = forcing.breakpoints();
    let table = state.table_speeds();
    if !table.is_empty() {
        let mut knots = vec![0.0];
        knots.extend(t.iter().copied());
        knots.push(spec.duration);
        for pair in knots.windows(2) {
            let (ta, tb) = (pair[0], pair[1]);
            let (wa, wb) = (spec.speed.omega(ta), spec.speed.omega(tb));
            for &p in &table {
                if (p - wa) * (p - wb) < 0.0 {
                    t.push(ta + (p - wa) / (wb - wa) * (tb - ta));
                }
            }
        }
    }
    t.retain(|&x| x > 0.0 && x < spec.duration);
    t.sort_by(f64::total_cmp);
    t.dedup();
    t
}
