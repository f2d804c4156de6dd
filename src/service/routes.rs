//! Handlers: each reads its body, parses it into a task (`model::task`, where every check and
//! size lives), runs or submits it, and answers.

use axum::Json;
use axum::extract::State;
use axum::http::{HeaderMap, HeaderValue, StatusCode, Uri, header};
use axum::response::{IntoResponse, Response};

use super::AppState;
use super::error::ApiError;
use super::guard::JobId;
use super::json::ApiJson;
use super::problems::Base;
use super::task::{negotiate, respond};
use super::{results, routes_jobs};
use crate::jobs;
use crate::model::api::{
    CampbellResponse, DampingMatricesRequest, DampingMatricesResponse, JobInfo, JobRequest,
    ModalRequest, ModalResponse, Problem, StabilityResponse, Status, SweepRequest,
    TimeResponseRequest, TimeResponseResponse, UnbalanceResponseRequest, UnbalanceResponseResponse,
};

/// The errors every analysis endpoint may answer, as problem+json.
#[derive(utoipa::IntoResponses)]
#[allow(dead_code)] // only read by the OpenAPI derive
pub(super) enum AnalysisErrors {
    #[response(
        status = 400,
        description = "Malformed JSON",
        content_type = "application/problem+json"
    )]
    Malformed(Problem),
    #[response(
        status = 408,
        description = "The body did not arrive in time",
        content_type = "application/problem+json"
    )]
    Timeout(Problem),
    #[response(
        status = 413,
        description = "Body too large",
        content_type = "application/problem+json"
    )]
    TooLarge(Problem),
    #[response(
        status = 415,
        description = "The body is not declared as JSON (Content-Type)",
        content_type = "application/problem+json"
    )]
    NotJson(Problem),
    #[response(
        status = 422,
        description = "Invalid model",
        content_type = "application/problem+json"
    )]
    Invalid(Problem),
    #[response(
        status = 503,
        description = "Queue full, or the analysis ran past WHIRL_REQUEST_TIME_LIMIT (submit a job); see Retry-After",
        content_type = "application/problem+json",
        headers(("Retry-After" = u32, description = "Seconds to wait"))
    )]
    Busy(Problem),
}

/// Liveness: 200 while the process lives.
#[utoipa::path(get, path = "/healthz", tag = "operations",
    responses((status = 200, description = "Alive", body = Status)))]
pub async fn healthz() -> Json<Status> {
    Json(Status {
        status: "ok".into(),
    })
}

/// Readiness: 200 while the job store answers and there is room for work; 503 when the store
/// is unreachable, or the worker pool's or the shared job queue is full.
#[utoipa::path(get, path = "/readyz", tag = "operations",
    responses(
        (status = 200, description = "Accepting work", body = Status),
        (status = 503, description = "Store unreachable, or queue full", body = Status)))]
pub async fn readyz(State(st): State<AppState>) -> (StatusCode, Json<Status>) {
    let answer = |code, status: &str| {
        (
            code,
            Json(Status {
                status: status.into(),
            }),
        )
    };
    match tokio::time::timeout(STORE_CHECK, st.jobs.queued()).await {
        Ok(Ok(queued)) if st.pool.ready() && !st.jobs.full(queued) => {
            answer(StatusCode::OK, "ready")
        }
        Ok(Ok(_)) => answer(StatusCode::SERVICE_UNAVAILABLE, "busy"),
        Ok(Err(_)) | Err(_) => answer(StatusCode::SERVICE_UNAVAILABLE, "store unreachable"),
    }
}

/// Longest `/readyz` and `/metrics` wait for the job store.
const STORE_CHECK: std::time::Duration = std::time::Duration::from_secs(2);

