//! [`ApiError`] over HTTP: its problem as `application/problem+json` (RFC 9457), with its
//! status code, and `Retry-After`, `Allow` or `Connection: close` where they apply.

use axum::http::{HeaderValue, StatusCode, header};
use axum::response::{IntoResponse, Response};

pub use crate::answer::error::{ApiError, RETRY_AFTER_SECONDS};

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        if let ApiError::Internal(d) = &self {
            tracing::error!(detail = %d, "internal error");
        }
        let status =
            StatusCode::from_u16(self.status()).unwrap_or(StatusCode::INTERNAL_SERVER_ERROR);
        let body = serde_json::to_vec(&self.problem()).unwrap_or_default();
        let mut resp = (status, body).into_response();
        let h = resp.headers_mut();
        h.insert(
            header::CONTENT_TYPE,
            HeaderValue::from_static("application/problem+json"),
        );
        if let ApiError::Unavailable(d) = &self {
            tracing::error!(detail = %d, "job store unavailable");
        }
        if matches!(
            self,
            ApiError::Busy | ApiError::TimeLimit(_) | ApiError::Unavailable(_)
        ) {
            h.insert(header::RETRY_AFTER, HeaderValue::from(RETRY_AFTER_SECONDS));
        }
        if let ApiError::MethodNotAllowed(allow) = &self
            && let Ok(v) = HeaderValue::from_str(allow)
        {
            h.insert(header::ALLOW, v);
        }
        if matches!(self, ApiError::TooLarge(_) | ApiError::RequestTimeout(_)) {
            // The rest of the body is not read: the connection cannot be reused.
            h.insert(header::CONNECTION, HeaderValue::from_static("close"));
        }
        resp
    }
}
