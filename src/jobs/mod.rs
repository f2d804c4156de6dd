//! Analyses run off the request: the worker pool that synchronous requests and jobs share
//! ([`pool`]), and the jobs: their store ([`store`]: SQLite or PostgreSQL), how a job and its
//! result are kept there ([`stored`]), this replica's runner that claims and runs them
//! ([`runner`]), and the counters `/metrics` shows ([`metrics`]). Below the HTTP layer, which
//! uses [`Jobs`] and the pool; above `answer`, whose outputs and errors it keeps.
//!
//! Asynchronous jobs as the API sees them: `POST /v1/jobs` puts an analysis in the shared
//! queue; its status, progress, result and cancellation are read from the job store, so any
//! replica answers for any job, and a restart forgets nothing.
//!
//! A job is validated when it is submitted (422 at once, never later) and admitted against the
//! shared queue (503 with `Retry-After` when `queue` jobs already wait, over all replicas). The
//! replica that received it then looks for work at once, so a job submitted to an idle replica
//! starts without waiting for a poll ([`runner`] claims and runs jobs).
//! Cancelling takes effect at once: the store records the job as cancelled, and the replica
//! running it stops its analysis at its next check (at once when that is this replica, within
//! a heartbeat otherwise). Results are kept gzipped in the store, within a total of compressed
//! bytes, a count and an age; past those the oldest finished jobs are forgotten (404).

pub mod metrics;
pub mod pool;
pub mod runner;
pub mod store;
pub mod stored;
pub mod studies;

use std::sync::Arc;
use std::time::{Duration, UNIX_EPOCH};

use serde_json::Value;

use crate::answer::ApiError;
use crate::model::Task;
use crate::model::api::{JobInfo, JobStatus};
use pool::WorkerPool;
use runner::Runner;
use store::{Filter, JobRow, NewJob, Stats, Store, StoreError, Submitted, status_text};
pub use stored::{Stored, job_input, parse_stored, stopped};

impl From<StoreError> for ApiError {
    fn from(e: StoreError) -> Self {
        ApiError::Unavailable(e.0)
    }
}

pub fn rfc3339_ms(ms: i64) -> String {
    let t = UNIX_EPOCH + Duration::from_millis(ms.max(0) as u64);
    rfc3339(t)
}

fn rfc3339(t: std::time::SystemTime) -> String {
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

/// A job's row as the API shows it.
pub fn info(r: &JobRow) -> JobInfo {
    JobInfo {
        id: r.id.clone(),
        analysis: r.analysis.clone(),
        status: r.status,
        progress: match r.status {
            JobStatus::Succeeded => 1.0,
            JobStatus::Queued => 0.0,
            _ => r.progress.clamp(0.0, 1.0),
        },
        created_at: rfc3339_ms(r.created_ms),
        started_at: r.started_ms.map(rfc3339_ms),
        finished_at: r.finished_ms.map(rfc3339_ms),
        error: r.error.clone(),
    }
}

fn not_found(id: &str) -> ApiError {
    ApiError::NotFound(format!("no job {id} (unknown, or finished and forgotten)"))
}

pub fn status_name(s: JobStatus) -> &'static str {
    status_text(s)
}

/// The jobs of the whole service, through the store.
pub struct Jobs {
    pub store: Arc<Store>,
    pub runner: Arc<Runner>,
    /// Jobs that may wait in the shared queue.
    queue: usize,
}

impl Jobs {
    pub fn new(store: Arc<Store>, runner: Arc<Runner>, queue: usize) -> Self {
        Jobs {
            store,
            runner,
            queue,
        }
    }

