//! Requests and answers of the analyses an API 684 / API 617 audit asks for: the undamped
//! critical speed map, static deflection and bearing loads, the Level I stability screen, the
//! non-synchronous frequency response, unbalance peaks with amplification factors and
//! separation margins, and the report that gathers them.

use serde::{Deserialize, Serialize};
use serde_json::Value;
use utoipa::openapi::schema::{ObjectBuilder, OneOfBuilder, SchemaFormat, Type};
use utoipa::openapi::{KnownFormat, RefOr, Schema};
use utoipa::{PartialSchema, ToSchema};

use super::*;

/// A log-spaced range: `count` values from `start` to `stop`, both included (> 0).
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct LogRange {
    #[schema(exclusive_minimum = 0.0)]
    pub start: f64,
    /// > start.
    pub stop: f64,
    /// >= 2.
    #[schema(minimum = 2)]
    pub count: i64,
}

/// Body of `POST /v1/critical-speed-map`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct CriticalSpeedMapRequest {
    /// A beam rotor: its supports are replaced by isotropic undamped springs.
    pub rotor: RotorInput,
    /// Support stiffness, N/m, log-spaced.
    pub stiffness: LogRange,
    /// Modes reported, one per degenerate x/y pair (default 4).
    #[serde(default)]
    #[schema(minimum = 1)]
    pub modes: Option<i64>,
    /// Unit of the speeds and frequencies of the answer: `rad/s` (the default), `rpm`, `Hz` or
    /// `cpm`; the answer's `output_unit` says which. Decay rates stay in 1/s.
    #[serde(default)]
    pub output_unit: Option<SpeedUnit>,
}

/// Where a mode of the map meets a support's actual stiffness.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct MapIntersection {
    /// Index of the support in `rotor.supports`.
    pub support: usize,
    pub node: usize,
    /// The coefficient whose curve meets the mode: `kxx` or `kyy` (both when they differ).
    pub coefficient: String,
    /// Mode, from 1.
    pub mode: usize,
    /// N/m.
    pub stiffness: f64,
    /// Undamped natural frequency there, rad/s: for a coefficient tabulated against speed,
    /// the speed at which the mode's frequency equals that speed (a critical speed).
    pub frequency: f64,
}

/// Answer of `POST /v1/critical-speed-map`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct CriticalSpeedMapResponse {
    /// Unit of every speed and whirl or natural frequency in this answer (the request's
    /// `output_unit`; rad/s by default). Decay rates are in 1/s whatever it is.
    #[serde(default)]
    pub output_unit: SpeedUnit,
    /// N/m.
    pub stiffness: Vec<f64>,
    /// `frequencies[mode - 1][i]`: undamped natural frequency at zero speed of each mode at
    /// `stiffness[i]`, rad/s.
    pub frequencies: Vec<Vec<f64>>,
    /// The modes at the actual supports' stiffness (exact, not read off the curves).
    pub intersections: Vec<MapIntersection>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
}

/// How `POST /v1/static` holds the shaft.
#[derive(Debug, Clone, Copy, Default, Deserialize, Serialize, ToSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum StaticSupports {
    /// The supports' own stiffness (at `speed`).
    #[default]
    Elastic,
    /// Rigid pinned supports at the support nodes (translations held, rotations free), as
    /// ROSS's `run_static`.
    Rigid,
}

/// Body of `POST /v1/static`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct StaticRequest {
    /// A beam rotor.
    pub rotor: RotorInput,
    /// Gravitational acceleration along -y, m/s^2 (default standard gravity, 9.80665; ROSS's
    /// `run_static` uses 9.8065).
    #[serde(default)]
    pub gravity: Option<f64>,
    #[serde(default)]
    pub supports: Option<StaticSupports>,
    /// Spin speed at which supports tabulated against speed are evaluated, rad/s or
    /// `{value, unit}` (default 0).
    #[serde(default)]
    pub speed: Option<SpeedInput>,
}

/// A support's load on the shaft.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct SupportReaction {
    /// Index of the support in `rotor.supports`.
    pub support: usize,
    pub node: usize,
    /// Upward (+y) force of the support on the shaft, N.
    pub reaction: f64,
    /// Its x component, N (nonzero only with cross-coupled supports).
    pub reaction_x: f64,
}

/// A node's static displacement.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct NodeDeflection {
    pub node: usize,
    /// Axial position, m.
    pub position: f64,
    /// Signed y displacement, m (negative: down).
    pub deflection: f64,
    /// x displacement, m (nonzero only with cross-coupled supports).
    pub deflection_x: f64,
    /// Slope `dy/dz` of the section (bending rotation), rad.
    #[serde(default)]
    pub slope: f64,
    /// Slope `dx/dz`, rad.
    #[serde(default)]
    pub slope_x: f64,
}

