//! Requests and answers of the frequency-domain analyses: modal, Campbell and stability (the
//! damping models as matrices: `damping.rs`).

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::*;

/// Body of `POST /v1/modal`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ModalRequest {
    pub rotor: RotorInput,
    pub damping: DampingInput,
    /// Spin speed, rad/s or `{value, unit}` (default 0).
    #[serde(default)]
    pub speed: SpeedInput,
    /// Report only the poles in the box `|decay_rate|, |frequency| <= max_frequency` and the
    /// natural frequencies up to it, rad/s or `{value, unit}` (default: all). A rotor past 600
    /// coordinates (a beam rotor without Guyan reduction, viscous or hysteretic model) is then
    /// held sparse: the box's poles of its full model by shift-invert Arnoldi through sparse
    /// factors, exact, its cost linear in the mesh (without it such a rotor is refused past
    /// WHIRL_MAX_DOFS).
    #[serde(default)]
    pub max_frequency: Option<SpeedInput>,
    /// Unit of the speeds and frequencies of the answer: `rad/s` (the default), `rpm`, `Hz` or
    /// `cpm`; the answer's `output_unit` says which. Decay rates stay in 1/s.
    #[serde(default)]
    pub output_unit: Option<SpeedUnit>,
    /// The motion solved: `lateral` (default), `torsional` or `axial` (a beam rotor's; see
    /// the Motion schema).
    #[serde(default)]
    pub motion: super::Motion,
}

/// Body of `POST /v1/campbell` and `POST /v1/stability`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct SweepRequest {
    pub rotor: RotorInput,
    pub damping: DampingInput,
    pub speeds: SpeedsInput,
    /// Campbell: report the branches whose |frequency| is at most this at some speed of the
    /// sweep, rad/s or `{value, unit}` (default: all). Stability considers every pole of a
    /// rotor solved dense; a rotor past 600 coordinates (viscous or hysteretic model, no Guyan
    /// reduction) is held sparse with it, its poles in the box `|decay_rate|, |frequency| <=
    /// max_frequency` considered (the answer's `max_frequency` says so).
    #[serde(default)]
    pub max_frequency: Option<SpeedInput>,
    /// Campbell only: report the `modes` branches of lowest |frequency| at the first speed,
    /// forward and backward counted together (ROSS's `frequencies`), 1 to 2n; with
    /// `max_frequency` too, those of them below it. The sweep is bounded, and may be reduced,
    /// as with `max_frequency` set to the highest of them. Stability ignores it.
    #[serde(default)]
    #[schema(minimum = 1)]
    pub modes: Option<i64>,
    /// Campbell only, with `max_frequency`: solve on the lowest undamped modes where that at
    /// least halves the state and reproduces the full model's poles below `max_frequency` to
    /// 1e-6 relative at the fastest speed of the sweep (default true). The answer's
    /// `reduction` says what was solved.
    #[serde(default)]
    pub modal_reduction: Option<bool>,
    /// Unit of the speeds and frequencies of the answer: `rad/s` (the default), `rpm`, `Hz` or
    /// `cpm`; the answer's `output_unit` says which. Decay rates stay in 1/s.
    #[serde(default)]
    pub output_unit: Option<SpeedUnit>,
    /// The motion solved: `lateral` (default), `torsional` or `axial` (a beam rotor's; see
    /// the Motion schema).
    #[serde(default)]
    pub motion: super::Motion,
    /// Campbell with `motion: torsional` (or axial): the interference diagram's excitations
    /// (orders of each shaft's speed, line frequencies) and operating range.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub interference: Option<super::InterferenceInput>,
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
    /// On supports over whirl frequency (`modal` only): the relative residual
    /// `||Z(s) x|| / ((|s|^2 ||M|| + |s| ||D|| + ||K||) ||x||)` of the rotor's equation at this
    /// pole, its supports read at its own `|frequency|`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub residual: Option<f64>,
}

