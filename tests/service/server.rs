//! What no client can do to the server: hold connections, trickle headers or bodies, stop
//! reading, walk away from an analysis, or outlast a shutdown. A real server on loopback,
//! short timeouts, every wait bounded.

use crate::common;
use std::time::{Duration, Instant};

use common::server::start;
use serde_json::{Value, json};
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpStream;
use whirl::service::Config;

fn quick() -> Config {
    Config {
        header_timeout: Duration::from_millis(400),
        body_timeout: Duration::from_millis(400),
        write_timeout: Duration::from_millis(400),
        ..Config::default()
    }
}

/// Reads until the peer closes or `limit` passes; `None` if it never closed.
async fn read_until_closed(s: &mut TcpStream, limit: Duration) -> Option<Vec<u8>> {
    let mut out = vec![];
    let mut buf = [0u8; 65536];
    let deadline = Instant::now() + limit;
    loop {
        let left = deadline.checked_duration_since(Instant::now())?;
        match tokio::time::timeout(left, s.read(&mut buf)).await {
            Err(_) => return None,
            Ok(Ok(0)) | Ok(Err(_)) => return Some(out),
            Ok(Ok(n)) => out.extend_from_slice(&buf[..n]),
        }
    }
}

/// One request on a new connection (`Connection: close`), the whole answer.
async fn request(
    addr: std::net::SocketAddr,
    method: &str,
    path: &str,
    body: Option<&Value>,
) -> (u16, String) {
    let mut s = TcpStream::connect(addr).await.unwrap();
    let body = body.map(|b| b.to_string()).unwrap_or_default();
    let head = format!(
        "{method} {path} HTTP/1.1\r\nhost: x\r\nconnection: close\r\ncontent-type: application/json\r\ncontent-length: {}\r\n\r\n",
        body.len()
    );
    s.write_all(head.as_bytes()).await.unwrap();
    s.write_all(body.as_bytes()).await.unwrap();
    let out = read_until_closed(&mut s, Duration::from_secs(60))
        .await
        .expect("answered");
    let text = String::from_utf8_lossy(&out).to_string();
    let status = text
        .split_whitespace()
        .nth(1)
        .and_then(|c| c.parse().ok())
        .unwrap_or(0);
    (status, text)
}