/// Internal forces at an end of an element.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct ShaftStation {
    /// Element, from 0 (joins nodes `element` and `element + 1`).
    pub element: usize,
    /// Axial position, m.
    pub position: f64,
    /// Shear force, N, ROSS's sign: minus the upward forces to the left of the section.
    pub shear: f64,
    /// Bending moment, N m, ROSS's sign: negative sagging.
    pub bending_moment: f64,
    /// Signed y displacement there, m: exact between nodes (the element's shape functions and
    /// the particular solution of its uniform weight).
    #[serde(default)]
    pub deflection: f64,
    /// x displacement there, m.
    #[serde(default)]
    pub deflection_x: f64,
}

/// Answer of `POST /v1/static`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct StaticResponse {
    pub gravity: f64,
    pub supports_model: StaticSupports,
    pub supports: Vec<SupportReaction>,
    pub nodes: Vec<NodeDeflection>,
    /// Both ends of every element, left to right.
    pub stations: Vec<ShaftStation>,
    /// The exact shear (linear in each element, the shaft's weight uniform along it) and
    /// bending moment (quadratic) at 9 points along every element, ends included.
    #[serde(default)]
    pub diagram: Vec<ShaftStation>,
    /// The largest |bending moment| along the shaft, N m (ROSS's sign), found exactly: at an
    /// element's end or where the shear vanishes inside it.
    #[serde(default)]
    pub max_moment: f64,
    /// Where it is, m.
    #[serde(default)]
    pub max_moment_position: f64,
    /// The largest |shear force|, N (ROSS's sign; at an element's end).
    #[serde(default)]
    pub max_shear: f64,
    /// Where it is, m (the left or right side of a node: `max_shear_element`).
    #[serde(default)]
    pub max_shear_position: f64,
    /// The element whose end carries it.
    #[serde(default)]
    pub max_shear_element: usize,
    /// The largest displacement `|(x, y)|` along the shaft, m, wherever it is (between nodes
    /// when it is there: the deflection curve is exact inside each element).
    #[serde(default)]
    pub max_deflection: f64,
    /// Where it is, m.
    #[serde(default)]
    pub max_deflection_position: f64,
    /// Its signed y displacement, m.
    #[serde(default)]
    pub max_deflection_y: f64,
    /// Weight of shaft and disks, N; the reactions balance it.
    pub weight: f64,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
}

/// A linear range (`start` may be 0).
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct LinearRange {
    #[schema(minimum = 0.0)]
    pub start: f64,
    /// > start.
    pub stop: f64,
    /// >= 2.
    #[schema(minimum = 2)]
    pub count: i64,
}

/// One stage's data for API 617's anticipated cross-coupling (Wachel's formula)
/// `q_A = B_c T / (D_c H_c) (rho_d / rho_s)`, `B_c = 3`, with the stage torque `T = P / Omega`
/// at the Level I speed: in SI, N m / m^2 = N/m (2 MW, 0.4 m, 20 mm at 10,000 rpm: 716 kN/m).
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct StageInput {
    /// Node of the impeller (where its share of q_A acts).
    #[schema(minimum = 0)]
    pub node: i64,
    /// Power of the stage, W.
    pub power: f64,
    /// Impeller diameter, m.
    pub diameter: f64,
    /// Smaller of the diffuser and impeller discharge widths, m.
    pub width: f64,
    /// Discharge over suction gas density (default 1).
    #[serde(default)]
    pub density_ratio: Option<f64>,
}

/// The machine data of API 617's Level I screen.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct MachineInput {
    pub stages: Vec<StageInput>,
    /// Mean gas density of the machine, kg/m^3 (suction and discharge averaged): with it the
    /// critical speed ratio is screened against API 617's Region A/B boundary.
    #[serde(default)]
    pub mean_gas_density: Option<f64>,
    /// Level II: further cross-coupled stiffness (a balance piston, a damper seal's estimate,
    /// ...), applied alone and with the stages and the seals.
    #[serde(default)]
    pub additional_cross_coupling: Option<Vec<CrossCouplingInput>>,
}

/// Cross-coupled stiffness at a node: `kxy = q`, `kyx = -q`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct CrossCouplingInput {
    pub node: i64,
    /// N/m.
    pub q: f64,
}