/// Complex translation of a node in a mode shape.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct NodeDisplacement {
    pub node: usize,
    pub re: f64,
    pub im: f64,
    /// Slope `d(x + i y)/dz` there (the rotation `phi_y - i phi_x`), 1/m, on the same scale as
    /// the translation, `[re, im]`: where a beam rotor's node keeps its rotation. With the next
    /// node's, the element's cubic shape functions give the shape between them.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub slope: Option<[f64; 2]>,
}

/// Where a beam rotor's nodes, supports and disks are along the shaft (for its mode shapes).
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct ShaftLayout {
    /// Axial position of each node, m, from node 0.
    pub positions: Vec<f64>,
    /// Nodes with a bearing (or any support that is not a seal).
    pub bearings: Vec<usize>,
    /// Nodes with a seal.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub seals: Vec<usize>,
    /// Nodes with a disk.
    pub disks: Vec<usize>,
    /// Left nodes of the couplings (each joins its node to the next): between them the shape
    /// is drawn straight, not as a beam's.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub couplings: Vec<usize>,
}

/// Answer of `POST /v1/modal`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct ModalResponse {
    /// Unit of every speed and whirl or natural frequency in this answer (the request's
    /// `output_unit`; rad/s by default). Decay rates are in 1/s whatever it is.
    #[serde(default)]
    pub output_unit: SpeedUnit,
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
    /// complex degree of freedom). Held sparse, the poles are counted in the box only as found,
    /// and this is 0.
    pub missing_poles: usize,
    /// The request's `max_frequency` (in `output_unit`): the poles reported are those in the box
    /// `|decay_rate|, |frequency| <= max_frequency`, the natural frequencies those up to it;
    /// null when every pole is.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_frequency: Option<f64>,
    /// How the full model was held: `dense`, or `sparse` (a rotor past 600 coordinates with
    /// `max_frequency`: shift-invert Arnoldi through sparse factors and Lanczos, exact, no
    /// dense matrix of the rotor's size).
    #[serde(default)]
    pub full_model: Storage,
    /// A beam rotor's nodes, supports and disks along the shaft.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shaft: Option<ShaftLayout>,
    /// On supports over whirl frequency: how the poles were made consistent with the
    /// frequency each reads them at.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub consistency: Option<ConsistencyInfo>,
    /// The motion solved. Torsional and axial motion is real: each mode is reported once (its
    /// pole of frequency >= 0; the conjugate is the same motion), its shape the twist (rad) or
    /// axial displacement of each node in `re`, `im`.
    #[serde(default)]
    pub motion: super::Motion,
    /// How the model was read where it needed saying: supports held at the ends of their
    /// tables of coefficients outside them.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
}

/// The poles of a rotor on supports over whirl frequency: each continued from a pole of the
/// rotor read synchronously (every table at frequency = speed) to the root of
/// `|Im s(w)| - w = 0`, `s(w)` the pole with the tables read at `w` (secant steps, each an
/// eigensolve about the last pole), so that it reads its supports at its own `|frequency|`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct ConsistencyInfo {
    /// The largest of the poles' `residual`s.
    pub max_residual: f64,
    /// Poles of the synchronous reading with no consistent pole near them (none reported).
    pub lost: usize,
    /// Poles of the synchronous reading that continued to a pole already reported.
    pub merged: usize,
    /// Eigensolves, in all.
    pub solves: usize,
    /// The whirl frequencies the poles read their supports at, rad/s: `[lowest, highest]`.
    pub read_at: [f64; 2],
}

