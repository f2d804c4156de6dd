//! The dynamic stiffness of a linear model, for harmonic solves without the state matrix.
//!
//! At `x = X e^{sigma t}` the model of `state.rs` (`M x'' + D x' + K x - W y = F`, each
//! branch `y_j' = (-d_j + i Omega rho_j) y_j + d_j u_j^H x`, `W = U diag(k)` but for a
//! support's branches) has
//! `y_j = d_j / (sigma + d_j - i Omega rho_j) u_j^H X`, so one system of the rotor's size is left:
//!
//! ```text
//! Z(sigma) X = F,   Z = sigma^2 M + sigma D(Omega) + K(Omega) + W_nu U^H
//!                       - W diag(d_j / (sigma + d_j - i Omega rho_j)) U^H
//! ```
//!
//! Solved as it stands, never through `M^-1`: the first-order system `(sigma - A) z = B f`
//! carries `M^-1 K`, of size `w_max^2`. On the soft heavily damped cross-coupled held-out rotor
//! (113 elements) the first-order unbalance response differed from ROSS's by 1.6e-7 of the
//! largest response; `Z X = F` differs from an extended-precision solve of ROSS's matrices by
//! 3.5e-10, and costs a factor of the rotor's size, not of the state's `2n + p`.

use crate::linalg::{self, CMat, LinalgError, c64};
use std::sync::Arc;

/// The second-order matrices a [`StateModel`](super::StateModel) was built from, kept by
/// [`StateModel::harmonic`](super::StateModel::harmonic) for constant coefficients.
#[derive(Debug, Clone)]
pub struct Physical {
    pub(super) mass: CMat,
    pub(super) d0: CMat,
    pub(super) d1: CMat,
    /// `K0 + W_nu U^H`.
    pub(super) k0: CMat,
    pub(super) k1: CMat,
    /// The branches' `U^H`, `W`, `d_j` and `rho_j` (`state::Branches`, copied: this module
    /// does not import `state`, which holds a `Physical`).
    pub(super) uh: CMat,
    pub(super) load: CMat,
    pub(super) rate: Vec<f64>,
    pub(super) spin: Vec<f64>,
}

impl Physical {
    /// `Z(sigma)` at spin speed `speed` (see the module docs).
    pub fn dynamic_stiffness(&self, speed: f64, sigma: c64) -> CMat {
        let n = self.mass.nrows();
        let sigma2 = sigma * sigma;
        let mut z = CMat::from_fn(n, n, |i, j| {
            self.mass[(i, j)] * sigma2
                + (self.d0[(i, j)] + self.d1[(i, j)] * speed) * sigma
                + self.k0[(i, j)]
                + self.k1[(i, j)] * speed
        });
        if !self.rate.is_empty() {
            let w: Vec<c64> = (0..self.rate.len())
                .map(|j| {
                    let den = sigma + self.rate[j] - c64::new(0.0, speed * self.spin[j]);
                    c64::new(-self.rate[j], 0.0) / den
                })
                .collect();
            z += linalg::scaled_product(&self.load, &w, &self.uh);
        }
        z
    }
}

/// `(A - sigma I)^-1` of the state matrix `A` of [`state.rs`](super::state) through `Z(sigma)`,
/// never forming `A` or `M^-1`. From `(A - sigma I) [v, x, y] = [b1, b2, b3]`: `v = b2 + sigma x`,
/// `y_j = (b3_j - d_j u_j^H x) / (a_j - sigma)` with `a_j = -d_j + i Omega rho_j`, and the first
/// row multiplied by `-M` leaves
/// `Z(sigma) x = -M b1 - (sigma M + D) b2 + W diag(1 / (a_j - sigma)) b3`.
pub struct ShiftInvert {
    sigma: c64,
    /// The model's matrices (its `M`), shared, not copied.
    phys: Arc<Physical>,
    /// `sigma M + D(Omega)`.
    damping: CMat,
    /// `W` (`U diag(k)`), `U^H diag(d)` rows and `1 / (a_j - sigma)`.
    uk: CMat,
    dyx: CMat,
    dyy: Vec<c64>,
    lu: linalg::ComplexLu,
}

