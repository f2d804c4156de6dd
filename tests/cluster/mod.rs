//! Helpers for the tests that run the built binary: servers on loopback ports (`PORT=0`, the
//! bound port read from the log), a small blocking HTTP/1.1 client, and PostgreSQL databases of
//! their own (created and dropped per test, so tests run in parallel and again).
#![allow(dead_code)]

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};
use std::sync::{Arc, Mutex, mpsc};
use std::time::{Duration, Instant};

use serde_json::{Value, json};

/// The PostgreSQL the tests use: `WHIRL_TEST_POSTGRES`, or the machine's local server.
pub fn admin_url() -> String {
    std::env::var("WHIRL_TEST_POSTGRES")
        .unwrap_or_else(|_| "postgres://postgres@127.0.0.1:5432/test".into())
}

fn runtime() -> tokio::runtime::Runtime {
    tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .unwrap()
}

/// A PostgreSQL database of this test's own, dropped at the end.
pub struct Database {
    pub url: String,
    name: String,
}

impl Database {
    pub fn create() -> Self {
        let admin = admin_url();
        let name = format!("whirl_test_{}", uuid::Uuid::now_v7().simple());
        runtime().block_on(async {
            use sqlx::Connection;
            let mut c = sqlx::PgConnection::connect(&admin)
                .await
                .unwrap_or_else(|e| {
                    panic!(
                        "PostgreSQL is needed for this test and none answers at {admin} \
                     (set WHIRL_TEST_POSTGRES): {e}"
                    )
                });
            sqlx::query(&format!("CREATE DATABASE {name}"))
                .execute(&mut c)
                .await
                .unwrap();
        });
        let base = admin.rsplit_once('/').map_or(admin.as_str(), |(b, _)| b);
        Database {
            url: format!("{base}/{name}"),
            name,
        }
    }

    /// `(attempts, expiries, status)` of every job, by id.
    pub fn jobs(&self) -> Vec<(String, i64, i64, String)> {
        runtime().block_on(async {
            use sqlx::{Connection, Row};
            let mut c = sqlx::PgConnection::connect(&self.url).await.unwrap();
            sqlx::query("SELECT id, attempts::int8 AS a, expiries::int8 AS e, status FROM jobs")
                .fetch_all(&mut c)
                .await
                .unwrap()
                .iter()
                .map(|r| (r.get("id"), r.get("a"), r.get("e"), r.get("status")))
                .collect()
        })
    }
}

impl Drop for Database {
    fn drop(&mut self) {
        let admin = admin_url();
        let name = self.name.clone();
        runtime().block_on(async {
            use sqlx::Connection;
            if let Ok(mut c) = sqlx::PgConnection::connect(&admin).await {
                let _ = sqlx::query(&format!("DROP DATABASE IF EXISTS {name} WITH (FORCE)"))
                    .execute(&mut c)
                    .await;
            }
        });
    }
}

/// `(attempts, expiries, status)` of every job in an embedded store.
pub fn sqlite_jobs(dir: &std::path::Path) -> Vec<(String, i64, i64, String)> {
    runtime().block_on(async {
        use sqlx::{Connection, Row};
        let opts = sqlx::sqlite::SqliteConnectOptions::new()
            .filename(dir.join("whirl.sqlite"))
            .read_only(true);
        let mut c = sqlx::SqliteConnection::connect_with(&opts).await.unwrap();
        sqlx::query("SELECT id, attempts, expiries, status FROM jobs")
            .fetch_all(&mut c)
            .await
            .unwrap()
            .iter()
            .map(|r| {
                (
                    r.get("id"),
                    r.get("attempts"),
                    r.get("expiries"),
                    r.get("status"),
                )
            })
            .collect()
    })
}

/// A response: status, headers (lower-case names), body.
pub struct Reply {
    pub status: u16,
    pub headers: Vec<(String, String)>,
    pub body: Vec<u8>,
}

impl Reply {
    pub fn header(&self, name: &str) -> Option<&str> {
        self.headers
            .iter()
            .find(|(k, _)| k == name)
            .map(|(_, v)| v.as_str())
    }

    pub fn json(&self) -> Value {
        serde_json::from_slice(&self.body).unwrap_or(Value::Null)
    }
}

