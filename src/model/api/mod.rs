//! Wire types of the HTTP/JSON contract (`../shared/spec/API.md`): what clients send and receive.
//! Field names are the contract; add fields, never rename them. All quantities SI, speeds and
//! frequencies in rad/s.
//!
//! This module holds the model every analysis takes (rotor, supports, damping, speeds); the
//! requests and answers live by kind: [`analyses`] (frequency domain), [`loads`] (forced
//! responses), [`service`] (health, problems, jobs).

mod analyses;
mod audit;
mod damping;
mod loads;
mod report;
mod service;
mod shaft;
mod studies;
mod torque;
mod train;
mod units;

pub use analyses::*;
pub use audit::*;
pub use damping::*;
pub use loads::*;
pub use report::*;
pub use service::*;
pub use shaft::*;
pub use studies::*;
pub use torque::*;
pub use train::*;
pub use units::*;

use serde::{Deserialize, Deserializer, Serialize};
use serde_json::Value;
use utoipa::ToSchema;

use super::tagged::{split_tag, strict_variant, unknown, variant};

/// The rotor model, tagged by `type`.
#[derive(Debug, Clone, Serialize, ToSchema)]
#[serde(tag = "type", rename_all = "lowercase")]
pub enum RotorInput {
    /// A point mass on a massless isotropic shaft (one node, node 0). With `mass = stiffness = 1`
    /// this is the paper's nondimensional rotor: speeds and poles come out in units of
    /// `sqrt(k/m)`.
    Jeffcott(JeffcottInput),
    /// A shaft of Timoshenko beam elements with rigid disks on isotropic supports.
    Beam(BeamInput),
    /// The rotor given directly as matrices in complex coordinates.
    Matrices(MatricesInput),
}

impl<'de> Deserialize<'de> for RotorInput {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        const TYPES: &[&str] = &["jeffcott", "beam", "matrices"];
        let (tag, rest) = split_tag(Value::deserialize(d)?, "type", TYPES)?;
        match tag.as_str() {
            "jeffcott" => strict_variant(rest).map(RotorInput::Jeffcott),
            "beam" => strict_variant(rest).map(RotorInput::Beam),
            "matrices" => strict_variant(rest).map(RotorInput::Matrices),
            other => Err(unknown("type", other, TYPES)),
        }
    }
}

/// Jeffcott (Laval) rotor.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct JeffcottInput {
    /// Mass, kg (> 0).
    #[schema(exclusive_minimum = 0.0)]
    pub mass: f64,
    /// Shaft stiffness, N/m (> 0).
    #[schema(exclusive_minimum = 0.0)]
    pub stiffness: f64,
    /// Loss factor of the rotating (shaft material) hysteretic damping, in [0, 1).
    #[serde(default)]
    #[schema(minimum = 0.0, exclusive_maximum = 1.0)]
    pub loss_factor_rotating: f64,
    /// Loss factor of the nonrotating (support) hysteretic damping, in [0, 1).
    #[serde(default)]
    #[schema(minimum = 0.0, exclusive_maximum = 1.0)]
    pub loss_factor_nonrotating: f64,
    /// Viscous rotating damping, N s/m (>= 0). Kept under every damping model.
    #[serde(default)]
    #[schema(minimum = 0.0)]
    pub damping_rotating: f64,
    /// Viscous nonrotating damping, N s/m (>= 0). Kept under every damping model.
    #[serde(default)]
    #[schema(minimum = 0.0)]
    pub damping_nonrotating: f64,
}

