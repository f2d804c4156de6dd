//! Handlers of the audit analyses (API 684 / API 617): like every analysis, each reads its
//! body, parses it into a task, runs it and answers.

use axum::extract::State;
use axum::http::HeaderMap;
use axum::response::Response;

use super::AppState;
use super::error::ApiError;
use super::json::ApiJson;
use super::routes::AnalysisErrors;
use super::task::{negotiate, respond};
use crate::model::api::{
    CriticalSpeedMapRequest, CriticalSpeedMapResponse, FrequencyResponseRequest,
    FrequencyResponseResponse, Level1Request, Level1Response, Problem, ReportRequest,
    ReportResponse, StaticRequest, StaticResponse,
};

/// Undamped critical speed map.
///
/// Every support replaced by an isotropic undamped spring of each stiffness (log-spaced): the
/// lowest undamped natural frequencies at zero speed, one per degenerate x/y pair (ROSS's
/// `run_ucs`), and where each mode meets the actual supports' stiffness (`kxx`, and `kyy` when
/// it differs; for coefficients tabulated against speed, the speed where the mode's frequency
/// equals the speed). Beam rotors.
#[utoipa::path(post, path = "/v1/critical-speed-map", tag = "audit", request_body = CriticalSpeedMapRequest,
    responses(
        (status = 200, description = "Frequencies per mode and stiffness (JSON; the table or the log-log map by Accept)",
         content((CriticalSpeedMapResponse = "application/json"), (String = "text/csv"), (String = "image/svg+xml"), (String = "image/png"))),
        (status = 406, description = "No acceptable format", body = Problem, content_type = "application/problem+json"),
        AnalysisErrors))]
pub async fn critical_speed_map(
    State(st): State<AppState>,
    headers: HeaderMap,
    ApiJson(req): ApiJson<CriticalSpeedMapRequest>,
) -> Result<Response, ApiError> {
    let format = negotiate(&headers)?;
    let task = req.parse(&st.config.limits())?;
    respond(&st, task, format).await
}

/// Static deflection under gravity and the bearing loads.
///
/// Gravity along -y on the consistent mass of shaft and disks: deflection of every node,
/// reaction of every support (the upward force on the shaft, N), shear force and bending
/// moment at both ends of every element. `supports: "rigid"` pins the shaft at the support
/// nodes, as ROSS's `run_static`; `elastic` (default) uses their stiffness. Beam rotors.
#[utoipa::path(post, path = "/v1/static", tag = "audit", request_body = StaticRequest,
    responses(
        (status = 200, description = "Deflections, reactions, shear and moment (JSON; the table or the plot by Accept)",
         content((StaticResponse = "application/json"), (String = "text/csv"), (String = "image/svg+xml"), (String = "image/png"))),
        (status = 406, description = "No acceptable format", body = Problem, content_type = "application/problem+json"),
        AnalysisErrors))]
pub async fn static_deflection(
    State(st): State<AppState>,
    headers: HeaderMap,
    ApiJson(req): ApiJson<StaticRequest>,
) -> Result<Response, ApiError> {
    let format = negotiate(&headers)?;
    let task = req.parse(&st.config.limits())?;
    respond(&st, task, format).await
}

/// Level I stability screen (API 617).
///
/// Skew cross-coupled stiffness `kxy = q`, `kyx = -q` (destabilising forward whirl) at the
/// node(s): the log decrement and frequency of the first forward mode against `q` at `speed`,
/// and `q0`, the cross-coupling at zero log decrement, by root finding. With `machine`, the
/// anticipated cross-coupling `q_A` of API 617, the log decrement there and the verdict. Under
/// every damping model: the hysteretic and equivalent margins differ.
#[utoipa::path(post, path = "/v1/level1", tag = "audit", request_body = Level1Request,
    responses(
        (status = 200, description = "Log decrement against cross-coupling, and q0 (JSON; the table or the plot by Accept)",
         content((Level1Response = "application/json"), (String = "text/csv"), (String = "image/svg+xml"), (String = "image/png"))),
        (status = 406, description = "No acceptable format", body = Problem, content_type = "application/problem+json"),
        AnalysisErrors))]
pub async fn level1(
    State(st): State<AppState>,
    headers: HeaderMap,
    ApiJson(req): ApiJson<Level1Request>,
) -> Result<Response, ApiError> {
    let format = negotiate(&headers)?;
    let task = req.parse(&st.config.limits())?;
    respond(&st, task, format).await
}

/// Non-synchronous frequency response at a fixed spin speed.
///
/// The response at `output.node` per unit harmonic force at `input.node`, along `direction`
/// (rad from x) or whirling `forward`/`backward`, against the excitation frequency: amplitude
/// and phase (m/N, rad), x and y parts, and the forward and backward circular parts. The
/// hysteretic model is exact here (frequency domain).
#[utoipa::path(post, path = "/v1/frequency-response", tag = "audit", request_body = FrequencyResponseRequest,
    responses(
        (status = 200, description = "Transfer function (JSON; the table or the Bode plot by Accept)",
         content((FrequencyResponseResponse = "application/json"), (String = "text/csv"), (String = "image/svg+xml"), (String = "image/png"))),
        (status = 406, description = "No acceptable format", body = Problem, content_type = "application/problem+json"),
        AnalysisErrors))]
pub async fn frequency_response(
    State(st): State<AppState>,
    headers: HeaderMap,
    ApiJson(req): ApiJson<FrequencyResponseRequest>,
) -> Result<Response, ApiError> {
    let format = negotiate(&headers)?;
    let task = req.parse(&st.config.limits())?;
    respond(&st, task, format).await
}

/// The whole audit in one answer.
///
/// Critical speed map, static bearing loads, Campbell diagram, unbalance response with
/// amplification factors and separation margins (API 684), the Level I screen (API 617), and
/// the same margins under the hysteretic, equivalent, nonviscous and viscous models side by
/// side, with a verdict per check. `Accept: text/html` gives a self-contained page with every
/// plot inline.
#[utoipa::path(post, path = "/v1/report", tag = "audit", request_body = ReportRequest,
    responses(
        (status = 200, description = "The audit (JSON, or the page by Accept: text/html)",
         content((ReportResponse = "application/json"), (String = "text/html"))),
        (status = 406, description = "No acceptable format", body = Problem, content_type = "application/problem+json"),
        AnalysisErrors))]
pub async fn report(
    State(st): State<AppState>,
    headers: HeaderMap,
    ApiJson(req): ApiJson<ReportRequest>,
) -> Result<Response, ApiError> {
    let format = negotiate(&headers)?;
    let task = req.parse(&st.config.limits())?;
    respond(&st, task, format).await
}
