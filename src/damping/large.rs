//! The full model of a large rotor, sparse: its shift-invert without a dense matrix.
//!
//! For the viscous and hysteretic models the full model is the rotor's own second-order
//! system (MODEL.md section 1, `state.rs` for its first-order form): at spin speed `Omega`,
//! `M x'' + D x' + K x = 0` with
//!
//! ```text
//! D = C_n + C_r - i Omega spin G,    K = K + i S - i Omega spin C_r   [+ i a K''_n + i diag(b, c) K''_r]
//! ```
//!
//! the bracket for one sign pattern `(a, b, c)` of the hysteretic model (`hysteretic.rs`), the
//! supports written on their translations in the layout as `system::realize` writes them.
//! Every matrix keeps the rotor's band, so `Z(sigma) = sigma^2 M + sigma D + K` factors sparse
//! at a cost linear in the mesh, and `(A - sigma I)^-1 [b1, b2] = [b2 + sigma x, x]` with
//! `Z(sigma) x = -M b1 - (sigma M + D) b2` (`harmonic::ShiftInvert` without internal
//! coordinates) is what shift-invert Arnoldi needs.

use super::hysteretic::{patterns, sign};
use crate::linalg::CMat;
use crate::linalg::sparse::{Lu, LuPattern};
use crate::linalg::{LinalgError, Sparse, c64};
use crate::model::damping::DampingModel;
use crate::model::supports::Matrix2;
use crate::system::{Layout, RotorSystem, point_action};
use std::sync::Arc;

/// Complex entries `(row, column, value)`, repeated positions summed.
type Entries = Vec<(usize, usize, c64)>;

/// One linear problem of the full model at one speed.
pub struct Problem {
    /// Size `N` of the second-order matrices (`n`, or `2 n` doubled).
    pub size: usize,
    mass: Entries,
    damping: Entries,
    stiffness: Entries,
    /// The hysteretic model's sign pattern `(a, b, c)` this problem assumes.
    pub signs: Option<(f64, f64, f64)>,
    /// The equivalent or nonviscous dampers, low-rank (`dampers.rs`).
    terms: Option<Arc<Terms>>,
}

/// The full model's second-order matrices at one speed, the hysteretic model's loss apart
/// (its sign depends on the frequency).
pub struct Parts {
    /// Size `N` of the matrices (`n`, or `2 n` doubled).
    pub size: usize,
    /// Rotor coordinates `n`: rows from `n` on are the conjugate copy (spin `-1`).
    n: usize,
    mass: Entries,
    damping: Entries,
    stiffness: Entries,
    /// `K''_n` and `K''_r`, real (empty for the viscous model).
    loss_n: Entries,
    loss_r: Entries,
}

/// The full model's matrices at `speed`, or `None` for the models built on a modal basis,
/// which have no sparse form.
pub fn parts(system: &RotorSystem, damping: &DampingModel, speed: f64) -> Option<Parts> {
    match damping {
        DampingModel::Viscous => Some(parts_of(system, false, speed)),
        DampingModel::Hysteretic => Some(parts_of(system, true, speed)),
        _ => None,
    }
}

/// The matrices at `speed` of the viscous model, or of the `hysteretic` one.
pub fn parts_of(system: &RotorSystem, hysteretic: bool, speed: f64) -> Parts {
    parts_read(system, hysteretic, speed, None)
}

