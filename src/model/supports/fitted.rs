//! Maxwell branches standing in for a support's dependence on the whirl frequency in the
//! time domain (`damping/whirl_fit.rs` fits them to a [`super::grid::Grid`]).
//!
//! Branch `j` is a spring `G_j` (a 2x2 matrix over `x, y`) in series with a damper `G_j / d_j`:
//! on the support's translation `u` it adds the force `-G_j (u - y_j)`, its internal
//! displacement following `y_j' = d_j (u - y_j)`, so at `u = U e^{i w t}` it adds the dynamic
//! stiffness `G_j i w / (i w + d_j)`: nothing statically, `G_j` at high frequency. The
//! support's own coefficients (its law) carry the rest: `K0 + i w C0 - w^2 M0`.

use super::Matrix2;

/// Most branches a support's fit may use.
pub const MAX_BRANCHES: usize = 16;

/// A support's branches: the rates, and each branch's stiffness at the speeds of its law's
/// table (one entry without speeds), linear between them and held outside, as the table is.
#[derive(Debug, Clone, PartialEq)]
pub struct Fitted {
    /// `d_j`, 1/s, increasing.
    pub rates: Vec<f64>,
    /// The spin speeds the stiffnesses are given at (empty: constant).
    pub speeds: Vec<f64>,
    /// Per speed, per rate, `G_j`.
    pub stiffness: Vec<Vec<Matrix2>>,
}

impl Fitted {
    /// Each branch's `G_j` at `speed`.
    pub fn at(&self, speed: f64) -> Vec<Matrix2> {
        let w = &self.speeds;
        let g = &self.stiffness;
        if w.len() < 2 || speed <= w[0] {
            return g[0].clone();
        }
        let last = w.len() - 1;
        if speed >= w[last] {
            return g[last].clone();
        }
        let k = w.partition_point(|&x| x <= speed) - 1;
        let t = (speed - w[k]) / (w[k + 1] - w[k]);
        g[k].iter()
            .zip(&g[k + 1])
            .map(|(a, b)| a.lerp(b, t))
            .collect()
    }
}