/// One configuration of API 617's Level II analysis.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct Level2Source {
    /// `bearings alone`, `seals`, `stages' q_A`, `additional cross-coupling` or `all together`.
    pub source: String,
    /// The first forward mode's log decrement at the speed (null where undefined).
    pub log_decrement: Option<f64>,
    /// Its whirl frequency, rad/s.
    pub frequency: Option<f64>,
    /// Log decrement >= 0.1.
    pub passes: bool,
}

/// API 617's Level II analysis: each destabilising source alone, then all together.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct Level2Response {
    pub sources: Vec<Level2Source>,
    /// Every configuration keeps a log decrement of at least 0.1.
    pub passes: bool,
}

/// Body of `POST /v1/level1`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct Level1Request {
    pub rotor: RotorInput,
    pub damping: DampingInput,
    /// Spin speed (the maximum continuous speed), rad/s or `{value, unit}`.
    pub speed: SpeedInput,
    /// The node the cross-coupling acts on; or `nodes`, which share it equally.
    #[serde(default)]
    #[schema(minimum = 0)]
    pub node: Option<i64>,
    #[serde(default)]
    pub nodes: Option<Vec<i64>>,
    /// Total cross-coupled stiffness q, N/m (`kxy = q`, `kyx = -q`, shared by the nodes).
    /// Default: 21 values from 0 to about twice q0, found first.
    #[serde(default)]
    pub cross_coupling: Option<LinearRange>,
    /// Stage data for the anticipated cross-coupling q_A (optional); when given, its nodes
    /// replace `node`/`nodes` for the distribution of q.
    #[serde(default)]
    pub machine: Option<MachineInput>,
    /// Whether Level I may be solved on a checked modal reduction (default true): the
    /// answer's `reduction` says what was solved. Level II is always solved on the full model.
    #[serde(default)]
    pub modal_reduction: Option<bool>,
    /// Unit of the speeds and frequencies of the answer: `rad/s` (the default), `rpm`, `Hz` or
    /// `cpm`; the answer's `output_unit` says which. Decay rates stay in 1/s.
    #[serde(default)]
    pub output_unit: Option<SpeedUnit>,
}

/// How a Level I screen was reduced: the modal basis holds the lowest modes, their static
/// corrections and the static responses at the cross-coupling's translations, so the
/// cross-coupling is a rank-two update of the reduced stiffness.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct Level1ReductionInfo {
    /// Undamped modes retained.
    pub modes: usize,
    /// Size of the basis.
    pub vectors: usize,
    /// State size of each reduced eigenproblem.
    pub states: usize,
    /// State size of the full model.
    pub full_states: usize,
    /// The total cross-coupling at which the poles were compared with the full model's (q0
    /// when found, else the largest q solved), N/m.
    pub checked_cross_coupling: f64,
    /// Largest `|s_reduced - s_full| / |s_full|` there over the poles with `|Re s|` and
    /// `|Im s|` within the band checked (at least the second natural frequency at rest and
    /// 1.5 times the first forward mode's modulus), both ways (at most 1e-5, else the full
    /// model is solved).
    pub max_relative_error: f64,
    /// How the full model was held for the reduction and its check: `dense`, or `sparse`
    /// (the viscous and hysteretic models of 100 states or more, and every model of a rotor
    /// past WHIRL_MAX_DOFS: Lanczos modes, sparse factors, no dense matrix of the rotor's
    /// size).
    #[serde(default)]
    pub full_model: super::Storage,
    /// The equivalent or nonviscous model of a rotor held sparse: its dampers are on the
    /// undamped modes up to 16 times the band checked (or the request's `modes`), this many
    /// (x/y modes each, on supports that are not isotropic; the dense models damp every mode).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub damped_modes: Option<usize>,
    /// Natural frequency of the highest of those modes, rad/s.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub damped_band: Option<f64>,
}

