//! Asynchronous jobs: `POST /v1/jobs` runs an analysis later; its status, progress, result and
//! cancellation live here.
//!
//! A job is validated and admitted to the worker pool when it is submitted (422 and 503 come
//! at once, never later), so an accepted job always runs. Cancelling takes effect at once: the
//! job is recorded as cancelled and its analysis is told to stop, which it does at its next
//! check (between speeds, samples and time steps); its worker and memory are released then.
//! A job that exceeds the time limit is stopped the same way and fails with the reason.
//! Results are kept as gzipped JSON, within a total of compressed bytes, a count and an age;
//! past those the oldest finished jobs are forgotten (404).

use std::collections::HashMap;
use std::io::{Read, Write};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

use tokio::sync::Notify;

use super::AppState;
use super::error::ApiError;
use super::task::{Format, Output, Rendered, execute, render};
use crate::analysis::control::Control;
use crate::model::Task;
use crate::model::api::{JobInfo, JobStatus, Problem};

/// A finished job's result: its JSON, gzipped.
pub struct Stored {
    pub analysis: &'static str,
    pub gzip: Vec<u8>,
}

impl Stored {
    fn new(analysis: &'static str, out: &Output) -> Result<Self, ApiError> {
        let json = serde_json::to_vec(out).map_err(|e| ApiError::Internal(e.to_string()))?;
        let mut enc = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
        enc.write_all(&json)
            .map_err(|e| ApiError::Internal(e.to_string()))?;
        let gzip = enc
            .finish()
            .map_err(|e| ApiError::Internal(e.to_string()))?;
        Ok(Stored { analysis, gzip })
    }

    fn json(&self) -> Result<Vec<u8>, ApiError> {
        let mut out = vec![];
        flate2::read::GzDecoder::new(&self.gzip[..])
            .read_to_end(&mut out)
            .map_err(|e| ApiError::Internal(format!("stored result: {e}")))?;
        Ok(out)
    }

    /// The result in the first acceptable format; the stored gzip itself when the client takes
    /// gzipped JSON (nothing is rebuilt).
    pub fn render(&self, formats: &[Format], gzip_ok: bool) -> Result<(Rendered, bool), ApiError> {
        if formats.first() == Some(&Format::Json) {
            if gzip_ok {
                return Ok((
                    Rendered {
                        media: Format::Json.media(),
                        body: self.gzip.clone(),
                    },
                    true,
                ));
            }
            return Ok((
                Rendered {
                    media: Format::Json.media(),
                    body: self.json()?,
                },
                false,
            ));
        }
        let out = Output::from_json(self.analysis, &self.json()?)?;
        Ok((render(&out, formats)?, false))
    }
}

struct Job {
    analysis: &'static str,
    status: JobStatus,
    control: Arc<Control>,
    /// Wakes the job's runner when it is stopped from outside.
    stop: Arc<Notify>,
    created: SystemTime,
    started: Option<SystemTime>,
    finished: Option<(SystemTime, Instant)>,
    error: Option<Problem>,
    result: Option<Arc<Stored>>,
}

/// Settings of the job store.
#[derive(Debug, Clone, Copy)]
pub struct JobLimits {
    /// How long a finished job is kept.
    pub retention: Duration,
    /// Most finished jobs kept (oldest forgotten first).
    pub max_finished: usize,
    /// Longest a job may run.
    pub time_limit: Duration,
    /// Compressed bytes of results kept.
    pub max_result_bytes: u64,
    /// Largest answer.
    pub max_response_bytes: u64,
}

struct Table {
    jobs: HashMap<String, Job>,
    /// Compressed bytes of the results held.
    stored: u64,
}

pub struct Jobs {
    table: Mutex<Table>,
    limits: JobLimits,
    accepting: std::sync::atomic::AtomicBool,
}

fn rfc3339(t: SystemTime) -> String {
    let d = t.duration_since(UNIX_EPOCH).unwrap_or_default();
    let secs = d.as_secs() as i64;
    let (days, rem) = (secs.div_euclid(86_400), secs.rem_euclid(86_400));
    // Civil from days (Howard Hinnant's algorithm).
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!(
        "{year:04}-{month:02}-{day:02}T{:02}:{:02}:{:02}.{:03}Z",
        rem / 3600,
        rem % 3600 / 60,
        rem % 60,
        d.subsec_millis()
    )
}

