//! From the second-order form to the first-order state matrix, with massless internal
//! coordinates eliminated by structure (MODEL.md section 4).
//!
//! Physical coordinates `x` (n, with mass), internal coordinates `y` (p, massless):
//!
//! ```text
//! M x'' + D(Omega) x' + (K(Omega) + U diag(nu k) U^H) x - U diag(k) y = F
//!                                   y' = (-d + i Omega rho) y + d (U^H x)
//! ```
//!
//! (`U diag(k)` is `W`, `U diag(nu k)` is `W_nu` in general: a support's branches, fitted to a
//! table over whirl frequency, push along `w_j` other than `u_j`, `system::SupportBranches`.)
//! The second line is the Maxwell branch `c_j (y_j' - i Omega rho_j y_j) + k_j (y_j - u_j^H x) = 0`
//! divided by `c_j = k_j / d_j` (`rho_j = 1` for a rotating branch on `r`, -1 for one on
//! `conj r` in doubled coordinates, 0 for a nonrotating one; `U` is real in the coordinates
//! `r` alone). With
//! `v = x'` the state `z = [v, x, y]` has `2n + p` entries, not `2(n + p)`, and
//! `z' = A(Omega) z` with `A = A0 + Omega A1` (`D = D0 + Omega D1`, `K = K0 + Omega K1`).

pub use super::branches::Branches;
use super::harmonic::{self, Physical};
use super::schedule::Schedule;
use crate::linalg::{self, CMat, LinalgError, RMat, c64};
use crate::system::Realized;
use std::sync::{Arc, OnceLock};

/// `M x'' + (D0 + Omega D1) x' + (K0 + Omega K1) x = F`, complex coefficients.
#[derive(Debug, Clone)]
pub struct SecondOrder {
    pub mass: CMat,
    pub d0: CMat,
    pub d1: CMat,
    pub k0: CMat,
    pub k1: CMat,
    /// Hermitian part of the stiffness, kept to classify poles by where their energy lies.
    pub stiffness: CMat,
}

/// `(A + A^H) / 2`.
pub fn hermitian_part(a: &CMat) -> CMat {
    CMat::from_fn(a.nrows(), a.ncols(), |i, j| {
        (a[(i, j)] + a[(j, i)].conj()) * 0.5
    })
}

impl SecondOrder {
    /// The rotor with its viscous damping only: `D = C_n + C_r - i Omega spin G`,
    /// `K = K - i Omega spin C_r` (`spin` is -1 on the conjugate rows of doubled coordinates).
    pub fn viscous(r: &Realized) -> Self {
        Self::with_damping(r, &r.damping_nonrotating, &r.damping_rotating)
    }

    /// The rotor with the given nonrotating and rotating viscous damping matrices.
    pub fn with_damping(r: &Realized, c_n: &CMat, c_r: &CMat) -> Self {
        let i = c64::new(0.0, 1.0);
        let g = r.spun(&r.gyroscopic);
        let cr = r.spun(c_r);
        let n = r.size();
        SecondOrder {
            mass: r.mass.clone(),
            d0: c_n + c_r,
            d1: CMat::from_fn(n, n, |a, b| -i * g[(a, b)]),
            k0: r.stiffness.clone(),
            k1: CMat::from_fn(n, n, |a, b| -i * cr[(a, b)]),
            stiffness: hermitian_part(&r.stiffness),
        }
    }

    pub fn n(&self) -> usize {
        self.mass.nrows()
    }

    /// `Phi^T (.) Phi` of every matrix: the system in the coordinates `q = Phi eta` (a real
    /// basis of the single layout).
    pub fn project(&self, phi: &RMat) -> SecondOrder {
        let pc = linalg::to_complex(phi);
        let pt = pc.transpose().to_owned();
        let c = |a: &CMat| &pt * a * &pc;
        SecondOrder {
            mass: c(&self.mass),
            d0: c(&self.d0),
            d1: c(&self.d1),
            k0: c(&self.k0),
            k1: c(&self.k1),
            stiffness: c(&self.stiffness),
        }
    }
}

fn real(x: f64) -> c64 {
    c64::new(x, 0.0)
}

