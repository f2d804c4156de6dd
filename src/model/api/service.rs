//! What the service itself answers: health, problems (errors) and jobs.

use serde::{Deserialize, Serialize};
use serde_json::Value;
use utoipa::ToSchema;

/// `GET /healthz`, `GET /readyz`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct Status {
    pub status: String,
}

/// An RFC 9457 problem: `application/problem+json`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct Problem {
    /// A URI reference naming the kind of problem.
    #[serde(rename = "type")]
    pub kind: String,
    pub title: String,
    pub status: u16,
    pub detail: String,
    /// Every bad field, with its JSON path (422).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub errors: Vec<ProblemField>,
}

/// One bad field of a request.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct ProblemField {
    /// JSON path of the field, e.g. `rotor.mass`.
    pub path: String,
    pub message: String,
}

/// An analysis a job can run: the synchronous endpoint of the same name.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, ToSchema, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum AnalysisName {
    Modal,
    Campbell,
    Stability,
    Damping,
    TimeResponse,
    UnbalanceResponse,
    CriticalSpeedMap,
    Static,
    Level1,
    FrequencyResponse,
    Report,
}

/// Body of `POST /v1/jobs`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct JobRequest {
    pub analysis: AnalysisName,
    /// The body the synchronous endpoint `POST /v1/<analysis>` takes.
    #[schema(value_type = Object)]
    pub input: Value,
}

/// State of a job.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, ToSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum JobStatus {
    Queued,
    Running,
    Succeeded,
    Failed,
    Cancelled,
}

/// A page of jobs, newest first (`GET /v1/jobs`).
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct JobList {
    pub jobs: Vec<JobInfo>,
    /// The next page's URL (older jobs), also in `Link: <...>; rel="next"`; absent on the
    /// last page.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub next: Option<String>,
}

/// A job's status.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
pub struct JobInfo {
    pub id: String,
    pub analysis: String,
    pub status: JobStatus,
    /// Fraction of the work done, 0 to 1 (speeds swept, samples computed).
    pub progress: f64,
    pub created_at: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub started_at: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub finished_at: Option<String>,
    /// Why the job failed or was cancelled.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<Problem>,
}
