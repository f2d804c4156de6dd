//! The job store: the queue and the results of jobs, in a database that every replica shares.
//!
//! # Design
//!
//! - **One small interface, two engines.** [`Store`] is an enum over an embedded SQLite file
//!   under `WHIRL_DATA_DIR` (the default: one server keeps its jobs and results across
//!   restarts, with no setup) and PostgreSQL (`WHIRL_DATABASE_URL`: several replicas serve one
//!   queue). Both run the same statements, spelled for each engine, on the same schema
//!   (`migrations/`, embedded in the binary and applied at connection).
//! - **A job is a row** (`jobs`): the request as received (analysis name and JSON input, so any
//!   replica parses it again into a task with its own limits), its lane and memory estimate
//!   (so a replica claims only what fits its pool), status, progress, timestamps, error
//!   (problem JSON), the replica that claimed it and its lease, and two counters: `attempts`
//!   (claims, i.e. executions) and `expiries` (leases that ran out).
//! - **Results** are the gzipped JSON of `jobs::Stored`, cut into chunks of [`CHUNK`] bytes
//!   (`job_chunks`), written with the final status in one transaction and read back one chunk
//!   at a time, so neither storing nor serving a result holds more than a chunk beyond what the
//!   analysis itself produced.
//! - **Claims.** A replica with a free worker takes the oldest queued job that fits its free
//!   lane and memory: one `UPDATE ... WHERE id = (SELECT ... FOR UPDATE SKIP LOCKED)` on
//!   PostgreSQL, so concurrent replicas never take the same row and never wait for each other.
//!   (SQLite serialises writers itself.) The claim sets `running`, the worker, a lease, and
//!   counts an attempt.
//! - **Leases.** The worker renews its lease with the job's progress every 250 ms; the same
//!   statement tells it when the job was cancelled elsewhere (it then matches no row); it
//!   renews a lease that ran out as long as no replica re-queued the job. Any replica re-queues
//!   a job whose lease ran out (its worker died) once, and fails it with that reason the second
//!   time, but only once the store has answered it for a whole lease (see Outages). Leases use
//!   the database's clock on PostgreSQL.
//! - **Fencing.** Every write of a worker names the worker and requires `running`, so a worker
//!   that lost its job (cancelled, re-queued, purged) changes nothing.
//! - **Admission** counts the shared queue: a job is inserted only while fewer than `queue`
//!   jobs wait (under an advisory lock on PostgreSQL, so replicas do not overshoot together).
//! - **Retention** is enforced in the store: finished jobs older than `retention` are not
//!   returned and are deleted, and beyond `max_finished` jobs or `max_bytes` of results the
//!   oldest finished are deleted (their chunks with them).
//! - **Studies** ([`studies`]): a study's samples are jobs naming it, claimed after every
//!   single job, outside admission, the listing and the retention of single jobs (they go
//!   with their study); [`Store::queued`] (admission, `/readyz`) counts single jobs.
//! - **Lazy connection.** The first use connects and migrates; a failure is returned (503)
//!   and retried at the next use, so a server starts without its database and `/readyz` says
//!   so.
//! - **Outages** (`breaker`): once a call finds the store unreachable, calls fail at once
//!   (503 without waiting for a connection); only the server's own pings ([`Store::ping`], the
//!   runner's upkeep every 250 ms) try the store until it answers, and the time the store came
//!   back is kept ([`Store::health`]): a lease that ran out while nobody could renew it is not
//!   a dead server's. A client's request waits [`REQUEST_WAIT`] (0.75 s) at most for a shared
//!   store, so the first call to meet a store whose packets are dropped answers within 1 s too.

mod breaker;
mod dir;
mod migrations;

pub use breaker::RETRY as PROBE_EVERY;
mod postgres;
mod sqlite;

use std::path::PathBuf;
use std::time::{Duration, SystemTime, UNIX_EPOCH};

use tokio::sync::OnceCell;

use super::pool::Lane;
use crate::model::api::{JobStatus, Problem};

/// Bytes of a result chunk.
pub const CHUNK: usize = 1 << 20;
/// Longest wait for a connection (then 503).
const CONNECT_TIMEOUT: Duration = Duration::from_secs(5);