/// Finite-element rotor. Nodes are numbered from 0 at the left end; each shaft segment adds
/// `elements` nodes.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct BeamInput {
    /// Materials by name.
    pub materials: std::collections::BTreeMap<String, MaterialInput>,
    /// Consecutive shaft segments, from the left end.
    pub shaft: Vec<SegmentInput>,
    /// Rigid disks.
    #[serde(default)]
    pub disks: Vec<DiskInput>,
    /// Nonrotating supports (bearings) on translations: isotropic or general.
    #[serde(default)]
    pub supports: Vec<SupportInput>,
    /// Seals: the same fields as `supports`, acting in every dynamic analysis exactly like a
    /// support, and left out of the undamped critical speed map and the static analysis (as
    /// API 684 and ROSS do: a seal's coefficients come from the pressure drop across it, not
    /// from carrying load).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub seals: Vec<SupportInput>,
    /// Point masses (bearing housings, pedestals), each with an optional isotropic stiffness
    /// and damping to ground. A point mass may sit on a shaft node or on a node off the shaft:
    /// those are numbered on from the shaft's last node (as ROSS numbers them), consecutively,
    /// and have a translation only. A support whose `n_link` is such a node joins the shaft to
    /// the pedestal.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub point_masses: Vec<PointMassInput>,
    /// Elements laid over the shaft's (sleeves, shrink fits, laminations): each spans shaft
    /// elements from node `node` on, and its matrices add to theirs (ROSS: several shaft
    /// elements on the same nodes).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub sleeves: Vec<SleeveInput>,
    /// Optional Guyan reduction: `{"guyan": "translations"}` keeps the translations and
    /// condenses the rotations.
    #[serde(default)]
    pub reduction: Option<ReductionInput>,
}

/// An isotropic material.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct MaterialInput {
    /// Young's modulus, Pa (> 0).
    #[schema(exclusive_minimum = 0.0)]
    pub young_modulus: f64,
    /// Density, kg/m^3 (> 0).
    #[schema(exclusive_minimum = 0.0)]
    pub density: f64,
    /// Poisson's ratio, in (-1, 0.5).
    #[schema(exclusive_minimum = -1.0, exclusive_maximum = 0.5)]
    pub poisson_ratio: f64,
    /// Loss factor of the material: rotating hysteretic damping, in [0, 1).
    #[serde(default)]
    #[schema(minimum = 0.0, exclusive_maximum = 1.0)]
    pub loss_factor: f64,
}

/// A uniform, hollow or solid, shaft segment.
#[derive(Debug, Clone, Default, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct SegmentInput {
    /// Length, m (> 0).
    #[schema(exclusive_minimum = 0.0)]
    pub length: f64,
    /// Outer diameter, m (> 0).
    #[schema(exclusive_minimum = 0.0)]
    pub outer_diameter: f64,
    /// Inner diameter, m (>= 0, < outer diameter; default 0: solid).
    #[serde(default)]
    #[schema(minimum = 0.0)]
    pub inner_diameter: f64,
    /// Name of a material in `materials` (required but for a coupling).
    #[serde(default)]
    pub material: String,
    /// Number of equal elements the segment is split into (default 1).
    #[serde(default)]
    pub elements: Option<i64>,
    /// Shear factor chi = 1/kappa (default: Cowper's formula for the annulus; of a conical
    /// element, for its mean diameters, as ROSS computes it).
    #[serde(default)]
    pub shear_factor: Option<f64>,
    /// Outer diameter at the segment's right end, m (default `outer_diameter`): a conical
    /// segment, its diameters linear along it; each of its elements is Genta and Gugliotta's
    /// conical Timoshenko element as ROSS implements it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub outer_diameter_right: Option<f64>,
    /// Inner diameter at the segment's right end, m (default `inner_diameter`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inner_diameter_right: Option<f64>,
    /// Axial force in the segment, N (tension > 0, compression < 0): its geometric stiffness
    /// (ROSS's `axial_force`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub axial_force: Option<f64>,
    /// Torque carried by the segment, N m: its geometric stiffness couples the two bending
    /// planes (ROSS's `torque`; in complex coordinates an imaginary, circulatory stiffness).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub torque: Option<f64>,
    /// Proportional (Rayleigh) viscous damping of the segment's elements.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rayleigh_damping: Option<RayleighInput>,
    /// A flexible coupling instead of a shaft: one element joining the shafts on either side
    /// (a train's shafts are the runs of segments between couplings). Its `length` places the
    /// nodes and its `outer_diameter` draws it; it takes no material or other shaft field.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub coupling: Option<CouplingInput>,
    /// A gear mesh instead of a shaft: the element joins the gear on the shaft before it to
    /// the gear on the shaft after it, which turns `ratio` times as fast. Torsional and axial
    /// analyses only (`motion`); its `length` places the nodes and its `outer_diameter` draws it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gear: Option<GearInput>,
    /// `false`: an Euler-Bernoulli element (no shear deformation; ROSS's `shear_effects`).
    /// Default true (Timoshenko).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shear_effects: Option<bool>,
    /// `false`: the element's sections have no rotary (transverse) inertia, and no gyroscopic
    /// moments (ROSS's `rotary_inertia`). Default true.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rotary_inertia: Option<bool>,
    /// `false`: the element has no gyroscopic moments (ROSS's `gyroscopic`). Default true.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gyroscopic: Option<bool>,
    /// Stress concentration factor of the segment's elements (>= 1, default 1: a keyway, a
    /// shoulder's fillet): the shaft stresses of torsional and axial responses are multiplied
    /// by it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(minimum = 1.0)]
    pub stress_concentration: Option<f64>,
}

