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
use crate::linalg::{self, CMat, LinalgError, RMat, c64};
use crate::model::damping::NonviscousSpec;
use crate::system::{Layout, Realized, RotorSystem};

/// The branches of one nonviscous damper, independent of the damper's size and tuning.
#[derive(Debug, Clone, PartialEq)]
pub struct BranchSet {
    count: usize,
    spacing: f64,
    nu: Vec<f64>,
    gamma: Vec<f64>,
}

/// Why branch parameters are invalid: the field (relative to the damper) and the reason.
#[derive(Debug, Clone, PartialEq)]
pub struct BranchSetError {
    pub field: &'static str,
    pub message: String,
}

impl BranchSet {
    /// Largest number of branches per damper.
    pub const MAX_BRANCHES: usize = 12;
    /// Largest ratio between consecutive relaxation rates.
    pub const MAX_SPACING: f64 = 1e6;

    /// Validates `count` (1..=12), `spacing` (> 1) and `nu` (one per branch), and solves the
    /// collocation for the `gamma_j`, which must all be positive (a negative branch stiffness
    /// would be an active element: spacings below about 3 give one with 3 or more branches).
    pub fn new(count: usize, spacing: f64, nu: Vec<f64>) -> Result<Self, BranchSetError> {
        if !(1..=Self::MAX_BRANCHES).contains(&count) {
            return Err(BranchSetError {
                field: "branches",
                message: format!("must be between 1 and {} (got {count})", Self::MAX_BRANCHES),
            });
        }
        if !spacing.is_finite() || spacing <= 1.0 || spacing > Self::MAX_SPACING {
            return Err(BranchSetError {
                field: "spacing",
                message: format!(
                    "must be a number in (1, {:e}] (got {spacing})",
                    Self::MAX_SPACING
                ),
            });
        }
        if nu.len() != count {
            return Err(BranchSetError {
                field: "nu",
                message: format!("needs one value per branch: {count} (got {})", nu.len()),
            });
        }
        let gamma = collocation_gammas(count, spacing).map_err(|_| BranchSetError {
            field: "spacing",
            message: "the collocation system for the branch weights is singular".into(),
        })?;
        if let Some(g) = gamma.iter().find(|g| **g <= 0.0) {
            return Err(BranchSetError {
                field: "spacing",
                message: format!(
                    "too small for {count} branches: the collocation gives a branch weight \
                     {g:.4} <= 0 (use a larger spacing or fewer branches)"
                ),
            });
        }
        Ok(BranchSet {
            count,
            spacing,
            nu,
            gamma,
        })
    }

    pub fn count(&self) -> usize {
        self.count
    }
    pub fn spacing(&self) -> f64 {
        self.spacing
    }
    pub fn nu(&self) -> &[f64] {
        &self.nu
    }
    pub fn gamma(&self) -> &[f64] {
        &self.gamma
    }

    /// Relaxation rates `d_j` centred on `omega0`.
    pub fn rates(&self, omega0: f64) -> Vec<f64> {
        let m = self.count as f64;
        (1..=self.count)
            .map(|j| omega0 * self.spacing.powf((2.0 * j as f64 - m - 1.0) / 2.0))
            .collect()
    }

    /// Loss factor the branches give at frequency `omega` (relative to `eta`, so 1 is exact)
    /// for a damper tuned at `omega0`.
    pub fn relative_loss(&self, omega: f64, omega0: f64) -> f64 {
        self.rates(omega0)
            .iter()
            .zip(&self.gamma)
            .map(|(d, g)| {
                let r = omega / d;
                g * r / (1.0 + r * r)
            })
            .sum()
    }
}

/// Collocation weights `gamma_j` for `m` branches `a` apart (module docs).
pub fn collocation_gammas(m: usize, a: f64) -> Result<Vec<f64>, linalg::LinalgError> {
    let t = RMat::from_fn(m, m, |i, j| {
        let r = a.powf(i as f64 - j as f64);
        r / (1.0 + r * r)
    });
    linalg::solve_real(&t, &vec![1.0; m])
}

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
    rotor_loss: &RMat,
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
        if loss.iter().any(|&l| l > 0.0) {
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
                let k = l * set.gamma[j];
                b.stiffness.push(k);
                b.main_stiffness.push(set.nu[j] * k);
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
            if loss <= 0.0 {
                continue;
            }
            for (j, d) in set.rates(w).into_iter().enumerate() {
                let kb = loss * set.gamma[j];
                out.stiffness.push(kb);
                out.main_stiffness.push(set.nu[j] * kb);
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

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: &[f64], b: &[f64], tol: f64) -> bool {
        a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol)
    }

    #[test]
    fn collocation_gammas_are_model_md_values() {
        // MODEL.md section 4, to the printed digits.
        assert!(close(&collocation_gammas(1, 10.0).unwrap(), &[2.0], 1e-12));
        assert!(close(
            &collocation_gammas(2, 10.0).unwrap(),
            &[1.66942, 1.66942],
            5e-6
        ));
        assert!(close(
            &collocation_gammas(3, 10.0).unwrap(),
            &[1.703488, 1.325351, 1.703488],
            5e-7
        ));
        assert!(close(
            &collocation_gammas(4, 10.0).unwrap(),
            &[1.700088, 1.360036, 1.360036, 1.700088],
            5e-7
        ));
    }

    #[test]
    fn branches_restore_the_loss_factor_at_every_relaxation_rate() {
        let set = BranchSet::new(5, 10.0, vec![1.0; 5]).unwrap();
        for d in set.rates(370.0) {
            assert!((set.relative_loss(d, 370.0) - 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn rates_are_decades_centred_on_the_tuning_frequency() {
        let set = BranchSet::new(3, 10.0, vec![1.0; 3]).unwrap();
        assert!(close(&set.rates(2.0), &[0.2, 2.0, 20.0], 1e-14));
    }

    #[test]
    fn small_spacings_that_need_active_branches_are_refused() {
        let e = BranchSet::new(3, 2.0, vec![1.0; 3]).unwrap_err();
        assert_eq!(e.field, "spacing");
        assert!(BranchSet::new(0, 10.0, vec![]).is_err());
        assert!(BranchSet::new(13, 10.0, vec![1.0; 13]).is_err());
        assert!(BranchSet::new(3, 1.0, vec![1.0; 3]).is_err());
        assert!(BranchSet::new(3, f64::NAN, vec![1.0; 3]).is_err());
    }
}
