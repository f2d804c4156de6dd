//! Studies over HTTP: `POST /v1/studies` checks the whole study (every pointer, every sample's
//! input, the limits) before queueing any sample; status, result (JSON, CSV, SVG or PNG plot)
//! and cancellation read the store, so any replica answers.

use axum::Json;
use axum::extract::{Query, State};
use axum::http::{HeaderMap, HeaderValue, StatusCode, header};
use axum::response::{IntoResponse, Response};

use super::AppState;
use super::error::ApiError;
use super::guard::is_job_id;
use super::json::ApiJson;
use super::problems::Base;
use super::task::negotiate;
use crate::jobs::studies::StudyLimits;
use crate::model::Invalid;
use crate::model::api::{Problem, StudyInfo, StudyRequest, StudyResult};
use crate::render::{Format, plot};
use crate::studies::{Study, table};

/// A study id from the path: the UUID `POST /v1/studies` answered, else 404 without a query.
pub struct StudyId(pub String);

impl<S: Send + Sync> axum::extract::FromRequestParts<S> for StudyId {
    type Rejection = ApiError;

    async fn from_request_parts(
        parts: &mut axum::http::request::Parts,
        state: &S,
    ) -> Result<Self, ApiError> {
        match axum::extract::Path::<String>::from_request_parts(parts, state).await {
            Ok(axum::extract::Path(id)) if is_job_id(&id) => Ok(StudyId(id)),
            _ => Err(ApiError::NotFound(
                "no such study: a study id is the UUID that POST /v1/studies answered".into(),
            )),
        }
    }
}

fn with_base(base: &Base, mut info: StudyInfo) -> StudyInfo {
    if let Some(p) = info.error.as_mut() {
        base.problem(p);
    }
    info
}

/// Run one analysis over many values of its parameters.
///
/// `parameters` are JSON pointers into `input` with a grid's `values` or a `distribution`;
/// `design` is `grid`, `monte-carlo` or `latin-hypercube` (seeded: the same `seed` draws the
/// same samples); `outputs` are JSON pointers into each sample's result. Every sample is
/// checked as a job would be before any is queued (a 422 names the field, or the sample and
/// its field); then each is a job in the shared queue, claimed by any replica after the
/// single jobs queued. 202 with `Location: /v1/studies/{id}`.
#[utoipa::path(post, path = "/v1/studies", tag = "studies", request_body = StudyRequest,
    responses(
        (status = 202, description = "Accepted; poll Location", body = StudyInfo,
         headers(("Location" = String, description = "URL of the study"))),
        (status = 400, description = "Malformed JSON", body = Problem, content_type = "application/problem+json"),
        (status = 413, description = "Body too large", body = Problem, content_type = "application/problem+json"),
        (status = 415, description = "The body is not declared as JSON", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "A bad pointer, design, distribution or sample input, or too many samples (`errors` names the field)", body = Problem, content_type = "application/problem+json"),
        (status = 503, description = "The server is stopping, the samples of all studies waiting would exceed WHIRL_STUDY_QUEUE, or the job store is unreachable; see Retry-After", body = Problem, content_type = "application/problem+json")))]
pub async fn submit_study(
    State(st): State<AppState>,
    base: Base,
    ApiJson(req): ApiJson<StudyRequest>,
) -> Result<Response, ApiError> {
    // A seed for a request without one: the random bits of a fresh UUIDv7.
    let seed = uuid::Uuid::now_v7().as_u64_pair().1 & ((1 << 53) - 1);
    let study = Study::parse(&req, st.config.max_study_samples, seed)?;
    let limits = StudyLimits {
        limits: st.config.limits(),
        result_bytes: st.config.job_result_bytes,
        queue: st.config.study_queue,
    };
    let info = st
        .jobs
        .submit_study(st.pool.clone(), &req, study, limits)
        .await?;
    let location = format!("/v1/studies/{}", info.id);
    let mut resp = (StatusCode::ACCEPTED, Json(with_base(&base, info))).into_response();
    if let Ok(v) = HeaderValue::from_str(&location) {
        resp.headers_mut().insert(header::LOCATION, v);
    }
    Ok(resp)
}

/// A study's status: samples queued, running, done and failed, and progress.
#[utoipa::path(get, path = "/v1/studies/{id}", tag = "studies",
    params(("id" = String, Path, description = "Study id")),
    responses(
        (status = 200, description = "Status", body = StudyInfo),
        (status = 404, description = "Unknown or forgotten study", body = Problem, content_type = "application/problem+json"),
        (status = 503, description = "The job store is unreachable; see Retry-After", body = Problem, content_type = "application/problem+json")))]
pub async fn get_study(
    State(st): State<AppState>,
    base: Base,
    StudyId(id): StudyId,
) -> Result<Json<StudyInfo>, ApiError> {
    Ok(Json(with_base(&base, st.jobs.study(&id).await?)))
}

