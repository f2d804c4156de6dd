//! Runs a validated task: assemble the rotor, build its damping model, analyse. The one entry
//! point of the numerics for the service (which converts the outcome to wire types).

mod audit;
mod audit_report;
mod campbell;
mod damping;
mod harmonic;
mod modal;
mod models;
mod threshold;
mod time;
mod time_fit;
mod time_train;

use models::assemble;
pub use models::build;
pub use time_fit::FittedTime;

use super::AnalysisError;
use super::audit::cases::{self, Assessment, Case};
use super::audit::critical_map::CriticalMap;
use super::audit::frequency::Excitation;
use super::audit::level1::{ForwardPole, Level1};
use super::audit::level1_reduced;
use super::audit::level2;
use super::audit::peaks::Peak;
use super::audit::placement;
use super::audit::statics::StaticResult;
use super::campbell::CampbellResult;
use super::control::Control;
use super::criticals::Critical;
use super::modal::ModalResult;
use super::poles::Whirl;
use super::response::ResponseReduction;
use super::stability::Threshold;
use super::stability_large;
use super::time::{TimeError, TimeResult};
use super::unbalance::Orbit;
use crate::damping::report::ModelMatrices;
use crate::damping::whirl_fit::SupportFit;
use crate::model::task::{MAX_CASES, ReportPlan, Task, TaskKind};
use crate::model::{Invalid, rotor::Rotor};

/// What an analysis found, in domain types.
#[derive(Debug, Clone)]
pub enum Outcome {
    Modal(ModalResult),
    Campbell(CampbellResult),
    Stability {
        threshold: Option<Threshold>,
        speeds: Vec<f64>,
        max_decay_rate: Vec<f64>,
        /// Held sparse: the bound of the poles considered and how the threshold was found (on
        /// a reduction; none on supports over whirl frequency, whose consistent poles are the
        /// full model's).
        held: Option<(f64, Option<Box<stability_large::Bounded>>)>,
    },
    Damping {
        matrices: Box<ModelMatrices>,
        model: &'static str,
        /// The fits of the supports over whirl frequency.
        fits: Vec<SupportFit>,
    },
    Time(
        TimeResult,
        Option<crate::analysis::reduction::Reduction>,
        time_fit::FittedTime,
    ),
    Unbalance {
        speeds: Vec<f64>,
        nodes: Vec<usize>,
        /// The orbit of each node at each speed.
        response: Vec<Vec<Orbit>>,
        /// The peaks of each node's amplitude (semi-major axis).
        peaks: Vec<Vec<Peak>>,
        range: Option<(f64, f64)>,
        model: &'static str,
        /// The checked modal reduction solved; `None` for the full model.
        reduction: Option<ResponseReduction>,
        /// Whether the full model was held sparse.
        sparse: bool,
    },
    CriticalMap {
        stiffness: Vec<f64>,
        map: CriticalMap,
    },
    Static {
        result: StaticResult,
        gravity: f64,
        rigid: bool,
    },
    Level1 {
        speed: f64,
        at: Vec<(usize, f64)>,
        qs: Vec<f64>,
        result: Level1,
        /// q_A and the first forward mode there.
        qa: Option<(f64, ForwardPole)>,
        /// The first critical speed on rigid supports (beam rotors), rad/s.
        rigid: Option<f64>,
        /// The machine's mean gas density, kg/m^3.
        density: Option<f64>,
        /// API 617's Level II, with the machine's data.
        level2: Option<Vec<(level2::Source, ForwardPole)>>,
        /// The checked reduction Level I ran on, if it did.
        reduction: Option<level1_reduced::Level1Reduction>,
        model: &'static str,
    },
    Frequency {
        speed: f64,
        input: (usize, Excitation),
        output: usize,
        frequencies: Vec<f64>,
        response: Vec<Orbit>,
        model: &'static str,
        reduction: Option<ResponseReduction>,
        /// Whether the full model was held sparse.
        sparse: bool,
        /// A train's element loads per unit input.
        elements: Vec<super::shaft_loads::ElementResponse>,
    },
    /// The report's parts, in the order of its plan: map, static, Campbell, unbalance, then
    /// per compared model its Campbell, Level I and unbalance; and its unbalance cases.
    Report {
        parts: Vec<Outcome>,
        cases: Vec<CaseOutcome>,
        /// The same on each bearing set, in the plan's order.
        sets: Vec<Outcome>,
    },
}

/// One of the report's unbalance cases, run.
#[derive(Debug, Clone)]
pub struct CaseOutcome {
    pub case: Case,
    pub shape: cases::Shape,
    /// An [`Outcome::Unbalance`].
    pub response: Box<Outcome>,
    pub assessment: Assessment,
}

/// Why a valid request could not be analysed.
#[derive(Debug, Clone, PartialEq)]
pub enum RunError {
    /// The model is invalid in a way only assembly shows (a rotor its supports do not hold).
    Invalid(Invalid),
    /// The analysis cannot be carried out on this model; the reason.
    Unsolvable(String),
    Cancelled,
}

impl From<AnalysisError> for RunError {
    fn from(e: AnalysisError) -> Self {
        match e {
            AnalysisError::Cancelled => RunError::Cancelled,
            e => RunError::Unsolvable(e.to_string()),
        }
    }
}

impl From<TimeError> for RunError {
    fn from(e: TimeError) -> Self {
        match e {
            TimeError::Cancelled => RunError::Cancelled,
            e => RunError::Unsolvable(e.to_string()),
        }
    }
}

/// An analysis that runs on its own: each task kind implements it beside its analysis, so a new
/// analysis or motion adds its own module and one line of [`run`].
pub trait Analysis {
    /// Runs the analysis, checking `control` for cancellation and counting progress there.
    fn run(&self, control: &Control) -> Result<Outcome, RunError>;
}

/// Runs `task`, checking `control` for cancellation and counting progress there.
pub fn run(task: &Task, control: &Control) -> Result<Outcome, RunError> {
    let analysis: &dyn Analysis = match &task.kind {
        TaskKind::Modal(t) => t,
        TaskKind::Campbell(t) => t,
        TaskKind::Stability(t) => t,
        TaskKind::Damping(t) => t,
        TaskKind::Time(t) => t,
        TaskKind::Unbalance(t) => t,
        TaskKind::CriticalMap(t) => t,
        TaskKind::Static(t) => t,
        TaskKind::Level1(t) => t,
        TaskKind::Frequency(t) => t,
        TaskKind::Report(plan) => plan.as_ref(),
    };
    analysis.run(control)
}
