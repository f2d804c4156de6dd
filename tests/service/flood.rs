//! Floods and slow readers (issue 28): connections that never send their headers do not starve
//! the probes, one client cannot take every connection, an answer waiting for a slow reader
//! holds its size of the memory budget until it is sent.
//! A real server on loopback, every wait bounded.

use crate::common;
use std::time::{Duration, Instant};

use common::server::start;
use serde_json::{Value, json};
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::{TcpSocket, TcpStream};
use whirl::service::Config;
use whirl::service::server::PROBE_CONNECTIONS;

/// One request on a new connection from `from` (a loopback address), the whole answer.
async fn request_from(
    from: [u8; 4],
    addr: std::net::SocketAddr,
    method: &str,
    path: &str,
    body: Option<&Value>,
) -> (u16, String) {
    let sock = TcpSocket::new_v4().unwrap();
    sock.bind((std::net::Ipv4Addr::from(from), 0).into())
        .unwrap();
    let mut s = sock.connect(addr).await.unwrap();
    let body = body.map(|b| b.to_string()).unwrap_or_default();
    let head = format!(
        "{method} {path} HTTP/1.1\r\nhost: x\r\nconnection: close\r\ncontent-type: application/json\r\ncontent-length: {}\r\n\r\n",
        body.len()
    );
    let mut out = vec![];
    let io = async {
        s.write_all(head.as_bytes()).await?;
        s.write_all(body.as_bytes()).await?;
        s.read_to_end(&mut out).await
    };
    let _ = tokio::time::timeout(Duration::from_secs(30), io).await;
    let text = String::from_utf8_lossy(&out).to_string();
    let status = text
        .split_whitespace()
        .nth(1)
        .and_then(|c| c.parse().ok())
        .unwrap_or(0);
    (status, text)
}

async fn request(addr: std::net::SocketAddr, method: &str, path: &str) -> u16 {
    request_from([127, 0, 0, 1], addr, method, path, None)
        .await
        .0
}

