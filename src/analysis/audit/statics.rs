//! Static deflection under gravity, support reactions, shear and bending moment (ROSS's
//! `run_static`).

use crate::analysis::AnalysisError;
use crate::model::rotor::BeamRotor;

/// How the shaft is held.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Held {
    /// By the supports' own stiffness at the given speed.
    Elastic { speed: f64 },
    /// Pinned at the support nodes.
    Rigid,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Reaction {
    /// Index of the support in the request's `rotor.supports`.
    pub support: usize,
    pub node: usize,
    /// Upward force on the shaft, N.
    pub y: f64,
    pub x: f64,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Deflection {
    pub node: usize,
    pub position: f64,
    pub y: f64,
    pub x: f64,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Station {
    pub element: usize,
    pub position: f64,
    /// ROSS's sign: minus the upward forces left of the section, N.
    pub shear: f64,
    /// ROSS's sign: negative sagging, N m.
    pub bending_moment: f64,
}

#[derive(Debug, Clone, PartialEq)]
pub struct StaticResult {
    pub reactions: Vec<Reaction>,
    pub nodes: Vec<Deflection>,
    /// Both ends of every element, left to right.
    pub stations: Vec<Station>,
    /// Weight of shaft and disks, N.
    pub weight: f64,
}

/// The rotor under gravity `gravity` along -y.
pub fn static_deflection(
    rotor: &BeamRotor,
    gravity: f64,
    held: Held,
) -> Result<StaticResult, AnalysisError> {
    let _ = (rotor, gravity, held);
    todo!()
}