/// How long finished jobs and their results are kept.
#[derive(Debug, Clone, Copy)]
pub struct Retention {
    pub age: Duration,
    pub max_finished: usize,
    pub max_bytes: u64,
}

/// A job to insert.
pub struct NewJob<'a> {
    pub id: &'a str,
    pub analysis: &'a str,
    pub input: &'a str,
    pub lane: Lane,
    pub memory_mib: u64,
    /// The client's `Idempotency-Key` and the SHA-256 (hex) of the request it came with.
    pub key: Option<(&'a str, &'a str)>,
}

/// What became of a submission.
#[derive(Debug, Clone)]
pub enum Submitted {
    /// Queued now.
    Queued(Box<JobRow>),
    /// The queue is full.
    Full,
    /// Its idempotency key names a job already: that job, and whether it came with the same
    /// request.
    Existing {
        row: Box<JobRow>,
        same_request: bool,
    },
}

/// What an engine's insert did.
pub(crate) enum Inserted {
    Row(Box<JobRow>),
    Full,
    /// The idempotency key is another job's (a concurrent submission with the same key).
    KeyTaken,
}

/// Whether an insert failed on a unique index (the idempotency key).
pub(crate) fn key_taken(e: &sqlx::Error) -> bool {
    e.as_database_error()
        .is_some_and(|d| d.is_unique_violation())
}

/// Which jobs `GET /v1/jobs` lists: newest first, those older than `before` (an id).
#[derive(Debug, Clone, Default)]
pub struct Filter {
    pub status: Option<JobStatus>,
    pub analysis: Option<String>,
    pub before: Option<String>,
    pub limit: u32,
}

/// A job as the API shows it.
#[derive(Debug, Clone)]
pub struct JobRow {
    pub id: String,
    pub analysis: String,
    pub status: JobStatus,
    pub progress: f64,
    /// Milliseconds since the Unix epoch.
    pub created_ms: i64,
    pub started_ms: Option<i64>,
    pub finished_ms: Option<i64>,
    pub error: Option<Problem>,
    pub attempts: i64,
    pub result_bytes: i64,
    pub result_chunks: i64,
}

/// A job this replica has claimed.
#[derive(Debug, Clone)]
pub struct Claimed {
    pub id: String,
    pub analysis: String,
    pub input: String,
    pub lane: Lane,
    pub memory_mib: u64,
    /// Time it waited in the queue.
    pub waited: Duration,
}

/// What this replica's pool can take now.
#[derive(Debug, Clone, Copy)]
pub struct Room {
    pub short: bool,
    pub long: bool,
    pub memory_mib: u64,
}

/// How a job ended, as its worker records it.
pub enum Ending {
    Succeeded(Vec<u8>),
    Failed(Problem),
    Cancelled(Problem),
}

/// A job whose lease ran out, and what became of it.
#[derive(Debug, Clone)]
pub struct Reaped {
    pub id: String,
    /// `queued` again, or `failed`.
    pub requeued: bool,
}

/// Jobs by status and bytes of results, over all replicas.
#[derive(Debug, Clone, Default)]
pub struct Stats {
    pub counts: Vec<(JobStatus, i64)>,
    pub result_bytes: i64,
}

impl Stats {
    pub fn count(&self, s: JobStatus) -> i64 {
        self.counts
            .iter()
            .find(|(k, _)| *k == s)
            .map_or(0, |(_, n)| *n)
    }
}

/// The store failed (unreachable, or an error of the database).
#[derive(Debug, Clone)]
pub struct StoreError(pub String);

impl std::fmt::Display for StoreError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl From<sqlx::Error> for StoreError {
    fn from(e: sqlx::Error) -> Self {
        StoreError(format!("job store: {e}"))
    }
}

impl From<sqlx::migrate::MigrateError> for StoreError {
    fn from(e: sqlx::migrate::MigrateError) -> Self {
        StoreError(format!("job store migration: {e}"))
    }
}

