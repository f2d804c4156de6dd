//! Nonviscous damping (model NVD; paper eqs. 11-31, MODEL.md section 4).
//!
//! A hysteretic damper (loss stiffness `eta k`) becomes `m` Maxwell branches, spring
//! `k_j = eta k gamma_j` in series with damper `c_j = k_j / d_j`, relaxation rates
//! `d_j = w0 a^((2j - m - 1)/2)` centred on the natural frequency `w0` of the mode it serves.
//! The weights `gamma_j` are fixed by collocation: the branches' loss stiffness equals `eta k`
//! at each `omega = d_i`, `sum_j gamma_j r_ij / (1 + r_ij^2) = 1` with `r_ij = d_i/d_j = a^(i-j)`,
//! a Toeplitz system in `(m, a)` only. A branch's static load is zero; at high frequency it
//! adds `sum_j nu_j k_j` of stiffness (`nu_j = 1`: plain Maxwell branch).
//!
//! On a multi-degree-of-freedom rotor (eq. 28) each retained undamped mode `i` gets one
//! nonrotating and one rotating damper, with loss stiffness `(Phi^T K'' Phi)_ii`, acting on the
//! modal coordinate `eta_i = (M phi_i)^T q`. Written on the physical coordinates (the paper's
//! back-transformation, exact when all modes are kept) the branch couples through `u = M phi_i`.
//! A damper with zero loss adds no branches.

use super::Bases;
use super::state::{Branches, SecondOrder, StateModel};
use crate::fem::modal::ModalBasis;
use crate::linalg::{self, CMat, LinalgError, RMat, Sparse, c64};
use crate::model::damping::NonviscousSpec;
pub use crate::model::damping::{BranchSet, BranchSetError, collocation_gammas};
use crate::system::{Layout, Realized, RotorSystem};

/// All branches of the model on the rotor, in physical coordinates (the paper's
/// back-transformed form), for each realization of its loss (one per support table speed;
/// one in all for constant supports). A damper exists where its mode has loss at some speed,
/// so every realization has the same internal coordinates.
///
/// Nonrotating dampers serve the modes of `bases` in the layout (the real x/y modes when the
/// coordinates are doubled); rotating ones, whose dampers are in the rotor, the axisymmetric
/// modes, on `r` (spin +1) and, doubled, on `conj r` too (spin -1).
pub fn branches(
    realized: &[&Realized],
    rotor_loss: &Sparse,
    bases: &Bases,
    spec: &NonviscousSpec,
) -> Vec<Branches> {
    let n_layout = realized[0].size();
    let n = rotor_loss.nrows();
    let doubled = realized[0].layout == Layout::Doubled;
    let axis = &bases.axis;
    let axis_coupling = linalg::to_complex(&axis.participation(&bases.axis_mass));
    let loss_r = axis.project(rotor_loss);
    // Nonrotating modes, their couplings, and their loss at each realization.
    let (omega_n, coupling_n, loss_n): (&[f64], CMat, Vec<Vec<f64>>) = match &bases.xy {
        None => {
            let phi = linalg::to_complex(&axis.phi);
            let loss = realized
                .iter()
                .map(|r| modal_loss(&r.loss_nonrotating, &phi))
                .collect();
            (&axis.omega, axis_coupling.clone(), loss)
        }
        Some((xy, mass)) => {
            let loss = realized
                .iter()
                .map(|r| modal_loss(&r.loss_nonrotating, &xy.phi))
                .collect();
            (&xy.omega, mass * &xy.phi, loss)
        }
    };
    let mut b = Builder {
        out: realized.iter().map(|_| Branches::none(n_layout)).collect(),
        columns: vec![],
    };
    let nonrotating = |i: usize, b: &mut Builder| {
        let loss: Vec<f64> = loss_n.iter().map(|l| l[i].max(0.0)).collect();
        if omega_n[i] > 0.0 && loss.iter().any(|&l| l > 0.0) {
            let col = (0..n_layout).map(|r| coupling_n[(r, i)]).collect();
            b.add(&spec.nonrotating, omega_n[i], &loss, i, 0.0, col);
        }
    };
    let rotating = |i: usize, b: &mut Builder| {
        let l = loss_r[(i, i)];
        if l <= 0.0 {
            return;
        }
        let loss = vec![l; realized.len()];
        let copies: &[f64] = if doubled { &[1.0, -1.0] } else { &[1.0] };
        for &spin in copies {
            let offset = if spin > 0.0 { 0 } else { n };
            let col = (0..n_layout)
                .map(|r| {
                    if r >= offset && r < offset + n {
                        axis_coupling[(r - offset, i)]
                    } else {
                        c64::new(0.0, 0.0)
                    }
                })
                .collect();
            b.add(&spec.rotating, axis.omega[i], &loss, i, spin, col);
        }
    };
    if doubled {
        (0..omega_n.len()).for_each(|i| nonrotating(i, &mut b));
        (0..axis.omega.len()).for_each(|i| rotating(i, &mut b));
    } else {
        // One damper pair per mode, in the order of the modes.
        for i in 0..axis.omega.len() {
            nonrotating(i, &mut b);
            rotating(i, &mut b);
        }
    }
    let u = CMat::from_fn(n_layout, b.columns.len(), |r, c| b.columns[c][r]);
    for br in &mut b.out {
        br.coupling = u.clone();
    }
    b.out
}