fn example(name: &str) -> Value {
    let path = format!("{}/examples/{name}", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// A Campbell sweep of many seconds (full compressor, viscous, 1500 speeds, no reduction).
fn long_sweep() -> Value {
    let mut input = example("compressor-hysteretic.campbell.json");
    input["rotor"].as_object_mut().unwrap().remove("reduction");
    input["damping"] = json!({"model": "viscous"});
    input["speeds"] = json!({"start": 0.0, "stop": 1500.0, "count": 1500});
    input["modal_reduction"] = json!(false);
    input
}

async fn analyses_running(addr: std::net::SocketAddr) -> u64 {
    let (_, text) = request(addr, "GET", "/metrics", None).await;
    text.lines()
        .find_map(|l| l.strip_prefix("whirl_analyses_running "))
        .and_then(|v| v.trim().parse().ok())
        .unwrap()
}

async fn wait_idle(addr: std::net::SocketAddr, limit: Duration) -> Duration {
    let t0 = Instant::now();
    while analyses_running(addr).await > 0 {
        assert!(
            t0.elapsed() < limit,
            "the analysis still runs after {limit:?}"
        );
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    t0.elapsed()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn trickled_headers_and_idle_keep_alives_are_dropped() {
    let srv = start(quick()).await;
    // Half a request line, never finished.
    let mut s = TcpStream::connect(srv.addr).await.unwrap();
    s.write_all(b"GET /healthz HTTP/1.1\r\nhost: x\r\n")
        .await
        .unwrap();
    let t0 = Instant::now();
    assert!(
        read_until_closed(&mut s, Duration::from_secs(3))
            .await
            .is_some()
    );
    assert!(t0.elapsed() < Duration::from_secs(2), "{:?}", t0.elapsed());
    // A kept-alive connection that goes quiet after its answer.
    let mut s = TcpStream::connect(srv.addr).await.unwrap();
    s.write_all(b"GET /healthz HTTP/1.1\r\nhost: x\r\n\r\n")
        .await
        .unwrap();
    let out = read_until_closed(&mut s, Duration::from_secs(3))
        .await
        .expect("closed when idle");
    assert!(String::from_utf8_lossy(&out).starts_with("HTTP/1.1 200"));
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn connections_beyond_the_limit_get_503_and_health_answers_again() {
    let srv = start(Config {
        max_connections: 8,
        header_timeout: Duration::from_secs(30),
        ..Config::default()
    })
    .await;
    let mut held = vec![];
    for _ in 0..8 {
        held.push(TcpStream::connect(srv.addr).await.unwrap());
    }
    // Accepted in order: give the server a moment to take all eight.
    tokio::time::sleep(Duration::from_millis(200)).await;
    let (status, text) = request(srv.addr, "GET", "/metrics", None).await;
    assert_eq!(status, 503, "{text}");
    assert!(text.contains("retry-after"), "{text}");
    // The probes have connections of their own (issue 28).
    assert_eq!(request(srv.addr, "GET", "/healthz", None).await.0, 200);
    drop(held);
    let t0 = Instant::now();
    loop {
        if request(srv.addr, "GET", "/metrics", None).await.0 == 200 {
            break;
        }
        assert!(t0.elapsed() < Duration::from_secs(2));
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_announced_oversize_body_is_413_before_it_is_sent() {
    let srv = start(quick()).await;
    let mut s = TcpStream::connect(srv.addr).await.unwrap();
    s.write_all(
        b"POST /v1/modal HTTP/1.1\r\nhost: x\r\ncontent-type: application/json\r\ncontent-length: 40000000\r\n\r\n{\"rotor\":",
    )
    .await
    .unwrap();
    let t0 = Instant::now();
    let out = read_until_closed(&mut s, Duration::from_secs(3))
        .await
        .expect("answered and closed");
    let text = String::from_utf8_lossy(&out);
    assert!(text.starts_with("HTTP/1.1 413"), "{text}");
    assert!(text.contains("application/problem+json"), "{text}");
    assert!(t0.elapsed() < Duration::from_secs(1));
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_body_that_does_not_arrive_is_408() {
    let srv = start(quick()).await;
    let mut s = TcpStream::connect(srv.addr).await.unwrap();
    s.write_all(
        b"POST /v1/modal HTTP/1.1\r\nhost: x\r\ncontent-type: application/json\r\ncontent-length: 1000\r\n\r\n{\"rotor\": {",
    )
    .await
    .unwrap();
    let out = read_until_closed(&mut s, Duration::from_secs(3))
        .await
        .expect("answered");
    let text = String::from_utf8_lossy(&out);
    assert!(text.starts_with("HTTP/1.1 408"), "{text}");
    assert!(text.contains("WHIRL_BODY_TIMEOUT"), "{text}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_client_that_stops_reading_a_large_answer_is_dropped() {
    let srv = start(quick()).await;
    // About 9 MB of JSON: far more than the socket buffers hold.
    let mut body = example("example1-shock-nvd.time-response.json");
    body["duration"] = json!(2.0);
    body["output_interval"] = json!(1e-5);
    body["nodes"] = json!([1]);
    let body = body.to_string();
    let sock = tokio::net::TcpSocket::new_v4().unwrap();
    sock.set_recv_buffer_size(4096).unwrap();
    let mut s = sock.connect(srv.addr).await.unwrap();
    let head = format!(
        "POST /v1/time-response HTTP/1.1\r\nhost: x\r\ncontent-type: application/json\r\ncontent-length: {}\r\n\r\n",
        body.len()
    );
    s.write_all(head.as_bytes()).await.unwrap();
    s.write_all(body.as_bytes()).await.unwrap();
    // Do not read for a while: the server's writes stall, then it gives up.
    tokio::time::sleep(Duration::from_secs(4)).await;
    let out = read_until_closed(&mut s, Duration::from_secs(10))
        .await
        .expect("the server closed");
    let text = String::from_utf8_lossy(&out[..out.len().min(4096)]).to_string();
    assert!(text.starts_with("HTTP/1.1 200"), "{text}");
    let announced: usize = text
        .lines()
        .find_map(|l| l.strip_prefix("content-length: "))
        .and_then(|v| v.trim().parse().ok())
        .expect("content-length");
    assert!(
        out.len() < announced,
        "got {} of {announced} bytes",
        out.len()
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_client_that_goes_away_cancels_its_analysis() {
    let srv = start(Config::default()).await;
    let body = long_sweep().to_string();
    let mut s = TcpStream::connect(srv.addr).await.unwrap();
    let head = format!(
        "POST /v1/campbell HTTP/1.1\r\nhost: x\r\ncontent-type: application/json\r\ncontent-length: {}\r\n\r\n",
        body.len()
    );
    s.write_all(head.as_bytes()).await.unwrap();
    s.write_all(body.as_bytes()).await.unwrap();
    let t0 = Instant::now();
    while analyses_running(srv.addr).await == 0 {
        assert!(t0.elapsed() < Duration::from_secs(10));
        tokio::time::sleep(Duration::from_millis(10)).await;
    }
    drop(s);
    // The sweep takes tens of seconds; cancelled, it stops at its next speed.
    let stopped = wait_idle(srv.addr, Duration::from_secs(2)).await;
    println!("stopped {stopped:?} after the client left");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_synchronous_analysis_past_its_time_limit_is_503_and_stops() {
    let srv = start(Config {
        request_time_limit: Duration::from_millis(500),
        ..Config::default()
    })
    .await;
    let t0 = Instant::now();
    let (status, text) = request(srv.addr, "POST", "/v1/campbell", Some(&long_sweep())).await;
    assert_eq!(status, 503, "{text}");
    assert!(t0.elapsed() < Duration::from_secs(3));
    assert!(text.contains("/v1/jobs"), "suggests a job: {text}");
    assert!(text.contains("retry-after"), "{text}");
    wait_idle(srv.addr, Duration::from_secs(2)).await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn metric_labels_are_a_fixed_set_and_404s_are_counted() {
    let srv = start(quick()).await;
    for i in 0..50 {
        let mut s = TcpStream::connect(srv.addr).await.unwrap();
        let line = format!("INVENTED{i} /healthz HTTP/1.1\r\nhost: x\r\nconnection: close\r\n\r\n");
        s.write_all(line.as_bytes()).await.unwrap();
        read_until_closed(&mut s, Duration::from_secs(3)).await;
    }
    assert_eq!(request(srv.addr, "GET", "/no/such/path", None).await.0, 404);
    let (_, text) = request(srv.addr, "GET", "/metrics", None).await;
    assert!(!text.contains("INVENTED"), "method names leak into labels");
    assert!(
        text.contains(r#"method="other",route="/healthz",status="405""#),
        "{text}"
    );
    assert!(
        text.contains(r#"method="GET",route="unmatched",status="404"} 1"#),
        "{text}"
    );
    let _ = &srv.state;
}

/// Requests through the router itself (no socket), for headers and bodies.
async fn call(
    state_config: Config,
    method: &str,
    path: &str,
    headers: &[(&str, &str)],
    body: Option<String>,
) -> (u16, axum::http::HeaderMap, Vec<u8>) {
    use http_body_util::BodyExt;
    use tower::ServiceExt;
    let app = whirl::service::app(state_config);
    let mut req = axum::http::Request::builder().method(method).uri(path);
    for (k, v) in headers {
        req = req.header(*k, *v);
    }
    let req = req
        .body(axum::body::Body::from(body.unwrap_or_default()))
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

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn large_answers_are_compressed_as_the_client_accepts() {
    let body = example("example1-nvd.campbell.json").to_string();
    let json = [("content-type", "application/json")];
    let (_, _, plain) = call(
        Config::default(),
        "POST",
        "/v1/campbell",
        &json,
        Some(body.clone()),
    )
    .await;
    for coding in ["gzip", "br", "zstd"] {
        let (status, h, bytes) = call(
            Config::default(),
            "POST",
            "/v1/campbell",
            &[
                ("content-type", "application/json"),
                ("accept-encoding", coding),
            ],
            Some(body.clone()),
        )
        .await;
        assert_eq!(status, 200);
        assert_eq!(h["content-encoding"], coding);
        assert!(
            bytes.len() * 2 < plain.len(),
            "{coding}: {} of {}",
            bytes.len(),
            plain.len()
        );
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn methods_media_types_and_ids() {
    let c = Config::default;
    // A method the path does not answer, OPTIONS included: problem+json with Allow.
    for method in ["DELETE", "OPTIONS", "PUT"] {
        let (status, h, body) = call(c(), method, "/v1/modal", &[], None).await;
        assert_eq!(status, 405, "{method}");
        assert_eq!(h["content-type"], "application/problem+json");
        assert_eq!(h["allow"], "POST");
        let v: Value = serde_json::from_slice(&body).unwrap();
        assert_eq!(v["status"], 405);
    }
    for (method, path, allow) in [
        ("POST", "/v1/jobs/abc", "GET, HEAD, DELETE"),
        ("PUT", "/healthz", "GET, HEAD"),
    ] {
        let (status, h, _) = call(c(), method, path, &[], None).await;
        assert_eq!(status, 405, "{method} {path}");
        assert_eq!(h["allow"], allow, "{method} {path}");
    }
    // The body must be declared as JSON.
    let body = example("jeffcott-nvd.modal.json").to_string();
    for ct in [
        None,
        Some("text/plain"),
        Some("application/x-www-form-urlencoded"),
    ] {
        let headers: Vec<(&str, &str)> = ct.map(|c| ("content-type", c)).into_iter().collect();
        let (status, h, _) = call(c(), "POST", "/v1/modal", &headers, Some(body.clone())).await;
        assert_eq!(status, 415, "{ct:?}");
        assert_eq!(h["content-type"], "application/problem+json");
    }
    // A key twice is ambiguous: 422 at its path.
    let dup = r#"{"rotor": {"type": "jeffcott", "mass": 1, "mass": 2, "stiffness": 1},
                  "damping": {"model": "viscous"}}"#;
    let (status, _, body) = call(
        c(),
        "POST",
        "/v1/modal",
        &[("content-type", "application/json")],
        Some(dup.into()),
    )
    .await;
    assert_eq!(status, 422);
    let v: Value = serde_json::from_slice(&body).unwrap();
    assert_eq!(v["errors"][0]["path"], "rotor.mass", "{v}");
    // Request ids are UUIDs, different every time.
    let (_, h1, _) = call(c(), "GET", "/healthz", &[], None).await;
    let (_, h2, _) = call(c(), "GET", "/healthz", &[], None).await;
    let (a, b) = (
        h1["x-request-id"].to_str().unwrap(),
        h2["x-request-id"].to_str().unwrap(),
    );
    assert!(uuid::Uuid::parse_str(a).is_ok() && uuid::Uuid::parse_str(b).is_ok());
    assert_ne!(a, b);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn error_lists_are_capped_with_a_count_of_the_rest() {
    let speeds: Vec<f64> = (0..100_000).map(|i| -(i as f64) - 1.0).collect();
    let body = json!({"rotor": {"type": "jeffcott", "mass": 1, "stiffness": 1},
                      "damping": {"model": "viscous"}, "speeds": speeds});
    let (status, _, bytes) = call(
        Config {
            max_speeds: 200_000,
            ..Config::default()
        },
        "POST",
        "/v1/campbell",
        &[("content-type", "application/json")],
        Some(body.to_string()),
    )
    .await;
    assert_eq!(status, 422);
    let v: Value = serde_json::from_slice(&bytes).unwrap();
    let errors = v["errors"].as_array().unwrap();
    assert_eq!(errors.len(), 100);
    assert!(bytes.len() < 20_000, "{} bytes", bytes.len());
    let detail = v["detail"].as_str().unwrap();
    assert!(detail.starts_with("100000 invalid field(s)"), "{detail}");
    // Each error once.
    let paths: std::collections::HashSet<&str> =
        errors.iter().map(|e| e["path"].as_str().unwrap()).collect();
    assert_eq!(paths.len(), 100);
}