/// Cancel a study: it and its queued and running samples are cancelled at once; a running
/// sample stops at its next check on whichever replica runs it. 409 once it has finished.
#[utoipa::path(delete, path = "/v1/studies/{id}", tag = "studies",
    params(("id" = String, Path, description = "Study id")),
    responses(
        (status = 200, description = "Cancelled", body = StudyInfo),
        (status = 404, description = "Unknown or forgotten study", body = Problem, content_type = "application/problem+json"),
        (status = 409, description = "Already finished", body = Problem, content_type = "application/problem+json"),
        (status = 503, description = "The job store is unreachable; see Retry-After", body = Problem, content_type = "application/problem+json")))]
pub async fn cancel_study(
    State(st): State<AppState>,
    base: Base,
    StudyId(id): StudyId,
) -> Result<Json<StudyInfo>, ApiError> {
    Ok(Json(with_base(&base, st.jobs.cancel_study(&id).await?)))
}

/// The plot's choice: which output, and against which parameter.
#[derive(Debug, Default, serde::Deserialize, utoipa::IntoParams)]
#[into_params(parameter_in = Query)]
#[serde(deny_unknown_fields)]
pub struct PlotQuery {
    /// The output plotted (one of the study's `outputs`; default the first).
    output: Option<String>,
    /// A parameter (one of the study's pointers): a scatter of the output against it instead
    /// of the output's histogram.
    against: Option<String>,
}

/// Index of `name` among `list`, or a 422 naming the query parameter.
fn index(list: &[String], name: Option<&str>, field: &str) -> Result<Option<usize>, ApiError> {
    let Some(name) = name else { return Ok(None) };
    list.iter()
        .position(|p| p == name)
        .map(Some)
        .ok_or_else(|| {
            ApiError::Invalid(Invalid::one(
                field,
                format!("{name:?} is not one of the study's {}", list.join(", ")),
            ))
        })
}

/// A finished (or cancelled) study's samples and their statistics.
///
/// JSON: every sample's `parameters`, `outputs` (null where the pointer finds nothing or the
/// sample failed, with its `error`) and `server`; a `summary` per output (mean, std, min, max,
/// percentiles 5/50/95, fraction of nulls) and Spearman's rank correlation of each output with
/// each parameter. `text/csv`: one row per sample. `image/svg+xml` or `image/png`: the
/// histogram of an output (`output`, default the first), or its scatter against a parameter
/// (`against`). 409 while samples are queued or running.
#[utoipa::path(get, path = "/v1/studies/{id}/result", tag = "studies",
    params(("id" = String, Path, description = "Study id"), PlotQuery),
    responses(
        (status = 200, description = "The study's result",
         content((StudyResult = "application/json"), (String = "text/csv"), (String = "image/svg+xml"), (String = "image/png"))),
        (status = 404, description = "Unknown or forgotten study", body = Problem, content_type = "application/problem+json"),
        (status = 406, description = "Format not available", body = Problem, content_type = "application/problem+json"),
        (status = 409, description = "Samples are still queued or running", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "`output` or `against` names no output or parameter of the study", body = Problem, content_type = "application/problem+json"),
        (status = 503, description = "The job store is unreachable; see Retry-After", body = Problem, content_type = "application/problem+json")))]
pub async fn study_result(
    State(st): State<AppState>,
    headers: HeaderMap,
    base: Base,
    StudyId(id): StudyId,
    query: Result<Query<PlotQuery>, axum::extract::rejection::QueryRejection>,
) -> Result<Response, ApiError> {
    let Query(q) = query.map_err(|e| Invalid::one("(query)", e.body_text()))?;
    let formats = negotiate(&headers)?;
    let format = formats
        .iter()
        .copied()
        .find(|f| matches!(f, Format::Json | Format::Csv | Format::Svg | Format::Png))
        .ok_or_else(|| {
            ApiError::NotAcceptable(
                "a study's result is application/json, text/csv, image/svg+xml or image/png".into(),
            )
        })?;
    let mut r = st.jobs.study_result(&id).await?;
    for s in &mut r.samples {
        if let Some(p) = s.error.as_mut() {
            base.problem(p);
        }
    }
    let (media, body) = match format {
        Format::Csv => (format.media(), table::csv(&r).into_bytes()),
        Format::Svg | Format::Png => {
            let k = index(&r.outputs, q.output.as_deref(), "output")?.unwrap_or(0);
            let j = index(&r.parameters, q.against.as_deref(), "against")?;
            let svg =
                plot::study(&r, k, j).map_err(|e| ApiError::Internal(format!("plot: {e}")))?;
            if format == Format::Svg {
                (format.media(), svg.into_bytes())
            } else {
                let png = crate::render::png::png(&svg)
                    .map_err(|e| ApiError::Internal(format!("PNG: {e}")))?;
                (format.media(), png)
            }
        }
        _ => {
            let body = serde_json::to_vec(&r).map_err(|e| ApiError::Internal(e.to_string()))?;
            ("application/json", body)
        }
    };
    let mut resp = (StatusCode::OK, body).into_response();
    resp.headers_mut()
        .insert(header::CONTENT_TYPE, HeaderValue::from_static(media));
    Ok(resp)
}
