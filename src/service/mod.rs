//! The HTTP service: the only layer that knows HTTP.
//!
//! [`app`] builds the whole router from a [`Config`], so tests drive it in process without a
//! socket. Requests are validated on the async runtime (cheap); every numerical analysis runs
//! on the blocking [`pool::WorkerPool`], so a long sweep never stalls other requests.

pub mod config;
pub mod convert;
pub mod error;
pub mod json;
pub mod openapi;
pub mod pool;
pub mod routes;

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
}

impl AppState {
    pub fn new(config: Config) -> Self {
        // One problem per core: faer stays sequential, sweeps parallelise over speeds.
        crate::linalg::set_sequential();
        AppState {
            pool: Arc::new(pool::WorkerPool::new(config.workers, config.queue)),
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
        .with_state(state)
        .split_for_parts();
    let router = router
        .merge(SwaggerUi::new("/docs").url("/openapi.json", api.clone()))
        .fallback(routes::not_found)
        .layer(DefaultBodyLimit::max(body_limit))
        .layer(axum::Extension(json::BodyLimit(body_limit)))
        .layer(TraceLayer::new_for_http());
    (router, api)
}

/// The application.
pub fn app(config: Config) -> Router {
    router(AppState::new(config)).0
}

/// The OpenAPI document the server serves (also committed as `openapi/openapi.json`).
pub fn openapi_document() -> utoipa::openapi::OpenApi {
    router(AppState::new(Config::default())).1
}
