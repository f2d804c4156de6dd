//! Wire types of the HTTP/JSON contract (`../shared/spec/API.md`): what clients send and receive.
//! Field names are the contract; add fields, never rename them. All quantities SI, speeds and
//! frequencies in rad/s.

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
    /// Nonrotating supports (bearings, seals) on translations: isotropic or general.
    #[serde(default)]
    pub supports: Vec<SupportInput>,
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
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
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
    /// Name of a material in `materials`.
    pub material: String,
    /// Number of equal elements the segment is split into (default 1).
    #[serde(default)]
    pub elements: Option<i64>,
    /// Shear factor chi = 1/kappa (default: Cowper's formula for the annulus).
    #[serde(default)]
    pub shear_factor: Option<f64>,
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

/// A support (bearing, seal, pedestal) on the translation of a node; nonrotating. Either the
/// isotropic form `{node, stiffness, damping, loss_factor}` or the general form
/// `{node, kxx, kxy, kyx, kyy, cxx, cxy, cyx, cyy, mxx, mxy, myx, myy, loss_factor, speeds}`:
/// force on the shaft `f = -K [x, y] - C [x', y'] - M [x'', y'']`, `K = [[kxx, kxy], [kyx, kyy]]`
/// (ROSS and API 684). Omitted coefficients are 0, except `kyy` and `cyy`, which default to
/// `kxx` and `cxx`. With `speeds` (increasing, rad/s) every coefficient may be an array of as
/// many values: linear in the spin speed between them, held at the end values outside.
#[derive(Debug, Clone, Default, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct SupportInput {
    #[schema(minimum = 0)]
    pub node: i64,
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
    /// Spin speeds of a table of coefficients, rad/s, increasing (2 to 64 of them).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub speeds: Option<Vec<f64>>,
}

/// A support coefficient: one number, or one per speed of the support's `speeds`.
#[derive(Debug, Clone, Serialize, ToSchema)]
#[serde(untagged)]
pub enum Coefficient {
    Number(f64),
    Table(Vec<f64>),
}

impl<'de> Deserialize<'de> for Coefficient {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        match Value::deserialize(d)? {
            v @ Value::Number(_) => variant(v).map(Coefficient::Number),
            v @ Value::Array(_) => variant(v).map(Coefficient::Table),
            _ => Err(serde::de::Error::custom(
                "must be a number or an array of numbers (one per speed of `speeds`)",
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

/// Spin speeds: a uniform grid `{start, stop, count}` or an explicit increasing list.
#[derive(Debug, Clone, Serialize, ToSchema)]
#[serde(untagged)]
pub enum SpeedsInput {
    Range(SpeedRange),
    List(Vec<f64>),
}

impl<'de> Deserialize<'de> for SpeedsInput {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        match Value::deserialize(d)? {
            v @ Value::Object(_) => variant(v).map(SpeedsInput::Range),
            v @ Value::Array(_) => variant(v).map(SpeedsInput::List),
            _ => Err(serde::de::Error::custom(
                "must be {\"start\", \"stop\", \"count\"} or a list of speeds",
            )),
        }
    }
}

/// A uniform grid of spin speeds, both ends included.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct SpeedRange {
    /// First speed, rad/s (>= 0).
    #[schema(minimum = 0.0)]
    pub start: f64,
    /// Last speed, rad/s (> start).
    pub stop: f64,
    /// Number of speeds (>= 2).
    #[schema(minimum = 2)]
    pub count: i64,
}

/// Body of `POST /v1/modal`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ModalRequest {
    pub rotor: RotorInput,
    pub damping: DampingInput,
    /// Spin speed, rad/s (default 0).
    #[serde(default)]
    pub speed: f64,
}

/// Body of `POST /v1/campbell` and `POST /v1/stability`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct SweepRequest {
    pub rotor: RotorInput,
    pub damping: DampingInput,
    pub speeds: SpeedsInput,
    /// Campbell only: report the branches whose |frequency| at their first speed is at most
    /// this, rad/s (default: all). Stability always considers every pole.
    #[serde(default)]
    pub max_frequency: Option<f64>,
    /// Campbell only, with `max_frequency`: solve on the lowest undamped modes where that at
    /// least halves the state and reproduces the full model's poles below `max_frequency` to
    /// 1e-6 relative at the fastest speed of the sweep (default true). The answer's
    /// `reduction` says what was solved.
    #[serde(default)]
    pub modal_reduction: Option<bool>,
}