/// Poles at one spin speed.
///
/// All poles of the rotor under the chosen damping model at `speed`: rotor poles labelled
/// `forward` or `backward`, and for the nonviscous model the overdamped `internal` poles of its
/// branches. Also the undamped nonrotating natural frequencies.
#[utoipa::path(post, path = "/v1/modal", tag = "analyses", request_body = ModalRequest,
    responses(
        (status = 200, description = "Poles (JSON; the table or the plot by Accept)",
         content((ModalResponse = "application/json"), (String = "text/csv"), (String = "image/svg+xml"), (String = "image/png"))),
        (status = 406, description = "No acceptable format", body = Problem, content_type = "application/problem+json"),
        AnalysisErrors))]
pub async fn modal(
    State(st): State<AppState>,
    headers: HeaderMap,
    ApiJson(req): ApiJson<ModalRequest>,
) -> Result<Response, ApiError> {
    let format = negotiate(&headers)?;
    let task = req.parse(&st.config.limits())?;
    respond(&st, task, format).await
}

/// Campbell diagram and decay-rate plot.
///
/// Every rotor branch over the sweep, tracked by mode shape (not by sorting frequencies), with
/// the forward critical speeds and the threshold of instability in the range. Internal poles
/// of the nonviscous model are kept out of the branches. A value the model does not define
/// (hysteretic model near a critical speed) is null. With `max_frequency`, the sweep runs on a
/// modal reduction where that at least halves the state and reproduces the full model's poles
/// below the bound to 1e-6 at the fastest speed; `reduction` says so.
#[utoipa::path(post, path = "/v1/campbell", tag = "analyses", request_body = SweepRequest,
    responses(
        (status = 200, description = "Branches (JSON; the table or the plot by Accept)",
         content((CampbellResponse = "application/json"), (String = "text/csv"), (String = "image/svg+xml"), (String = "image/png"))),
        (status = 406, description = "No acceptable format", body = Problem, content_type = "application/problem+json"),
        AnalysisErrors))]
pub async fn campbell(
    State(st): State<AppState>,
    headers: HeaderMap,
    ApiJson(req): ApiJson<SweepRequest>,
) -> Result<Response, ApiError> {
    let format = negotiate(&headers)?;
    let task = req.parse_campbell(&st.config.limits())?;
    respond(&st, task, format).await
}

/// Threshold of instability.
///
/// The lowest spin speed in `[start, stop]` at which any pole has `decay_rate > 0`. The speeds
/// are the grid that brackets the crossing; the threshold is then refined by root finding to
/// 1e-6 relative (or better). `threshold` is null when the rotor is stable over the range,
/// and equals the range's start when it is already unstable there.
#[utoipa::path(post, path = "/v1/stability", tag = "analyses", request_body = SweepRequest,
    responses(
        (status = 200, description = "Threshold (JSON; the table or the plot by Accept)",
         content((StabilityResponse = "application/json"), (String = "text/csv"), (String = "image/svg+xml"), (String = "image/png"))),
        (status = 406, description = "No acceptable format", body = Problem, content_type = "application/problem+json"),
        AnalysisErrors))]
pub async fn stability(
    State(st): State<AppState>,
    headers: HeaderMap,
    ApiJson(req): ApiJson<SweepRequest>,
) -> Result<Response, ApiError> {
    let format = negotiate(&headers)?;
    let task = req.parse_stability(&st.config.limits())?;
    respond(&st, task, format).await
}

/// Equivalent or nonviscous damping as matrices, for integration elsewhere.
///
/// The equivalent model's `C_eq` (rotating and nonrotating apart), or the nonviscous model's
/// augmented matrices with the internal coordinates labelled (mode, branch, rotating,
/// relaxation rate), in second-order or state form. For every nonviscous damper, the quality
/// of its fit: the loss factor of the branches against frequency over a band, its largest and
/// RMS deviation from the target, the change of storage stiffness, and the added states. With
/// `fit.max_deviation`, the number of branches is chosen to meet it.
#[utoipa::path(post, path = "/v1/damping", tag = "analyses", request_body = DampingMatricesRequest,
    responses(
        (status = 200, description = "Matrices and fit report", body = DampingMatricesResponse),
        AnalysisErrors))]
