//! Request and answer of `POST /v1/damping`: a damping model as matrices.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::*;

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
    /// `translation`, `rotation`, `internal` (a nonviscous damper's branch) or `support
    /// branch` (a branch fitted to a support's table over whirl frequency).
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
    /// The support a `support branch` is fitted to (its table over whirl frequency).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub support: Option<String>,
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
    /// The supports over whirl frequency, each fitted by Maxwell branches (their internal
    /// coordinates follow the model's).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub support_fits: Vec<SupportFitInfo>,
    /// How the model was read where it needed saying: supports held at the ends of their
    /// tables of coefficients outside them.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
}

/// How a support's table over whirl frequency is carried into the time domain: its dynamic
/// stiffness `H(w) = K(w) + i w C(w) - w^2 M(w)` replaced by
/// `K0 + i w C0 - w^2 M0 + sum_j G_j i w / (i w + d_j)` (Maxwell branches, one internal
/// coordinate each on `r`, and on `conj r` when doubled).
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct SupportFitInfo {
    /// The support (`rotor.supports[i]` or `rotor.seals[i]`).
    pub support: String,
    /// The branches' relaxation rates `d_j`, 1/s.
    pub rates: Vec<f64>,
    /// The table's frequencies, first and last (rad/s): where the fit is measured. Past the
    /// last the fitted support follows its branches (`K0 + sum G_j`, `C0`), not the table's
    /// straight continuation.
    pub band: [f64; 2],
    /// Largest `|H~ - H|` over the band (and the table's speeds) of each coefficient, relative
    /// to the support's direct `|H|` (`max(|H_xx|, |H_yy|)`) at that frequency; measured at the
    /// table's frequencies, three readings between each two and 40 per decade of the band, and
    /// between them. The fit is held to the table at the spin speed of a time response at
    /// constant speed (and at `speed` here), where an unbalance whirls.
    pub deviation: Matrix2Out,
    /// The largest of `deviation`.
    pub max_deviation: f64,
    /// The speeds the fit was made at (rad/s; linear between them); empty when constant.
    pub speeds: Vec<f64>,
    /// Whether a symmetric cross term was shrunk to keep every branch passive.
    pub shrunk: bool,
}

/// A 2x2 coefficient matrix by its entries.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, ToSchema)]
pub struct Matrix2Out {
    pub xx: f64,
    pub xy: f64,
    pub yx: f64,
    pub yy: f64,
}

/// A pole `s = decay_rate + i frequency` (1/s, rad/s).
#[derive(Debug, Clone, Copy, Deserialize, Serialize, ToSchema)]
pub struct PoleValue {
    pub decay_rate: f64,
    pub frequency: f64,
}

/// A pole of the rotor and the nearest of the model fitted for the time domain.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct FitPolePair {
    /// Consistent with the whirl frequency it reads its supports at (as `/v1/modal` finds it,
    /// under the viscous model, or the hysteretic for the nonviscous and equivalent models).
    pub consistent: PoleValue,
    /// The fitted model's (the member of a mirror pair on the same side, in doubled
    /// coordinates).
    pub fitted: PoleValue,
    /// `|fitted - consistent| / |consistent|`.
    pub distance: f64,
}

/// The poles of the model integrated (its supports over whirl frequency fitted by Maxwell
/// branches) against the rotor's own at one speed of the integration, compared before
/// integrating. A fitted model with a pole that grows where every pole of the rotor decays is
/// refitted, held also at that pole's frequency, and not integrated if it still grows.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct FitPolesInfo {
    /// Spin speed, rad/s (the constant speed, or each knot of the speed profile).
    pub speed: f64,
    /// Each pole of the rotor with its partner, by increasing |frequency|.
    pub poles: Vec<FitPolePair>,
    /// The largest `distance`.
    pub max_distance: f64,
    /// The largest decay rate of the rotor's poles, 1/s.
    pub max_decay_rate: f64,
    /// The largest decay rate of the fitted model's poles (its branches' included), 1/s.
    pub fitted_max_decay_rate: f64,
    /// Poles of the fitted model that grow with no growing pole of the rotor beside them.
    pub unstable: Vec<PoleValue>,
    /// Poles of the consistency search not found, and merged into others.
    pub lost: usize,
    pub merged: usize,
}