/// `z' = (A0(Omega) + Omega A1(Omega)) z`, `z = [v, x, y]`. `A0` and `A1` are constant, or,
/// for supports tabulated against speed, given at the table's speeds and linear between
/// them (held outside): exact when the mass coefficients are constant, since every other
/// coefficient enters the state matrix linearly. With supports on ROSS's curves, `A0` is
/// built once and the supports' change from it is a [`Schedule`].
#[derive(Debug, Clone)]
pub struct StateModel {
    /// Speeds of the table (one entry, ignored, for constant coefficients).
    points: Vec<f64>,
    /// `A0`, `A1` per point. Formed on first use where the second-order matrices are kept (a
    /// harmonic solve never needs them: on a 456-coordinate rotor the `M^-1` products took
    /// 0.14 s of a 0.17 s unbalance response); formed at once otherwise.
    dense: OnceLock<Dense>,
    n: usize,
    branches: Branches,
    stiffness: CMat,
    schedule: Option<Arc<Schedule>>,
    /// The second-order matrices, kept for constant coefficients only (a table's or a
    /// schedule's harmonic solves go through `A`).
    physical: Option<Arc<Physical>>,
}

/// The state matrix's constant and speed parts at each table point.
#[derive(Debug, Clone)]
struct Dense {
    a0: Vec<CMat>,
    a1: Vec<CMat>,
}

impl Dense {
    /// Entry `(i, j)` of `A(speed)` on the table's `segment` at `speed`.
    fn entry(&self, (k, t): (usize, f64), speed: f64, i: usize, j: usize) -> c64 {
        let at = |k: usize| self.a0[k][(i, j)] + self.a1[k][(i, j)] * speed;
        if t == 0.0 {
            at(k)
        } else {
            at(k) * (1.0 - t) + at(k + 1) * t
        }
    }
}

impl StateModel {
    pub fn new(so: &SecondOrder, br: &Branches) -> Result<Self, LinalgError> {
        // Formed at once (its solve with M is the check of M), then the second-order form
        // dropped.
        let mut m = Self::kept(so, br);
        m.force()?;
        m.physical = None;
        Ok(m)
    }

    /// The model keeping its second-order matrices for harmonic solves (`harmonic.rs`), its
    /// state matrix formed when first asked for: only for constant coefficients, whose
    /// matrices do not change with the speed but through `Omega` (a table's or a schedule's
    /// harmonic solves go through `A`).
    pub fn harmonic(so: &SecondOrder, br: &Branches) -> Result<Self, LinalgError> {
        // M is factored now, as forming `A` would, so that a singular one fails here, not
        // where `A` is first asked for.
        linalg::mass_factors(&so.mass)?;
        Ok(Self::kept(so, br))
    }

    /// The model with its second-order form and no state matrix yet.
    fn kept(so: &SecondOrder, br: &Branches) -> Self {
        // W_nu U^H, a product of n x p factors (p reaches 6n with nonviscous damping).
        let u = &br.coupling;
        let uh = u.adjoint().to_owned();
        let kadd = &br.main_load() * &uh;
        let physical = Physical {
            mass: so.mass.clone(),
            d0: so.d0.clone(),
            d1: so.d1.clone(),
            k0: &so.k0 + &kadd,
            k1: so.k1.clone(),
            uh,
            load: br.load(),
            rate: br.rate.clone(),
            spin: br.spin.clone(),
        };
        StateModel {
            points: vec![0.0],
            dense: OnceLock::new(),
            n: so.n(),
            branches: br.clone(),
            stiffness: so.stiffness.clone(),
            schedule: None,
            physical: Some(Arc::new(physical)),
        }
    }

    /// Forms the state matrix now (where it may not be formed later: the second-order form
    /// is about to be dropped), failing where `M` is singular.
    fn force(&self) -> Result<&Dense, LinalgError> {
        if let Some(d) = self.dense.get() {
            return Ok(d);
        }
        let phys = self
            .physical
            .as_ref()
            .expect("a state model without A keeps its M, D, K");
        let (a0, a1) = phys.state_matrices()?;
        Ok(self.dense.get_or_init(|| Dense {
            a0: vec![a0],
            a1: vec![a1],
        }))
    }

    /// The state matrices; `M` was factored when the model was built (`DampedModel::build`
    /// checks it), so forming them later cannot fail but by a bug.
    fn dense(&self) -> &Dense {
        self.force()
            .expect("M was factored when the model was built")
    }

    /// The second-order form, if kept ([`StateModel::harmonic`]).
    pub fn physical(&self) -> Option<&Arc<Physical>> {
        self.physical.as_ref()
    }

    /// The model with its tabulated supports scheduled (built at the schedule's reference
    /// speed, one point).
    pub fn scheduled(mut self, schedule: Arc<Schedule>) -> Self {
        debug_assert_eq!(self.points.len(), 1);
        self.dense();
        self.schedule = Some(schedule);
        self.physical = None;
        self
    }

