//! What an analysis's endpoint returns: one `model::api` answer per analysis, read back from
//! its JSON when a job's result is served.

use serde::Serialize;

use super::error::ApiError;
use crate::model::api::{
    CampbellResponse, CriticalSpeedMapResponse, DampingMatricesResponse, FrequencyResponseResponse,
    Level1Response, ModalResponse, ReportResponse, StabilityResponse, StaticResponse,
    TimeResponseResponse, UnbalanceResponseResponse,
};

/// The result of an analysis, as its endpoint returns it: its JSON names the analysis in
/// `analysis` (first), so that a job's result, which may be any of them, says which it is
/// (the OpenAPI document's `JobResult` discriminates on it).
#[derive(Debug, Clone, Serialize)]
#[serde(tag = "analysis")]
pub enum Output {
    #[serde(rename = "modal")]
    Modal(ModalResponse),
    #[serde(rename = "campbell")]
    Campbell(CampbellResponse),
    #[serde(rename = "stability")]
    Stability(StabilityResponse),
    #[serde(rename = "damping")]
    Damping(Box<DampingMatricesResponse>),
    #[serde(rename = "time-response")]
    Time(TimeResponseResponse),
    #[serde(rename = "unbalance-response")]
    Unbalance(UnbalanceResponseResponse),
    #[serde(rename = "critical-speed-map")]
    CriticalMap(CriticalSpeedMapResponse),
    #[serde(rename = "static")]
    Static(StaticResponse),
    #[serde(rename = "level1")]
    Level1(Level1Response),
    #[serde(rename = "frequency-response")]
    Frequency(FrequencyResponseResponse),
    #[serde(rename = "report")]
    Report(Box<ReportResponse>),
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

    pub(super) fn set_warnings(&mut self, w: Vec<String>) {
        match self {
            // The analysis's own (supports over whirl frequency read past their tables) after.
            Output::Modal(o) => {
                let own = std::mem::take(&mut o.warnings);
                o.warnings = w;
                o.warnings.extend(own);
            }
            Output::Campbell(o) => o.warnings = w,
            Output::Stability(o) => o.warnings = w,
            Output::Damping(o) => o.warnings = w,
            Output::Time(o) => {
                let own = std::mem::take(&mut o.warnings);
                o.warnings = w;
                o.warnings.extend(own);
            }
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
    pub(super) fn values(&self) -> u64 {
        match self {
            Output::Campbell(c) => {
                c.speeds.len() as u64
                    * (1 + 5 * c.branches.len() as u64 + 2 * c.overdamped.len() as u64)
            }
            _ => 0,
        }
    }
}