/// One Campbell branch: the same physical mode followed from speed to speed, whatever its whirl
/// does (the lower mode of an anisotropic pair turns backward above rest; a nearly planar mode's
/// whirl ratio may change sign).
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct Branch {
    /// Mode number: the forward and backward branches of one mode share it (1F and 1B, ...),
    /// modes numbered by |frequency| where they start.
    pub mode: usize,
    /// The direction of most of its poles (`whirl_ratio` gives it at each speed).
    pub whirl: Whirl,
    /// Whirl frequency at each speed, rad/s, as `/v1/modal` reports the pole there (negative
    /// where it whirls backward); null where the model defines no pole for this mode.
    pub frequency: Vec<Option<f64>>,
    /// Decay rate at each speed, 1/s; null where the model defines no pole for this mode.
    pub decay_rate: Vec<Option<f64>>,
    /// Logarithmic decrement `-2 pi sigma / |omega|` at each speed; null where undefined.
    #[serde(default)]
    pub log_decrement: Vec<Option<f64>>,
    /// Damping ratio `-sigma / |s|` at each speed; null where undefined.
    #[serde(default)]
    pub damping_ratio: Vec<Option<f64>>,
    /// Whirl ratio at each speed, in [-1, 1]: +1 circular forward, -1 circular backward, 0
    /// planar (always +-1 on isotropic supports); null where undefined.
    #[serde(default)]
    pub whirl_ratio: Vec<Option<f64>>,
}

/// Poles overdamped at every speed of the sweep (`|frequency| <= 0.01 |decay_rate|`, a log
/// decrement past 628: real at rest, turned slowly at speed by the gyroscopic coupling of a
/// heavily damped support), followed like branches but not part of the Campbell diagram.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct OverdampedBranch {
    /// Decay rate at each speed, 1/s; null where it has no pole.
    pub decay_rate: Vec<Option<f64>>,
    /// Its residual frequency at each speed, rad/s (round-off at rest).
    pub frequency: Vec<Option<f64>>,
}

/// A crossing of a branch with the 1x line (whirl frequency = spin speed), refined by root
/// finding on the model to 1e-12 relative.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct CriticalSpeed {
    /// Spin speed, rad/s.
    pub speed: f64,
    /// Whirl of the pole at the crossing.
    pub whirl: Whirl,
    /// Mode number of the branch.
    pub mode: usize,
    /// Index of the branch in `branches`.
    pub branch: usize,
    /// Decay rate of the pole there, 1/s.
    pub decay_rate: f64,
    /// `-2 pi sigma / |omega|` there.
    pub log_decrement: Option<f64>,
    /// `-sigma / |s|` there.
    pub damping_ratio: f64,
    /// Whirl ratio there.
    pub whirl_ratio: f64,
    /// Damping ratio above 0.2 (API 684's amplification factor `1 / (2 zeta)` below 2.5): a
    /// critically damped crossing, not a critical speed that needs a separation margin.
    pub critically_damped: bool,
}

/// Two branches whose hand-over at a speed the tracking could not tell apart (veering, or a
/// crossing with similar shapes): the assignment made and the swap cost nearly the same.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct Ambiguity {
    /// Spin speed, rad/s.
    pub speed: f64,
    /// Indices of the two branches in `branches`.
    pub branches: [usize; 2],
}

