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
    let units = task.cost.work;
    let limit = st.config.request_time_limit;
    // A report is refused before it starts when one of no more estimated work already ran
    // past the limit on this server: a job runs it instead. Not extrapolated from the pace of
    // reports that finished: the estimate is a full-model flop count, and a reduction makes
    // reports of larger estimates faster (a 72-element anisotropic rotor's one-model report,
    // estimated at 76 s from a 55-element isotropic one's pace, ran in 1.7 s).
    if name == "report"
        && let Some(stopped) = st.pace.stopped(name)
        && units >= stopped
    {
        return Err(ApiError::Unsolvable(format!(
            "a report of no more estimated work than this one ran past the synchronous limit \
             of {} s on this server (WHIRL_REQUEST_TIME_LIMIT): submit it as a job, POST \
             /v1/jobs with {{\"analysis\": \"report\", \"input\": <this body>}}, and poll it",
            limit.as_secs()
        )));
    }
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
    let result = tokio::time::timeout(limit, work).await;
    guard.armed = false;
    st.metrics.observe_analysis(name, t0.elapsed());
    match result {
        Err(_) => {
            control.cancel();
            st.pace.record_stopped(name, units);
            tracing::warn!(
                analysis = name,
                limit_s = limit.as_secs_f64(),
                "time limit: analysis stopped"
            );
            Err(ApiError::TimeLimit(limit))
        }
        Ok(r) => {
            let (rendered, hold) = r?;
            let rendered = rendered?;
            Ok(held_answer(rendered, hold))
        }
    }
}

/// For each analysis, the least work estimate (`Cost::work`) of a synchronous run this
/// server stopped at the time limit.
#[derive(Debug, Default)]
pub struct Pace(std::sync::Mutex<std::collections::HashMap<&'static str, f64>>);

impl Pace {
    pub fn record_stopped(&self, name: &'static str, work: f64) {
        if !(work > 0.0 && work.is_finite()) {
            return;
        }
        let mut m = self.0.lock().unwrap_or_else(|e| e.into_inner());
        let w = m.entry(name).or_insert(work);
        *w = w.min(work);
    }

    /// The least work of a run of `name` stopped at the limit, if any was.
    pub fn stopped(&self, name: &'static str) -> Option<f64> {
        let m = self.0.lock().unwrap_or_else(|e| e.into_inner());
        m.get(name).copied()
    }
}

/// Bytes of an answer handed to the connection at a time.
const ANSWER_CHUNK: usize = 64 << 10;

/// The answer as a body of chunks that holds its share of the memory budget until the last
/// chunk is taken or the client goes away (see `WorkerPool::run_answer`).
fn held_answer(r: Rendered, hold: AnswerHold) -> Response {
    let body = Held {
        rest: Bytes::from(r.body),
        hold: Some(hold),
    };
    let mut resp = (StatusCode::OK, Body::new(body)).into_response();
    let h = resp.headers_mut();
    h.insert(header::CONTENT_TYPE, HeaderValue::from_static(r.media));
    resp
}

/// An answer handed out [`ANSWER_CHUNK`] bytes at a time, with its exact length as the size
/// hint: the server announces it (`Content-Length`) when the body goes out as it is, and the
/// compression layer, which changes the length, drops it (a header set here stayed, and
/// clients that accept gzip saw the connection drop).
struct Held {
    rest: Bytes,
    hold: Option<AnswerHold>,
}

impl axum::body::HttpBody for Held {
    type Data = Bytes;
    type Error = std::convert::Infallible;

    fn poll_frame(
        mut self: std::pin::Pin<&mut Self>,
        _: &mut std::task::Context<'_>,
    ) -> std::task::Poll<Option<Result<http_body::Frame<Bytes>, Self::Error>>> {
        if self.rest.is_empty() {
            self.hold = None;
            return std::task::Poll::Ready(None);
        }
        let n = self.rest.len().min(ANSWER_CHUNK);
        let chunk = self.rest.split_to(n);
        if self.rest.is_empty() {
            self.hold = None;
        }
        std::task::Poll::Ready(Some(Ok(http_body::Frame::data(chunk))))
    }

    fn is_end_stream(&self) -> bool {
        self.rest.is_empty()
    }

    fn size_hint(&self) -> http_body::SizeHint {
        http_body::SizeHint::with_exact(self.rest.len() as u64)
    }
}

impl IntoResponse for Rendered {
    fn into_response(self) -> Response {
        let mut resp = (StatusCode::OK, self.body).into_response();
        resp.headers_mut()
            .insert(header::CONTENT_TYPE, HeaderValue::from_static(self.media));
        resp
    }
}