/// One request on a connection of its own.
pub fn request(
    port: u16,
    method: &str,
    path: &str,
    body: Option<&Value>,
    headers: &[(&str, &str)],
) -> Reply {
    let mut s = TcpStream::connect(("127.0.0.1", port)).expect("connect");
    s.set_read_timeout(Some(Duration::from_secs(60))).unwrap();
    let body = body.map(|b| b.to_string()).unwrap_or_default();
    let mut head = format!(
        "{method} {path} HTTP/1.1\r\nhost: 127.0.0.1\r\nconnection: close\r\n\
         content-type: application/json\r\ncontent-length: {}\r\n",
        body.len()
    );
    for (k, v) in headers {
        head.push_str(&format!("{k}: {v}\r\n"));
    }
    head.push_str("\r\n");
    s.write_all(head.as_bytes()).unwrap();
    s.write_all(body.as_bytes()).unwrap();
    let mut raw = vec![];
    s.read_to_end(&mut raw).unwrap();
    let split = raw
        .windows(4)
        .position(|w| w == b"\r\n\r\n")
        .expect("a response head");
    let head = String::from_utf8_lossy(&raw[..split]).to_string();
    let mut lines = head.lines();
    let status = lines
        .next()
        .and_then(|l| l.split(' ').nth(1))
        .and_then(|c| c.parse().ok())
        .expect("a status line");
    let headers: Vec<(String, String)> = lines
        .filter_map(|l| l.split_once(':'))
        .map(|(k, v)| (k.trim().to_ascii_lowercase(), v.trim().to_string()))
        .collect();
    let mut body = raw[split + 4..].to_vec();
    if headers
        .iter()
        .any(|(k, v)| k == "transfer-encoding" && v.contains("chunked"))
    {
        body = dechunk(&body);
    }
    Reply {
        status,
        headers,
        body,
    }
}

fn dechunk(mut b: &[u8]) -> Vec<u8> {
    let mut out = vec![];
    loop {
        let eol = b.windows(2).position(|w| w == b"\r\n").expect("chunk size");
        let size = usize::from_str_radix(
            String::from_utf8_lossy(&b[..eol])
                .split(';')
                .next()
                .unwrap()
                .trim(),
            16,
        )
        .unwrap();
        b = &b[eol + 2..];
        if size == 0 {
            return out;
        }
        out.extend_from_slice(&b[..size]);
        b = &b[size + 2..];
    }
}

pub fn gunzip(gz: &[u8]) -> Vec<u8> {
    let mut out = vec![];
    flate2::read::GzDecoder::new(gz)
        .read_to_end(&mut out)
        .unwrap();
    out
}

/// The built server, on a free loopback port.
pub struct Server {
    child: Child,
    pub port: u16,
    log: Arc<Mutex<String>>,
}

