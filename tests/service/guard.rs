//! What stands between a request and the analyses (issue 28): the bearer token, security
//! headers, request ids, job ids checked before any store sees them, problem+json for every
//! error, objects where the schema says object, the run-up step estimate before any work, and
//! the embedded store's private, locked directory. The app in process, no socket.

use std::os::unix::fs::PermissionsExt;
use std::time::{Duration, Instant};

use http_body_util::BodyExt;
use serde_json::{Value, json};
use tower::ServiceExt;
use whirl::service::guard::ApiToken;
use whirl::service::{AppState, Config, app};

async fn call(
    app: axum::Router,
    method: &str,
    path: &str,
    headers: &[(&str, &str)],
    body: Option<Value>,
) -> (u16, axum::http::HeaderMap, Vec<u8>) {
    let mut req = axum::http::Request::builder().method(method).uri(path);
    for (k, v) in headers {
        req = req.header(*k, *v);
    }
    if body.is_some() {
        req = req.header("content-type", "application/json");
    }
    let req = req
        .body(axum::body::Body::from(
            body.map(|b| b.to_string()).unwrap_or_default(),
        ))
        .unwrap();
    let resp = app.oneshot(req).await.unwrap();
    let status = resp.status().as_u16();
    let headers = resp.headers().clone();
    let bytes = resp
        .into_body()
        .collect()
        .await
        .unwrap()
        .to_bytes()
        .to_vec();
    (status, headers, bytes)
}

