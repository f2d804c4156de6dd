//! The HTTP service: the only layer that knows HTTP. Handlers ([`routes`], [`routes_audit`],
//! [`routes_convert`]) read a body ([`json`]), parse it into a task with one call into `model`,
//! run it ([`task`]) or submit it as a job (`jobs`), and answer; around them the configuration
//! ([`config`]), the errors as problems ([`error`]), the OpenAPI document ([`openapi`]), the
//! middleware (here and [`metrics`]), job results streamed from the store ([`results`]) and
//! the connection handling ([`server`]).
//!
//! [`app`] builds the whole router from a [`Config`], so tests drive it in process without a
//! socket. Requests are validated on the async runtime (cheap); every numerical analysis runs
//! on the blocking [`pool::WorkerPool`], so a long sweep never stalls other requests. Jobs live
//! in the [`store::Store`] (SQLite by default, PostgreSQL shared by replicas), and each
//! replica's [`runner::Runner`] claims and runs them on its pool.

pub mod config;
pub mod cors;
pub mod error;
pub mod guard;
pub mod json;
pub mod metrics;
pub mod openapi;
pub mod problems;
pub mod results;
pub mod routes;
pub mod routes_audit;
pub mod routes_convert;
pub mod routes_jobs;
pub mod routes_studies;
pub mod server;
pub mod slow;
pub mod task;

use std::sync::Arc;
use std::time::Duration;

use axum::Router;
use axum::extract::{DefaultBodyLimit, Request};
use axum::http::{HeaderValue, StatusCode, header};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};
use tower_http::compression::CompressionLayer;
use tower_http::trace::TraceLayer;
use utoipa_axum::router::OpenApiRouter;
use utoipa_swagger_ui::SwaggerUi;

use crate::jobs::{self, pool, runner, store};
pub use config::Config;
pub use error::ApiError;

/// Shared by all handlers.
#[derive(Clone)]
pub struct AppState {
    pub config: Arc<Config>,
    pub pool: Arc<pool::WorkerPool>,
    pub jobs: Arc<jobs::Jobs>,
    pub metrics: Arc<metrics::Metrics>,
    /// Measured pace of synchronous analyses (a report past the limit is refused up front).
    pub pace: Arc<task::Pace>,
}

impl AppState {
    /// The state, with its job store not yet connected and its runner not started (see
    /// [`AppState::start`]).
    pub fn new(config: Config) -> Self {
        // One problem per core: faer stays sequential, sweeps parallelise over speeds.
        crate::linalg::set_sequential();
        let retention = store::Retention {
            age: config.job_retention,
            max_finished: config.max_finished_jobs,
            max_bytes: config.job_result_bytes,
        };
        let config = Arc::new(config);
        let pool = Arc::new(pool::WorkerPool::new(
            config.workers,
            config.queue,
            config.threads(),
            config.memory_budget,
        ));
        let metrics = Arc::new(metrics::Metrics::default());
        let store = Arc::new(store::Store::new(config.store_target(), retention));
        let runner = Arc::new(runner::Runner::new(
            store.clone(),
            pool.clone(),
            metrics.clone(),
            config.runner(),
        ));
        AppState {
            jobs: Arc::new(jobs::Jobs::new(store, runner, config.queue)),
            pool,
            metrics,
            pace: Arc::default(),
            config,
        }
    }

    /// Starts claiming and running jobs, and the store's upkeep (on the current runtime).
    pub fn start(&self) {
        self.jobs.runner.start();
    }
}