/// [`parts_of`] with supports over whirl frequency read at `whirl` (rad/s, either sign) where
/// given, else synchronously.
pub fn parts_read(system: &RotorSystem, hysteretic: bool, speed: f64, whirl: Option<f64>) -> Parts {
    let layout = system.layout();
    let n = system.n();
    let size = layout.size(n);
    let spin = |i: usize| if i < n { 1.0 } else { -1.0 };
    let i1 = c64::new(0.0, 1.0);
    let real = |v: f64| c64::new(v, 0.0);
    // A rotor matrix on the diagonal block(s), times `f(row)`.
    let blocks = |out: &mut Entries, a: &Sparse, f: &dyn Fn(usize) -> c64| {
        for (i, j, v) in a.entries() {
            out.push((i, j, f(i) * v));
            if layout == Layout::Doubled {
                out.push((n + i, n + j, f(n + i) * v));
            }
        }
    };
    let support = |out: &mut Entries, w: &[(usize, f64)], a: &Matrix2| {
        let k = point_action(a, layout);
        for &(i, wi) in w {
            for &(j, wj) in w {
                for b in 0..k.nrows() {
                    for c in 0..k.ncols() {
                        out.push((i + b * n, j + c * n, k[(b, c)] * (wi * wj)));
                    }
                }
            }
        }
    };
    let (mut mass, mut d, mut k) = (vec![], vec![], vec![]);
    let (mut loss_n, mut loss_r) = (vec![], vec![]);
    blocks(&mut mass, &system.mass, &|_| real(1.0));
    blocks(&mut d, &system.damping_nonrotating, &|_| real(1.0));
    blocks(&mut d, &system.damping_rotating, &|_| real(1.0));
    blocks(&mut d, &system.gyroscopic, &|i| -i1 * (speed * spin(i)));
    blocks(&mut k, &system.stiffness_rotating, &|_| real(1.0));
    blocks(&mut k, &system.stiffness_nonrotating, &|_| real(1.0));
    blocks(&mut k, &system.circulatory, &|i| i1 * spin(i));
    blocks(&mut k, &system.damping_rotating, &|i| {
        -i1 * (speed * spin(i))
    });
    if hysteretic {
        blocks(&mut loss_n, &system.hysteretic_nonrotating, &|_| real(1.0));
        blocks(&mut loss_r, &system.hysteretic_rotating, &|_| real(1.0));
    }
    for p in &system.supports {
        let c = match whirl {
            Some(l) => p.support.at_whirl(speed, l),
            None => p.support.at(speed),
        };
        let w = p.at.weights();
        support(&mut k, &w, &c.k);
        support(&mut d, &w, &c.c);
        support(&mut mass, &w, &c.m);
        if hysteretic {
            support(
                &mut loss_n,
                &w,
                &c.k.symmetric().scaled(p.support.loss_factor),
            );
        }
    }
    Parts {
        size,
        n,
        mass,
        damping: d,
        stiffness: k,
        loss_n,
        loss_r,
    }
}

impl Parts {
    /// `K + i a K''_n + i diag(b, c) K''_r` of the sign pattern `(a, b, c)` (`K` alone for the
    /// viscous model).
    fn stiffness(&self, (a, b, c): (f64, f64, f64)) -> Entries {
        let i1 = c64::new(0.0, 1.0);
        let mut kk = self.stiffness.clone();
        kk.extend(self.loss_n.iter().map(|&(i, j, v)| (i, j, i1 * a * v)));
        kk.extend(self.loss_r.iter().map(|&(i, j, v)| {
            let rot = if i < self.n { b } else { c };
            (i, j, i1 * rot * v)
        }));
        kk
    }

