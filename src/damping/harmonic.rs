//! The dynamic stiffness of a linear model, for harmonic solves without the state matrix.
//!
//! At `x = X e^{sigma t}` the model of `state.rs` (`M x'' + D x' + K x - U k y = F`, each
//! branch `y_j' = (-d_j + i Omega rho_j) y_j + d_j u_j^H x`) has
//! `y_j = d_j / (sigma + d_j - i Omega rho_j) u_j^H X`, so one system of the rotor's size is left:
//!
//! ```text
//! Z(sigma) X = F,   Z = sigma^2 M + sigma D(Omega) + K(Omega) + U diag(nu k) U^H
//!                       - U diag(k_j d_j / (sigma + d_j - i Omega rho_j)) U^H
//! ```
//!
//! Solved as it stands, never through `M^-1`: the first-order system `(sigma - A) z = B f`
//! carries `M^-1 K`, of size `w_max^2`. On the soft heavily damped cross-coupled held-out rotor
//! (113 elements) the first-order unbalance response differed from ROSS's by 1.6e-7 of the
//! largest response; `Z X = F` differs from an extended-precision solve of ROSS's matrices by
//! 3.5e-10, and costs a factor of the rotor's size, not of the state's `2n + p`.

use crate::linalg::{self, CMat, c64};

/// The second-order matrices a [`StateModel`](super::StateModel) was built from, kept by
/// [`StateModel::harmonic`](super::StateModel::harmonic) for constant coefficients.
#[derive(Debug, Clone)]
pub struct Physical {
    pub(super) mass: CMat,
    pub(super) d0: CMat,
    pub(super) d1: CMat,
    /// `K0 + U diag(nu k) U^H`.
    pub(super) k0: CMat,
    pub(super) k1: CMat,
    /// The branches' `U`, `U^H`, `k_j`, `d_j` and `rho_j` (`state::Branches`, copied: this
    /// module does not import `state`, which holds a `Physical`).
    pub(super) u: CMat,
    pub(super) uh: CMat,
    pub(super) stiffness: Vec<f64>,
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
        if !self.stiffness.is_empty() {
            let w: Vec<c64> = (0..self.stiffness.len())
                .map(|j| {
                    let den = sigma + self.rate[j] - c64::new(0.0, speed * self.spin[j]);
                    c64::new(-self.stiffness[j] * self.rate[j], 0.0) / den
                })
                .collect();
            z += linalg::scaled_product(&self.u, &w, &self.uh);
        }
        z
    }
}
