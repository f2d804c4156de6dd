//! Prometheus metrics in text format: requests, jobs by status, queue depth, analysis
//! durations, and the job store: the shared queue's depth over all replicas, claim latency,
//! time jobs wait in the queue, lease expiries and store errors. Here the middleware that
//! counts requests and the exposition text; the counters are [`Metrics`] (`jobs::metrics`).

use std::sync::atomic::Ordering;

use axum::extract::{MatchedPath, Request, State};
use axum::middleware::Next;
use axum::response::Response;

use super::AppState;
pub use crate::jobs::metrics::Metrics;
use crate::jobs::metrics::{BUCKETS, CLAIM_BUCKETS};
use crate::jobs::status_name;
use crate::jobs::store::Stats;
use crate::model::api::JobStatus;

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
        "# HELP whirl_memory_reserved_bytes Heap reserved by running analyses (estimates: long ones, and the synchronous answers of short ones) and by answers not yet sent.\n",
    );
    s.push_str(&format!(
        "# TYPE whirl_memory_reserved_bytes gauge\nwhirl_memory_reserved_bytes {}\n",
        st.pool.memory_in_use()
    ));
    s.push_str("# HELP whirl_memory_budget_bytes Heap running analyses and answers not yet sent may reserve.\n");
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
