//! Failing fast while the store is unreachable, and knowing when it came back.
//!
//! After a call finds the store unreachable, calls fail at once (no connection attempt, no
//! wait for the pool's timeout). Only probes go through, one at a time and one every
//! [`RETRY`] at most: the server's own pings (the runner's upkeep), never a client's request,
//! which would otherwise wait for the pool's connection timeout (3 s) whenever it happened to
//! be the one let through. The first probe that gets an answer closes the breaker. The time
//! the store came back is kept: leases that ran out during an outage say nothing about their
//! servers until the workers have had a lease to renew them ([`Breaker::trusted_for`]).
//!
//! The server's own calls already under way when the store goes away are not cut short: they
//! find out when the pool gives up on a connection (3 s), and the first to fail opens the
//! breaker; a client's request gives up after `REQUEST_WAIT` (0.75 s) and opens it too. An outage
//! shorter than that makes no call fail (they all wait, and go on when the store is back);
//! the runner's upkeep notices it as a ping that took too long ([`Breaker::doubt`]), and the
//! store is not trusted for a lease from then either.

use std::sync::Mutex;
use std::time::{Duration, Instant};

use super::StoreError;

/// How often a call goes through to an unreachable store.
pub const RETRY: Duration = Duration::from_millis(250);

#[derive(Default)]
struct State {
    /// Since when the store has been unreachable, if it is.
    down_since: Option<Instant>,
    /// When the next probe may go.
    retry_at: Option<Instant>,
    /// A probe is under way.
    probing: bool,
    /// When the store last came back after an outage (or was last slow to answer).
    up_since: Option<Instant>,
}

#[derive(Default)]
pub struct Breaker(Mutex<State>);

/// One call let through; say how it went with [`Pass::done`].
pub struct Pass<'a> {
    breaker: &'a Breaker,
    probe: bool,
    done: bool,
}

impl Breaker {
    fn state(&self) -> std::sync::MutexGuard<'_, State> {
        self.0.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// A call may go to the store, or fails at once while the store is unreachable; but for
    /// a `probe` when one is due.
    pub fn enter(&self, probe: bool) -> Result<Pass<'_>, StoreError> {
        let mut s = self.state();
        let Some(since) = s.down_since else {
            return Ok(Pass {
                breaker: self,
                probe: false,
                done: false,
            });
        };
        if !probe || s.probing || s.retry_at.is_some_and(|t| Instant::now() < t) {
            return Err(StoreError(format!(
                "job store unreachable for {:.1} s (tried again every {} ms)",
                since.elapsed().as_secs_f64(),
                RETRY.as_millis()
            )));
        }
        s.probing = true;
        Ok(Pass {
            breaker: self,
            probe: true,
            done: false,
        })
    }

    /// Whether the store has answered for at least `span` since it last came back (always,
    /// if it never went away while this process watched).
    pub fn trusted_for(&self, span: Duration) -> bool {
        let s = self.state();
        s.down_since.is_none() && s.up_since.is_none_or(|t| t.elapsed() >= span)
    }

    /// The store was slow to answer (an outage too short for calls to fail, since the pool
    /// waits for a connection): not trusted for a while, as if it had just come back.
    pub fn doubt(&self) {
        self.state().up_since = Some(Instant::now());
    }

    /// Whether the store is unreachable now, as far as this process knows.
    pub fn down(&self) -> bool {
        self.state().down_since.is_some()
    }
}

impl Pass<'_> {
    /// The call reached the store (`unreachable` false, whatever the store answered) or not.
    pub fn done(mut self, unreachable: bool) {
        self.done = true;
        let now = Instant::now();
        let mut s = self.breaker.state();
        if unreachable {
            s.down_since.get_or_insert(now);
            s.retry_at = Some(now + RETRY);
        } else if s.down_since.take().is_some() {
            s.up_since = Some(now);
            s.retry_at = None;
        }
        if self.probe {
            s.probing = false;
        }
    }
}

impl Drop for Pass<'_> {
    fn drop(&mut self) {
        // A probe whose caller went away: let the next one go.
        if self.probe && !self.done {
            self.breaker.state().probing = false;
        }
    }
}

/// Whether an error means the store could not be reached (as opposed to an answer of it).
pub fn unreachable(e: &sqlx::Error) -> bool {
    match e {
        sqlx::Error::Io(_)
        | sqlx::Error::Tls(_)
        | sqlx::Error::PoolTimedOut
        | sqlx::Error::PoolClosed
        | sqlx::Error::WorkerCrashed
        | sqlx::Error::Protocol(_) => true,
        // PostgreSQL's connection exceptions and shutdowns (SQLSTATE 08xxx, 57P0x).
        sqlx::Error::Database(d) => d
            .code()
            .is_some_and(|c| c.starts_with("08") || c.starts_with("57P")),
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fails_fast_then_probes_then_waits_a_lease() {
        let b = Breaker::default();
        assert!(b.trusted_for(Duration::from_secs(1)));
        b.enter(false).unwrap().done(true);
        assert!(b.down());
        // At once after the failure: no call goes through.
        let t0 = Instant::now();
        assert!(b.enter(false).is_err());
        assert!(b.enter(true).is_err());
        assert!(t0.elapsed() < Duration::from_millis(5));
        std::thread::sleep(RETRY);
        // A client's call never probes; the server's probe goes, one at a time.
        assert!(b.enter(false).is_err());
        let probe = b.enter(true).unwrap();
        assert!(b.enter(true).is_err(), "one probe at a time");
        assert!(b.enter(false).is_err());
        probe.done(false);
        assert!(!b.down());
        assert!(b.enter(false).is_ok());
        assert!(!b.trusted_for(Duration::from_millis(200)));
        std::thread::sleep(Duration::from_millis(200));
        assert!(b.trusted_for(Duration::from_millis(200)));
        // Slow to answer: not trusted again for a while.
        b.doubt();
        assert!(!b.trusted_for(Duration::from_millis(200)));
        assert!(!b.down(), "still reachable");
    }
}
