//! Undamped, nonrotating modes: the basis of the equivalent and nonviscous models.
//!
//! `K phi_i = w_i^2 M phi_i` with `phi^T M phi = I`. For a retained subset `Phi*` the projection
//! back is `Mbar^-1 Phi*^T M = Phi*^T M` (mass-normalised), which is `Phi^-1` when all modes are
//! kept; so one formula serves the full and the reduced mode sets (paper eq. 7 and after).

use crate::linalg::{self, LinalgError, RMat};
use crate::system::RotorSystem;

/// Mass-normalised undamped modes of the nonrotating rotor, lowest first.
#[derive(Debug, Clone)]
pub struct ModalBasis {
    /// Natural frequencies `w_i`, rad/s, ascending.
    pub omega: Vec<f64>,
    /// Modes as columns.
    pub phi: RMat,
}

/// Why a modal basis cannot be built.
#[derive(Debug, Clone, PartialEq)]
pub enum ModalError {
    Linalg(LinalgError),
    /// A mode with (numerically) zero frequency: the rotor is not supported.
    RigidBody {
        mode: usize,
        omega_squared: f64,
    },
}

impl std::fmt::Display for ModalError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Linalg(e) => write!(f, "{e}"),
            Self::RigidBody { mode, .. } => write!(
                f,
                "mode {mode} of the nonrotating system has zero natural frequency: the rotor \
                 needs supports (stiffness) that hold it in place"
            ),
        }
    }
}

impl ModalBasis {
    /// All modes of `(K, M)`, `K` the total stiffness.
    pub fn of(system: &RotorSystem) -> Result<Self, ModalError> {
        let k = system.stiffness();
        let modes = linalg::symmetric_modes(&k, &system.mass).map_err(ModalError::Linalg)?;
        // A rigid-body mode has w^2 ~ 0 relative to the largest; equivalent and nonviscous
        // damping divide by w, so refuse it here rather than produce infinities.
        let largest = modes.omega_squared.iter().cloned().fold(0.0, f64::max);
        for (i, &w2) in modes.omega_squared.iter().enumerate() {
            if w2 <= 1e-11 * largest || w2 <= 0.0 {
                return Err(ModalError::RigidBody {
                    mode: i + 1,
                    omega_squared: w2,
                });
            }
        }
        Ok(ModalBasis {
            omega: modes.omega_squared.iter().map(|w2| w2.sqrt()).collect(),
            phi: modes.phi,
        })
    }

    /// The lowest `count` modes.
    pub fn truncated(&self, count: usize) -> Self {
        let count = count.min(self.omega.len());
        ModalBasis {
            omega: self.omega[..count].to_vec(),
            phi: self.phi.subcols(0, count).to_owned(),
        }
    }

    pub fn len(&self) -> usize {
        self.omega.len()
    }

    pub fn is_empty(&self) -> bool {
        self.omega.is_empty()
    }

    /// Modal projection of a symmetric matrix: `Phi^T A Phi`.
    pub fn project(&self, a: &RMat) -> RMat {
        self.phi.transpose() * a * &self.phi
    }

    /// `M Phi`: its columns map physical coordinates to modal ones (`eta = (M Phi)^T q`).
    pub fn participation(&self, mass: &RMat) -> RMat {
        mass * &self.phi
    }
}