/// The router with its OpenAPI document (`split_for_parts` keeps them in sync by construction).
pub fn router(state: AppState) -> (Router, serde_json::Value) {
    let limits = json::BodyLimits {
        max_bytes: state.config.max_body_bytes,
        timeout: state.config.body_timeout,
    };
    let (router, api) = OpenApiRouter::with_openapi(openapi::base())
        .routes(utoipa_axum::routes!(routes::healthz))
        .routes(utoipa_axum::routes!(routes::readyz))
        .routes(utoipa_axum::routes!(routes::modal))
        .routes(utoipa_axum::routes!(routes::campbell))
        .routes(utoipa_axum::routes!(routes::stability))
        .routes(utoipa_axum::routes!(routes::damping_matrices))
        .routes(utoipa_axum::routes!(routes::time_response))
        .routes(utoipa_axum::routes!(routes::unbalance_response))
        .routes(utoipa_axum::routes!(routes_audit::critical_speed_map))
        .routes(utoipa_axum::routes!(routes_audit::static_deflection))
        .routes(utoipa_axum::routes!(routes_audit::level1))
        .routes(utoipa_axum::routes!(routes_audit::frequency_response))
        .routes(utoipa_axum::routes!(routes_audit::report))
        .routes(utoipa_axum::routes!(routes_convert::convert_ross))
        .routes(utoipa_axum::routes!(
            routes::submit_job,
            routes_jobs::list_jobs
        ))
        .routes(utoipa_axum::routes!(routes::get_job, routes::cancel_job))
        .routes(utoipa_axum::routes!(routes::job_result))
        .routes(utoipa_axum::routes!(routes_studies::submit_study))
        .routes(utoipa_axum::routes!(
            routes_studies::get_study,
            routes_studies::cancel_study
        ))
        .routes(utoipa_axum::routes!(routes_studies::study_result))
        .routes(utoipa_axum::routes!(routes::metrics))
        .routes(utoipa_axum::routes!(problems::page))
        .with_state(state.clone())
        .split_for_parts();
    // After the routes: utoipa-axum replaces the component schemas as it registers each one.
    let api = openapi::secured(api);
    let allowed = Arc::new(allowed_methods(&api));
    // Served as JSON from here on: utoipa's types cannot read back an untyped schema (`{}`, the
    // items of an array of any JSON), so the finished document never returns to them.
    let doc =
        openapi::for_clients(serde_json::to_value(&api).expect("the OpenAPI document serialises"));
    let request_id = axum::http::HeaderName::from_static("x-request-id");
    let router = router
        .merge(SwaggerUi::new("/docs").external_url_unchecked("/openapi.json", doc.clone()))
        .route_layer(axum::middleware::from_fn(metrics::label))
        .fallback(routes::not_found)
        .layer(DefaultBodyLimit::max(limits.max_bytes))
        .layer(axum::Extension(limits))
        .layer(axum::middleware::from_fn_with_state(limits, refuse_large_bodies))
        .layer(axum::middleware::from_fn_with_state(
            allowed,
            method_problems,
        ))
        .layer(axum::middleware::from_fn_with_state(
            problems::PublicUrl(state.config.public_url.clone()),
            problems::absolute_types,
        ))
        .layer(axum::middleware::from_fn_with_state(
            state.clone(),
            metrics::track,
        ))
        .layer(axum::middleware::from_fn_with_state(
            state.config.api_token.clone(),
            guard::require_token,
        ))
        .layer(axum::middleware::from_fn(guard::harden))
        .layer(CompressionLayer::new())
        .layer(
            TraceLayer::new_for_http()
                .make_span_with(|req: &Request<_>| {
                    let id = req
                        .headers()
                        .get("x-request-id")
                        .and_then(|v| v.to_str().ok())
                        .unwrap_or("-");
                    tracing::info_span!("request", method = %req.method(), uri = %req.uri(), request_id = %id)
                })
                .on_response(log_response)
                .on_failure(()),
        )
        .layer(tower_http::request_id::PropagateRequestIdLayer::new(request_id.clone()))
        .layer(tower_http::request_id::SetRequestIdLayer::new(request_id, RequestIds))
        .layer(axum::middleware::map_request(guard::bound_request_id));
    // Outermost: a preflight is answered before any other layer sees it.
    let router = match cors::layer(&state.config.cors_origins) {
        Some(layer) => router.layer(layer),
        None => router,
    };
    (router, doc)
}

