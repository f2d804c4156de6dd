//! Requests parsed into tasks: one `parse(&Limits)` per request. Every field is checked and
//! every size the request implies is computed here, from the validated input, before anything
//! proportional to it is allocated; the service only reads the body, calls `parse`, submits the
//! task and answers.

use super::api::{
    AnalysisName, CriticalSpeedMapRequest, DampingInput, DampingMatricesRequest,
    FrequencyResponseRequest, Level1Request, MatrixForm, ModalRequest, Motion, ReportRequest,
    RotorInput, SpeedInput, StaticRequest, SweepRequest, TimeResponseRequest,
    UnbalanceResponseRequest,
};
use super::damping::BranchSet;
use super::damping::DampingModel;
use super::error::{Invalid, finite, non_negative, positive};
use super::limits::{
    BATCH_PER_THREAD, BYTES_PER_VALUE, Cost, Limits, MAX_DAMPED_MODES, SPARSE_ARNOLDI, SPARSE_FROM,
    SPARSE_HARMONIC_BYTES, SPARSE_REDUCED_STATES, Size, damper_bytes_per_coordinate,
    sparse_bytes_per_coordinate,
};
use super::loads::{Excitation, Force, Pwl, SpeedLaw, TimeSpec, Unbalance, sample_count};
use super::rotor::BeamRotor;
use super::rotor::Rotor;
use super::speeds::SpeedGrid;
use super::supports::held_warning;

mod analyses;
mod audit;
mod cost;
mod held;
mod loads;
mod report;
mod report_torsion;
mod whirl;

pub use audit::STANDARD_GRAVITY;
pub use cost::sparse_states;
use cost::{SPARSE_WORK, sparse_harmonic_cost, sparse_sweep_cost, sparse_time_cost, sweep_cost};
pub use report::{MAX_CASES, ModelPlan, ReportPlan, SWEEP_OVER_MCS};
pub use report_torsion::TorsionPlan;

/// A validated rotor and damping model.
#[derive(Debug, Clone)]
pub struct Model {
    pub rotor: Rotor,
    pub damping: DampingModel,
}

impl Model {
    /// Validates rotor and damping together, adding to the errors already found, and checks
    /// the state size the pair implies.
    pub fn parse(
        rotor: &RotorInput,
        damping: &DampingInput,
        limits: &Limits,
        bad: Invalid,
    ) -> Result<Self, Invalid> {
        Self::parse_motion(rotor, damping, Motion::Lateral, limits, bad)
    }

    /// [`Model::parse`] for the motion an analysis solves (`Rotor::parse_motion`).
    pub fn parse_motion(
        rotor: &RotorInput,
        damping: &DampingInput,
        motion: Motion,
        limits: &Limits,
        mut bad: Invalid,
    ) -> Result<Self, Invalid> {
        let rotor = match Rotor::parse_motion(rotor, motion, limits) {
            Ok(r) => Some(r),
            Err(e) => {
                bad.extend(e);
                None
            }
        };
        // `modes` is bounded by the rotor's size; without a valid rotor, only from below.
        let dofs = rotor.as_ref().map(Rotor::dof_count);
        let damping = match DampingModel::parse(damping, dofs) {
            Ok(d) => Some(d),
            Err(e) => {
                bad.extend(e);
                None
            }
        };
        let (Some(rotor), Some(damping)) = (rotor, damping) else {
            return Err(bad);
        };
        let model = Model { rotor, damping };
        model.check_states(limits, &mut bad);
        bad.into_result(|| model)
    }