/// Direction of whirl of a pole: `forward` (whirl frequency > 0), `backward` (< 0), or
/// `internal` (an overdamped pole of the nonviscous model's internal coordinates).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize, ToSchema)]
#[serde(rename_all = "lowercase")]
pub enum Whirl {
    Forward,
    Backward,
    Internal,
}

/// A pole `s = decay_rate + i frequency` of the free motion `q0 e^{s t}`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct Pole {
    /// Real part sigma, 1/s; > 0 means unstable.
    pub decay_rate: f64,
    /// Imaginary part omega, rad/s: > 0 forward, < 0 backward whirl.
    pub frequency: f64,
    pub whirl: Whirl,
    /// `-sigma / |s|`.
    pub damping_ratio: f64,
    /// `-2 pi sigma / |omega|`; null for a pole that does not oscillate.
    pub log_decrement: Option<f64>,
    /// Rotor poles: `(F - B) / (F + B)` of the forward and backward circular parts of the
    /// orbits, in [-1, 1]: +1 circular forward, -1 circular backward, 0 planar (elliptical in
    /// between; always +-1 on isotropic supports).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub whirl_ratio: Option<f64>,
    /// Mode shape (`modal` only, rotor poles): the complex translation `x + i y` of each node,
    /// scaled so that the largest is 1 and real.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shape: Option<Vec<NodeDisplacement>>,
}

/// Complex translation of a node in a mode shape.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct NodeDisplacement {
    pub node: usize,
    pub re: f64,
    pub im: f64,
}

/// Answer of `POST /v1/modal`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct ModalResponse {
    /// Spin speed, rad/s.
    pub speed: f64,
    /// Rotor poles by increasing |frequency|, then internal poles by decreasing |decay_rate|.
    pub poles: Vec<Pole>,
    /// Natural frequencies of the undamped nonrotating system, rad/s, ascending.
    pub natural_frequencies: Vec<f64>,
    /// Size of the first-order eigenproblem solved (per sign combination for `hysteretic`).
    pub states: usize,
    /// Rotor poles the model does not define at this speed (hysteretic model near a critical
    /// speed: no sign-consistent root), counted against the number of rotor poles (2 per
    /// complex degree of freedom).
    pub missing_poles: usize,
    /// How the model was read where it needed saying: supports held at the ends of their
    /// tables of coefficients outside them.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
}

/// One Campbell branch: the same physical mode followed from speed to speed.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct Branch {
    /// Mode number, 1 = lowest |frequency| at the first speed, counted per whirl direction.
    pub mode: usize,
    pub whirl: Whirl,
    /// Whirl frequency at each speed, rad/s (negative for backward whirl); null where the
    /// model defines no pole for this mode.
    pub frequency: Vec<Option<f64>>,
    /// Decay rate at each speed, 1/s; null where the model defines no pole for this mode.
    pub decay_rate: Vec<Option<f64>>,
}

/// Answer of `POST /v1/campbell`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct CampbellResponse {
    pub speeds: Vec<f64>,
    pub branches: Vec<Branch>,
    /// Speeds where a forward branch crosses the 1x line (frequency = speed), interpolated.
    pub critical_speeds: Vec<f64>,
    /// Lowest speed of the range at which a pole has decay_rate > 0, refined by root finding;
    /// null when stable over the whole range.
    pub threshold: Option<f64>,
    /// The modal reduction the sweep ran on; null when it ran on the full model.
    pub reduction: Option<ReductionInfo>,
    /// How the model was read where it needed saying: supports held at the ends of their
    /// tables of coefficients outside them.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
}

