//! A synchronous analysis: the formats the client accepts (`Accept`), the task run on the
//! worker pool within the request time limit (cancelled when the client goes away), and the
//! rendered answer as the response.

use axum::body::{Body, Bytes};
use axum::http::{HeaderMap, HeaderValue, StatusCode, header};
use axum::response::{IntoResponse, Response};

use std::sync::Arc;

use super::AppState;
use super::error::ApiError;
use crate::analysis::control::Control;
use crate::answer::execute;
use crate::jobs::pool::AnswerHold;
use crate::model::Task;
use crate::render::{Format, Rendered, render};

/// The formats acceptable to the client, best first (`Accept`, with q-values; none: JSON).
pub fn negotiate(headers: &HeaderMap) -> Result<Vec<Format>, ApiError> {
    let Some(accept) = headers.get(header::ACCEPT).and_then(|v| v.to_str().ok()) else {
        return Ok(vec![Format::Json]);
    };
    let mut ranked: Vec<(f64, usize, Format)> = vec![];
    for (i, item) in accept.split(',').enumerate() {
        let mut parts = item.split(';');
        let media = parts.next().unwrap_or("").trim().to_ascii_lowercase();
        let q = parts
            .filter_map(|p| p.trim().strip_prefix("q="))
            .find_map(|v| v.trim().parse::<f64>().ok())
            .unwrap_or(1.0);
        if q <= 0.0 {
            continue;
        }
        let formats: &[Format] = match media.as_str() {
            "application/json" | "application/*" | "*/*" | "application/problem+json" => {
                &[Format::Json]
            }
            "text/csv" => &[Format::Csv],
            "text/html" | "application/xhtml+xml" => &[Format::Html],
            "text/*" => &[Format::Csv, Format::Html],
            "image/svg+xml" => &[Format::Svg],
            "image/png" => &[Format::Png],
            "image/*" => &[Format::Svg, Format::Png],
            _ => &[],
        };
        ranked.extend(formats.iter().map(|f| (q, i, *f)));
    }
    ranked.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
    let out: Vec<Format> = ranked.into_iter().map(|r| r.2).collect();
    if out.is_empty() {
        return Err(ApiError::NotAcceptable(
            "this API answers application/json, text/csv, image/svg+xml, image/png or (the \
             report) text/html"
                .into(),
        ));
    }
    Ok(out)
}

/// Cancels an analysis when its request is dropped (the client went away) before it answered.
struct CancelOnDrop {
    control: Arc<Control>,
    analysis: &'static str,
    armed: bool,
}

impl Drop for CancelOnDrop {
    fn drop(&mut self) {
        if self.armed {
            self.control.cancel();
            tracing::info!(
                analysis = self.analysis,
                "the client went away: analysis cancelled"
            );
        }
    }
}

/// Runs a task on the worker pool within the request time limit, and renders its output
/// there too (large answers take time to serialise). The answer holds its size of the memory
/// budget until the client has read it. The analysis is cancelled when the
/// client disconnects or the limit passes.
pub async fn respond(
    st: &AppState,
    task: Task,
    formats: Vec<Format>,
) -> Result<Response, ApiError> {
    let name = task.name();
    let admission = st.pool.admit(&task.cost, task.size_field())?;
    let control = Arc::new(Control::default());
    let mut guard = CancelOnDrop {
        control: control.clone(),
        analysis: name,
        armed: true,
    };
    let c = control.clone();
    let max_bytes = st.config.max_response_bytes;
    let t0 = std::time::Instant::now();
    let work = st.pool.run_answer(admission, move || {
        let rendered = execute(&task, &c, max_bytes).and_then(|out| render(&out, &formats));
        let bytes = rendered.as_ref().map_or(0, |r| r.body.len() as u64);
        (rendered, bytes)
    });
    let limit = st.config.request_time_limit;
    let result = tokio::time::timeout(limit, work).await;
    guard.armed = false;
    st.metrics.observe_analysis(name, t0.elapsed());
    match result {
        Err(_) => {
            control.cancel();
            tracing::warn!(
                analysis = name,
                limit_s = limit.as_secs_f64(),
                "time limit: analysis stopped"
            );
            Err(ApiError::TimeLimit(limit))
        }
        Ok(r) => {
            let (rendered, hold) = r?;
            Ok(held_answer(rendered?, hold))
        }
    }
}

/// Bytes of an answer handed to the connection at a time.
const ANSWER_CHUNK: usize = 64 << 10;

/// The answer as a body of chunks that holds its share of the memory budget until the last
/// chunk is taken or the client goes away (see `WorkerPool::run_answer`).
fn held_answer(r: Rendered, hold: AnswerHold) -> Response {
    let body = Bytes::from(r.body);
    let len = body.len();
    let chunks = futures_util::stream::unfold((body, hold), |(mut rest, hold)| async move {
        if rest.is_empty() {
            return None;
        }
        let chunk = rest.split_to(rest.len().min(ANSWER_CHUNK));
        Some((Ok::<_, std::convert::Infallible>(chunk), (rest, hold)))
    });
    let mut resp = (StatusCode::OK, Body::from_stream(chunks)).into_response();
    let h = resp.headers_mut();
    h.insert(header::CONTENT_TYPE, HeaderValue::from_static(r.media));
    // The stream does not say its length: the header does (no chunked encoding).
    h.insert(header::CONTENT_LENGTH, HeaderValue::from(len));
    resp
}

impl IntoResponse for Rendered {
    fn into_response(self) -> Response {
        let mut resp = (StatusCode::OK, self.body).into_response();
        resp.headers_mut()
            .insert(header::CONTENT_TYPE, HeaderValue::from_static(self.media));
        resp
    }
}