impl Physical {
    /// `A0`, `A1` from the second-order form: one solve with `M` for
    /// `[D0 | K0 + W_nu U^H | W | D1 | K1]`.
    pub fn state_matrices(&self) -> Result<(CMat, CMat), LinalgError> {
        let n = self.mass.nrows();
        let p = self.rate.len();
        let size = 2 * n + p;
        let mut rhs = CMat::zeros(n, 4 * n + p);
        for r in 0..n {
            for c in 0..n {
                rhs[(r, c)] = self.d0[(r, c)];
                rhs[(r, n + c)] = self.k0[(r, c)];
                rhs[(r, 2 * n + p + c)] = self.d1[(r, c)];
                rhs[(r, 3 * n + p + c)] = self.k1[(r, c)];
            }
            for j in 0..p {
                rhs[(r, 2 * n + j)] = self.load[(r, j)];
            }
        }
        let sol = linalg::mass_solve(&self.mass, &rhs)?;
        let mut a0 = CMat::zeros(size, size);
        let mut a1 = CMat::zeros(size, size);
        for r in 0..n {
            for c in 0..n {
                a0[(r, c)] = -sol[(r, c)];
                a0[(r, n + c)] = -sol[(r, n + c)];
                a1[(r, c)] = -sol[(r, 2 * n + p + c)];
                a1[(r, n + c)] = -sol[(r, 3 * n + p + c)];
            }
            for j in 0..p {
                a0[(r, 2 * n + j)] = sol[(r, 2 * n + j)];
            }
            a0[(n + r, r)] = c64::new(1.0, 0.0);
        }
        for j in 0..p {
            let d = self.rate[j];
            for c in 0..n {
                a0[(2 * n + j, n + c)] = self.uh[(j, c)] * d;
            }
            a0[(2 * n + j, 2 * n + j)] = c64::new(-d, 0.0);
            a1[(2 * n + j, 2 * n + j)] = c64::new(0.0, self.spin[j]);
        }
        Ok((a0, a1))
    }

    /// `(A(speed) - sigma I)^-1`, one factor of `Z(sigma)`.
    pub fn shift_invert(self: &Arc<Self>, speed: f64, sigma: c64) -> ShiftInvert {
        let n = self.mass.nrows();
        let p = self.rate.len();
        let damping = CMat::from_fn(n, n, |i, j| {
            self.mass[(i, j)] * sigma + self.d0[(i, j)] + self.d1[(i, j)] * speed
        });
        let dyy: Vec<c64> = (0..p)
            .map(|j| {
                let a = c64::new(-self.rate[j], speed * self.spin[j]);
                c64::new(1.0, 0.0) / (a - sigma)
            })
            .collect();
        ShiftInvert {
            sigma,
            phys: self.clone(),
            damping,
            uk: self.load.clone(),
            dyx: CMat::from_fn(p, n, |j, c| self.uh[(j, c)] * self.rate[j]),
            dyy,
            lu: linalg::ComplexLu::new(&self.dynamic_stiffness(speed, sigma)),
        }
    }
}

impl ShiftInvert {
    /// `(A - sigma I)^-1 b`, `b = [b1, b2, b3]` (`n`, `n`, `p`).
    pub fn solve(&self, b: &[c64]) -> Vec<c64> {
        let n = self.phys.mass.nrows();
        let (b1, rest) = b.split_at(n);
        let (b2, b3) = rest.split_at(n);
        let minus = c64::new(-1.0, 0.0);
        let mut x = vec![c64::new(0.0, 0.0); n];
        linalg::add_matvec(&mut x, &self.phys.mass, b1, minus);
        linalg::add_matvec(&mut x, &self.damping, b2, minus);
        if !b3.is_empty() {
            let w: Vec<c64> = b3.iter().zip(&self.dyy).map(|(b, d)| b * d).collect();
            linalg::add_matvec(&mut x, &self.uk, &w, c64::new(1.0, 0.0));
        }
        self.lu.solve_in_place(&mut x);
        let mut out: Vec<c64> = b2.iter().zip(&x).map(|(b, x)| b + self.sigma * x).collect();
        out.extend_from_slice(&x);
        let mut y = b3.to_vec();
        if !y.is_empty() {
            linalg::add_matvec(&mut y, &self.dyx, &x, minus);
        }
        out.extend(y.iter().zip(&self.dyy).map(|(y, d)| y * d));
        out
    }
}
