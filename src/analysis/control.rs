//! Cooperative cancellation and progress of a long analysis.
//!
//! The analyses check [`Control::check`] between speeds, refinement iterations and time steps
//! (each well under a second), and count their work with [`Control::advance`], so that a job
//! can report real progress and be stopped within a second. Numerics know nothing of who
//! asks: the service sets the flag (client cancel, time limit, shutdown) and reads the counts.
//!
//! An analysis made of others (the report) gives each a share of the whole with
//! [`Control::part`]: a part's own counts then fill its share only, so announcing a later
//! part's work never takes progress back. What [`Control::progress`] reports never decreases.

use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

#[derive(Debug, Default)]
pub struct Control {
    cancelled: AtomicBool,
    done: AtomicU64,
    total: AtomicU64,
    /// The share of the whole the current counts fill: `(start, width)`; `None` is `(0, 1)`.
    window: Mutex<Option<(f64, f64)>>,
    /// The largest progress reported (bits of a non-negative f64, which order as integers).
    reported: AtomicU64,
}

/// The analysis was stopped from outside.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Cancelled;

impl Control {
    pub fn cancel(&self) {
        self.cancelled.store(true, Ordering::SeqCst);
    }

    pub fn is_cancelled(&self) -> bool {
        self.cancelled.load(Ordering::Relaxed)
    }

    /// `Err` once cancelled.
    pub fn check(&self) -> Result<(), Cancelled> {
        if self.is_cancelled() {
            Err(Cancelled)
        } else {
            Ok(())
        }
    }

    /// Announces `n` more units of work.
    pub fn expect(&self, n: u64) {
        self.total.fetch_add(n, Ordering::Relaxed);
    }

    /// `n` units done.
    pub fn advance(&self, n: u64) {
        self.done.fetch_add(n, Ordering::Relaxed);
    }

    /// Fraction done, in [0, 1]; never less than it said before.
    pub fn progress(&self) -> f64 {
        let (start, width) = self.window().unwrap_or((0.0, 1.0));
        let total = self.total.load(Ordering::SeqCst);
        let done = self.done.load(Ordering::SeqCst);
        let within = if total == 0 {
            0.0
        } else {
            (done as f64 / total as f64).clamp(0.0, 1.0)
        };
        let now = (start + width * within).clamp(0.0, 1.0);
        let before = self.reported.fetch_max(now.to_bits(), Ordering::SeqCst);
        f64::from_bits(before).max(now)
    }

    fn window(&self) -> Option<(f64, f64)> {
        *self.window.lock().unwrap_or_else(|e| e.into_inner())
    }

    fn set_window(&self, w: Option<(f64, f64)>) {
        *self.window.lock().unwrap_or_else(|e| e.into_inner()) = w;
    }

    /// Runs `f` as the part `[from, to]` (fractions) of the current share: its counts fill
    /// that part only, and once it returns progress stands at least at the part's end. Parts
    /// nest (a report's bearing sets are reports).
    pub fn part<T>(&self, from: f64, to: f64, f: impl FnOnce() -> T) -> T {
        let outer = self.window();
        let (start, width) = outer.unwrap_or((0.0, 1.0));
        let (from, to) = (from.clamp(0.0, 1.0), to.clamp(from.clamp(0.0, 1.0), 1.0));
        // Counts first, then the window: a reader in between sees less done, never more.
        let saved = (
            self.done.swap(0, Ordering::SeqCst),
            self.total.swap(0, Ordering::SeqCst),
        );
        self.set_window(Some((start + width * from, width * (to - from))));
        let out = f();
        let end = (start + width * to).clamp(0.0, 1.0);
        self.reported.fetch_max(end.to_bits(), Ordering::SeqCst);
        self.done.store(0, Ordering::SeqCst);
        self.set_window(outer);
        self.total.store(saved.1, Ordering::SeqCst);
        self.done.store(saved.0, Ordering::SeqCst);
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parts_fill_their_share_and_progress_never_decreases() {
        let c = Control::default();
        let mut seen = vec![c.progress()];
        // Three parts of 1/2, 1/4 and 1/4; each announces its work only when it starts, as
        // the report's analyses do.
        for (from, to, n) in [(0.0, 0.5, 10u64), (0.5, 0.75, 40), (0.75, 1.0, 4)] {
            c.part(from, to, || {
                c.expect(n);
                for _ in 0..n {
                    c.advance(1);
                    seen.push(c.progress());
                }
                // More work found late: the share is not exceeded, nothing goes back.
                c.expect(n);
                seen.push(c.progress());
            });
            seen.push(c.progress());
        }
        assert!(seen.windows(2).all(|w| w[1] >= w[0]), "{seen:?}");
        // Half-way through the second part, a quarter of its share: 0.5 + 0.25 * 20/40.
        assert_eq!(seen[11 + 1 + 20], 0.625);
        assert_eq!(*seen.last().unwrap(), 1.0);
        // Nested parts: the second half of the first half ends at 0.5.
        let c = Control::default();
        c.part(0.0, 0.5, || {
            c.part(0.5, 1.0, || {
                c.expect(2);
                c.advance(1);
                assert_eq!(c.progress(), 0.375);
            })
        });
        assert_eq!(c.progress(), 0.5);
    }
}
