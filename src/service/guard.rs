//! What stands between a request and the handlers: the bearer token (`WHIRL_API_TOKEN`), the
//! client's request id bounded, job ids checked before they reach a store, security headers on
//! every answer, and every error answered as problem+json (including the framework's own
//! rejections, which are `text/plain`).

use axum::body::Body;
use axum::extract::{FromRequestParts, Path, Request, State};
use axum::http::request::Parts;
use axum::http::{HeaderValue, StatusCode, header};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};
use sha2::{Digest, Sha256};

use super::error::ApiError;
use crate::model::api::Problem;

/// The API token, kept as its SHA-256 digest (never printed, never compared byte by byte).
#[derive(Clone)]
pub struct ApiToken([u8; 32]);

impl std::fmt::Debug for ApiToken {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("ApiToken(..)")
    }
}

/// Shortest token accepted (a guessable token is no lock).
pub const MIN_TOKEN_CHARS: usize = 16;

impl ApiToken {
    /// A token of at least [`MIN_TOKEN_CHARS`] visible ASCII characters (it travels in a header).
    pub fn new(token: &str) -> Result<Self, String> {
        if token.len() < MIN_TOKEN_CHARS || !token.bytes().all(|b| b.is_ascii_graphic()) {
            return Err(format!(
                "WHIRL_API_TOKEN: expected at least {MIN_TOKEN_CHARS} visible ASCII characters \
                 (no spaces), e.g. the output of `openssl rand -hex 32`"
            ));
        }
        Ok(ApiToken(Sha256::digest(token.as_bytes()).into()))
    }

    /// Whether `given` is the token, in a time that depends on neither: the digests are
    /// compared in full (a mismatch at the first byte takes as long as one at the last), and
    /// the time of hashing `given` tells nothing about the token.
    pub fn matches(&self, given: &[u8]) -> bool {
        let d: [u8; 32] = Sha256::digest(given).into();
        let diff = d
            .iter()
            .zip(&self.0)
            .fold(0u8, |acc, (a, b)| std::hint::black_box(acc | (a ^ b)));
        diff == 0
    }
}

/// Paths open without the token: the probes (an orchestrator has no token), and the API's
/// documentation (the same for every deployment, committed with the code).
pub fn open_path(path: &str) -> bool {
    matches!(path, "/healthz" | "/readyz" | "/openapi.json")
        || path == "/docs"
        || path.starts_with("/docs/")
}

/// With a token configured, every request outside [`open_path`] needs
/// `Authorization: Bearer <token>`: else 401 problem+json with `WWW-Authenticate`.
pub async fn require_token(
    State(token): State<Option<ApiToken>>,
    req: Request,
    next: Next,
) -> Response {
    let Some(token) = token else {
        return next.run(req).await;
    };
    if open_path(req.uri().path()) {
        return next.run(req).await;
    }
    let given = req
        .headers()
        .get(header::AUTHORIZATION)
        .map(|v| v.as_bytes())
        .and_then(|v| {
            let (scheme, rest) = v.split_at(v.iter().position(|b| *b == b' ')?);
            scheme
                .eq_ignore_ascii_case(b"bearer")
                .then(|| rest.trim_ascii())
        });
    let verdict = given.map(|t| token.matches(t));
    match verdict {
        Some(true) => next.run(req).await,
        Some(false) => unauthorized("the bearer token is not the one this server accepts"),
        None => unauthorized(
            "this server requires `Authorization: Bearer <token>` (WHIRL_API_TOKEN) on every \
             path but /healthz, /readyz and the documentation",
        ),
    }
}

fn unauthorized(detail: &str) -> Response {
    let mut resp = problem_response(Problem {
        kind: "/problems/unauthorized".into(),
        title: "Unauthorized".into(),
        status: 401,
        detail: detail.into(),
        errors: vec![],
    });
    resp.headers_mut().insert(
        header::WWW_AUTHENTICATE,
        HeaderValue::from_static("Bearer realm=\"whirl\""),
    );
    resp
}

fn problem_response(p: Problem) -> Response {
    let status = StatusCode::from_u16(p.status).unwrap_or(StatusCode::INTERNAL_SERVER_ERROR);
    let body = serde_json::to_vec(&p).unwrap_or_default();
    let mut resp = (status, body).into_response();
    resp.headers_mut().insert(
        header::CONTENT_TYPE,
        HeaderValue::from_static("application/problem+json"),
    );
    resp
}

/// Longest client request id kept.
pub const MAX_REQUEST_ID: usize = 128;

/// Whether a client's `x-request-id` is kept as is: 1 to [`MAX_REQUEST_ID`] letters, digits or
/// `-_.:/+=@` (UUIDs, trace ids, base64). Anything else (quotes, braces, spaces, control
/// characters) could forge log lines, and a long id would be echoed and logged in full.
pub fn acceptable_request_id(id: &[u8]) -> bool {
    (1..=MAX_REQUEST_ID).contains(&id.len())
        && id
            .iter()
            .all(|b| b.is_ascii_alphanumeric() || b"-_.:/+=@".contains(b))
}

/// Drops an unacceptable client request id (every one given, if several): a fresh UUIDv7 is
/// made in its place.
pub async fn bound_request_id(mut req: Request) -> Request {
    let headers = req.headers_mut();
    let ids: Vec<&HeaderValue> = headers.get_all("x-request-id").iter().collect();
    if ids.len() > 1 || ids.iter().any(|v| !acceptable_request_id(v.as_bytes())) {
        headers.remove("x-request-id");
    }
    req
}

