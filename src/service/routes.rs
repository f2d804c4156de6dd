//! Handlers: validate on the runtime, compute on the worker pool, convert to wire types.

use axum::Json;
use axum::extract::Path;
use axum::extract::State;
use axum::http::{HeaderMap, HeaderValue, StatusCode, Uri, header};
use axum::response::{IntoResponse, Response};
use serde_json::Value;

use super::AppState;
use super::convert;
use super::error::ApiError;
use super::jobs;
use super::json::ApiJson;
use super::task::{Output, Task, negotiate, render, respond};
use crate::analysis;
use crate::analysis::time::{SpeedLaw, TimeSpec};
use crate::analysis::unbalance::SteadyUnbalance;
use crate::damping::report;
use crate::damping::{DampedModel, DampingError};
use crate::fem::modal::ModalError;
use crate::model::Invalid;
use crate::model::api::{
    AnalysisName, CampbellResponse, DampingInput, DampingMatricesRequest, DampingMatricesResponse,
    JobInfo, JobRequest, JobStatus, MatrixForm, ModalRequest, ModalResponse, Problem, RotorInput,
    StabilityResponse, Status, SweepRequest, TimeResponseRequest, TimeResponseResponse,
    UnbalanceResponseRequest, UnbalanceResponseResponse,
};
use crate::model::damping::DampingModel;
use crate::model::error::{finite, non_negative, positive};
use crate::model::loads::{Force, Pwl, Unbalance};
use crate::model::rotor::Rotor;
use crate::model::speeds::SpeedGrid;
use crate::system::RotorSystem;

/// The errors every analysis endpoint may answer, as problem+json.
#[derive(utoipa::IntoResponses)]
#[allow(dead_code)] // only read by the OpenAPI derive
enum AnalysisErrors {
    #[response(
        status = 400,
        description = "Malformed JSON",
        content_type = "application/problem+json"
    )]
    Malformed(Problem),
    #[response(
        status = 413,
        description = "Body too large",
        content_type = "application/problem+json"
    )]
    TooLarge(Problem),
    #[response(
        status = 422,
        description = "Invalid model",
        content_type = "application/problem+json"
    )]
    Invalid(Problem),
    #[response(
        status = 503,
        description = "Queue full; see Retry-After",
        content_type = "application/problem+json"
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
        (status = 200, description = "Poles (JSON; the table or the plot by Accept)",
         content((ModalResponse = "application/json"), (String = "text/csv"))),
        (status = 406, description = "No acceptable format", body = Problem, content_type = "application/problem+json"),
        AnalysisErrors))]
pub async fn modal(
    State(st): State<AppState>,
    headers: HeaderMap,
    ApiJson(req): ApiJson<ModalRequest>,
) -> Result<Response, ApiError> {
    let format = negotiate(&headers)?;
    let task = prepare_modal(&st, req)?;
    respond(&st, "modal", task, format).await
}

/// Validates a `modal` request into a task.
pub fn prepare_modal(st: &AppState, req: ModalRequest) -> Result<Task, ApiError> {
    let mut bad = Invalid::default();
    let speed = bad.check("speed", non_negative(req.speed));
    let parsed = validate_model(st, &req.rotor, &req.damping, bad)?;
    let speed = speed.expect("validated");
    let max_states = st.config.max_states;
    Ok(Task::new(move |_| {
        let (system, model) = build(&parsed, max_states)?;
        let r = analysis::modal::modal(&system, &model, speed)?;
        Ok(Output::Modal(convert::modal(&r)))
    }))
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
         content((CampbellResponse = "application/json"), (String = "text/csv"), (String = "image/svg+xml"))),
        (status = 406, description = "No acceptable format", body = Problem, content_type = "application/problem+json"),
        AnalysisErrors))]
pub async fn campbell(
    State(st): State<AppState>,
    headers: HeaderMap,
    ApiJson(req): ApiJson<SweepRequest>,
) -> Result<Response, ApiError> {
    let format = negotiate(&headers)?;
    let task = prepare_campbell(&st, req)?;
    respond(&st, "campbell", task, format).await
}

