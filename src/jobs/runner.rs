//! This replica's side of the shared queue: it claims jobs when its pool has room, runs them,
//! renews their leases, records how they end, and keeps the store tidy.
//!
//! # Design
//!
//! - **Claim passes** run after a submission to this replica, when a job here ends, and every
//!   [`POLL`] (jobs submitted to other replicas, workers freed by synchronous requests, jobs
//!   re-queued). A pass takes a free worker from the pool *before* it claims
//!   ([`WorkerPool::try_worker`]) and claims only a job that fits that lane and the free memory
//!   budget; passes are serialised on this replica. So a replica never claims more than its
//!   pool can start, and a job waits in the shared queue, where any replica with room can take
//!   it, rather than inside a busy replica.
//! - **Running a claimed job.** Its stored request is parsed again with this replica's limits
//!   and run on the pool. A heartbeat every [`HEARTBEAT`] writes its progress and renews its
//!   lease. A heartbeat that matches no row means the job was stopped elsewhere (cancelled on
//!   another replica, or forgotten): its `Control` is cancelled, and the analysis stops at its
//!   next check. A cancel received here stops it at once.
//! - **Time limit.** A job running past `WHIRL_JOB_TIME_LIMIT` is recorded as failed with the
//!   reason, and its analysis is stopped.
//! - **Losing the store.** A worker keeps its job while it cannot reach the store, and renews
//!   the lease when it can again; only if another replica re-queued the job meanwhile (the
//!   renewal then matches no row) does it stop. A worker that cannot record an end retries
//!   until the store answers (for a lease at most once the server is shutting down).
//! - **Probing the store.** While the store is unreachable, the maintenance loop pings it
//!   every [`PROBE_EVERY`]: the only call let through until it answers (clients' calls and the
//!   workers' heartbeats fail at once meanwhile).
//! - **Maintenance**, every quarter lease (between 0.25 and 2 s): jobs whose lease ran out are
//!   re-queued once and failed the second time (any replica does it; the update is atomic),
//!   but only by a replica that has reached the store for a whole lease since it last found it
//!   unreachable, and right after a ping answered promptly (a quarter lease, 0.25 to 1 s): after
//!   an outage the workers that kept their jobs renew them first, so an expiry is a server that
//!   is gone, not an outage. An outage too short for any call to fail (the pool waits 3 s for a
//!   connection) shows as a slow ping, and counts as one: no reap for a lease after it, and none
//!   sent into it to run when it ends. Retention is applied too.
//! - **Shutdown.** No more claims or submissions. Running jobs get the grace, and what is left
//!   is handed back to the queue, each logged, to run again from the start on another replica
//!   or after the restart. Queued jobs stay queued.

use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use tokio::sync::Notify;

use super::metrics::Metrics;
use super::pool::{Lane, Reserved, WorkerPool, release_free_memory};
use super::store::{Claimed, Ending, PROBE_EVERY, Room, Store};
use super::stored::{Stored, parse_stored, stopped};
use crate::analysis::control::Control;
use crate::answer::{ApiError, execute};
use crate::model::Limits;

/// How often a running job's progress is written and its lease renewed.
pub const HEARTBEAT: Duration = Duration::from_millis(250);
/// How often an idle replica looks for queued jobs.
pub const POLL: Duration = Duration::from_millis(500);

/// What the runner takes of the service's settings (`service::Config::runner`).
#[derive(Debug, Clone, Copy)]
pub struct Settings {
    /// The limits a stored request is parsed with: this replica's.
    pub limits: Limits,
    pub max_response_bytes: u64,
    pub job_time_limit: Duration,
    /// Compressed bytes of finished jobs' results kept.
    pub job_result_bytes: u64,
    /// How long a running job's lease lasts without a heartbeat.
    pub job_lease: Duration,
}

/// A job running on this replica.
struct Local {
    control: Arc<Control>,
    /// Wakes its runner when it is stopped from outside.
    stop: Arc<Notify>,
}

pub struct Runner {
    /// This replica's name in the store (`worker` of the jobs it claims).
    pub worker: String,
    store: Arc<Store>,
    pool: Arc<WorkerPool>,
    metrics: Arc<Metrics>,
    config: Settings,
    local: Mutex<HashMap<String, Local>>,
    claiming: tokio::sync::Mutex<()>,
    wake: Notify,
    accepting: AtomicBool,
}

