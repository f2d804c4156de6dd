//! Rendering: an answer as a document, knowing neither HTTP nor the store. JSON (the answer
//! itself), a table ([`csv()`]: `text/csv`), a plot ([`plot`], and [`plot_audit`] for the
//! audit's analyses: `image/svg+xml`) or the audit report ([`report`]: one self-contained
//! `text/html` page). [`render()`] writes an [`Output`] in the first of the formats a client
//! accepts that it has.

mod csv;
pub mod plot;
pub mod plot_audit;
pub mod report;

pub use csv::csv;

use crate::answer::{ApiError, Output};

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

/// A rendered answer: media type and body.
pub struct Rendered {
    pub media: &'static str,
    pub body: Vec<u8>,
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
        Output::Report(r) => report::html(r, &r.rotor)
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