/// Validates a `campbell` request into a task.
pub fn prepare_campbell(st: &AppState, req: SweepRequest) -> Result<Task, ApiError> {
    let (parsed, grid) = validate_sweep(st, &req)?;
    let max_states = st.config.max_states;
    let max_frequency = req.max_frequency.unwrap_or(f64::INFINITY);
    let reduce = req.modal_reduction.unwrap_or(true);
    Ok(Task::new(move |control| {
        let (system, model) = build(&parsed, max_states)?;
        let r = analysis::campbell::campbell_below(
            &system,
            &parsed.damping,
            &model,
            grid.as_slice(),
            max_frequency,
            reduce,
            control,
        )?;
        Ok(Output::Campbell(convert::campbell(&r)))
    }))
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
         content((StabilityResponse = "application/json"), (String = "text/csv"), (String = "image/svg+xml"))),
        (status = 406, description = "No acceptable format", body = Problem, content_type = "application/problem+json"),
        AnalysisErrors))]
pub async fn stability(
    State(st): State<AppState>,
    headers: HeaderMap,
    ApiJson(req): ApiJson<SweepRequest>,
) -> Result<Response, ApiError> {
    let format = negotiate(&headers)?;
    let task = prepare_stability(&st, req)?;
    respond(&st, "stability", task, format).await
}

/// Validates a `stability` request into a task.
pub fn prepare_stability(st: &AppState, req: SweepRequest) -> Result<Task, ApiError> {
    let (parsed, grid) = validate_sweep(st, &req)?;
    let max_states = st.config.max_states;
    Ok(Task::new(move |control| {
        let (_, model) = build(&parsed, max_states)?;
        let (t, curve) = analysis::stability::stability_curve(&model, grid.as_slice(), control)?;
        Ok(Output::Stability(convert::stability(
            t.as_ref(),
            grid.as_slice(),
            curve,
        )))
    }))
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
    let task = prepare_damping_matrices(&st, req)?;
    respond(&st, "damping", task, format).await
}

/// Validates a `damping_matrices` request into a task.
pub fn prepare_damping_matrices(
    st: &AppState,
    req: DampingMatricesRequest,
) -> Result<Task, ApiError> {
    let mut bad = Invalid::default();
    let fit = req.fit.clone().unwrap_or_default();
    let band = match fit.band {
        Some([lo, hi]) if lo.is_finite() && hi.is_finite() && lo > 0.0 && hi > lo => Some([lo, hi]),
        Some(b) => {
            bad.push(
                "fit.band",
                format!("must be [low, high] with 0 < low < high (got {b:?})"),
            );
            None
        }
        None => None,
    };
    let auto = match fit.max_deviation {
        None => None,
        Some(d) if d.is_finite() && d > 0.0 => Some(d),
        Some(d) => {
            bad.push(
                "fit.max_deviation",
                format!("must be a number > 0 (got {d})"),
            );
            None
        }
    };
    if auto.is_some() {
        match &req.damping {
            DampingInput::Nonviscous(nv) => {
                for (side, b) in [("rotating", &nv.rotating), ("nonrotating", &nv.nonrotating)] {
                    if let Some(b) = b
                        && (b.branches.is_some() || b.nu.is_some())
                    {
                        bad.push(
                            format!("damping.{side}"),
                            "fit.max_deviation chooses the number of branches: omit `branches` \
                             and `nu`",
                        );
                    }
                }
                if band.is_none() && fit.band.is_none() {
                    bad.push("fit.band", "needed with fit.max_deviation");
                }
            }
            _ => bad.push("fit.max_deviation", "applies to the nonviscous model only"),
        }
    }
    let parsed = validate_model(st, &req.rotor, &req.damping, bad)?;
    if matches!(
        parsed.damping,
        DampingModel::Viscous | DampingModel::Hysteretic
    ) {
        return Err(ApiError::Invalid(Invalid::one(
            "damping.model",
            format!(
                "`{}` adds no matrices: this endpoint returns the `equivalent` or `nonviscous` \
                 model (hysteretic damping has no time-domain form; nonviscous is its \
                 time-domain model)",
                parsed.damping.name()
            ),
        )));
    }
    let form = req.form.unwrap_or(MatrixForm::SecondOrder);
    let max_states = st.config.max_states;
    Ok(Task::new(move |_| {
        damping_report(&parsed, form, band, auto, max_states).map(|r| Output::Damping(Box::new(r)))
    }))
}