/// A name for this replica: host, process and a random part.
fn worker_name() -> String {
    let host = std::fs::read_to_string("/proc/sys/kernel/hostname")
        .ok()
        .or_else(|| std::env::var("HOSTNAME").ok())
        .map(|h| h.trim().to_string())
        .filter(|h| !h.is_empty())
        .unwrap_or_else(|| "whirl".into());
    let id = uuid::Uuid::now_v7().simple().to_string();
    format!("{host}/{}/{}", std::process::id(), &id[id.len() - 8..])
}

impl Runner {
    pub fn new(
        store: Arc<Store>,
        pool: Arc<WorkerPool>,
        metrics: Arc<Metrics>,
        config: Settings,
    ) -> Self {
        Runner {
            worker: worker_name(),
            store,
            pool,
            metrics,
            config,
            local: Mutex::new(HashMap::new()),
            claiming: tokio::sync::Mutex::new(()),
            wake: Notify::new(),
            accepting: AtomicBool::new(true),
        }
    }

    fn local(&self) -> std::sync::MutexGuard<'_, HashMap<String, Local>> {
        self.local.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Whether this replica takes and claims jobs (not shutting down).
    pub fn accepting(&self) -> bool {
        self.accepting.load(Ordering::SeqCst)
    }

    /// Jobs running on this replica.
    pub fn running_here(&self) -> usize {
        self.local().len()
    }

    /// Starts the claim and maintenance loops (on the current runtime). They work once the
    /// store has been connected: by the binary at startup, or by a first request.
    pub fn start(self: &Arc<Self>) {
        let me = self.clone();
        tokio::spawn(async move {
            while me.accepting() {
                tokio::select! {
                    () = me.wake.notified() => {}
                    () = tokio::time::sleep(POLL) => {}
                }
                if me.store.connected() {
                    me.claim_pass().await;
                }
            }
        });
        tokio::spawn(self.clone().maintain());
    }

    /// Claims and starts queued jobs while this replica's pool has room for them.
    pub async fn claim_pass(self: &Arc<Self>) {
        let _one = self.claiming.lock().await;
        while self.accepting() {
            let short = self.pool.try_worker(Lane::Short);
            let long = self.pool.try_worker(Lane::Long);
            if short.is_none() && long.is_none() {
                return;
            }
            let room = Room {
                short: short.is_some(),
                long: long.is_some(),
                memory_mib: self.pool.memory_free_mib(),
            };
            let t0 = Instant::now();
            let job = match self
                .store
                .claim(&self.worker, room, self.config.job_lease)
                .await
            {
                Ok(Some(job)) => job,
                Ok(None) => return,
                Err(e) => {
                    self.metrics.store_error();
                    tracing::warn!(error = %e, "could not look for queued jobs");
                    return;
                }
            };
            self.metrics.observe_claim(t0.elapsed(), job.waited);
            let worker = match job.lane {
                Lane::Short => short,
                Lane::Long => long,
            };
            let Some(worker) = worker else {
                // The claim matches only lanes with a worker in hand: not reached.
                let _ = self.store.release(&job.id, &self.worker).await;
                return;
            };
            let reserved = self.pool.reserve(job.lane, worker, job.memory_mib);
            tracing::info!(
                job = %job.id,
                analysis = %job.analysis,
                waited_ms = job.waited.as_millis() as u64,
                "job claimed"
            );
            let control = Arc::new(Control::default());
            let stop = Arc::new(Notify::new());
            self.local().insert(
                job.id.clone(),
                Local {
                    control: control.clone(),
                    stop: stop.clone(),
                },
            );
            tokio::spawn(self.clone().run(job, reserved, control, stop));
        }
    }

    /// Stops the analysis of a job running here (it was cancelled here).
    pub fn stop_here(&self, id: &str) {
        if let Some(l) = self.local().get(id) {
            l.control.cancel();
            l.stop.notify_one();
        }
    }