/// A sweep or a time response solved on the lowest undamped nonrotating modes (a Rayleigh-Ritz
/// reduction), and how well it reproduces the full model. The threshold then concerns the poles those modes carry.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct ReductionInfo {
    /// Undamped modes retained.
    pub modes: usize,
    /// Size of the basis: those modes and the independent static corrections of the forces that
    /// couple them (gyroscopic, damping, loss), made modes of the subspace again.
    pub vectors: usize,
    /// Natural frequency of the highest retained mode, rad/s.
    pub band: f64,
    /// State size of each eigenproblem solved.
    pub states: usize,
    /// State size of the full model.
    pub full_states: usize,
    /// Speed at which every full-model pole with |decay_rate| and |frequency| at most
    /// `max_frequency` was compared with the reduced ones (and the other way round), rad/s.
    pub checked_speed: f64,
    /// Largest distance between a reduced and a full-model pole found there: for a sweep
    /// relative, `|s_reduced - s_full| / |s_full|` (at most 1e-6); for a time response
    /// relative to the decay rate, `|s_reduced - s_full| / max(|Re s_full|, 1e-3 |s_full|)`
    /// (at most 1e-3: a forced response near a pole moves by about that fraction).
    pub max_relative_error: f64,
}

/// Answer of `POST /v1/stability`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct StabilityResponse {
    /// Lowest speed in `range` at which a pole has decay_rate > 0 (to 1e-6 relative), or null.
    pub threshold: Option<f64>,
    /// Mode number of the pole that becomes unstable (by |frequency| within its whirl).
    pub mode: Option<usize>,
    pub whirl: Option<Whirl>,
    /// Whirl frequency of that pole at the threshold, rad/s.
    pub frequency: Option<f64>,
    /// `[start, stop]` searched.
    pub range: [f64; 2],
    /// The grid searched, rad/s.
    pub speeds: Vec<f64>,
    /// Largest decay rate of all poles at each grid speed, 1/s.
    pub max_decay_rate: Vec<f64>,
    /// How the model was read where it needed saying: supports held at the ends of their
    /// tables of coefficients outside them.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
}

/// `GET /healthz`, `GET /readyz`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct Status {
    pub status: String,
}

/// An RFC 9457 problem: `application/problem+json`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct Problem {
    /// A URI reference naming the kind of problem.
    #[serde(rename = "type")]
    pub kind: String,
    pub title: String,
    pub status: u16,
    pub detail: String,
    /// Every bad field, with its JSON path (422).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub errors: Vec<ProblemField>,
}

/// One bad field of a request.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct ProblemField {
    /// JSON path of the field, e.g. `rotor.mass`.
    pub path: String,
    pub message: String,
}

/// Body of `POST /v1/damping`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct DampingMatricesRequest {
    pub rotor: RotorInput,
    /// `equivalent` or `nonviscous` (the models with time-domain matrices).
    pub damping: DampingInput,
    /// Matrices in second-order form (default) or the first-order state matrix.
    #[serde(default)]
    pub form: Option<MatrixForm>,
    /// Band and target of the nonviscous fit report; with `max_deviation` the number of
    /// branches of each side is chosen automatically (omit `branches` and `nu` then).
    #[serde(default)]
    pub fit: Option<FitInput>,
    /// Spin speed at which supports tabulated against speed are evaluated, rad/s (default 0).
    #[serde(default)]
    pub speed: Option<f64>,
}

/// Form of the returned matrices.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, ToSchema, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum MatrixForm {
    /// `M q'' + (C_n + C_r - i Omega G) q' + (K - i Omega C_r) q = F`, internal coordinates
    /// appended to `q`.
    SecondOrder,
    /// `z' = (A0 + Omega A1) z + B F`, `z = [v, x, y]`, `v = x'`: `2n + p` states.
    State,
}

/// Fit options of the nonviscous model.
#[derive(Debug, Clone, Default, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct FitInput {
    /// `[low, high]`, rad/s: the band of frequencies the damper material sees (`omega` for
    /// supports, `omega - Omega` in the rotor). Default: per damper, `branches` spacings wide
    /// centred on its tuning frequency.
    #[serde(default)]
    pub band: Option<[f64; 2]>,
    /// Largest acceptable relative deviation of the loss factor over the band; when given,
    /// each side gets the fewest branches (1..=12) that achieve it for every mode.
    #[serde(default)]
    pub max_deviation: Option<f64>,
}