pub fn status_text(s: JobStatus) -> &'static str {
    match s {
        JobStatus::Queued => "queued",
        JobStatus::Running => "running",
        JobStatus::Succeeded => "succeeded",
        JobStatus::Failed => "failed",
        JobStatus::Cancelled => "cancelled",
    }
}

pub(crate) fn parse_status(s: &str) -> Result<JobStatus, sqlx::Error> {
    Ok(match s {
        "queued" => JobStatus::Queued,
        "running" => JobStatus::Running,
        "succeeded" => JobStatus::Succeeded,
        "failed" => JobStatus::Failed,
        "cancelled" => JobStatus::Cancelled,
        other => return Err(sqlx::Error::Decode(format!("job status {other:?}").into())),
    })
}

pub(crate) fn lane_text(l: Lane) -> &'static str {
    match l {
        Lane::Short => "short",
        Lane::Long => "long",
    }
}

pub(crate) fn parse_lane(s: &str) -> Lane {
    if s == "short" {
        Lane::Short
    } else {
        Lane::Long
    }
}

pub(crate) fn parse_problem(s: Option<String>) -> Option<Problem> {
    s.and_then(|s| serde_json::from_str(&s).ok())
}

pub(crate) fn problem_json(p: &Problem) -> String {
    serde_json::to_string(p).unwrap_or_default()
}

/// The status, error and result of an ending, as stored.
pub(crate) fn ending_parts(e: &Ending) -> (&'static str, Option<String>, &[u8]) {
    match e {
        Ending::Succeeded(gzip) => ("succeeded", None, gzip),
        Ending::Failed(p) => ("failed", Some(problem_json(p)), &[]),
        Ending::Cancelled(p) => ("cancelled", Some(problem_json(p)), &[]),
    }
}

pub(crate) fn now_ms() -> i64 {
    SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map_or(0, |d| d.as_millis() as i64)
}

pub(crate) fn ms(d: Duration) -> i64 {
    d.as_millis().min(i64::MAX as u128) as i64
}

/// Where the jobs live.
#[derive(Debug, Clone)]
pub enum Target {
    /// The embedded default: `whirl.sqlite` in this directory.
    Sqlite(PathBuf),
    /// A PostgreSQL URL.
    Postgres(String),
}

enum Engine {
    Sqlite(sqlite::Sqlite),
    Postgres(postgres::Postgres),
}

/// The job store (see the module docs).
pub struct Store {
    target: Target,
    retention: Retention,
    engine: OnceCell<Engine>,
    /// The embedded store's directory lock, held while the store lives.
    dir_lock: std::sync::Mutex<Option<std::sync::Arc<std::fs::File>>>,
    breaker: breaker::Breaker,
}

/// How long a client's request waits for a shared store before it fails (503): a store whose
/// packets are dropped would otherwise hold it for the pool's connection timeout (3 s). The
/// server's own calls (the runner's claims, heartbeats and results) wait for the pool.
pub const REQUEST_WAIT: Duration = Duration::from_millis(750);

/// Runs `$call` on whichever engine is connected,
/// through the breaker: at once 503 while the store is unreachable, but for a due probe. A
/// client's `request` waits [`REQUEST_WAIT`] at most for PostgreSQL; not answering by then
/// opens the breaker, as an unreachable store does (the next probe closes it).
macro_rules! on_engine {
    ($self:ident, request, $e:ident => $call:expr) => {
        on_engine!(@run $self, false, Some(REQUEST_WAIT), $e => $call)
    };
    ($self:ident, $e:ident => $call:expr) => {
        on_engine!(@run $self, false, None, $e => $call)
    };
    ($self:ident, $probe:expr, $e:ident => $call:expr) => {
        on_engine!(@run $self, $probe, None, $e => $call)
    };
    (@run $self:ident, $probe:expr, $wait:expr, $e:ident => $call:expr) => {{
        let pass = $self.breaker.enter($probe)?;
        let wait: Option<Duration> = $wait;
        let r = match $self.engine().await {
            Err(e) => {
                pass.done(true);
                return Err(e);
            }
            Ok(Engine::Sqlite($e)) => $call.await,
            Ok(Engine::Postgres($e)) => match wait {
                None => $call.await,
                Some(wait) => match tokio::time::timeout(wait, $call).await {
                    Ok(r) => r,
                    Err(_) => {
                        pass.done(true);
                        return Err(StoreError(format!(
                            "job store: no answer within {} ms",
                            wait.as_millis()
                        )));
                    }
                },
            },
        };
        match r {
            Ok(v) => {
                pass.done(false);
                Ok(v)
            }
            Err(e) => {
                pass.done(breaker::unreachable(&e));
                Err(e.into())
            }
        }
    }};
}