    /// The entries of `Z(i lambda)` (mass, damping, stiffness, loss in turn, repeated
    /// positions apart), without a copy: for the hysteretic model the loss at the signs of
    /// `lambda` (supports), `lambda - Omega` (rotor rows) and `lambda + Omega` (conjugate rows),
    /// `sgn 0 = 0`. Every speed and frequency gives entries at the same positions (zeros kept).
    fn dynamic(&self, lambda: f64, speed: f64) -> impl Iterator<Item = (usize, usize, c64)> + '_ {
        let (a, b, c) = (sign(lambda), sign(lambda - speed), sign(lambda + speed));
        let s = c64::new(0.0, lambda);
        let i1 = c64::new(0.0, 1.0);
        let n = self.n;
        scaled(&self.mass, s * s)
            .chain(scaled(&self.damping, s))
            .chain(self.stiffness.iter().copied())
            .chain(scaled(&self.loss_n, i1 * a))
            .chain(self.loss_r.iter().map(move |&(i, j, v)| {
                let rot = if i < n { b } else { c };
                (i, j, i1 * rot * v)
            }))
    }

    /// `X` of `Z(i lambda) X = rhs`, the steady response at frequency `lambda` (rad/s, of
    /// either sign), through a factor on `pattern` ([`Parts::pattern`]).
    pub fn steady(
        &self,
        pattern: &LuPattern,
        lambda: f64,
        speed: f64,
        rhs: &[c64],
        terms: Option<&Arc<Terms>>,
    ) -> Result<Vec<c64>, LinalgError> {
        let values: Vec<c64> = self.dynamic(lambda, speed).map(|e| e.2).collect();
        let lu = pattern.factor(&values)?;
        let mut x = rhs.to_vec();
        lu.solve_in_place(&mut x);
        // The equivalent or nonviscous dampers (their branches eliminated at `i lambda`): the
        // Woodbury correction of `Z0^-1 rhs`.
        if let Some(t) = terms.filter(|t| !t.terms.is_empty()) {
            low_rank(t.clone(), &lu, c64::new(0.0, lambda))?.correct(&mut x);
        }
        if x.iter().any(|v| !(v.re.is_finite() && v.im.is_finite())) {
            return Err(LinalgError::NonFinite);
        }
        Ok(x)
    }

    /// The positions of `Z`'s entries, analysed once for every speed and frequency.
    pub fn pattern(&self) -> Result<LuPattern, LinalgError> {
        let positions: Vec<(usize, usize)> = self.dynamic(1.0, 0.0).map(|e| (e.0, e.1)).collect();
        LuPattern::new(self.size, &positions)
    }
}

/// `list` times `f`, entry by entry.
fn scaled(list: &Entries, f: c64) -> impl Iterator<Item = (usize, usize, c64)> + '_ {
    list.iter().map(move |&(i, j, v)| (i, j, f * v))
}

/// One low-rank term `l w(s) r^H` (columns by index into [`Terms::columns`]).
#[derive(Debug, Clone)]
pub struct Term {
    pub left: usize,
    pub right: usize,
    /// `w(s) = a s + b + branches`.
    pub a: c64,
    pub b: c64,
    /// Maxwell branches on `right`'s coordinate (then `left == right`): `(k, nu k, d, rho)`.
    pub branches: Vec<(f64, f64, f64, f64)>,
}

/// The dampers at one spin speed, as terms of `Z(s)`.
#[derive(Debug, Clone)]
pub struct Terms {
    pub speed: f64,
    pub columns: Vec<Vec<c64>>,
    pub terms: Vec<Term>,
}

impl Terms {
    /// Internal coordinates (branches).
    pub fn internal(&self) -> usize {
        self.terms.iter().map(|t| t.branches.len()).sum()
    }

    /// `w_t(s)` of each term.
    pub fn weights(&self, s: c64) -> Vec<c64> {
        let i1 = c64::new(0.0, 1.0);
        self.terms
            .iter()
            .map(|t| {
                let mut w = t.a * s + t.b;
                for &(k, nuk, d, rho) in &t.branches {
                    w += c64::new(nuk, 0.0) - k * d / (s + d - i1 * (self.speed * rho));
                }
                w
            })
            .collect()
    }
}

/// `K''_n` and the supports' loss at `speed`, in the layout (the nonrotating dampers' loss).
pub fn nonrotating_loss_entries(system: &RotorSystem, speed: f64) -> Entries {
    parts_of(system, true, speed).loss_n
}

/// `K''_r` on the diagonal block(s) of the layout (`doubled`: both copies).
pub fn rotor_loss_entries(system: &RotorSystem, doubled: bool) -> Entries {
    let n = system.n();
    let mut out = vec![];
    for (i, j, v) in system.hysteretic_rotating.entries() {
        out.push((i, j, c64::new(v, 0.0)));
        if doubled {
            out.push((n + i, n + j, c64::new(v, 0.0)));
        }
    }
    out
}

