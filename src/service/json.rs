//! A JSON body extractor whose rejections are problems with the path of the bad field:
//! syntax errors are 400, type and value errors 422, an oversized body 413.

use axum::body::Bytes;
use axum::extract::{FromRequest, Request};
use axum::http::StatusCode;
use serde::de::DeserializeOwned;
use serde_json::error::Category;

use super::error::ApiError;
use crate::model::Invalid;
use crate::model::tagged;

/// `Json<T>` with problem+json rejections.
pub struct ApiJson<T>(pub T);

impl<S: Send + Sync, T: DeserializeOwned> FromRequest<S> for ApiJson<T> {
    type Rejection = ApiError;

    async fn from_request(req: Request, state: &S) -> Result<Self, ApiError> {
        let limit = req
            .extensions()
            .get::<BodyLimit>()
            .map(|l| l.0)
            .unwrap_or(0);
        let bytes = Bytes::from_request(req, state).await.map_err(|e| {
            if e.status() == StatusCode::PAYLOAD_TOO_LARGE {
                ApiError::TooLarge(limit)
            } else {
                ApiError::Malformed(e.body_text())
            }
        })?;
        parse(&bytes).map(ApiJson)
    }
}

/// The configured body limit, for the 413 message.
#[derive(Clone, Copy)]
pub struct BodyLimit(pub usize);

/// Parses a body, naming the path of the first bad field. Two passes: JSON syntax first (400),
/// then the typed content (422 with the path).
pub fn parse<T: DeserializeOwned>(bytes: &[u8]) -> Result<T, ApiError> {
    let value: serde_json::Value = serde_json::from_slice(bytes).map_err(|e| {
        let msg = e.to_string();
        if msg.starts_with("number out of range") {
            // Valid JSON syntax whose number is not a finite double (1e999): a bad value.
            ApiError::Invalid(Invalid::one(
                "(body)",
                format!("a number is not a finite double: {msg}"),
            ))
        } else {
            ApiError::Malformed(format!("the body is not valid JSON: {msg}"))
        }
    })?;
    if !value.is_object() {
        return Err(ApiError::Invalid(Invalid::one(
            "(body)",
            "the body must be a JSON object",
        )));
    }
    serde_path_to_error::deserialize(value).map_err(|e| {
        let outer = e.path().to_string();
        let inner = e.into_inner();
        match inner.classify() {
            Category::Data => {
                let msg = inner.to_string();
                let (path, message) = match tagged::split_nested(&msg) {
                    Some((p, m)) => (tagged::join(&outer, p), m.to_string()),
                    None => (tagged::join(&outer, "."), tagged::strip_position(&msg)),
                };
                ApiError::Invalid(Invalid::one(path, message))
            }
            _ => ApiError::Malformed(format!("the body is not valid JSON: {inner}")),
        }
    })
}
