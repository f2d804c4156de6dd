//! Why a request has no answer: one error type for every layer that answers (reading and
//! validating the request, the analysis, the worker pool, the job store, rendering), with its
//! status code and its problem (RFC 9457). A failed job keeps the problem; `service::error`
//! sends it as `application/problem+json`.

use crate::analysis::AnalysisError;
use crate::analysis::run::RunError;
use crate::model::Invalid;
use crate::model::api::{Problem, ProblemField};
use crate::model::json::JsonError;

#[derive(Debug)]
pub enum ApiError {
    /// 400: the body is not JSON.
    Malformed(String),
    /// 400: the body is not TOML (`POST /v1/convert/ross`).
    MalformedToml(String),
    /// 422: the JSON does not describe a valid model (every bad field with its path).
    Invalid(Invalid),
    /// 422: a valid request the analysis cannot carry out on this model.
    Unsolvable(String),
    /// 413: the body is larger than the configured limit.
    TooLarge(usize),
    /// 503 with `Retry-After`: the queue in front of the workers is full, or the memory
    /// budget cannot hold a synchronous answer now.
    Busy,
    /// 404.
    NotFound(String),
    /// 406: no acceptable representation.
    NotAcceptable(String),
    /// 500: a bug; the server keeps serving.
    Internal(String),
    /// The analysis was stopped (a job's cancel, time limit or shutdown): the job records why.
    Cancelled,
    /// Why a job was stopped.
    Stopped(String),
    /// 409: the resource is not in a state for this request.
    Conflict(String),
    /// 415: the body is not declared as JSON.
    UnsupportedMediaType(String),
    /// 405, with the methods the path allows.
    MethodNotAllowed(String),
    /// 408: the body did not arrive in time.
    RequestTimeout(std::time::Duration),
    /// 503: a synchronous analysis ran past its time limit (it was stopped).
    TimeLimit(std::time::Duration),
    /// 503 with `Retry-After`: the job store cannot be reached.
    Unavailable(String),
    /// 422: an `Idempotency-Key` already names a job submitted with another request.
    KeyReused(String),
}

impl From<Invalid> for ApiError {
    fn from(e: Invalid) -> Self {
        ApiError::Invalid(e)
    }
}

impl From<JsonError> for ApiError {
    fn from(e: JsonError) -> Self {
        match e {
            JsonError::Malformed(d) => ApiError::Malformed(d),
            JsonError::Invalid(i) => ApiError::Invalid(i),
        }
    }
}

impl From<AnalysisError> for ApiError {
    fn from(e: AnalysisError) -> Self {
        match e {
            AnalysisError::Cancelled => ApiError::Cancelled,
            e => ApiError::Unsolvable(e.to_string()),
        }
    }
}

impl From<RunError> for ApiError {
    fn from(e: RunError) -> Self {
        match e {
            RunError::Invalid(i) => ApiError::Invalid(i),
            RunError::Unsolvable(d) => ApiError::Unsolvable(d),
            RunError::Cancelled => ApiError::Cancelled,
        }
    }
}

/// Seconds a client is asked to wait when the queue is full.
pub const RETRY_AFTER_SECONDS: u32 = 5;

impl ApiError {
    /// The HTTP status code of the problem.
    pub fn status(&self) -> u16 {
        match self {
            ApiError::Malformed(_) | ApiError::MalformedToml(_) => 400,
            ApiError::Invalid(_) | ApiError::Unsolvable(_) | ApiError::KeyReused(_) => 422,
            ApiError::TooLarge(_) => 413,
            ApiError::Busy | ApiError::TimeLimit(_) | ApiError::Unavailable(_) => 503,
            ApiError::UnsupportedMediaType(_) => 415,
            ApiError::MethodNotAllowed(_) => 405,
            ApiError::RequestTimeout(_) => 408,
            ApiError::NotFound(_) => 404,
            ApiError::NotAcceptable(_) => 406,
            ApiError::Internal(_) => 500,
            ApiError::Cancelled | ApiError::Stopped(_) | ApiError::Conflict(_) => 409,
        }
    }

