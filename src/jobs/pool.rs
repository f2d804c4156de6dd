//! The blocking worker pool that runs analyses off the async runtime, fairly and within a
//! memory budget.
//!
//! - **Two lanes.** An analysis whose estimated work is small (about a tenth of a second on
//!   one core) and whose heap is small runs in the *short* lane: its own permits and a shared
//!   compute pool at normal priority. Everything else runs in the *long* lane: at most
//!   `workers` at once, each on a compute pool of its own whose threads run at a lower
//!   priority (nice 10). Long sweeps then share the cores fairly with each other, and never
//!   make a short request wait behind them.
//! - **Memory.** A long analysis holds its estimated peak heap (see `model::limits`) from a
//!   budget while it runs, and waits when the budget is spent; one that could never fit is
//!   refused at admission (422). Short analyses are bounded by their lane's count instead.
//!   A synchronous answer holds its estimate from the same budget before it runs, and its
//!   size after, until the client has read it ([`WorkerPool::run_answer`]): slow readers
//!   cannot pile answers up beside it, and a short analysis whose answer the budget cannot
//!   hold now is refused at once (503) rather than run.
//! - **Admission.** Each lane counts its own: at most `workers + queue` long analyses and
//!   `2 x threads + queue` short ones are running or waiting; beyond that a request is refused
//!   at once with 503 and `Retry-After` rather than piling up memory. Long sweeps filling
//!   their queue never refuse a short request.
//! - **Jobs** wait in the shared queue (`jobs::store`), not here: a replica claims one only
//!   with a free worker of its lane in hand ([`WorkerPool::try_worker`]) and when its memory
//!   estimate fits the free budget, so claims respect each replica's workers and memory.
//!
//! A panic inside an analysis fails that request with 500 and leaves the server serving.

use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};

use tokio::sync::{OwnedSemaphorePermit, Semaphore};

use crate::answer::ApiError;
use crate::model::{Cost, Invalid};

/// Work (flops, as estimated) up to which an analysis is short.
pub const SHORT_WORK: f64 = 1.5e9;
/// Heap up to which a short analysis needs no share of the budget.
pub const SHORT_BYTES: u64 = 64 << 20;
/// Short analyses running at once, per core.
const SHORT_PER_CORE: usize = 2;

const MIB: u64 = 1 << 20;

/// Which lane an analysis runs in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Lane {
    Short,
    Long,
}

impl Lane {
    pub fn of(cost: &Cost) -> Self {
        if cost.work <= SHORT_WORK && cost.peak_bytes <= SHORT_BYTES {
            Lane::Short
        } else {
            Lane::Long
        }
    }
}

pub struct WorkerPool {
    long: Arc<Semaphore>,
    short: Arc<Semaphore>,
    /// The memory budget of the long lane, in MiB permits.
    memory: Arc<Semaphore>,
    budget_mib: u64,
    /// MiB of the budget set aside for each running short analysis's heap (none when the
    /// budget is too small to set the short lane's worst case aside).
    short_aside_mib: u64,
    /// Long analyses running or waiting (admission of the long lane).
    in_flight: Arc<AtomicUsize>,
    /// Short analyses running or waiting (admission of the short lane).
    short_in_flight: Arc<AtomicUsize>,
    workers: usize,
    queue: usize,
    threads: usize,
    short_pool: Arc<rayon::ThreadPool>,
    /// The long lane's compute pools not in use: each long analysis takes one (at most
    /// `workers` exist) and gives it back, so its threads, and the allocator arenas they warmed,
    /// serve the next one instead of being started and faulted in again per analysis.
    long_pools: Arc<std::sync::Mutex<Vec<rayon::ThreadPool>>>,
}

/// A place in the pool: held from admission until the analysis ends or is abandoned, so that
/// the queue bound holds.
pub struct Admission {
    _slot: Slot,
    lane: Lane,
    mib: u32,
    /// MiB a synchronous answer takes from the budget before it runs (see
    /// [`WorkerPool::run_answer`]).
    answer_mib: u32,
}

/// A claimed job's place in the pool (see [`WorkerPool::reserve`]).
pub struct Reserved {
    _slot: Slot,
    worker: OwnedSemaphorePermit,
    memory: Option<OwnedSemaphorePermit>,
    mib: u32,
}

/// Memory of the budget held for an answer until it is sent (see
/// [`WorkerPool::run_answer`]).
pub struct AnswerHold(Option<OwnedSemaphorePermit>);

