//! The OpenAPI document's frame; paths and schemas come from the handlers' annotations.

use utoipa::OpenApi;

#[derive(OpenApi)]
#[openapi(
    info(
        title = "Whirl",
        description = "Rotordynamics computation service: poles, Campbell diagrams and stability \
thresholds of rotors with hysteretic damping treated properly (hysteretic, equivalent viscous and \
nonviscous models, rotating and nonrotating apart). SI units; speeds and frequencies in rad/s. \
Errors are application/problem+json with the path of every bad field.",
        license(name = "MIT")
    ),
    tags(
        (name = "analyses", description = "Eigenvalue analyses of a rotor model"),
        (name = "audit", description = "The analyses of an API 684 / API 617 rotordynamic audit, and the report"),
        (name = "jobs", description = "Asynchronous analyses: submit, poll, fetch, cancel"),
        (name = "operations", description = "Health, readiness and metrics")
    )
)]
struct ApiDoc;

pub fn base() -> utoipa::openapi::OpenApi {
    ApiDoc::openapi()
}
