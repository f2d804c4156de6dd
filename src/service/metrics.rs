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

/// Counts every matched request by method, route template and status.
pub async fn track(State(st): State<AppState>, req: Request, next: Next) -> Response {
    let method = req.method().to_string();
    let route = req
        .extensions()
        .get::<MatchedPath>()
        .map(|p| p.as_str().to_string())
        .unwrap_or_else(|| "unmatched".into());
    let resp = next.run(req).await;
    st.metrics
        .count_request(&method, &route, resp.status().as_u16());
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