fn damping_report(
    p: &Parsed,
    form: MatrixForm,
    band: Option<[f64; 2]>,
    auto: Option<f64>,
    max_states: usize,
) -> Result<DampingMatricesResponse, ApiError> {
    let system = RotorSystem::assemble(&p.rotor)
        .map_err(|e| ApiError::Unsolvable(format!("the rotor cannot be assembled: {e}")))?;
    let options = report::Options {
        state_form: form == MatrixForm::State,
        band,
        max_deviation: auto,
        max_states,
    };
    let r = report::matrices(&system, &p.damping, &options).map_err(|e| match e {
        report::ReportError::Damping(e) => damping_error(e, &p.rotor),
        e @ report::ReportError::Unreachable { .. } => {
            ApiError::Invalid(Invalid::one("fit.max_deviation", e.to_string()))
        }
        e @ report::ReportError::NonFinite => ApiError::Unsolvable(e.to_string()),
        e @ report::ReportError::TooLarge { .. } => {
            ApiError::Invalid(Invalid::one("damping", e.to_string()))
        }
    })?;
    Ok(convert::damping_matrices(&r, p.damping.name()))
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
         content((TimeResponseResponse = "application/json"), (String = "text/csv"), (String = "image/svg+xml"))),
        (status = 406, description = "No acceptable format", body = Problem, content_type = "application/problem+json"),
        AnalysisErrors))]
pub async fn time_response(
    State(st): State<AppState>,
    headers: HeaderMap,
    ApiJson(req): ApiJson<TimeResponseRequest>,
) -> Result<Response, ApiError> {
    let format = negotiate(&headers)?;
    let task = prepare_time_response(&st, req)?;
    respond(&st, "time-response", task, format).await
}

/// Validates a `time_response` request into a task.
pub fn prepare_time_response(st: &AppState, req: TimeResponseRequest) -> Result<Task, ApiError> {
    let mut bad = Invalid::default();
    if matches!(req.damping, DampingInput::Hysteretic(_)) {
        bad.push(
            "damping.model",
            "the hysteretic model is defined for harmonic motion only and cannot be integrated \
             in time; use `nonviscous` (its time-domain model) or `equivalent`",
        );
    }
    let speed = match (req.speed, &req.speed_profile) {
        (Some(w), None) => bad.check("speed", non_negative(w)).map(SpeedLaw::Constant),
        (None, Some(p)) => {
            let law = Pwl::parse(p, "speed_profile", false, &mut bad);
            if p.iter().any(|q| q[1] < 0.0) {
                bad.push("speed_profile", "speeds must be >= 0");
            }
            law.map(SpeedLaw::Profile)
        }
        (Some(_), Some(_)) => {
            bad.push("speed", "give `speed` or `speed_profile`, not both");
            None
        }
        (None, None) => {
            bad.push("speed", "give `speed` (constant) or `speed_profile`");
            None
        }
    };
    let duration = bad.check("duration", positive(req.duration));
    let dt = bad.check("output_interval", positive(req.output_interval));
    let tolerance = match req.tolerance {
        None => Some(1e-6),
        Some(x) if (1e-12..=1e-2).contains(&x) => Some(x),
        Some(x) => {
            bad.push("tolerance", format!("must be in [1e-12, 1e-2] (got {x})"));
            None
        }
    };
    let parsed = validate_model(st, &req.rotor, &req.damping, bad)?;
    let mut bad = Invalid::default();
    let nodes = parsed.rotor.node_count();
    let node = |bad: &mut Invalid, at: String, k: i64| node_index(bad, at, k, nodes);
    let mut forces = vec![];
    for (i, f) in req.forces.iter().enumerate() {
        let at = format!("forces[{i}]");
        let n = node(&mut bad, format!("{at}.node"), f.node);
        let dir = bad.check(&format!("{at}.direction"), finite(f.direction));
        let h = Pwl::parse(&f.history, &format!("{at}.history"), true, &mut bad);
        if let (Some(node), Some(direction), Some(history)) = (n, dir, h) {
            forces.push(Force {
                node,
                direction,
                history,
            });
        }
    }
    let mut unbalances = vec![];
    for (i, u) in req.unbalances.iter().enumerate() {
        let at = format!("unbalances[{i}]");
        let n = node(&mut bad, format!("{at}.node"), u.node);
        let amount = bad.check(&format!("{at}.amount"), non_negative(u.amount));
        let phase = bad.check(&format!("{at}.phase"), finite(u.phase));
        let from = bad.check(&format!("{at}.from"), non_negative(u.from));
        if let (Some(node), Some(amount), Some(phase), Some(from)) = (n, amount, phase, from) {
            unbalances.push(Unbalance {
                node,
                amount,
                phase,
                from,
            });
        }
    }
    let out = report_nodes(&mut bad, &req.nodes, nodes, node);
    if let (Some(d), Some(h)) = (duration, dt) {
        let samples = (d / h).floor() + 1.0;
        if samples * out.len().max(1) as f64 > st.config.max_samples as f64 {
            bad.push(
                "output_interval",
                format!(
                    "{samples} samples x {} nodes exceed the limit of {} values \
                     (WHIRL_MAX_SAMPLES): use a longer interval or fewer nodes",
                    out.len(),
                    st.config.max_samples
                ),
            );
        }
    }
    if !bad.is_empty() {
        return Err(bad.into());
    }
    let spec = TimeSpec {
        speed: speed.expect("validated"),
        forces,
        unbalances,
        duration: duration.expect("validated"),
        output_interval: dt.expect("validated"),
        nodes: out,
        tolerance: tolerance.expect("validated"),
        max_steps: st.config.max_steps,
    };
    let max_states = st.config.max_states;
    Ok(Task::new(move |control| {
        let (system, model) = build(&parsed, max_states)?;
        let r =
            analysis::time::time_response(&system, &model, &spec, false, control).map_err(|e| {
                match e {
                    analysis::time::TimeError::Cancelled => ApiError::Cancelled,
                    e => ApiError::Unsolvable(e.to_string()),
                }
            })?;
        Ok(Output::Time(convert::time_response(&r)))
    }))
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
         content((UnbalanceResponseResponse = "application/json"), (String = "text/csv"), (String = "image/svg+xml"))),
        (status = 406, description = "No acceptable format", body = Problem, content_type = "application/problem+json"),
        AnalysisErrors))]