    /// The schedule of its supports on ROSS's curves, if any.
    pub fn schedule(&self) -> Option<&Schedule> {
        self.schedule.as_deref()
    }

    /// The models at the speeds of a table, as one (their structure must agree).
    pub fn table(speeds: &[f64], models: Vec<StateModel>) -> Self {
        debug_assert_eq!(speeds.len(), models.len());
        let mut it = models.into_iter();
        let mut first = it.next().expect("a table has points");
        let mut dense = first.dense().clone();
        for m in it {
            let d = m.dense();
            dense.a0.push(d.a0[0].clone());
            dense.a1.push(d.a1[0].clone());
        }
        first.dense = OnceLock::from(dense);
        first.points = speeds.to_vec();
        first.physical = None;
        first
    }

    /// The model whose state matrix is the mean of `self`'s and `other`'s at every speed (same
    /// structure and table): the hysteretic model with a sign set to 0, from the two models
    /// with that sign at +1 and -1 (the state matrix is linear in the imaginary stiffness).
    pub fn mean(&self, other: &StateModel) -> StateModel {
        debug_assert_eq!(self.points, other.points);
        let avg = |a: &[CMat], b: &[CMat]| -> Vec<CMat> {
            a.iter()
                .zip(b)
                .map(|(x, y)| {
                    CMat::from_fn(x.nrows(), x.ncols(), |i, j| (x[(i, j)] + y[(i, j)]) * 0.5)
                })
                .collect()
        };
        let (a, b) = (self.dense(), other.dense());
        StateModel {
            points: self.points.clone(),
            dense: OnceLock::from(Dense {
                a0: avg(&a.a0, &b.a0),
                a1: avg(&a.a1, &b.a1),
            }),
            n: self.n,
            branches: self.branches.clone(),
            stiffness: CMat::from_fn(self.n, self.n, |i, j| {
                (self.stiffness[(i, j)] + other.stiffness[(i, j)]) * 0.5
            }),
            schedule: self.schedule.clone(),
            physical: None,
        }
    }

    /// The table's segment and weight at `speed`: `A = (1 - t) A[k] + t A[k + 1]`.
    fn segment(&self, speed: f64) -> (usize, f64) {
        let w = &self.points;
        let last = w.len() - 1;
        if last == 0 || speed <= w[0] {
            return (0, 0.0);
        }
        if speed >= w[last] {
            return (last, 0.0);
        }
        let k = w.partition_point(|&x| x <= speed) - 1;
        (k, (speed - w[k]) / (w[k + 1] - w[k]))
    }

    /// `A0` and `A1` at rest (the first table point).
    pub fn a0(&self) -> &CMat {
        &self.dense().a0[0]
    }

    pub fn a1(&self) -> &CMat {
        &self.dense().a1[0]
    }

    /// The state matrix at spin speed `speed`.
    pub fn at(&self, speed: f64) -> CMat {
        let segment = self.segment(speed);
        let size = self.size();
        let dense = self.dense();
        let mut a = CMat::from_fn(size, size, |i, j| dense.entry(segment, speed, i, j));
        if let Some(s) = &self.schedule {
            s.add_to(&mut a, speed);
        }
        a
    }

    /// The speeds where the table's interpolation changes segment (none for constant
    /// coefficients and ROSS's curves).
    pub fn table_speeds(&self) -> Vec<f64> {
        match &self.schedule {
            Some(s) => s.breaks(),
            None if self.points.len() > 1 => self.points.clone(),
            None => vec![],
        }
    }

    /// `(F1, F2)` of `A(w) = F0 + w F1 + w^2 F2` on the table segment holding `speed` (affine
    /// outside the table and for constant coefficients: `F2 = None`), the schedule's part
    /// aside (see [`Self::schedule`]). Within a segment
    /// `A = (1 - t)(a0_k + w a1_k) + t (a0_k+1 + w a1_k+1)`, `t = (w - w_k) / (w_k+1 - w_k)`,
    /// so `A(w) - A(u) = (w - u) F1 + (w^2 - u^2) F2` for `w`, `u` in the segment.
    pub fn speed_terms(&self, speed: f64) -> (CMat, Option<CMat>) {
        let (k, t) = self.segment(speed);
        let Dense { a0, a1 } = self.dense();
        if t == 0.0 {
            return (a1[k].clone(), None);
        }
        let (wk, span) = (self.points[k], self.points[k + 1] - self.points[k]);
        let d0 = &a0[k + 1] - &a0[k];
        let d1 = &a1[k + 1] - &a1[k];
        let size = self.size();
        let f1 = CMat::from_fn(size, size, |i, j| {
            a1[k][(i, j)] + (d0[(i, j)] - d1[(i, j)] * wk) / span
        });
        let f2 = CMat::from_fn(size, size, |i, j| d1[(i, j)] / span);
        (f1, Some(f2))
    }

