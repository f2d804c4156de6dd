//! The blocking worker pool that runs analyses off the async runtime.
//!
//! At most `workers` analyses run at once (a semaphore in front of `spawn_blocking`), at most
//! `queue` more wait for a permit; beyond that a request is refused at once with 503 and
//! `Retry-After` rather than piling up memory. A panic inside an analysis fails that request
//! with 500 and leaves the server serving.

use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};

use tokio::sync::Semaphore;

use super::error::ApiError;

pub struct WorkerPool {
    permits: Arc<Semaphore>,
    in_flight: Arc<AtomicUsize>,
    workers: usize,
    queue: usize,
}

/// A place in the pool: held from admission until the analysis ends, however it ends (even if
/// the client goes away), so an admitted analysis is never dropped for lack of room.
pub struct Admission(Arc<AtomicUsize>);

impl Drop for Admission {
    fn drop(&mut self) {
        self.0.fetch_sub(1, Ordering::SeqCst);
    }
}

impl WorkerPool {
    pub fn new(workers: usize, queue: usize) -> Self {
        WorkerPool {
            permits: Arc::new(Semaphore::new(workers)),
            in_flight: Arc::new(AtomicUsize::new(0)),
            workers,
            queue,
        }
    }

    /// Whether a new analysis would be accepted now.
    pub fn ready(&self) -> bool {
        self.in_flight.load(Ordering::SeqCst) < self.workers + self.queue
    }

    /// Analyses running or waiting.
    pub fn in_flight(&self) -> usize {
        self.in_flight.load(Ordering::SeqCst)
    }

    /// Takes a place, or `Busy` when workers and queue are full.
    pub fn admit(&self) -> Result<Admission, ApiError> {
        let before = self.in_flight.fetch_add(1, Ordering::SeqCst);
        let admission = Admission(self.in_flight.clone());
        if before >= self.workers + self.queue {
            return Err(ApiError::Busy);
        }
        Ok(admission)
    }

    /// Analyses running now.
    pub fn running(&self) -> usize {
        self.workers - self.permits.available_permits()
    }

    /// Runs `f` on a blocking thread once a worker is free.
    pub async fn run<T, F>(&self, f: F) -> Result<T, ApiError>
    where
        T: Send + 'static,
        F: FnOnce() -> Result<T, ApiError> + Send + 'static,
    {
        let admission = self.admit()?;
        self.run_admitted(admission, || {}, f).await
    }

    /// Runs an admitted analysis: waits for a worker, calls `started` when it has one, runs `f`.
    pub async fn run_admitted<T, F>(
        &self,
        _admission: Admission,
        started: impl FnOnce(),
        f: F,
    ) -> Result<T, ApiError>
    where
        T: Send + 'static,
        F: FnOnce() -> Result<T, ApiError> + Send + 'static,
    {
        let permit = self
            .permits
            .clone()
            .acquire_owned()
            .await
            .map_err(|_| ApiError::Internal("the worker pool is closed".into()))?;
        started();
        tokio::task::spawn_blocking(move || {
            let _permit = permit;
            f()
        })
        .await
        .map_err(|e| {
            if e.is_panic() {
                ApiError::Internal("the analysis failed unexpectedly (a bug); it was logged".into())
            } else {
                ApiError::Internal("the analysis was cancelled".into())
            }
        })?
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[tokio::test(flavor = "multi_thread", worker_threads = 2)]
    async fn a_panic_fails_the_request_not_the_pool() {
        let pool = WorkerPool::new(1, 0);
        let r: Result<(), ApiError> = pool.run(|| panic!("boom")).await;
        assert!(matches!(r, Err(ApiError::Internal(_))));
        assert_eq!(pool.run(|| Ok(7)).await.unwrap(), 7);
        assert_eq!(pool.in_flight(), 0);
    }

    #[tokio::test(flavor = "multi_thread", worker_threads = 2)]
    async fn a_full_queue_refuses_at_once() {
        let test = async {
            let pool = Arc::new(WorkerPool::new(1, 1));
            let (tx, rx) = std::sync::mpsc::channel::<()>();
            let p = pool.clone();
            let running = tokio::spawn(async move {
                p.run(move || {
                    rx.recv().ok();
                    Ok(())
                })
                .await
            });
            // The first analysis holds the only worker before the second one queues.
            while pool.permits.available_permits() > 0 {
                tokio::time::sleep(std::time::Duration::from_millis(1)).await;
            }
            let p = pool.clone();
            let waiting = tokio::spawn(async move { p.run(|| Ok(())).await });
            while pool.in_flight() < 2 {
                tokio::time::sleep(std::time::Duration::from_millis(1)).await;
            }
            assert!(!pool.ready());
            assert!(matches!(pool.run(|| Ok(())).await, Err(ApiError::Busy)));
            tx.send(()).unwrap();
            running.await.unwrap().unwrap();
            waiting.await.unwrap().unwrap();
            assert!(pool.ready());
            assert_eq!(pool.in_flight(), 0);
        };
        tokio::time::timeout(std::time::Duration::from_secs(20), test)
            .await
            .expect("the pool test must not hang");
    }
}