/// A complex matrix as its real and imaginary parts.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct ComplexMatrix {
    pub re: Vec<Vec<f64>>,
    pub im: Vec<Vec<f64>>,
}

/// Second-order matrices of the coordinates in `coordinates`:
/// `M q'' + (C_n + C_r - i Omega S G) q' + (K - i Omega S C_r) q = F`, `S = diag(spin)`
/// (`spin` all 1 unless the coordinates are doubled). Real and symmetric for isotropic
/// supports; supports in the general form may add imaginary parts (`imaginary`).
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct SecondOrderMatrices {
    pub mass: Vec<Vec<f64>>,
    pub gyroscopic: Vec<Vec<f64>>,
    pub stiffness: Vec<Vec<f64>>,
    /// Rotating damping (its circulatory term is `-i Omega S C_r q`).
    pub damping_rotating: Vec<Vec<f64>>,
    pub damping_nonrotating: Vec<Vec<f64>>,
    /// The imaginary parts of the same matrices, when any is nonzero.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(no_recursion)]
    pub imaginary: Option<Box<SecondOrderMatrices>>,
    /// Doubled coordinates `(r, conj r)`: -1 on the `conj r` coordinates (and their rotating
    /// branches), where the terms in the spin speed change sign; +1 elsewhere.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spin: Option<Vec<f64>>,
}

/// First-order form `z' = (A0 + Omega A1) z + B F`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct StateMatrices {
    /// `A0`, the state matrix at rest.
    pub constant: ComplexMatrix,
    /// `A1 = dA/dOmega`.
    pub per_speed: ComplexMatrix,
    /// `B` (states x physical coordinates): `M^-1` on the velocities, zero elsewhere.
    pub input: Vec<Vec<f64>>,
}

/// A coordinate of the returned matrices.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct CoordinateOut {
    pub index: usize,
    /// `translation`, `rotation` or `internal`.
    pub kind: String,
    /// Doubled coordinates: whether this is the `conj r` copy of a physical coordinate.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub conjugate: Option<bool>,
    /// Node of a physical coordinate.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub node: Option<usize>,
    /// Mode (from 1) whose damper an internal coordinate belongs to.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mode: Option<usize>,
    /// Branch (from 1) within its damper.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub branch: Option<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rotating: Option<bool>,
    /// Relaxation rate d_j, 1/s.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub relaxation_rate: Option<f64>,
}

/// The loss of one undamped mode and its equivalent viscous damping.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct ModeLoss {
    pub mode: usize,
    pub natural_frequency: f64,
    pub loss_factor_rotating: f64,
    pub loss_factor_nonrotating: f64,
}

/// A point of a damper's loss-factor curve.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct FitPoint {
    /// Frequency the damper material sees, rad/s.
    pub frequency: f64,
    pub loss_factor: f64,
    /// Added storage stiffness relative to the modal stiffness.
    pub storage_change: f64,
}

/// How one nonviscous damper reproduces its hysteretic loss.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct DamperReport {
    pub mode: usize,
    pub rotating: bool,
    pub tuning_frequency: f64,
    /// Target loss factor of the mode.
    pub loss_factor: f64,
    pub branches: usize,
    pub spacing: f64,
    pub relaxation_rates: Vec<f64>,
    /// Branch springs k_j and dampers c_j, modal units (mass-normalised modes).
    pub springs: Vec<f64>,
    pub dampers: Vec<f64>,
    pub band: [f64; 2],
    /// Largest `|eta_branches / eta - 1|` over the band.
    pub max_deviation: f64,
    pub rms_deviation: f64,
    pub storage_change_at_tuning: f64,
    pub max_storage_change: f64,
    pub added_states: usize,
    pub curve: Vec<FitPoint>,
}

