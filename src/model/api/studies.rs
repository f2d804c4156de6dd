//! Studies (`/v1/studies`): one job request run over many values of its parameters (a grid, or
//! samples of distributions), each sample a job in the shared queue.

use serde::{Deserialize, Serialize};
use serde_json::Value;
use utoipa::ToSchema;

use super::{AnalysisName, JobStatus, Problem};

/// Body of `POST /v1/studies`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct StudyRequest {
    pub analysis: AnalysisName,
    /// The body the synchronous endpoint `POST /v1/<analysis>` takes: every sample is this
    /// input with its parameters' values put in.
    #[schema(value_type = Object)]
    pub input: Value,
    /// What varies: each a JSON pointer into `input` (RFC 6901) with `values` (a grid) or a
    /// `distribution` (Monte Carlo, Latin hypercube).
    pub parameters: Vec<StudyParameter>,
    pub design: StudyDesign,
    /// Samples to draw (`monte-carlo`, `latin-hypercube`); a grid has the product of its
    /// lists' lengths (`samples`, if given, must equal it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub samples: Option<u64>,
    /// Seed of the random designs: the same seed draws the same samples. Chosen by the server
    /// (and shown in the result) if not given.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seed: Option<u64>,
    /// JSON pointers into each sample's result (the body `POST /v1/<analysis>` answers), e.g.
    /// `/threshold` of a stability analysis.
    pub outputs: Vec<String>,
}

/// A parameter of a study: where in the input, and the values it takes.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct StudyParameter {
    /// RFC 6901 pointer to a value present in `input`, e.g. `/rotor/loss_factor_nonrotating`.
    pub pointer: String,
    /// The values of a grid (any JSON: numbers, or e.g. damping model names).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub values: Option<Vec<Value>>,
    /// The distribution of a random design.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub distribution: Option<Distribution>,
}

/// A distribution, optionally truncated to `[min, max]`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct Distribution {
    #[serde(rename = "type")]
    pub kind: DistributionKind,
    /// `uniform`: lower bound.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub low: Option<f64>,
    /// `uniform`: upper bound.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub high: Option<f64>,
    /// `normal`: mean.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mean: Option<f64>,
    /// `normal`: standard deviation (> 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub std: Option<f64>,
    /// `lognormal`: mean of the value's natural logarithm.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mu: Option<f64>,
    /// `lognormal`: standard deviation of the value's natural logarithm (> 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sigma: Option<f64>,
    /// Truncation: no value below.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min: Option<f64>,
    /// Truncation: no value above.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max: Option<f64>,
}

#[derive(Debug, Clone, Copy, Deserialize, Serialize, ToSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum DistributionKind {
    Uniform,
    Normal,
    Lognormal,
}

/// How the samples are chosen.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, ToSchema, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum StudyDesign {
    /// Every combination of the parameters' `values` (the first parameter varies slowest).
    Grid,
    /// Independent random draws of each distribution.
    MonteCarlo,
    /// Latin hypercube: each parameter's probability range cut into `samples` equal strata,
    /// exactly one sample in each, paired at random.
    LatinHypercube,
}

/// State of a study.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, ToSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum StudyStatus {
    /// No sample has started.
    Queued,
    Running,
    /// Every sample has finished (succeeded or failed).
    Finished,
    Cancelled,
}

/// Samples by state.
#[derive(Debug, Clone, Default, Deserialize, Serialize, ToSchema, PartialEq, Eq)]
pub struct StudyCounts {
    pub queued: u64,
    pub running: u64,
    /// Succeeded.
    pub done: u64,
    pub failed: u64,
    pub cancelled: u64,
}

/// A study's status and progress.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct StudyInfo {
    pub id: String,
    pub analysis: String,
    pub design: StudyDesign,
    pub status: StudyStatus,
    /// Samples finished (done or failed) over samples.
    pub progress: f64,
    pub samples: u64,
    pub counts: StudyCounts,
    pub created_at: String,
    /// Why the study was cancelled.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<Problem>,
}

/// One sample of a study's result.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct StudySample {
    /// Its index, from 0.
    pub sample: u64,
    pub status: JobStatus,
    /// The value of each parameter, in the order of `parameters`.
    pub parameters: Vec<Value>,
    /// The value at each output pointer, in the order of `outputs`; null where the pointer
    /// finds nothing or the sample did not succeed.
    pub outputs: Vec<Value>,
    /// The replica that computed it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub server: Option<String>,
    /// Why it failed or was cancelled.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<Problem>,
}

/// Statistics of one output over the samples; `null` where there are too few numbers.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema, PartialEq)]
pub struct OutputSummary {
    pub output: String,
    /// Samples whose output is a number.
    pub count: u64,
    /// Fraction of the samples whose output is not a number (null: e.g. no threshold in
    /// range, a failed sample, a pointer that finds nothing).
    pub null_fraction: f64,
    pub mean: Option<f64>,
    /// Sample standard deviation (n - 1).
    pub std: Option<f64>,
    pub min: Option<f64>,
    pub max: Option<f64>,
    /// Percentiles 5, 50 and 95 (linear between order statistics).
    pub p5: Option<f64>,
    pub p50: Option<f64>,
    pub p95: Option<f64>,
}

/// Spearman's rank correlation of an output with a parameter, over the samples where both are
/// numbers; `null` where either is constant or fewer than 3 pairs.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema, PartialEq)]
pub struct Sensitivity {
    pub parameter: String,
    pub output: String,
    pub spearman: Option<f64>,
    pub count: u64,
}

/// Every sample of a study with its outputs, their statistics and sensitivities.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct StudyResult {
    pub id: String,
    pub analysis: String,
    pub design: StudyDesign,
    pub status: StudyStatus,
    /// The seed the samples were drawn with (random designs).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub seed: Option<u64>,
    /// The parameters' pointers, the order of each sample's `parameters`.
    pub parameters: Vec<String>,
    /// The outputs' pointers, the order of each sample's `outputs`.
    pub outputs: Vec<String>,
    pub samples: Vec<StudySample>,
    pub summary: Vec<OutputSummary>,
    pub sensitivity: Vec<Sensitivity>,
}
