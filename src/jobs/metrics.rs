//! The counters this replica keeps for `/metrics`: requests (counted by the HTTP layer),
//! analysis durations, and the job store's claims, queue waits, lease expiries and errors
//! (counted by the runner). `service::metrics` writes them out.

use std::collections::BTreeMap;
use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Duration;

/// Upper bounds of the duration histograms (analyses, queue waits), s.
pub(crate) const BUCKETS: [f64; 10] = [0.01, 0.05, 0.1, 0.5, 1.0, 5.0, 10.0, 30.0, 60.0, 300.0];
/// Upper bounds of the claim latency histogram, s.
pub(crate) const CLAIM_BUCKETS: [f64; 10] = [
    0.0005, 0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.5, 1.0,
];

#[derive(Default)]
pub(crate) struct Histogram {
    counts: [u64; BUCKETS.len()],
    sum: f64,
    count: u64,
}

impl Histogram {
    fn observe(&mut self, bounds: &[f64; 10], s: f64) {
        for (i, le) in bounds.iter().enumerate() {
            if s <= *le {
                self.counts[i] += 1;
            }
        }
        self.sum += s;
        self.count += 1;
    }

    pub(crate) fn render(&self, out: &mut String, name: &str, labels: &str, bounds: &[f64; 10]) {
        let sep = if labels.is_empty() { "" } else { "," };
        for (le, c) in bounds.iter().zip(self.counts) {
            out.push_str(&format!("{name}_bucket{{{labels}{sep}le=\"{le}\"}} {c}\n"));
        }
        out.push_str(&format!(
            "{name}_bucket{{{labels}{sep}le=\"+Inf\"}} {}\n",
            self.count
        ));
        let braces = if labels.is_empty() {
            String::new()
        } else {
            format!("{{{labels}}}")
        };
        out.push_str(&format!("{name}_sum{braces} {}\n", self.sum));
        out.push_str(&format!("{name}_count{braces} {}\n", self.count));
    }
}

#[derive(Default)]
pub struct Metrics {
    pub(crate) requests: Mutex<BTreeMap<(String, String, u16), u64>>,
    pub(crate) analyses: Mutex<BTreeMap<String, Histogram>>,
    /// Time of the claim statement.
    pub(crate) claims: Mutex<Histogram>,
    /// Time claimed jobs waited in the queue.
    pub(crate) waits: Mutex<Histogram>,
    pub(crate) lease_expiries: AtomicU64,
    pub(crate) store_errors: AtomicU64,
}

impl Metrics {
    pub fn count_request(&self, method: &str, route: &str, status: u16) {
        let mut r = self.requests.lock().unwrap_or_else(|e| e.into_inner());
        *r.entry((method.to_string(), route.to_string(), status))
            .or_default() += 1;
    }

    pub fn observe_analysis(&self, analysis: &str, d: Duration) {
        let mut a = self.analyses.lock().unwrap_or_else(|e| e.into_inner());
        a.entry(analysis.to_string())
            .or_default()
            .observe(&BUCKETS, d.as_secs_f64());
    }

    /// A claim took `took`; the job had waited `waited` in the queue.
    pub fn observe_claim(&self, took: Duration, waited: Duration) {
        self.claims
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .observe(&CLAIM_BUCKETS, took.as_secs_f64());
        self.waits
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .observe(&BUCKETS, waited.as_secs_f64());
    }

    pub fn lease_expired(&self) {
        self.lease_expiries.fetch_add(1, Ordering::Relaxed);
    }

    pub fn store_error(&self) {
        self.store_errors.fetch_add(1, Ordering::Relaxed);
    }
}
