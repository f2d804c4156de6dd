//! Asynchronous jobs: `POST /v1/jobs` runs an analysis later; its status, progress, result and
//! cancellation live here.
//!
//! A job is validated and admitted to the worker pool when it is submitted (422 and 503 come
//! at once, never later), so an accepted job always runs. Cancelling a queued job takes effect
//! at once; a running one stops at its next check (the analyses check between speeds and
//! every few time steps, well under a second apart). A job that exceeds the time limit is
//! stopped the same way and fails with the reason. Finished jobs are kept for a time and within
//! a count, then forgotten (404).

use std::collections::HashMap;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

use super::AppState;
use super::error::ApiError;
use super::task::{Output, Task};
use crate::analysis::control::Control;
use crate::model::api::{JobInfo, JobStatus, Problem};

struct Job {
    analysis: String,
    status: JobStatus,
    control: Arc<Control>,
    created: SystemTime,
    started: Option<SystemTime>,
    finished: Option<(SystemTime, Instant)>,
    /// Why it was stopped, if it was (client, time limit, shutdown).
    stop_reason: Option<(JobStatus, String)>,
    error: Option<Problem>,
    output: Option<Arc<Output>>,
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
}

pub struct Jobs {
    jobs: Mutex<HashMap<String, Job>>,
    limits: JobLimits,
    accepting: std::sync::atomic::AtomicBool,
    counter: std::sync::atomic::AtomicU64,
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
            jobs: Mutex::new(HashMap::new()),
            limits,
            accepting: std::sync::atomic::AtomicBool::new(true),
            counter: std::sync::atomic::AtomicU64::new(0),
        }
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, HashMap<String, Job>> {
        self.jobs.lock().unwrap_or_else(|e| e.into_inner())
    }

    fn new_id(&self) -> String {
        let n = self
            .counter
            .fetch_add(1, std::sync::atomic::Ordering::SeqCst);
        let nanos = SystemTime::now()
            .duration_since(UNIX_EPOCH)
            .unwrap_or_default()
            .as_nanos();
        // Unique per process (counter) and unlikely to repeat across restarts (time).
        let mix = (nanos as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ n.rotate_left(32);
        format!("{:016x}{:08x}", mix, n as u32)
    }

    /// Forgets finished jobs past retention, then the oldest beyond the count.
    fn purge(&self, jobs: &mut HashMap<String, Job>) {
        let now = Instant::now();
        jobs.retain(|_, j| {
            j.finished
                .is_none_or(|(_, at)| now.duration_since(at) < self.limits.retention)
        });
        let mut finished: Vec<(Instant, String)> = jobs
            .iter()
            .filter_map(|(id, j)| j.finished.map(|(_, at)| (at, id.clone())))
            .collect();
        if finished.len() > self.limits.max_finished {
            finished.sort();
            for (_, id) in finished
                .iter()
                .take(finished.len() - self.limits.max_finished)
            {
                jobs.remove(id);
            }
        }
    }

    fn info(id: &str, j: &Job) -> JobInfo {
        JobInfo {
            id: id.to_string(),
            analysis: j.analysis.clone(),
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
        let mut jobs = self.lock();
        self.purge(&mut jobs);
        jobs.get(id)
            .map(|j| Self::info(id, j))
            .ok_or_else(|| not_found(id))
    }

    /// The output of a succeeded job; 409 otherwise.
    pub fn result(&self, id: &str) -> Result<Arc<Output>, ApiError> {
        let mut jobs = self.lock();
        self.purge(&mut jobs);
        let j = jobs.get(id).ok_or_else(|| not_found(id))?;
        match (&j.output, j.status) {
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

    /// Cancels a job: a queued one at once, a running one at its next check.
    pub fn cancel(&self, id: &str, reason: &str) -> Result<JobInfo, ApiError> {
        let mut jobs = self.lock();
        let j = jobs.get_mut(id).ok_or_else(|| not_found(id))?;
        match j.status {
            JobStatus::Queued => {
                j.control.cancel();
                j.status = JobStatus::Cancelled;
                j.finished = Some((SystemTime::now(), Instant::now()));
                j.error = Some(stopped(reason));
            }
            JobStatus::Running => {
                j.stop_reason = Some((JobStatus::Cancelled, reason.to_string()));
                j.control.cancel();
            }
            s => {
                return Err(ApiError::Conflict(format!(
                    "job {id} has already finished ({})",
                    status_name(s)
                )));
            }
        }
        Ok(Self::info(id, j))
    }

    /// Counts by status, for the metrics.
    pub fn counts(&self) -> [(JobStatus, usize); 5] {
        let jobs = self.lock();
        let mut c = [
            (JobStatus::Queued, 0),
            (JobStatus::Running, 0),
            (JobStatus::Succeeded, 0),
            (JobStatus::Failed, 0),
            (JobStatus::Cancelled, 0),
        ];
        for j in jobs.values() {
            if let Some(e) = c.iter_mut().find(|e| e.0 == j.status) {
                e.1 += 1;
            }
        }
        c
    }

    /// Stops taking jobs; lets running ones finish within `grace`, then cancels what is left
    /// (queued and running) with the reason recorded.
    pub async fn shutdown(&self, grace: Duration) {
        self.accepting
            .store(false, std::sync::atomic::Ordering::SeqCst);
        let deadline = Instant::now() + grace;
        let busy = |jobs: &Jobs| {
            jobs.lock()
                .values()
                .any(|j| matches!(j.status, JobStatus::Queued | JobStatus::Running))
        };
        while busy(self) && Instant::now() < deadline {
            tokio::time::sleep(Duration::from_millis(50)).await;
        }
        let ids: Vec<String> = self
            .lock()
            .iter()
            .filter(|(_, j)| matches!(j.status, JobStatus::Queued | JobStatus::Running))
            .map(|(id, _)| id.clone())
            .collect();
        for id in ids {
            let _ = self.cancel(&id, "the server is shutting down");
        }
        let deadline = Instant::now() + Duration::from_secs(2);
        while busy(self) && Instant::now() < deadline {
            tokio::time::sleep(Duration::from_millis(20)).await;
        }
    }

    fn finish(&self, id: &str, result: Result<Output, ApiError>) {
        let mut jobs = self.lock();
        let Some(j) = jobs.get_mut(id) else { return };
        if j.status == JobStatus::Cancelled {
            return; // cancelled while queued
        }
        j.finished = Some((SystemTime::now(), Instant::now()));
        match result {
            Ok(out) => {
                j.status = JobStatus::Succeeded;
                j.output = Some(Arc::new(out));
            }
            Err(ApiError::Cancelled) => {
                let (status, reason) = j
                    .stop_reason
                    .clone()
                    .unwrap_or((JobStatus::Cancelled, "cancelled".into()));
                j.status = status;
                j.error = Some(stopped(&reason));
            }
            Err(e) => {
                j.status = JobStatus::Failed;
                j.error = Some(e.problem());
            }
        }
        self.purge(&mut jobs);
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
pub fn submit(st: &AppState, analysis: &str, task: Task) -> Result<JobInfo, ApiError> {
    let jobs = st.jobs.clone();
    if !jobs.accepting.load(std::sync::atomic::Ordering::SeqCst) {
        return Err(ApiError::Busy);
    }
    let admission = st.pool.admit()?;
    let id = jobs.new_id();
    let control = Arc::new(Control::default());
    let info = {
        let mut map = jobs.lock();
        jobs.purge(&mut map);
        let job = Job {
            analysis: analysis.to_string(),
            status: JobStatus::Queued,
            control: control.clone(),
            created: SystemTime::now(),
            started: None,
            finished: None,
            stop_reason: None,
            error: None,
            output: None,
        };
        let info = Jobs::info(&id, &job);
        map.insert(id.clone(), job);
        info
    };
    let pool = st.pool.clone();
    let metrics = st.metrics.clone();
    let limit = jobs.limits.time_limit;
    let analysis = analysis.to_string();
    tokio::spawn(async move {
        let start_id = id.clone();
        let start_jobs = jobs.clone();
        let run_control = control.clone();
        let started = move || {
            let mut map = start_jobs.lock();
            if let Some(j) = map.get_mut(&start_id)
                && j.status == JobStatus::Queued
            {
                j.status = JobStatus::Running;
                j.started = Some(SystemTime::now());
            }
        };
        let t0 = Instant::now();
        let work = pool.run_admitted(admission, started, move || {
            // Cancelled while it waited: do nothing.
            run_control.check().map_err(|_| ApiError::Cancelled)?;
            task.run(&run_control)
        });
        tokio::pin!(work);
        let result = tokio::select! {
            r = &mut work => r,
            _ = tokio::time::sleep(limit) => {
                {
                    let mut map = jobs.lock();
                    if let Some(j) = map.get_mut(&id) {
                        j.stop_reason = Some((
                            JobStatus::Failed,
                            format!("exceeded the time limit of {} s (WHIRL_JOB_TIME_LIMIT)", limit.as_secs()),
                        ));
                    }
                }
                control.cancel();
                work.await
            }
        };
        metrics.observe_analysis(&analysis, t0.elapsed());
        jobs.finish(&id, result);
    });
    Ok(info)
}
