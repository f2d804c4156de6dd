//! Requests and answers of the frequency-domain analyses: modal, Campbell, stability, and
//! the damping models as matrices.

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
    /// How the model was read where it needed saying: supports held at the ends of their
    /// tables of coefficients outside them.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
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
    /// Spin speed at which supports tabulated against speed are evaluated, rad/s or
    /// `{value, unit}` (default 0).
    #[serde(default)]
    pub speed: Option<SpeedInput>,
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