pub async fn damping_matrices(
    State(st): State<AppState>,
    headers: HeaderMap,
    ApiJson(req): ApiJson<DampingMatricesRequest>,
) -> Result<Response, ApiError> {
    let format = negotiate(&headers)?;
    let task = req.parse(&st.config.limits())?;
    respond(&st, task, format).await
}

/// Time response: shocks, run-ups through critical speeds, blade loss.
///
/// Nonrotating forces with piecewise-linear histories and unbalances rotating with the shaft
/// (appearing at `from`: blade loss), at a constant speed or along a piecewise-linear speed
/// profile (the unbalance force includes the angular-acceleration term). From rest. At constant
/// speed the response is exact (modal superposition); with a varying speed it is integrated
/// by TR-BDF2 (L-stable, error-controlled). The hysteretic model is refused: it is defined for
/// harmonic motion only; `nonviscous` is its time-domain model.
#[utoipa::path(post, path = "/v1/time-response", tag = "analyses", request_body = TimeResponseRequest,
    responses(
        (status = 200, description = "Displacements of the nodes (JSON; the table or the plot by Accept)",
         content((TimeResponseResponse = "application/json"), (String = "text/csv"), (String = "image/svg+xml"), (String = "image/png"))),
        (status = 406, description = "No acceptable format", body = Problem, content_type = "application/problem+json"),
        AnalysisErrors))]
pub async fn time_response(
    State(st): State<AppState>,
    headers: HeaderMap,
    ApiJson(req): ApiJson<TimeResponseRequest>,
) -> Result<Response, ApiError> {
    let format = negotiate(&headers)?;
    let task = req.parse(&st.config.limits())?;
    respond(&st, task, format).await
}

/// Steady synchronous response to unbalance against speed.
///
/// Amplitude (radius of the circular forward orbit) and phase of every requested node at each
/// speed, for all four models. In synchronous whirl the rotor material sees zero frequency:
/// rotating viscous, equivalent and nonviscous damping do no work there, and the hysteretic
/// model (undefined at zero frequency) is evaluated with `sgn 0 = 0`, the same limit; the
/// answer's `note` says so.
#[utoipa::path(post, path = "/v1/unbalance-response", tag = "analyses", request_body = UnbalanceResponseRequest,
    responses(
        (status = 200, description = "Amplitude and phase per node and speed (JSON; the table or the plot by Accept)",
         content((UnbalanceResponseResponse = "application/json"), (String = "text/csv"), (String = "image/svg+xml"), (String = "image/png"))),
        (status = 406, description = "No acceptable format", body = Problem, content_type = "application/problem+json"),
        AnalysisErrors))]
pub async fn unbalance_response(
    State(st): State<AppState>,
    headers: HeaderMap,
    ApiJson(req): ApiJson<UnbalanceResponseRequest>,
) -> Result<Response, ApiError> {
    let format = negotiate(&headers)?;
    let task = req.parse(&st.config.limits())?;
    respond(&st, task, format).await
}