/// The full model's problems at `speed`: one (viscous; equivalent and nonviscous with their
/// dampers' `terms` at the speed, `dampers.rs`), four (hysteretic, one per sign pattern), or
/// `None` for the equivalent and nonviscous models without them.
pub fn problems(
    system: &RotorSystem,
    damping: &DampingModel,
    terms: Option<Arc<Terms>>,
    speed: f64,
) -> Option<Vec<Problem>> {
    let (parts, terms) = match (damping, terms) {
        (DampingModel::Viscous | DampingModel::Hysteretic, _) => {
            (parts(system, damping, speed)?, None)
        }
        (_, Some(t)) => (parts_of(system, false, speed), Some(t)),
        (_, None) => return None,
    };
    let problem = |signs: Option<(f64, f64, f64)>| Problem {
        size: parts.size,
        mass: parts.mass.clone(),
        damping: parts.damping.clone(),
        stiffness: parts.stiffness(signs.unwrap_or((0.0, 0.0, 0.0))),
        signs,
        terms: terms.clone(),
    };
    Some(match damping {
        DampingModel::Hysteretic => patterns(system.layout())
            .into_iter()
            .map(|p| problem(Some(p)))
            .collect(),
        _ => vec![problem(None)],
    })
}

/// The hysteretic model's problem at a forward crossing of the 1x line: the rotating loss's
/// sign there 0, the mean of its two problems (`analysis::criticals`), every root accepted.
pub fn crossing_problem(system: &RotorSystem, speed: f64) -> Option<Problem> {
    let parts = parts(system, &DampingModel::Hysteretic, speed)?;
    let counter = match system.layout() {
        Layout::Doubled => 1.0,
        _ => 0.0,
    };
    Some(Problem {
        size: parts.size,
        mass: parts.mass.clone(),
        damping: parts.damping.clone(),
        stiffness: parts.stiffness((1.0, 0.0, counter)),
        signs: None,
        terms: None,
    })
}

/// `(A - sigma I)^-1` of one problem's first-order form, through a sparse factor of `Z0(sigma)`
/// and, with dampers, the Woodbury identity for their low-rank term `L W R^H`:
/// `Z^-1 = Z0^-1 - Y (I + W R^H Y)^-1 W R^H Z0^-1`, `Y = Z0^-1 L` (one solve per column).
/// Internal coordinates as in `harmonic::ShiftInvert`: from `(A - sigma I) [v, x, y] = b`,
/// `v = b2 + sigma x`, `y_j = (b3_j - d_j u_j^H x) / (a_j - sigma)` with
/// `a_j = -d_j + i Omega rho_j`, and
/// `Z(sigma) x = -M b1 - (sigma M + D) b2 + sum_j u_j k_j b3_j / (a_j - sigma)`.
pub struct ShiftInvert {
    sigma: c64,
    size: usize,
    mass: Entries,
    /// `sigma M + D` (sparse part).
    damping: Entries,
    lu: Lu,
    low: Option<LowRank>,
}

/// The dampers' part of a shift-invert.
struct LowRank {
    terms: Arc<Terms>,
    /// `Y = Z0^-1 L` (a column per term), and the factored capacitance `I + W R^H Y`.
    y: CMat,
    w: Vec<c64>,
    capacitance: crate::linalg::ComplexLu,
    /// Per branch: its term and `1 / (a_j - sigma)`.
    branch: Vec<(usize, f64, f64, c64)>,
}

/// `u^H x`.
fn dot(u: &[c64], x: &[c64]) -> c64 {
    u.iter().zip(x).map(|(a, b)| a.conj() * b).sum()
}

impl Problem {
    pub fn shift_invert(&self, sigma: c64) -> Result<ShiftInvert, LinalgError> {
        let mut damping: Entries = self
            .mass
            .iter()
            .map(|&(i, j, v)| (i, j, sigma * v))
            .collect();
        damping.extend_from_slice(&self.damping);
        let mut z: Entries = self
            .mass
            .iter()
            .map(|&(i, j, v)| (i, j, sigma * sigma * v))
            .collect();
        z.extend(self.damping.iter().map(|&(i, j, v)| (i, j, sigma * v)));
        z.extend_from_slice(&self.stiffness);
        let lu = Lu::new(self.size, &z)?;
        let low = match &self.terms {
            Some(t) if !t.terms.is_empty() => Some(low_rank(t.clone(), &lu, sigma)?),
            _ => None,
        };
        Ok(ShiftInvert {
            sigma,
            size: self.size,
            mass: self.mass.clone(),
            damping,
            lu,
            low,
        })
    }

