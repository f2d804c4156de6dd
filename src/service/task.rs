//! A validated request ready to run, its output, and how the output is rendered: JSON by
//! default, `text/csv` (the table) or `image/svg+xml` (the plot) on request through `Accept`.

use axum::http::{HeaderMap, HeaderValue, StatusCode, header};
use axum::response::{IntoResponse, Response};
use serde::Serialize;

use std::sync::Arc;

use super::AppState;
use super::convert;
use super::convert_audit;
use super::error::ApiError;
use super::plot;
use super::plot_audit;
use crate::analysis::control::Control;
use crate::analysis::run::{Outcome, run};
use crate::model::Task;
use crate::model::api::{
    CampbellResponse, CriticalSpeedMapResponse, DampingMatricesResponse, FrequencyResponseResponse,
    Level1Response, ModalResponse, ReportResponse, StabilityResponse, StaticResponse,
    TimeResponseResponse, UnbalanceResponseResponse,
};
use crate::model::limits::BYTES_PER_VALUE;
use crate::model::task::TaskKind;

/// The result of an analysis, as its endpoint returns it.
#[derive(Debug, Clone, Serialize)]
#[serde(untagged)]
pub enum Output {
    Modal(ModalResponse),
    Campbell(CampbellResponse),
    Stability(StabilityResponse),
    Damping(Box<DampingMatricesResponse>),
    Time(TimeResponseResponse),
    Unbalance(UnbalanceResponseResponse),
    CriticalMap(CriticalSpeedMapResponse),
    Static(StaticResponse),
    Level1(Level1Response),
    Frequency(FrequencyResponseResponse),
    Report(Box<ReportResponse>),
}

impl Output {
    /// The wire form of an outcome of `task`.
    fn of(o: Outcome, task: &Task) -> Result<Self, ApiError> {
        Ok(match o {
            Outcome::Modal(r) => Output::Modal(convert::modal(&r)),
            Outcome::Campbell(r) => Output::Campbell(convert::campbell(&r)),
            Outcome::Stability {
                threshold,
                speeds,
                max_decay_rate,
            } => Output::Stability(convert::stability(
                threshold.as_ref(),
                &speeds,
                max_decay_rate,
            )),
            Outcome::Damping { matrices, model } => {
                Output::Damping(Box::new(convert::damping_matrices(&matrices, model)))
            }
            Outcome::Time(r, reduction) => {
                let mut t = convert::time_response(&r);
                t.reduction = reduction.as_ref().map(convert::reduction);
                Output::Time(t)
            }
            Outcome::Unbalance {
                speeds,
                nodes,
                response,
                peaks,
                range,
                model,
            } => {
                let mut u = convert::unbalance_response(&speeds, &nodes, &response, model);
                for (n, p) in u.nodes.iter_mut().zip(&peaks) {
                    n.peaks = convert_audit::peaks(p, range);
                }
                Output::Unbalance(u)
            }
            Outcome::CriticalMap { stiffness, map } => {
                Output::CriticalMap(convert_audit::critical_map(&stiffness, &map))
            }
            Outcome::Static {
                result,
                gravity,
                rigid,
            } => Output::Static(convert_audit::statics(&result, gravity, rigid)),
            Outcome::Level1 {
                speed,
                at,
                qs,
                result,
                qa,
                model,
            } => Output::Level1(convert_audit::level1(speed, &at, &qs, &result, qa, model)),
            Outcome::Frequency {
                speed,
                input,
                output,
                frequencies,
                response,
                model,
            } => Output::Frequency(convert_audit::frequency(
                speed,
                input,
                output,
                &frequencies,
                &response,
                model,
            )),
            Outcome::Report(parts) => {
                let TaskKind::Report(plan) = &task.kind else {
                    return Err(ApiError::Internal(
                        "a report outcome of another task".into(),
                    ));
                };
                let tasks = plan.tasks();
                let parts = parts
                    .into_iter()
                    .zip(tasks)
                    .map(|(o, t)| {
                        let mut out = Output::of(o, t)?;
                        out.set_warnings(t.warnings.clone());
                        Ok(out)
                    })
                    .collect::<Result<Vec<_>, ApiError>>()?;
                Output::Report(Box::new(
                    convert_audit::report(parts, plan).map_err(ApiError::Internal)?,
                ))
            }
        })
    }
}