    /// Admits a validated job to the shared queue (`input`: its JSON as received); returns its
    /// status (queued). With an idempotency `key` (the client's, and the SHA-256 of the
    /// request it came with) a job the key already names is returned instead (`true`: a
    /// replay), and a different request under a key in use is refused.
    pub async fn submit(
        &self,
        pool: &WorkerPool,
        input: &Value,
        task: &Task,
        key: Option<(&str, &str)>,
    ) -> Result<(JobInfo, bool), ApiError> {
        if !self.runner.accepting() {
            return Err(ApiError::Busy);
        }
        let (lane, memory_mib) = pool.needs(&task.cost, task.size_field())?;
        let id = uuid::Uuid::now_v7().to_string();
        let input = serde_json::to_string(input).map_err(|e| ApiError::Internal(e.to_string()))?;
        let job = NewJob {
            id: &id,
            analysis: task.name(),
            input: &input,
            lane,
            memory_mib,
            key,
        };
        let row = match self.store.submit(&job, self.queue).await? {
            Submitted::Queued(row) => row,
            Submitted::Full => return Err(ApiError::Busy),
            Submitted::Existing {
                row,
                same_request: true,
            } => return Ok((info(&row), true)),
            Submitted::Existing { row, .. } => {
                return Err(ApiError::KeyReused(format!(
                    "the Idempotency-Key names job {} ({}), submitted with another request; \
                     use a new key for a new job",
                    row.id, row.analysis
                )));
            }
        };
        tracing::info!(job = %id, analysis = task.name(), "job queued");
        // Start it here if this replica has room (oldest first), in a task of its own: a
        // client that goes away must not interrupt a claim.
        let runner = self.runner.clone();
        let _ = tokio::spawn(async move { runner.claim_pass().await }).await;
        Ok((info(&row), false))
    }

    /// Jobs by `filter`, newest first.
    pub async fn list(&self, filter: &Filter) -> Result<Vec<JobInfo>, ApiError> {
        Ok(self.store.list(filter).await?.iter().map(info).collect())
    }

    pub async fn get(&self, id: &str) -> Result<JobInfo, ApiError> {
        let row = self.store.get(id).await?.ok_or_else(|| not_found(id))?;
        Ok(info(&row))
    }

    /// The row of a succeeded job (its result is in the store); 409 otherwise.
    pub async fn result(&self, id: &str) -> Result<JobRow, ApiError> {
        let row = self.store.get(id).await?.ok_or_else(|| not_found(id))?;
        if row.status == JobStatus::Succeeded {
            return Ok(row);
        }
        Err(ApiError::Conflict(format!(
            "job {id} is {}: its result exists once it has succeeded{}",
            status_name(row.status),
            row.error
                .as_ref()
                .map(|e| format!(" ({})", e.detail))
                .unwrap_or_default()
        )))
    }

    /// Cancels a job at once: recorded as cancelled with `reason` in the store (every replica
    /// sees it), its analysis stopped here at once, or by the replica running it within a
    /// heartbeat. 409 if it has finished.
    pub async fn cancel(&self, id: &str, reason: &str) -> Result<JobInfo, ApiError> {
        match self.store.cancel(id, &stopped(reason)).await? {
            Some(row) => {
                self.runner.stop_here(id);
                tracing::info!(job = id, analysis = %row.analysis, reason, "job stopped");
                Ok(info(&row))
            }
            None => match self.store.get(id).await? {
                Some(row) => Err(ApiError::Conflict(format!(
                    "job {id} has already finished ({})",
                    status_name(row.status)
                ))),
                None => Err(not_found(id)),
            },
        }
    }

    /// Jobs waiting in the shared queue.
    pub async fn queued(&self) -> Result<i64, ApiError> {
        Ok(self.store.queued().await?)
    }

    /// Whether the shared queue is full.
    pub fn full(&self, queued: i64) -> bool {
        queued >= self.queue as i64
    }

    /// Jobs by status over all replicas, for the metrics.
    pub async fn stats(&self) -> Result<Stats, StoreError> {
        self.store.stats().await
    }

    /// Stops taking and claiming jobs; lets this replica's running jobs finish within `grace`,
    /// then hands what is left back to the queue, each logged (see [`Runner::shutdown`]); the
    /// data directory is then free for the next server.
    pub async fn shutdown(&self, grace: Duration) {
        self.runner.shutdown(grace).await;
        self.store.release_dir();
    }
}