/// Answer of `POST /v1/campbell`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct CampbellResponse {
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
    pub branches: Vec<Branch>,
    /// Speeds where a forward branch crosses the 1x line (frequency = speed) and is not
    /// critically damped, refined (see `criticals`), ascending.
    pub critical_speeds: Vec<f64>,
    /// Every crossing of a branch with the 1x line, forward and backward, by speed.
    #[serde(default)]
    pub criticals: Vec<CriticalSpeed>,
    /// Poles overdamped at every speed (not Campbell branches).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub overdamped: Vec<OverdampedBranch>,
    /// Ambiguous hand-overs between branches (none when every branch was followed clearly).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub ambiguities: Vec<Ambiguity>,
    /// Lowest speed of the range at which a pole has decay_rate > 0, refined by root finding;
    /// null when stable over the whole range.
    pub threshold: Option<f64>,
    /// The modal reduction the sweep ran on; null when it ran on the full model.
    pub reduction: Option<ReductionInfo>,
    /// The motion solved; torsional and axial sweeps keep one branch per mode (frequency >= 0).
    #[serde(default)]
    pub motion: super::Motion,
    /// A torsional or axial sweep's interference diagram: the excitations, their crossings
    /// with each mode and API 684's separation margins.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub interference: Option<super::Interference>,
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
    /// Every speed checked so, `checked_speed` first: a sweep over supports that change with
    /// the speed is also checked at its lowest and middle speeds.
    #[serde(default)]
    pub checked_speeds: Vec<f64>,
    /// Largest distance between a reduced and a full-model pole found there: for a sweep
    /// relative, `|s_reduced - s_full| / |s_full|` (at most 1e-6); for a time response
    /// relative to the decay rate, `|s_reduced - s_full| / max(|Re s_full|, 1e-3 |s_full|)`
    /// (at most 1e-3: a forced response near a pole moves by about that fraction).
    pub max_relative_error: f64,
    /// How the full model was held for the check: `dense` (small rotors), or `sparse` (large
    /// ones: sparse matrices and factors, the lowest modes by Lanczos, the full model's poles
    /// by shift-invert Arnoldi; no dense matrix of the rotor's size).
    #[serde(default)]
    pub full_model: Storage,
    /// For a Campbell diagram, the poles reported outside that box (a heavily damped mode whose
    /// |decay_rate|, or a branch whose |frequency|, passes `max_frequency`), which the check does
    /// not cover: each replaced by the full model's pole nearest it at its speed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub outside_box: Option<OutsideBox>,
    /// The equivalent or nonviscous model of a rotor held sparse: its dampers are on the
    /// undamped modes up to 16 times `max_frequency` (or the request's `modes`), this many
    /// (x/y modes each, on supports that are not isotropic; the dense models damp every mode).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub damped_modes: Option<usize>,
    /// Natural frequency of the highest of those modes, rad/s.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub damped_band: Option<f64>,
}

/// The poles of a reduced sweep outside the box its reduction was checked in (see
/// [`ReductionInfo::outside_box`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Deserialize, Serialize, ToSchema)]
pub struct OutsideBox {
    /// Poles reported outside the box, over every speed.
    pub poles: usize,
    /// Of those, replaced by the full model's pole nearest them (searched within 25 % of
    /// each).
    pub refined: usize,
    /// Of those, removed: the full model has no pole within 25 % of them. The rest (`poles -
    /// refined - removed`) are kept as the reduced model gives them.
    pub removed: usize,
    /// Largest change of a refined pole, relative to its modulus.
    pub largest_change: f64,
}

/// How a rotor's full model was held (see [`ReductionInfo::full_model`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize, Serialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum Storage {
    #[default]
    Dense,
    Sparse,
}

/// Answer of `POST /v1/stability`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct StabilityResponse {
    /// The rotor is the paper's nondimensional Jeffcott rotor (mass = stiffness = 1): its speeds,
    /// frequencies and decay rates are in units of sqrt(k/m) and its times in units of
    /// sqrt(m/k), and the plots label them so, without physical units.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub nondimensional: bool,
    /// Unit of every speed and whirl or natural frequency in this answer (the request's
    /// `output_unit`; rad/s by default). Decay rates are in 1/s whatever it is.
    #[serde(default)]
    pub output_unit: SpeedUnit,
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
    /// Largest decay rate of all poles at each grid speed, 1/s (held sparse, of those in the
    /// box below `max_frequency`, on the reduction).
    pub max_decay_rate: Vec<f64>,
    /// Held sparse (a rotor past 600 coordinates with `max_frequency`): the poles considered
    /// are those in the box `|decay_rate|, |frequency| <= max_frequency` (in `output_unit`);
    /// null when every pole is.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_frequency: Option<f64>,
    /// Held sparse: the modal reduction the grid was searched on, checked against the full
    /// model's poles in the box through sparse factors.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reduction: Option<ReductionInfo>,
    /// Held sparse, with a threshold: true where it was closed on the full model (the secant
    /// on the decay rate of the full model's pole, to 1e-10 relative), false where it is the
    /// reduction's (a jump of the hysteretic model, or the range's start).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub threshold_closed: Option<bool>,
    /// How the model was read where it needed saying: supports held at the ends of their
    /// tables of coefficients outside them.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
}
