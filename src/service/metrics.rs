//! Prometheus metrics in text format: requests, jobs by status, queue depth, analysis
//! durations.

use std::collections::BTreeMap;
use std::sync::Mutex;
use std::time::Duration;

use axum::extract::{MatchedPath, Request, State};
use axum::middleware::Next;
use axum::response::Response;

use super::AppState;
use super::jobs::status_name;

/// Upper bounds of the duration histogram, s.
const BUCKETS: [f64; 10] = [0.01, 0.05, 0.1, 0.5, 1.0, 5.0, 10.0, 30.0, 60.0, 300.0];

#[derive(Default)]
struct Histogram {
    counts: [u64; BUCKETS.len()],
    sum: f64,
    count: u64,
}

#[derive(Default)]
pub struct Metrics {
    requests: Mutex<BTreeMap<(String, String, u16), u64>>,
    analyses: Mutex<BTreeMap<String, Histogram>>,
}

impl Metrics {
    pub fn count_request(&self, method: &str, route: &str, status: u16) {
        let mut r = self.requests.lock().unwrap_or_else(|e| e.into_inner());
        *r.entry((method.to_string(), route.to_string(), status))
            .or_default() += 1;
    }

    pub fn observe_analysis(&self, analysis: &str, d: Duration) {
        let mut a = self.analyses.lock().unwrap_or_else(|e| e.into_inner());
        let h = a.entry(analysis.to_string()).or_default();
        let s = d.as_secs_f64();
        for (i, le) in BUCKETS.iter().enumerate() {
            if s <= *le {
                h.counts[i] += 1;
            }
        }
        h.sum += s;
        h.count += 1;
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

/// The exposition text.
pub fn render(st: &AppState) -> String {
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
    s.push_str("# HELP whirl_jobs Jobs held, by status.\n# TYPE whirl_jobs gauge\n");
    for (status, n) in st.jobs.counts() {
        s.push_str(&format!(
            "whirl_jobs{{status=\"{}\"}} {n}\n",
            status_name(status)
        ));
    }
    let running = st.pool.running();
    s.push_str("# HELP whirl_analyses_running Analyses running on the workers.\n");
    s.push_str(&format!(
        "# TYPE whirl_analyses_running gauge\nwhirl_analyses_running {running}\n"
    ));
    s.push_str("# HELP whirl_queue_depth Analyses admitted and waiting for a worker.\n");
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
    s.push_str("# HELP whirl_job_results_bytes Compressed bytes of finished results held.\n");
    s.push_str(&format!(
        "# TYPE whirl_job_results_bytes gauge\nwhirl_job_results_bytes {}\n",
        st.jobs.stored_bytes()
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
        for (le, c) in BUCKETS.iter().zip(h.counts) {
            s.push_str(&format!(
                "whirl_analysis_duration_seconds_bucket{{analysis=\"{a}\",le=\"{le}\"}} {c}\n"
            ));
        }
        s.push_str(&format!(
            "whirl_analysis_duration_seconds_bucket{{analysis=\"{a}\",le=\"+Inf\"}} {}\n",
            h.count
        ));
        s.push_str(&format!(
            "whirl_analysis_duration_seconds_sum{{analysis=\"{a}\"}} {}\n",
            h.sum
        ));
        s.push_str(&format!(
            "whirl_analysis_duration_seconds_count{{analysis=\"{a}\"}} {}\n",
            h.count
        ));
    }
    s
}
