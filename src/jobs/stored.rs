//! A job as the store keeps it: its request, parsed again into a task with the limits of the
//! replica that runs it, its result (the output's JSON, gzipped), and the problem of a job
//! that was stopped.

use std::io::{Read, Write};

use serde_json::Value;

use crate::answer::{ApiError, Output};
use crate::model::api::{AnalysisName, Problem};
use crate::model::json::from_value;
use crate::model::task::JobInput;
use crate::model::{Invalid, Limits, Task};

/// A finished job's result: its JSON, gzipped (as the store keeps it).
pub struct Stored {
    pub analysis: &'static str,
    pub gzip: Vec<u8>,
}

impl Stored {
    pub fn new(analysis: &'static str, out: &Output) -> Result<Self, ApiError> {
        let json = serde_json::to_vec(out).map_err(|e| ApiError::Internal(e.to_string()))?;
        let mut enc = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
        enc.write_all(&json)
            .map_err(|e| ApiError::Internal(e.to_string()))?;
        let gzip = enc
            .finish()
            .map_err(|e| ApiError::Internal(e.to_string()))?;
        Ok(Stored { analysis, gzip })
    }

    /// The output of `analysis` back from its gzipped JSON.
    pub fn output(analysis: &str, gzip: &[u8]) -> Result<Output, ApiError> {
        let mut json = vec![];
        flate2::read::GzDecoder::new(gzip)
            .read_to_end(&mut json)
            .map_err(|e| ApiError::Internal(format!("stored result: {e}")))?;
        Output::from_json(analysis, &json)
    }
}

/// A job's input, typed by its analysis.
pub fn job_input(analysis: AnalysisName, input: Value) -> Result<JobInput, ApiError> {
    if !input.is_object() {
        return Err(ApiError::Invalid(Invalid::one(
            "(body)",
            "must be a JSON object: the body of the analysis's endpoint",
        )));
    }
    Ok(match analysis {
        AnalysisName::Modal => JobInput::Modal(from_value(input)?),
        AnalysisName::Campbell => JobInput::Campbell(from_value(input)?),
        AnalysisName::Stability => JobInput::Stability(from_value(input)?),
        AnalysisName::Damping => JobInput::Damping(from_value(input)?),
        AnalysisName::TimeResponse => JobInput::Time(from_value(input)?),
        AnalysisName::UnbalanceResponse => JobInput::Unbalance(from_value(input)?),
        AnalysisName::CriticalSpeedMap => JobInput::CriticalMap(from_value(input)?),
        AnalysisName::Static => JobInput::Static(from_value(input)?),
        AnalysisName::Level1 => JobInput::Level1(from_value(input)?),
        AnalysisName::FrequencyResponse => JobInput::Frequency(from_value(input)?),
        AnalysisName::Report => JobInput::Report(Box::new(from_value(input)?)),
    })
}

/// A stored request parsed again into a task, with this replica's limits.
pub fn parse_stored(analysis: &str, input: &str, limits: &Limits) -> Result<Task, ApiError> {
    let bad = |e: serde_json::Error| ApiError::Internal(format!("stored job: {e}"));
    let name: AnalysisName =
        serde_json::from_value(Value::String(analysis.to_string())).map_err(bad)?;
    let value: Value = serde_json::from_str(input).map_err(bad)?;
    Ok(job_input(name, value)?.parse(limits)?)
}

pub fn stopped(reason: &str) -> Problem {
    ApiError::Stopped(reason.to_string()).problem()
}