impl Output {
    /// An output read back from its JSON (a stored job result), by its analysis's name.
    pub fn from_json(analysis: &str, json: &[u8]) -> Result<Self, ApiError> {
        let bad = |e: serde_json::Error| ApiError::Internal(format!("stored result: {e}"));
        Ok(match analysis {
            "modal" => Output::Modal(serde_json::from_slice(json).map_err(bad)?),
            "campbell" => Output::Campbell(serde_json::from_slice(json).map_err(bad)?),
            "stability" => Output::Stability(serde_json::from_slice(json).map_err(bad)?),
            "damping" => Output::Damping(Box::new(serde_json::from_slice(json).map_err(bad)?)),
            "time-response" => Output::Time(serde_json::from_slice(json).map_err(bad)?),
            "unbalance-response" => Output::Unbalance(serde_json::from_slice(json).map_err(bad)?),
            "critical-speed-map" => Output::CriticalMap(serde_json::from_slice(json).map_err(bad)?),
            "static" => Output::Static(serde_json::from_slice(json).map_err(bad)?),
            "level1" => Output::Level1(serde_json::from_slice(json).map_err(bad)?),
            "frequency-response" => Output::Frequency(serde_json::from_slice(json).map_err(bad)?),
            "report" => Output::Report(Box::new(serde_json::from_slice(json).map_err(bad)?)),
            other => return Err(ApiError::Internal(format!("unknown analysis {other}"))),
        })
    }

    fn set_warnings(&mut self, w: Vec<String>) {
        match self {
            Output::Modal(o) => o.warnings = w,
            Output::Campbell(o) => o.warnings = w,
            Output::Stability(o) => o.warnings = w,
            Output::Damping(o) => o.warnings = w,
            Output::Time(o) => o.warnings = w,
            Output::Unbalance(o) => o.warnings = w,
            Output::CriticalMap(o) => o.warnings = w,
            Output::Static(o) => o.warnings = w,
            Output::Level1(o) => o.warnings = w,
            Output::Frequency(o) => o.warnings = w,
            Output::Report(o) => o.warnings = w,
        }
    }

    /// Numbers in the answer, where only the analysis knows them (a Campbell sweep below a
    /// frequency bound); others were bounded when the request was parsed.
    fn values(&self) -> u64 {
        match self {
            Output::Campbell(c) => c.speeds.len() as u64 * (1 + 2 * c.branches.len() as u64),
            _ => 0,
        }
    }
}

/// Runs a task to its output, refusing an answer beyond `max_bytes`.
pub fn execute(task: &Task, control: &Control, max_bytes: u64) -> Result<Output, ApiError> {
    let mut out = Output::of(run(task, control)?, task)?;
    out.set_warnings(task.warnings.clone());
    let bytes = out.values() * BYTES_PER_VALUE;
    if bytes > max_bytes {
        return Err(ApiError::Unsolvable(format!(
            "the answer would be about {} MB, more than the limit of {} MB \
             (WHIRL_MAX_RESPONSE_BYTES): use a lower max_frequency or fewer speeds",
            bytes.div_ceil(1 << 20),
            max_bytes >> 20
        )));
    }
    Ok(out)
}

/// A representation of a result.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    Json,
    Csv,
    Svg,
    Html,
}

