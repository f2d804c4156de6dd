//! The binary as an operator runs it: SIGTERM ends it within the grace period whatever its
//! clients do, running jobs are handed back to the store's queue (logged), and logs carry no
//! terminal colours when they go to a file or a pipe.

use std::io::{Read, Write};
use std::net::TcpStream;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use serde_json::{Value, json};

fn free_port() -> u16 {
    std::net::TcpListener::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port()
}

fn http(port: u16, method: &str, path: &str, body: &str) -> String {
    let Ok(mut s) = TcpStream::connect(("127.0.0.1", port)) else {
        return String::new();
    };
    s.set_read_timeout(Some(Duration::from_secs(30))).unwrap();
    write!(
        s,
        "{method} {path} HTTP/1.1\r\nhost: x\r\nconnection: close\r\ncontent-type: application/json\r\ncontent-length: {}\r\n\r\n{body}",
        body.len()
    )
    .unwrap();
    let mut out = String::new();
    let _ = s.read_to_string(&mut out);
    out
}

fn long_job() -> Value {
    let path = format!(
        "{}/examples/compressor-hysteretic.campbell.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let mut input: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    input["rotor"].as_object_mut().unwrap().remove("reduction");
    input["damping"] = json!({"model": "viscous"});
    input["speeds"] = json!({"start": 0.0, "stop": 1500.0, "count": 1500});
    input["modal_reduction"] = json!(false);
    json!({"analysis": "campbell", "input": input})
}

#[test]
fn sigterm_ends_the_process_within_the_grace_whatever_the_clients_do() {
    let port = free_port();
    let data = std::env::temp_dir().join(format!("whirl-process-{port}"));
    let mut child = Command::new(env!("CARGO_BIN_EXE_whirl"))
        .env("HOST", "127.0.0.1")
        .env("PORT", port.to_string())
        .env("WHIRL_DATA_DIR", &data)
        .env("WHIRL_SHUTDOWN_GRACE", "1")
        // Nothing else would drop the stalled client below.
        .env("WHIRL_HEADER_TIMEOUT", "120")
        .env("WHIRL_BODY_TIMEOUT", "120")
        .env("RUST_LOG", "info")
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let t0 = Instant::now();
    while !http(port, "GET", "/healthz", "").starts_with("HTTP/1.1 200") {
        assert!(t0.elapsed() < Duration::from_secs(10), "did not start");
        std::thread::sleep(Duration::from_millis(50));
    }
    // A client that announced a body and stalls; a long job running.
    let mut stalled = TcpStream::connect(("127.0.0.1", port)).unwrap();
    stalled
        .write_all(b"POST /v1/modal HTTP/1.1\r\nhost: x\r\ncontent-type: application/json\r\ncontent-length: 1000\r\n\r\n{\"rotor\"")
        .unwrap();
    let answer = http(port, "POST", "/v1/jobs", &long_job().to_string());
    assert!(answer.starts_with("HTTP/1.1 202"), "{answer}");
    std::thread::sleep(Duration::from_millis(500));
    let t0 = Instant::now();
    // SAFETY: kill sends a signal to the child we spawned.
    unsafe {
        libc::kill(child.id() as i32, libc::SIGTERM);
    }
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        assert!(
            t0.elapsed() < Duration::from_secs(8),
            "still running {:?} after SIGTERM",
            t0.elapsed()
        );
        std::thread::sleep(Duration::from_millis(20));
    };
    let took = t0.elapsed();
    println!("exited {took:?} after SIGTERM (grace 1 s)");
    assert!(status.success(), "{status}");
    assert!(took < Duration::from_secs(4), "{took:?}");
    let mut log = String::new();
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut log)
        .unwrap();
    // The running job goes back to the queue (it survives the rollout), logged.
    assert!(log.contains("job handed back to the queue"), "{log}");
    assert!(!log.contains('\u{1b}'), "ANSI escapes in a piped log");
    drop(stalled);
    let _ = std::fs::remove_dir_all(&data);
}

#[test]
fn help_lists_every_setting_and_the_operations_page_documents_each() {
    let out = Command::new(env!("CARGO_BIN_EXE_whirl"))
        .arg("--help")
        .output()
        .unwrap();
    assert!(out.status.success());
    let help = String::from_utf8(out.stdout).unwrap();
    let readme =
        std::fs::read_to_string(format!("{}/docs/operations.md", env!("CARGO_MANIFEST_DIR")))
            .unwrap();
    for s in whirl::service::config::SETTINGS {
        assert!(
            help.contains(s.var) && help.contains(s.default),
            "--help misses {}",
            s.var
        );
        assert!(
            readme.contains(&format!("`{}`", s.var)),
            "docs/operations.md misses {}",
            s.var
        );
    }
    let out = Command::new(env!("CARGO_BIN_EXE_whirl"))
        .arg("--version")
        .output()
        .unwrap();
    assert_eq!(
        String::from_utf8(out.stdout).unwrap().trim(),
        format!("whirl {}", env!("CARGO_PKG_VERSION"))
    );
}

#[test]
fn a_closed_pipe_is_not_a_panic() {
    // `whirl openapi | head -c 10`: the reader goes away after a few bytes.
    let mut child = Command::new(env!("CARGO_BIN_EXE_whirl"))
        .arg("openapi")
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = [0u8; 10];
    child
        .stdout
        .as_mut()
        .unwrap()
        .read_exact(&mut first)
        .unwrap();
    drop(child.stdout.take());
    let status = child.wait().unwrap();
    let mut err = String::new();
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut err)
        .unwrap();
    assert!(!err.contains("panicked"), "{err}");
    assert!(status.success(), "{status} {err}");
}
