//! Handlers: validate on the runtime, compute on the worker pool, convert to wire types.

use axum::Json;
use axum::extract::State;
use axum::http::{StatusCode, Uri};

use super::AppState;
use super::convert;
use super::error::ApiError;
use super::json::ApiJson;
use crate::analysis;
use crate::damping::{DampedModel, DampingError};
use crate::fem::modal::ModalError;
use crate::model::Invalid;
use crate::model::api::{
    CampbellResponse, DampingInput, ModalRequest, ModalResponse, Problem, RotorInput,
    StabilityResponse, Status, SweepRequest,
};
use crate::model::damping::DampingModel;
use crate::model::error::non_negative;
use crate::model::rotor::Rotor;
use crate::model::speeds::SpeedGrid;
use crate::system::RotorSystem;

/// Liveness: 200 while the process lives.
#[utoipa::path(get, path = "/healthz", tag = "operations",
    responses((status = 200, description = "Alive", body = Status)))]
pub async fn healthz() -> Json<Status> {
    Json(Status {
        status: "ok".into(),
    })
}

/// Readiness: 200 while the worker pool accepts work, 503 when its queue is full.
#[utoipa::path(get, path = "/readyz", tag = "operations",
    responses(
        (status = 200, description = "Accepting work", body = Status),
        (status = 503, description = "Queue full", body = Status)))]
pub async fn readyz(State(st): State<AppState>) -> (StatusCode, Json<Status>) {
    if st.pool.ready() {
        (
            StatusCode::OK,
            Json(Status {
                status: "ready".into(),
            }),
        )
    } else {
        (
            StatusCode::SERVICE_UNAVAILABLE,
            Json(Status {
                status: "busy".into(),
            }),
        )
    }
}

/// Poles at one spin speed.
///
/// All poles of the rotor under the chosen damping model at `speed`: rotor poles labelled
/// `forward` or `backward`, and for the nonviscous model the overdamped `internal` poles of its
/// branches. Also the undamped nonrotating natural frequencies.
#[utoipa::path(post, path = "/v1/modal", tag = "analyses", request_body = ModalRequest,
    responses(
        (status = 200, description = "Poles", body = ModalResponse),
        (status = 400, description = "Malformed JSON", body = Problem, content_type = "application/problem+json"),
        (status = 413, description = "Body too large", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "Invalid model", body = Problem, content_type = "application/problem+json"),
        (status = 503, description = "Queue full; see Retry-After", body = Problem, content_type = "application/problem+json")))]
pub async fn modal(
    State(st): State<AppState>,
    ApiJson(req): ApiJson<ModalRequest>,
) -> Result<Json<ModalResponse>, ApiError> {
    let mut bad = Invalid::default();
    let speed = bad.check("speed", non_negative(req.speed));
    let parsed = validate_model(&st, &req.rotor, &req.damping, bad)?;
    let speed = speed.expect("validated");
    let max_states = st.config.max_states;
    st.pool
        .run(move || {
            let (system, model) = build(&parsed, max_states)?;
            let r = analysis::modal::modal(&system, &model, speed)?;
            Ok(Json(convert::modal(&r)))
        })
        .await
}

/// Campbell diagram and decay-rate plot.
///
/// Every rotor branch over the sweep, tracked by mode shape (not by sorting frequencies), with
/// the forward critical speeds and the threshold of instability in the range. Internal poles
/// of the nonviscous model are kept out of the branches. A value the model does not define
/// (hysteretic model near a critical speed) is null.
#[utoipa::path(post, path = "/v1/campbell", tag = "analyses", request_body = SweepRequest,
    responses(
        (status = 200, description = "Branches", body = CampbellResponse),
        (status = 400, description = "Malformed JSON", body = Problem, content_type = "application/problem+json"),
        (status = 413, description = "Body too large", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "Invalid model", body = Problem, content_type = "application/problem+json"),
        (status = 503, description = "Queue full; see Retry-After", body = Problem, content_type = "application/problem+json")))]
pub async fn campbell(
    State(st): State<AppState>,
    ApiJson(req): ApiJson<SweepRequest>,
) -> Result<Json<CampbellResponse>, ApiError> {
    let (parsed, grid) = validate_sweep(&st, &req)?;
    let max_states = st.config.max_states;
    st.pool
        .run(move || {
            let (_, model) = build(&parsed, max_states)?;
            let r = analysis::campbell::campbell(&model, grid.as_slice())?;
            Ok(Json(convert::campbell(&r)))
        })
        .await
}