    /// Sizes of the model as solved, with `branches` per nonviscous damper (its own when
    /// `None`).
    pub fn size_with(&self, branches: Option<(usize, usize)>) -> Size {
        let n = self.rotor.dof_count();
        // Doubled coordinates: twice the degrees of freedom, a nonrotating damper per x/y mode
        // and each rotating one on both copies.
        let copies = if self.rotor.doubled() { 2 } else { 1 };
        let (rotating, nonrotating) = self.rotor.loss_sides();
        let (internal, problems) = match &self.damping {
            DampingModel::Nonviscous(spec) => {
                let (br, bn) =
                    branches.unwrap_or((spec.rotating.count(), spec.nonrotating.count()));
                let modes = spec.modes.unwrap_or(n);
                let per_mode = usize::from(rotating) * br + usize::from(nonrotating) * bn;
                (copies * modes * per_mode, 1)
            }
            DampingModel::Hysteretic => (0, 4),
            _ => (0, 1),
        };
        let general = self.rotor.general_supports();
        // A table over whirl frequency is fitted by branches in the time domain: at most
        // `MAX_BRANCHES` each, on `r` (and `conj r`), realized at its speeds.
        let fitted = general.iter().filter(|s| s.frequency_dependent()).count();
        let internal = internal + copies * fitted * crate::model::supports::fitted::MAX_BRANCHES;
        let mut speeds: Vec<f64> = general
            .iter()
            .flat_map(|s| s.tabulated_speeds().iter().copied())
            .collect();
        speeds.sort_by(f64::total_cmp);
        speeds.dedup();
        // Supports on ROSS's curves put every table on one scheduled model (`n x 2` more per
        // support, not counted).
        if general.iter().any(|s| s.ross()) {
            speeds.truncate(1);
        }
        Size {
            assembled: copies * self.rotor.assembled_dofs(),
            dofs: copies * n,
            internal,
            problems,
            points: speeds.len().max(1),
        }
    }

    pub fn size(&self) -> Size {
        self.size_with(None)
    }

    /// Warnings for analysis speeds in `[lo, hi]` outside a support's table, and for modal
    /// bases taken at rest below a table.
    pub fn warnings(&self, lo: f64, hi: f64) -> Vec<String> {
        let mut out = vec![];
        for s in self.rotor.general_supports() {
            let path = s.path();
            if let Some(w) = held_warning(&path, s, lo, hi) {
                out.push(w);
            }
            if let Some(g) = s.grid() {
                out.extend(g.few_points(&path));
                out.extend(g.past(&path, false, (lo, hi)));
            }
            if self.damping.on_modes() && s.speeds().first().is_some_and(|&w| w > 0.0) {
                out.push(format!(
                    "{path}: the {} model is built on the modes of the rotor at rest, where \
                     this support's coefficients are taken as at its table's first speed",
                    self.damping.name()
                ));
            }
        }
        out
    }

    /// Warnings for supports over whirl frequency read at whirl frequencies in `[lo, hi]`
    /// (rad/s) past their tables, and for a direct coefficient that changes sign there.
    pub fn whirl_warnings(&self, lo: f64, hi: f64) -> Vec<String> {
        let mut out = vec![];
        for s in self.rotor.general_supports() {
            if let Some(g) = s.grid() {
                out.extend(g.past(&s.path(), true, (lo, hi)));
                out.extend(g.sign_changes(&s.path(), (lo, hi)));
            }
        }
        out
    }

    fn check_states(&self, limits: &Limits, bad: &mut Invalid) {
        let size = self.size();
        let states = size.states();
        if states <= limits.max_states {
            return;
        }
        if 2 * size.dofs <= limits.max_states {
            bad.push(
                "damping",
                format!(
                    "the model would have up to {states} states ({} from the rotor, {} from \
                     the nonviscous branches), more than the limit of {} (WHIRL_MAX_STATES): \
                     use fewer branches, `modes`, or Guyan reduction",
                    2 * size.dofs,
                    size.internal,
                    limits.max_states
                ),
            );
        } else {
            bad.push(
                "rotor",
                format!(
                    "the rotor has {} degrees of freedom, {states} states, more than the limit \
                     of {} (WHIRL_MAX_STATES): use Guyan reduction (`reduction`) or fewer \
                     elements",
                    size.dofs, limits.max_states
                ),
            );
        }
    }
}

/// A validated analysis and what it will cost.
#[derive(Debug, Clone)]
pub struct Task {
    pub kind: TaskKind,
    pub cost: Cost,
    /// What the answer should say about how the model was read (supports held outside their
    /// tables).
    pub warnings: Vec<String>,
    /// Unit of the speeds and frequencies of the answer (the request's `output_unit`).
    pub output_unit: super::api::SpeedUnit,
}