/// Submit an analysis to run later.
///
/// `{"analysis": "campbell", "input": {...}}`: the input is what `POST /v1/<analysis>` takes,
/// validated now (422 at once). 202 with `Location: /v1/jobs/{id}` when admitted; 503 with
/// `Retry-After` when the queue is full. An accepted job always runs. With an
/// `Idempotency-Key`, sending the same request again (a retry after a lost answer) answers
/// with the job that key already names (`Idempotent-Replayed: true`) instead of a new job, as
/// long as that job is kept; the same key with another request is a 422.
#[utoipa::path(post, path = "/v1/jobs", tag = "jobs", request_body = JobRequest,
    params(("Idempotency-Key" = Option<String>, Header,
        description = "A key of the client's choosing (1 to 255 visible ASCII characters, e.g. a UUID) naming this submission")),
    responses(
        (status = 202, description = "Accepted; poll Location", body = JobInfo,
         headers(("Location" = String, description = "URL of the job"),
                 ("Idempotent-Replayed" = String, description = "`true` when the Idempotency-Key named this job already"))),
        (status = 400, description = "Malformed JSON", body = Problem, content_type = "application/problem+json"),
        (status = 408, description = "The body did not arrive in time", body = Problem, content_type = "application/problem+json"),
        (status = 413, description = "Body too large", body = Problem, content_type = "application/problem+json"),
        (status = 415, description = "The body is not declared as JSON", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "Invalid input, or an Idempotency-Key used with another request", body = Problem, content_type = "application/problem+json"),
        (status = 503, description = "Queue full, or the job store unreachable; see Retry-After", body = Problem, content_type = "application/problem+json")))]
pub async fn submit_job(
    State(st): State<AppState>,
    headers: HeaderMap,
    base: Base,
    ApiJson(req): ApiJson<JobRequest>,
) -> Result<Response, ApiError> {
    let key = routes_jobs::idempotency_key(&headers)?;
    let input = jobs::job_input(req.analysis, req.input.clone()).map_err(in_input)?;
    let task = input
        .parse(&st.config.limits())
        .map_err(|e| in_input(e.into()))?;
    let sha = key.as_ref().map(|_| routes_jobs::request_sha256(&req));
    let keyed = key.as_deref().zip(sha.as_deref());
    let (info, replayed) = st
        .jobs
        .submit(&st.pool, &req.input, &task, keyed)
        .await
        .map_err(in_input)?;
    let location = format!("/v1/jobs/{}", info.id);
    let mut resp = (StatusCode::ACCEPTED, Json(base.job(info))).into_response();
    if let Ok(v) = HeaderValue::from_str(&location) {
        resp.headers_mut().insert(header::LOCATION, v);
    }
    if replayed {
        resp.headers_mut()
            .insert("idempotent-replayed", HeaderValue::from_static("true"));
    }
    Ok(resp)
}

/// Paths of a job's input are under `input`.
fn in_input(e: ApiError) -> ApiError {
    match e {
        ApiError::Invalid(mut inv) => {
            inv.prefix_paths(|p| {
                if p == "(body)" {
                    "input".into()
                } else {
                    format!("input.{p}")
                }
            });
            ApiError::Invalid(inv)
        }
        other => other,
    }
}

/// A job's status and progress.
#[utoipa::path(get, path = "/v1/jobs/{id}", tag = "jobs",
    params(("id" = String, Path, description = "Job id")),
    responses(
        (status = 200, description = "Status", body = JobInfo),
        (status = 404, description = "Unknown or forgotten job", body = Problem, content_type = "application/problem+json"),
        (status = 503, description = "The job store is unreachable; see Retry-After", body = Problem, content_type = "application/problem+json")))]
pub async fn get_job(
    State(st): State<AppState>,
    base: Base,
    JobId(id): JobId,
) -> Result<Json<JobInfo>, ApiError> {
    st.jobs.get(&id).await.map(|j| Json(base.job(j)))
}

/// A succeeded job's result: the body its synchronous endpoint returns (JSON, CSV or SVG by
/// `Accept`); 409 before it has succeeded. A result never changes: it carries an `ETag` and
/// `Cache-Control: immutable`, and `If-None-Match` with that tag answers 304 without a body.
#[utoipa::path(get, path = "/v1/jobs/{id}/result", tag = "jobs",
    params(("id" = String, Path, description = "Job id"),
        ("If-None-Match" = Option<String>, Header, description = "ETags of copies the client holds")),
    responses(
        (status = 200, description = "The analysis result",
         content((Object = "application/json"), (String = "text/csv"), (String = "image/svg+xml"), (String = "image/png")),
         headers(("ETag" = String, description = "The result in this representation (weak: the same for every content coding)"),
                 ("Cache-Control" = String, description = "`private, max-age=31536000, immutable`"))),
        (status = 304, description = "Not modified: the copy whose ETag was sent is current",
         headers(("ETag" = String, description = "The result's tag"))),
        (status = 404, description = "Unknown or forgotten job", body = Problem, content_type = "application/problem+json"),
        (status = 406, description = "Format not available", body = Problem, content_type = "application/problem+json"),
        (status = 409, description = "Not succeeded (yet)", body = Problem, content_type = "application/problem+json"),
        (status = 503, description = "The job store is unreachable; see Retry-After", body = Problem, content_type = "application/problem+json")))]
