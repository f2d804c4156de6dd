//! Damping models: each turns a [`RotorSystem`] with hysteretic (imaginary) stiffness into
//! first-order systems `z' = A(Omega) z` that the analyses solve.
//!
//! - `viscous`: the loss factors are dropped.
//! - `hysteretic` (H, MODEL.md section 2): four linear problems, one per sign pair `(a, b)` of
//!   `K + i a K''_n + i b K''_r`; a root is a pole only where `sgn(omega) = a` and
//!   `sgn(omega - Omega) = b`. Frequency domain only.
//! - `equivalent` (E, section 3): each mode's loss stiffness over its natural frequency, as a
//!   viscous damping matrix, rotating (with its circulatory term) and nonrotating apart.
//! - `nonviscous` (NVD, section 4): Maxwell branches on massless internal coordinates.
//!
//! Every `A(Omega) = A0 + Omega A1` is affine in the spin speed, so a sweep assembles once.

pub mod equivalent;
pub mod hysteretic;
pub mod nonviscous;
pub mod state;

use crate::fem::modal::{ModalBasis, ModalError};
use crate::linalg::LinalgError;
use crate::model::damping::DampingModel;
use crate::system::RotorSystem;
pub use state::{Branches, SecondOrder, StateModel};

/// A rotor under one damping model, ready for eigenvalue analyses.
#[derive(Debug, Clone)]
pub enum DampedModel {
    /// Viscous, equivalent and nonviscous models: one linear system.
    Linear(Box<StateModel>),
    /// The hysteretic model: one linear system per sign pair, roots filtered by consistency.
    Hysteretic(Vec<hysteretic::SignedModel>),
}

/// Why a damping model cannot be built for a rotor.
#[derive(Debug, Clone, PartialEq)]
pub enum DampingError {
    Modal(ModalError),
    Linalg(LinalgError),
}

impl std::fmt::Display for DampingError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Modal(e) => write!(f, "{e}"),
            Self::Linalg(e) => write!(f, "{e}"),
        }
    }
}

impl From<ModalError> for DampingError {
    fn from(e: ModalError) -> Self {
        Self::Modal(e)
    }
}

impl From<LinalgError> for DampingError {
    fn from(e: LinalgError) -> Self {
        Self::Linalg(e)
    }
}

impl DampedModel {
    /// Builds the model. The modal basis (equivalent, nonviscous) is computed here, once.
    pub fn build(system: &RotorSystem, model: &DampingModel) -> Result<Self, DampingError> {
        let viscous = SecondOrder::viscous(system);
        match model {
            DampingModel::Viscous => Ok(Self::Linear(Box::new(StateModel::new(
                &viscous,
                &Branches::none(system.n()),
            )?))),
            DampingModel::Hysteretic => Ok(Self::Hysteretic(hysteretic::signed_models(system)?)),
            DampingModel::Equivalent { modes } => {
                let basis = basis(system, *modes)?;
                let so = equivalent::second_order(system, &basis);
                Ok(Self::Linear(Box::new(StateModel::new(
                    &so,
                    &Branches::none(system.n()),
                )?)))
            }
            DampingModel::Nonviscous(spec) => {
                let basis = basis(system, spec.modes)?;
                let branches = nonviscous::branches(system, &basis, spec);
                Ok(Self::Linear(Box::new(StateModel::new(
                    &viscous, &branches,
                )?)))
            }
        }
    }

    /// Complex degrees of freedom of the rotor (not counting internal coordinates).
    pub fn dofs(&self) -> usize {
        match self {
            Self::Linear(m) => m.n(),
            Self::Hysteretic(v) => v[0].model.n(),
        }
    }

    /// Size of each first-order eigenproblem.
    pub fn states(&self) -> usize {
        match self {
            Self::Linear(m) => m.size(),
            Self::Hysteretic(v) => v[0].model.size(),
        }
    }
}

fn basis(system: &RotorSystem, modes: Option<usize>) -> Result<ModalBasis, ModalError> {
    let all = ModalBasis::of(system)?;
    Ok(match modes {
        Some(k) => all.truncated(k),
        None => all,
    })
}
