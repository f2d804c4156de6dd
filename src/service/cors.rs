//! Cross-origin requests from browsers (CORS), for the origins in `WHIRL_CORS_ORIGINS` only.
//!
//! With no origins configured (the default) there is no CORS layer at all: a browser page on
//! another origin cannot read any answer, and `OPTIONS` stays a 405. With origins, tower-http's
//! `CorsLayer` answers every `OPTIONS` as a preflight, for any path (granting nothing to an
//! origin not listed), and marks the answers to those origins readable, with the headers a client needs exposed
//! (`Location` of a job, `ETag`, `Retry-After`, `Link` of a job listing, `x-request-id`).

use std::time::Duration;

use axum::http::{HeaderName, HeaderValue, Method, header};
use tower_http::cors::{AllowOrigin, CorsLayer};

/// How long a browser may cache a preflight's answer.
const MAX_AGE: Duration = Duration::from_secs(600);

/// The origins allowed: none, a list, or any (`*`, for a public, unauthenticated service).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub enum Origins {
    #[default]
    None,
    Any,
    List(Vec<String>),
}

impl Origins {
    /// `WHIRL_CORS_ORIGINS`: `*`, or origins separated by commas
    /// (`https://app.example.com,http://localhost:5173`), each a scheme, a host and maybe a
    /// port, as a browser sends it in `Origin`.
    pub fn parse(text: &str) -> Result<Self, String> {
        let text = text.trim();
        if text.is_empty() {
            return Ok(Origins::None);
        }
        if text == "*" {
            return Ok(Origins::Any);
        }
        let mut list = vec![];
        for o in text.split(',').map(str::trim).filter(|o| !o.is_empty()) {
            let rest = o
                .strip_prefix("https://")
                .or_else(|| o.strip_prefix("http://"))
                .ok_or_else(|| {
                    format!("WHIRL_CORS_ORIGINS: {o:?} must start with http:// or https://")
                })?;
            let host_ok = !rest.is_empty()
                && rest
                    .bytes()
                    .all(|b| b.is_ascii_alphanumeric() || b".-:[]".contains(&b));
            if !host_ok {
                return Err(format!(
                    "WHIRL_CORS_ORIGINS: {o:?} is not an origin (scheme://host[:port], no path or \
                     trailing slash)"
                ));
            }
            list.push(o.to_ascii_lowercase());
        }
        Ok(Origins::List(list))
    }
}

/// The CORS layer for `origins`; `None` when no origin may call.
pub fn layer(origins: &Origins) -> Option<CorsLayer> {
    let allow = match origins {
        Origins::None => return None,
        Origins::Any => AllowOrigin::any(),
        Origins::List(list) => AllowOrigin::list(
            list.iter()
                .filter_map(|o| HeaderValue::from_str(o).ok())
                .collect::<Vec<_>>(),
        ),
    };
    Some(
        CorsLayer::new()
            .allow_origin(allow)
            .allow_methods([Method::GET, Method::HEAD, Method::POST, Method::DELETE])
            .allow_headers([
                header::CONTENT_TYPE,
                header::ACCEPT,
                header::AUTHORIZATION,
                header::IF_NONE_MATCH,
                HeaderName::from_static("idempotency-key"),
                HeaderName::from_static("x-request-id"),
            ])
            .expose_headers([
                header::LOCATION,
                header::ETAG,
                header::RETRY_AFTER,
                header::LINK,
                HeaderName::from_static("x-request-id"),
                HeaderName::from_static("idempotent-replayed"),
            ])
            .max_age(MAX_AGE),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn origins() {
        assert_eq!(Origins::parse("").unwrap(), Origins::None);
        assert_eq!(Origins::parse(" * ").unwrap(), Origins::Any);
        assert_eq!(
            Origins::parse("https://App.example.com, http://localhost:5173").unwrap(),
            Origins::List(vec![
                "https://app.example.com".into(),
                "http://localhost:5173".into()
            ])
        );
        assert!(Origins::parse("app.example.com").is_err());
        assert!(Origins::parse("https://app.example.com/").is_err());
        assert!(Origins::parse("https://a.com/path").is_err());
    }
}
