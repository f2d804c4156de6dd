//! Studies as jobs: every sample of a [`Study`] checked as a job (parsed with this replica's
//! limits, sized against the pool's memory budget) before any is queued, then queued with the
//! study in one transaction; the study's state read back from its samples' rows (so any
//! replica answers, and a restart or a dead replica loses nothing: a sample whose replica died
//! is re-queued by the lease, like any job); its result assembled from the samples' stored
//! results.

use std::io::Read;
use std::sync::Arc;

use serde_json::Value;

use super::pool::WorkerPool;
use super::store::studies::{NewSample, NewStudy, SampleRow, StudyRow};
use super::{Jobs, job_input, rfc3339_ms, stopped};
use crate::answer::ApiError;
use crate::model::api::{
    JobStatus, StudyCounts, StudyDesign, StudyInfo, StudyRequest, StudyResult, StudySample,
    StudyStatus,
};
use crate::model::{Invalid, Limits};
use crate::studies::{Study, pointer, summary};

/// What a study may take before any sample runs.
#[derive(Debug, Clone, Copy)]
pub struct StudyLimits {
    /// Each sample's input is parsed with these.
    pub limits: Limits,
    /// Compressed bytes of results kept (`WHIRL_JOB_RESULT_BYTES`): the samples' inputs and
    /// results together must fit.
    pub result_bytes: u64,
    /// Samples of all studies waiting in the shared queue (`WHIRL_STUDY_QUEUE`).
    pub queue: usize,
}

/// Samples read from the store at once for a result.
const PAGE: usize = 200;

fn not_found(id: &str) -> ApiError {
    ApiError::NotFound(format!(
        "no study {id} (unknown, or finished and forgotten)"
    ))
}

fn internal(e: impl std::fmt::Display) -> ApiError {
    ApiError::Internal(format!("study: {e}"))
}

/// The request a study was stored with.
fn request(row: &StudyRow) -> Result<StudyRequest, ApiError> {
    serde_json::from_str(&row.request).map_err(internal)
}

/// A study's status from its samples.
pub fn study_info(row: &StudyRow) -> Result<StudyInfo, ApiError> {
    let n = |s| row.count(s).max(0) as u64;
    let counts = StudyCounts {
        queued: n(JobStatus::Queued),
        running: n(JobStatus::Running),
        done: n(JobStatus::Succeeded),
        failed: n(JobStatus::Failed),
        cancelled: n(JobStatus::Cancelled),
    };
    let samples = row.samples.max(0) as u64;
    let status = if row.cancelled {
        StudyStatus::Cancelled
    } else if counts.queued + counts.running == 0 {
        StudyStatus::Finished
    } else if counts.queued == samples {
        StudyStatus::Queued
    } else {
        StudyStatus::Running
    };
    Ok(StudyInfo {
        id: row.id.clone(),
        analysis: row.analysis.clone(),
        design: request(row)?.design,
        status,
        progress: if samples == 0 {
            1.0
        } else {
            (counts.done + counts.failed) as f64 / samples as f64
        },
        samples,
        counts,
        created_at: rfc3339_ms(row.created_ms),
        error: row.error.clone(),
    })
}

