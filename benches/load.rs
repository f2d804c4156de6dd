//! Fairness under load (a benchmark, not a test): latency of small `modal` requests alone and
//! while two long Campbell sweeps run as jobs, both jobs' progress, and how long a cancel
//! takes to free its worker. A real server on loopback.
//!
//! `cargo bench --bench load`

use std::time::{Duration, Instant};

use serde_json::{Value, json};
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpStream;
use whirl::service::server::{ServerLimits, serve};
use whirl::service::{Config, app_with_state};

fn example(name: &str) -> Value {
    let path = format!("{}/examples/{name}", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

async fn request(port: u16, method: &str, path: &str, body: &str) -> (u16, String) {
    let mut s = TcpStream::connect(("127.0.0.1", port)).await.unwrap();
    let head = format!(
        "{method} {path} HTTP/1.1\r\nhost: x\r\nconnection: close\r\ncontent-type: application/json\r\ncontent-length: {}\r\n\r\n",
        body.len()
    );
    s.write_all(head.as_bytes()).await.unwrap();
    s.write_all(body.as_bytes()).await.unwrap();
    let mut out = vec![];
    s.read_to_end(&mut out).await.unwrap();
    let text = String::from_utf8_lossy(&out).to_string();
    let status = text
        .split_whitespace()
        .nth(1)
        .and_then(|c| c.parse().ok())
        .unwrap_or(0);
    let body = text.split_once("\r\n\r\n").map_or("", |x| x.1).to_string();
    (status, body)
}

fn percentile(v: &mut [f64], p: f64) -> f64 {
    v.sort_by(f64::total_cmp);
    v[((v.len() - 1) as f64 * p).round() as usize]
}

async fn latencies(port: u16, body: &str, n: usize) -> (f64, f64, f64) {
    let mut ms = vec![];
    for _ in 0..n {
        let t0 = Instant::now();
        let (status, _) = request(port, "POST", "/v1/modal", body).await;
        assert_eq!(status, 200);
        ms.push(t0.elapsed().as_secs_f64() * 1e3);
    }
    let max = ms.iter().cloned().fold(0.0, f64::max);
    (percentile(&mut ms, 0.5), percentile(&mut ms, 0.99), max)
}

async fn job(port: u16, id: &str) -> Value {
    let (_, body) = request(port, "GET", &format!("/v1/jobs/{id}"), "").await;
    serde_json::from_str(&body).unwrap()
}

async fn running(port: u16) -> u64 {
    let (_, text) = request(port, "GET", "/metrics", "").await;
    text.lines()
        .find_map(|l| l.strip_prefix("whirl_analyses_running "))
        .and_then(|v| v.trim().parse().ok())
        .unwrap()
}

#[tokio::main(flavor = "multi_thread", worker_threads = 2)]
async fn main() {
    let listener = tokio::net::TcpListener::bind("127.0.0.1:0").await.unwrap();
    let port = listener.local_addr().unwrap().port();
    let config = Config::default();
    let limits = ServerLimits::of(&config);
    let (app, _state) = app_with_state(config);
    tokio::spawn(serve(
        listener,
        app,
        limits,
        std::future::pending(),
        Duration::from_secs(1),
    ));

    let small = [
        ("jeffcott NVD", example("jeffcott-nvd.modal.json")),
        (
            "example 1 NVD (32 states)",
            example("example1-nvd.modal.json"),
        ),
        (
            "compressor NVD (250 states)",
            example("compressor-nvd.modal.json"),
        ),
    ];
    println!(
        "cores: {}",
        std::thread::available_parallelism().map_or(0, |n| n.get())
    );
    println!("small modal requests, alone (ms): p50, p99, max of 60");
    for (name, body) in &small {
        let (p50, p99, max) = latencies(port, &body.to_string(), 60).await;
        println!("  {name:<30} {p50:8.1} {p99:8.1} {max:8.1}");
    }

    let mut long = example("compressor-hysteretic.campbell.json");
    long["rotor"].as_object_mut().unwrap().remove("reduction");
    long["damping"] = json!({"model": "viscous"});
    long["speeds"] = json!({"start": 0.0, "stop": 1500.0, "count": 1500});
    long["modal_reduction"] = json!(false);
    let submit = json!({"analysis": "campbell", "input": long}).to_string();
    let mut ids = vec![];
    for _ in 0..2 {
        let (status, body) = request(port, "POST", "/v1/jobs", &submit).await;
        assert_eq!(status, 202, "{body}");
        let v: Value = serde_json::from_str(&body).unwrap();
        ids.push(v["id"].as_str().unwrap().to_string());
    }
    tokio::time::sleep(Duration::from_millis(500)).await;
    println!("the same during two long sweeps (jobs, 1500 speeds of a 404-state model each):");
    for (name, body) in &small {
        let (p50, p99, max) = latencies(port, &body.to_string(), 60).await;
        println!("  {name:<30} {p50:8.1} {p99:8.1} {max:8.1}");
    }
    for id in &ids {
        let v = job(port, id).await;
        println!(
            "  job {}: {} progress {:.3}",
            &id[..8],
            v["status"],
            v["progress"]
        );
    }
    let before = running(port).await;
    let t0 = Instant::now();
    let (status, body) = request(port, "DELETE", &format!("/v1/jobs/{}", ids[0]), "").await;
    let recorded = t0.elapsed();
    assert_eq!(status, 200, "{body}");
    while running(port).await >= before {
        tokio::time::sleep(Duration::from_millis(5)).await;
    }
    println!(
        "cancel under load: recorded in {:.1} ms, worker freed in {:.1} ms",
        recorded.as_secs_f64() * 1e3,
        t0.elapsed().as_secs_f64() * 1e3
    );
    let _ = request(port, "DELETE", &format!("/v1/jobs/{}", ids[1]), "").await;
}
