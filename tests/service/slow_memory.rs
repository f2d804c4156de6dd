//! Slow readers against the memory budget, on the built binary as an operator runs it: with
//! `WHIRL_MEMORY_BUDGET=64M`, eight clients each ask for a 20 MB time response at once and read
//! it at 4 KB/s. Every byte held for them counts in the budget until it is sent, and a request
//! that would take the budget past its size is refused before its memory is spent, so the
//! server's resident size (`VmRSS` and `VmHWM` of `/proc/<pid>/status`) stays within 100 MB of
//! its idle size, and each client gets either its answer, as far as it has read, or a 503 with
//! `Retry-After`.

use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use serde_json::{Value, json};
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpSocket;

const CLIENTS: usize = 8;
/// How long the clients read (the server drops a reader this slow after `WHIRL_WRITE_TIMEOUT`,
/// 30 s by default: later than this).
const READING: Duration = Duration::from_secs(20);
/// The most the resident size may grow over idle, bytes.
const GROWTH: u64 = 100_000_000;

/// The built server, killed when dropped.
struct Process(Child, std::path::PathBuf);

impl Drop for Process {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
        let _ = std::fs::remove_dir_all(&self.1);
    }
}

/// `VmRSS` and `VmHWM` of a process, bytes.
fn resident(pid: u32) -> (u64, u64) {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).unwrap();
    let kb = |key: &str| -> u64 {
        let line = status.lines().find(|l| l.starts_with(key)).unwrap();
        line.split_whitespace()
            .nth(1)
            .unwrap()
            .parse::<u64>()
            .unwrap()
            * 1024
    };
    (kb("VmRSS:"), kb("VmHWM:"))
}

