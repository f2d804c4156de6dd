//! From the second-order form to the first-order state matrix, with massless internal
//! coordinates eliminated by structure (MODEL.md section 4).
//!
//! Physical coordinates `x` (n, with mass), internal coordinates `y` (p, massless):
//!
//! ```text
//! M x'' + D(Omega) x' + (K(Omega) + U diag(nu k) U^T) x - U diag(k) y = F
//!                                   y' = (-d + i Omega rho) y + d (U^T x)
//! ```
//!
//! The second line is the Maxwell branch `c_j (y_j' - i Omega rho_j y_j) + k_j (y_j - u_j^T x) = 0`
//! divided by `c_j = k_j / d_j` (`rho_j = 1` for a rotating branch, 0 otherwise). With
//! `v = x'` the state `z = [v, x, y]` has `2n + p` entries, not `2(n + p)`, and
//! `z' = A(Omega) z` with `A = A0 + Omega A1` (`D = D0 + Omega D1`, `K = K0 + Omega K1`).

use crate::linalg::{self, CMat, LinalgError, RMat, c64};
use crate::system::RotorSystem;

/// `M x'' + (D0 + Omega D1) x' + (K0 + Omega K1) x = F`, complex coefficients.
#[derive(Debug, Clone)]
pub struct SecondOrder {
    pub mass: RMat,
    pub d0: CMat,
    pub d1: CMat,
    pub k0: CMat,
    pub k1: CMat,
    /// Real stiffness, kept to classify poles by where their energy lies.
    pub stiffness: RMat,
}

impl SecondOrder {
    /// The rotor with its viscous damping only: `D = C_n + C_r - i Omega G`,
    /// `K = K - i Omega C_r`.
    pub fn viscous(s: &RotorSystem) -> Self {
        Self::with_damping(s, &s.damping_nonrotating, &s.damping_rotating)
    }

    /// The rotor with the given nonrotating and rotating viscous damping matrices.
    pub fn with_damping(s: &RotorSystem, c_n: &RMat, c_r: &RMat) -> Self {
        let n = s.n();
        let k = s.stiffness();
        let i = c64::new(0.0, 1.0);
        SecondOrder {
            mass: s.mass.clone(),
            d0: linalg::to_complex(&(c_n + c_r)),
            d1: CMat::from_fn(n, n, |r, c| -i * s.gyroscopic[(r, c)]),
            k0: linalg::to_complex(&k),
            k1: CMat::from_fn(n, n, |r, c| -i * c_r[(r, c)]),
            stiffness: k,
        }
    }

    pub fn n(&self) -> usize {
        self.mass.nrows()
    }

    /// `Phi^T (.) Phi` of every matrix: the system in the coordinates `q = Phi eta`.
    pub fn project(&self, phi: &RMat) -> SecondOrder {
        let pc = linalg::to_complex(phi);
        let pt = pc.transpose().to_owned();
        let c = |a: &CMat| &pt * a * &pc;
        SecondOrder {
            mass: phi.transpose() * &self.mass * phi,
            d0: c(&self.d0),
            d1: c(&self.d1),
            k0: c(&self.k0),
            k1: c(&self.k1),
            stiffness: phi.transpose() * &self.stiffness * phi,
        }
    }
}

/// Maxwell branches on massless internal coordinates (see the module docs).
#[derive(Debug, Clone)]
pub struct Branches {
    /// `U`: column j maps physical coordinates to the coordinate branch j acts on.
    pub coupling: RMat,
    /// Branch spring stiffness `k_j`.
    pub stiffness: Vec<f64>,
    /// Stiffness `nu_j k_j` the branch adds on its main coordinate.
    pub main_stiffness: Vec<f64>,
    /// Relaxation rate `d_j = k_j / c_j`, 1/s.
    pub rate: Vec<f64>,
    /// Whether the branch's damper is in the rotor (circulatory term on `y_j`).
    pub rotating: Vec<bool>,
    /// Mode (0-based) whose damper the branch belongs to.
    pub mode: Vec<usize>,
    /// Index j (0-based) of the branch within its damper.
    pub index: Vec<usize>,
}