pub async fn unbalance_response(
    State(st): State<AppState>,
    headers: HeaderMap,
    ApiJson(req): ApiJson<UnbalanceResponseRequest>,
) -> Result<Response, ApiError> {
    let format = negotiate(&headers)?;
    let task = prepare_unbalance_response(&st, req)?;
    respond(&st, "unbalance-response", task, format).await
}

/// Validates a `unbalance_response` request into a task.
pub fn prepare_unbalance_response(
    st: &AppState,
    req: UnbalanceResponseRequest,
) -> Result<Task, ApiError> {
    let mut bad = Invalid::default();
    let grid = match SpeedGrid::parse(&req.speeds, st.config.max_speeds) {
        Ok(g) => Some(g),
        Err(e) => {
            bad.extend(e);
            None
        }
    };
    if req.unbalances.is_empty() {
        bad.push("unbalances", "needs at least one unbalance");
    }
    let parsed = validate_model(st, &req.rotor, &req.damping, bad)?;
    let mut bad = Invalid::default();
    let nodes = parsed.rotor.node_count();
    let node = |bad: &mut Invalid, at: String, k: i64| node_index(bad, at, k, nodes);
    let mut unb = vec![];
    for (i, u) in req.unbalances.iter().enumerate() {
        let at = format!("unbalances[{i}]");
        let n = node(&mut bad, format!("{at}.node"), u.node);
        let amount = bad.check(&format!("{at}.amount"), non_negative(u.amount));
        let phase = bad.check(&format!("{at}.phase"), finite(u.phase));
        if let (Some(n), Some(a), Some(p)) = (n, amount, phase) {
            unb.push((n, a, p));
        }
    }
    let out = report_nodes(&mut bad, &req.nodes, nodes, node);
    if !bad.is_empty() {
        return Err(bad.into());
    }
    let grid = grid.expect("validated");
    let max_states = st.config.max_states;
    let model_name = parsed.damping.name();
    Ok(Task::new(move |control| {
        let (system, model) = build(&parsed, max_states)?;
        let dof = |n: usize| analysis::time::translation(&system, n);
        let unbalances: Vec<SteadyUnbalance> = unb
            .iter()
            .map(|&(n, amount, phase)| SteadyUnbalance {
                dof: dof(n),
                amount,
                phase,
            })
            .collect();
        let dofs: Vec<usize> = out.iter().map(|&n| dof(n)).collect();
        let q = analysis::unbalance::unbalance_response(
            &system,
            &model,
            grid.as_slice(),
            &unbalances,
            &dofs,
            control,
        )?;
        Ok(Output::Unbalance(convert::unbalance_response(
            grid.as_slice(),
            &out,
            &q,
            model_name,
        )))
    }))
}