/// A rigid disk at a node.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct DiskInput {
    #[schema(minimum = 0)]
    pub node: i64,
    /// Mass, kg (>= 0).
    pub mass: f64,
    /// Polar moment of inertia, kg m^2 (>= 0).
    #[serde(default)]
    #[schema(minimum = 0.0)]
    pub polar_inertia: f64,
    /// Transverse (diametral) moment of inertia, kg m^2 (>= 0).
    #[serde(default)]
    #[schema(minimum = 0.0)]
    pub transverse_inertia: f64,
}

/// A point mass on the translation of a node (ROSS's `PointMass`), optionally held to ground.
#[derive(Debug, Clone, Default, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct PointMassInput {
    /// A shaft node, or a node off the shaft (numbered on from the shaft's last node).
    #[schema(minimum = 0)]
    pub node: i64,
    /// Mass, kg (>= 0; > 0 on a node off the shaft).
    #[schema(minimum = 0.0)]
    pub mass: f64,
    /// Isotropic stiffness to ground, N/m (>= 0, default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(minimum = 0.0)]
    pub stiffness: Option<f64>,
    /// Isotropic viscous damping to ground, N s/m (>= 0, default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(minimum = 0.0)]
    pub damping: Option<f64>,
}

/// A support (bearing, seal, pedestal) on the translation of a node; nonrotating. Either the
/// isotropic form `{node, stiffness, damping, loss_factor}` or the general form
/// `{node, kxx, kxy, kyx, kyy, cxx, cxy, cyx, cyy, mxx, mxy, myx, myy, loss_factor, speeds}`:
/// force on the shaft `f = -K [x, y] - C [x', y'] - M [x'', y'']`, `K = [[kxx, kxy], [kyx, kyy]]`
/// (ROSS and API 684). Omitted coefficients are 0, except `kyy` and `cyy`, which default to
/// `kxx` and `cxx`. With `speeds` (increasing, rad/s) every coefficient may be an array of as
/// many values: linear in the spin speed between them, held at the end values outside.
/// With `n_link` the support joins two nodes (a bearing from the shaft to a pedestal, as
/// ROSS's `n_link`): its force acts on the relative motion `node - n_link`, equal and opposite
/// on the two.
#[derive(Debug, Clone, Default, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct SupportInput {
    #[schema(minimum = 0)]
    pub node: i64,
    /// The node it links `node` to (default: ground). Usually a pedestal's node off the shaft.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(minimum = 0)]
    pub n_link: Option<i64>,
    /// Isotropic form: stiffness, N/m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stiffness: Option<f64>,
    /// Isotropic form: viscous damping, N s/m (>= 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(minimum = 0.0)]
    pub damping: Option<f64>,
    /// Loss factor: nonrotating hysteretic damping `loss_factor` times the (symmetric part of
    /// the) stiffness, in [0, 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(minimum = 0.0, exclusive_maximum = 1.0)]
    pub loss_factor: Option<f64>,
    /// General form: stiffness coefficients, N/m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kxx: Option<Coefficient>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kxy: Option<Coefficient>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kyx: Option<Coefficient>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kyy: Option<Coefficient>,
    /// General form: damping coefficients, N s/m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cxx: Option<Coefficient>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cxy: Option<Coefficient>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cyx: Option<Coefficient>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cyy: Option<Coefficient>,
    /// General form: mass coefficients, kg.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mxx: Option<Coefficient>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mxy: Option<Coefficient>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub myx: Option<Coefficient>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub myy: Option<Coefficient>,
    /// Axial stiffness, N/m (a thrust bearing; ROSS's `kzz`): read by axial analyses
    /// (`motion: axial`) only, from the same `speeds`/`frequencies` as the others.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kzz: Option<Coefficient>,
    /// Axial damping, N s/m (ROSS's `czz`): axial analyses only.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub czz: Option<Coefficient>,
    /// Spin speeds of a table of coefficients, rad/s, increasing (2 to 512 of them; each speed
    /// keeps a state matrix, counted against the memory budget before anything is built).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub speeds: Option<Vec<f64>>,
    /// Whirl frequencies of a table of coefficients, rad/s, >= 0 and increasing (2 to 512): each
    /// coefficient is then one number, a list over them, or with `speeds` a list of lists (per
    /// speed, a list over the frequencies). A pole reads the table at its own `|frequency|`, a
    /// harmonic response at the excitation frequency, a static analysis at 0; where only one
    /// value is read at a speed it is the synchronous one (frequency = speed).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub frequencies: Option<Vec<f64>>,
    /// How a table is read between and beyond its points: `linear` by default for a table over
    /// `speeds` alone, `pchip` for one over `frequencies`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub interpolation: Option<Interpolation>,
}

