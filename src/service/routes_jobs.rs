//! The job listing (`GET /v1/jobs`), and what `POST /v1/jobs` needs for its
//! `Idempotency-Key`.

use axum::Json;
use axum::extract::rejection::QueryRejection;
use axum::extract::{Query, State};
use axum::http::{HeaderMap, HeaderValue, header};
use axum::response::{IntoResponse, Response};
use serde_json::Value;
use sha2::{Digest, Sha256};

use super::AppState;
use super::error::ApiError;
use super::problems::Base;
use crate::jobs::store::Filter;
use crate::model::Invalid;
use crate::model::api::{AnalysisName, JobList, JobRequest, JobStatus, Problem};

/// Jobs per page when `limit` is not given, and at most.
const PAGE: u32 = 20;
const MAX_PAGE: u32 = 100;
/// Longest `Idempotency-Key`.
const MAX_KEY: usize = 255;

/// The filters and the page of `GET /v1/jobs` (for the OpenAPI document; read by [`filter`]).
#[derive(utoipa::IntoParams)]
#[into_params(parameter_in = Query)]
#[allow(dead_code)]
pub struct JobQuery {
    /// Only jobs in this state.
    status: Option<JobStatus>,
    /// Only jobs of this analysis.
    analysis: Option<AnalysisName>,
    /// Jobs per page, 1 to 100 (default 20).
    #[param(minimum = 1, maximum = 100)]
    limit: Option<u32>,
    /// Only jobs older than this one (a job id: the last of the previous page; `next` gives it).
    before: Option<String>,
}

/// List jobs, newest first.
///
/// Every job kept (queued, running, and finished within the retention), over all replicas,
/// filtered by `status` and `analysis`, a page at a time: `next` (and `Link: rel="next"`) is
/// the URL of the next page, absent on the last one.
#[utoipa::path(get, path = "/v1/jobs", tag = "jobs", params(JobQuery),
    responses(
        (status = 200, description = "A page of jobs", body = JobList,
         headers(("Link" = String, description = "`<next page>; rel=\"next\"` unless this is the last page"))),
        (status = 422, description = "A bad filter or page (`errors` names the parameter)", body = Problem, content_type = "application/problem+json"),
        (status = 503, description = "The job store is unreachable; see Retry-After", body = Problem, content_type = "application/problem+json")))]
pub async fn list_jobs(
    State(st): State<AppState>,
    base: Base,
    query: Result<Query<Vec<(String, String)>>, QueryRejection>,
) -> Result<Response, ApiError> {
    let Query(pairs) = query.map_err(|e| Invalid::one("(query)", e.body_text()))?;
    let mut filter = filter(&pairs)?;
    let limit = filter.limit;
    // One more than the page: whether there is a next page.
    filter.limit += 1;
    let mut jobs = st.jobs.list(&filter).await?;
    let next = (jobs.len() > limit as usize).then(|| {
        jobs.truncate(limit as usize);
        let last = jobs.last().map(|j| j.id.clone()).unwrap_or_default();
        let mut q = vec![];
        if let Some(s) = filter.status {
            q.push(format!("status={}", crate::jobs::status_name(s)));
        }
        if let Some(a) = &filter.analysis {
            q.push(format!("analysis={a}"));
        }
        q.push(format!("limit={limit}"));
        q.push(format!("before={last}"));
        format!("/v1/jobs?{}", q.join("&"))
    });
    let jobs = jobs.into_iter().map(|j| base.job(j)).collect();
    let mut resp = Json(JobList {
        jobs,
        next: next.clone(),
    })
    .into_response();
    if let Some(v) = next.and_then(|n| HeaderValue::from_str(&format!("<{n}>; rel=\"next\"")).ok())
    {
        resp.headers_mut().insert(header::LINK, v);
    }
    Ok(resp)
}