    async fn run(
        self: Arc<Self>,
        job: Claimed,
        reserved: Reserved,
        control: Arc<Control>,
        stop: Arc<Notify>,
    ) {
        let id = job.id.clone();
        let heartbeat = tokio::spawn(self.clone().heartbeat(
            id.clone(),
            control.clone(),
            stop.clone(),
        ));
        match parse_stored(&job.analysis, &job.input, &self.config.limits) {
            Ok(task) => {
                let analysis = task.name();
                let max_bytes = self.config.max_response_bytes;
                let c = control.clone();
                let t0 = Instant::now();
                let work = self.pool.run_reserved(job.lane, reserved, move || {
                    // Stopped while it waited for memory: do nothing.
                    c.check().map_err(|_| ApiError::Cancelled)?;
                    let out = execute(&task, &c, max_bytes)?;
                    Stored::new(analysis, &out)
                });
                let limit = self.config.job_time_limit;
                // Stopped here or elsewhere: the analysis lets go of its worker and memory at
                // its next check (the blocking thread holds them), and the next poll sees them.
                let ending = tokio::select! {
                    r = work => {
                        self.metrics.observe_analysis(analysis, t0.elapsed());
                        Some(self.ending(r.and_then(|r| r)))
                    }
                    () = tokio::time::sleep(limit) => {
                        control.cancel();
                        Some(Ending::Failed(stopped(&format!(
                            "exceeded the time limit of {} s (WHIRL_JOB_TIME_LIMIT)",
                            limit.as_secs_f64()
                        ))))
                    }
                    // Cancelled, forgotten or handed back: recorded by whoever stopped it.
                    () = stop.notified() => { control.cancel(); None }
                };
                if let Some(e) = ending {
                    self.record(&id, e).await;
                }
            }
            Err(e) => {
                drop(reserved);
                self.record(&id, Ending::Failed(e.problem())).await;
            }
        }
        heartbeat.abort();
        self.local().remove(&id);
        self.wake.notify_one();
        let _ = tokio::task::spawn_blocking(release_free_memory).await;
    }

    /// How an analysis's outcome is recorded.
    fn ending(&self, r: Result<Stored, ApiError>) -> Ending {
        let max = self.config.job_result_bytes;
        match r {
            Ok(stored) if stored.gzip.len() as u64 > max => Ending::Failed(
                ApiError::Unsolvable(format!(
                    "the result is {} MB compressed, more than the {} MB kept for all jobs \
                     (WHIRL_JOB_RESULT_BYTES)",
                    stored.gzip.len().div_ceil(1 << 20),
                    max >> 20
                ))
                .problem(),
            ),
            Ok(stored) => Ending::Succeeded(stored.gzip),
            Err(ApiError::Cancelled) => Ending::Cancelled(stopped("cancelled")),
            Err(e) => Ending::Failed(e.problem()),
        }
    }

    /// Records a job's end (retrying for a lease while the store is unreachable), then applies
    /// the retention.
    async fn record(&self, id: &str, ending: Ending) {
        let lease = self.config.job_lease;
        let mut deadline = None;
        loop {
            match self.store.finish(id, &self.worker, &ending).await {
                Ok(true) => {
                    let status = match &ending {
                        Ending::Succeeded(_) => "succeeded",
                        Ending::Failed(_) => "failed",
                        Ending::Cancelled(_) => "cancelled",
                    };
                    tracing::info!(job = id, status, "job finished");
                    break;
                }
                Ok(false) => {
                    tracing::debug!(job = id, "job ended after it was stopped elsewhere");
                    break;
                }
                Err(e) => {
                    self.metrics.store_error();
                    // Kept while the server lives; a lease more once it is shutting down.
                    if !self.accepting()
                        && *deadline.get_or_insert_with(|| Instant::now() + lease) < Instant::now()
                    {
                        tracing::error!(
                            job = id, error = %e,
                            "could not record the job's end before shutting down: its lease runs \
                             out and it is re-queued"
                        );
                        break;
                    }
                    tokio::time::sleep(HEARTBEAT).await;
                }
            }
        }
        if let Err(e) = self.store.purge().await {
            self.metrics.store_error();
            tracing::warn!(error = %e, "retention not applied");
        }
    }

