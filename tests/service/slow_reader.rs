//! Slow readers on a real server (issue 28, item 1): a client that reads a 10.5 MB synchronous
//! answer at 4 KB/s is reset about one `WHIRL_WRITE_TIMEOUT` after its answer started, having
//! received a few kB of it, and the answer's share of the memory budget is released; a client
//! that stops reading is dropped after the timeout; a client reading at full speed meanwhile
//! gets every byte.
//!
//! On loopback the kernel takes megabytes of an answer into the socket's buffer at once, so
//! these also check that what went out before the first wait does not count for the client,
//! and that a dropped connection is reset: closed plainly, its socket would go on trickling
//! those megabytes to the client for minutes.

use crate::common;
use std::time::{Duration, Instant};

use common::server::{Server, start};
use serde_json::{Value, json};
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::{TcpSocket, TcpStream};
use whirl::service::Config;

const WRITE_TIMEOUT: Duration = Duration::from_secs(2);

/// A time response of 10.5 MB of JSON (2 s of the paper's shock, one node, every 10 us).
fn large_answer() -> String {
    let path = format!(
        "{}/examples/example1-shock-nvd.time-response.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let mut body: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    body["duration"] = json!(2.0);
    body["output_interval"] = json!(1e-5);
    body["nodes"] = json!([1]);
    body.to_string()
}

/// Sends the request for the large answer, on a socket with a receive buffer of 4 KiB if
/// `small` (the kernel doubles it).
async fn ask_large(addr: std::net::SocketAddr, small: bool) -> TcpStream {
    let body = large_answer();
    let sock = TcpSocket::new_v4().unwrap();
    if small {
        sock.set_recv_buffer_size(4096).unwrap();
    }
    let mut s = sock.connect(addr).await.unwrap();
    let head = format!(
        "POST /v1/time-response HTTP/1.1\r\nhost: x\r\nconnection: close\r\n\
         content-type: application/json\r\ncontent-length: {}\r\n\r\n",
        body.len()
    );
    s.write_all(head.as_bytes()).await.unwrap();
    s.write_all(body.as_bytes()).await.unwrap();
    s
}

/// How a slow client's reading ended.
#[derive(Debug)]
struct Slow {
    /// Bytes received.
    bytes: usize,
    /// From the first byte of the answer to the end of the connection.
    lasted: Duration,
    /// The connection was reset (not closed after the whole answer).
    reset: bool,
    /// `Content-Length` of the answer.
    announced: usize,
}

/// Waits for the answer's first bytes, then reads `take` bytes every `every` (nothing more if
/// `take` is 0, until `limit`), until the connection ends or `limit` after the first byte.
async fn read_slowly(mut s: TcpStream, take: usize, every: Duration, limit: Duration) -> Slow {
    let mut head = vec![0u8; 1024];
    let n = tokio::time::timeout(Duration::from_secs(30), s.read(&mut head))
        .await
        .expect("the answer starts within 30 s")
        .unwrap();
    let first = Instant::now();
    let text = String::from_utf8_lossy(&head[..n]).to_string();
    assert!(text.starts_with("HTTP/1.1 200"), "{text}");
    let announced = text
        .lines()
        .find_map(|l| l.strip_prefix("content-length: "))
        .and_then(|v| v.trim().parse().ok())
        .expect("content-length in the first kB");
    let mut bytes = n;
    let mut buf = vec![0u8; take.max(1)];
    let reset = loop {
        if first.elapsed() > limit {
            break false;
        }
        tokio::time::sleep(every).await;
        if take == 0 {
            continue;
        }
        match s.read(&mut buf).await {
            Ok(0) => break false,
            Ok(n) => bytes += n,
            Err(e) => {
                assert_eq!(e.kind(), std::io::ErrorKind::ConnectionReset, "{e}");
                break true;
            }
        }
    };
    Slow {
        bytes,
        lasted: first.elapsed(),
        reset,
        announced,
    }
}

/// The whole answer at full speed: its length and `Content-Length`.
async fn read_fast(mut s: TcpStream) -> (usize, usize) {
    let mut out = vec![];
    tokio::time::timeout(Duration::from_secs(60), s.read_to_end(&mut out))
        .await
        .expect("the answer within 60 s")
        .unwrap();
    let text = String::from_utf8_lossy(&out[..out.len().min(4096)]).to_string();
    assert!(text.starts_with("HTTP/1.1 200"), "{text}");
    let announced = text
        .lines()
        .find_map(|l| l.strip_prefix("content-length: "))
        .and_then(|v| v.trim().parse().ok())
        .expect("content-length");
    let head = text.find("\r\n\r\n").unwrap() + 4;
    (out.len() - head, announced)
}

/// Waits until no answer holds memory of the budget; how long that took.
async fn released(srv: &Server, limit: Duration) -> Duration {
    let t0 = Instant::now();
    while srv.state.pool.memory_in_use() > 0 {
        assert!(
            t0.elapsed() < limit,
            "{} bytes of the budget still held after {limit:?}",
            srv.state.pool.memory_in_use()
        );
        tokio::time::sleep(Duration::from_millis(10)).await;
    }
    t0.elapsed()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_trickling_reader_is_reset_within_a_write_timeout_and_a_fast_one_gets_it_all() {
    let srv = start(Config {
        write_timeout: WRITE_TIMEOUT,
        ..Config::default()
    })
    .await;
    let slow = ask_large(srv.addr, true).await;
    // 1 KiB every 250 ms: 4 KB/s, always some progress, an eighth of the minimum.
    let slow = tokio::spawn(read_slowly(
        slow,
        1024,
        Duration::from_millis(250),
        WRITE_TIMEOUT * 5,
    ));
    // Meanwhile, once the slow answer is going out, a client that reads at full speed.
    let t0 = Instant::now();
    while srv.state.pool.memory_in_use() == 0 || srv.state.pool.running() > 0 {
        assert!(t0.elapsed() < Duration::from_secs(30), "no answer");
        tokio::time::sleep(Duration::from_millis(10)).await;
    }
    let addr = srv.addr;
    let fast = tokio::spawn(async move { read_fast(ask_large(addr, false).await).await });
    let slow = slow.await.unwrap();
    let (got, announced) = fast.await.unwrap();
    eprintln!(
        "trickling reader: reset {:?} after its answer started, {} of {} bytes received; \
         the fast reader got {got} of {announced}",
        slow.lasted, slow.bytes, slow.announced
    );
    assert!(slow.reset, "{slow:?}");
    // Dropped when a timeout of waiting ends (the kernel wakes the server only when a third of
    // its megabytes of socket buffer is free, so not one write gets through), then the client
    // reads what its 8 KiB of buffer held and sees the reset: a second more at 4 KB/s.
    assert!(
        slow.lasted >= WRITE_TIMEOUT && slow.lasted < WRITE_TIMEOUT + Duration::from_secs(3),
        "{slow:?}"
    );
    assert!(slow.bytes < 32 << 10, "{slow:?}");
    assert!(slow.announced > 8_000_000, "{slow:?}");
    assert_eq!(got, announced, "the fast reader gets every byte");
    assert_eq!(announced, slow.announced);
    let t = released(&srv, Duration::from_secs(2)).await;
    eprintln!("the budget is free {t:?} later");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_reader_that_stops_is_dropped_after_the_timeout_and_its_answer_released() {
    let srv = start(Config {
        write_timeout: WRITE_TIMEOUT,
        ..Config::default()
    })
    .await;
    let mut s = ask_large(srv.addr, true).await;
    // The answer goes out when the analysis ends: from then, its size is held in the budget.
    let t0 = Instant::now();
    while srv.state.pool.memory_in_use() == 0 || srv.state.pool.running() > 0 {
        assert!(t0.elapsed() < Duration::from_secs(30), "no answer");
        tokio::time::sleep(Duration::from_millis(5)).await;
    }
    let held = srv.state.pool.memory_in_use();
    // The client reads nothing.
    let t = released(&srv, WRITE_TIMEOUT * 3).await;
    eprintln!(
        "a reader that stopped: its answer's {} MiB released {t:?} after it started",
        held >> 20
    );
    assert!(held >= 8 << 20, "{held}");
    assert!(
        t >= WRITE_TIMEOUT - Duration::from_millis(100)
            && t < WRITE_TIMEOUT + Duration::from_millis(1000),
        "{t:?}"
    );
    // The client then finds what its buffer held, and a reset: nothing more of the 10.5 MB.
    let mut got = 0;
    let mut buf = vec![0u8; 64 << 10];
    let end = loop {
        match tokio::time::timeout(Duration::from_secs(5), s.read(&mut buf)).await {
            Err(_) => panic!("neither data nor an end within 5 s after {got} bytes"),
            Ok(Ok(0)) => break None,
            Ok(Ok(n)) => got += n,
            Ok(Err(e)) => break Some(e.kind()),
        }
    };
    eprintln!("then it read {got} bytes and {end:?}");
    assert_eq!(end, Some(std::io::ErrorKind::ConnectionReset));
    assert!(got < 32 << 10, "{got} bytes after the drop");
}