    /// `||Z(s) x|| / ((|s|^2 ||M|| + |s| ||D|| + ||K||) ||x||)` (max-norms, row sums for the
    /// matrices): how nearly `(s, x)` is an eigenpair of this problem without internal
    /// coordinates, relative to the size of its terms.
    pub fn residual(&self, s: c64, x: &[c64]) -> f64 {
        let mut r = vec![c64::new(0.0, 0.0); self.size];
        let mut rows = vec![[0.0f64; 3]; self.size];
        for (k, (list, f)) in [
            (&self.mass, s * s),
            (&self.damping, s),
            (&self.stiffness, c64::new(1.0, 0.0)),
        ]
        .into_iter()
        .enumerate()
        {
            for &(i, j, v) in list.iter() {
                r[i] += f * v * x[j];
                rows[i][k] += v.norm();
            }
        }
        let norm = |k: usize| rows.iter().map(|row| row[k]).fold(0.0, f64::max);
        let scale = s.norm_sqr() * norm(0) + s.norm() * norm(1) + norm(2);
        let xn = x.iter().map(|v| v.norm()).fold(0.0, f64::max);
        let rn = r.iter().map(|v| v.norm()).fold(0.0, f64::max);
        rn / (scale * xn).max(f64::MIN_POSITIVE)
    }

    /// Internal coordinates of this problem (the nonviscous model's branches).
    pub fn internal(&self) -> usize {
        self.terms.as_ref().map_or(0, |t| t.internal())
    }

    /// Fraction of the elastic energy of a mode `z = [v, x, y]` stored in the rotor rather
    /// than in the branch springs, as `StateModel::rotor_energy_fraction` (`Re x^H K x` and
    /// `k_j |y_j - u_j^H x|^2`): near 1 for a rotor pole, O(eta) for an internal one.
    pub fn rotor_fraction(&self, z: &[c64]) -> f64 {
        let n = self.size;
        let x = &z[n..2 * n];
        let e_rotor: f64 = self
            .stiffness
            .iter()
            .map(|&(i, j, v)| (x[i].conj() * v * x[j]).re)
            .sum::<f64>()
            .abs();
        let mut e_branch = 0.0;
        if let Some(t) = &self.terms {
            let mut y = z[2 * n..].iter();
            for term in &t.terms {
                let ux = dot(&t.columns[term.right], x);
                for &(k, ..) in &term.branches {
                    let yj = y.next().copied().unwrap_or_default();
                    e_branch += k * (yj - ux).norm_sqr();
                }
            }
        }
        let total = e_rotor + e_branch;
        if total > 0.0 { e_rotor / total } else { 1.0 }
    }

    /// Whether the root `s` at spin speed `speed` has the signs this problem assumed (always,
    /// for the viscous model).
    pub fn consistent(&self, s: c64, speed: f64) -> bool {
        self.signs
            .is_none_or(|signs| super::hysteretic::consistent(signs, s, speed))
    }
}

