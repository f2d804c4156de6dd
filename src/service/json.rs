//! A JSON body extractor whose rejections are problems with the path of the bad field: a body
//! not declared as JSON is 415, syntax errors are 400, type and value errors (including
//! numbers beyond double range and duplicate keys) 422, an oversized body 413 and a body that
//! does not arrive in time 408. The body itself is read by `model::json`.

use std::time::Duration;

use axum::body::Bytes;
use axum::extract::{FromRequest, Request};
use axum::http::{StatusCode, header};
use serde::de::DeserializeOwned;

use super::error::ApiError;
use crate::model::json::parse;

/// `Json<T>` with problem+json rejections.
pub struct ApiJson<T>(pub T);

/// Body limits, for the extractor.
#[derive(Clone, Copy)]
pub struct BodyLimits {
    pub max_bytes: usize,
    pub timeout: Duration,
}

/// Whether a `Content-Type` is JSON (`application/json` or a `+json` type).
pub fn is_json(content_type: Option<&str>) -> bool {
    content_type
        .and_then(|ct| ct.split(';').next())
        .map(|m| m.trim().to_ascii_lowercase())
        .is_some_and(|m| {
            m == "application/json" || (m.starts_with("application/") && m.ends_with("+json"))
        })
}

impl<S: Send + Sync, T: DeserializeOwned> FromRequest<S> for ApiJson<T> {
    type Rejection = ApiError;

    async fn from_request(req: Request, state: &S) -> Result<Self, ApiError> {
        let bytes = limited_body(req, state, ApiError::Malformed, |ct| {
            is_json(ct).then_some(()).ok_or_else(|| {
                ApiError::UnsupportedMediaType(format!(
                    "the body must be JSON, sent with `Content-Type: application/json` (got {}); \
                     with curl, use --json or -H 'content-type: application/json'",
                    ct.map_or("none".to_string(), |c| format!("`{c}`"))
                ))
            })
        })
        .await?;
        Ok(parse(&bytes).map(ApiJson)?)
    }
}

/// A request's body within the [`BodyLimits`]: `media` refuses a wrong `Content-Type` (before
/// anything is read), then 413 past the size limit, 408 past the time limit, and `malformed`
/// for a body that could not be read.
pub async fn limited_body<S: Send + Sync>(
    req: Request,
    state: &S,
    malformed: fn(String) -> ApiError,
    media: impl FnOnce(Option<&str>) -> Result<(), ApiError>,
) -> Result<Bytes, ApiError> {
    let limits = req
        .extensions()
        .get::<BodyLimits>()
        .copied()
        .unwrap_or(BodyLimits {
            max_bytes: 0,
            timeout: Duration::from_secs(30),
        });
    let ct = req
        .headers()
        .get(header::CONTENT_TYPE)
        .and_then(|v| v.to_str().ok());
    media(ct)?;
    let read = Bytes::from_request(req, state);
    match tokio::time::timeout(limits.timeout, read).await {
        Err(_) => Err(ApiError::RequestTimeout(limits.timeout)),
        Ok(r) => r.map_err(|e| {
            if e.status() == StatusCode::PAYLOAD_TOO_LARGE {
                ApiError::TooLarge(limits.max_bytes)
            } else {
                malformed(e.body_text())
            }
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn json_media_types() {
        assert!(is_json(Some("application/json")));
        assert!(is_json(Some("Application/JSON; charset=utf-8")));
        assert!(is_json(Some("application/problem+json")));
        assert!(!is_json(Some("application/x-www-form-urlencoded")));
        assert!(!is_json(Some("text/plain")));
        assert!(!is_json(None));
    }
}