#[derive(Debug, Clone)]
pub enum TaskKind {
    Modal(ModalTask),
    Campbell(CampbellTask),
    Stability(StabilityTask),
    Damping(DampingTask),
    Time(TimeTask),
    Unbalance(UnbalanceTask),
    CriticalMap(CriticalMapTask),
    Static(StaticTask),
    Level1(Level1Task),
    Frequency(FrequencyTask),
    Report(Box<ReportPlan>),
}

/// Poles at one speed.
#[derive(Debug, Clone)]
pub struct ModalTask {
    pub model: Model,
    pub speed: f64,
    /// Poles in the box `|Re s|, |Im s| <=` this (infinite: all).
    pub max_frequency: f64,
    /// Held sparse (then bounded).
    pub sparse: bool,
}

/// A sweep over speeds with branches tracked.
#[derive(Debug, Clone)]
pub struct CampbellTask {
    pub model: Model,
    pub speeds: SpeedGrid,
    /// Branches below this |frequency| (infinite: all).
    pub max_frequency: f64,
    /// Only the lowest this many branches at the first speed.
    pub modes: Option<usize>,
    /// Whether a checked modal reduction may be used.
    pub reduce: bool,
    /// Whether the rotor is held sparse (`analysis::large`): a bounded sweep of the viscous
    /// or hysteretic model, no Guyan reduction, more than [`SPARSE_FROM`] coordinates.
    pub sparse: bool,
    /// Largest reduced model the sparse path may solve (its cost was estimated so).
    pub max_states: usize,
    /// A torsional or axial train's interference diagram.
    pub interference: Option<super::train::Spec>,
}

/// The threshold of instability over a speed range.
#[derive(Debug, Clone)]
pub struct StabilityTask {
    pub model: Model,
    pub speeds: SpeedGrid,
    /// Held sparse: the poles in the box `|Re s|, |Im s| <=` this are considered, on a
    /// reduction of at most `max_states` states (`None`: every pole, dense).
    pub held: Option<(f64, usize)>,
}

/// The damping model's matrices and fits.
#[derive(Debug, Clone)]
pub struct DampingTask {
    pub model: Model,
    pub state_form: bool,
    pub band: Option<[f64; 2]>,
    pub max_deviation: Option<f64>,
    /// The fit may choose no more states than this.
    pub max_states: usize,
    /// Spin speed at which tabulated supports are evaluated.
    pub speed: f64,
}

/// A time response.
#[derive(Debug, Clone)]
pub struct TimeTask {
    pub model: Model,
    pub spec: TimeSpec,
    /// Whether the rotor is held sparse ([`Model::parse_held`]): integrated on a reduction
    /// checked through sparse factors, never on its full model.
    pub sparse: bool,
}

/// The steady unbalance response over speeds.
#[derive(Debug, Clone)]
pub struct UnbalanceTask {
    pub model: Model,
    pub speeds: SpeedGrid,
    /// `(node, m e, phase)`.
    pub unbalances: Vec<(usize, f64, f64)>,
    pub nodes: Vec<usize>,
    /// Operating range `(min, max)`, rad/s: the peaks' separation margins.
    pub range: Option<(f64, f64)>,
    /// Whether a checked modal reduction may be used.
    pub reduce: bool,
    /// Whether the rotor is held sparse ([`Model::parse_held`]).
    pub sparse: bool,
}

/// The undamped critical speed map.
#[derive(Debug, Clone)]
pub struct CriticalMapTask {
    pub rotor: BeamRotor,
    pub stiffness: Vec<f64>,
    pub modes: usize,
}

/// The static deflection under gravity.
#[derive(Debug, Clone)]
pub struct StaticTask {
    pub rotor: BeamRotor,
    pub gravity: f64,
    pub rigid: bool,
    /// Speed at which tabulated supports are evaluated.
    pub speed: f64,
}

