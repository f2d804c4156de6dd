//! Prometheus metrics in text format: requests, jobs by status, queue depth, analysis
//! durations, and the job store: the shared queue's depth over all replicas, claim latency,
//! time jobs wait in the queue, lease expiries and store errors.

use std::collections::BTreeMap;
use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Duration;

use axum::extract::{MatchedPath, Request, State};
use axum::middleware::Next;
use axum::response::Response;

use super::AppState;
use super::jobs::status_name;
use super::store::Stats;
use crate::model::api::JobStatus;

/// Upper bounds of the duration histograms (analyses, queue waits), s.
const BUCKETS: [f64; 10] = [0.01, 0.05, 0.1, 0.5, 1.0, 5.0, 10.0, 30.0, 60.0, 300.0];
/// Upper bounds of the claim latency histogram, s.
const CLAIM_BUCKETS: [f64; 10] = [
    0.0005, 0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.5, 1.0,
];

#[derive(Default)]
struct Histogram {
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

    fn render(&self, out: &mut String, name: &str, labels: &str, bounds: &[f64; 10]) {
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
    requests: Mutex<BTreeMap<(String, String, u16), u64>>,
    analyses: Mutex<BTreeMap<String, Histogram>>,
    /// Time of the claim statement.
    claims: Mutex<Histogram>,
    /// Time claimed jobs waited in the queue.
    waits: Mutex<Histogram>,
    lease_expiries: AtomicU64,
    store_errors: AtomicU64,
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

/// The route template a request matched, carried out on its response.
#[derive(Clone)]
pub struct Route(pub String);

/// Inside the router: puts the matched route template on the response for [`track`].
pub async fn label(req: Request, next: Next) -> Response {
    let route = req
        .extensions()
        .get::<MatchedPath>()
        .map(|p| p.as_str().to_string());
    let mut resp = next.run(req).await;
    if let Some(r) = route {
        resp.extensions_mut().insert(Route(r));
    }
    resp
}

/// A method as a label: the standard ones by name, anything else as `other` (a label set an
/// attacker can grow is a memory leak).
fn method_label(m: &axum::http::Method) -> &'static str {
    use axum::http::Method;
    match *m {
        Method::GET => "GET",
        Method::POST => "POST",
        Method::DELETE => "DELETE",
        Method::HEAD => "HEAD",
        Method::OPTIONS => "OPTIONS",
        Method::PUT => "PUT",
        Method::PATCH => "PATCH",
        _ => "other",
    }
}

/// Counts every request by method, route template (`unmatched` for no route) and status.
pub async fn track(State(st): State<AppState>, req: Request, next: Next) -> Response {
    let method = method_label(req.method());
    let resp = next.run(req).await;
    let route = resp
        .extensions()
        .get::<Route>()
        .map_or("unmatched", |r| r.0.as_str())
        .to_string();
    st.metrics
        .count_request(method, &route, resp.status().as_u16());
    resp
}

/// The exposition text; `stats`: the store's counts (`None`: unreachable).
pub fn render(st: &AppState, stats: Option<Stats>) -> String {
    let mut s = String::new();
    s.push_str("# HELP whirl_http_requests_total HTTP requests by method, route and status.\n");
    s.push_str("# TYPE whirl_http_requests_total counter\n");
    for ((m, r, c), n) in st
        .metrics
        .requests
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .iter()
    {
        s.push_str(&format!(
            "whirl_http_requests_total{{method=\"{m}\",route=\"{r}\",status=\"{c}\"}} {n}\n"
        ));
    }
    s.push_str(&format!(
        "# HELP whirl_store_up Whether the job store ({}) answers.\n",
        if st.jobs.store.shared() {
            "PostgreSQL"
        } else {
            "SQLite"
        }
    ));
    s.push_str(&format!(
        "# TYPE whirl_store_up gauge\nwhirl_store_up {}\n",
        u8::from(stats.is_some())
    ));
    if let Some(stats) = &stats {
        s.push_str("# HELP whirl_jobs Jobs in the store (all replicas), by status.\n");
        s.push_str("# TYPE whirl_jobs gauge\n");
        for status in [
            JobStatus::Queued,
            JobStatus::Running,
            JobStatus::Succeeded,
            JobStatus::Failed,
            JobStatus::Cancelled,
        ] {
            s.push_str(&format!(
                "whirl_jobs{{status=\"{}\"}} {}\n",
                status_name(status),
                stats.count(status)
            ));
        }
        s.push_str(
            "# HELP whirl_store_queue_depth Jobs waiting in the shared queue (all replicas).\n",
        );
        s.push_str(&format!(
            "# TYPE whirl_store_queue_depth gauge\nwhirl_store_queue_depth {}\n",
            stats.count(JobStatus::Queued)
        ));
        s.push_str(
            "# HELP whirl_job_results_bytes Compressed bytes of finished results in the store.\n",
        );
        s.push_str(&format!(
            "# TYPE whirl_job_results_bytes gauge\nwhirl_job_results_bytes {}\n",
            stats.result_bytes
        ));
    }
    s.push_str("# HELP whirl_jobs_running_here Jobs running on this replica.\n");
    s.push_str(&format!(
        "# TYPE whirl_jobs_running_here gauge\nwhirl_jobs_running_here {}\n",
        st.jobs.runner.running_here()
    ));
    let m = &st.metrics;
    s.push_str("# HELP whirl_store_lease_expiries_total Jobs found with an expired lease (their server died) by this replica.\n");
    s.push_str(&format!(
        "# TYPE whirl_store_lease_expiries_total counter\nwhirl_store_lease_expiries_total {}\n",
        m.lease_expiries.load(Ordering::Relaxed)
    ));
    s.push_str("# HELP whirl_store_errors_total Failed operations on the job store.\n");
    s.push_str(&format!(
        "# TYPE whirl_store_errors_total counter\nwhirl_store_errors_total {}\n",
        m.store_errors.load(Ordering::Relaxed)
    ));
    s.push_str("# HELP whirl_store_claim_duration_seconds Time to claim a queued job.\n");
    s.push_str("# TYPE whirl_store_claim_duration_seconds histogram\n");
    m.claims.lock().unwrap_or_else(|e| e.into_inner()).render(
        &mut s,
        "whirl_store_claim_duration_seconds",
        "",
        &CLAIM_BUCKETS,
    );
    s.push_str(
        "# HELP whirl_job_queue_wait_seconds Time jobs waited in the queue before a claim.\n",
    );
    s.push_str("# TYPE whirl_job_queue_wait_seconds histogram\n");
    m.waits.lock().unwrap_or_else(|e| e.into_inner()).render(
        &mut s,
        "whirl_job_queue_wait_seconds",
        "",
        &BUCKETS,
    );
    let running = st.pool.running();
    s.push_str("# HELP whirl_analyses_running Analyses running on the workers.\n");
    s.push_str(&format!(
        "# TYPE whirl_analyses_running gauge\nwhirl_analyses_running {running}\n"
    ));
    s.push_str(
        "# HELP whirl_queue_depth Analyses of this server admitted and waiting for a worker.\n",
    );
    s.push_str(&format!(
        "# TYPE whirl_queue_depth gauge\nwhirl_queue_depth {}\n",
        st.pool.in_flight().saturating_sub(running)
    ));
    s.push_str(
        "# HELP whirl_memory_reserved_bytes Heap reserved by running long analyses (estimates).\n",
    );
    s.push_str(&format!(
        "# TYPE whirl_memory_reserved_bytes gauge\nwhirl_memory_reserved_bytes {}\n",
        st.pool.memory_in_use()
    ));
    s.push_str("# HELP whirl_memory_budget_bytes Heap long analyses may reserve.\n");
    s.push_str(&format!(
        "# TYPE whirl_memory_budget_bytes gauge\nwhirl_memory_budget_bytes {}\n",
        st.pool.memory_budget()
    ));
    s.push_str("# HELP whirl_analysis_duration_seconds Wall time of analyses.\n");
    s.push_str("# TYPE whirl_analysis_duration_seconds histogram\n");
    for (a, h) in st
        .metrics
        .analyses
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .iter()
    {
        h.render(
            &mut s,
            "whirl_analysis_duration_seconds",
            &format!("analysis=\"{a}\""),
            &BUCKETS,
        );
    }
    s
}