/// The Woodbury parts of `terms` at `sigma`.
fn low_rank(terms: Arc<Terms>, lu: &Lu, sigma: c64) -> Result<LowRank, LinalgError> {
    let w = terms.weights(sigma);
    let n = terms.columns.first().map_or(0, |c| c.len());
    let r = terms.terms.len();
    // One multi-column solve and one product (a dot product per pair took most of a
    // frequency's time on the 1080-element train).
    let mut y = CMat::from_fn(n, r, |i, t| terms.columns[terms.terms[t].left][i]);
    lu.solve_columns(&mut y);
    let right = CMat::from_fn(n, r, |i, t| terms.columns[terms.terms[t].right][i]);
    let h = right.adjoint() * &y;
    let cap = CMat::from_fn(r, r, |i, j| {
        let delta = if i == j { 1.0 } else { 0.0 };
        c64::new(delta, 0.0) + w[i] * h[(i, j)]
    });
    let finite =
        (0..r).all(|i| (0..r).all(|j| cap[(i, j)].re.is_finite() && cap[(i, j)].im.is_finite()));
    if !finite {
        return Err(LinalgError::NonFinite);
    }
    let speed = terms.speed;
    let branch = terms
        .terms
        .iter()
        .enumerate()
        .flat_map(|(t, term)| {
            term.branches.iter().map(move |&(k, _, d, rho)| {
                let a = c64::new(-d, speed * rho);
                (t, k, d, c64::new(1.0, 0.0) / (a - sigma))
            })
        })
        .collect();
    Ok(LowRank {
        capacitance: crate::linalg::ComplexLu::new(&cap),
        terms,
        y,
        w,
        branch,
    })
}

impl LowRank {
    /// `x - Y (I + W R^H Y)^-1 W R^H x`: `Z^-1 b` from `x = Z0^-1 b`.
    fn correct(&self, x: &mut [c64]) {
        let t = &self.terms;
        let mut s: Vec<c64> = t
            .terms
            .iter()
            .zip(&self.w)
            .map(|(term, w)| w * dot(&t.columns[term.right], x))
            .collect();
        self.capacitance.solve_in_place(&mut s);
        for (t, s) in s.iter().enumerate() {
            let s = -*s;
            x.iter_mut()
                .enumerate()
                .for_each(|(i, x)| *x += s * self.y[(i, t)]);
        }
    }
}

impl ShiftInvert {
    /// State size `2 N + p`.
    pub fn states(&self) -> usize {
        2 * self.size + self.low.as_ref().map_or(0, |l| l.branch.len())
    }

    /// Coordinates `N`: the displacements are the state's entries `N..2 N`.
    pub fn coordinates(&self) -> usize {
        self.size
    }

    /// `(A - sigma I)^-1 b`, `b = [b1, b2, b3]` (velocities, displacements, branches).
    pub fn solve(&self, b: &[c64]) -> Vec<c64> {
        let n = self.size;
        let (b1, rest) = b.split_at(n);
        let (b2, b3) = rest.split_at(n);
        let mut x = vec![c64::new(0.0, 0.0); n];
        for &(i, j, v) in &self.mass {
            x[i] -= v * b1[j];
        }
        for &(i, j, v) in &self.damping {
            x[i] -= v * b2[j];
        }
        if let Some(low) = &self.low {
            let t = &low.terms;
            // The dampers' damping part on b2, and the branches' load.
            for term in &t.terms {
                if term.a != c64::new(0.0, 0.0) {
                    let f = term.a * dot(&t.columns[term.right], b2);
                    axpy(&mut x, &t.columns[term.left], -f);
                }
            }
            for (&(term, k, _, inv), b) in low.branch.iter().zip(b3) {
                let c = &t.columns[t.terms[term].left];
                axpy(&mut x, c, inv * k * b);
            }
        }
        self.lu.solve_in_place(&mut x);
        if let Some(low) = &self.low {
            low.correct(&mut x);
        }
        let mut out: Vec<c64> = b2.iter().zip(&x).map(|(b, x)| b + self.sigma * x).collect();
        out.extend_from_slice(&x);
        if let Some(low) = &self.low {
            let t = &low.terms;
            let ux: Vec<c64> = t
                .terms
                .iter()
                .map(|term| dot(&t.columns[term.right], &x))
                .collect();
            out.extend(
                low.branch
                    .iter()
                    .zip(b3)
                    .map(|(&(term, _, d, inv), b)| (b - ux[term] * d) * inv),
            );
        }
        out
    }
}

/// `y += a x`.
fn axpy(y: &mut [c64], x: &[c64], a: c64) {
    y.iter_mut().zip(x).for_each(|(y, x)| *y += a * x);
}