impl AnswerHold {
    /// Bytes held.
    pub fn bytes(&self) -> u64 {
        self.0.as_ref().map_or(0, |m| m.num_permits() as u64 * MIB)
    }
}

struct Slot(Arc<AtomicUsize>);

impl Drop for Slot {
    fn drop(&mut self) {
        self.0.fetch_sub(1, Ordering::SeqCst);
    }
}

/// Lowers the calling thread's priority (Linux: nice is per thread).
fn lower_priority() {
    #[cfg(target_os = "linux")]
    // SAFETY: setpriority only reads its integer arguments.
    unsafe {
        libc::setpriority(libc::PRIO_PROCESS, 0, 10);
    }
}

impl WorkerPool {
    /// `workers` long analyses at once, `queue` more waiting, `threads` compute threads per
    /// analysis, `memory_budget` bytes for the long lane.
    pub fn new(workers: usize, queue: usize, threads: usize, memory_budget: u64) -> Self {
        let short_permits = SHORT_PER_CORE * threads.max(1);
        // The short lane's worst case is set aside from the budget.
        let reserved = short_permits as u64 * SHORT_BYTES;
        let budget_mib = (memory_budget.saturating_sub(reserved) / MIB).max(64);
        let short_aside_mib =
            (memory_budget / MIB).saturating_sub(budget_mib) / short_permits as u64;
        let short_pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads.max(1))
            .thread_name(|i| format!("whirl-short-{i}"))
            .build()
            .expect("a thread pool of a few threads");
        WorkerPool {
            long: Arc::new(Semaphore::new(workers)),
            short: Arc::new(Semaphore::new(short_permits)),
            memory: Arc::new(Semaphore::new(budget_mib as usize)),
            budget_mib,
            short_aside_mib,
            in_flight: Arc::new(AtomicUsize::new(0)),
            short_in_flight: Arc::new(AtomicUsize::new(0)),
            workers,
            queue,
            threads: threads.max(1),
            short_pool: Arc::new(short_pool),
            long_pools: Arc::default(),
        }
    }

    /// Whether a new long analysis would be accepted now.
    pub fn ready(&self) -> bool {
        self.in_flight.load(Ordering::SeqCst) < self.workers + self.queue
    }

    /// Analyses running or waiting (both lanes).
    pub fn in_flight(&self) -> usize {
        self.in_flight.load(Ordering::SeqCst) + self.short_in_flight.load(Ordering::SeqCst)
    }

    /// The admission counter and bound of a lane.
    fn counter(&self, lane: Lane) -> (&Arc<AtomicUsize>, usize) {
        match lane {
            Lane::Short => (
                &self.short_in_flight,
                SHORT_PER_CORE * self.threads + self.queue,
            ),
            Lane::Long => (&self.in_flight, self.workers + self.queue),
        }
    }

    /// Analyses running now (both lanes).
    pub fn running(&self) -> usize {
        self.workers - self.long.available_permits() + SHORT_PER_CORE * self.threads
            - self.short.available_permits()
    }

    /// Bytes of the budget held by running analyses and by answers not yet sent.
    pub fn memory_in_use(&self) -> u64 {
        (self.budget_mib - self.memory.available_permits() as u64) * MIB
    }

    /// The long lane's memory budget, bytes.
    pub fn memory_budget(&self) -> u64 {
        self.budget_mib * MIB
    }

    /// The lane and the MiB of budget an analysis of this cost needs: 422 when it could never
    /// fit in the memory budget (`path`: the field that sizes it).
    pub fn needs(&self, cost: &Cost, path: &str) -> Result<(Lane, u64), ApiError> {
        let lane = Lane::of(cost);
        let mib = match lane {
            Lane::Short => 0,
            Lane::Long => cost.peak_bytes.div_ceil(MIB).max(1),
        };
        self.fits(mib, path)?;
        Ok((lane, mib))
    }

    /// 422 when `mib` could never fit in the memory budget.
    fn fits(&self, mib: u64, path: &str) -> Result<(), ApiError> {
        if mib > self.budget_mib {
            return Err(ApiError::Invalid(Invalid::one(
                path,
                format!(
                    "this analysis needs about {} MB, more than the memory budget of {} MB \
                     (WHIRL_MEMORY_BUDGET): use a smaller model, fewer speeds or samples",
                    mib, self.budget_mib
                ),
            )));
        }
        Ok(())
    }

    /// MiB of the budget an analysis answering synchronously takes before it runs: a long
    /// one its whole estimate; a short one its answer's estimate, and what of its heap the
    /// short lane's set-aside does not cover (all of it when the budget is too small for
    /// one), since its answer outlives its place in the lane.
    fn answer_needs(&self, lane: Lane, cost: &Cost, mib: u64) -> u64 {
        match lane {
            Lane::Long => mib,
            Lane::Short => {
                let uncovered = cost.peak_bytes.saturating_sub(self.short_aside_mib * MIB);
                uncovered.max(cost.response_bytes).div_ceil(MIB).max(1)
            }
        }
    }

    /// Takes a place for an analysis of this cost: 422 when it could never fit in the memory
    /// budget (`path`: the field that sizes it), 503 when its lane's workers and queue are
    /// full.
    pub fn admit(&self, cost: &Cost, path: &str) -> Result<Admission, ApiError> {
        let (lane, mib) = self.needs(cost, path)?;
        let answer_mib = self.answer_needs(lane, cost, mib);
        self.fits(answer_mib, path)?;
        let (counter, bound) = self.counter(lane);
        let before = counter.fetch_add(1, Ordering::SeqCst);
        let slot = Slot(counter.clone());
        if before >= bound {
            return Err(ApiError::Busy);
        }
        Ok(Admission {
            _slot: slot,
            lane,
            mib: mib as u32,
            answer_mib: answer_mib as u32,
        })
    }

    /// A free worker of `lane` now, if there is one (a job is claimed from the shared queue
    /// only with one in hand).
    pub fn try_worker(&self, lane: Lane) -> Option<OwnedSemaphorePermit> {
        match lane {
            Lane::Short => self.short.clone().try_acquire_owned().ok(),
            Lane::Long => self.long.clone().try_acquire_owned().ok(),
        }
    }

    /// MiB of the budget free now.
    pub fn memory_free_mib(&self) -> u64 {
        self.memory.available_permits() as u64
    }

    /// A claimed job's place: the worker taken for it, and its memory if free now (else it is
    /// waited for when the job runs). Counted in flight, beyond the queue bound (the job was
    /// admitted to the shared queue), in its lane.
    pub fn reserve(&self, lane: Lane, worker: OwnedSemaphorePermit, mib: u64) -> Reserved {
        let (counter, _) = self.counter(lane);
        counter.fetch_add(1, Ordering::SeqCst);
        let mib = mib.min(self.budget_mib) as u32;
        let memory = if mib > 0 {
            self.memory.clone().try_acquire_many_owned(mib).ok()
        } else {
            None
        };
        Reserved {
            _slot: Slot(counter.clone()),
            worker,
            memory,
            mib,
        }
    }

    /// Runs an admitted analysis: waits for its lane and its memory, calls `started`, then runs
    /// `f` on a blocking thread inside a compute pool (see the module docs). The permits are
    /// held by the blocking thread: if the caller stops waiting, they are released only when
    /// `f` returns.
    pub async fn run<T, F>(
        &self,
        admission: Admission,
        started: impl FnOnce(),
        f: F,
    ) -> Result<T, ApiError>
    where
        T: Send + 'static,
        F: FnOnce() -> T + Send + 'static,
    {
        let memory = if admission.mib > 0 {
            Some(
                self.memory
                    .clone()
                    .acquire_many_owned(admission.mib)
                    .await
                    .map_err(closed)?,
            )
        } else {
            None
        };
        let lane = match admission.lane {
            Lane::Short => self.short.clone(),
            Lane::Long => self.long.clone(),
        };
        let permit = lane.acquire_owned().await.map_err(closed)?;
        started();
        let kind = admission.lane;
        self.spawn(kind, (permit, memory, admission), f).await
    }

    /// Runs an admitted analysis like [`run`](Self::run), for an answer that stays in memory
    /// until the client has taken it: `f` returns the answer and its size in bytes, and that
    /// many bytes of the memory budget are held by the returned [`AnswerHold`] until it is
    /// dropped (with the answer's last chunk). The analysis takes its share of the budget
    /// before it runs (see [`answer_needs`](Self::answer_needs)), and its answer keeps its
    /// size of that share: the answers waiting for slow readers, the analyses rendering them
    /// and the analyses running never hold more than the budget together, and no answer waits
    /// for the budget once it exists. A long analysis waits for its share; a short one is
    /// refused at once (503) when the budget cannot give it now, as is an answer larger than
    /// its share when the budget cannot give the rest.
    pub async fn run_answer<T, F>(
        &self,
        admission: Admission,
        f: F,
    ) -> Result<(T, AnswerHold), ApiError>
    where
        T: Send + 'static,
        F: FnOnce() -> (T, u64) + Send + 'static,
    {
        let memory = match admission.lane {
            Lane::Long if admission.answer_mib > 0 => Some(
                self.memory
                    .clone()
                    .acquire_many_owned(admission.answer_mib)
                    .await
                    .map_err(closed)?,
            ),
            Lane::Long => None,
            Lane::Short => Some(
                self.memory
                    .clone()
                    .try_acquire_many_owned(admission.answer_mib)
                    .map_err(|_| ApiError::Busy)?,
            ),
        };
        let lane = match admission.lane {
            Lane::Short => self.short.clone(),
            Lane::Long => self.long.clone(),
        };
        let permit = lane.acquire_owned().await.map_err(closed)?;
        let kind = admission.lane;
        // The blocking thread hands the permits back with the answer instead of dropping them.
        let ((out, bytes), (permit, memory, admission)) = self
            .spawn(kind, (), move || (f(), (permit, memory, admission)))
            .await?;
        let need = (bytes.div_ceil(MIB) as u32).min(self.budget_mib as u32);
        let mut hold = memory;
        let have = hold.as_ref().map_or(0, |m| m.num_permits() as u32);
        if have > need {
            hold = hold.and_then(|mut m| m.split(need as usize));
        } else if have < need {
            let more = self
                .memory
                .clone()
                .try_acquire_many_owned(need - have)
                .map_err(|_| ApiError::Busy)?;
            hold = Some(match hold {
                Some(mut m) => {
                    m.merge(more);
                    m
                }
                None => more,
            });
        }
        drop((permit, admission));
        Ok((out, AnswerHold(hold)))
    }

    /// Runs a reserved job's analysis like [`run`](Self::run), first waiting for its memory if
    /// it was not free when the job was claimed.
    pub async fn run_reserved<T, F>(&self, lane: Lane, r: Reserved, f: F) -> Result<T, ApiError>
    where
        T: Send + 'static,
        F: FnOnce() -> T + Send + 'static,
    {
        let memory = match r.memory {
            Some(m) => Some(m),
            None if r.mib > 0 => Some(
                self.memory
                    .clone()
                    .acquire_many_owned(r.mib)
                    .await
                    .map_err(closed)?,
            ),
            None => None,
        };
        self.spawn(lane, (r.worker, memory, r._slot), f).await
    }

    /// Runs `f` on a blocking thread in the lane's compute pool, holding `held` until it returns.
    async fn spawn<T, F, H>(&self, lane: Lane, held: H, f: F) -> Result<T, ApiError>
    where
        T: Send + 'static,
        F: FnOnce() -> T + Send + 'static,
        H: Send + 'static,
    {
        let threads = self.threads;
        let short = self.short_pool.clone();
        let pools = self.long_pools.clone();
        tokio::task::spawn_blocking(move || {
            let _held = held;
            match lane {
                Lane::Short => short.install(f),
                Lane::Long => {
                    let idle = pools.lock().ok().and_then(|mut p| p.pop());
                    let pool = idle.map(Ok).unwrap_or_else(|| {
                        rayon::ThreadPoolBuilder::new()
                            .num_threads(threads)
                            .thread_name(|i| format!("whirl-long-{i}"))
                            .start_handler(|_| lower_priority())
                            .build()
                    });
                    match pool {
                        // A panic in `f` unwinds past the push: that pool is dropped.
                        Ok(pool) => {
                            let out = pool.install(f);
                            if let Ok(mut p) = pools.lock() {
                                p.push(pool);
                            }
                            out
                        }
                        Err(_) => short.install(f),
                    }
                }
            }
        })
        .await
        .map_err(|e| {
            if e.is_panic() {
                ApiError::Internal("the analysis failed unexpectedly (a bug); it was logged".into())
            } else {
                ApiError::Internal("the analysis was cancelled".into())
            }
        })
    }
}

/// Gives the heap the allocator keeps after a large analysis back to the system (glibc keeps
/// freed memory in per-thread arenas; without this the resident size of a server creeps up by
/// the peaks of past analyses). Blocking: call it off the async runtime.
pub fn release_free_memory() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: malloc_trim only walks the allocator's own free lists.
    unsafe {
        libc::malloc_trim(0);
    }
}

fn closed(_: tokio::sync::AcquireError) -> ApiError {
    ApiError::Internal("the worker pool is closed".into())
}

#[cfg(test)]
#[path = "pool_tests.rs"]
mod tests;