fn example(name: &str) -> Value {
    let path = format!("{}/examples/{name}", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// Connections that send nothing, from `from`.
async fn idle(addr: std::net::SocketAddr, n: usize, from: [u8; 4]) -> Vec<TcpStream> {
    let mut held = vec![];
    for _ in 0..n {
        let sock = TcpSocket::new_v4().unwrap();
        sock.bind((std::net::Ipv4Addr::from(from), 0).into())
            .unwrap();
        held.push(sock.connect(addr).await.unwrap());
    }
    // Accepted in order: give the server a moment to take them all.
    tokio::time::sleep(Duration::from_millis(200)).await;
    held
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_flood_of_silent_connections_does_not_starve_the_probes() {
    let srv = start(Config {
        max_connections: 8,
        header_timeout: Duration::from_secs(30),
        ..Config::default()
    })
    .await;
    // Every connection taken, and the probes' reserve too: 40 that never send a header.
    let _flood = idle(srv.addr, 8 + PROBE_CONNECTIONS + 16, [127, 0, 0, 1]).await;
    // The reserve's silent connections are dropped after a second; then every probe answers.
    tokio::time::sleep(Duration::from_millis(1200)).await;
    let (mut ok, mut probes) = (0, 0);
    let t0 = Instant::now();
    while t0.elapsed() < Duration::from_secs(2) {
        for path in ["/healthz", "/readyz"] {
            probes += 1;
            if request(srv.addr, "GET", path).await == 200 {
                ok += 1;
            }
        }
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
    eprintln!("probes answered 200 during the flood: {ok} of {probes}");
    assert_eq!(ok, probes, "{ok} of {probes} probes answered");
    // Work is refused on a reserved connection, with Retry-After.
    let modal = example("jeffcott-nvd.modal.json");
    let (status, text) =
        request_from([127, 0, 0, 1], srv.addr, "POST", "/v1/modal", Some(&modal)).await;
    assert_eq!(status, 503, "{text}");
    assert!(text.contains("retry-after"), "{text}");
    assert!(text.contains("application/problem+json"), "{text}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn one_client_cannot_take_every_connection() {
    let srv = start(Config {
        max_connections: 64,
        max_connections_per_client: 4,
        header_timeout: Duration::from_secs(30),
        ..Config::default()
    })
    .await;
    let _held = idle(srv.addr, 4, [127, 0, 0, 1]).await;
    let modal = example("jeffcott-nvd.modal.json");
    // Its fifth connection gets the probes' reserve only; another client is served.
    let (status, _) =
        request_from([127, 0, 0, 1], srv.addr, "POST", "/v1/modal", Some(&modal)).await;
    assert_eq!(status, 503);
    assert_eq!(request(srv.addr, "GET", "/healthz").await, 200);
    let (status, text) =
        request_from([127, 0, 0, 2], srv.addr, "POST", "/v1/modal", Some(&modal)).await;
    assert_eq!(status, 200, "{text:.300}");
    // The setting.
    let c = Config::from_lookup(|k| (k == "WHIRL_MAX_CONNECTIONS_PER_CLIENT").then(|| "3".into()))
        .unwrap();
    assert_eq!(c.max_connections_per_client, 3);
}

/// A time response of about 9 MB of JSON.
fn large_answer() -> String {
    let mut body = example("example1-shock-nvd.time-response.json");
    body["duration"] = json!(2.0);
    body["output_interval"] = json!(1e-5);
    body["nodes"] = json!([1]);
    body.to_string()
}

/// Sends a request for the large answer (on a socket with a small receive buffer if `small`).
async fn ask_large(addr: std::net::SocketAddr, small: bool) -> TcpStream {
    let body = large_answer();
    let sock = TcpSocket::new_v4().unwrap();
    if small {
        sock.set_recv_buffer_size(4096).unwrap();
    }
    let mut s = sock.connect(addr).await.unwrap();
    let head = format!(
        "POST /v1/time-response HTTP/1.1\r\nhost: x\r\nconnection: close\r\ncontent-type: application/json\r\ncontent-length: {}\r\n\r\n",
        body.len()
    );
    s.write_all(head.as_bytes()).await.unwrap();
    s.write_all(body.as_bytes()).await.unwrap();
    s
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_answer_holds_its_memory_until_a_slow_reader_has_it() {
    let srv = start(Config {
        write_timeout: Duration::from_secs(60),
        ..Config::default()
    })
    .await;
    let mut s = ask_large(srv.addr, true).await;
    // The analysis runs, the answer waits for the client: its size stays in the budget.
    let t0 = Instant::now();
    let mut held = 0;
    while t0.elapsed() < Duration::from_secs(30) {
        held = srv.state.pool.memory_in_use();
        if held > 0 && srv.state.pool.running() == 0 {
            break;
        }
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    tokio::time::sleep(Duration::from_millis(500)).await;
    let waiting = srv.state.pool.memory_in_use();
    // Read it all.
    let mut out = vec![];
    tokio::time::timeout(Duration::from_secs(60), s.read_to_end(&mut out))
        .await
        .expect("the answer arrives")
        .unwrap();
    let text = String::from_utf8_lossy(&out[..out.len().min(4096)]).to_string();
    assert!(text.starts_with("HTTP/1.1 200"), "{text}");
    let announced: usize = text
        .lines()
        .find_map(|l| l.strip_prefix("content-length: "))
        .and_then(|v| v.trim().parse().ok())
        .expect("content-length");
    let head = text.find("\r\n\r\n").unwrap() + 4;
    assert_eq!(out.len() - head, announced);
    let mib = (announced as u64).div_ceil(1 << 20);
    eprintln!(
        "a {announced}-byte answer held {} MiB of the budget while its client did not read",
        waiting >> 20
    );
    assert!(announced > 8_000_000, "{announced}");
    assert_eq!(waiting, mib << 20, "held {held}, then {waiting}");
    // Sent: released.
    let t0 = Instant::now();
    while srv.state.pool.memory_in_use() > 0 {
        assert!(
            t0.elapsed() < Duration::from_secs(2),
            "still held after it was sent"
        );
        tokio::time::sleep(Duration::from_millis(10)).await;
    }
}