impl Branches {
    /// No internal coordinates.
    pub fn none(n: usize) -> Self {
        Branches {
            coupling: RMat::zeros(n, 0),
            stiffness: vec![],
            main_stiffness: vec![],
            rate: vec![],
            rotating: vec![],
            mode: vec![],
            index: vec![],
        }
    }

    pub fn len(&self) -> usize {
        self.stiffness.len()
    }

    pub fn is_empty(&self) -> bool {
        self.stiffness.is_empty()
    }
}

/// `z' = (A0 + Omega A1) z`, `z = [v, x, y]`.
#[derive(Debug, Clone)]
pub struct StateModel {
    a0: CMat,
    a1: CMat,
    n: usize,
    branches: Branches,
    stiffness: RMat,
}

impl StateModel {
    pub fn new(so: &SecondOrder, br: &Branches) -> Result<Self, LinalgError> {
        let n = so.n();
        let p = br.len();
        let size = 2 * n + p;
        let u = &br.coupling;
        // Right-hand sides for one SPD solve with M: [D0 | K0 + U nu k U^T | U k | D1 | K1].
        let mut rhs = CMat::zeros(n, 4 * n + p);
        for r in 0..n {
            for c in 0..n {
                let mut kadd = 0.0;
                for j in 0..p {
                    kadd += u[(r, j)] * br.main_stiffness[j] * u[(c, j)];
                }
                rhs[(r, c)] = so.d0[(r, c)];
                rhs[(r, n + c)] = so.k0[(r, c)] + kadd;
                rhs[(r, 2 * n + p + c)] = so.d1[(r, c)];
                rhs[(r, 3 * n + p + c)] = so.k1[(r, c)];
            }
            for j in 0..p {
                rhs[(r, 2 * n + j)] = c64::new(u[(r, j)] * br.stiffness[j], 0.0);
            }
        }
        let sol = linalg::spd_solve(&so.mass, &rhs)?;
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
            let d = br.rate[j];
            for c in 0..n {
                a0[(2 * n + j, n + c)] = c64::new(d * u[(c, j)], 0.0);
            }
            a0[(2 * n + j, 2 * n + j)] = c64::new(-d, 0.0);
            if br.rotating[j] {
                a1[(2 * n + j, 2 * n + j)] = c64::new(0.0, 1.0);
            }
        }
        Ok(StateModel {
            a0,
            a1,
            n,
            branches: br.clone(),
            stiffness: so.stiffness.clone(),
        })
    }

    /// `A0`: the state matrix at rest.
    pub fn a0(&self) -> &CMat {
        &self.a0
    }

    /// `A1 = dA/dOmega`.
    pub fn a1(&self) -> &CMat {
        &self.a1
    }

    /// The state matrix at spin speed `speed`.
    pub fn at(&self, speed: f64) -> CMat {
        &self.a0 + faer_scale(speed, &self.a1)
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

    /// Fraction of a mode's elastic energy stored in the rotor rather than in the branch
    /// springs: near 1 for a rotor pole, O(eta) for an internal one, whatever the units of
    /// the internal coordinates.
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
        let mut e_branch = 0.0;
        for (j, yj) in y.iter().enumerate() {
            let ux: c64 = x
                .iter()
                .enumerate()
                .map(|(c, xc)| self.branches.coupling[(c, j)] * xc)
                .sum();
            e_branch += self.branches.stiffness[j] * (yj - ux).norm_sqr();
        }
        let total = e_rotor.abs() + e_branch;
        if total > 0.0 {
            e_rotor.abs() / total
        } else {
            1.0
        }
    }
}

fn faer_scale(s: f64, a: &CMat) -> CMat {
    CMat::from_fn(a.nrows(), a.ncols(), |i, j| a[(i, j)] * s)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::rotor::Jeffcott;

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
        let m = StateModel::new(&SecondOrder::viscous(&s), &Branches::none(1)).unwrap();
        let a = m.at(3.0);
        assert!((a[(0, 0)] - c64::new(-0.3, 0.0)).norm() < 1e-15);
        assert!((a[(0, 1)] - c64::new(-4.0, 0.3)).norm() < 1e-15);
        assert!((a[(1, 0)] - c64::new(1.0, 0.0)).norm() < 1e-15);
    }
}
