//! Equivalent viscous damping (model E; paper eqs. 5-7 and 9, MODEL.md section 3).
//!
//! With the mass-normalised undamped modes `Phi` (natural frequencies `w_i`), for nonrotating
//! and rotating damping separately: `kbar''_ii = (Phi^T K'' Phi)_ii`, `cbar_ii = kbar''_ii / w_i`,
//! and back to physical coordinates with `Phi^-1 = Phi^T M` (also right for a reduced mode set,
//! `Mbar = I`): `C_eq = (M Phi) diag(cbar) (M Phi)^T`. Off-diagonal modal terms are dropped
//! (light damping). The rotating part is rotating damping: it brings `-i Omega C_eq,r`.
//! Jeffcott: `c_eq = k''/w_n`, threshold `Omega* = 1 + eta_n / eta_r` (eq. 10).

use super::state::SecondOrder;
use crate::fem::modal::ModalBasis;
use crate::linalg::RMat;
use crate::system::RotorSystem;

/// `C_eq` for one hysteretic matrix `K''`.
pub fn equivalent_matrix(k_loss: &RMat, mass: &RMat, basis: &ModalBasis) -> RMat {
    let modal = basis.project(k_loss);
    let p = basis.participation(mass);
    let n = mass.nrows();
    let mut c = RMat::zeros(n, n);
    for (i, w) in basis.omega.iter().enumerate() {
        let cbar = modal[(i, i)] / w;
        if cbar == 0.0 {
            continue;
        }
        for r in 0..n {
            for s in 0..n {
                c[(r, s)] += p[(r, i)] * cbar * p[(s, i)];
            }
        }
    }
    c
}

/// The rotor with `C_n + C_eq,n` and `C_r + C_eq,r`.
pub fn second_order(system: &RotorSystem, basis: &ModalBasis) -> SecondOrder {
    let c_n = &system.damping_nonrotating
        + equivalent_matrix(&system.hysteretic_nonrotating, &system.mass, basis);
    let c_r = &system.damping_rotating
        + equivalent_matrix(&system.hysteretic_rotating, &system.mass, basis);
    SecondOrder::with_damping(system, &c_n, &c_r)
}