impl Server {
    /// Starts `whirl` with these settings (and nothing else from the environment).
    pub fn start(env: &[(&str, &str)]) -> Server {
        let mut cmd = Command::new(env!("CARGO_BIN_EXE_whirl"));
        cmd.env_clear()
            .env("PATH", std::env::var("PATH").unwrap_or_default())
            .env("HOST", "127.0.0.1")
            .env("PORT", "0")
            .env("WHIRL_LOG_FORMAT", "json")
            .env("RUST_LOG", "info")
            .env("WHIRL_SHUTDOWN_GRACE", "1")
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::piped());
        for (k, v) in env {
            cmd.env(k, v);
        }
        let mut child = cmd.spawn().expect("the whirl binary");
        let stderr = child.stderr.take().unwrap();
        let log = Arc::new(Mutex::new(String::new()));
        let (tx, rx) = mpsc::channel();
        let l = log.clone();
        std::thread::spawn(move || {
            for line in BufReader::new(stderr).lines().map_while(Result::ok) {
                if let Ok(v) = serde_json::from_str::<Value>(&line)
                    && let Some(addr) = v["fields"]["addr"].as_str()
                    && let Some(port) = addr.rsplit(':').next().and_then(|p| p.parse::<u16>().ok())
                {
                    let _ = tx.send(port);
                }
                let mut l = l.lock().unwrap();
                l.push_str(&line);
                l.push('\n');
            }
        });
        let port = rx
            .recv_timeout(Duration::from_secs(30))
            .unwrap_or_else(|_| panic!("the server did not start:\n{}", log.lock().unwrap()));
        let s = Server { child, port, log };
        // Ready once the store answers.
        let t0 = Instant::now();
        while s.get("/readyz").status != 200 {
            assert!(
                t0.elapsed() < Duration::from_secs(30),
                "not ready:\n{}",
                s.log()
            );
            std::thread::sleep(Duration::from_millis(20));
        }
        s
    }

    pub fn log(&self) -> String {
        self.log.lock().unwrap().clone()
    }

    pub fn pid(&self) -> u32 {
        self.child.id()
    }

    pub fn request(
        &self,
        method: &str,
        path: &str,
        body: Option<&Value>,
        headers: &[(&str, &str)],
    ) -> Reply {
        request(self.port, method, path, body, headers)
    }

    pub fn get(&self, path: &str) -> Reply {
        self.request("GET", path, None, &[])
    }

    pub fn json(&self, method: &str, path: &str, body: Option<&Value>) -> (u16, Value) {
        let r = self.request(method, path, body, &[]);
        (r.status, r.json())
    }

    /// Submits a job; its id.
    pub fn submit(&self, job: &Value) -> String {
        let (s, v) = self.json("POST", "/v1/jobs", Some(job));
        assert_eq!(s, 202, "{v}");
        v["id"].as_str().unwrap().to_string()
    }

    /// Polls a job until `done` or `limit`; its last status.
    pub fn wait(&self, id: &str, done: impl Fn(&Value) -> bool, limit: Duration) -> Value {
        let t0 = Instant::now();
        loop {
            let (_, v) = self.json("GET", &format!("/v1/jobs/{id}"), None);
            if done(&v) || t0.elapsed() > limit {
                return v;
            }
            std::thread::sleep(Duration::from_millis(20));
        }
    }

    /// A metric's value (the first line starting with `name`).
    pub fn metric(&self, name: &str) -> f64 {
        let text = String::from_utf8(self.get("/metrics").body).unwrap();
        text.lines()
            .find(|l| l.starts_with(name) && l[name.len()..].starts_with(' '))
            .and_then(|l| l.rsplit(' ').next())
            .and_then(|v| v.parse().ok())
            .unwrap_or_else(|| panic!("no metric {name} in:\n{text}"))
    }

    /// A counter's value, 0 when it has no line yet.
    pub fn count(&self, name: &str) -> f64 {
        let text = String::from_utf8(self.get("/metrics").body).unwrap();
        text.lines()
            .find(|l| l.starts_with(name) && l[name.len()..].starts_with(' '))
            .and_then(|l| l.rsplit(' ').next())
            .and_then(|v| v.parse().ok())
            .unwrap_or(0.0)
    }

    /// Resident memory, KiB.
    pub fn rss_kib(&self) -> u64 {
        let status = std::fs::read_to_string(format!("/proc/{}/status", self.pid())).unwrap();
        status
            .lines()
            .find(|l| l.starts_with("VmRSS:"))
            .and_then(|l| l.split_whitespace().nth(1))
            .and_then(|v| v.parse().ok())
            .unwrap()
    }

    /// SIGKILL: no shutdown at all.
    pub fn kill(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }

    /// SIGTERM, and waits for the process to end.
    pub fn terminate(&mut self) -> std::process::ExitStatus {
        // SAFETY: kill only sends a signal to our child.
        unsafe {
            libc::kill(self.child.id() as i32, libc::SIGTERM);
        }
        self.child.wait().unwrap()
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        self.kill();
    }
}

pub fn finished(v: &Value) -> bool {
    ["succeeded", "failed", "cancelled"].contains(&v["status"].as_str().unwrap_or(""))
}

/// Running again after `first` (claimed anew: a later start).
pub fn claimed_again(first: &Value, v: &Value) -> bool {
    v["status"] == "running" && v["started_at"] != first["started_at"]
}

pub fn running(v: &Value) -> bool {
    v["status"] == "running" && v["progress"].as_f64().unwrap_or(0.0) > 0.0
}

fn example(name: &str) -> Value {
    let path = format!("{}/examples/{name}", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// A job of a few milliseconds.
pub fn quick_job() -> Value {
    json!({"analysis": "campbell", "input": example("jeffcott-nvd.campbell.json")})
}

/// A Campbell sweep of the compressor on its full model, viscous, `speeds` speeds: about 25 ms
/// a speed on 2 cores, cancellation checked between speeds.
pub fn sweep_job(speeds: usize) -> Value {
    let mut input = example("compressor-hysteretic.campbell.json");
    input["damping"] = json!({"model": "viscous"});
    input["speeds"] = json!({"start": 0.0, "stop": 1500.0, "count": speeds});
    input["modal_reduction"] = json!(false);
    json!({"analysis": "campbell", "input": input})
}

/// A time response whose result is about `samples` samples of one node (x and y).
pub fn large_result_job(samples: usize) -> Value {
    let mut input = example("example1-shock-nvd.time-response.json");
    let duration = 0.5;
    input["duration"] = json!(duration);
    input["output_interval"] = json!(duration / samples as f64);
    json!({"analysis": "time-response", "input": input})
}
