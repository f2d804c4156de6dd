//! The HTTP service: the only layer that knows HTTP.
//!
//! [`app`] builds the whole router from a [`Config`], so tests drive it in process without a
//! socket. Requests are validated on the async runtime (cheap); every numerical analysis runs
//! on the blocking [`pool::WorkerPool`], so a long sweep never stalls other requests.

pub mod config;
pub mod convert;
pub mod error;
pub mod jobs;
pub mod json;
pub mod metrics;
pub mod openapi;
pub mod plot;
pub mod pool;
pub mod routes;
pub mod task;

use std::sync::Arc;

use axum::Router;
use axum::extract::DefaultBodyLimit;
use tower_http::trace::TraceLayer;
use utoipa_axum::router::OpenApiRouter;
use utoipa_swagger_ui::SwaggerUi;

pub use config::Config;
pub use error::ApiError;

/// Shared by all handlers.
#[derive(Clone)]
pub struct AppState {
    pub config: Arc<Config>,
    pub pool: Arc<pool::WorkerPool>,
    pub jobs: Arc<jobs::Jobs>,
    pub metrics: Arc<metrics::Metrics>,
}

impl AppState {
    pub fn new(config: Config) -> Self {
        // One problem per core: faer stays sequential, sweeps parallelise over speeds.
        crate::linalg::set_sequential();
        let limits = jobs::JobLimits {
            retention: std::time::Duration::from_secs(config.job_retention),
            max_finished: config.max_finished_jobs,
            time_limit: std::time::Duration::from_secs(config.job_time_limit),
        };
        AppState {
            pool: Arc::new(pool::WorkerPool::new(config.workers, config.queue)),
            jobs: Arc::new(jobs::Jobs::new(limits)),
            metrics: Arc::new(metrics::Metrics::default()),
            config: Arc::new(config),
        }
    }
}

/// The router with its OpenAPI document (`split_for_parts` keeps them in sync by construction).
pub fn router(state: AppState) -> (Router, utoipa::openapi::OpenApi) {
    let body_limit = state.config.max_body_bytes;
    let (router, api) = OpenApiRouter::with_openapi(openapi::base())
        .routes(utoipa_axum::routes!(routes::healthz))
        .routes(utoipa_axum::routes!(routes::readyz))
        .routes(utoipa_axum::routes!(routes::modal))
        .routes(utoipa_axum::routes!(routes::campbell))
        .routes(utoipa_axum::routes!(routes::stability))
        .routes(utoipa_axum::routes!(routes::damping_matrices))
        .routes(utoipa_axum::routes!(routes::time_response))
        .routes(utoipa_axum::routes!(routes::unbalance_response))
        .routes(utoipa_axum::routes!(routes::submit_job))
        .routes(utoipa_axum::routes!(routes::get_job, routes::cancel_job))
        .routes(utoipa_axum::routes!(routes::job_result))
        .routes(utoipa_axum::routes!(routes::metrics))
        .with_state(state.clone())
        .split_for_parts();
    let request_id = axum::http::HeaderName::from_static("x-request-id");
    let router = router
        .merge(SwaggerUi::new("/docs").url("/openapi.json", api.clone()))
        .route_layer(axum::middleware::from_fn_with_state(state, metrics::track))
        .fallback(routes::not_found)
        .layer(DefaultBodyLimit::max(body_limit))
        .layer(axum::Extension(json::BodyLimit(body_limit)))
        .layer(
            TraceLayer::new_for_http().make_span_with(|req: &axum::http::Request<_>| {
                let id = req
                    .headers()
                    .get("x-request-id")
                    .and_then(|v| v.to_str().ok())
                    .unwrap_or("-");
                tracing::info_span!("request", method = %req.method(), uri = %req.uri(), request_id = %id)
            })
            .on_response(tower_http::trace::DefaultOnResponse::new().level(tracing::Level::INFO)),
        )
        .layer(tower_http::request_id::PropagateRequestIdLayer::new(request_id.clone()))
        .layer(tower_http::request_id::SetRequestIdLayer::new(request_id, RequestIds::default()));
    (router, api)
}

/// Request ids `x-request-id` (kept when the client sends one), in logs and responses.
#[derive(Clone, Default)]
struct RequestIds(Arc<std::sync::atomic::AtomicU64>);

impl tower_http::request_id::MakeRequestId for RequestIds {
    fn make_request_id<B>(
        &mut self,
        _: &axum::http::Request<B>,
    ) -> Option<tower_http::request_id::RequestId> {
        let n = self.0.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        axum::http::HeaderValue::from_str(&format!("{:x}-{n}", std::process::id()))
            .ok()
            .map(tower_http::request_id::RequestId::new)
    }
}

/// The application.
pub fn app(config: Config) -> Router {
    router(AppState::new(config)).0
}

/// The application and its state (for the binary's graceful shutdown of jobs).
pub fn app_with_state(config: Config) -> (Router, AppState) {
    let state = AppState::new(config);
    (router(state.clone()).0, state)
}

/// The OpenAPI document the server serves (also committed as `openapi/openapi.json`).
pub fn openapi_document() -> utoipa::openapi::OpenApi {
    router(AppState::new(Config::default())).1
}