/// How a support's table is read.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize, ToSchema)]
#[serde(rename_all = "lowercase")]
pub enum Interpolation {
    /// Linear between the points. Over `speeds` alone: held at the end values outside them;
    /// over `frequencies`: continued along the end segments (as ROSS 3).
    Linear,
    /// A table over `frequencies` (and `speeds`): scipy's `PchipInterpolator` (shape
    /// preserving, through every value) along the frequencies, then along the speeds,
    /// continued past the ends along the end slopes (ROSS 3's tables).
    Pchip,
    /// ROSS 2.3.0's: each coefficient on scipy's `interp1d` (2 or 3 speeds: linear,
    /// quadratic) or its smoothing spline (`UnivariateSpline`, 4 speeds and more), which
    /// need not pass through the table's values, extrapolated beyond the table. Stiffness and
    /// damping only: mass coefficients constant, no loss factor.
    Ross,
}

/// A support coefficient: one number, one per point of the support's `speeds` (or
/// `frequencies`), or with both a list per speed of values over the frequencies.
#[derive(Debug, Clone, Serialize, ToSchema)]
#[serde(untagged)]
pub enum Coefficient {
    Number(f64),
    Table(Vec<f64>),
    Grid(Vec<Vec<f64>>),
}

impl<'de> Deserialize<'de> for Coefficient {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        match Value::deserialize(d)? {
            v @ Value::Number(_) => variant(v).map(Coefficient::Number),
            Value::Array(v) if v.iter().any(Value::is_array) => {
                variant(Value::Array(v)).map(Coefficient::Grid)
            }
            v @ Value::Array(_) => variant(v).map(Coefficient::Table),
            _ => Err(serde::de::Error::custom(
                "must be a number, an array of numbers (one per speed of `speeds` or frequency \
                 of `frequencies`) or an array of such arrays (one per speed)",
            )),
        }
    }
}

