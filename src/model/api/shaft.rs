//! Wire types of a shaft beyond uniform segments: sleeves laid over it and proportional damping.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// Proportional (Rayleigh) damping of shaft elements: `C_e = alpha M_e + beta K_e`, with `K_e`
/// the element's bending stiffness and the geometric stiffness of its axial force (not of its
/// torque).
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct RayleighInput {
    /// Mass-proportional coefficient, 1/s (>= 0).
    #[serde(default)]
    #[schema(minimum = 0.0)]
    pub alpha: f64,
    /// Stiffness-proportional coefficient, s (>= 0).
    #[serde(default)]
    #[schema(minimum = 0.0)]
    pub beta: f64,
    /// `rotating` (default): damping of the shaft's material, which turns with it and so adds
    /// the circulatory stiffness `-i Omega C` that destabilises above the first critical.
    /// `nonrotating`: added to the nonrotating damping, without that term (as ROSS 2.3.0
    /// adds it).
    #[serde(default)]
    pub frame: DampingFrame,
}

/// The frame a damping acts in.
#[derive(Debug, Clone, Copy, Default, Deserialize, Serialize, ToSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum DampingFrame {
    #[default]
    Rotating,
    Nonrotating,
}

/// An element laid over shaft elements (a sleeve, a shrink-fitted part, a lamination stack):
/// it spans the `elements` shaft elements from node `node` on, each piece as long as the shaft
/// element under it, and its matrices add to theirs. A sleeve of negligible stiffness (ROSS's
/// compressor example gives its sleeves E = G = 1 psi) adds mass and inertia only.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct SleeveInput {
    /// The shaft node it starts at.
    #[schema(minimum = 0)]
    pub node: i64,
    /// Shaft elements it spans, from `node` on (default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub elements: Option<i64>,
    /// Outer diameter at its left end, m (> 0).
    #[schema(exclusive_minimum = 0.0)]
    pub outer_diameter: f64,
    /// Inner diameter at its left end, m (>= 0, < outer diameter; default 0).
    #[serde(default)]
    #[schema(minimum = 0.0)]
    pub inner_diameter: f64,
    /// Outer diameter at its right end, m (default `outer_diameter`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub outer_diameter_right: Option<f64>,
    /// Inner diameter at its right end, m (default `inner_diameter`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inner_diameter_right: Option<f64>,
    /// Name of a material in `materials`.
    pub material: String,
    /// Shear factor chi = 1/kappa (default: Cowper's formula).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shear_factor: Option<f64>,
    /// Axial force, N (tension > 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub axial_force: Option<f64>,
    /// Torque, N m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub torque: Option<f64>,
    /// Proportional damping.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rayleigh_damping: Option<RayleighInput>,
}