    /// `A(speed) x` without forming `A`.
    pub fn apply(&self, speed: f64, x: &[c64]) -> Vec<c64> {
        let (k, t) = self.segment(speed);
        let mut y = vec![c64::new(0.0, 0.0); self.size()];
        let mut add = |a: &CMat, f: f64| {
            if f != 0.0 {
                linalg::add_matvec(&mut y, a, x, real(f));
            }
        };
        let Dense { a0, a1 } = self.dense();
        add(&a0[k], 1.0 - t);
        add(&a1[k], speed * (1.0 - t));
        if t != 0.0 {
            add(&a0[k + 1], t);
            add(&a1[k + 1], speed * t);
        }
        if let Some(s) = &self.schedule {
            s.apply_add(speed, x, &mut y);
        }
        y
    }

    /// Physical complex degrees of freedom.
    pub fn n(&self) -> usize {
        self.n
    }

    /// Internal coordinates.
    pub fn p(&self) -> usize {
        self.branches.len()
    }

    /// State size `2n + p`.
    pub fn size(&self) -> usize {
        2 * self.n + self.p()
    }

    /// Fraction of a mode's elastic energy stored in the rotor (and its supports' fitted
    /// branches) rather than in the damping model's branch springs: near 1 for a rotor pole,
    /// O(eta) for an internal one, whatever the units of the internal coordinates.
    pub fn rotor_energy_fraction(&self, x: &[c64], y: &[c64]) -> f64 {
        let n = self.n;
        let mut e_rotor = 0.0;
        for (r, xr) in x.iter().enumerate().take(n) {
            let kx: c64 = x
                .iter()
                .enumerate()
                .map(|(c, xc)| self.stiffness[(r, c)] * xc)
                .sum();
            e_rotor += (xr.conj() * kx).re;
        }
        // A support's fitted branches are part of the rotor's supports: their poles are the
        // support's, counted with the rotor's.
        let own = self.branches.len() - self.branches.from_supports;
        let (mut e_branch, mut e_support) = (0.0, 0.0);
        for (j, yj) in y.iter().enumerate() {
            let ux: c64 = x
                .iter()
                .enumerate()
                .map(|(c, xc)| self.branches.coupling[(c, j)].conj() * xc)
                .sum();
            let e = self.branches.stiffness[j] * (yj - ux).norm_sqr();
            match j < own {
                true => e_branch += e,
                false => e_support += e,
            }
        }
        let total = e_rotor.abs() + e_support + e_branch;
        if total > 0.0 {
            (e_rotor.abs() + e_support) / total
        } else {
            1.0
        }
    }

    /// `(A(speed) - sigma I)^-1` by the structure of `A` (see [`ShiftInvert`]), through the
    /// second-order matrices where they are kept (no `A`, no `M^-1`).
    pub fn shift_invert(&self, speed: f64, sigma: c64) -> ShiftInvert {
        if let Some(phys) = &self.physical {
            return ShiftInvert::Physical(phys.shift_invert(speed, sigma));
        }
        let (n, p) = (self.n, self.p());
        let segment = self.segment(speed);
        // With a schedule, the entries of the matrix it changes.
        let scheduled = self.schedule.as_ref().map(|_| self.at(speed));
        let dense = self.dense();
        let e = |i: usize, j: usize| match &scheduled {
            Some(a) => a[(i, j)],
            None => dense.entry(segment, speed, i, j),
        };
        let avv = CMat::from_fn(n, n, |i, j| {
            e(i, j) - if i == j { sigma } else { c64::new(0.0, 0.0) }
        });
        let avy = CMat::from_fn(n, p, |i, j| e(i, 2 * n + j));
        let ayx = CMat::from_fn(p, n, |i, j| e(2 * n + i, n + j));
        let dyy: Vec<c64> = (0..p)
            .map(|j| c64::new(1.0, 0.0) / (e(2 * n + j, 2 * n + j) - sigma))
            .collect();
        // S = sigma (A_vv - sigma) + A_vx - A_vy diag(dyy) A_yx.
        let scaled = CMat::from_fn(p, n, |i, j| ayx[(i, j)] * dyy[i]);
        let coupled = &avy * &scaled;
        let s = CMat::from_fn(n, n, |i, j| {
            avv[(i, j)] * sigma + e(i, n + j) - coupled[(i, j)]
        });
        ShiftInvert::Structured(Structured {
            n,
            sigma,
            avv,
            avy,
            ayx,
            dyy,
            lu: linalg::ComplexLu::new(&s),
        })
    }

