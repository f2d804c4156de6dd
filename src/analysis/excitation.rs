//! What a torsional interference diagram answers (`interference`): each mode's crossings with
//! the excitations and API 684's separation margins.

use crate::model::train::Spec;

/// API 684's torsional separation margin.
pub const MARGIN: f64 = 0.10;

/// A crossing, or a mode's margin from a fixed line.
#[derive(Debug, Clone, PartialEq)]
pub struct Crossing {
    pub line: usize,
    pub mode: usize,
    /// Reference speed, rad/s (`None` for a fixed line).
    pub speed: Option<f64>,
    /// Natural frequency there, rad/s.
    pub frequency: f64,
    pub damping_ratio: f64,
    pub margin: f64,
    /// Beyond the sweep: extrapolated from the frequency nearest the operating range.
    pub beyond_sweep: bool,
}

impl Crossing {
    pub fn passes(&self) -> bool {
        self.margin >= MARGIN - 1e-12
    }
}

/// The diagram's answer.
#[derive(Debug, Clone, PartialEq)]
pub struct Interference {
    pub spec: Spec,
    pub crossings: Vec<Crossing>,
}