/// A node of a rotor with `nodes` nodes, or the error at `at`.
fn node_index(bad: &mut Invalid, at: String, k: i64, nodes: usize) -> Option<usize> {
    if k >= 0 && (k as u64) < nodes as u64 {
        Some(k as usize)
    } else {
        bad.push(
            at,
            format!("node {k} does not exist (nodes 0 to {})", nodes - 1),
        );
        None
    }
}

/// The nodes to report: the requested ones (validated) or all.
fn report_nodes(
    bad: &mut Invalid,
    requested: &Option<Vec<i64>>,
    nodes: usize,
    node: impl Fn(&mut Invalid, String, i64) -> Option<usize>,
) -> Vec<usize> {
    match requested {
        None => (0..nodes).collect(),
        Some(list) => {
            if list.is_empty() {
                bad.push("nodes", "needs at least one node (or omit it for all)");
            }
            list.iter()
                .enumerate()
                .filter_map(|(i, &k)| node(bad, format!("nodes[{i}]"), k))
                .collect()
        }
    }
}

/// Submit an analysis to run later.
///
/// `{"analysis": "campbell", "input": {...}}`: the input is what `POST /v1/<analysis>` takes,
/// validated now (422 at once). 202 with `Location: /v1/jobs/{id}` when admitted; 503 with
/// `Retry-After` when the queue is full. An accepted job always runs.
#[utoipa::path(post, path = "/v1/jobs", tag = "jobs", request_body = JobRequest,
    responses(
        (status = 202, description = "Accepted; poll Location", body = JobInfo,
         headers(("Location" = String, description = "URL of the job"))),
        (status = 400, description = "Malformed JSON", body = Problem, content_type = "application/problem+json"),
        (status = 413, description = "Body too large", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "Invalid input", body = Problem, content_type = "application/problem+json"),
        (status = 503, description = "Queue full; see Retry-After", body = Problem, content_type = "application/problem+json")))]
pub async fn submit_job(
    State(st): State<AppState>,
    ApiJson(req): ApiJson<JobRequest>,
) -> Result<Response, ApiError> {
    fn input<T: serde::de::DeserializeOwned>(v: Value) -> Result<T, ApiError> {
        let bytes = serde_json::to_vec(&v).map_err(|e| ApiError::Internal(e.to_string()))?;
        super::json::parse(&bytes).map_err(|e| match e {
            ApiError::Invalid(mut inv) => {
                for f in &mut inv.0 {
                    f.path = if f.path == "(body)" {
                        "input".into()
                    } else {
                        format!("input.{}", f.path)
                    };
                }
                ApiError::Invalid(inv)
            }
            other => other,
        })
    }
    let prefix = |e: ApiError| match e {
        ApiError::Invalid(mut inv) => {
            for f in &mut inv.0 {
                if !f.path.starts_with("input") {
                    f.path = format!("input.{}", f.path);
                }
            }
            ApiError::Invalid(inv)
        }
        other => other,
    };
    let (name, task) = match req.analysis {
        AnalysisName::Modal => (
            "modal",
            prepare_modal(&st, input(req.input)?).map_err(prefix)?,
        ),
        AnalysisName::Campbell => (
            "campbell",
            prepare_campbell(&st, input(req.input)?).map_err(prefix)?,
        ),
        AnalysisName::Stability => (
            "stability",
            prepare_stability(&st, input(req.input)?).map_err(prefix)?,
        ),
        AnalysisName::Damping => (
            "damping",
            prepare_damping_matrices(&st, input(req.input)?).map_err(prefix)?,
        ),
        AnalysisName::TimeResponse => (
            "time-response",
            prepare_time_response(&st, input(req.input)?).map_err(prefix)?,
        ),
        AnalysisName::UnbalanceResponse => (
            "unbalance-response",
            prepare_unbalance_response(&st, input(req.input)?).map_err(prefix)?,
        ),
    };
    let info = jobs::submit(&st, name, task)?;
    let location = format!("/v1/jobs/{}", info.id);
    let mut resp = (StatusCode::ACCEPTED, Json(info)).into_response();
    if let Ok(v) = HeaderValue::from_str(&location) {
        resp.headers_mut().insert(header::LOCATION, v);
    }
    Ok(resp)
}