// After the macro, which they use.
pub mod studies;
mod studies_pg;
mod studies_sqlite;

impl Store {
    /// A store that connects at its first use.
    pub fn new(target: Target, retention: Retention) -> Self {
        Store {
            target,
            retention,
            engine: OnceCell::new(),
            dir_lock: std::sync::Mutex::new(None),
            breaker: breaker::Breaker::default(),
        }
    }

    /// Lets go of the data directory's lock (a server that has shut down: the next may start).
    pub fn release_dir(&self) {
        *self.dir_lock.lock().unwrap_or_else(|e| e.into_inner()) = None;
    }

    /// What this server knows of the store's health: whether it is unreachable, and whether
    /// it has answered long enough to judge leases by ([`breaker::Breaker::trusted_for`]).
    pub fn health(&self) -> &breaker::Breaker {
        &self.breaker
    }

    /// The embedded store's directory for this server alone: created private (0700) and
    /// locked, or an error naming the server that holds it. Taken at the first use at the
    /// latest; the binary takes it at start, so a second server on one directory stops there.
    /// Nothing to do for PostgreSQL.
    pub fn claim_dir(&self) -> Result<(), StoreError> {
        let Target::Sqlite(path) = &self.target else {
            return Ok(());
        };
        let mut held = self.dir_lock.lock().unwrap_or_else(|e| e.into_inner());
        if held.is_none() {
            *held = Some(dir::claim(path)?);
        }
        Ok(())
    }

    /// Where the store is, for the logs (no password).
    pub fn describe(&self) -> String {
        match &self.target {
            Target::Sqlite(dir) => format!("sqlite:{}", dir.join(sqlite::FILE).display()),
            Target::Postgres(url) => postgres::describe(url),
        }
    }

    /// Whether it has been connected (by a first use).
    pub fn connected(&self) -> bool {
        self.engine.initialized()
    }

    /// Whether it is the shared engine (PostgreSQL).
    pub fn shared(&self) -> bool {
        matches!(self.target, Target::Postgres(_))
    }

    async fn engine(&self) -> Result<&Engine, StoreError> {
        self.engine
            .get_or_try_init(|| async {
                let connect = async {
                    match &self.target {
                        Target::Sqlite(dir) => {
                            self.claim_dir()?;
                            dir::private_files(dir, sqlite::FILE)?;
                            let m = migrations::sqlite().await?;
                            sqlite::Sqlite::connect(dir, self.retention, &m)
                                .await
                                .map(Engine::Sqlite)
                        }
                        Target::Postgres(url) => {
                            let m = migrations::postgres().await?;
                            postgres::Postgres::connect(url, self.retention, &m)
                                .await
                                .map(Engine::Postgres)
                        }
                    }
                };
                match tokio::time::timeout(CONNECT_TIMEOUT, connect).await {
                    Ok(r) => r,
                    Err(_) => Err(StoreError(format!(
                        "job store: no connection to {} within {} s",
                        self.describe(),
                        CONNECT_TIMEOUT.as_secs()
                    ))),
                }
            })
            .await
    }

    /// Connects (and migrates) now; `Ok` when the store answers. While the store is
    /// unreachable, this is the probe that tries it (every [`PROBE_EVERY`] at most).
    pub async fn ping(&self) -> Result<(), StoreError> {
        on_engine!(self, true, e => e.ping())
    }

