//! Rendering: an answer as a document, knowing neither HTTP nor the store. JSON (the answer
//! itself), a table ([`csv()`]: `text/csv`), a plot ([`plot`], and [`plot_audit`] for the
//! audit's analyses: `image/svg+xml`, or rasterised from that SVG by [`png`]: `image/png`) or
//! the audit report ([`report`]: one self-contained
//! `text/html` page). [`render()`] writes an [`Output`] in the first of the formats a client
//! accepts that it has.

mod csv;
pub mod plot;
pub mod plot_audit;
pub mod png;
pub mod report;

pub use csv::csv;

use crate::answer::{ApiError, Output};

/// A representation of a result.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    Json,
    Csv,
    Svg,
    Png,
    Html,
}

impl Format {
    pub fn media(self) -> &'static str {
        match self {
            Format::Json => "application/json",
            Format::Csv => "text/csv",
            Format::Svg => "image/svg+xml",
            Format::Png => "image/png",
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
            Format::Png => match svg(out)? {
                Some(s) => Some(png::png(&s).map_err(|e| ApiError::Internal(format!("PNG: {e}")))?),
                None => None,
            },
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
        v.push("image/png");
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
    // The plots label rad/s and rpm themselves, whatever unit the JSON answer is in.
    let out = &*out.in_rad_s();
    let r = match out {
        Output::Campbell(c) if c.interference.is_some() => plot::interference(c),
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
    r.map(|s| Some(titled(&s, title(out))))
        .map_err(|e| ApiError::Internal(format!("plot: {e}")))
}

/// What a plot shows: its SVG `<title>` (read by screen readers, shown as a tooltip).
fn title(out: &Output) -> &'static str {
    match out {
        Output::Campbell(_) => {
            "Campbell diagram: whirl frequencies and decay rates against spin speed"
        }
        Output::Stability(_) => "Stability: largest decay rate against spin speed",
        Output::Time(_) => "Time response: displacements against time, and orbits",
        Output::Unbalance(_) => "Unbalance response: amplitude and phase against spin speed",
        Output::CriticalMap(_) => {
            "Undamped critical speed map: frequencies against support stiffness"
        }
        Output::Static(_) => "Static deflection, shear force and bending moment along the rotor",
        Output::Level1(_) => {
            "API 617 Level I stability: log decrement against cross-coupled stiffness"
        }
        Output::Frequency(_) => {
            "Frequency response: amplitude and phase against excitation frequency"
        }
        Output::Modal(_) => "Mode shapes along the rotor",
        Output::Damping(_) | Output::Report(_) => "Whirl",
    }
}

/// `svg` with `<title>` as the first child of its root (kept if it has one).
fn titled(svg: &str, title: &str) -> String {
    let Some(start) = svg.find("<svg") else {
        return svg.to_string();
    };
    let Some(end) = svg[start..].find('>').map(|k| start + k + 1) else {
        return svg.to_string();
    };
    if svg[end..].trim_start().starts_with("<title") {
        return svg.to_string();
    }
    format!(
        "{}\n<title>{}</title>{}",
        &svg[..end],
        plot::svg::escape(title),
        &svg[end..]
    )
}
