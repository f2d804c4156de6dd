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
pub mod report;
pub mod state;

use crate::fem::modal::{ModalBasis, ModalError};
use crate::linalg::LinalgError;
use crate::model::damping::DampingModel;
use crate::system::RotorSystem;
pub use state::{Branches, SecondOrder, StateModel};

/// A rotor under one damping model, ready for eigenvalue analyses.
#[derive(Debug, Clone)]
pub struct DampedModel {
    pub kind: ModelKind,
    /// Undamped nonrotating modes of the rotor (all of them): natural frequencies ascending,
    /// rad/s, and the basis a modal reduction starts from.
    pub basis: ModalBasis,
}

/// The linear problem(s) a damping model poses.
#[derive(Debug, Clone)]
pub enum ModelKind {
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
    /// Builds the model. The modal basis is computed once, here: it proves the rotor is held
    /// (no rigid-body mode) for every model, and it is the basis of the equivalent and
    /// nonviscous models.
    pub fn build(system: &RotorSystem, model: &DampingModel) -> Result<Self, DampingError> {
        let all = ModalBasis::of(system)?;
        let truncated = |modes: Option<usize>| match modes {
            Some(k) => all.truncated(k),
            None => all.clone(),
        };
        let n = system.n();
        let kind = match model {
            DampingModel::Viscous => ModelKind::Linear(Box::new(StateModel::new(
                &SecondOrder::viscous(system),
                &Branches::none(n),
            )?)),
            DampingModel::Hysteretic => ModelKind::Hysteretic(hysteretic::signed_models(system)?),
            DampingModel::Equivalent { modes } => {
                let so = equivalent::second_order(system, &truncated(*modes));
                ModelKind::Linear(Box::new(StateModel::new(&so, &Branches::none(n))?))
            }
            DampingModel::Nonviscous(spec) => {
                let branches = nonviscous::branches(system, &truncated(spec.modes), spec);
                ModelKind::Linear(Box::new(StateModel::new(
                    &SecondOrder::viscous(system),
                    &branches,
                )?))
            }
        };
        Ok(DampedModel { kind, basis: all })
    }

    /// Complex degrees of freedom of the rotor (not counting internal coordinates).
    pub fn dofs(&self) -> usize {
        match &self.kind {
            ModelKind::Linear(m) => m.n(),
            ModelKind::Hysteretic(v) => v[0].model.n(),
        }
    }

    /// Size of each first-order eigenproblem.
    pub fn states(&self) -> usize {
        match &self.kind {
            ModelKind::Linear(m) => m.size(),
            ModelKind::Hysteretic(v) => v[0].model.size(),
        }
    }
}
