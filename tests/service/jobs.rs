//! The operable service: job lifecycle, cancellation latency, the queue bound under a burst,
//! time limits, shutdown, plots and tables, metrics and request ids. In process, each test
//! with an embedded job store of its own (a temporary directory).

use std::time::{Duration, Instant};

use axum::Router;
use axum::body::Body;
use axum::http::{Request, StatusCode, header};
use http_body_util::BodyExt;
use serde_json::{Value, json};
use tower::ServiceExt;
use whirl::service::{Config, app, app_with_state};

/// The default settings, with a job store of this test's own (kept while the guard lives).
fn config() -> (Config, tempfile::TempDir) {
    let dir = tempfile::tempdir().unwrap();
    let config = Config {
        data_dir: dir.path().to_path_buf(),
        ..Config::default()
    };
    (config, dir)
}

async fn call(
    app: &Router,
    method: &str,
    uri: &str,
    body: Option<Value>,
    accept: Option<&str>,
) -> (StatusCode, axum::http::HeaderMap, Vec<u8>) {
    let mut req = Request::builder()
        .method(method)
        .uri(uri)
        .header(header::CONTENT_TYPE, "application/json");
    if let Some(a) = accept {
        req = req.header(header::ACCEPT, a);
    }
    let req = req
        .body(
            body.map(|b| Body::from(b.to_string()))
                .unwrap_or_else(Body::empty),
        )
        .unwrap();
    let resp = app.clone().oneshot(req).await.unwrap();
    let (status, headers) = (resp.status(), resp.headers().clone());
    (
        status,
        headers,
        resp.into_body()
            .collect()
            .await
            .unwrap()
            .to_bytes()
            .to_vec(),
    )
}

async fn json_call(
    app: &Router,
    method: &str,
    uri: &str,
    body: Option<Value>,
) -> (StatusCode, Value) {
    let (s, _, b) = call(app, method, uri, body, None).await;
    (s, serde_json::from_slice(&b).unwrap_or(Value::Null))
}

