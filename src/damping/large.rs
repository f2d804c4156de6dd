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
use crate::linalg::sparse::{Lu, LuPattern};
use crate::linalg::{LinalgError, Sparse, c64};
use crate::model::damping::DampingModel;
use crate::model::supports::Matrix2;
use crate::system::{Layout, RotorSystem, point_action};

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
    let layout = system.layout();
    let n = system.n();
    let size = match layout {
        Layout::Single => n,
        Layout::Doubled => 2 * n,
    };
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
        let c = p.support.at(speed);
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
    ) -> Result<Vec<c64>, LinalgError> {
        let values: Vec<c64> = self.dynamic(lambda, speed).map(|e| e.2).collect();
        let lu = pattern.factor(&values)?;
        let mut x = rhs.to_vec();
        lu.solve_in_place(&mut x);
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

/// The full model's problems at `speed`: one (viscous), four (hysteretic, one per sign
/// pattern), or `None` for the models built on a modal basis, which have no sparse form.
pub fn problems(system: &RotorSystem, damping: &DampingModel, speed: f64) -> Option<Vec<Problem>> {
    let parts = parts(system, damping, speed)?;
    let problem = |signs: Option<(f64, f64, f64)>| Problem {
        size: parts.size,
        mass: parts.mass.clone(),
        damping: parts.damping.clone(),
        stiffness: parts.stiffness(signs.unwrap_or((0.0, 0.0, 0.0))),
        signs,
    };
    Some(match damping {
        DampingModel::Hysteretic => patterns(system.layout())
            .into_iter()
            .map(|p| problem(Some(p)))
            .collect(),
        _ => vec![problem(None)],
    })
}

/// `(A - sigma I)^-1` of one problem's first-order form, through a sparse factor of `Z(sigma)`.
pub struct ShiftInvert {
    sigma: c64,
    size: usize,
    mass: Entries,
    /// `sigma M + D`.
    damping: Entries,
    lu: Lu,
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
        Ok(ShiftInvert {
            sigma,
            size: self.size,
            mass: self.mass.clone(),
            damping,
            lu: Lu::new(self.size, &z)?,
        })
    }

    /// Whether the root `s` at spin speed `speed` has the signs this problem assumed (always,
    /// for the viscous model).
    pub fn consistent(&self, s: c64, speed: f64) -> bool {
        self.signs
            .is_none_or(|signs| super::hysteretic::consistent(signs, s, speed))
    }
}

impl ShiftInvert {
    /// State size `2 N`.
    pub fn states(&self) -> usize {
        2 * self.size
    }

    /// `(A - sigma I)^-1 b`, `b = [b1, b2]` (velocities, displacements).
    pub fn solve(&self, b: &[c64]) -> Vec<c64> {
        let n = self.size;
        let (b1, b2) = b.split_at(n);
        let mut x = vec![c64::new(0.0, 0.0); n];
        for &(i, j, v) in &self.mass {
            x[i] -= v * b1[j];
        }
        for &(i, j, v) in &self.damping {
            x[i] -= v * b2[j];
        }
        self.lu.solve_in_place(&mut x);
        let mut out: Vec<c64> = b2.iter().zip(&x).map(|(b, x)| b + self.sigma * x).collect();
        out.extend_from_slice(&x);
        out
    }
}
