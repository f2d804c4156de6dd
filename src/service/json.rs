//! A JSON body extractor whose rejections are problems with the path of the bad field: a body
//! not declared as JSON is 415, syntax errors are 400, type and value errors (including
//! numbers beyond double range and duplicate keys) 422, an oversized body 413 and a body that
//! does not arrive in time 408.

use std::time::Duration;

use axum::body::Bytes;
use axum::extract::{FromRequest, Request};
use axum::http::{StatusCode, header};
use serde::Deserialize;
use serde::de::{DeserializeOwned, Error as _, MapAccess, SeqAccess, Visitor};
use serde_json::error::Category;
use serde_json::{Map, Number, Value};

use super::error::ApiError;
use crate::model::Invalid;
use crate::model::tagged;

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
        if !is_json(ct) {
            return Err(ApiError::UnsupportedMediaType(format!(
                "the body must be JSON, sent with `Content-Type: application/json` (got {}); \
                 with curl, use --json or -H 'content-type: application/json'",
                ct.map_or("none".to_string(), |c| format!("`{c}`"))
            )));
        }
        let read = Bytes::from_request(req, state);
        let bytes = match tokio::time::timeout(limits.timeout, read).await {
            Err(_) => return Err(ApiError::RequestTimeout(limits.timeout)),
            Ok(r) => r.map_err(|e| {
                if e.status() == StatusCode::PAYLOAD_TOO_LARGE {
                    ApiError::TooLarge(limits.max_bytes)
                } else {
                    ApiError::Malformed(e.body_text())
                }
            })?,
        };
        parse(&bytes).map(ApiJson)
    }
}

/// A JSON value read strictly: a key given twice in one object is an error, not last-wins.
struct Strict(Value);

impl<'de> Deserialize<'de> for Strict {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(StrictVisitor)
    }
}

struct StrictVisitor;

impl<'de> Visitor<'de> for StrictVisitor {
    type Value = Strict;

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("a JSON value")
    }
    fn visit_bool<E>(self, v: bool) -> Result<Strict, E> {
        Ok(Strict(Value::Bool(v)))
    }
    fn visit_i64<E>(self, v: i64) -> Result<Strict, E> {
        Ok(Strict(Value::Number(v.into())))
    }
    fn visit_u64<E>(self, v: u64) -> Result<Strict, E> {
        Ok(Strict(Value::Number(v.into())))
    }
    fn visit_f64<E: serde::de::Error>(self, v: f64) -> Result<Strict, E> {
        Number::from_f64(v)
            .map(|n| Strict(Value::Number(n)))
            .ok_or_else(|| E::custom("must be a finite number"))
    }
    fn visit_str<E>(self, v: &str) -> Result<Strict, E> {
        Ok(Strict(Value::String(v.to_string())))
    }
    fn visit_string<E>(self, v: String) -> Result<Strict, E> {
        Ok(Strict(Value::String(v)))
    }
    fn visit_unit<E>(self) -> Result<Strict, E> {
        Ok(Strict(Value::Null))
    }
    fn visit_none<E>(self) -> Result<Strict, E> {
        Ok(Strict(Value::Null))
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Strict, A::Error> {
        let mut out = Vec::with_capacity(seq.size_hint().unwrap_or(0).min(4096));
        while let Some(Strict(v)) = seq.next_element()? {
            out.push(v);
        }
        Ok(Strict(Value::Array(out)))
    }
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Strict, A::Error> {
        let mut out = Map::new();
        while let Some(key) = map.next_key::<String>()? {
            if out.contains_key(&key) {
                return Err(A::Error::custom(tagged::nested_message(
                    &key,
                    "this key appears twice in its object (the JSON would be ambiguous)",
                )));
            }
            let Strict(v) = map.next_value()?;
            out.insert(key, v);
        }
        Ok(Strict(Value::Object(out)))
    }
}

/// A data error at `outer`, whose message may carry a path inside it.
fn at_path(outer: &str, msg: &str) -> ApiError {
    let (path, message) = match tagged::split_nested(msg) {
        Some((p, m)) => (tagged::join(outer, p), m.to_string()),
        None => (tagged::join(outer, "."), tagged::strip_position(msg)),
    };
    ApiError::Invalid(Invalid::one(path, message))
}

/// Parses a body, naming the path of the first bad field. Two passes: the JSON itself (400 for
/// syntax; 422 with the path for a number beyond double range or a duplicate key), then the
/// typed content (422 with the path).
pub fn parse<T: DeserializeOwned>(bytes: &[u8]) -> Result<T, ApiError> {
    let mut de = serde_json::Deserializer::from_slice(bytes);
    let value = match serde_path_to_error::deserialize::<_, Strict>(&mut de) {
        Ok(Strict(v)) => {
            de.end()
                .map_err(|e| ApiError::Malformed(format!("the body is not valid JSON: {e}")))?;
            v
        }
        Err(e) => {
            let outer = e.path().to_string();
            let inner = e.into_inner();
            let msg = inner.to_string();
            return Err(if msg.starts_with("number out of range") {
                at_path(
                    &outer,
                    "must be a finite number (this one is beyond double range)",
                )
            } else if inner.classify() == Category::Data {
                at_path(&outer, &msg)
            } else {
                ApiError::Malformed(format!("the body is not valid JSON: {msg}"))
            });
        }
    };
    if !value.is_object() {
        return Err(ApiError::Invalid(Invalid::one(
            "(body)",
            "the body must be a JSON object",
        )));
    }
    from_value(value)
}

/// The typed content of a JSON value, naming the path of the first bad field.
pub fn from_value<T: DeserializeOwned>(value: Value) -> Result<T, ApiError> {
    serde_path_to_error::deserialize(value).map_err(|e| {
        let outer = e.path().to_string();
        let inner = e.into_inner();
        match inner.classify() {
            Category::Data => at_path(&outer, &inner.to_string()),
            _ => ApiError::Malformed(format!("the body is not valid JSON: {inner}")),
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn path_of(body: &str) -> (String, String) {
        match parse::<Value>(body.as_bytes()) {
            Err(ApiError::Invalid(inv)) => {
                let e = &inv.errors()[0];
                (e.path.clone(), e.message.clone())
            }
            other => panic!("{:?}", other.map(|_| ())),
        }
    }

    #[test]
    fn duplicate_keys_and_huge_numbers_are_named() {
        let (p, m) = path_of(r#"{"rotor": {"mass": 1, "mass": 2}}"#);
        assert_eq!(p, "rotor.mass");
        assert!(m.contains("twice"), "{m}");
        let (p, m) = path_of(r#"{"speeds": [1, 2, 1e999]}"#);
        assert_eq!(p, "speeds[2]");
        assert!(m.contains("finite"), "{m}");
    }

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