/// A job's status and progress.
#[utoipa::path(get, path = "/v1/jobs/{id}", tag = "jobs",
    params(("id" = String, Path, description = "Job id")),
    responses(
        (status = 200, description = "Status", body = JobInfo),
        (status = 404, description = "Unknown or forgotten job", body = Problem, content_type = "application/problem+json")))]
pub async fn get_job(
    State(st): State<AppState>,
    Path(id): Path<String>,
) -> Result<Json<JobInfo>, ApiError> {
    st.jobs.get(&id).map(Json)
}

/// A succeeded job's result: the body its synchronous endpoint returns (JSON, CSV or SVG by
/// `Accept`); 409 before it has succeeded.
#[utoipa::path(get, path = "/v1/jobs/{id}/result", tag = "jobs",
    params(("id" = String, Path, description = "Job id")),
    responses(
        (status = 200, description = "The analysis result",
         content((Object = "application/json"), (String = "text/csv"), (String = "image/svg+xml"))),
        (status = 404, description = "Unknown or forgotten job", body = Problem, content_type = "application/problem+json"),
        (status = 406, description = "Format not available", body = Problem, content_type = "application/problem+json"),
        (status = 409, description = "Not succeeded (yet)", body = Problem, content_type = "application/problem+json")))]
pub async fn job_result(
    State(st): State<AppState>,
    headers: HeaderMap,
    Path(id): Path<String>,
) -> Result<Response, ApiError> {
    let formats = negotiate(&headers)?;
    let out = st.jobs.result(&id)?;
    render(&out, &formats)
}

/// Cancel a job: a queued one at once (200, `cancelled`), a running one within a second
/// (202, still `running` until it stops); 409 if it has finished.
#[utoipa::path(delete, path = "/v1/jobs/{id}", tag = "jobs",
    params(("id" = String, Path, description = "Job id")),
    responses(
        (status = 200, description = "Cancelled", body = JobInfo),
        (status = 202, description = "Cancellation requested", body = JobInfo),
        (status = 404, description = "Unknown or forgotten job", body = Problem, content_type = "application/problem+json"),
        (status = 409, description = "Already finished", body = Problem, content_type = "application/problem+json")))]
pub async fn cancel_job(
    State(st): State<AppState>,
    Path(id): Path<String>,
) -> Result<Response, ApiError> {
    let info = st.jobs.cancel(&id, "cancelled by the client")?;
    let status = if info.status == JobStatus::Cancelled {
        StatusCode::OK
    } else {
        StatusCode::ACCEPTED
    };
    Ok((status, Json(info)).into_response())
}

/// Prometheus metrics.
#[utoipa::path(get, path = "/metrics", tag = "operations",
    responses((status = 200, description = "Prometheus text format", body = String, content_type = "text/plain")))]
pub async fn metrics(State(st): State<AppState>) -> Response {
    let mut resp = super::metrics::render(&st).into_response();
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
    if let Some(f) = req.max_frequency
        && !(f.is_finite() && f > 0.0)
    {
        bad.push("max_frequency", format!("must be a number > 0 (got {f})"));
    }
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

/// A rigid-body rotor is an invalid input (its supports, or its stiffness); anything else
/// is a model the analysis cannot solve.
fn damping_error(e: DampingError, rotor: &Rotor) -> ApiError {
    match e {
        DampingError::Modal(ModalError::RigidBody { .. }) => {
            let path = match rotor {
                Rotor::Beam(_) => "rotor.supports",
                _ => "rotor.stiffness",
            };
            ApiError::Invalid(Invalid::one(path, e.to_string()))
        }
        other => ApiError::Unsolvable(other.to_string()),
    }
}

/// Assembles the rotor and builds its damping model (on the worker pool: solves eigenproblems).
fn build(p: &Parsed, max_states: usize) -> Result<(RotorSystem, DampedModel), ApiError> {
    let system = RotorSystem::assemble(&p.rotor)
        .map_err(|e| ApiError::Unsolvable(format!("the rotor cannot be assembled: {e}")))?;
    let model = DampedModel::build(&system, &p.damping).map_err(|e| damping_error(e, &p.rotor))?;
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
