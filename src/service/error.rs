//! One error type for every handler, answered as `application/problem+json` (RFC 9457).

use axum::http::{HeaderValue, StatusCode, header};
use axum::response::{IntoResponse, Response};

use crate::analysis::AnalysisError;
use crate::model::Invalid;
use crate::model::api::{Problem, ProblemField};

#[derive(Debug)]
pub enum ApiError {
    /// 400: the body is not JSON.
    Malformed(String),
    /// 422: the JSON does not describe a valid model (every bad field with its path).
    Invalid(Invalid),
    /// 422: a valid request the analysis cannot carry out on this model.
    Unsolvable(String),
    /// 413: the body is larger than the configured limit.
    TooLarge(usize),
    /// 503 with `Retry-After`: the queue in front of the workers is full.
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
}

impl From<Invalid> for ApiError {
    fn from(e: Invalid) -> Self {
        ApiError::Invalid(e)
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

/// Seconds a client is asked to wait when the queue is full.
pub const RETRY_AFTER_SECONDS: u32 = 5;

impl ApiError {
    pub fn status(&self) -> StatusCode {
        match self {
            ApiError::Malformed(_) => StatusCode::BAD_REQUEST,
            ApiError::Invalid(_) | ApiError::Unsolvable(_) => StatusCode::UNPROCESSABLE_ENTITY,
            ApiError::TooLarge(_) => StatusCode::PAYLOAD_TOO_LARGE,
            ApiError::Busy => StatusCode::SERVICE_UNAVAILABLE,
            ApiError::NotFound(_) => StatusCode::NOT_FOUND,
            ApiError::NotAcceptable(_) => StatusCode::NOT_ACCEPTABLE,
            ApiError::Internal(_) => StatusCode::INTERNAL_SERVER_ERROR,
            ApiError::Cancelled | ApiError::Stopped(_) | ApiError::Conflict(_) => {
                StatusCode::CONFLICT
            }
        }
    }

    pub fn problem(&self) -> Problem {
        let (kind, title, detail, errors) = match self {
            ApiError::Malformed(d) => ("malformed-json", "Malformed JSON", d.clone(), vec![]),
            ApiError::Invalid(inv) => (
                "invalid-model",
                "Invalid model",
                format!("{} invalid field(s): {inv}", inv.0.len()),
                inv.0
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
                    "all workers are busy and the queue is full; retry in {RETRY_AFTER_SECONDS} s"
                ),
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
        };
        Problem {
            kind: format!("/problems/{kind}"),
            title: title.into(),
            status: self.status().as_u16(),
            detail,
            errors,
        }
    }
}

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        if let ApiError::Internal(d) = &self {
            tracing::error!(detail = %d, "internal error");
        }
        let status = self.status();
        let body = serde_json::to_vec(&self.problem()).unwrap_or_default();
        let mut resp = (status, body).into_response();
        let h = resp.headers_mut();
        h.insert(
            header::CONTENT_TYPE,
            HeaderValue::from_static("application/problem+json"),
        );
        if matches!(self, ApiError::Busy) {
            h.insert(header::RETRY_AFTER, HeaderValue::from(RETRY_AFTER_SECONDS));
        }
        resp
    }
}
