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

use utoipa::openapi::security::{Http, HttpAuthScheme, SecurityRequirement, SecurityScheme};
use utoipa::openapi::{Content, Ref, RefOr, ResponseBuilder};

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
        (name = "models", description = "Rotor models from other programs' files: ROSS's `Rotor.save`"),
        (name = "jobs", description = "Asynchronous analyses: submit, poll, fetch, cancel"),
        (name = "studies", description = "One analysis over a grid or random samples of its parameters, each sample a job"),
        (name = "operations", description = "Health, readiness and metrics")
    )
)]
struct ApiDoc;

pub fn base() -> utoipa::openapi::OpenApi {
    ApiDoc::openapi()
}

/// The bearer token (`WHIRL_API_TOKEN`) in the document: a `bearer` scheme, required by every
/// operation but the probes when the server has a token (`security: [{bearer: []}, {}]`: the
/// token, or none where none is set), and the 401 each of them may then answer.
pub fn secured(mut api: utoipa::openapi::OpenApi) -> utoipa::openapi::OpenApi {
    let mut scheme = Http::new(HttpAuthScheme::Bearer);
    scheme.description = Some(
        "`Authorization: Bearer <token>`, when the server is started with WHIRL_API_TOKEN \
         (every path but /healthz and /readyz)"
            .into(),
    );
    api.components
        .get_or_insert_with(Default::default)
        .add_security_scheme("bearer", SecurityScheme::Http(scheme));
    api.security = Some(vec![
        SecurityRequirement::new("bearer", Vec::<String>::new()),
        SecurityRequirement::default(),
    ]);
    let unauthorized = ResponseBuilder::new()
        .description(
            "The bearer token is missing or not the server's (only with WHIRL_API_TOKEN set)",
        )
        .content(
            "application/problem+json",
            Content::new(Some(RefOr::Ref(Ref::from_schema_name("Problem")))),
        )
        .build();
    for (path, item) in api.paths.paths.iter_mut() {
        let probe = matches!(path.as_str(), "/healthz" | "/readyz");
        for op in [
            &mut item.get,
            &mut item.post,
            &mut item.put,
            &mut item.patch,
            &mut item.delete,
        ]
        .into_iter()
        .flatten()
        {
            if probe {
                op.security = Some(vec![SecurityRequirement::default()]);
            } else {
                op.responses
                    .responses
                    .insert("401".into(), RefOr::T(unauthorized.clone()));
            }
        }
    }
    api
}