    /// The branches (internal coordinates).
    pub fn branches(&self) -> &Branches {
        &self.branches
    }
}

/// `(A - sigma I)^-1` for `A = [[A_vv, A_vx, A_vy], [I, 0, 0], [0, A_yx, A_yy]]` (`A_yy`
/// diagonal): from `b = [b1, b2, b3]`, `v = b2 + sigma x` and
/// `y = (A_yy - sigma)^-1 (b3 - A_yx x)` leave one `n x n` system,
/// `(sigma (A_vv - sigma) + A_vx - A_vy (A_yy - sigma)^-1 A_yx) x
/// = b1 - (A_vv - sigma) b2 - A_vy (A_yy - sigma)^-1 b3`, factored once; or the same through
/// the second-order matrices ([`harmonic::ShiftInvert`]).
pub enum ShiftInvert {
    Structured(Structured),
    Physical(harmonic::ShiftInvert),
}

impl ShiftInvert {
    /// `(A - sigma I)^-1 b`.
    pub fn solve(&self, b: &[c64]) -> Vec<c64> {
        match self {
            ShiftInvert::Structured(s) => s.solve(b),
            ShiftInvert::Physical(p) => p.solve(b),
        }
    }
}

/// [`ShiftInvert`] from the entries of `A`.
pub struct Structured {
    n: usize,
    sigma: c64,
    /// `A_vv - sigma I`.
    avv: CMat,
    avy: CMat,
    ayx: CMat,
    /// `1 / (A_yy - sigma)`.
    dyy: Vec<c64>,
    lu: linalg::ComplexLu,
}

impl Structured {
    /// `(A - sigma I)^-1 b`.
    pub fn solve(&self, b: &[c64]) -> Vec<c64> {
        let n = self.n;
        let (b1, rest) = b.split_at(n);
        let (b2, b3) = rest.split_at(n);
        let w: Vec<c64> = b3.iter().zip(&self.dyy).map(|(b, d)| b * d).collect();
        let mut x = b1.to_vec();
        let minus = real(-1.0);
        linalg::add_matvec(&mut x, &self.avv, b2, minus);
        linalg::add_matvec(&mut x, &self.avy, &w, minus);
        self.lu.solve_in_place(&mut x);
        let mut out: Vec<c64> = b2.iter().zip(&x).map(|(b, x)| b + self.sigma * x).collect();
        out.extend_from_slice(&x);
        let mut y = b3.to_vec();
        linalg::add_matvec(&mut y, &self.ayx, &x, minus);
        out.extend(y.iter().zip(&self.dyy).map(|(y, d)| y * d));
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::rotor::Jeffcott;
    use crate::system::RotorSystem;

    #[test]
    fn viscous_jeffcott_state_matrix_is_the_textbook_one() {
        // m = 2, k = 8, c_n = 0.4, c_r = 0.2: A = [[-(c)/m + i Omega G/m, -(k - i Omega c_r)/m], [1, 0]]
        let j = Jeffcott::parse(
            &crate::model::api::JeffcottInput {
                mass: 2.0,
                stiffness: 8.0,
                loss_factor_rotating: 0.0,
                loss_factor_nonrotating: 0.0,
                damping_rotating: 0.2,
                damping_nonrotating: 0.4,
            },
            "rotor",
        )
        .unwrap();
        let s = RotorSystem::jeffcott(&j);
        let r = Realized::at(&s, 0.0);
        let m = StateModel::new(&SecondOrder::viscous(&r), &Branches::none(1)).unwrap();
        let a = m.at(3.0);
        assert!((a[(0, 0)] - c64::new(-0.3, 0.0)).norm() < 1e-15);
        assert!((a[(0, 1)] - c64::new(-4.0, 0.3)).norm() < 1e-15);
        assert!((a[(1, 0)] - c64::new(1.0, 0.0)).norm() < 1e-15);
    }
}