/// Answer of `POST /v1/damping`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct DampingMatricesResponse {
    pub model: String,
    /// The coordinates of the second-order matrices, physical first, then internal.
    pub coordinates: Vec<CoordinateOut>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub second_order: Option<SecondOrderMatrices>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub state: Option<StateMatrices>,
    /// Equivalent model: the added `C_eq` alone, rotating and nonrotating.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub equivalent_rotating: Option<Vec<Vec<f64>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub equivalent_nonrotating: Option<Vec<Vec<f64>>>,
    /// Imaginary part of `equivalent_nonrotating`, when nonzero (supports in the general form).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub equivalent_nonrotating_imaginary: Option<Vec<Vec<f64>>>,
    /// Modal loss factors of the retained modes.
    pub modes: Vec<ModeLoss>,
    /// Nonviscous model: one report per damper.
    pub dampers: Vec<DamperReport>,
    /// Internal coordinates (= added states) of the model.
    pub added_states: usize,
    /// Branches per damper actually used, rotating and nonrotating.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub branches_rotating: Option<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub branches_nonrotating: Option<usize>,
    /// How the model was read where it needed saying: supports held at the ends of their
    /// tables of coefficients outside them.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
}

/// A nonrotating force with a fixed direction.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ForceInput {
    #[schema(minimum = 0)]
    pub node: i64,
    /// Angle of the force from the x axis, rad.
    #[serde(default)]
    pub direction: f64,
    /// `[[t, F], ...]`, s and N, piecewise linear; a repeated time is a jump; held constant
    /// before the first and after the last point.
    pub history: Vec<[f64; 2]>,
}

/// An unbalance rotating with the shaft.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct UnbalanceInput {
    #[schema(minimum = 0)]
    pub node: i64,
    /// `m e`, kg m (>= 0).
    #[schema(minimum = 0.0)]
    pub amount: f64,
    /// Angle on the rotor, rad (0: on the x axis at t = 0).
    #[serde(default)]
    pub phase: f64,
    /// Time it appears, s (default 0); later than 0 makes a sudden unbalance (blade loss).
    #[serde(default)]
    #[schema(minimum = 0.0)]
    pub from: f64,
}

/// Body of `POST /v1/time-response`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct TimeResponseRequest {
    pub rotor: RotorInput,
    /// `viscous`, `equivalent` or `nonviscous` (hysteretic damping has no time-domain form).
    pub damping: DampingInput,
    /// Constant spin speed, rad/s (give this or `speed_profile`).
    #[serde(default)]
    pub speed: Option<f64>,
    /// `[[t, Omega], ...]`: piecewise-linear spin speed (run-up, run-down), held after the last
    /// point; no jumps.
    #[serde(default)]
    pub speed_profile: Option<Vec<[f64; 2]>>,
    #[serde(default)]
    pub forces: Vec<ForceInput>,
    #[serde(default)]
    pub unbalances: Vec<UnbalanceInput>,
    /// Length of the simulation, s.
    #[schema(exclusive_minimum = 0.0)]
    pub duration: f64,
    /// Output sampling interval, s: samples at 0, dt, 2 dt, ... up to `duration`.
    #[schema(exclusive_minimum = 0.0)]
    pub output_interval: f64,
    /// Nodes to report (default: all nodes with a translation).
    #[serde(default)]
    pub nodes: Option<Vec<i64>>,
    /// Relative tolerance of the implicit integrator (varying speed), in [1e-12, 1e-2];
    /// default 1e-6.
    #[serde(default)]
    pub tolerance: Option<f64>,
    /// Varying speed: integrate on the lowest undamped modes and the static corrections of
    /// the coupling forces, the supports and the loads, where that at least halves the state
    /// and, at the fastest speed, reproduces every full-model pole below twice that speed
    /// (at least 1.5 times the first natural frequency) within 1e-3 of its decay rate, and
    /// the other way round (default true). The answer's `reduction` says what was solved.
    #[serde(default)]
    pub modal_reduction: Option<bool>,
}