/// Model reduction.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ReductionInput {
    /// Guyan (static) condensation; `translations` keeps the translation of every node.
    pub guyan: GuyanKeep,
}

/// Which degrees of freedom Guyan reduction keeps.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, ToSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum GuyanKeep {
    Translations,
}

/// The rotor as matrices in complex coordinates (`q = x + i y` per degree of freedom):
/// `M q'' + (C_n + C_r - i Omega G) q' + (K - i Omega C_r + i K''_n + i K''_r) q = F`.
/// All matrices are square, of one size, real and symmetric; `mass` positive definite.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct MatricesInput {
    /// Mass matrix, rows of numbers.
    pub mass: Vec<Vec<f64>>,
    /// Stiffness matrix.
    pub stiffness: Vec<Vec<f64>>,
    /// Gyroscopic (polar inertia) matrix (default zero).
    #[serde(default)]
    pub gyroscopic: Option<Vec<Vec<f64>>>,
    /// Rotating viscous damping C_r (default zero).
    #[serde(default)]
    pub damping_rotating: Option<Vec<Vec<f64>>>,
    /// Nonrotating viscous damping C_n (default zero).
    #[serde(default)]
    pub damping_nonrotating: Option<Vec<Vec<f64>>>,
    /// Rotating imaginary stiffness K''_r (default zero).
    #[serde(default)]
    pub hysteretic_rotating: Option<Vec<Vec<f64>>>,
    /// Nonrotating imaginary stiffness K''_n (default zero).
    #[serde(default)]
    pub hysteretic_nonrotating: Option<Vec<Vec<f64>>>,
    /// Supports in the general form (see `SupportInput`) acting on degree of freedom `node`
    /// as a translation `x + i y`, beside the matrices: cross-coupled, anisotropic or
    /// speed-dependent bearings and seals.
    #[serde(default)]
    pub supports: Vec<SupportInput>,
}

/// How hysteretic damping (the loss factors) is modelled, tagged by `model`. Viscous damping
/// is kept under every model.
#[derive(Debug, Clone, Serialize, ToSchema)]
#[serde(tag = "model", rename_all = "lowercase")]
pub enum DampingInput {
    /// Loss factors ignored: viscous damping only.
    Viscous(NoOptions),
    /// Hysteretic damping itself (frequency domain): imaginary stiffness `i sgn(omega) K_n''`
    /// and `i sgn(omega - Omega) K_r''`; poles are the sign-consistent roots. Near a forward
    /// critical speed a mode may have no consistent pole: it is reported as missing (`null`).
    Hysteretic(NoOptions),
    /// Equivalent viscous damping (paper eqs. 5-7, 9): each mode's modal loss stiffness divided
    /// by its undamped natural frequency, rotating and nonrotating apart.
    Equivalent(EquivalentInput),
    /// Nonviscous damping (Maxwell branches, paper eqs. 11-31): each hysteretic damper of each
    /// retained mode becomes `branches` spring-damper branches, relaxation rates one `spacing`
    /// apart centred on the mode's natural frequency, adding one massless internal coordinate
    /// each. Valid in the time domain.
    Nonviscous(NonviscousInput),
}

impl<'de> Deserialize<'de> for DampingInput {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        const MODELS: &[&str] = &["viscous", "hysteretic", "equivalent", "nonviscous"];
        let (tag, rest) = split_tag(Value::deserialize(d)?, "model", MODELS)?;
        match tag.as_str() {
            "viscous" => strict_variant(rest).map(DampingInput::Viscous),
            "hysteretic" => strict_variant(rest).map(DampingInput::Hysteretic),
            "equivalent" => strict_variant(rest).map(DampingInput::Equivalent),
            "nonviscous" => strict_variant(rest).map(DampingInput::Nonviscous),
            other => Err(unknown("model", other, MODELS)),
        }
    }
}

/// No options.
#[derive(Debug, Clone, Default, Deserialize, Serialize, ToSchema)]
pub struct NoOptions {}