fn example(name: &str) -> Value {
    let path = format!("{}/examples/{name}", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn store_dir() -> (Config, tempfile::TempDir) {
    let dir = tempfile::tempdir().unwrap();
    let config = Config {
        data_dir: dir.path().join("data"),
        ..Config::default()
    };
    (config, dir)
}

const TOKEN: &str = "9f2c4e1a-token-of-the-test-7d3b";

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_token_locks_every_path_but_the_probes_and_the_docs() {
    let (config, _dir) = store_dir();
    let app = app(Config {
        api_token: Some(ApiToken::new(TOKEN).unwrap()),
        ..config
    });
    let modal = example("jeffcott-nvd.modal.json");
    let bearer = format!("Bearer {TOKEN}");
    let wrong = format!("Bearer {TOKEN}x");
    for (method, path, body) in [
        ("POST", "/v1/modal", Some(modal.clone())),
        ("GET", "/metrics", None),
        ("GET", "/v1/jobs/01890a5d-ac96-774b-bcce-b302099a8057", None),
        (
            "DELETE",
            "/v1/jobs/01890a5d-ac96-774b-bcce-b302099a8057",
            None,
        ),
        ("GET", "/no/such/path", None),
    ] {
        for headers in [vec![], vec![("authorization", wrong.as_str())]] {
            let (status, h, body) = call(app.clone(), method, path, &headers, body.clone()).await;
            assert_eq!(status, 401, "{method} {path} {headers:?}");
            assert_eq!(h["www-authenticate"], "Bearer realm=\"whirl\"");
            assert_eq!(h["content-type"], "application/problem+json");
            let v: Value = serde_json::from_slice(&body).unwrap();
            assert_eq!(v["status"], 401, "{v}");
        }
    }
    let auth = [("authorization", bearer.as_str())];
    let (status, _, _) = call(app.clone(), "POST", "/v1/modal", &auth, Some(modal)).await;
    assert_eq!(status, 200);
    let (status, _, body) = call(app.clone(), "GET", "/metrics", &auth, None).await;
    assert_eq!(status, 200);
    assert!(String::from_utf8_lossy(&body).contains("whirl_"));
    // The scheme's name is case-insensitive (RFC 9110).
    let lower = format!("bearer {TOKEN}");
    let (status, _, _) = call(
        app.clone(),
        "GET",
        "/metrics",
        &[("authorization", lower.as_str())],
        None,
    )
    .await;
    assert_eq!(status, 200);
    for path in ["/healthz", "/readyz", "/docs/", "/openapi.json"] {
        let (status, _, _) = call(app.clone(), "GET", path, &[], None).await;
        assert_eq!(status, 200, "{path} needs no token");
    }
    // The setting: a short token is refused at start, an empty one means none.
    let short = Config::from_lookup(|k| (k == "WHIRL_API_TOKEN").then(|| "secret".into()));
    assert!(short.unwrap_err().contains("at least 16"));
    let none = Config::from_lookup(|k| (k == "WHIRL_API_TOKEN").then(String::new)).unwrap();
    assert!(none.api_token.is_none());
    let set = Config::from_lookup(|k| (k == "WHIRL_API_TOKEN").then(|| TOKEN.into())).unwrap();
    assert!(set.api_token.unwrap().matches(TOKEN.as_bytes()));
    assert!(
        !format!(
            "{:?}",
            Config::from_lookup(|k| (k == "WHIRL_API_TOKEN").then(|| TOKEN.into())).unwrap()
        )
        .contains(TOKEN)
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn every_answer_has_nosniff_and_a_content_security_policy() {
    let (config, _dir) = store_dir();
    let app = app(config);
    let report = example("rotor-a-nvd.report.json");
    let cases = [
        ("GET", "/healthz", None, "application/json"),
        ("GET", "/docs/", None, "text/html"),
        ("POST", "/v1/report", Some(report), "text/html"),
        ("GET", "/nowhere", None, "application/json"),
    ];
    for (method, path, body, accept) in cases {
        let (status, h, _) = call(app.clone(), method, path, &[("accept", accept)], body).await;
        assert!(status == 200 || status == 404, "{path}: {status}");
        assert_eq!(h["x-content-type-options"], "nosniff", "{path}");
        let csp = h["content-security-policy"].to_str().unwrap();
        assert!(csp.contains("default-src 'none'"), "{path}: {csp}");
        assert!(csp.contains("frame-ancestors 'none'"), "{path}: {csp}");
        if path == "/docs/" {
            assert!(csp.contains("script-src 'self'"), "{csp}");
        } else {
            // No script runs in a report or a plot, whatever a field holds.
            assert!(!csp.contains("script-src"), "{path}: {csp}");
        }
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn request_ids_are_kept_only_when_short_and_plain() {
    let (config, _dir) = store_dir();
    let app = app(config);
    let kept = "00-4bf92f3577b34da6a3ce929d0e0e4736-00f067aa0ba902b7-01";
    let (_, h, _) = call(
        app.clone(),
        "GET",
        "/healthz",
        &[("x-request-id", kept)],
        None,
    )
    .await;
    assert_eq!(h["x-request-id"], kept);
    let long = "a".repeat(200_000);
    for bad in [
        long.as_str(),
        "x\"}{\"level\":\"ERROR\",\"msg\":\"forged",
        "two words",
        "",
    ] {
        let (_, h, _) = call(
            app.clone(),
            "GET",
            "/healthz",
            &[("x-request-id", bad)],
            None,
        )
        .await;
        let id = h["x-request-id"].to_str().unwrap();
        let uuid = uuid::Uuid::parse_str(id).unwrap_or_else(|_| panic!("{id:.80}"));
        assert_eq!(uuid.get_version_num(), 7);
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn job_ids_are_checked_before_any_store_and_every_error_is_a_problem() {
    // Nothing listens on port 1: a request that reached the store would wait and get 503.
    let app = app(Config {
        database_url: Some("postgres://whirl@127.0.0.1:1/whirl".into()),
        ..Config::default()
    });
    for (method, path) in [
        ("GET", "/v1/jobs/abc%00def"),
        ("GET", "/v1/jobs/%FF%FE"),
        ("GET", "/v1/jobs/%FF/result"),
        ("DELETE", "/v1/jobs/01890a5d-ac96-774b-bcce-b302099a805%00"),
        ("GET", "/v1/jobs/01890A5D-AC96-774B-BCCE-B302099A8057"),
        ("GET", "/v1/jobs/x%20y"),
    ] {
        let t0 = Instant::now();
        let (status, h, body) = call(app.clone(), method, path, &[], None).await;
        let took = t0.elapsed();
        assert_eq!(status, 404, "{method} {path}");
        assert_eq!(h["content-type"], "application/problem+json", "{path}");
        let v: Value = serde_json::from_slice(&body).unwrap();
        assert!(v["detail"].as_str().unwrap().contains("UUID"), "{v}");
        assert!(took < Duration::from_millis(100), "{path}: {took:?}");
    }
    // A valid id does reach the (unreachable) store: 503.
    let (status, _, _) = call(
        app.clone(),
        "GET",
        "/v1/jobs/01890a5d-ac96-774b-bcce-b302099a8057",
        &[],
        None,
    )
    .await;
    assert_eq!(status, 503);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_nul_in_a_job_id_on_postgresql_is_a_404_not_an_outage() {
    let url = std::env::var("WHIRL_TEST_POSTGRES")
        .unwrap_or_else(|_| "postgres://postgres@127.0.0.1:5432/test".into());
    let app = app(Config {
        database_url: Some(url),
        ..Config::default()
    });
    let (status, h, body) = call(app.clone(), "GET", "/v1/jobs/ab%00cd", &[], None).await;
    assert_eq!(status, 404, "{}", String::from_utf8_lossy(&body));
    assert_eq!(h["content-type"], "application/problem+json");
    let (status, _, _) = call(app.clone(), "GET", "/readyz", &[], None).await;
    assert_eq!(status, 200, "the store is up, and was never in doubt");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_array_where_an_object_is_read_is_a_422_at_its_path() {
    let (config, _dir) = store_dir();
    let app = app(config);
    let mut body = example("example1-nvd.modal.json");
    let (status, _, ok) = call(app.clone(), "POST", "/v1/modal", &[], Some(body.clone())).await;
    assert_eq!(status, 200, "{}", String::from_utf8_lossy(&ok));
    // The first support as an array, in the order of its fields: once read by position.
    body["rotor"]["supports"][0] = json!([0, 2.0e6, 0.06]);
    let (status, h, bad) = call(app.clone(), "POST", "/v1/modal", &[], Some(body)).await;
    let v: Value = serde_json::from_slice(&bad).unwrap();
    assert_eq!(status, 422, "{v}");
    assert_eq!(h["content-type"], "application/problem+json");
    assert_eq!(v["errors"][0]["path"], "rotor.supports[0]", "{v}");
    assert!(
        v["errors"][0]["message"]
            .as_str()
            .unwrap()
            .contains("must be an object"),
        "{v}"
    );
    // Everywhere: the damping's branches, a speed range, a job's input.
    let mut body = example("example1-nvd.campbell.json");
    body["speeds"] = json!([0.0, 50.0, 100.0]);
    let (status, _, _) = call(app.clone(), "POST", "/v1/campbell", &[], Some(body)).await;
    assert_eq!(status, 200, "a list of speeds is a list");
    let mut body = example("example1-nvd.modal.json");
    body["damping"]["rotating"] = json!([3, 10]);
    let (status, _, bad) = call(app.clone(), "POST", "/v1/modal", &[], Some(body)).await;
    let v: Value = serde_json::from_slice(&bad).unwrap();
    assert_eq!(status, 422, "{v}");
    assert_eq!(v["errors"][0]["path"], "damping.rotating", "{v}");
    let job =
        json!({"analysis": "modal", "input": {"rotor": [1, 1], "damping": {"model": "viscous"}}});
    let (status, _, bad) = call(app.clone(), "POST", "/v1/jobs", &[], Some(job)).await;
    let v: Value = serde_json::from_slice(&bad).unwrap();
    assert_eq!(status, 422, "{v}");
    assert_eq!(v["errors"][0]["path"], "input.rotor", "{v}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_run_up_too_fast_for_the_step_limit_is_refused_before_any_work() {
    let (config, _dir) = store_dir();
    let app = app(config);
    // 0 to 1e6 rad/s in 1 s: the unbalance turns through 5e5 rad, 2.5e6 steps of 0.2 rad.
    let mut body = example("example1-runup-nvd.time-response.json");
    body["speed_profile"] = json!([[0, 0], [1, 1.0e6]]);
    body["duration"] = json!(1.0);
    let t0 = Instant::now();
    let (status, _, bad) = call(app.clone(), "POST", "/v1/time-response", &[], Some(body)).await;
    let took = t0.elapsed();
    let v: Value = serde_json::from_slice(&bad).unwrap();
    assert_eq!(status, 422, "{v}");
    assert_eq!(v["errors"][0]["path"], "speed_profile", "{v}");
    let msg = v["errors"][0]["message"].as_str().unwrap();
    assert!(
        msg.contains("5.000e5 rad") && msg.contains("2.500e6"),
        "{msg}"
    );
    assert!(took < Duration::from_millis(200), "refused after {took:?}");
    eprintln!("run-up to 1e6 rad/s in 1 s refused in {took:?}");
    // The estimate is a lower bound of the steps taken: the example's run-up (0 to 600 rad/s
    // in 3 s: 900 rad, 4500 steps at least) on the exponential integrator and on TR-BDF2.
    for reduce in [true, false] {
        let mut body = example("example1-runup-nvd.time-response.json");
        body["modal_reduction"] = json!(reduce);
        let (status, _, ok) = call(app.clone(), "POST", "/v1/time-response", &[], Some(body)).await;
        let v: Value = serde_json::from_slice(&ok).unwrap();
        assert_eq!(status, 200, "{v:.300}");
        let steps = v["steps"].as_u64().unwrap();
        eprintln!("run-up, {}: {steps} steps (estimate 4500)", v["method"]);
        assert!(steps >= 4500, "{} took {steps} steps", v["method"]);
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_data_directory_is_private_and_held_by_one_server() {
    let (config, _dir) = store_dir();
    let data = config.data_dir.clone();
    let state = AppState::new(config.clone());
    state.start();
    let app = whirl::service::router(state.clone()).0;
    let (status, _, _) = call(app.clone(), "GET", "/readyz", &[], None).await;
    assert_eq!(status, 200);
    // A job, so that the WAL and the shared memory exist.
    let job = json!({"analysis": "modal", "input": example("jeffcott-nvd.modal.json")});
    let (status, _, _) = call(app.clone(), "POST", "/v1/jobs", &[], Some(job)).await;
    assert_eq!(status, 202);
    let mode = |p: &std::path::Path| std::fs::metadata(p).unwrap().permissions().mode() & 0o777;
    assert_eq!(mode(&data), 0o700, "the directory");
    for f in [
        "whirl.sqlite",
        "whirl.sqlite-wal",
        "whirl.sqlite-shm",
        "whirl.lock",
    ] {
        assert_eq!(mode(&data.join(f)), 0o600, "{f}");
    }
    // Another store of this process shares the directory (SQLite serves both)...
    let other = AppState::new(config);
    other.jobs.store.claim_dir().unwrap();
    // ...but a second server, another process, stops at start naming this one.
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_whirl"))
        .env("WHIRL_DATA_DIR", &data)
        .env("HOST", "127.0.0.1")
        .env("PORT", "0")
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let start = std::time::Instant::now();
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        if start.elapsed() > Duration::from_secs(20) {
            child.kill().unwrap();
            panic!("a second server on the same directory kept running");
        }
        std::thread::sleep(Duration::from_millis(50));
    };
    let mut err = String::new();
    std::io::Read::read_to_string(&mut child.stderr.take().unwrap(), &mut err).unwrap();
    assert!(!status.success());
    assert!(err.contains("in use by another whirl server"), "{err}");
    assert!(err.contains(&std::process::id().to_string()), "{err}");
}