/// The response of one node.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct NodeHistory {
    pub node: usize,
    /// Displacement along x, m.
    pub x: Vec<f64>,
    /// Displacement along y, m.
    pub y: Vec<f64>,
}

/// Answer of `POST /v1/time-response`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct TimeResponseResponse {
    pub time: Vec<f64>,
    pub nodes: Vec<NodeHistory>,
    /// `exact` (constant speed: modal superposition, exact for piecewise-linear forces and
    /// unbalance) or `implicit` (TR-BDF2, L-stable, error-controlled).
    pub method: String,
    /// Integration steps taken (implicit) or 0.
    pub steps: usize,
    /// Size of the state.
    pub states: usize,
    /// The modal reduction integrated (varying speed); null when the full model was.
    #[serde(default)]
    pub reduction: Option<ReductionInfo>,
    /// How the model was read where it needed saying: supports held at the ends of their
    /// tables of coefficients outside them.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
}

/// Unbalance for the steady response (no `from`).
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct SteadyUnbalanceInput {
    #[schema(minimum = 0)]
    pub node: i64,
    /// `m e`, kg m.
    #[schema(minimum = 0.0)]
    pub amount: f64,
    #[serde(default)]
    pub phase: f64,
}

/// Body of `POST /v1/unbalance-response`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct UnbalanceResponseRequest {
    pub rotor: RotorInput,
    pub damping: DampingInput,
    pub speeds: SpeedsInput,
    pub unbalances: Vec<SteadyUnbalanceInput>,
    /// Nodes to report (default: all nodes with a translation).
    #[serde(default)]
    pub nodes: Option<Vec<i64>>,
}

/// Steady synchronous response of one node: an elliptical orbit (a circle on isotropic
/// supports).
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct NodeUnbalance {
    pub node: usize,
    /// Semi-major axis of the orbit, m (zero to peak): the radius of a circular orbit.
    pub amplitude: Vec<f64>,
    /// Angle of the forward part of the whirl relative to the rotor's reference (the
    /// unbalance at phase 0), rad: `r = a e^{i Omega t} + conj(b) e^{-i Omega t}` with
    /// `a = |a| e^{i phase}`; for a circular orbit `r = amplitude e^{i (Omega t + phase)}`.
    pub phase: Vec<f64>,
    /// `x(t) = x_amplitude cos(Omega t + x_phase)`, m and rad (ROSS's complex amplitudes).
    pub x_amplitude: Vec<f64>,
    pub x_phase: Vec<f64>,
    /// `y(t) = y_amplitude cos(Omega t + y_phase)`.
    pub y_amplitude: Vec<f64>,
    pub y_phase: Vec<f64>,
    /// Semi-axes of the orbit, m.
    pub major: Vec<f64>,
    pub minor: Vec<f64>,
}

/// Answer of `POST /v1/unbalance-response`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct UnbalanceResponseResponse {
    pub speeds: Vec<f64>,
    pub nodes: Vec<NodeUnbalance>,
    /// How the damping model treats synchronous whirl.
    pub note: String,
    /// How the model was read where it needed saying: supports held at the ends of their
    /// tables of coefficients outside them.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
}

/// An analysis a job can run: the synchronous endpoint of the same name.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, ToSchema, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum AnalysisName {
    Modal,
    Campbell,
    Stability,
    Damping,
    TimeResponse,
    UnbalanceResponse,
}

/// Body of `POST /v1/jobs`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct JobRequest {
    pub analysis: AnalysisName,
    /// The body the synchronous endpoint `POST /v1/<analysis>` takes.
    #[schema(value_type = Object)]
    pub input: Value,
}

/// State of a job.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, ToSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum JobStatus {
    Queued,
    Running,
    Succeeded,
    Failed,
    Cancelled,
}

/// A job's status.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct JobInfo {
    pub id: String,
    pub analysis: String,
    pub status: JobStatus,
    /// Fraction of the work done, 0 to 1 (speeds swept, samples computed).
    pub progress: f64,
    pub created_at: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub started_at: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub finished_at: Option<String>,
    /// Why the job failed or was cancelled.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<Problem>,
}