/// The listing's query, each parameter checked (422 naming every bad one).
fn filter(pairs: &[(String, String)]) -> Result<Filter, ApiError> {
    let mut bad = Invalid::default();
    let mut f = Filter {
        limit: PAGE,
        ..Filter::default()
    };
    let mut seen = std::collections::BTreeSet::new();
    for (k, v) in pairs {
        if !seen.insert(k.as_str()) {
            bad.push(k.as_str(), "given twice");
            continue;
        }
        match k.as_str() {
            "status" => match serde_json::from_value::<JobStatus>(Value::String(v.clone())) {
                Ok(s) => f.status = Some(s),
                Err(_) => bad.push(
                    "status",
                    format!("{v:?}: expected queued, running, succeeded, failed or cancelled"),
                ),
            },
            "analysis" => match serde_json::from_value::<AnalysisName>(Value::String(v.clone())) {
                Ok(_) => f.analysis = Some(v.clone()),
                Err(_) => bad.push(
                    "analysis",
                    format!("{v:?}: not an analysis (POST /v1/<analysis>)"),
                ),
            },
            "limit" => match v.parse::<u32>() {
                Ok(n) if (1..=MAX_PAGE).contains(&n) => f.limit = n,
                _ => bad.push(
                    "limit",
                    format!("{v:?}: expected a whole number from 1 to {MAX_PAGE}"),
                ),
            },
            "before" => match uuid::Uuid::parse_str(v) {
                Ok(id) => f.before = Some(id.hyphenated().to_string()),
                Err(_) => bad.push("before", format!("{v:?}: expected a job id")),
            },
            other => bad.push(
                other,
                "unknown parameter, expected one of `status`, `analysis`, `limit`, `before`",
            ),
        }
    }
    if bad.is_empty() {
        Ok(f)
    } else {
        Err(bad.into())
    }
}

/// The request's `Idempotency-Key`, if any (422 when it is not 1 to 255 visible ASCII
/// characters).
pub fn idempotency_key(headers: &HeaderMap) -> Result<Option<String>, ApiError> {
    let mut values = headers.get_all("idempotency-key").iter();
    let Some(v) = values.next() else {
        return Ok(None);
    };
    let bad = |m: &str| ApiError::Invalid(Invalid::one("Idempotency-Key", m));
    if values.next().is_some() {
        return Err(bad("given twice"));
    }
    let key = v
        .to_str()
        .ok()
        .map(str::trim)
        .filter(|k| !k.is_empty() && k.len() <= MAX_KEY && k.bytes().all(|b| b.is_ascii_graphic()))
        .ok_or_else(|| bad("expected 1 to 255 visible ASCII characters, e.g. a UUID"))?;
    Ok(Some(key.to_string()))
}

/// SHA-256 (hex) of a job request, independent of its fields' order and spacing: a retry of
/// the same request under the same key has the same hash.
pub fn request_sha256(req: &JobRequest) -> String {
    let analysis = serde_json::to_value(req.analysis).unwrap_or_default();
    let canonical = canonical(&Value::Array(vec![analysis, req.input.clone()]));
    let digest = Sha256::digest(canonical.as_bytes());
    digest.iter().map(|b| format!("{b:02x}")).collect()
}

/// Compact JSON with every object's keys sorted.
fn canonical(v: &Value) -> String {
    match v {
        Value::Object(m) => {
            let mut keys: Vec<&String> = m.keys().collect();
            keys.sort();
            let items: Vec<String> = keys
                .into_iter()
                .map(|k| format!("{}:{}", Value::String(k.clone()), canonical(&m[k])))
                .collect();
            format!("{{{}}}", items.join(","))
        }
        Value::Array(a) => format!(
            "[{}]",
            a.iter().map(canonical).collect::<Vec<_>>().join(",")
        ),
        other => other.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_hash_ignores_order_and_spacing() {
        let a: JobRequest =
            serde_json::from_str(r#"{"analysis":"modal","input":{"a":1,"b":[1,{"y":2,"x":1}]}}"#)
                .unwrap();
        let b: JobRequest = serde_json::from_str(
            r#"{ "input": { "b": [1, {"x": 1, "y": 2}], "a": 1 }, "analysis": "modal" }"#,
        )
        .unwrap();
        let c: JobRequest = serde_json::from_str(
            r#"{"analysis":"campbell","input":{"a":1,"b":[1,{"y":2,"x":1}]}}"#,
        )
        .unwrap();
        assert_eq!(request_sha256(&a), request_sha256(&b));
        assert_ne!(request_sha256(&a), request_sha256(&c));
        assert_eq!(request_sha256(&a).len(), 64);
    }
}