pub async fn job_result(
    State(st): State<AppState>,
    headers: HeaderMap,
    JobId(id): JobId,
) -> Result<Response, ApiError> {
    let formats = negotiate(&headers)?;
    let row = st.jobs.result(&id).await?;
    let tag = results::etag(&row.id, &formats);
    if results::matches(&headers, &tag) {
        return Ok(results::not_modified(&tag));
    }
    let mut resp =
        results::respond(st.jobs.store.clone(), row, formats, accepts_gzip(&headers)).await?;
    results::immutable(&mut resp, &tag);
    Ok(resp)
}

/// Whether `Accept-Encoding` takes gzip (q > 0).
fn accepts_gzip(headers: &HeaderMap) -> bool {
    headers
        .get_all(header::ACCEPT_ENCODING)
        .iter()
        .filter_map(|v| v.to_str().ok())
        .flat_map(|v| v.split(','))
        .any(|item| {
            let mut parts = item.split(';');
            let coding = parts.next().unwrap_or("").trim().to_ascii_lowercase();
            let q = parts
                .filter_map(|p| p.trim().strip_prefix("q="))
                .find_map(|v| v.trim().parse::<f64>().ok())
                .unwrap_or(1.0);
            q > 0.0 && (coding == "gzip" || coding == "*")
        })
}

/// Cancel a job: recorded as `cancelled` at once (200), on whichever replica receives it; the
/// running analysis stops at its next check (between speeds, samples or steps) on the replica
/// running it, within a second, and frees its worker then. 409 if it has finished.
#[utoipa::path(delete, path = "/v1/jobs/{id}", tag = "jobs",
    params(("id" = String, Path, description = "Job id")),
    responses(
        (status = 200, description = "Cancelled", body = JobInfo),
        (status = 404, description = "Unknown or forgotten job", body = Problem, content_type = "application/problem+json"),
        (status = 409, description = "Already finished", body = Problem, content_type = "application/problem+json"),
        (status = 503, description = "The job store is unreachable; see Retry-After", body = Problem, content_type = "application/problem+json")))]
pub async fn cancel_job(
    State(st): State<AppState>,
    base: Base,
    JobId(id): JobId,
) -> Result<Json<JobInfo>, ApiError> {
    st.jobs
        .cancel(&id, "cancelled by the client")
        .await
        .map(|j| Json(base.job(j)))
}

/// Prometheus metrics.
#[utoipa::path(get, path = "/metrics", tag = "operations",
    responses((status = 200, description = "Prometheus text format", body = String, content_type = "text/plain")))]
pub async fn metrics(State(st): State<AppState>) -> Response {
    let stats = match tokio::time::timeout(STORE_CHECK, st.jobs.stats()).await {
        Ok(r) => r,
        Err(_) => Err(jobs::store::StoreError("no answer".into())),
    };
    let mut resp = super::metrics::render(&st, stats.ok()).into_response();
    resp.headers_mut().insert(
        header::CONTENT_TYPE,
        HeaderValue::from_static("text/plain; version=0.0.4; charset=utf-8"),
    );
    resp
}

/// 404 for any other path.
pub async fn not_found(uri: Uri) -> ApiError {
    ApiError::NotFound(format!("no such endpoint: {}", uri.path()))
}
