//! Requests and answers of the forced responses: time response and steady unbalance response.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::*;

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

/// A spin speed history: `[[t, Omega], ...]` in s and rad/s, or `{points, unit}`.
#[derive(Debug, Clone, Serialize, ToSchema)]
#[serde(untagged)]
pub enum SpeedProfile {
    RadPerSecond(Vec<[f64; 2]>),
    Valued(SpeedPoints),
}

/// `[[t, Omega], ...]`, t in s and Omega in `unit`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct SpeedPoints {
    pub points: Vec<[f64; 2]>,
    pub unit: SpeedUnit,
}

impl SpeedProfile {
    /// The points with Omega in rad/s, and the path of the list as typed.
    pub fn rad_s(&self) -> (Vec<[f64; 2]>, &'static str) {
        match self {
            SpeedProfile::RadPerSecond(p) => (p.clone(), "speed_profile"),
            SpeedProfile::Valued(v) => (
                v.points
                    .iter()
                    .map(|&[t, w]| [t, v.unit.to_rad_s(w)])
                    .collect(),
                "speed_profile.points",
            ),
        }
    }
}

impl<'de> Deserialize<'de> for SpeedProfile {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        use crate::model::tagged::variant;
        match serde_json::Value::deserialize(d)? {
            v @ serde_json::Value::Array(_) => variant(v).map(SpeedProfile::RadPerSecond),
            v @ serde_json::Value::Object(_) => variant(v).map(SpeedProfile::Valued),
            _ => Err(serde::de::Error::custom(
                "must be [[t, Omega], ...] (s, rad/s) or {\"points\", \"unit\"}",
            )),
        }
    }
}

/// Body of `POST /v1/time-response`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct TimeResponseRequest {
    pub rotor: RotorInput,
    /// `viscous`, `equivalent` or `nonviscous` (hysteretic damping has no time-domain form).
    pub damping: DampingInput,
    /// Constant spin speed, rad/s or `{value, unit}` (give this or `speed_profile`; a
    /// torsional or axial response does not depend on it, and takes 0 without it).
    #[serde(default)]
    pub speed: Option<SpeedInput>,
    /// `[[t, Omega], ...]` (s, rad/s), or `{points: [[t, Omega], ...], unit}` with Omega in
    /// `unit`: piecewise-linear spin speed (run-up, run-down), held after the last point; no
    /// jumps.
    #[serde(default)]
    pub speed_profile: Option<SpeedProfile>,
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
    /// Relative tolerance of the integrators (varying speed), in [1e-12, 1e-2]; default
    /// 1e-6. On a modal reduction (the exponential integrator) it bounds the error relative
    /// to the response's peak; on the full model (TR-BDF2) it controls the local error.
    #[serde(default)]
    pub tolerance: Option<f64>,
    /// Varying speed: integrate on the lowest undamped modes and the static corrections of
    /// the coupling forces, the supports and the loads, where that at least halves the state
    /// and, at the fastest speed, reproduces every full-model pole below twice that speed
    /// (at least 1.5 times the first natural frequency) within 1e-3 of its decay rate, and
    /// the other way round (default true). The answer's `reduction` says what was solved.
    #[serde(default)]
    pub modal_reduction: Option<bool>,
    /// The motion solved: `lateral` (default), `torsional` (each force's history a torque,
    /// N m, the answer's `x` a twist, rad) or `axial` (an axial force, the answer's `x` an
    /// axial displacement, m). Unbalances act laterally only.
    #[serde(default)]
    pub motion: super::Motion,
    /// Torsional only: a synchronous motor's start-up (its air-gap and load torques).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub motor_start: Option<super::MotorStartInput>,
    /// Torsional only: a generator's short circuit (its air-gap torque).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub short_circuit: Option<super::ShortCircuitInput>,
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
    /// The rotor is the paper's nondimensional Jeffcott rotor (mass = stiffness = 1): its speeds,
    /// frequencies and decay rates are in units of sqrt(k/m) and its times in units of
    /// sqrt(m/k), and the plots label them so, without physical units.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub nondimensional: bool,
    /// The motion solved (as the request's `motion`).
    #[serde(default)]
    pub motion: super::Motion,
    pub time: Vec<f64>,
    /// Each reported node's displacement; in torsion (axially) `x` is its twist, rad (axial
    /// displacement, m), relative to the train's rigid motion where nothing holds the train
    /// (`rigid_motion`), and `y` is 0.
    pub nodes: Vec<NodeHistory>,
    /// A free train's rigid turning (axially: sliding) that the loads drive, beside its
    /// vibration (torsional and axial responses; null where supports hold the train).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rigid_motion: Option<super::RigidMotion>,
    /// Torsional and axial responses: every element's torque (axial force) over time, its
    /// peak and the peak's stress.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub elements: Vec<super::ElementLoadHistory>,
    /// `exact` (constant speed: modal superposition, exact for piecewise-linear forces and
    /// unbalance), `exponential` (varying speed on a modal reduction: ETD-RK4, every pole
    /// integrated exactly) or `implicit` (TR-BDF2, L-stable, error-controlled).
    pub method: String,
    /// Integration steps taken (exponential, implicit) or 0.
    pub steps: usize,
    /// Size of the state.
    pub states: usize,
    /// The modal reduction integrated (varying speed); null when the full model was.
    #[serde(default)]
    pub reduction: Option<ReductionInfo>,
    /// The supports over whirl frequency, each carried into the time domain by Maxwell
    /// branches fitted to its table, and how well.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub support_fits: Vec<super::SupportFitInfo>,
    /// With supports over whirl frequency: the fitted model's poles against the rotor's own at
    /// each speed integrated, compared before integrating.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub fit_poles: Vec<super::FitPolesInfo>,
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
    /// With it, each peak gets its separation margin from this range and the margin API 684
    /// requires.
    #[serde(default)]
    pub operating_range: Option<OperatingRange>,
    /// Whether the response may be solved on a checked modal reduction (default true): the
    /// lowest modes with their static corrections at the loads, supports and outputs, compared
    /// with the full model at the lowest and highest speed and at the largest response. The
    /// answer's `reduction` says what was solved.
    #[serde(default)]
    pub modal_reduction: Option<bool>,
    /// Unit of the speeds and frequencies of the answer: `rad/s` (the default), `rpm`, `Hz` or
    /// `cpm`; the answer's `output_unit` says which. Decay rates stay in 1/s.
    #[serde(default)]
    pub output_unit: Option<SpeedUnit>,
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
    /// Resonance peaks of `amplitude` (local maxima inside the range, refined between the
    /// grid's speeds), with their amplification factors.
    #[serde(default)]
    pub peaks: Vec<ResponsePeak>,
}

