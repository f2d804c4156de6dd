//! Model conversion: a rotor file of another program in, the Whirl rotor out. The conversion
//! is cheap and bounded by the body limit and the model limits (elements counted before
//! anything is built), so it needs no worker of the pool: it runs on a blocking thread of the
//! runtime (an 8 MB file, the default body limit, takes about 0.3 s).

use axum::Json;
use axum::extract::{FromRequest, Request, State};

use super::AppState;
use super::error::ApiError;
use super::json::limited_body;
use crate::model::api::Problem;
use crate::model::ross::{self, ConvertError, ConvertRossResponse};

/// The media type of a ROSS rotor file.
pub const TOML: &str = "application/toml";

/// Whether a `Content-Type` is TOML (`application/toml`, any parameters).
pub fn is_toml(content_type: Option<&str>) -> bool {
    content_type
        .and_then(|ct| ct.split(';').next())
        .is_some_and(|m| m.trim().eq_ignore_ascii_case(TOML))
}

/// A TOML body as text, read within the body limits: 415 when it is not declared as TOML, 413
/// past the size limit, 408 past the time limit, 400 when it is not UTF-8.
pub struct TomlText(pub String);

impl<S: Send + Sync> FromRequest<S> for TomlText {
    type Rejection = ApiError;

    async fn from_request(req: Request, state: &S) -> Result<Self, ApiError> {
        let bytes = limited_body(req, state, ApiError::MalformedToml, |ct| {
            is_toml(ct).then_some(()).ok_or_else(|| {
                ApiError::UnsupportedMediaType(format!(
                    "the body must be a ROSS rotor file, sent with `Content-Type: {TOML}` (got \
                     {}); with curl, use --data-binary @rotor.toml -H 'Content-Type: {TOML}'",
                    ct.map_or("none".to_string(), |c| format!("`{c}`"))
                ))
            })
        })
        .await?;
        let text = String::from_utf8(bytes.to_vec()).map_err(|e| {
            let (line, column) = ross::position(
                &String::from_utf8_lossy(&bytes),
                e.utf8_error().valid_up_to(),
            );
            ApiError::MalformedToml(format!(
                "the body is not UTF-8 text (TOML is): line {line}, column {column}"
            ))
        })?;
        Ok(TomlText(text))
    }
}

/// The request body: the file's bytes, TOML text.
#[derive(utoipa::ToSchema)]
#[schema(value_type = String, format = Binary)]
#[allow(dead_code)] // only read by the OpenAPI derive
pub(super) struct RossFileBody(String);

/// The errors of the conversion, as problem+json.
#[derive(utoipa::IntoResponses)]
#[allow(dead_code)] // only read by the OpenAPI derive
pub(super) enum ConvertErrors {
    #[response(
        status = 400,
        description = "Not TOML (the line and column in `detail`), or not UTF-8",
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
        description = "The body is not declared as TOML (Content-Type: application/toml)",
        content_type = "application/problem+json"
    )]
    NotToml(Problem),
    #[response(
        status = 422,
        description = "An element the converter cannot represent, or a bad value: `errors` \
                       names each by its TOML table (and key), with its line",
        content_type = "application/problem+json"
    )]
    Invalid(Problem),
}

/// Convert a ROSS rotor file into a Whirl rotor.
///
/// The body is the text of the file ROSS 2.3.0's `Rotor.save` wrote (TOML, `Content-Type:
/// application/toml`); the answer's `rotor` posts unchanged as the `rotor` of every analysis.
/// ROSS's node numbers are kept, nodes off the shaft included. Shaft elements (conical, with
/// sleeves on the same nodes, axial force, torque, proportional damping), disks, point masses,
/// bearings and seals (constant or tabulated, with ROSS's interpolation, linked to pedestals
/// by `n_link`) are converted, with their torsional and axial data (couplings, `kzz`, `czz`) and elements' options for the `motion` analyses. `warnings`
/// says what changed. An element a Whirl rotor cannot hold is a 422 naming its table.
#[utoipa::path(post, path = "/v1/convert/ross", tag = "models",
    request_body(content = inline(RossFileBody), content_type = "application/toml",
        description = "The file ROSS's `Rotor.save(\"rotor.toml\")` wrote"),
    responses(
        (status = 200, description = "The Whirl rotor and the conversion's warnings", body = ConvertRossResponse),
        ConvertErrors))]
pub async fn convert_ross(
    State(st): State<AppState>,
    TomlText(text): TomlText,
) -> Result<Json<ConvertRossResponse>, ApiError> {
    // Linear in the body, but a body of megabytes takes a few hundred milliseconds: off the
    // async runtime's threads.
    let limits = st.config.limits();
    let converted = tokio::task::spawn_blocking(move || ross::convert(&text, &limits))
        .await
        .map_err(|e| ApiError::Internal(format!("the conversion stopped: {e}")))?
        .map_err(|e| match e {
            ConvertError::Malformed(d) => ApiError::MalformedToml(d),
            ConvertError::Invalid(i) => ApiError::Invalid(i),
        })?;
    Ok(Json(ConvertRossResponse {
        rotor: converted.rotor,
        warnings: converted.warnings,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn toml_media_types() {
        assert!(is_toml(Some("application/toml")));
        assert!(is_toml(Some("Application/TOML; charset=utf-8")));
        assert!(!is_toml(Some("application/json")));
        assert!(!is_toml(Some("text/plain")));
        assert!(!is_toml(None));
    }
}
