//! Machine trains: the motion an analysis solves (lateral, torsional, axial), couplings, gear
//! meshes, and the torsional interference diagram's excitations and answer.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::{SpeedInput, SpeedUnit};

/// The motion an analysis solves: `lateral` (bending, the default), `torsional` (each node's
/// twist about the axis) or `axial` (each node's displacement along it). The three are
/// uncoupled in a straight shaft's linear model.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize, Serialize, ToSchema)]
#[serde(rename_all = "lowercase")]
pub enum Motion {
    #[default]
    Lateral,
    Torsional,
    Axial,
}

impl Motion {
    pub fn is_lateral(&self) -> bool {
        *self == Motion::Lateral
    }
}

/// A gear mesh joining two shafts of a train that turn at different speeds. Each shaft is
/// modelled in its own angles (true angles and torques); the mesh is a spring along its line
/// of action, referred to the driving shaft: for twists `theta_1` (before) and `theta_2`
/// (after), its torque on the driving gear is `mesh_stiffness (theta_2 / ratio - theta_1)`.
#[derive(Debug, Clone, Default, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct GearInput {
    /// Speed of the driven shaft over the driving shaft's (> 0; 3 for a speed increaser of
    /// 1:3). Each gear's inertia is a disk on its node.
    #[schema(exclusive_minimum = 0.0)]
    pub ratio: f64,
    /// Torsional stiffness of the mesh referred to the driving shaft, N m/rad (> 0: the tooth
    /// stiffness times the driving gear's base radius squared).
    #[schema(exclusive_minimum = 0.0)]
    pub mesh_stiffness: f64,
    /// Viscous damping of the mesh referred to the driving shaft, N m s/rad (>= 0).
    #[serde(default)]
    #[schema(minimum = 0.0)]
    pub mesh_damping: f64,
    /// Axial stiffness between the two gears, N/m (>= 0; a helical mesh's, for axial
    /// analyses; 0 leaves the shafts axially apart).
    #[serde(default)]
    #[schema(minimum = 0.0)]
    pub axial_stiffness: f64,
}

/// Excitations of the torsional interference diagram (`/v1/campbell` with `motion: torsional`).
#[derive(Debug, Clone, Default, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct InterferenceInput {
    /// Orders of each shaft's speed that excite the train (default `[1, 2]`): each gives a
    /// line `order x ratio x speed` per shaft speed in the train.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub orders: Option<Vec<f64>>,
    /// Electrical line frequency of the train's motors or generators (rad/s, or `{value, unit}`
    /// e.g. `{"value": 50, "unit": "Hz"}`): it and twice it are fixed excitations.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub line_frequency: Option<SpeedInput>,
    /// Operating speeds `[min, max]` of the reference (first) shaft, in the sweep's unit
    /// (default: the sweep's first and last speeds): the range the separation margins are
    /// measured from.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub operating_range: Option<[f64; 2]>,
}

/// One excitation of the interference diagram.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct Excitation {
    /// `order` of a shaft's speed, or `line` (a fixed frequency).
    pub kind: String,
    /// The order (of the shaft's speed), or the multiple of the line frequency.
    pub order: f64,
    /// Speed of the excitation's shaft over the reference shaft's (1 for the first shaft; 0
    /// for a fixed frequency).
    pub ratio: f64,
    /// Its frequency per unit reference speed (`order x ratio`), or its fixed frequency in the
    /// answer's unit for a line.
    pub slope: f64,
    /// Fixed frequency (a line excitation), in the answer's unit.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub frequency: Option<f64>,
}

/// A crossing of a torsional (or axial) natural frequency with an excitation.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct InterferenceCritical {
    /// Index of the excitation in `excitations`.
    pub excitation: usize,
    /// Mode number (1 the lowest).
    pub mode: usize,
    /// Reference shaft speed of the crossing, in the answer's unit (null for a line
    /// excitation, which crosses no speed).
    pub speed: Option<f64>,
    /// Natural frequency there, in the answer's unit.
    pub frequency: f64,
    /// Damping ratio of the mode there.
    pub damping_ratio: f64,
    /// Separation margin from the operating range (API 684): for an order, how far the
    /// natural frequency lies below `order x ratio x min` or above `order x ratio x max`,
    /// relative to that excitation frequency; for a line, `|f_n - f| / f`. Negative inside the
    /// range.
    pub margin: f64,
    /// Whether the margin is at least 10% (API 684's torsional criterion).
    pub passes: bool,
    /// The crossing lies beyond the sweep: its speed is the natural frequency at the sweep's
    /// speed nearest the operating range over the order's slope (exact where, as in torsion,
    /// the natural frequency does not move with speed).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub beyond_sweep: bool,
}

/// The torsional interference diagram: excitation lines and their crossings.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct Interference {
    pub excitations: Vec<Excitation>,
    /// Operating range of the reference shaft, in the answer's unit.
    pub operating_range: [f64; 2],
    /// Every crossing (and every mode's margin from every line), by speed.
    pub criticals: Vec<InterferenceCritical>,
    /// Unit of the speeds and frequencies here.
    pub unit: SpeedUnit,
}