impl Format {
    pub fn media(self) -> &'static str {
        match self {
            Format::Json => "application/json",
            Format::Csv => "text/csv",
            Format::Svg => "image/svg+xml",
            Format::Html => "text/html; charset=utf-8",
        }
    }
}

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
            "image/svg+xml" | "image/*" => &[Format::Svg],
            _ => &[],
        };
        ranked.extend(formats.iter().map(|f| (q, i, *f)));
    }
    ranked.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
    let out: Vec<Format> = ranked.into_iter().map(|r| r.2).collect();
    if out.is_empty() {
        return Err(ApiError::NotAcceptable(
            "this API answers application/json, text/csv, image/svg+xml or (the report) \
             text/html"
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
/// there too (large answers take time to serialise). The analysis is cancelled when the
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
    let work = st.pool.run(
        admission,
        || {},
        move || {
            let out = execute(&task, &c, max_bytes)?;
            render(&out, &formats)
        },
    );
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
        Ok(r) => Ok(r??.into_response()),
    }
}

/// A rendered answer: media type and body.
pub struct Rendered {
    pub media: &'static str,
    pub body: Vec<u8>,
}

impl IntoResponse for Rendered {
    fn into_response(self) -> Response {
        let mut resp = (StatusCode::OK, self.body).into_response();
        resp.headers_mut()
            .insert(header::CONTENT_TYPE, HeaderValue::from_static(self.media));
        resp
    }
}

/// The output in the first acceptable format it supports (406 if none).
pub fn render(out: &Output, formats: &[Format]) -> Result<Rendered, ApiError> {
    for &f in formats {
        let body = match f {
            Format::Json => {
                Some(serde_json::to_vec(out).map_err(|e| ApiError::Internal(e.to_string()))?)
            }
            Format::Csv => csv(out).map(String::into_bytes),
            Format::Svg => svg(out)?.map(String::into_bytes),
            Format::Html => html(out)?.map(String::into_bytes),
        };
        if let Some(body) = body {
            return Ok(Rendered {
                media: f.media(),
                body,
            });
        }
    }
    Err(ApiError::NotAcceptable(format!(
        "this result is available as {}",
        supported(out).join(", ")
    )))
}

fn supported(out: &Output) -> Vec<&'static str> {
    let mut v = vec!["application/json"];
    if csv_supported(out) {
        v.push("text/csv");
    }
    let plotted = match out {
        Output::Modal(m) => plot::modal_plotted(m),
        Output::Damping(_) | Output::Report(_) => false,
        _ => true,
    };
    if plotted {
        v.push("image/svg+xml");
    }
    if matches!(out, Output::Report(_)) {
        v.push("text/html");
    }
    v
}

fn csv_supported(out: &Output) -> bool {
    !matches!(out, Output::Damping(_) | Output::Report(_))
}

fn html(out: &Output) -> Result<Option<String>, ApiError> {
    match out {
        Output::Report(r) => super::report::html(r, &r.rotor)
            .map(Some)
            .map_err(|e| ApiError::Internal(format!("report page: {e}"))),
        _ => Ok(None),
    }
}

fn svg(out: &Output) -> Result<Option<String>, ApiError> {
    let r = match out {
        Output::Campbell(c) => plot::campbell(c),
        Output::Stability(s) => plot::stability(s),
        Output::Time(t) => plot::time(t),
        Output::Unbalance(u) => plot::unbalance(u),
        Output::CriticalMap(c) => plot_audit::critical_speed_map(c),
        Output::Static(s) => plot_audit::static_deflection(s),
        Output::Level1(l) => plot_audit::level1(l),
        Output::Frequency(f) => plot_audit::frequency_response(f),
        Output::Modal(m) => match plot::modal(m) {
            Ok(None) => return Ok(None),
            r => r.map(Option::unwrap_or_default),
        },
        _ => return Ok(None),
    };
    r.map(Some)
        .map_err(|e| ApiError::Internal(format!("plot: {e}")))
}

fn num(v: Option<f64>) -> String {
    v.map(|x| format!("{x}")).unwrap_or_default()
}

