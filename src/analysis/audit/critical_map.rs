//! The undamped critical speed map (ROSS's `run_ucs`).

use crate::analysis::AnalysisError;
use crate::analysis::control::Control;
use crate::model::rotor::BeamRotor;

/// Where a mode meets a support's actual stiffness.
#[derive(Debug, Clone, PartialEq)]
pub struct Intersection {
    /// Index of the support in the request's `rotor.supports`.
    pub support: usize,
    pub node: usize,
    /// `"kxx"` or `"kyy"`.
    pub coefficient: &'static str,
    /// Mode, from 1.
    pub mode: usize,
    pub stiffness: f64,
    pub frequency: f64,
}

#[derive(Debug, Clone, PartialEq)]
pub struct CriticalMap {
    /// `frequencies[mode][i]` at `stiffness[i]`, rad/s.
    pub frequencies: Vec<Vec<f64>>,
    pub intersections: Vec<Intersection>,
}

/// The lowest `modes` undamped natural frequencies at zero speed (one per degenerate pair)
/// with every support replaced by an isotropic undamped spring of each `stiffness`.
pub fn critical_speed_map(
    rotor: &BeamRotor,
    stiffness: &[f64],
    modes: usize,
    control: &Control,
) -> Result<CriticalMap, AnalysisError> {
    let _ = (rotor, stiffness, modes, control);
    todo!()
}
