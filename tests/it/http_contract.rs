//! What browser and generated clients rely on (issue 32): CORS from the configured origins
//! only, immutable job results with ETags and 304, the job listing with filters and pages,
//! `Idempotency-Key` on submission, answers that name their analysis (the discriminator of a
//! job's result), absolute problem types that resolve to a page, and progress that never goes
//! back. In process, each test with a job store of its own.

use std::time::{Duration, Instant};

use axum::Router;
use axum::body::Body;
use axum::http::{HeaderMap, Request, StatusCode, header};
use http_body_util::BodyExt;
use serde_json::{Value, json};
use tower::ServiceExt;
use whirl::service::cors::Origins;
use whirl::service::{Config, app};

fn config() -> (Config, tempfile::TempDir) {
    let dir = tempfile::tempdir().unwrap();
    let config = Config {
        data_dir: dir.path().to_path_buf(),
        ..Config::default()
    };
    (config, dir)
}

/// A request with `headers`; status, headers and body.
async fn call(
    app: &Router,
    method: &str,
    uri: &str,
    body: Option<&Value>,
    headers: &[(&str, &str)],
) -> (StatusCode, HeaderMap, Vec<u8>) {
    let mut req = Request::builder().method(method).uri(uri);
    if body.is_some() {
        req = req.header(header::CONTENT_TYPE, "application/json");
    }
    for (k, v) in headers {
        req = req.header(*k, *v);
    }
    let req = req
        .body(body.map_or_else(Body::empty, |b| Body::from(b.to_string())))
        .unwrap();
    let resp = app.clone().oneshot(req).await.unwrap();
    let (status, headers) = (resp.status(), resp.headers().clone());
    let bytes = resp.into_body().collect().await.unwrap().to_bytes();
    (status, headers, bytes.to_vec())
}

async fn json(app: &Router, method: &str, uri: &str, body: Option<&Value>) -> (StatusCode, Value) {
    let (s, _, b) = call(app, method, uri, body, &[]).await;
    (s, serde_json::from_slice(&b).unwrap_or(Value::Null))
}

fn example(name: &str) -> Value {
    let path = format!("{}/examples/{name}", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn header_of<'a>(h: &'a HeaderMap, name: &str) -> &'a str {
    h.get(name).map_or("", |v| v.to_str().unwrap())
}

async fn submit(app: &Router, job: &Value) -> String {
    let (s, v) = json(app, "POST", "/v1/jobs", Some(job)).await;
    assert_eq!(s, StatusCode::ACCEPTED, "{v}");
    v["id"].as_str().unwrap().to_string()
}