/// The result as a table: one row per speed, time or pole.
pub fn csv(out: &Output) -> Option<String> {
    let mut s = String::new();
    match out {
        Output::Modal(m) => {
            s.push_str("decay_rate,frequency,whirl,damping_ratio,log_decrement,whirl_ratio\n");
            for p in &m.poles {
                let whirl = serde_json::to_value(p.whirl).ok()?.as_str()?.to_string();
                s.push_str(&format!(
                    "{},{},{whirl},{},{},{}\n",
                    p.decay_rate,
                    p.frequency,
                    p.damping_ratio,
                    num(p.log_decrement),
                    num(p.whirl_ratio)
                ));
            }
        }
        Output::Campbell(c) => {
            s.push_str("speed");
            for b in &c.branches {
                let w = if b.whirl == crate::model::api::Whirl::Forward {
                    "forward"
                } else {
                    "backward"
                };
                s.push_str(&format!(
                    ",mode{}_{w}_frequency,mode{}_{w}_decay_rate",
                    b.mode, b.mode
                ));
            }
            s.push('\n');
            for (i, w) in c.speeds.iter().enumerate() {
                s.push_str(&format!("{w}"));
                for b in &c.branches {
                    s.push_str(&format!(
                        ",{},{}",
                        num(b.frequency[i]),
                        num(b.decay_rate[i])
                    ));
                }
                s.push('\n');
            }
        }
        Output::Stability(st) => {
            s.push_str("speed,max_decay_rate\n");
            for (w, d) in st.speeds.iter().zip(&st.max_decay_rate) {
                s.push_str(&format!("{w},{d}\n"));
            }
        }
        Output::Time(t) => {
            s.push_str("time");
            for n in &t.nodes {
                s.push_str(&format!(",node{}_x,node{}_y", n.node, n.node));
            }
            s.push('\n');
            for (i, time) in t.time.iter().enumerate() {
                s.push_str(&format!("{time}"));
                for n in &t.nodes {
                    s.push_str(&format!(",{},{}", n.x[i], n.y[i]));
                }
                s.push('\n');
            }
        }
        Output::Unbalance(u) => {
            s.push_str("speed");
            for n in &u.nodes {
                for c in [
                    "amplitude",
                    "phase",
                    "x_amplitude",
                    "x_phase",
                    "y_amplitude",
                    "y_phase",
                    "major",
                    "minor",
                ] {
                    s.push_str(&format!(",node{}_{c}", n.node));
                }
            }
            s.push('\n');
            for (i, w) in u.speeds.iter().enumerate() {
                s.push_str(&format!("{w}"));
                for n in &u.nodes {
                    for c in [
                        &n.amplitude,
                        &n.phase,
                        &n.x_amplitude,
                        &n.x_phase,
                        &n.y_amplitude,
                        &n.y_phase,
                        &n.major,
                        &n.minor,
                    ] {
                        s.push_str(&format!(",{}", c[i]));
                    }
                }
                s.push('\n');
            }
        }
        Output::CriticalMap(c) => {
            s.push_str("stiffness");
            for k in 1..=c.frequencies.len() {
                s.push_str(&format!(",mode{k}_frequency"));
            }
            s.push('\n');
            for (i, k) in c.stiffness.iter().enumerate() {
                s.push_str(&format!("{k}"));
                for f in &c.frequencies {
                    s.push_str(&format!(",{}", f[i]));
                }
                s.push('\n');
            }
        }
        Output::Static(st) => {
            s.push_str("node,position,deflection,deflection_x,reaction,reaction_x\n");
            for n in &st.nodes {
                let r = st.supports.iter().filter(|r| r.node == n.node);
                let (ry, rx) = r.fold((None, None), |(y, x), r| {
                    (
                        Some(y.unwrap_or(0.0) + r.reaction),
                        Some(x.unwrap_or(0.0) + r.reaction_x),
                    )
                });
                s.push_str(&format!(
                    "{},{},{},{},{},{}\n",
                    n.node,
                    n.position,
                    n.deflection,
                    n.deflection_x,
                    num(ry),
                    num(rx)
                ));
            }
        }
        Output::Level1(l) => {
            s.push_str("cross_coupling,log_decrement,frequency\n");
            for (i, q) in l.cross_coupling.iter().enumerate() {
                s.push_str(&format!(
                    "{q},{},{}\n",
                    num(l.log_decrement[i]),
                    num(l.frequency[i])
                ));
            }
        }
        Output::Frequency(f) => {
            s.push_str(
                "frequency,amplitude,phase,x_amplitude,x_phase,y_amplitude,y_phase,forward,\
                 backward\n",
            );
            for i in 0..f.frequencies.len() {
                s.push_str(&format!(
                    "{},{},{},{},{},{},{},{},{}\n",
                    f.frequencies[i],
                    f.amplitude[i],
                    f.phase[i],
                    f.x_amplitude[i],
                    f.x_phase[i],
                    f.y_amplitude[i],
                    f.y_phase[i],
                    f.forward[i],
                    f.backward[i]
                ));
            }
        }
        Output::Damping(_) | Output::Report(_) => return None,
    }
    Some(s)
}