/// A time response of about 20 MB of JSON: 140,000 samples (1.4 s of the paper's shock every
/// 10 us) of three nodes.
fn twenty_megabytes() -> String {
    let path = format!(
        "{}/examples/example1-shock-nvd.time-response.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let mut body: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    body["duration"] = json!(1.4);
    body["output_interval"] = json!(1e-5);
    body["nodes"] = json!([1, 2, 3]);
    body.to_string()
}

/// How a client fared.
#[derive(Debug)]
enum Outcome {
    /// 200: the answer's `Content-Length`, and the bytes read of it when the client stopped
    /// (the connection still open, nothing wrong with what came).
    Reading { announced: usize, read: usize },
    /// 503 with `Retry-After`: the problem's `type`.
    Refused(String),
}

/// Asks for the answer on a socket of a small receive buffer and reads it at 4 KB/s (1 KiB
/// every 250 ms) until `until`.
async fn slow_client(port: u16, body: String, until: Instant) -> Outcome {
    let sock = TcpSocket::new_v4().unwrap();
    sock.set_recv_buffer_size(4096).unwrap();
    let mut s = sock.connect(([127, 0, 0, 1], port).into()).await.unwrap();
    let head = format!(
        "POST /v1/time-response HTTP/1.1\r\nhost: x\r\nconnection: close\r\n\
         content-type: application/json\r\ncontent-length: {}\r\n\r\n",
        body.len()
    );
    s.write_all(head.as_bytes()).await.unwrap();
    s.write_all(body.as_bytes()).await.unwrap();
    let mut got = vec![];
    let mut buf = vec![0u8; 1024];
    // The head first (a refusal is short: read it whole).
    let end = loop {
        let n = tokio::time::timeout_at(until.into(), s.read(&mut buf))
            .await
            .expect("the answer or a refusal before the clients stop")
            .unwrap();
        got.extend_from_slice(&buf[..n]);
        if let Some(k) = got.windows(4).position(|w| w == b"\r\n\r\n") {
            break k + 4;
        }
        assert!(n > 0, "the connection ended before the head");
    };
    let head = String::from_utf8_lossy(&got[..end]).to_ascii_lowercase();
    let field = |name: &str| {
        head.lines()
            .find_map(|l| l.strip_prefix(name))
            .map(|v| v.trim().to_string())
    };
    if head.starts_with("http/1.1 503") {
        assert!(field("retry-after:").is_some(), "{head}");
        let mut rest = got[end..].to_vec();
        s.read_to_end(&mut rest).await.unwrap();
        let problem: Value = serde_json::from_slice(&rest).unwrap();
        return Outcome::Refused(problem["type"].as_str().unwrap().to_string());
    }
    assert!(head.starts_with("http/1.1 200"), "{head}");
    let announced: usize = field("content-length:").unwrap().parse().unwrap();
    let mut read = got.len() - end;
    while Instant::now() < until {
        tokio::time::sleep(Duration::from_millis(250)).await;
        let n = s.read(&mut buf).await.expect("no reset while reading");
        assert!(n > 0, "the answer ended after {read} of {announced} bytes");
        read += n;
    }
    Outcome::Reading { announced, read }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn eight_slow_readers_of_20_mb_keep_the_server_within_100_mb_of_idle() {
    let port = std::net::TcpListener::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port();
    let data = std::env::temp_dir().join(format!("whirl-slow-memory-{port}"));
    let child = Command::new(env!("CARGO_BIN_EXE_whirl"))
        .env("HOST", "127.0.0.1")
        .env("PORT", port.to_string())
        .env("WHIRL_DATA_DIR", &data)
        .env("WHIRL_MEMORY_BUDGET", "64M")
        .env("RUST_LOG", "warn")
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let server = Process(child, data);
    let pid = server.0.id();
    let t0 = Instant::now();
    while tokio::net::TcpStream::connect(("127.0.0.1", port))
        .await
        .is_err()
    {
        assert!(t0.elapsed() < Duration::from_secs(10), "did not start");
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
    tokio::time::sleep(Duration::from_millis(500)).await;
    let (idle, _) = resident(pid);

    let body = twenty_megabytes();
    let until = Instant::now() + READING;
    let clients: Vec<_> = (0..CLIENTS)
        .map(|_| tokio::spawn(slow_client(port, body.clone(), until)))
        .collect();
    let mut peak = idle;
    while clients.iter().any(|c| !c.is_finished()) {
        peak = peak.max(resident(pid).0);
        tokio::time::sleep(Duration::from_millis(100)).await;
    }
    let (last, hwm) = resident(pid);
    // A client's failure is reported after the sizes (a panic's message in place of its outcome).
    let mut outcomes = vec![];
    for c in clients {
        outcomes.push(c.await.map_err(|e| {
            let p = e.into_panic();
            p.downcast_ref::<String>()
                .cloned()
                .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default()
        }));
    }
    let mb = |b: u64| b as f64 / 1e6;
    eprintln!(
        "{CLIENTS} readers at 4 KB/s, WHIRL_MEMORY_BUDGET=64M: idle {:.1} MB, sampled peak \
         {:.1} MB (+{:.1}), VmHWM {:.1} MB (+{:.1}), at the end {:.1} MB; {outcomes:?}",
        mb(idle),
        mb(peak),
        mb(peak - idle),
        mb(hwm),
        mb(hwm.saturating_sub(idle)),
        mb(last)
    );
    assert!(
        peak - idle <= GROWTH,
        "sampled peak +{:.1} MB",
        mb(peak - idle)
    );
    assert!(
        hwm.saturating_sub(idle) <= GROWTH,
        "VmHWM +{:.1} MB",
        mb(hwm - idle)
    );
    let mut reading = 0;
    for o in &outcomes {
        let o = o.as_ref().expect("every client read or was refused");
        match o {
            Outcome::Reading { announced, read } => {
                reading += 1;
                assert!((18_000_000..22_000_000).contains(announced), "{o:?}");
                assert!(*read > 0 && read < announced, "{o:?}");
            }
            Outcome::Refused(kind) => assert!(kind.ends_with("/problems/busy"), "{kind}"),
        }
    }
    assert!(reading >= 1, "no answer was served: {outcomes:?}");
}