    pub fn problem(&self) -> Problem {
        let (kind, title, detail, errors) = match self {
            ApiError::Malformed(d) => ("malformed-json", "Malformed JSON", d.clone(), vec![]),
            ApiError::MalformedToml(d) => ("malformed-toml", "Malformed TOML", d.clone(), vec![]),
            ApiError::Invalid(inv) => (
                "invalid-model",
                "Invalid model",
                format!(
                    "{} invalid field(s){}: {inv}",
                    inv.count(),
                    if inv.omitted() > 0 {
                        format!(" (the first {} are listed)", inv.errors().len())
                    } else {
                        String::new()
                    }
                ),
                inv.errors()
                    .iter()
                    .map(|e| ProblemField {
                        path: e.path.clone(),
                        message: e.message.clone(),
                    })
                    .collect(),
            ),
            ApiError::Unsolvable(d) => (
                "unsolvable-model",
                "Model cannot be analysed",
                d.clone(),
                vec![],
            ),
            ApiError::TooLarge(limit) => (
                "payload-too-large",
                "Request body too large",
                format!("the body exceeds the limit of {limit} bytes (WHIRL_MAX_BODY_BYTES)"),
                vec![],
            ),
            ApiError::Busy => (
                "busy",
                "Service busy",
                format!(
                    "all workers are busy and the queue is full, or the memory budget \
                     (WHIRL_MEMORY_BUDGET) cannot hold this answer beside the analyses running \
                     and the answers being sent; retry in {RETRY_AFTER_SECONDS} s"
                ),
                vec![],
            ),
            ApiError::Unavailable(d) => (
                "store-unavailable",
                "Job store unavailable",
                format!("{d}; retry in {RETRY_AFTER_SECONDS} s"),
                vec![],
            ),
            ApiError::NotFound(d) => ("not-found", "Not found", d.clone(), vec![]),
            ApiError::NotAcceptable(d) => ("not-acceptable", "Not acceptable", d.clone(), vec![]),
            ApiError::Internal(d) => ("internal", "Internal error", d.clone(), vec![]),
            ApiError::Cancelled => (
                "cancelled",
                "Cancelled",
                "the analysis was cancelled".into(),
                vec![],
            ),
            ApiError::Stopped(d) => ("stopped", "Job stopped", d.clone(), vec![]),
            ApiError::Conflict(d) => ("conflict", "Conflict", d.clone(), vec![]),
            ApiError::KeyReused(d) => (
                "idempotency-key-reused",
                "Idempotency key reused",
                d.clone(),
                vec![],
            ),
            ApiError::UnsupportedMediaType(d) => (
                "unsupported-media-type",
                "Unsupported media type",
                d.clone(),
                vec![],
            ),
            ApiError::MethodNotAllowed(allow) => (
                "method-not-allowed",
                "Method not allowed",
                format!("this path answers {allow}"),
                vec![],
            ),
            ApiError::RequestTimeout(t) => (
                "request-timeout",
                "Request timeout",
                format!(
                    "the body did not arrive within {} s (WHIRL_BODY_TIMEOUT)",
                    t.as_secs_f64()
                ),
                vec![],
            ),
            ApiError::TimeLimit(t) => (
                "time-limit",
                "Analysis time limit",
                format!(
                    "the analysis did not finish within {} s (WHIRL_REQUEST_TIME_LIMIT) and was \
                     stopped; submit it as a job (POST /v1/jobs), which may run longer and can \
                     be polled",
                    t.as_secs_f64()
                ),
                vec![],
            ),
        };
        Problem {
            kind: format!("/problems/{kind}"),
            title: title.into(),
            status: self.status(),
            detail,
            errors,
        }
    }
}
