//! Equivalent viscous damping (model E; paper eqs. 5-7 and 9, MODEL.md section 3).
//!
//! With the mass-normalised undamped modes `Phi` (natural frequencies `w_i`), for nonrotating
//! and rotating damping separately: `kbar''_ii = (Phi^H K'' Phi)_ii`, `cbar_ii = kbar''_ii / w_i`,
//! and back to physical coordinates with `Phi^-1 = Phi^H M` (also right for a reduced mode set,
//! `Mbar = I`): `C_eq = (M Phi) diag(cbar) (M Phi)^H`. Off-diagonal modal terms are dropped
//! (light damping). The rotating part is rotating damping: it brings `-i Omega C_eq,r`.
//! Jeffcott: `c_eq = k''/w_n`, threshold `Omega* = 1 + eta_n / eta_r` (eq. 10).
//!
//! On supports that are not isotropic both parts are built on the real x/y modes (doubled
//! coordinates): each x/y mode then gets its own share of the shaft's loss, which depends on
//! how much of its strain energy is in the shaft, in x and in y. The rotating part acts on the
//! velocity relative to the rotor, `C_eq,r (q' - i Omega S q)` (`S`: the sign of the spin terms
//! per row), as the rotating viscous damping does.

use super::Bases;
use super::state::SecondOrder;
use crate::fem::modal::ModalBasis;
use crate::linalg::{self, CMat, RMat, Sparse};
use crate::system::Realized;

/// `C_eq` for one hysteretic matrix `K''` over modes `phi` (columns, `phi^H M phi = I`).
pub fn equivalent(k_loss: &CMat, mass: &CMat, omega: &[f64], phi: &CMat) -> CMat {
    let p = mass * phi;
    let n = mass.nrows();
    let kp = k_loss * phi;
    let mut c = CMat::zeros(n, n);
    for (i, w) in omega.iter().enumerate() {
        if *w == 0.0 {
            // A rigid-body mode (a free train's): no stiffness, no loss.
            continue;
        }
        let modal: f64 = (0..n).map(|r| (phi[(r, i)].conj() * kp[(r, i)]).re).sum();
        let cbar = modal / w;
        if cbar == 0.0 {
            continue;
        }
        for s in 0..n {
            let ps = p[(s, i)].conj() * cbar;
            for r in 0..n {
                c[(r, s)] += p[(r, i)] * ps;
            }
        }
    }
    c
}

/// `C_eq` for a real `K''` over a real basis (the single layout's arithmetic).
pub fn equivalent_matrix(k_loss: &Sparse, mass: &Sparse, basis: &ModalBasis) -> RMat {
    let modal = basis.project(k_loss);
    let p = basis.participation(mass);
    let n = mass.nrows();
    let mut c = RMat::zeros(n, n);
    for (i, w) in basis.omega.iter().enumerate() {
        if *w == 0.0 {
            continue;
        }
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

/// `C_eq,r` and `C_eq,n` of a realization, in its layout.
pub fn matrices(r: &Realized, rotor_loss: &Sparse, bases: &Bases) -> (CMat, CMat) {
    match &bases.xy {
        None => {
            let c_r = equivalent_matrix(rotor_loss, &bases.axis_mass, &bases.axis);
            let c_n = equivalent(
                &r.loss_nonrotating,
                &linalg::to_complex(&bases.axis_mass.to_dense()),
                &bases.axis.omega,
                &linalg::to_complex(&bases.axis.phi),
            );
            (linalg::to_complex(&c_r), c_n)
        }
        Some((xy, mass)) => (
            equivalent(&r.loss_rotating, mass, &xy.omega, &xy.phi),
            equivalent(&r.loss_nonrotating, mass, &xy.omega, &xy.phi),
        ),
    }
}

/// The rotor with `C_n + C_eq,n` and `C_r + C_eq,r`.
pub fn second_order(r: &Realized, rotor_loss: &Sparse, bases: &Bases) -> SecondOrder {
    let (c_r, c_n) = matrices(r, rotor_loss, bases);
    SecondOrder::with_damping(
        r,
        &(&r.damping_nonrotating + &c_n),
        &(&r.damping_rotating + &c_r),
    )
}