fn example(name: &str) -> Value {
    let path = format!("{}/examples/{name}", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// A Campbell sweep of many seconds: the compressor, viscous (one eigenproblem per speed, so
/// cancellation is checked every few tens of ms even on a loaded machine), many speeds, on the
/// full model (modal reduction would make it take well under a second).
fn long_job() -> Value {
    let mut input = example("compressor-hysteretic.campbell.json");
    input["damping"] = json!({"model": "viscous"});
    input["speeds"] = json!({"start": 0.0, "stop": 1500.0, "count": 1500});
    input["modal_reduction"] = json!(false);
    json!({"analysis": "campbell", "input": input})
}

async fn wait_for(app: &Router, id: &str, done: impl Fn(&Value) -> bool, limit: Duration) -> Value {
    let t0 = Instant::now();
    loop {
        let (_, v) = json_call(app, "GET", &format!("/v1/jobs/{id}"), None).await;
        if done(&v) || t0.elapsed() > limit {
            return v;
        }
        tokio::time::sleep(Duration::from_millis(10)).await;
    }
}

fn finished(v: &Value) -> bool {
    ["succeeded", "failed", "cancelled"].contains(&v["status"].as_str().unwrap_or(""))
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_job_is_submitted_polled_and_fetched() {
    let (config, _dir) = config();
    let app = app(config);
    let input = example("jeffcott-nvd.campbell.json");
    let (status, headers, body) = call(
        &app,
        "POST",
        "/v1/jobs",
        Some(json!({"analysis": "campbell", "input": input})),
        None,
    )
    .await;
    assert_eq!(status, StatusCode::ACCEPTED);
    let job: Value = serde_json::from_slice(&body).unwrap();
    let id = job["id"].as_str().unwrap().to_string();
    assert_eq!(headers[header::LOCATION], format!("/v1/jobs/{id}").as_str());
    assert_eq!(job["analysis"], "campbell");
    let v = wait_for(&app, &id, finished, Duration::from_secs(20)).await;
    assert_eq!(v["status"], "succeeded", "{v}");
    assert_eq!(v["progress"], 1.0);
    assert!(
        v["created_at"].is_string() && v["started_at"].is_string() && v["finished_at"].is_string()
    );
    // The result is the synchronous body.
    let (_, result) = json_call(&app, "GET", &format!("/v1/jobs/{id}/result"), None).await;
    let (_, sync) = json_call(&app, "POST", "/v1/campbell", Some(input)).await;
    assert_eq!(result, sync);
    // And the table or the plot on request.
    let (s, h, csv) = call(
        &app,
        "GET",
        &format!("/v1/jobs/{id}/result"),
        None,
        Some("text/csv"),
    )
    .await;
    assert_eq!(
        (s, h[header::CONTENT_TYPE].to_str().unwrap()),
        (StatusCode::OK, "text/csv")
    );
    assert!(
        String::from_utf8(csv)
            .unwrap()
            .starts_with("speed [rad/s],mode1_forward_frequency [rad/s]")
    );
    let (s, _, svg) = call(
        &app,
        "GET",
        &format!("/v1/jobs/{id}/result"),
        None,
        Some("image/svg+xml"),
    )
    .await;
    assert_eq!(s, StatusCode::OK);
    assert!(String::from_utf8(svg).unwrap().contains("<svg"));
    // Unknown jobs are 404; cancelling a finished one is 409.
    assert_eq!(
        json_call(&app, "GET", "/v1/jobs/nope", None).await.0,
        StatusCode::NOT_FOUND
    );
    assert_eq!(
        json_call(&app, "DELETE", &format!("/v1/jobs/{id}"), None)
            .await
            .0,
        StatusCode::CONFLICT
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn invalid_job_input_is_refused_at_once_with_the_path() {
    let (config, _dir) = config();
    let app = app(config);
    let (status, v) = json_call(&app, "POST", "/v1/jobs", Some(json!({"analysis": "modal",
        "input": {"rotor": {"type": "jeffcott", "mass": -1.0, "stiffness": 1.0}, "damping": {"model": "viscous"}}}))).await;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(v["errors"][0]["path"], "input.rotor.mass");
    let (status, _) = json_call(
        &app,
        "POST",
        "/v1/jobs",
        Some(json!({"analysis": "everything", "input": {}})),
    )
    .await;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_running_job_reports_progress_and_stops_within_a_second_of_cancel() {
    let (config, _dir) = config();
    let app = app(config);
    let (status, job) = json_call(&app, "POST", "/v1/jobs", Some(long_job())).await;
    assert_eq!(status, StatusCode::ACCEPTED);
    let id = job["id"].as_str().unwrap().to_string();
    // 409 before success.
    assert_eq!(
        json_call(&app, "GET", &format!("/v1/jobs/{id}/result"), None)
            .await
            .0,
        StatusCode::CONFLICT
    );
    // Progress really advances.
    let v = wait_for(
        &app,
        &id,
        |v| v["progress"].as_f64().unwrap_or(0.0) > 0.05,
        Duration::from_secs(30),
    )
    .await;
    let p = v["progress"].as_f64().unwrap();
    assert!(p > 0.05 && p < 1.0 && v["status"] == "running", "{v}");
    let t0 = Instant::now();
    let (status, v) = json_call(&app, "DELETE", &format!("/v1/jobs/{id}"), None).await;
    assert_eq!(status, StatusCode::OK, "{v}");
    assert_eq!(v["status"], "cancelled", "recorded at once: {v}");
    let v = wait_for(&app, &id, finished, Duration::from_secs(5)).await;
    let latency = t0.elapsed();
    assert_eq!(v["status"], "cancelled");
    assert!(
        latency < Duration::from_secs(1),
        "stopped after {latency:?}"
    );
    assert!(v["error"]["detail"].as_str().unwrap().contains("client"));
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_burst_fills_the_queue_and_nothing_accepted_is_lost() {
    let (config, _dir) = config();
    let app = app(Config {
        workers: 1,
        queue: 2,
        ..config
    });
    let mut accepted = vec![];
    let mut refused = 0;
    for _ in 0..8 {
        let (status, headers, body) = call(&app, "POST", "/v1/jobs", Some(long_job()), None).await;
        match status {
            StatusCode::ACCEPTED => accepted.push(
                serde_json::from_slice::<Value>(&body).unwrap()["id"]
                    .as_str()
                    .unwrap()
                    .to_string(),
            ),
            StatusCode::SERVICE_UNAVAILABLE => {
                assert!(headers.contains_key(header::RETRY_AFTER));
                refused += 1;
            }
            s => panic!("unexpected {s}"),
        }
    }
    assert_eq!((accepted.len(), refused), (3, 5));
    let (status, _) = json_call(&app, "GET", "/readyz", None).await;
    assert_eq!(status, StatusCode::SERVICE_UNAVAILABLE);
    // Queued and running jobs are cancelled at once (200). The first job takes the worker
    // asynchronously: wait until it has.
    let first = wait_for(
        &app,
        &accepted[0],
        |v| v["status"] == "running",
        Duration::from_secs(10),
    )
    .await;
    assert_eq!(first["status"], "running", "{first}");
    let mut statuses = vec![];
    for id in &accepted {
        statuses.push(
            json_call(&app, "DELETE", &format!("/v1/jobs/{id}"), None)
                .await
                .0,
        );
    }
    assert_eq!(statuses, [StatusCode::OK; 3]);
    for id in &accepted {
        let v = wait_for(&app, id, finished, Duration::from_secs(5)).await;
        assert_eq!(v["status"], "cancelled", "{v}");
    }
    // The running analysis frees its worker at its next check, within a second.
    let t0 = Instant::now();
    while json_call(&app, "GET", "/readyz", None).await.0 != StatusCode::OK {
        assert!(
            t0.elapsed() < Duration::from_secs(1),
            "still busy after a second"
        );
        tokio::time::sleep(Duration::from_millis(10)).await;
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_job_over_its_time_limit_fails_with_the_reason() {
    let (config, _dir) = config();
    let app = app(Config {
        job_time_limit: Duration::from_secs(1),
        ..config
    });
    let (_, job) = json_call(&app, "POST", "/v1/jobs", Some(long_job())).await;
    let id = job["id"].as_str().unwrap().to_string();
    let v = wait_for(&app, &id, finished, Duration::from_secs(5)).await;
    assert_eq!(v["status"], "failed", "{v}");
    assert!(
        v["error"]["detail"]
            .as_str()
            .unwrap()
            .contains("time limit")
    );
}

/// The store keeps jobs across a shutdown: a job still running after the grace goes back to
/// the queue (it is not lost, nor cancelled), and the next server on the store runs it.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn shutdown_hands_running_jobs_back_to_the_queue() {
    let (config, _dir) = config();
    let (app, state) = app_with_state(config.clone());
    let (_, job) = json_call(&app, "POST", "/v1/jobs", Some(long_job())).await;
    let id = job["id"].as_str().unwrap().to_string();
    wait_for(
        &app,
        &id,
        |v| v["status"] == "running",
        Duration::from_secs(5),
    )
    .await;
    state.jobs.shutdown(Duration::from_millis(100)).await;
    let (_, v) = json_call(&app, "GET", &format!("/v1/jobs/{id}"), None).await;
    assert_eq!(v["status"], "queued", "{v}");
    // New jobs are refused.
    assert_eq!(
        json_call(&app, "POST", "/v1/jobs", Some(long_job()))
            .await
            .0,
        StatusCode::SERVICE_UNAVAILABLE
    );
    // The next server on the same store runs it.
    let next = whirl::service::app(config);
    let v = wait_for(
        &next,
        &id,
        |v| v["status"] == "running",
        Duration::from_secs(5),
    )
    .await;
    assert_eq!(v["status"], "running", "{v}");
    let (status, _) = json_call(&next, "DELETE", &format!("/v1/jobs/{id}"), None).await;
    assert_eq!(status, StatusCode::OK);
}

/// Retention is enforced in the store: by count, by compressed bytes of results, and by age.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn finished_jobs_are_forgotten_past_their_count_bytes_and_age() {
    let quick = || json!({"analysis": "campbell", "input": example("jeffcott-nvd.campbell.json")});
    async fn run(app: &Router, job: Value) -> String {
        let (status, v) = json_call(app, "POST", "/v1/jobs", Some(job)).await;
        assert_eq!(status, StatusCode::ACCEPTED, "{v}");
        let id = v["id"].as_str().unwrap().to_string();
        let v = wait_for(app, &id, finished, Duration::from_secs(20)).await;
        assert_eq!(v["status"], "succeeded", "{v}");
        id
    }
    let kept = |app: Router, id: String| async move {
        json_call(&app, "GET", &format!("/v1/jobs/{id}"), None)
            .await
            .0
            == StatusCode::OK
    };
    // Each result is about 4960 bytes gzipped: 12000 bytes keep two, as does a count of two.
    for limits in [
        Config {
            max_finished_jobs: 2,
            ..Config::default()
        },
        Config {
            job_result_bytes: 12000,
            ..Config::default()
        },
    ] {
        let (config, _dir) = config();
        let app = app(Config {
            data_dir: config.data_dir,
            ..limits
        });
        let mut ids = vec![];
        for _ in 0..3 {
            ids.push(run(&app, quick()).await);
        }
        // Retention runs right after a job finishes: give it a moment to have run.
        let t0 = Instant::now();
        let held = loop {
            let mut held = vec![];
            for id in &ids {
                held.push(kept(app.clone(), id.clone()).await);
            }
            if held == [false, true, true] || t0.elapsed() > Duration::from_secs(3) {
                break held;
            }
            tokio::time::sleep(Duration::from_millis(20)).await;
        };
        assert_eq!(held, [false, true, true], "the oldest is forgotten");
    }
    let (config, _dir) = config();
    let app = app(Config {
        job_retention: Duration::from_secs(1),
        ..config
    });
    let id = run(&app, quick()).await;
    assert!(kept(app.clone(), id.clone()).await);
    tokio::time::sleep(Duration::from_millis(1100)).await;
    assert!(
        !kept(app.clone(), id).await,
        "forgotten after its retention"
    );
}

/// Without its store the service still serves analyses, but it is not ready, and the job
/// endpoints answer 503 with `Retry-After` (not 500, not a hang).
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_unreachable_store_fails_readiness_and_jobs_with_503() {
    let app = app(Config {
        // Nothing listens on port 1.
        database_url: Some("postgres://whirl@127.0.0.1:1/whirl".into()),
        ..Config::default()
    });
    let (status, v) = json_call(&app, "GET", "/readyz", None).await;
    assert_eq!(status, StatusCode::SERVICE_UNAVAILABLE, "{v}");
    assert_eq!(v["status"], "store unreachable");
    let input = example("jeffcott-nvd.campbell.json");
    let job = json!({"analysis": "campbell", "input": input});
    let (status, headers, _) = call(&app, "POST", "/v1/jobs", Some(job), None).await;
    assert_eq!(status, StatusCode::SERVICE_UNAVAILABLE);
    assert!(headers.contains_key(header::RETRY_AFTER));
    let (status, _) = json_call(
        &app,
        "GET",
        "/v1/jobs/01890a5d-ac96-774b-bcce-b302099a8057",
        None,
    )
    .await;
    assert_eq!(status, StatusCode::SERVICE_UNAVAILABLE);
    let (status, _) = json_call(&app, "POST", "/v1/campbell", Some(input)).await;
    assert_eq!(status, StatusCode::OK, "analyses do not need the store");
    let (_, _, text) = call(&app, "GET", "/metrics", None, None).await;
    assert!(
        String::from_utf8(text)
            .unwrap()
            .contains("whirl_store_up 0")
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn plots_and_tables_by_accept() {
    let (config, _dir) = config();
    let app = app(config);
    let body = example("example1-equivalent.campbell.json");
    let (s, h, svg) = call(
        &app,
        "POST",
        "/v1/campbell",
        Some(body.clone()),
        Some("image/svg+xml"),
    )
    .await;
    assert_eq!(
        (s, h[header::CONTENT_TYPE].to_str().unwrap()),
        (StatusCode::OK, "image/svg+xml")
    );
    let svg = String::from_utf8(svg).unwrap();
    for text in [
        "Campbell diagram",
        "Decay-rate plot",
        "spin speed [rad/s]",
        "spin speed [rpm]",
        "forward",
        "backward",
        "threshold 882.7",
    ] {
        assert!(svg.contains(text), "{text} missing from the plot");
    }
    let (_, _, csv) = call(&app, "POST", "/v1/campbell", Some(body), Some("text/csv")).await;
    let csv = String::from_utf8(csv).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines.len(), 202, "header and 201 speeds");
    // Per branch: frequency, decay rate, log decrement, damping ratio, whirl ratio.
    assert_eq!(lines[0].split(',').count(), 1 + 8 * 5);
    assert!(lines[1].starts_with("0,"));
    for (file, endpoint, header_start) in [
        (
            "example1-runup-nvd.time-response.json",
            "time-response",
            "time [s],node1_x [m],node1_y [m]",
        ),
        (
            "compressor-equivalent.stability.json",
            "stability",
            "speed [rad/s],max_decay_rate [1/s]",
        ),
        (
            "example1-nvd.unbalance-response.json",
            "unbalance-response",
            "speed [rad/s],node1_amplitude [m]",
        ),
    ] {
        let (s, _, csv) = call(
            &app,
            "POST",
            &format!("/v1/{endpoint}"),
            Some(example(file)),
            Some("text/csv"),
        )
        .await;
        assert_eq!(s, StatusCode::OK);
        assert!(
            String::from_utf8(csv).unwrap().starts_with(header_start),
            "{endpoint}"
        );
        let (s, h, svg) = call(
            &app,
            "POST",
            &format!("/v1/{endpoint}"),
            Some(example(file)),
            Some("image/svg+xml"),
        )
        .await;
        assert_eq!(
            (s, h[header::CONTENT_TYPE].to_str().unwrap()),
            (StatusCode::OK, "image/svg+xml")
        );
        assert!(String::from_utf8(svg).unwrap().contains("<svg"));
    }
    // q-values are honoured; an impossible format is 406.
    let (_, h, _) = call(
        &app,
        "POST",
        "/v1/modal",
        Some(example("jeffcott-nvd.modal.json")),
        Some("text/csv;q=0.5, application/json"),
    )
    .await;
    assert_eq!(h[header::CONTENT_TYPE], "application/json");
    let (s, _, _) = call(
        &app,
        "POST",
        "/v1/modal",
        Some(example("jeffcott-nvd.modal.json")),
        Some("image/svg+xml"),
    )
    .await;
    assert_eq!(s, StatusCode::NOT_ACCEPTABLE);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn metrics_and_request_ids() {
    let (config, _dir) = config();
    let app = app(config);
    let (_, h, _) = call(
        &app,
        "POST",
        "/v1/modal",
        Some(example("jeffcott-nvd.modal.json")),
        None,
    )
    .await;
    assert!(h.contains_key("x-request-id"));
    let (s, h, text) = call(&app, "GET", "/metrics", None, None).await;
    assert_eq!(s, StatusCode::OK);
    assert!(
        h[header::CONTENT_TYPE]
            .to_str()
            .unwrap()
            .starts_with("text/plain")
    );
    let text = String::from_utf8(text).unwrap();
    for line in [
        "whirl_http_requests_total{method=\"POST\",route=\"/v1/modal\",status=\"200\"} 1",
        "whirl_jobs{status=\"queued\"} 0",
        "whirl_queue_depth 0",
        "whirl_analysis_duration_seconds_count{analysis=\"modal\"} 1",
    ] {
        assert!(text.contains(line), "{line} missing from:\n{text}");
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_audit_analyses_run_as_jobs_and_their_results_render_again() {
    let (config, _dir) = config();
    let app = app(config);
    for (analysis, file, accept) in [
        (
            "critical-speed-map",
            "rotor-a.critical-speed-map.json",
            "text/csv",
        ),
        ("static", "ross-rotor-example.static.json", "image/svg+xml"),
        ("level1", "example1-hysteretic.level1.json", "text/csv"),
        (
            "frequency-response",
            "example1-hysteretic.frequency-response.json",
            "image/svg+xml",
        ),
        ("report", "rotor-a-nvd.report.json", "text/html"),
    ] {
        let body = json!({"analysis": analysis, "input": example(file)});
        let (status, v) = json_call(&app, "POST", "/v1/jobs", Some(body)).await;
        assert_eq!(status, StatusCode::ACCEPTED, "{analysis}: {v}");
        let id = v["id"].as_str().unwrap().to_string();
        let done = wait_for(&app, &id, finished, Duration::from_secs(120)).await;
        assert_eq!(done["status"], "succeeded", "{analysis}: {done}");
        let uri = format!("/v1/jobs/{id}/result");
        let (status, _) = json_call(&app, "GET", &uri, None).await;
        assert_eq!(status, StatusCode::OK, "{analysis}");
        // The stored result is read back into its type and rendered in the other formats.
        let (status, headers, body) = call(&app, "GET", &uri, None, Some(accept)).await;
        assert_eq!(status, StatusCode::OK, "{analysis} as {accept}");
        let ctype = headers[header::CONTENT_TYPE].to_str().unwrap();
        assert!(ctype.starts_with(accept), "{analysis}: {ctype}");
        assert!(body.len() > 200, "{analysis}: {} bytes", body.len());
    }
}