/// Options of the equivalent viscous model.
#[derive(Debug, Clone, Default, Deserialize, Serialize, ToSchema)]
pub struct EquivalentInput {
    /// Number of lowest undamped modes that carry the equivalent damping (default: all).
    #[serde(default)]
    pub modes: Option<i64>,
}

/// Options of the nonviscous model.
#[derive(Debug, Clone, Default, Deserialize, Serialize, ToSchema)]
pub struct NonviscousInput {
    /// Branches modelling the rotating (shaft material) loss factor.
    #[serde(default)]
    pub rotating: Option<BranchesInput>,
    /// Branches modelling the nonrotating (support) loss factor.
    #[serde(default)]
    pub nonrotating: Option<BranchesInput>,
    /// Number of lowest undamped modes that get dampers (default: all).
    #[serde(default)]
    pub modes: Option<i64>,
}

/// Maxwell branches of one nonviscous damper.
#[derive(Debug, Clone, Default, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct BranchesInput {
    /// Number of branches m, 1..=12 (default 3).
    #[serde(default)]
    #[schema(minimum = 1, maximum = 12)]
    pub branches: Option<i64>,
    /// Ratio a between consecutive relaxation rates (default 10, one decade).
    #[serde(default)]
    #[schema(exclusive_minimum = 1.0)]
    pub spacing: Option<f64>,
    /// Weights nu_j of the branch stiffness on the main coordinate, one per branch (default 1:
    /// plain Maxwell branches). The paper's Example 1 uses nu_j = 1/gamma_j for the
    /// nonrotating dampers.
    #[serde(default)]
    pub nu: Option<Vec<f64>>,
}

/// Spin speeds: a uniform grid `{start, stop, count, unit}`, an explicit increasing list in
/// rad/s, or one in a unit, `{values, unit}`.
#[derive(Debug, Clone, Serialize, ToSchema)]
#[serde(untagged)]
pub enum SpeedsInput {
    Range(SpeedRange),
    List(Vec<f64>),
    Values(SpeedValues),
}

impl SpeedsInput {
    /// The unit the numbers are in.
    pub fn unit(&self) -> SpeedUnit {
        match self {
            SpeedsInput::Range(r) => r.unit.unwrap_or_default(),
            SpeedsInput::List(_) => SpeedUnit::RadPerSecond,
            SpeedsInput::Values(v) => v.unit,
        }
    }

    /// The numbers of a list, as typed.
    pub fn list(&self) -> Option<&[f64]> {
        match self {
            SpeedsInput::Range(_) => None,
            SpeedsInput::List(l) => Some(l),
            SpeedsInput::Values(v) => Some(&v.values),
        }
    }
}

/// An explicit increasing list of speeds in `unit`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct SpeedValues {
    pub values: Vec<f64>,
    pub unit: SpeedUnit,
}

impl<'de> Deserialize<'de> for SpeedsInput {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        match Value::deserialize(d)? {
            v @ Value::Object(_) if v.get("values").is_some() => {
                variant(v).map(SpeedsInput::Values)
            }
            v @ Value::Object(_) => variant(v).map(SpeedsInput::Range),
            v @ Value::Array(_) => variant(v).map(SpeedsInput::List),
            _ => Err(serde::de::Error::custom(
                "must be {\"start\", \"stop\", \"count\", \"unit\"}, a list of speeds in rad/s \
                 or {\"values\", \"unit\"}",
            )),
        }
    }
}

/// A uniform grid of spin speeds, both ends included.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct SpeedRange {
    /// First speed, in `unit` (>= 0).
    #[schema(minimum = 0.0)]
    pub start: f64,
    /// Last speed, in `unit` (> start).
    pub stop: f64,
    /// Number of speeds (>= 2).
    #[schema(minimum = 2)]
    pub count: i64,
    /// Unit of `start` and `stop` (default rad/s); the grid is uniform in it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub unit: Option<SpeedUnit>,
}