/// Answer of `POST /v1/level1`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct Level1Response {
    /// Unit of every speed and whirl or natural frequency in this answer (the request's
    /// `output_unit`; rad/s by default). Decay rates are in 1/s whatever it is.
    #[serde(default)]
    pub output_unit: SpeedUnit,
    pub speed: f64,
    pub nodes: Vec<usize>,
    /// Share of q at each node.
    pub weights: Vec<f64>,
    /// Total cross-coupling, N/m.
    pub cross_coupling: Vec<f64>,
    /// Log decrement of the first forward mode at each q (null where the hysteretic model
    /// defines no such pole).
    pub log_decrement: Vec<Option<f64>>,
    /// Its whirl frequency, rad/s.
    pub frequency: Vec<Option<f64>>,
    /// Log decrement and frequency without cross-coupling.
    pub log_decrement_0: Option<f64>,
    pub frequency_0: Option<f64>,
    /// Cross-coupling at which the first forward mode's log decrement is zero, N/m, to 1e-6
    /// relative; null if it stays stable up to 1e3 times `cross_coupling.stop`.
    pub q0: Option<f64>,
    /// API 617's anticipated cross-coupling, N/m (with `machine`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub qa: Option<f64>,
    /// Log decrement at q_A.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub log_decrement_at_qa: Option<f64>,
    /// `q0 / qa`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ratio: Option<f64>,
    /// API 617 Level I: passes when no reason in `level2_reasons` applies (the negation of
    /// `level2_required`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub passes: Option<bool>,
    /// Whether API 617 requires a Level II analysis (with `machine`): q0 / q_A < 2, or the log
    /// decrement at q_A below 0.1, or 2 <= q0 / q_A < 10 with the machine in Region B of the
    /// critical speed ratio against mean gas density (without `mean_gas_density` that screen
    /// cannot clear it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub level2_required: Option<bool>,
    /// Why Level II is required (empty when it is not).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub level2_reasons: Vec<String>,
    /// First undamped critical speed on rigid supports (bearing nodes held, seals left out),
    /// rad/s (beam rotors).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rigid_critical_speed: Option<f64>,
    /// API 617's critical speed ratio: `speed` (the maximum continuous speed) over
    /// `rigid_critical_speed`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub critical_speed_ratio: Option<f64>,
    /// `A` or `B`: where (mean gas density, critical speed ratio) falls against API 617's
    /// boundary (CSR 2.5 up to 16.53 kg/m^3, then `2.69 - 0.0115 rho` to 2.0 at 60 kg/m^3;
    /// above 60 kg/m^3 every machine is in Region B), with `machine.mean_gas_density`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub region: Option<String>,
    /// API 617's Level II, with `machine`: the first forward mode's log decrement on the
    /// bearings alone, with each destabilising source alone, and with all together.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub level2: Option<Level2Response>,
    /// The checked modal reduction Level I was solved on; absent when the full model was
    /// (`"modal_reduction": false`, or no reduction passed its check).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reduction: Option<Level1ReductionInfo>,
    /// On supports over whirl frequency: the largest residual of a first forward pole found
    /// (each consistent with the frequency it reads them at; the rotor's equation at it,
    /// relative, as `/v1/modal`'s `residual`). Level I is then solved on the full model.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_residual: Option<f64>,
    pub model: String,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
}

/// Where a frequency response is excited: a force along `direction` (angle from x, rad), or
/// a circular force whirling `forward` or `backward`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ResponseInput {
    #[schema(minimum = 0)]
    pub node: i64,
    /// An angle (rad) or `"forward"`/`"backward"` (default 0: along x).
    #[serde(default)]
    #[schema(value_type = Option<ExcitationDirection>)]
    pub direction: Option<Value>,
}

/// The schema of a frequency response's `input.direction` (read by hand from a JSON value in
/// `model::task`): an angle from x in rad, or a circular force whirling one way.
pub struct ExcitationDirection;

impl PartialSchema for ExcitationDirection {
    fn schema() -> RefOr<Schema> {
        OneOfBuilder::new()
            .item(
                ObjectBuilder::new()
                    .schema_type(Type::Number)
                    .format(Some(SchemaFormat::KnownFormat(KnownFormat::Double)))
                    .description(Some("A force along this angle from x, rad.")),
            )
            .item(
                ObjectBuilder::new()
                    .schema_type(Type::String)
                    .enum_values(Some(["forward", "backward"]))
                    .description(Some("A circular force whirling forward or backward.")),
            )
            .description(Some(
                "An angle from x (rad), or `forward`/`backward` for a circular force.",
            ))
            .into()
    }
}

impl ToSchema for ExcitationDirection {}

/// Where a frequency response is read.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ResponseOutput {
    #[schema(minimum = 0)]
    pub node: i64,
}

/// Body of `POST /v1/frequency-response`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct FrequencyResponseRequest {
    pub rotor: RotorInput,
    pub damping: DampingInput,
    /// Spin speed, rad/s or `{value, unit}` (default 0).
    #[serde(default)]
    pub speed: SpeedInput,
    pub input: ResponseInput,
    pub output: ResponseOutput,
    /// Excitation frequencies (> 0): a grid or a list, in rad/s unless its `unit` says.
    pub frequencies: SpeedsInput,
    /// Whether the response may be solved on a checked modal reduction (default true; see
    /// `/v1/unbalance-response`). The answer's `reduction` says what was solved.
    #[serde(default)]
    pub modal_reduction: Option<bool>,
    /// Unit of the speeds and frequencies of the answer: `rad/s` (the default), `rpm`, `Hz` or
    /// `cpm`; the answer's `output_unit` says which. Decay rates stay in 1/s.
    #[serde(default)]
    pub output_unit: Option<SpeedUnit>,
    /// The motion solved: `lateral` (default; the input a force, m/N), `torsional` (the input a
    /// torque at `input.node`, the answer in rad/(N m)) or `axial` (an axial force, m/N).
    #[serde(default)]
    pub motion: super::Motion,
}

