//! The OpenAPI document's frame; paths and schemas come from the handlers' annotations, and
//! [`for_clients`] finishes the assembled document so that client generators can use it.
//!
//! utoipa describes serde's internally tagged enums as untagged `oneOf`s of inline `allOf`s,
//! leaves a job's `input` and result untyped, and has no place for request examples taken
//! from `examples/`. Generators (openapi-python-client, openapi-generator, openapi-typescript)
//! then drop endpoints or type valid bodies as empty objects. The pass in [`clients`] rewrites
//! those parts of the document; the wire format does not change (`.ci/clients` checks the
//! committed document with every generator).

mod clients;
mod examples;

use utoipa::OpenApi;

pub use clients::for_clients;

#[derive(OpenApi)]
#[openapi(
    info(
        title = "Whirl",
        description = "Rotordynamics computation service: poles, Campbell diagrams and stability \
thresholds of rotors with hysteretic damping treated properly (hysteretic, equivalent viscous and \
nonviscous models, rotating and nonrotating apart). SI units; speeds and frequencies in rad/s. \
Errors are application/problem+json with the path of every bad field.",
        license(name = "MIT", identifier = "MIT")
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
