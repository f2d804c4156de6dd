//! The report's wire types: its request, its unbalance cases and its answer.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::*;

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
    /// Campbell branches: those below this frequency, rad/s or `{value, unit}` (default 1.5 x
    /// the last speed).
    #[serde(default)]
    pub max_frequency: Option<SpeedInput>,
    /// Damping models compared side by side (default: hysteretic, equivalent and nonviscous
    /// built from `damping`'s options where they apply, and viscous).
    #[serde(default)]
    pub models: Option<Vec<DampingInput>>,
    /// Close-clearance locations (seals, balance pistons, impeller eyes): each unbalance
    /// case's response, scaled by API 617's scale factor, must stay under 75% of the minimum
    /// diametral clearance there.
    #[serde(default)]
    pub clearances: Option<Vec<ClearanceInput>>,
    /// Bearing sets (API 684: minimum, nominal and maximum clearance, ...): the audit is
    /// repeated on the rotor with each set's supports (and seals, when given), each with its
    /// own checks; the verdict covers them all.
    #[serde(default)]
    pub cases: Option<Vec<BearingSetInput>>,
    /// The train's torsional audit beside the lateral one: its natural frequencies against the
    /// orders of its shafts' speeds and the line frequency (API 684's 10% separation over the
    /// operating range), and a motor's start-up or a generator's short circuit with its peak
    /// shaft torques.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub torsion: Option<TorsionInput>,
}

/// The report's torsional section.
#[derive(Debug, Clone, Default, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct TorsionInput {
    /// Orders of each shaft's speed that excite the train (default `[1, 2]`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub orders: Option<Vec<f64>>,
    /// Electrical line frequency of the train's motor or generator: it and twice it excite it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub line_frequency: Option<SpeedInput>,
    /// The transient's damping model (default: the report's, or `nonviscous`, its time-domain
    /// form, where the report's is hysteretic).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub damping: Option<DampingInput>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub motor_start: Option<MotorStartInput>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub short_circuit: Option<ShortCircuitInput>,
    /// Length of the transient, s (with `motor_start` or `short_circuit`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub duration: Option<f64>,
    /// Its output interval, s (default `duration / 2000`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub output_interval: Option<f64>,
}

/// The report's torsional section.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct TorsionReport {
    /// The torsional interference diagram over the report's speeds (under the report's damping
    /// model), its crossings and margins from the operating range.
    pub campbell: CampbellResponse,
    /// The start-up or short-circuit transient: every element's torque and its peak.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub transient: Option<TimeResponseResponse>,
}

/// A set of bearings (and seals) the audit is repeated with.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct BearingSetInput {
    pub name: String,
    /// Replace `rotor.supports`.
    pub supports: Vec<SupportInput>,
    /// Replace `rotor.seals` (default: the rotor's).
    #[serde(default)]
    pub seals: Option<Vec<SupportInput>>,
}

/// The audit on one bearing set.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct BearingSetReport {
    pub name: String,
    pub critical_speed_map: CriticalSpeedMapResponse,
    pub static_deflection: StaticResponse,
    pub campbell: CampbellResponse,
    pub level1: Level1Response,
    pub unbalance_cases: Vec<UnbalanceCase>,
    pub models: Vec<ModelMargins>,
    pub checks: Vec<ReportCheck>,
}

/// A close-clearance location of the report.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ClearanceInput {
    pub node: i64,
    /// Minimum diametral running clearance, m (> 0).
    pub diametral: f64,
}

/// An unbalance API 684 places for a mode.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct PlacedUnbalance {
    pub node: usize,
    /// `Ua = 2 x 6350 W / N` g mm, as kg m (W in kg, N the maximum continuous speed in rpm).
    pub amount: f64,
    /// rad: 0, or pi for the second antinode of a mode whose lobes move in opposition.
    pub phase: f64,
    /// W, kg.
    pub weight: f64,
    /// Which of API 684's rules placed it (one antinode, two antinodes, overhung).
    pub rule: String,
}

/// A close-clearance location's check in one unbalance case.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct ClearanceResult {
    pub node: usize,
    /// Minimum diametral clearance, m.
    pub diametral: f64,
    /// The largest peak-to-peak amplitude over the sweep times the scale factor, m.
    pub scaled_amplitude: f64,
    /// Where it is, rad/s.
    pub speed: f64,
    /// 75% of `diametral`, m.
    pub limit: f64,
    pub passes: bool,
}

/// One of the report's unbalance cases: a forward critical speed in the sweep, excited as API
/// 684 prescribes from its mode shape there, under the report's damping model.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct UnbalanceCase {
    /// 1-based, by increasing critical speed among the forward ones.
    pub mode: usize,
    /// The Campbell diagram's critical speed of the mode, rad/s.
    pub critical_speed: f64,
    /// Its log decrement there.
    pub log_decrement: Option<f64>,
    /// The mode's shape at its critical speed: the signed major semi-axis of each node's
    /// orbit, scaled to 1 at the node that moves most, by axial position.
    pub shape: Vec<ShapePoint>,
    /// The same along the shaft, `[position m, value]` at 9 points per element: the element's
    /// cubic (Hermite) interpolation of its ends' translations and rotations.
    #[serde(default)]
    pub shape_curve: Vec<[f64; 2]>,
    pub unbalances: Vec<PlacedUnbalance>,
    /// The response at the unbalances', bearings' and clearances' nodes, with its peaks, AF
    /// and separation margins; amplitudes zero to peak (`amplitude_peak_to_peak` in the
    /// peaks).
    pub response: UnbalanceResponseResponse,
    /// API 617's `Avl = 25.4 um sqrt(12000 / N)`, at most 25.4 um, m peak to peak.
    pub vibration_limit: f64,
    /// `A1`: the largest peak-to-peak amplitude at a bearing over the operating range, m; its
    /// node and speed.
    pub max_bearing_amplitude: Option<f64>,
    pub max_bearing_amplitude_node: Option<usize>,
    pub max_bearing_amplitude_speed: Option<f64>,
    /// Whether `A1 <= Avl`.
    pub within_vibration_limit: Option<bool>,
    /// `Scc = Avl / A1`, at most 6 (API 617).
    pub scale_factor: Option<f64>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub clearances: Vec<ClearanceResult>,
}

/// One node of a mode shape.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct ShapePoint {
    pub node: usize,
    pub position: f64,
    pub value: f64,
}

/// What produced a report.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct Provenance {
    /// `whirl`.
    pub software: String,
    /// The crate's version.
    pub version: String,
    /// SHA-256 (hex) of the request as parsed and written again as compact JSON, its fields
    /// in the order of this specification: the same model gives the same hash whatever its
    /// spacing or key order.
    pub input_sha256: String,
    /// When the report was computed, RFC 3339 UTC.
    pub generated: String,
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
    /// The unbalances of `unbalance` (the comparison across models), kg m.
    pub unbalances: Vec<SteadyUnbalanceInput>,
    /// API 684's unbalance cases, one per forward critical speed of the Campbell diagram in
    /// the sweep (at most 4, the lowest).
    #[serde(default)]
    pub unbalance_cases: Vec<UnbalanceCase>,
    /// API 617's `Avl` at the maximum continuous speed, m peak to peak.
    #[serde(default)]
    pub vibration_limit: f64,
    /// The audit on each of the request's bearing sets (`cases`); their checks are in
    /// `checks` too, prefixed by the set's name.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub bearing_sets: Vec<BearingSetReport>,
    /// The torsional section, when the request asks for it; its margins are in `checks`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub torsion: Option<TorsionReport>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub provenance: Option<Provenance>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
}