/// API 617's Level I (and II) stability screen.
#[derive(Debug, Clone)]
pub struct Level1Task {
    pub model: Model,
    pub speed: f64,
    /// `(node, share of q)`.
    pub at: Vec<(usize, f64)>,
    pub qs: Vec<f64>,
    /// API 617's anticipated cross-coupling, N/m.
    pub qa: Option<f64>,
    /// The machine's mean gas density, kg/m^3 (the Region A/B screen).
    pub density: Option<f64>,
    /// Level II's further cross-coupling, `(node, q N/m)`; Level II runs with `qa`.
    pub extra: Vec<(usize, f64)>,
    /// Whether Level I may run on a checked modal reduction.
    pub reduce: bool,
    /// Whether the rotor is held sparse ([`Model::parse_held`]): Level I on a reduction
    /// checked through sparse factors only, no Level II.
    pub sparse: bool,
}

/// A non-synchronous frequency response at one speed.
#[derive(Debug, Clone)]
pub struct FrequencyTask {
    pub model: Model,
    pub speed: f64,
    pub input: (usize, Excitation),
    pub output: usize,
    pub frequencies: Vec<f64>,
    /// Whether a checked modal reduction may be used.
    pub reduce: bool,
    /// Whether the rotor is held sparse ([`Model::parse_held`]).
    pub sparse: bool,
}

impl Task {
    /// The analysis's name, as in its path.
    pub fn name(&self) -> &'static str {
        match &self.kind {
            TaskKind::Modal(ModalTask { .. }) => "modal",
            TaskKind::Campbell(CampbellTask { .. }) => "campbell",
            TaskKind::Stability(StabilityTask { .. }) => "stability",
            TaskKind::Damping(DampingTask { .. }) => "damping",
            TaskKind::Time(TimeTask { .. }) => "time-response",
            TaskKind::Unbalance(UnbalanceTask { .. }) => "unbalance-response",
            TaskKind::CriticalMap(CriticalMapTask { .. }) => "critical-speed-map",
            TaskKind::Static(StaticTask { .. }) => "static",
            TaskKind::Level1(Level1Task { .. }) => "level1",
            TaskKind::Frequency(FrequencyTask { .. }) => "frequency-response",
            TaskKind::Report(_) => "report",
        }
    }

    /// The rotor and damping model analysed (none for the analyses without damping, and for
    /// the report, which runs several).
    pub fn model(&self) -> Option<&Model> {
        match &self.kind {
            TaskKind::Modal(ModalTask { model, .. })
            | TaskKind::Campbell(CampbellTask { model, .. })
            | TaskKind::Stability(StabilityTask { model, .. })
            | TaskKind::Damping(DampingTask { model, .. })
            | TaskKind::Time(TimeTask { model, .. })
            | TaskKind::Unbalance(UnbalanceTask { model, .. })
            | TaskKind::Level1(Level1Task { model, .. })
            | TaskKind::Frequency(FrequencyTask { model, .. }) => Some(model),
            TaskKind::CriticalMap(CriticalMapTask { .. })
            | TaskKind::Static(StaticTask { .. })
            | TaskKind::Report(_) => None,
        }
    }

    /// The field that sizes the task most (for a message about its memory).
    pub fn size_field(&self) -> &'static str {
        let size = self.cost.size;
        let model = size.model_bytes() + 2 * size.eigen_bytes();
        let rest = self.cost.peak_bytes.saturating_sub(model);
        match &self.kind {
            TaskKind::Damping(DampingTask { .. }) => "damping",
            TaskKind::Modal(ModalTask { .. }) => "rotor",
            TaskKind::Time(TimeTask { .. }) if rest > model => "output_interval",
            TaskKind::Campbell(CampbellTask { .. })
            | TaskKind::Stability(StabilityTask { .. })
            | TaskKind::Unbalance(UnbalanceTask { .. })
            | TaskKind::Report(_)
                if rest > model =>
            {
                "speeds"
            }
            TaskKind::CriticalMap(CriticalMapTask { .. }) if rest > model => "stiffness",
            TaskKind::Level1(Level1Task { .. }) if rest > model => "cross_coupling",
            TaskKind::Frequency(FrequencyTask { .. }) if rest > model => "frequencies",
            _ => "rotor",
        }
    }

    /// Refuses a task whose answer would exceed the limit (`path`: the field that sets it).
    fn bounded(self, limits: &Limits, path: &str) -> Result<Self, Invalid> {
        self.whirl_read()?;
        if self.cost.response_bytes > limits.max_response_bytes {
            return Err(Invalid::one(
                path,
                format!(
                    "the answer would be about {} MB, more than the limit of {} MB \
                     (WHIRL_MAX_RESPONSE_BYTES)",
                    self.cost.response_bytes.div_ceil(1 << 20),
                    limits.max_response_bytes >> 20
                ),
            ));
        }
        Ok(self)
    }
}