    /// Renews the lease of a job running here and writes its progress, until it ends or is
    /// stopped elsewhere; through an outage of the store too (the job goes on, and the lease is
    /// renewed when the store answers again).
    async fn heartbeat(self: Arc<Self>, id: String, control: Arc<Control>, stop: Arc<Notify>) {
        let lease = self.config.job_lease;
        let mut renewed = Instant::now();
        let mut warned = false;
        let mut tick = tokio::time::interval(HEARTBEAT);
        tick.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Delay);
        tick.tick().await;
        loop {
            tick.tick().await;
            let beat = self
                .store
                .heartbeat(&id, &self.worker, control.progress(), lease);
            let r = match tokio::time::timeout(lease / 2, beat).await {
                Ok(r) => r.map_err(|e| e.0),
                Err(_) => Err("no answer".into()),
            };
            match r {
                Ok(true) => {
                    if warned {
                        tracing::info!(job = %id, "job store back: lease renewed, the job goes on");
                        warned = false;
                    }
                    renewed = Instant::now();
                }
                Ok(false) => {
                    tracing::info!(job = %id, "job stopped elsewhere: stopping its analysis");
                    control.cancel();
                    stop.notify_one();
                    return;
                }
                Err(e) => {
                    self.metrics.store_error();
                    if !warned && renewed.elapsed() >= lease {
                        tracing::warn!(
                            job = %id, error = %e,
                            "lease not renewed for a lease (the store is unreachable): the job \
                             goes on here, and its lease is renewed when the store answers"
                        );
                        warned = true;
                    }
                }
            }
        }
    }

    /// Pings the store: whether it answered within `prompt`. An outage shorter than the
    /// pool's wait for a connection fails no call: a reap sent into it would run when the store
    /// is back, before the workers could renew the leases that ran out meanwhile. A ping that
    /// took longer is such an outage (or a store too busy to judge leases by): the store is
    /// not trusted for a lease from its answer on.
    async fn ping_promptly(&self, prompt: Duration) -> bool {
        let t0 = Instant::now();
        let r = self.store.ping().await;
        if t0.elapsed() > prompt {
            tracing::debug!(
                took_ms = t0.elapsed().as_millis() as u64,
                "the job store was slow to answer: expired leases are not judged for a lease"
            );
            self.store.health().doubt();
            return false;
        }
        r.is_ok()
    }

    /// Re-queues jobs whose worker died, and applies retention, forever.
    async fn maintain(self: Arc<Self>) {
        let lease = self.config.job_lease;
        let every = (lease / 4).clamp(Duration::from_millis(250), Duration::from_secs(2));
        let prompt = (lease / 4).clamp(HEARTBEAT, Duration::from_secs(1));
        let purge_every = Duration::from_secs(5);
        let mut purged = Instant::now();
        let reason = stopped(&format!(
            "the server running this job stopped responding twice (its lease of {} s ran out \
             each time); it is not run a third time",
            lease.as_secs_f64()
        ));
        loop {
            if self.store.health().down() {
                // The probe: the only call that tries the store until it answers.
                tokio::time::sleep(PROBE_EVERY).await;
                let _ = self.store.ping().await;
                continue;
            }
            tokio::time::sleep(every).await;
            if !self.store.connected() {
                continue;
            }
            if !self.store.health().trusted_for(lease) {
                // Down, or back for less than a lease: expired leases are not deaths yet.
                self.ping_promptly(prompt).await;
                continue;
            }
            // A prompt answer first: see `ping_promptly`.
            if !self.ping_promptly(prompt).await {
                continue;
            }
            match self.store.reap(&reason).await {
                Ok(reaped) => {
                    for r in &reaped {
                        self.metrics.lease_expired();
                        if r.requeued {
                            tracing::warn!(job = %r.id, "lease expired (its server stopped): job re-queued");
                        } else {
                            tracing::warn!(job = %r.id, "lease expired a second time: job failed");
                        }
                    }
                    if reaped.iter().any(|r| r.requeued) {
                        self.wake.notify_one();
                    }
                }
                Err(e) => {
                    self.metrics.store_error();
                    tracing::debug!(error = %e, "could not look for expired leases");
                }
            }
            if purged.elapsed() >= purge_every {
                purged = Instant::now();
                if let Err(e) = self.store.purge().await {
                    self.metrics.store_error();
                    tracing::debug!(error = %e, "retention not applied");
                }
            }
        }
    }

    /// Stops taking and claiming jobs; lets running ones finish within `grace`, then hands
    /// what is left back to the queue, each logged. Queued jobs stay queued.
    pub async fn shutdown(&self, grace: Duration) {
        self.accepting.store(false, Ordering::SeqCst);
        self.wake.notify_one();
        // A pass under way ends; none starts again.
        drop(self.claiming.lock().await);
        let deadline = Instant::now() + grace;
        while self.running_here() > 0 && Instant::now() < deadline {
            tokio::time::sleep(Duration::from_millis(50)).await;
        }
        let left: Vec<(String, Arc<Control>, Arc<Notify>)> = self
            .local()
            .iter()
            .map(|(id, l)| (id.clone(), l.control.clone(), l.stop.clone()))
            .collect();
        for (id, control, stop) in left {
            match self.store.release(&id, &self.worker).await {
                Ok(true) => tracing::warn!(
                    job = %id,
                    "the server is shutting down: job handed back to the queue, to run again \
                     from the start on another replica or after the restart"
                ),
                Ok(false) => {}
                Err(e) => tracing::error!(
                    job = %id, error = %e,
                    "the server is shutting down and the store is unreachable: the job is \
                     re-queued when its lease runs out"
                ),
            }
            control.cancel();
            stop.notify_one();
        }
        match self.store.queued().await {
            Ok(n) if n > 0 => {
                tracing::info!(
                    queued = n,
                    "queued jobs stay in the store for the other replicas or the next start"
                )
            }
            _ => {}
        }
    }
}
