//! A synchronous report that cannot finish within the time limit is refused up front, with a
//! pointer to /v1/jobs, once a report of no more estimated work ran past the limit on this
//! server: not after another minute of work. A report that finished sets no pace: a smaller
//! one after it still runs.

use std::time::{Duration, Instant};

use axum::body::Body;
use axum::http::{Request, header};
use http_body_util::BodyExt;
use serde_json::{Value, json};
use tower::ServiceExt;
use whirl::service::{Config, app};

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_report_past_the_limit_is_refused_before_it_starts() {
    let dir = tempfile::tempdir().unwrap();
    let app = app(Config {
        data_dir: dir.path().to_path_buf(),
        request_time_limit: Duration::from_secs(1),
        ..Config::default()
    });
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/compressor-nvd.campbell.json"
    ))
    .unwrap();
    let v: Value = serde_json::from_str(&text).unwrap();
    // The 100-element compressor under four damping models: far more than 1 s.
    let body = json!({"rotor": v["rotor"], "damping": {"model": "nonviscous"},
                      "operating_range": {"min": 700.0, "max": 1000.0}});
    let post = |app: axum::Router| {
        let body = body.clone();
        async move {
            let req = Request::builder()
                .method("POST")
                .uri("/v1/report")
                .header(header::CONTENT_TYPE, "application/json")
                .body(Body::from(body.to_string()))
                .unwrap();
            let t = Instant::now();
            let resp = app.oneshot(req).await.unwrap();
            let status = resp.status().as_u16();
            let bytes = resp.into_body().collect().await.unwrap().to_bytes();
            let v: Value = serde_json::from_slice(&bytes).unwrap_or(Value::Null);
            (status, v, t.elapsed())
        }
    };
    // Nothing measured yet: it runs, and is stopped at the limit (503).
    let (status, first, took) = post(app.clone()).await;
    assert_eq!(status, 503, "{first}");
    assert!(took >= Duration::from_secs(1));
    // The same report again: refused at once (422), saying why and where to go.
    let (status, second, took) = post(app.clone()).await;
    println!("refused in {took:?}: {}", second["detail"]);
    assert_eq!(status, 422, "{second}");
    assert!(took < Duration::from_millis(200), "{took:?}");
    let detail = second["detail"].as_str().unwrap();
    assert!(detail.contains("POST /v1/jobs"), "{detail}");
    assert!(detail.contains("WHIRL_REQUEST_TIME_LIMIT"), "{detail}");
    assert!(
        detail.contains("ran past the synchronous limit of 1 s"),
        "{detail}"
    );
    // A report of less estimated work still runs: a 10-element shaft, one model.
    let small = json!({"rotor": {"type": "beam",
        "materials": {"steel": {"young_modulus": 2.11e11, "density": 7810.0, "poisson_ratio": 0.3,
                                "loss_factor": 0.0}},
        "shaft": [{"length": 1.0, "outer_diameter": 0.05, "inner_diameter": 0.0,
                   "material": "steel", "elements": 10}],
        "disks": [{"node": 5, "mass": 10.0, "polar_inertia": 0.05, "transverse_inertia": 0.025}],
        "supports": [{"node": 0, "stiffness": 1e7, "damping": 1e3},
                     {"node": 10, "stiffness": 1e7, "damping": 1e3}]},
        "damping": {"model": "viscous"}, "models": [{"model": "viscous"}],
        "operating_range": {"min": 300.0, "max": 400.0}});
    let req = Request::builder()
        .method("POST")
        .uri("/v1/report")
        .header(header::CONTENT_TYPE, "application/json")
        .body(Body::from(small.to_string()))
        .unwrap();
    let resp = app.clone().oneshot(req).await.unwrap();
    let status = resp.status().as_u16();
    let bytes = resp.into_body().collect().await.unwrap().to_bytes();
    assert_eq!(status, 200, "{}", String::from_utf8_lossy(&bytes));
}