/// A job id from the path, checked before any store sees it: the canonical UUID form that
/// `POST /v1/jobs` hands out. Anything else (a NUL, invalid UTF-8, another spelling) names no
/// job: 404, without a query.
pub struct JobId(pub String);

/// Whether `id` is a job id as this service writes them.
pub fn is_job_id(id: &str) -> bool {
    id.len() == 36 && uuid::Uuid::try_parse(id).is_ok_and(|u| u.hyphenated().to_string() == id)
}

impl<S: Send + Sync> FromRequestParts<S> for JobId {
    type Rejection = ApiError;

    async fn from_request_parts(parts: &mut Parts, state: &S) -> Result<Self, ApiError> {
        match Path::<String>::from_request_parts(parts, state).await {
            Ok(Path(id)) if is_job_id(&id) => Ok(JobId(id)),
            _ => Err(ApiError::NotFound(
                "no such job: a job id is the UUID that POST /v1/jobs answered \
                 (e.g. 01890a5d-ac96-774b-bcce-b302099a8057)"
                    .into(),
            )),
        }
    }
}

/// The Content-Security-Policy of the documentation (Swagger UI: its own scripts and styles,
/// inline styles it sets, data: icons, the OpenAPI document fetched from here).
const CSP_DOCS: &str = "default-src 'none'; script-src 'self'; style-src 'self' 'unsafe-inline'; \
    img-src 'self' data:; connect-src 'self'; base-uri 'none'; form-action 'none'; \
    frame-ancestors 'none'";
/// The Content-Security-Policy of everything else (JSON, CSV, SVG plots, the HTML report):
/// no script, no fetch, no frame; inline styles only (the report's and the plots').
const CSP_API: &str = "default-src 'none'; style-src 'unsafe-inline'; img-src data:; \
    base-uri 'none'; form-action 'none'; frame-ancestors 'none'";

/// `X-Content-Type-Options: nosniff` and a Content-Security-Policy on every answer; every error
/// as problem+json (a rejection of the framework's, `text/plain`, is wrapped in a problem
/// with the same status and its text as the detail).
pub async fn harden(req: Request, next: Next) -> Response {
    let docs = req.uri().path() == "/docs" || req.uri().path().starts_with("/docs/");
    let mut resp = next.run(req).await;
    let status = resp.status();
    let plain = resp
        .headers()
        .get(header::CONTENT_TYPE)
        .and_then(|v| v.to_str().ok())
        .is_none_or(|ct| ct.starts_with("text/plain"));
    if (status.is_client_error() || status.is_server_error()) && plain {
        resp = as_problem(resp).await;
    }
    let h = resp.headers_mut();
    h.insert(
        header::X_CONTENT_TYPE_OPTIONS,
        HeaderValue::from_static("nosniff"),
    );
    h.insert(
        header::CONTENT_SECURITY_POLICY,
        HeaderValue::from_static(if docs { CSP_DOCS } else { CSP_API }),
    );
    resp
}

/// A plain-text error answer as a problem (its headers kept, but its type and length).
async fn as_problem(resp: Response) -> Response {
    let (mut parts, body) = resp.into_parts();
    // The framework's rejections are a line of text; read at most a little of it.
    let text = match axum::body::to_bytes(body, 4096).await {
        Ok(b) => String::from_utf8_lossy(&b).trim().to_string(),
        Err(_) => String::new(),
    };
    let status = parts.status;
    let title = status.canonical_reason().unwrap_or("Error");
    let kind = title.to_ascii_lowercase().replace(' ', "-");
    let p = Problem {
        kind: format!("/problems/{kind}"),
        title: title.into(),
        status: status.as_u16(),
        detail: if text.is_empty() {
            title.to_string()
        } else {
            text
        },
        errors: vec![],
    };
    let body = serde_json::to_vec(&p).unwrap_or_default();
    parts.headers.remove(header::CONTENT_LENGTH);
    parts.headers.insert(
        header::CONTENT_TYPE,
        HeaderValue::from_static("application/problem+json"),
    );
    Response::from_parts(parts, Body::from(body))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tokens_request_ids_and_job_ids() {
        let t = ApiToken::new("0123456789abcdef-secret").unwrap();
        assert!(t.matches(b"0123456789abcdef-secret"));
        assert!(!t.matches(b"0123456789abcdef-secreT"));
        assert!(!t.matches(b""));
        assert!(ApiToken::new("short").is_err());
        assert!(ApiToken::new("has a space in it, long enough").is_err());
        assert_eq!(format!("{t:?}"), "ApiToken(..)");
        assert!(acceptable_request_id(
            b"01890a5d-ac96-774b-bcce-b302099a8057"
        ));
        assert!(acceptable_request_id(
            b"00-4bf92f3577b34da6a3ce929d0e0e4736-01"
        ));
        assert!(!acceptable_request_id(b"a\"}{\"level\":\"ERROR"));
        assert!(!acceptable_request_id(&[b'a'; MAX_REQUEST_ID + 1]));
        assert!(!acceptable_request_id(b""));
        assert!(is_job_id("01890a5d-ac96-774b-bcce-b302099a8057"));
        assert!(!is_job_id("01890A5D-AC96-774B-BCCE-B302099A8057"));
        assert!(!is_job_id("01890a5dac96774bbcceb302099a8057"));
        assert!(!is_job_id("01890a5d-ac96-774b-bcce-b302099a805\0"));
    }
}