/// Answer of `POST /v1/unbalance-response`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct UnbalanceResponseResponse {
    /// The rotor is the paper's nondimensional Jeffcott rotor (mass = stiffness = 1): its speeds,
    /// frequencies and decay rates are in units of sqrt(k/m) and its times in units of
    /// sqrt(m/k), and the plots label them so, without physical units.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub nondimensional: bool,
    /// Unit of every speed and whirl or natural frequency in this answer (the request's
    /// `output_unit`; rad/s by default). Decay rates are in 1/s whatever it is.
    #[serde(default)]
    pub output_unit: SpeedUnit,
    pub speeds: Vec<f64>,
    pub nodes: Vec<NodeUnbalance>,
    /// The modal reduction the response was solved on; null when the full model was.
    #[serde(default)]
    pub reduction: Option<ResponseReductionInfo>,
    /// How the full model was held: `dense`, or `sparse` (a rotor past 600 coordinates under
    /// the viscous or hysteretic model: one sparse factor of its dynamic stiffness per
    /// frequency, exact, its cost linear in the mesh, never reduced).
    #[serde(default)]
    pub full_model: Storage,
    /// How the damping model treats synchronous whirl.
    pub note: String,
    /// How the model was read where it needed saying: supports held at the ends of their
    /// tables of coefficients outside them.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
}

/// A harmonic response solved on a modal reduction, and how well it reproduces the full model.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct ResponseReductionInfo {
    /// Undamped modes retained (those up to twice the highest frequency, widened until the
    /// check passes).
    pub modes: usize,
    /// Size of the basis: those modes, the static corrections of the forces that couple them
    /// and the static responses to unit loads at the loads, supports and outputs.
    pub vectors: usize,
    /// Natural frequency of the highest retained mode, rad/s.
    pub band: f64,
    /// Size of each reduced solve.
    pub states: usize,
    /// Size of the full model's.
    pub full_states: usize,
    /// Where the reduced response was compared with the full model's (rad/s): the lowest and
    /// highest speed (frequency) and that of the largest response.
    pub checked: Vec<f64>,
    /// Largest difference found there, `|a - a_full| + |b - b_full|` over the outputs,
    /// relative to the largest `|a_full| + |b_full|` (at most 1e-7).
    pub max_relative_error: f64,
}