/// Answer of `POST /v1/frequency-response`: per unit force (m/N) at each frequency, the
/// response `x(t) = Re(X e^{i omega t})`, `y(t) = Re(Y e^{i omega t})` and its forward and
/// backward circular parts `r(t) = F e^{i omega t} + B e^{-i omega t}`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct FrequencyResponseResponse {
    /// Unit of every speed and whirl or natural frequency in this answer (the request's
    /// `output_unit`; rad/s by default). Decay rates are in 1/s whatever it is.
    #[serde(default)]
    pub output_unit: SpeedUnit,
    pub speed: f64,
    pub input_node: usize,
    pub output_node: usize,
    /// Along `direction` (the input's direction; x for a circular input), m/N.
    pub frequencies: Vec<f64>,
    pub amplitude: Vec<f64>,
    /// rad.
    pub phase: Vec<f64>,
    pub x_amplitude: Vec<f64>,
    pub x_phase: Vec<f64>,
    pub y_amplitude: Vec<f64>,
    pub y_phase: Vec<f64>,
    pub forward: Vec<f64>,
    pub backward: Vec<f64>,
    /// Torsional and axial responses: every element's torque (axial force) per unit input.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub elements: Vec<super::ElementLoadResponse>,
    pub model: String,
    /// The modal reduction the response was solved on; null when the full model was.
    #[serde(default)]
    pub reduction: Option<super::ResponseReductionInfo>,
    /// How the full model was held: `dense`, or `sparse` (a rotor past 600 coordinates under
    /// the viscous or hysteretic model: one sparse factor of its dynamic stiffness per
    /// frequency, exact, its cost linear in the mesh, never reduced).
    #[serde(default)]
    pub full_model: super::Storage,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
}

/// `[low, high]` operating speeds, in `unit` (rad/s unless it says).
#[derive(Debug, Clone, Copy, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct OperatingRange {
    /// Minimum operating speed.
    pub min: f64,
    /// Maximum continuous speed.
    pub max: f64,
    /// Unit of `min` and `max` (default rad/s).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub unit: Option<super::SpeedUnit>,
}

/// A resonance peak of an unbalance response curve.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct ResponsePeak {
    /// Speed of the peak (the critical speed N_c), rad/s.
    pub speed: f64,
    /// Amplitude there, m, zero to peak (the orbit's semi-major axis).
    pub amplitude: f64,
    /// The same peak to peak (twice `amplitude`), as API 617's limits read it, m.
    #[serde(default)]
    pub amplitude_peak_to_peak: f64,
    /// `N_c / (N_2 - N_1)`, the half-power points where the amplitude is `peak / sqrt 2`
    /// (the same ratio on zero-to-peak and peak-to-peak amplitudes); with one half-power point
    /// only, `N_c / (2 |N_c - N_i|)` (`one_sided`); null with neither, or for an undamped
    /// (unbounded) peak.
    pub amplification_factor: Option<f64>,
    /// AF below 2.5: critically damped in API 684's sense, no separation margin required
    /// (`required_margin` null); null without an AF.
    #[serde(default)]
    pub critically_damped: Option<bool>,
    /// The AF came from one half-power point (the other outside the sweep or behind a
    /// neighbouring peak), the peak taken as symmetric.
    #[serde(default)]
    pub one_sided: bool,
    /// Half-power speeds `[N_1, N_2]`, rad/s.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub half_power: Option<[f64; 2]>,
    /// With `operating_range`: distance from the range, percent of its nearer end (API 684:
    /// below, `100 (N_min - N_c) / N_min`; above, `100 (N_c - N_max) / N_max`; 0 inside).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub separation_margin: Option<f64>,
    /// Separation margin API 684 requires for this amplification factor, percent: none below
    /// AF 2.5 (critically damped); else `17 (1 - 1 / (AF - 1.5))` (at most 16) below the
    /// range and `10 + 17 (1 - 1 / (AF - 1.5))` (at most 26) above it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub required_margin: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub passes: Option<bool>,
    /// Whether the peak and its half-power points were refined on the response itself (one
    /// steady solve per step, within a budget of about two sweeps per request); else they
    /// are read off the grid by linear interpolation.
    #[serde(default)]
    pub refined: bool,
}