/// A typed speed in rad/s (>= 0), or its error added to `bad` at `name` (or `name.value`).
fn speed_at(bad: &mut Invalid, name: &str, speed: SpeedInput) -> Option<f64> {
    typed_speed(bad, name, speed, non_negative)
}

/// A typed speed in rad/s whose number as typed passes `check`; its error otherwise.
fn typed_speed(
    bad: &mut Invalid,
    name: &str,
    speed: SpeedInput,
    check: fn(f64) -> Result<f64, String>,
) -> Option<f64> {
    bad.check(&speed.field(name), check(speed.value()))
        .map(|_| speed.rad_s())
}

/// The speeds of a sweep, adding their errors to `bad`.
fn speeds(
    input: &super::api::SpeedsInput,
    limits: &Limits,
    bad: &mut Invalid,
) -> Option<SpeedGrid> {
    match SpeedGrid::parse(input, limits.max_speeds) {
        Ok(g) => Some(g),
        Err(e) => {
            bad.extend(e);
            None
        }
    }
}

/// A job's input, typed by its analysis: what `POST /v1/jobs` validates.
pub enum JobInput {
    Modal(ModalRequest),
    Campbell(SweepRequest),
    Stability(SweepRequest),
    Damping(DampingMatricesRequest),
    Time(TimeResponseRequest),
    Unbalance(UnbalanceResponseRequest),
    CriticalMap(CriticalSpeedMapRequest),
    Static(StaticRequest),
    Level1(Level1Request),
    Frequency(FrequencyResponseRequest),
    Report(Box<ReportRequest>),
}

impl JobInput {
    pub fn analysis(&self) -> AnalysisName {
        match self {
            JobInput::Modal(_) => AnalysisName::Modal,
            JobInput::Campbell(_) => AnalysisName::Campbell,
            JobInput::Stability(_) => AnalysisName::Stability,
            JobInput::Damping(_) => AnalysisName::Damping,
            JobInput::Time(_) => AnalysisName::TimeResponse,
            JobInput::Unbalance(_) => AnalysisName::UnbalanceResponse,
            JobInput::CriticalMap(_) => AnalysisName::CriticalSpeedMap,
            JobInput::Static(_) => AnalysisName::Static,
            JobInput::Level1(_) => AnalysisName::Level1,
            JobInput::Frequency(_) => AnalysisName::FrequencyResponse,
            JobInput::Report(_) => AnalysisName::Report,
        }
    }

    pub fn parse(&self, limits: &Limits) -> Result<Task, Invalid> {
        match self {
            JobInput::Modal(r) => r.parse(limits),
            JobInput::Campbell(r) => r.parse_campbell(limits),
            JobInput::Stability(r) => r.parse_stability(limits),
            JobInput::Damping(r) => r.parse(limits),
            JobInput::Time(r) => r.parse(limits),
            JobInput::Unbalance(r) => r.parse(limits),
            JobInput::CriticalMap(r) => r.parse(limits),
            JobInput::Static(r) => r.parse(limits),
            JobInput::Level1(r) => r.parse(limits),
            JobInput::Frequency(r) => r.parse(limits),
            JobInput::Report(r) => r.parse(limits),
        }
    }
}