    /// Inserts a queued job unless `queue` jobs already wait, or its idempotency key names a
    /// job already.
    pub async fn submit(&self, job: &NewJob<'_>, queue: usize) -> Result<Submitted, StoreError> {
        for _ in 0..2 {
            if let Some((key, sha)) = job.key
                && let Some((row, stored)) = self.keyed(key).await?
            {
                let same_request = stored.as_deref() == Some(sha);
                return Ok(Submitted::Existing {
                    row: Box::new(row),
                    same_request,
                });
            }
            let inserted: Result<Inserted, StoreError> =
                on_engine!(self, request, e => e.submit(job, queue));
            let inserted = inserted?;
            match inserted {
                Inserted::Row(row) => return Ok(Submitted::Queued(row)),
                Inserted::Full => return Ok(Submitted::Full),
                // Another request with the same key won the insert: answer with its job.
                Inserted::KeyTaken => continue,
            }
        }
        Err(StoreError(
            "job store: the idempotency key was taken and then forgotten".into(),
        ))
    }

    /// The job an idempotency key names (however old: a key is free again once its job is
    /// deleted), with the hash of its request.
    async fn keyed(&self, key: &str) -> Result<Option<(JobRow, Option<String>)>, StoreError> {
        on_engine!(self, request, e => e.keyed(key))
    }

    /// Jobs by `filter`, newest first (finished ones within the retention).
    pub async fn list(&self, filter: &Filter) -> Result<Vec<JobRow>, StoreError> {
        on_engine!(self, request, e => e.list(filter))
    }

    /// A job, unless unknown or finished longer ago than the retention.
    pub async fn get(&self, id: &str) -> Result<Option<JobRow>, StoreError> {
        on_engine!(self, request, e => e.get(id))
    }

    /// Records a queued or running job as cancelled with `error`, at once; `None` if it is not
    /// queued or running (unknown, or finished).
    pub async fn cancel(&self, id: &str, error: &Problem) -> Result<Option<JobRow>, StoreError> {
        on_engine!(self, request, e => e.cancel(id, &problem_json(error)))
    }

    /// Claims the oldest queued job that fits `room` for `worker`, with a lease.
    pub async fn claim(
        &self,
        worker: &str,
        room: Room,
        lease: Duration,
    ) -> Result<Option<Claimed>, StoreError> {
        on_engine!(self, e => e.claim(worker, room, lease))
    }

    /// Renews the lease of a running job and records its progress; `false` when the job is no
    /// longer this worker's and running (cancelled, re-queued, forgotten).
    pub async fn heartbeat(
        &self,
        id: &str,
        worker: &str,
        progress: f64,
        lease: Duration,
    ) -> Result<bool, StoreError> {
        on_engine!(self, e => e.heartbeat(id, worker, progress, lease))
    }

    /// Records how a running job ended, with its result; `false` (nothing written) when the
    /// job is no longer this worker's and running.
    pub async fn finish(
        &self,
        id: &str,
        worker: &str,
        ending: &Ending,
    ) -> Result<bool, StoreError> {
        on_engine!(self, e => e.finish(id, worker, ending))
    }

    /// Hands a running job back to the queue (this worker is stopping).
    pub async fn release(&self, id: &str, worker: &str) -> Result<bool, StoreError> {
        on_engine!(self, e => e.release(id, worker))
    }

    /// Re-queues running jobs whose lease ran out, or fails them with `error` when their lease
    /// had run out before.
    pub async fn reap(&self, error: &Problem) -> Result<Vec<Reaped>, StoreError> {
        on_engine!(self, e => e.reap(&problem_json(error)))
    }

    /// Deletes finished jobs beyond the retention; returns how many.
    pub async fn purge(&self) -> Result<u64, StoreError> {
        on_engine!(self, e => e.purge())
    }

    /// Chunk `seq` of a job's result.
    pub async fn chunk(&self, id: &str, seq: i64) -> Result<Option<Vec<u8>>, StoreError> {
        on_engine!(self, request, e => e.chunk(id, seq))
    }

    /// Jobs waiting in the queue, over all replicas.
    pub async fn queued(&self) -> Result<i64, StoreError> {
        on_engine!(self, e => e.queued())
    }

    pub async fn stats(&self) -> Result<Stats, StoreError> {
        on_engine!(self, e => e.stats())
    }
}