/// Threshold of instability.
///
/// The lowest spin speed in `[start, stop]` at which any pole has `decay_rate > 0`. The speeds
/// are the grid that brackets the crossing; the threshold is then refined by root finding to
/// 1e-6 relative (or better). `threshold` is null when the rotor is stable over the range,
/// and equals the range's start when it is already unstable there.
#[utoipa::path(post, path = "/v1/stability", tag = "analyses", request_body = SweepRequest,
    responses(
        (status = 200, description = "Threshold", body = StabilityResponse),
        (status = 400, description = "Malformed JSON", body = Problem, content_type = "application/problem+json"),
        (status = 413, description = "Body too large", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "Invalid model", body = Problem, content_type = "application/problem+json"),
        (status = 503, description = "Queue full; see Retry-After", body = Problem, content_type = "application/problem+json")))]
pub async fn stability(
    State(st): State<AppState>,
    ApiJson(req): ApiJson<SweepRequest>,
) -> Result<Json<StabilityResponse>, ApiError> {
    let (parsed, grid) = validate_sweep(&st, &req)?;
    let max_states = st.config.max_states;
    st.pool
        .run(move || {
            let (_, model) = build(&parsed, max_states)?;
            let t = analysis::stability::stability(&model, grid.as_slice())?;
            Ok(Json(convert::stability(
                t.as_ref(),
                [grid.first(), grid.last()],
            )))
        })
        .await
}

/// 404 for any other path.
pub async fn not_found(uri: Uri) -> ApiError {
    ApiError::NotFound(format!("no such endpoint: {}", uri.path()))
}

/// A validated rotor and damping model.
pub struct Parsed {
    rotor: Rotor,
    damping: DampingModel,
}

/// Validates rotor and damping together, adding to errors already found.
fn validate_model(
    st: &AppState,
    rotor: &RotorInput,
    damping: &DampingInput,
    mut bad: Invalid,
) -> Result<Parsed, ApiError> {
    let rotor = match Rotor::parse(rotor, &st.config.limits()) {
        Ok(r) => Some(r),
        Err(e) => {
            bad.extend(e);
            None
        }
    };
    // `modes` is bounded by the rotor's size; without a valid rotor, by nothing yet.
    let dofs = rotor.as_ref().map_or(usize::MAX, Rotor::dof_count);
    let damping = match DampingModel::parse(damping, dofs) {
        Ok(d) => Some(d),
        Err(e) => {
            bad.extend(e);
            None
        }
    };
    if !bad.is_empty() {
        return Err(bad.into());
    }
    Ok(Parsed {
        rotor: rotor.expect("validated"),
        damping: damping.expect("validated"),
    })
}

fn validate_sweep(st: &AppState, req: &SweepRequest) -> Result<(Parsed, SpeedGrid), ApiError> {
    let mut bad = Invalid::default();
    let grid = match SpeedGrid::parse(&req.speeds, st.config.max_speeds) {
        Ok(g) => Some(g),
        Err(e) => {
            bad.extend(e);
            None
        }
    };
    let parsed = validate_model(st, &req.rotor, &req.damping, bad)?;
    Ok((parsed, grid.expect("validated")))
}

/// Assembles the rotor and builds its damping model (on the worker pool: solves eigenproblems).
fn build(p: &Parsed, max_states: usize) -> Result<(RotorSystem, DampedModel), ApiError> {
    let system = RotorSystem::assemble(&p.rotor)
        .map_err(|e| ApiError::Unsolvable(format!("the rotor cannot be assembled: {e}")))?;
    let model = DampedModel::build(&system, &p.damping).map_err(|e| match e {
        DampingError::Modal(ModalError::RigidBody { .. }) => {
            let path = match p.rotor {
                Rotor::Beam(_) => "rotor.supports",
                _ => "rotor.stiffness",
            };
            ApiError::Invalid(Invalid::one(path, e.to_string()))
        }
        other => ApiError::Unsolvable(other.to_string()),
    })?;
    if model.states() > max_states {
        return Err(ApiError::Invalid(Invalid::one(
            "damping",
            format!(
                "the model has {} states, more than the limit of {max_states} \
                 (WHIRL_MAX_STATES): use Guyan reduction, `modes`, or fewer branches",
                model.states()
            ),
        )));
    }
    Ok((system, model))
}