/// Every sample checked as a job would be; the first that fails is a 422 naming the sample
/// and its field.
fn check_samples(
    study: &Study,
    plan: &[Vec<Value>],
    pool: &WorkerPool,
    limits: StudyLimits,
) -> Result<Vec<NewSample>, ApiError> {
    let mut out = Vec::with_capacity(plan.len());
    let mut bytes = 0u64;
    for (k, values) in plan.iter().enumerate() {
        let input = study.input(values);
        let named = |e: ApiError| match e {
            ApiError::Invalid(mut inv) => {
                inv.prefix_paths(|p| match p {
                    "(body)" => format!("samples[{k}].input"),
                    p => format!("samples[{k}].input.{p}"),
                });
                let shown: Vec<String> = study
                    .parameters
                    .iter()
                    .zip(values)
                    .map(|(p, v)| format!("{} = {v}", p.pointer))
                    .collect();
                inv.push(
                    format!("samples[{k}]"),
                    format!("the input with {} is invalid", shown.join(", ")),
                );
                ApiError::Invalid(inv)
            }
            other => other,
        };
        let task = job_input(study.analysis, input.clone())
            .and_then(|i| i.parse(&limits.limits).map_err(ApiError::from))
            .map_err(named)?;
        let (lane, memory_mib) = pool.needs(&task.cost, task.size_field()).map_err(named)?;
        let input = serde_json::to_string(&input).map_err(internal)?;
        bytes = bytes
            .saturating_add(task.cost.response_bytes)
            .saturating_add(input.len() as u64);
        out.push(NewSample {
            id: uuid::Uuid::now_v7().to_string(),
            input,
            parameters: serde_json::to_string(values).map_err(internal)?,
            lane,
            memory_mib,
        });
    }
    if bytes > limits.result_bytes {
        return Err(too_large(plan.len(), bytes, limits));
    }
    Ok(out)
}

/// 422: the samples would take more than the bytes kept.
fn too_large(samples: usize, bytes: u64, limits: StudyLimits) -> ApiError {
    ApiError::Invalid(Invalid::one(
        "samples",
        format!(
            "{samples} samples whose inputs and results would take about {} MB, more than the \
             {} MB of results kept (WHIRL_JOB_RESULT_BYTES): fewer samples or a smaller analysis",
            bytes.div_ceil(1 << 20),
            limits.result_bytes >> 20
        ),
    ))
}

/// A sample as the result shows it.
fn sample(r: &SampleRow, pointers: &[String]) -> StudySample {
    StudySample {
        sample: r.sample.max(0) as u64,
        status: r.status,
        parameters: serde_json::from_str(&r.parameters).unwrap_or_default(),
        outputs: outputs(r, pointers),
        // A sample cancelled while running was not computed there.
        server: r
            .worker
            .clone()
            .filter(|_| r.status != JobStatus::Cancelled),
        error: r.error.clone(),
    }
}

/// A sample's outputs from its stored result (all null unless it succeeded).
fn outputs(row: &SampleRow, pointers: &[String]) -> Vec<Value> {
    let nulls = || vec![Value::Null; pointers.len()];
    if row.status != JobStatus::Succeeded {
        return nulls();
    }
    let mut json = vec![];
    if flate2::read::GzDecoder::new(&row.gzip[..])
        .read_to_end(&mut json)
        .is_err()
    {
        return nulls();
    }
    let Ok(doc) = serde_json::from_slice::<Value>(&json) else {
        return nulls();
    };
    pointers
        .iter()
        .map(|p| pointer::get(&doc, p).cloned().unwrap_or(Value::Null))
        .collect()
}

impl Jobs {
    /// Checks every sample of `study` and queues them all with the study (202), or none.
    pub async fn submit_study(
        &self,
        pool: Arc<WorkerPool>,
        req: &StudyRequest,
        study: Study,
        limits: StudyLimits,
    ) -> Result<StudyInfo, ApiError> {
        if !self.runner.accepting() {
            return Err(ApiError::Busy);
        }
        // A study the shared queue could never hold is the request's fault, not a wait.
        if study.samples > limits.queue {
            return Err(ApiError::Invalid(Invalid::one(
                "samples",
                format!(
                    "{} samples, more than the {} samples of all studies the queue holds \
                     (WHIRL_STUDY_QUEUE)",
                    study.samples, limits.queue
                ),
            )));
        }
        // The inputs alone past the bound: refused before thousands of them are written.
        let one = serde_json::to_string(&study.input).map_err(internal)?.len() as u64;
        if one.saturating_mul(study.samples as u64) > limits.result_bytes {
            return Err(too_large(
                study.samples,
                one.saturating_mul(study.samples as u64),
                limits,
            ));
        }
        let mut stored = req.clone();
        stored.seed = Some(study.seed);
        let request = serde_json::to_string(&stored).map_err(internal)?;
        let analysis = study.analysis;
        // Parsing thousands of inputs is CPU work: off the async runtime.
        let samples = tokio::task::spawn_blocking(move || {
            let plan = study.plan();
            check_samples(&study, &plan, &pool, limits)
        })
        .await
        .map_err(internal)??;
        let id = uuid::Uuid::now_v7().to_string();
        let name = serde_json::to_value(analysis).map_err(internal)?;
        let new = NewStudy {
            id: &id,
            analysis: name.as_str().unwrap_or_default(),
            request: &request,
        };
        if !self
            .store
            .submit_study(&new, &samples, limits.queue)
            .await?
        {
            return Err(ApiError::Busy);
        }
        tracing::info!(study = %id, samples = samples.len(), "study queued");
        let runner = self.runner.clone();
        let _ = tokio::spawn(async move { runner.claim_pass().await }).await;
        self.study(&id).await
    }