impl Jobs {
    pub fn new(limits: JobLimits) -> Self {
        Jobs {
            table: Mutex::new(Table {
                jobs: HashMap::new(),
                stored: 0,
            }),
            limits,
            accepting: std::sync::atomic::AtomicBool::new(true),
        }
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Table> {
        self.table.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// A UUIDv7: unique across restarts and replicas, and ordered by creation time.
    fn new_id(&self) -> String {
        uuid::Uuid::now_v7().to_string()
    }

    /// Forgets finished jobs past retention, then the oldest beyond the count and beyond the
    /// bytes of results.
    fn purge(&self, t: &mut Table) {
        let now = Instant::now();
        let retention = self.limits.retention;
        let mut freed = 0;
        t.jobs.retain(|_, j| {
            let keep = j
                .finished
                .is_none_or(|(_, at)| now.duration_since(at) < retention);
            if !keep {
                freed += j.result.as_ref().map_or(0, |r| r.gzip.len() as u64);
            }
            keep
        });
        t.stored -= freed;
        let mut finished: Vec<(Instant, String)> = t
            .jobs
            .iter()
            .filter_map(|(id, j)| j.finished.map(|(_, at)| (at, id.clone())))
            .collect();
        finished.sort();
        let mut count = finished.len();
        for (_, id) in finished {
            if count <= self.limits.max_finished && t.stored <= self.limits.max_result_bytes {
                break;
            }
            if let Some(j) = t.jobs.remove(&id) {
                t.stored -= j.result.as_ref().map_or(0, |r| r.gzip.len() as u64);
            }
            count -= 1;
        }
    }

    fn info(id: &str, j: &Job) -> JobInfo {
        JobInfo {
            id: id.to_string(),
            analysis: j.analysis.to_string(),
            status: j.status,
            progress: match j.status {
                JobStatus::Succeeded => 1.0,
                JobStatus::Queued => 0.0,
                _ => j.control.progress(),
            },
            created_at: rfc3339(j.created),
            started_at: j.started.map(rfc3339),
            finished_at: j.finished.map(|(t, _)| rfc3339(t)),
            error: j.error.clone(),
        }
    }

    pub fn get(&self, id: &str) -> Result<JobInfo, ApiError> {
        let mut t = self.lock();
        self.purge(&mut t);
        t.jobs
            .get(id)
            .map(|j| Self::info(id, j))
            .ok_or_else(|| not_found(id))
    }

    /// The result of a succeeded job; 409 otherwise.
    pub fn result(&self, id: &str) -> Result<Arc<Stored>, ApiError> {
        let mut t = self.lock();
        self.purge(&mut t);
        let j = t.jobs.get(id).ok_or_else(|| not_found(id))?;
        match (&j.result, j.status) {
            (Some(o), JobStatus::Succeeded) => Ok(o.clone()),
            (_, status) => Err(ApiError::Conflict(format!(
                "job {id} is {}: its result exists once it has succeeded{}",
                status_name(status),
                j.error
                    .as_ref()
                    .map(|e| format!(" ({})", e.detail))
                    .unwrap_or_default()
            ))),
        }
    }

    /// Stops a job at once: it is recorded with `status` and `reason`, its analysis told to
    /// stop, its runner woken. 409 if it has finished.
    fn stop(&self, id: &str, status: JobStatus, reason: &str) -> Result<JobInfo, ApiError> {
        let mut t = self.lock();
        let j = t.jobs.get_mut(id).ok_or_else(|| not_found(id))?;
        match j.status {
            JobStatus::Queued | JobStatus::Running => {
                j.control.cancel();
                j.stop.notify_one();
                j.status = status;
                j.finished = Some((SystemTime::now(), Instant::now()));
                j.error = Some(stopped(reason));
                tracing::info!(job = id, analysis = j.analysis, reason, "job stopped");
                Ok(Self::info(id, j))
            }
            s => Err(ApiError::Conflict(format!(
                "job {id} has already finished ({})",
                status_name(s)
            ))),
        }
    }

    /// Cancels a job (a client's request).
    pub fn cancel(&self, id: &str, reason: &str) -> Result<JobInfo, ApiError> {
        self.stop(id, JobStatus::Cancelled, reason)
    }

    /// Compressed bytes of the results held.
    pub fn stored_bytes(&self) -> u64 {
        self.lock().stored
    }

    /// Counts by status, for the metrics.
    pub fn counts(&self) -> [(JobStatus, usize); 5] {
        let t = self.lock();
        let mut c = [
            (JobStatus::Queued, 0),
            (JobStatus::Running, 0),
            (JobStatus::Succeeded, 0),
            (JobStatus::Failed, 0),
            (JobStatus::Cancelled, 0),
        ];
        for j in t.jobs.values() {
            if let Some(e) = c.iter_mut().find(|e| e.0 == j.status) {
                e.1 += 1;
            }
        }
        c
    }

    /// Stops taking jobs; lets running ones finish within `grace`, then stops what is left
    /// (queued and running) as cancelled by the shutdown, each logged.
    pub async fn shutdown(&self, grace: Duration) {
        self.accepting
            .store(false, std::sync::atomic::Ordering::SeqCst);
        let deadline = Instant::now() + grace;
        let busy = |jobs: &Jobs| -> Vec<String> {
            jobs.lock()
                .jobs
                .iter()
                .filter(|(_, j)| matches!(j.status, JobStatus::Queued | JobStatus::Running))
                .map(|(id, _)| id.clone())
                .collect()
        };
        while !busy(self).is_empty() && Instant::now() < deadline {
            tokio::time::sleep(Duration::from_millis(50)).await;
        }
        for id in busy(self) {
            if self
                .stop(
                    &id,
                    JobStatus::Cancelled,
                    "cancelled: the server is shutting down",
                )
                .is_ok()
            {
                tracing::warn!(job = %id, "job cancelled by shutdown");
            }
        }
    }

    /// Records how a job's analysis ended, unless it was stopped before.
    fn finish(&self, id: &str, result: Result<Stored, ApiError>) {
        let mut t = self.lock();
        let Some(j) = t.jobs.get_mut(id) else { return };
        if !matches!(j.status, JobStatus::Queued | JobStatus::Running) {
            return; // stopped from outside: already recorded
        }
        j.finished = Some((SystemTime::now(), Instant::now()));
        let mut added = 0;
        match result {
            Ok(stored) if stored.gzip.len() as u64 > self.limits.max_result_bytes => {
                j.status = JobStatus::Failed;
                j.error = Some(
                    ApiError::Unsolvable(format!(
                        "the result is {} MB compressed, more than the {} MB kept for all jobs \
                         (WHIRL_JOB_RESULT_BYTES)",
                        stored.gzip.len().div_ceil(1 << 20),
                        self.limits.max_result_bytes >> 20
                    ))
                    .problem(),
                );
            }
            Ok(stored) => {
                j.status = JobStatus::Succeeded;
                added = stored.gzip.len() as u64;
                j.result = Some(Arc::new(stored));
            }
            Err(ApiError::Cancelled) => {
                j.status = JobStatus::Cancelled;
                j.error = Some(stopped("cancelled"));
            }
            Err(e) => {
                j.status = JobStatus::Failed;
                j.error = Some(e.problem());
            }
        }
        t.stored += added;
        self.purge(&mut t);
    }
}

fn stopped(reason: &str) -> Problem {
    ApiError::Stopped(reason.to_string()).problem()
}

fn not_found(id: &str) -> ApiError {
    ApiError::NotFound(format!("no job {id} (unknown, or finished and forgotten)"))
}

pub fn status_name(s: JobStatus) -> &'static str {
    match s {
        JobStatus::Queued => "queued",
        JobStatus::Running => "running",
        JobStatus::Succeeded => "succeeded",
        JobStatus::Failed => "failed",
        JobStatus::Cancelled => "cancelled",
    }
}

/// Admits and starts a job; returns its status (queued).
pub fn submit(st: &AppState, task: Task) -> Result<JobInfo, ApiError> {
    let jobs = st.jobs.clone();
    if !jobs.accepting.load(std::sync::atomic::Ordering::SeqCst) {
        return Err(ApiError::Busy);
    }
    let admission = st.pool.admit(&task.cost, task.size_field())?;
    let id = jobs.new_id();
    let analysis = task.name();
    let control = Arc::new(Control::default());
    let stop = Arc::new(Notify::new());
    let info = {
        let mut t = jobs.lock();
        jobs.purge(&mut t);
        let job = Job {
            analysis,
            status: JobStatus::Queued,
            control: control.clone(),
            stop: stop.clone(),
            created: SystemTime::now(),
            started: None,
            finished: None,
            error: None,
            result: None,
        };
        let info = Jobs::info(&id, &job);
        t.jobs.insert(id.clone(), job);
        info
    };
    let pool = st.pool.clone();
    let metrics = st.metrics.clone();
    let limit = jobs.limits.time_limit;
    let max_bytes = jobs.limits.max_response_bytes;
    tokio::spawn(async move {
        let start_id = id.clone();
        let start_jobs = jobs.clone();
        let started = move || {
            let mut t = start_jobs.lock();
            if let Some(j) = t.jobs.get_mut(&start_id)
                && j.status == JobStatus::Queued
            {
                j.status = JobStatus::Running;
                j.started = Some(SystemTime::now());
            }
        };
        let t0 = Instant::now();
        let run_control = control.clone();
        let work = pool.run(admission, started, move || {
            // Stopped while it waited: do nothing.
            run_control.check().map_err(|_| ApiError::Cancelled)?;
            let out = execute(&task, &run_control, max_bytes)?;
            Stored::new(analysis, &out)
        });
        tokio::select! {
            r = work => {
                metrics.observe_analysis(analysis, t0.elapsed());
                jobs.finish(&id, r.and_then(|r| r));
            }
            _ = tokio::time::sleep(limit) => {
                let reason = format!(
                    "exceeded the time limit of {} s (WHIRL_JOB_TIME_LIMIT)",
                    limit.as_secs_f64()
                );
                let _ = jobs.stop(&id, JobStatus::Failed, &reason);
            }
            // Cancelled or shut down: recorded by `stop`; the analysis stops at its next check.
            _ = stop.notified() => {}
        }
    });
    Ok(info)
}
