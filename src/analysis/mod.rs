//! Analyses on a damped model: poles at one speed (`modal`), sweeps with branch tracking
//! (`campbell`), and the threshold of instability (`stability`).

pub mod audit;
pub mod campbell;
pub mod campbell_whirl;
pub mod consistent;
pub mod control;
pub mod criticals;
pub mod excitation;
pub mod interference;
pub mod large;
pub mod modal;
pub mod nearest;
pub mod poles;
pub mod reduction;
pub mod refine;
pub mod response;
pub mod roots;
pub mod run;
pub mod shaft_loads;
pub mod stability;
pub mod stability_large;
pub mod time;
pub mod tracking;
pub mod unbalance;

use crate::damping::DampingError;
use crate::linalg::LinalgError;

/// Why an analysis could not be carried out on a (valid) model.
#[derive(Debug, Clone, PartialEq)]
pub enum AnalysisError {
    Damping(DampingError),
    Linalg(LinalgError),
    Cancelled,
}

impl std::fmt::Display for AnalysisError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Damping(e) => write!(f, "{e}"),
            Self::Linalg(e) => write!(f, "{e}"),
            Self::Cancelled => write!(f, "cancelled"),
        }
    }
}

impl std::error::Error for AnalysisError {}

impl From<DampingError> for AnalysisError {
    fn from(e: DampingError) -> Self {
        Self::Damping(e)
    }
}

impl From<LinalgError> for AnalysisError {
    fn from(e: LinalgError) -> Self {
        Self::Linalg(e)
    }
}

impl From<control::Cancelled> for AnalysisError {
    fn from(_: control::Cancelled) -> Self {
        Self::Cancelled
    }
}