    pub async fn study(&self, id: &str) -> Result<StudyInfo, ApiError> {
        let row = self.store.study(id).await?.ok_or_else(|| not_found(id))?;
        study_info(&row)
    }

    /// Every sample with its outputs, and their statistics: once every sample has finished
    /// (409 before), or with what finished of a cancelled study.
    pub async fn study_result(&self, id: &str) -> Result<StudyResult, ApiError> {
        let row = self.store.study(id).await?.ok_or_else(|| not_found(id))?;
        let info = study_info(&row)?;
        if info.status != StudyStatus::Finished && info.status != StudyStatus::Cancelled {
            return Err(ApiError::Conflict(format!(
                "study {id} is {}: {} of {} samples finished; its result exists once all have",
                if info.status == StudyStatus::Queued {
                    "queued"
                } else {
                    "running"
                },
                info.counts.done + info.counts.failed,
                info.samples
            )));
        }
        let req = Arc::new(request(&row)?);
        // A page of samples at a time: only their outputs are kept, not their results.
        let mut samples: Vec<StudySample> = Vec::with_capacity(info.samples as usize);
        for from in (0..row.samples.max(0)).step_by(PAGE) {
            let rows = self.store.study_samples(id, from, PAGE as i64).await?;
            let req = req.clone();
            let page = tokio::task::spawn_blocking(move || {
                rows.iter()
                    .map(|r| sample(r, &req.outputs))
                    .collect::<Vec<_>>()
            })
            .await
            .map_err(internal)?;
            samples.extend(page);
        }
        let parameters: Vec<String> = req.parameters.iter().map(|p| p.pointer.clone()).collect();
        let (summary, sensitivity) = summary::summarize(&samples, &parameters, &req.outputs);
        Ok(StudyResult {
            id: id.to_string(),
            analysis: info.analysis,
            design: req.design,
            status: info.status,
            seed: req.seed.filter(|_| req.design != StudyDesign::Grid),
            parameters,
            outputs: req.outputs.clone(),
            samples,
            summary,
            sensitivity,
        })
    }

    /// Cancels a study: recorded as cancelled, its queued and running samples cancelled (each
    /// stopped at once here, within a heartbeat on another replica). 409 once it has finished.
    pub async fn cancel_study(&self, id: &str) -> Result<StudyInfo, ApiError> {
        let row = self.store.study(id).await?.ok_or_else(|| not_found(id))?;
        if study_info(&row)?.status == StudyStatus::Finished {
            return Err(ApiError::Conflict(format!(
                "study {id} has already finished: every sample has run"
            )));
        }
        let reason = "the study was cancelled by the client";
        let ids = self
            .store
            .cancel_study(id, &stopped(reason))
            .await?
            .ok_or_else(|| not_found(id))?;
        for job in &ids {
            self.runner.stop_here(job);
        }
        tracing::info!(study = id, samples = ids.len(), "study cancelled");
        self.study(id).await
    }
}