async fn wait(app: &Router, id: &str) -> Value {
    let t0 = Instant::now();
    loop {
        let (_, v) = json(app, "GET", &format!("/v1/jobs/{id}"), None).await;
        let s = v["status"].as_str().unwrap_or("").to_string();
        if !["queued", "running"].contains(&s.as_str()) || t0.elapsed() > Duration::from_secs(60) {
            return v;
        }
        tokio::time::sleep(Duration::from_millis(10)).await;
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn cors_answers_the_configured_origins_only() {
    let preflight = [
        ("origin", "https://app.example.com"),
        ("access-control-request-method", "POST"),
        (
            "access-control-request-headers",
            "content-type, idempotency-key",
        ),
    ];
    // By default: no CORS at all (OPTIONS is a 405, no header grants anything).
    let (config, _dir) = config();
    let plain = app(config);
    let (s, h, _) = call(&plain, "OPTIONS", "/v1/campbell", None, &preflight).await;
    assert_eq!(s, StatusCode::METHOD_NOT_ALLOWED);
    assert!(h.get("access-control-allow-origin").is_none());
    let (_, h, _) = call(&plain, "GET", "/healthz", None, &preflight[..1]).await;
    assert!(h.get("access-control-allow-origin").is_none());

    let (mut config, _dir) = self::config();
    config.cors_origins = Origins::parse("https://app.example.com, http://localhost:5173").unwrap();
    let cors = app(config);
    let (s, h, body) = call(&cors, "OPTIONS", "/v1/campbell", None, &preflight).await;
    assert_eq!(s, StatusCode::OK);
    assert!(body.is_empty());
    assert_eq!(
        header_of(&h, "access-control-allow-origin"),
        "https://app.example.com"
    );
    let methods = header_of(&h, "access-control-allow-methods").to_ascii_lowercase();
    for m in ["get", "post", "delete"] {
        assert!(methods.contains(m), "{methods}");
    }
    let allowed = header_of(&h, "access-control-allow-headers").to_ascii_lowercase();
    for a in ["content-type", "idempotency-key", "if-none-match"] {
        assert!(allowed.contains(a), "{allowed}");
    }
    assert_eq!(header_of(&h, "access-control-max-age"), "600");
    // A simple request from an allowed origin: readable, with the job headers exposed.
    let (s, h, _) = call(
        &cors,
        "GET",
        "/healthz",
        None,
        &[("origin", "http://localhost:5173")],
    )
    .await;
    assert_eq!(s, StatusCode::OK);
    assert_eq!(
        header_of(&h, "access-control-allow-origin"),
        "http://localhost:5173"
    );
    let exposed = header_of(&h, "access-control-expose-headers").to_ascii_lowercase();
    for e in ["location", "etag", "retry-after", "link", "x-request-id"] {
        assert!(exposed.contains(e), "{exposed}");
    }
    assert!(
        header_of(&h, "vary")
            .to_ascii_lowercase()
            .contains("origin")
    );
    // Another origin is not granted anything.
    let (s, h, _) = call(
        &cors,
        "GET",
        "/healthz",
        None,
        &[("origin", "https://evil.example")],
    )
    .await;
    assert_eq!(s, StatusCode::OK);
    assert!(h.get("access-control-allow-origin").is_none());
    let evil = [preflight[1], ("origin", "https://evil.example")];
    let (_, h, _) = call(&cors, "OPTIONS", "/v1/campbell", None, &evil).await;
    assert!(h.get("access-control-allow-origin").is_none());
    // With CORS on, tower-http answers every OPTIONS as a preflight; without an allowed
    // origin it grants nothing.
    let (s, h, _) = call(&cors, "OPTIONS", "/v1/campbell", None, &[]).await;
    assert_eq!(s, StatusCode::OK);
    assert!(h.get("access-control-allow-origin").is_none());
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn job_results_are_immutable_and_revalidate_with_304() {
    let (config, _dir) = config();
    let app = app(config);
    let input = example("jeffcott-nvd.campbell.json");
    let id = submit(&app, &json!({"analysis": "campbell", "input": input})).await;
    assert_eq!(wait(&app, &id).await["status"], "succeeded");
    let uri = format!("/v1/jobs/{id}/result");
    let (s, h, body) = call(&app, "GET", &uri, None, &[]).await;
    assert_eq!(s, StatusCode::OK);
    let tag = header_of(&h, "etag").to_string();
    assert_eq!(tag, format!("W/\"{id}.json\""));
    assert_eq!(
        header_of(&h, "cache-control"),
        "private, max-age=31536000, immutable"
    );
    // The answer names its analysis, first, and equals the synchronous answer.
    let result: Value = serde_json::from_slice(&body).unwrap();
    assert_eq!(result["analysis"], "campbell");
    assert!(String::from_utf8_lossy(&body).starts_with(r#"{"analysis":"campbell","#));
    let (_, sync) = json(&app, "POST", "/v1/campbell", Some(&input)).await;
    assert_eq!(sync, result);

    // The tag again: 304, no body, the same tag and caching; gzip or not, the same tag.
    for (inm, enc) in [
        (tag.clone(), "identity"),
        (tag.clone(), "gzip"),
        (tag.trim_start_matches("W/").to_string(), "gzip"),
        (format!("\"other\", {tag}"), "identity"),
        ("*".to_string(), "identity"),
    ] {
        let (s, h, body) = call(
            &app,
            "GET",
            &uri,
            None,
            &[("if-none-match", &inm), ("accept-encoding", enc)],
        )
        .await;
        assert_eq!(s, StatusCode::NOT_MODIFIED, "{inm}");
        assert!(body.is_empty());
        assert_eq!(header_of(&h, "etag"), tag);
        assert_eq!(
            header_of(&h, "cache-control"),
            "private, max-age=31536000, immutable"
        );
    }
    // Another representation has another tag: the JSON's does not answer for the table.
    let (s, h, body) = call(
        &app,
        "GET",
        &uri,
        None,
        &[("if-none-match", &tag), ("accept", "text/csv")],
    )
    .await;
    assert_eq!(s, StatusCode::OK);
    assert!(!body.is_empty());
    let csv_tag = header_of(&h, "etag").to_string();
    assert_eq!(csv_tag, format!("W/\"{id}.csv\""));
    let (s, _, _) = call(
        &app,
        "GET",
        &uri,
        None,
        &[("if-none-match", &csv_tag), ("accept", "text/csv")],
    )
    .await;
    assert_eq!(s, StatusCode::NOT_MODIFIED);
    // A stale tag gets the body.
    let (s, _, body) = call(&app, "GET", &uri, None, &[("if-none-match", "W/\"old\"")]).await;
    assert_eq!((s, body.len() > 100), (StatusCode::OK, true));
    // Status answers are not results: no immutable caching there.
    let (_, h, _) = call(&app, "GET", &format!("/v1/jobs/{id}"), None, &[]).await;
    assert!(h.get("etag").is_none() && h.get("cache-control").is_none());
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn jobs_are_listed_newest_first_by_filter_and_page() {
    let (config, _dir) = config();
    let app = app(config);
    let campbell = json!({"analysis": "campbell", "input": example("jeffcott-nvd.campbell.json")});
    let modal = json!({"analysis": "modal", "input": example("jeffcott-nvd.modal.json")});
    let mut ids = vec![];
    for job in [&campbell, &modal, &campbell, &modal, &campbell] {
        ids.push(submit(&app, job).await);
    }
    for id in &ids {
        assert_eq!(wait(&app, id).await["status"], "succeeded");
    }
    let newest_first: Vec<String> = ids.iter().rev().cloned().collect();
    let listed = |v: &Value| -> Vec<String> {
        v["jobs"]
            .as_array()
            .unwrap()
            .iter()
            .map(|j| j["id"].as_str().unwrap().to_string())
            .collect()
    };
    let (s, all) = json(&app, "GET", "/v1/jobs", None).await;
    assert_eq!(s, StatusCode::OK);
    assert_eq!(listed(&all), newest_first);
    assert!(all.get("next").is_none());
    assert_eq!(all["jobs"][0]["status"], "succeeded");
    assert_eq!(all["jobs"][0]["progress"], 1.0);

    let (_, m) = json(&app, "GET", "/v1/jobs?analysis=modal", None).await;
    assert_eq!(listed(&m), vec![ids[3].clone(), ids[1].clone()]);
    let (_, c) = json(
        &app,
        "GET",
        "/v1/jobs?analysis=campbell&status=succeeded",
        None,
    )
    .await;
    assert_eq!(
        listed(&c),
        vec![ids[4].clone(), ids[2].clone(), ids[0].clone()]
    );
    let (_, none) = json(&app, "GET", "/v1/jobs?status=running", None).await;
    assert_eq!(listed(&none), Vec::<String>::new());

    // Pages of two: 2 + 2 + 1, following `next` (and the same in `Link`).
    let mut uri = "/v1/jobs?limit=2".to_string();
    let mut pages = vec![];
    loop {
        let (s, h, b) = call(&app, "GET", &uri, None, &[]).await;
        assert_eq!(s, StatusCode::OK);
        let v: Value = serde_json::from_slice(&b).unwrap();
        pages.push(listed(&v));
        let Some(next) = v["next"].as_str() else {
            assert!(h.get("link").is_none());
            break;
        };
        assert_eq!(header_of(&h, "link"), format!("<{next}>; rel=\"next\""));
        uri = next.to_string();
    }
    assert_eq!(
        pages.iter().map(Vec::len).collect::<Vec<_>>(),
        vec![2, 2, 1]
    );
    assert_eq!(pages.concat(), newest_first);

    // Bad filters: 422 naming each parameter.
    let (s, v) = json(
        &app,
        "GET",
        "/v1/jobs?status=done&analysis=nope&limit=0&before=x&colour=red",
        None,
    )
    .await;
    assert_eq!(s, StatusCode::UNPROCESSABLE_ENTITY);
    let mut paths: Vec<&str> = v["errors"]
        .as_array()
        .unwrap()
        .iter()
        .map(|e| e["path"].as_str().unwrap())
        .collect();
    paths.sort();
    assert_eq!(paths, ["analysis", "before", "colour", "limit", "status"]);
    let (s, _) = json(&app, "GET", "/v1/jobs?limit=101", None).await;
    assert_eq!(s, StatusCode::UNPROCESSABLE_ENTITY);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_idempotency_key_names_one_job() {
    let (config, _dir) = config();
    let app = app(config);
    let input = example("jeffcott-nvd.campbell.json");
    let body = json!({"analysis": "campbell", "input": input});
    let key = [("idempotency-key", "5f0c6a2e-retry-me")];
    let (s, h, b) = call(&app, "POST", "/v1/jobs", Some(&body), &key).await;
    assert_eq!(s, StatusCode::ACCEPTED);
    assert!(h.get("idempotent-replayed").is_none());
    let first: Value = serde_json::from_slice(&b).unwrap();
    let id = first["id"].as_str().unwrap();
    // The same request again (its fields in another order): the same job, said so.
    let mut reordered = serde_json::Map::new();
    reordered.insert("input".into(), body["input"].clone());
    reordered.insert("analysis".into(), body["analysis"].clone());
    let (s, h, b) = call(
        &app,
        "POST",
        "/v1/jobs",
        Some(&Value::Object(reordered)),
        &key,
    )
    .await;
    assert_eq!(s, StatusCode::ACCEPTED);
    assert_eq!(header_of(&h, "idempotent-replayed"), "true");
    assert_eq!(header_of(&h, "location"), format!("/v1/jobs/{id}"));
    let again: Value = serde_json::from_slice(&b).unwrap();
    assert_eq!(again["id"], id);
    // Once it has run, still the same job.
    assert_eq!(wait(&app, id).await["status"], "succeeded");
    let (_, _, b) = call(&app, "POST", "/v1/jobs", Some(&body), &key).await;
    let done: Value = serde_json::from_slice(&b).unwrap();
    assert_eq!(
        (done["id"].as_str(), done["status"].as_str()),
        (Some(id), Some("succeeded"))
    );
    // The same key with another request: 422, naming the job the key belongs to.
    let mut other = body.clone();
    other["input"]["speeds"]["count"] = json!(7);
    let (s, _, b) = call(&app, "POST", "/v1/jobs", Some(&other), &key).await;
    assert_eq!(s, StatusCode::UNPROCESSABLE_ENTITY);
    let p: Value = serde_json::from_slice(&b).unwrap();
    assert!(
        p["type"]
            .as_str()
            .unwrap()
            .ends_with("/problems/idempotency-key-reused")
    );
    assert!(p["detail"].as_str().unwrap().contains(id), "{p}");
    // Without a key, or with another, a new job each time.
    let (_, b) = json(&app, "POST", "/v1/jobs", Some(&body)).await;
    assert_ne!(b["id"], id);
    let (_, _, b) = call(
        &app,
        "POST",
        "/v1/jobs",
        Some(&body),
        &[("idempotency-key", "k2")],
    )
    .await;
    assert_ne!(serde_json::from_slice::<Value>(&b).unwrap()["id"], id);
    // A key that is not one: 422 naming the header.
    let (s, _, b) = call(
        &app,
        "POST",
        "/v1/jobs",
        Some(&body),
        &[("idempotency-key", "a b")],
    )
    .await;
    assert_eq!(s, StatusCode::UNPROCESSABLE_ENTITY);
    let p: Value = serde_json::from_slice(&b).unwrap();
    assert_eq!(p["errors"][0]["path"], "Idempotency-Key");
    let (_, all) = json(&app, "GET", "/v1/jobs", None).await;
    assert_eq!(all["jobs"].as_array().unwrap().len(), 3);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn problem_types_are_absolute_and_resolve_to_their_page() {
    let (config, _dir) = config();
    let app = app(config);
    let bad = json!({"rotor": {"type": "jeffcott", "mass": -1, "stiffness": 1}, "damping": {"model": "viscous"}, "speed": 0});
    let host = [("host", "whirl.test:8080")];
    let (s, h, b) = call(&app, "POST", "/v1/modal", Some(&bad), &host).await;
    assert_eq!(s, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(header_of(&h, "content-type"), "application/problem+json");
    let p: Value = serde_json::from_slice(&b).unwrap();
    assert_eq!(p["type"], "http://whirl.test:8080/problems/invalid-model");
    // The page it names: served here, describing that problem.
    let (s, h, page) = call(&app, "GET", "/problems/invalid-model", None, &[]).await;
    assert_eq!(s, StatusCode::OK);
    assert!(header_of(&h, "content-type").starts_with("text/html"));
    let page = String::from_utf8(page).unwrap();
    assert!(page.contains("<h1>Invalid model</h1>") && page.contains("<strong>422</strong>"));
    // Every kind of answer: 404, 405 (from a layer), behind a TLS proxy.
    let (_, _, b) = call(&app, "GET", "/v2/nothing", None, &host).await;
    let p: Value = serde_json::from_slice(&b).unwrap();
    assert_eq!(p["type"], "http://whirl.test:8080/problems/not-found");
    let proxied = [
        ("host", "whirl.example.com"),
        ("x-forwarded-proto", "https"),
    ];
    let (s, _, b) = call(&app, "PUT", "/v1/modal", None, &proxied).await;
    assert_eq!(s, StatusCode::METHOD_NOT_ALLOWED);
    let p: Value = serde_json::from_slice(&b).unwrap();
    assert_eq!(
        p["type"],
        "https://whirl.example.com/problems/method-not-allowed"
    );
    let (s, _, page) = call(&app, "GET", "/problems/method-not-allowed", None, &[]).await;
    assert_eq!(s, StatusCode::OK);
    assert!(
        String::from_utf8(page)
            .unwrap()
            .contains("<code>Allow</code>")
    );
    // No such kind: a 404 problem (whose own type resolves).
    let (s, _, _) = call(&app, "GET", "/problems/no-such-thing", None, &[]).await;
    assert_eq!(s, StatusCode::NOT_FOUND);
    // A stopped job's error too.
    let mut long = example("compressor-hysteretic.campbell.json");
    long["damping"] = json!({"model": "viscous"});
    long["speeds"] = json!({"start": 0.0, "stop": 1500.0, "count": 1500});
    long["modal_reduction"] = json!(false);
    let id = submit(&app, &json!({"analysis": "campbell", "input": long})).await;
    let (_, _, b) = call(&app, "DELETE", &format!("/v1/jobs/{id}"), None, &host).await;
    let v: Value = serde_json::from_slice(&b).unwrap();
    assert_eq!(
        v["error"]["type"],
        "http://whirl.test:8080/problems/stopped"
    );
    let (_, _, b) = call(&app, "GET", &format!("/v1/jobs/{id}"), None, &host).await;
    let v: Value = serde_json::from_slice(&b).unwrap();
    assert_eq!(
        v["error"]["type"],
        "http://whirl.test:8080/problems/stopped"
    );

    // WHIRL_PUBLIC_URL wins over Host.
    let (mut config, _dir2) = self::config();
    config.public_url = Some("https://api.example.com/whirl".into());
    let app = whirl::service::app(config);
    let (_, _, b) = call(&app, "POST", "/v1/modal", Some(&bad), &host).await;
    let p: Value = serde_json::from_slice(&b).unwrap();
    assert_eq!(
        p["type"],
        "https://api.example.com/whirl/problems/invalid-model"
    );
}

/// A report runs many analyses one after another, each announcing its work when it starts; its
/// progress used to fall back at each (0.76 -> 0.47).
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_report_jobs_progress_never_decreases() {
    let (config, _dir) = config();
    let app = app(config);
    // Sweeps of 1500 speeds: a report of a few seconds, many heartbeats (runner::HEARTBEAT,
    // 0.25 s, writes a job's progress); its default sweeps finish in about one second.
    let mut input = example("rotor-a-nvd.report.json");
    input["speeds"] = json!({"start": 0, "stop": 455, "count": 1500});
    let id = submit(&app, &json!({"analysis": "report", "input": input})).await;
    let mut seen: Vec<f64> = vec![];
    let t0 = Instant::now();
    let last = loop {
        let (_, v) = json(&app, "GET", &format!("/v1/jobs/{id}"), None).await;
        let p = v["progress"].as_f64().unwrap();
        if seen.last() != Some(&p) {
            seen.push(p);
        }
        if !["queued", "running"].contains(&v["status"].as_str().unwrap()) {
            break v;
        }
        assert!(t0.elapsed() < Duration::from_secs(600), "{v}");
        tokio::time::sleep(Duration::from_millis(20)).await;
    };
    assert_eq!(last["status"], "succeeded", "{last}");
    assert!(
        seen.windows(2).all(|w| w[1] >= w[0]),
        "progress went back: {seen:?}"
    );
    // It moved in steps, not 0 then 1.
    let between = seen.iter().filter(|p| **p > 0.0 && **p < 1.0).count();
    assert!(between >= 5, "{seen:?}");
    println!(
        "report progress: {} distinct values over {:.1} s: {seen:?}",
        seen.len(),
        t0.elapsed().as_secs_f64()
    );
}