/// One log line per response, at a level by its status: a 503 is the service shedding load as
/// designed (a warning), a 500 is a bug (an error).
fn log_response<B>(resp: &Response<B>, latency: Duration, _: &tracing::Span) {
    let status = resp.status().as_u16();
    let ms = latency.as_secs_f64() * 1e3;
    match status {
        500..=599 if status != 503 => tracing::error!(status, ms, "response"),
        503 | 429 => tracing::warn!(status, ms, "response"),
        _ => tracing::info!(status, ms, "response"),
    }
}

/// 413 from `Content-Length` before any of the body is read.
async fn refuse_large_bodies(
    axum::extract::State(limits): axum::extract::State<json::BodyLimits>,
    req: Request,
    next: Next,
) -> Response {
    let announced = req
        .headers()
        .get(header::CONTENT_LENGTH)
        .and_then(|v| v.to_str().ok())
        .and_then(|v| v.trim().parse::<u64>().ok());
    if announced.is_some_and(|n| n > limits.max_bytes as u64) {
        return ApiError::TooLarge(limits.max_bytes).into_response();
    }
    next.run(req).await
}

/// Path templates of the API and the methods each answers (`Allow`), from the OpenAPI document.
type Allowed = Vec<(Vec<String>, String)>;

fn allowed_methods(api: &utoipa::openapi::OpenApi) -> Allowed {
    api.paths
        .paths
        .iter()
        .map(|(path, item)| {
            let mut methods = vec![];
            for (name, op) in [
                ("GET", &item.get),
                ("HEAD", &item.get),
                ("POST", &item.post),
                ("PUT", &item.put),
                ("PATCH", &item.patch),
                ("DELETE", &item.delete),
            ] {
                if op.is_some() {
                    methods.push(name);
                }
            }
            let segments = path.split('/').map(str::to_string).collect();
            (segments, methods.join(", "))
        })
        .collect()
}

/// The `Allow` of a request path (`{name}` segments match any one segment).
fn allow_of(allowed: &Allowed, path: &str) -> String {
    let segs: Vec<&str> = path.split('/').collect();
    allowed
        .iter()
        .find(|(t, _)| {
            t.len() == segs.len()
                && t.iter()
                    .zip(&segs)
                    .all(|(a, b)| (a.starts_with('{') && a.ends_with('}')) || a == b)
        })
        .map(|(_, m)| m.clone())
        .unwrap_or_default()
}

/// A method the path does not answer (OPTIONS included) is a problem+json 405 with `Allow`.
async fn method_problems(
    axum::extract::State(allowed): axum::extract::State<Arc<Allowed>>,
    req: Request,
    next: Next,
) -> Response {
    let path = req.uri().path().to_string();
    let resp = next.run(req).await;
    if resp.status() != StatusCode::METHOD_NOT_ALLOWED {
        return resp;
    }
    let allow = allow_of(&allowed, &path);
    let mut out = ApiError::MethodNotAllowed(allow).into_response();
    if let Some(route) = resp.extensions().get::<metrics::Route>() {
        out.extensions_mut().insert(route.clone());
    }
    out
}

/// Request ids `x-request-id` (kept when the client sends an acceptable one, see
/// [`guard::acceptable_request_id`]): UUIDv7, unique across restarts, containers and replicas,
/// and ordered by time.
#[derive(Clone, Default)]
struct RequestIds;

impl tower_http::request_id::MakeRequestId for RequestIds {
    fn make_request_id<B>(
        &mut self,
        _: &axum::http::Request<B>,
    ) -> Option<tower_http::request_id::RequestId> {
        HeaderValue::from_str(&uuid::Uuid::now_v7().to_string())
            .ok()
            .map(tower_http::request_id::RequestId::new)
    }
}

/// The application, running jobs (call it inside a Tokio runtime).
pub fn app(config: Config) -> Router {
    app_with_state(config).0
}

/// The application and its state (for the binary's graceful shutdown of jobs).
pub fn app_with_state(config: Config) -> (Router, AppState) {
    let state = AppState::new(config);
    state.start();
    (router(state.clone()).0, state)
}

/// The OpenAPI document the server serves (also committed as `openapi/openapi.json`); the
/// store is never touched.
pub fn openapi_document() -> serde_json::Value {
    router(AppState::new(Config::default())).1
}
