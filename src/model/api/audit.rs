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
    /// Gravitational acceleration along -y, m/s^2 (default 9.8065).
    #[serde(default)]
    pub gravity: Option<f64>,
    #[serde(default)]
    pub supports: Option<StaticSupports>,
    /// Spin speed at which supports tabulated against speed are evaluated, rad/s (default 0).
    #[serde(default)]
    pub speed: Option<f64>,
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

/// One stage's data for API 617's anticipated cross-coupling
/// `q_A = B_c C P / (D_c H_c N) (rho_d / rho_s)` (B_c = 3, C = 9.55; P in kW, N in rpm,
/// D_c and H_c in mm, q in kN/mm; converted to N/m here).
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
}

/// Body of `POST /v1/level1`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct Level1Request {
    pub rotor: RotorInput,
    pub damping: DampingInput,
    /// Spin speed (the maximum continuous speed), rad/s.
    pub speed: f64,
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
}

/// Answer of `POST /v1/level1`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct Level1Response {
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
    /// API 617 Level I: passes when the log decrement at q_A is at least 0.1 and
    /// q0 / q_A at least 2; else a Level II analysis is required.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub passes: Option<bool>,
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
    /// Spin speed, rad/s (default 0).
    #[serde(default)]
    pub speed: f64,
    pub input: ResponseInput,
    pub output: ResponseOutput,
    /// Excitation frequencies, rad/s (> 0): a grid or a list.
    pub frequencies: SpeedsInput,
}

/// Answer of `POST /v1/frequency-response`: per unit force (m/N) at each frequency, the
/// response `x(t) = Re(X e^{i omega t})`, `y(t) = Re(Y e^{i omega t})` and its forward and
/// backward circular parts `r(t) = F e^{i omega t} + B e^{-i omega t}`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct FrequencyResponseResponse {
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
    pub model: String,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
}

/// `[low, high]` operating speeds, rad/s.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct OperatingRange {
    /// Minimum operating speed, rad/s.
    pub min: f64,
    /// Maximum continuous speed, rad/s.
    pub max: f64,
}

/// A resonance peak of an unbalance response curve.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct ResponsePeak {
    /// Speed of the peak (the critical speed N_c), rad/s.
    pub speed: f64,
    /// Amplitude there, m.
    pub amplitude: f64,
    /// `N_c / (N_2 - N_1)`, the half-power points where the amplitude is `peak / sqrt 2`;
    /// null when a half-power point lies outside the speeds swept.
    pub amplification_factor: Option<f64>,
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

/// Body of `POST /v1/report`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ReportRequest {
    /// A beam rotor.
    pub rotor: RotorInput,
    /// The model of the detailed plots (Campbell, unbalance); the margins are computed under
    /// every model in `models` too.
    pub damping: DampingInput,
    pub operating_range: OperatingRange,
    /// Speeds of the Campbell and unbalance sweeps (default 0 to 1.25 x the maximum speed:
    /// 121 speeds for Campbell, 481 for the unbalance response).
    #[serde(default)]
    pub speeds: Option<SpeedsInput>,
    /// Unbalances (default: API 684's `U = 6350 W / N` g mm at the heaviest disk's node, W the
    /// rotor's weight in kg and N the maximum continuous speed in rpm, converted to kg m).
    #[serde(default)]
    pub unbalances: Option<Vec<SteadyUnbalanceInput>>,
    /// Nodes of the unbalance response (default: the unbalances' nodes and the supports').
    #[serde(default)]
    pub nodes: Option<Vec<i64>>,
    /// Cross-coupling of the Level I screen (default: 21 values from 0 to about twice q0) and
    /// where it acts (default: the unbalance node).
    #[serde(default)]
    pub cross_coupling: Option<LinearRange>,
    #[serde(default)]
    pub cross_coupling_nodes: Option<Vec<i64>>,
    #[serde(default)]
    pub machine: Option<MachineInput>,
    /// Critical speed map stiffness (default 1e5 to 1e10 N/m, 31 values).
    #[serde(default)]
    pub stiffness: Option<LogRange>,
    /// Campbell branches: those below this frequency, rad/s (default 1.5 x the last speed).
    #[serde(default)]
    pub max_frequency: Option<f64>,
    /// Damping models compared side by side (default: hysteretic, equivalent and nonviscous
    /// built from `damping`'s options where they apply, and viscous).
    #[serde(default)]
    pub models: Option<Vec<DampingInput>>,
}

/// One damping model's margins in the report.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct ModelMargins {
    pub model: String,
    /// Forward critical speeds in the swept range, rad/s.
    pub critical_speeds: Vec<f64>,
    /// Onset speed of instability in the swept range, rad/s.
    pub threshold: Option<f64>,
    /// Log decrement of the first forward mode at the maximum continuous speed.
    pub log_decrement: Option<f64>,
    /// Level I: cross-coupling at zero log decrement, N/m.
    pub q0: Option<f64>,
    /// Unbalance peaks of the first response node (the synchronous models only: the
    /// hysteretic model's synchronous response equals the others' at `omega = Omega`).
    pub peaks: Vec<ResponsePeak>,
}

/// One line of the report's verdict.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct ReportCheck {
    /// What is checked.
    pub check: String,
    /// The damping model it was checked under.
    pub model: String,
    pub value: String,
    pub requirement: String,
    pub passes: bool,
}

/// Answer of `POST /v1/report` (as JSON; `Accept: text/html` gives the page).
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct ReportResponse {
    /// The rotor audited, as given.
    pub rotor: RotorInput,
    pub operating_range: OperatingRange,
    pub critical_speed_map: CriticalSpeedMapResponse,
    pub static_deflection: StaticResponse,
    pub campbell: CampbellResponse,
    pub unbalance: UnbalanceResponseResponse,
    pub level1: Level1Response,
    /// The same margins under each damping model.
    pub models: Vec<ModelMargins>,
    pub checks: Vec<ReportCheck>,
    /// The unbalances used, kg m.
    pub unbalances: Vec<SteadyUnbalanceInput>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
}