/// A flexible coupling between two shaft ends (ROSS's `CouplingElement`): springs and dampers
/// between the translations, the rotations, the twists and the axial displacements of its two
/// nodes, and the masses and inertias of its two halves lumped on them. It turns with the
/// shafts, so its lateral damping is rotating damping (viscous, and hysteretic by
/// `loss_factor`); in torsion and axially the frames do not differ. Isotropic: a
/// coupling that is stiffer in one direction than the other turns that direction with it,
/// which no linear time-invariant model holds.
#[derive(Debug, Clone, Default, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct CouplingInput {
    /// Lateral (translational) stiffness between the two nodes, N/m (>= 0; ROSS's `kt_x = kt_y`).
    #[serde(default)]
    #[schema(minimum = 0.0)]
    pub translational_stiffness: f64,
    /// Angular (bending) stiffness between the two nodes' rotations, N m/rad (>= 0; ROSS's
    /// `kr_x = kr_y`).
    #[serde(default)]
    #[schema(minimum = 0.0)]
    pub angular_stiffness: f64,
    /// Lateral viscous damping, N s/m (>= 0), rotating with the coupling.
    #[serde(default)]
    #[schema(minimum = 0.0)]
    pub translational_damping: f64,
    /// Angular viscous damping, N m s/rad (>= 0), rotating with the coupling.
    #[serde(default)]
    #[schema(minimum = 0.0)]
    pub angular_damping: f64,
    /// Loss factor of the coupling's stiffness (elastomeric couplings): rotating hysteretic
    /// damping, in [0, 1).
    #[serde(default)]
    #[schema(minimum = 0.0, exclusive_maximum = 1.0)]
    pub loss_factor: f64,
    /// Mass of each half, kg (>= 0), lumped on its node: `[left, right]`.
    #[serde(default)]
    #[schema(min_items = 2, max_items = 2)]
    pub mass: [f64; 2],
    /// Polar moment of inertia of each half, kg m^2 (>= 0): `[left, right]`.
    #[serde(default)]
    #[schema(min_items = 2, max_items = 2)]
    pub polar_inertia: [f64; 2],
    /// Transverse (diametral) moment of inertia of each half, kg m^2 (>= 0; default half the
    /// polar one, as ROSS takes it): `[left, right]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(min_items = 2, max_items = 2)]
    pub transverse_inertia: Option<[f64; 2]>,
    /// Torsional stiffness between the two nodes' twists, N m/rad (>= 0; ROSS's `kr_z`): read by
    /// torsional analyses; 0 leaves the shafts on either side free of each other in torsion.
    #[serde(default)]
    #[schema(minimum = 0.0)]
    pub torsional_stiffness: f64,
    /// Torsional viscous damping, N m s/rad (>= 0; ROSS's `cr_z`).
    #[serde(default)]
    #[schema(minimum = 0.0)]
    pub torsional_damping: f64,
    /// Axial stiffness between the two nodes, N/m (>= 0; ROSS's `kt_z`): axial analyses.
    #[serde(default)]
    #[schema(minimum = 0.0)]
    pub axial_stiffness: f64,
    /// Axial viscous damping, N s/m (>= 0; ROSS's `ct_z`).
    #[serde(default)]
    #[schema(minimum = 0.0)]
    pub axial_damping: f64,
}

impl Interference {
    /// Mode `mode`'s crossing of least margin: its nearest excitation.
    pub fn nearest(&self, mode: usize) -> Option<&InterferenceCritical> {
        self.criticals
            .iter()
            .filter(|k| k.mode == mode)
            .min_by(|a, b| a.margin.total_cmp(&b.margin))
    }

    /// 1.5 times the highest excitation frequency over the operating range, in the answer's
    /// unit: a mode above it is more than 50% from every excitation, out of their reach.
    pub fn reach(&self) -> f64 {
        let top = self
            .excitations
            .iter()
            .map(|e| e.frequency.unwrap_or(e.slope * self.operating_range[1]))
            .fold(0.0, f64::max);
        1.5 * top
    }

    /// The label of excitation `e`: `2x`, `1x of the 3.2x shaft` (a shaft turning 3.2 times as
    /// fast), `f_L`, `2 f_L`.
    pub fn label(&self, e: usize) -> String {
        let x = &self.excitations[e];
        let k = plain(x.order);
        match x.kind.as_str() {
            "line" if x.order == 1.0 => "f_L".into(),
            "line" => format!("{k} f_L"),
            _ if x.ratio == 1.0 => format!("{k}x"),
            _ => format!("{k}x of the {}x shaft", plain(x.ratio)),
        }
    }
}

/// `2`, `3.2`, `0.333`: a number without trailing zeros.
pub fn plain(v: f64) -> String {
    let s = format!("{v:.3}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}