/// The branches of every realization, built damper by damper.
struct Builder {
    out: Vec<Branches>,
    columns: Vec<Vec<c64>>,
}

impl Builder {
    /// A damper of `set` tuned at `w0` with loss stiffness `loss` (one per realization) on the
    /// coordinate `col^H q`.
    fn add(
        &mut self,
        set: &BranchSet,
        w0: f64,
        loss: &[f64],
        mode: usize,
        spin: f64,
        col: Vec<c64>,
    ) {
        for (j, d) in set.rates(w0).into_iter().enumerate() {
            for (b, l) in self.out.iter_mut().zip(loss) {
                let k = l * set.gamma()[j];
                b.stiffness.push(k);
                b.main_stiffness.push(set.nu()[j] * k);
                b.rate.push(d);
                b.spin.push(spin);
                b.mode.push(mode);
                b.index.push(j);
            }
            self.columns.push(col.clone());
        }
    }
}

/// `(phi_i^H K'' phi_i)` of each mode.
fn modal_loss(k_loss: &CMat, phi: &CMat) -> Vec<f64> {
    let kp = k_loss * phi;
    (0..phi.ncols())
        .map(|i| {
            (0..phi.nrows())
                .map(|r| (phi[(r, i)].conj() * kp[(r, i)]).re)
                .sum()
        })
        .collect()
}

/// The model in modal coordinates (paper eq. 28): `Phi^T (.) Phi` of the viscous rotor (the
/// modal gyroscopic and damping matrices full), one damper pair per retained mode on its own
/// modal coordinate. With all modes kept its poles are those of the physical form; with fewer,
/// it is the modally truncated rotor. Single layout, constant supports.
pub fn modal_form(
    system: &RotorSystem,
    basis: &ModalBasis,
    spec: &NonviscousSpec,
) -> Result<StateModel, LinalgError> {
    let r = Realized::at(system, 0.0);
    let so = SecondOrder::viscous(&r).project(&basis.phi);
    let k = basis.len();
    let identity = RMat::from_fn(k, k, |i, j| if i == j { 1.0 } else { 0.0 });
    let loss_n = basis.project(&system.hysteretic_nonrotating);
    let loss_r = basis.project(&system.hysteretic_rotating);
    let mut out = Branches::none(k);
    let mut columns: Vec<usize> = vec![];
    for (i, &w) in basis.omega.iter().enumerate() {
        for (set, loss, spin) in [
            (&spec.nonrotating, loss_n[(i, i)], 0.0),
            (&spec.rotating, loss_r[(i, i)], 1.0),
        ] {
            if loss <= 0.0 || w == 0.0 {
                continue;
            }
            for (j, d) in set.rates(w).into_iter().enumerate() {
                let kb = loss * set.gamma()[j];
                out.stiffness.push(kb);
                out.main_stiffness.push(set.nu()[j] * kb);
                out.rate.push(d);
                out.spin.push(spin);
                out.mode.push(i);
                out.index.push(j);
                columns.push(i);
            }
        }
    }
    out.coupling = CMat::from_fn(k, columns.len(), |r, c| {
        c64::new(identity[(r, columns[c])], 0.0)
    });
    StateModel::new(&so, &out)
}
