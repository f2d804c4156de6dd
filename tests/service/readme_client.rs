//! The Python client of docs/clients.md, run as it stands: the block is read out of the page, so the
//! text a user copies is the text tested. It talks to the real binary over a socket, and its
//! printed numbers are checked against the same analyses run in process.
//!
//! It needs `python3` with `httpx`; where the machine's Python lacks it, a virtual environment
//! under `target/` gets the pinned version from PyPI once.

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use serde_json::{Value, json};

use crate::common;

const HTTPX: &str = "httpx==0.28.1";

/// The page's ```python block and the ```text block after it (what it prints).
fn readme_python() -> (String, String) {
    let readme =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/clients.md")).unwrap();
    let block = |from: usize, fence: &str| {
        let start = from + readme[from..].find(fence).expect(fence) + fence.len();
        let end = start + readme[start..].find("```").unwrap();
        (readme[start..end].to_string(), end)
    };
    let (script, end) = block(0, "```python\n");
    let (printed, _) = block(end + 3, "```text\n");
    (script, printed)
}

/// A Python that imports httpx: the machine's, or one set up under target/.
fn python() -> PathBuf {
    let has_httpx = |py: &Path| {
        Command::new(py)
            .args(["-c", "import httpx"])
            .stderr(Stdio::null())
            .status()
            .is_ok_and(|s| s.success())
    };
    let system = PathBuf::from("python3");
    if has_httpx(&system) {
        return system;
    }
    let venv = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/readme-client-venv");
    let py = venv.join("bin/python");
    if !has_httpx(&py) {
        let ok = Command::new("python3")
            .args(["-m", "venv"])
            .arg(&venv)
            .status()
            .is_ok_and(|s| s.success());
        assert!(ok, "python3 -m venv {} failed", venv.display());
        let ok = Command::new(&py)
            .args(["-m", "pip", "install", "-q", HTTPX])
            .status()
            .is_ok_and(|s| s.success());
        assert!(
            ok,
            "pip install {HTTPX} failed (PyPI must be reachable once)"
        );
    }
    py
}

struct Server(Child);

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

fn serve() -> (Server, String) {
    let port = std::net::TcpListener::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port();
    let data = std::env::temp_dir().join(format!("whirl-readme-client-{port}"));
    let child = Command::new(env!("CARGO_BIN_EXE_whirl"))
        .env("HOST", "127.0.0.1")
        .env("PORT", port.to_string())
        .env("WHIRL_DATA_DIR", &data)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let server = Server(child);
    let deadline = Instant::now() + Duration::from_secs(30);
    while std::net::TcpStream::connect(("127.0.0.1", port)).is_err() {
        assert!(Instant::now() < deadline, "the server did not listen");
        std::thread::sleep(Duration::from_millis(50));
    }
    (server, format!("http://127.0.0.1:{port}"))
}

fn example() -> Value {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/example1-nvd.campbell.json"
    );
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

#[tokio::test]
async fn the_readme_python_client_runs_and_prints_the_analyses() {
    let (script, printed) = readme_python();
    let py = python();
    let (_server, url) = serve();
    let out = Command::new(&py)
        .arg("-c")
        .arg(&script)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("WHIRL_URL", &url)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(
        stdout, printed,
        "the page's output block is what the script prints"
    );
    let lines: Vec<&str> = stdout.lines().collect();

    // The same analyses in process: what the script printed is what the API answers.
    let sweep = example();
    let at_rest = json!({"rotor": sweep["rotor"], "damping": sweep["damping"], "speed": 0.0});
    let (status, modal) = common::post_json("/v1/modal", &at_rest).await;
    assert_eq!(status, 200, "{modal}");
    let forward: Vec<&Value> = modal["poles"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|p| p["whirl"] == "forward")
        .take(2)
        .collect();
    assert_eq!(forward.len(), 2);
    for (line, p) in lines.iter().zip(&forward) {
        let expected = format!(
            "forward pole {:.3} {:+.2}i, log dec {:.4}",
            p["decay_rate"].as_f64().unwrap(),
            p["frequency"].as_f64().unwrap(),
            p["log_decrement"].as_f64().unwrap()
        );
        assert_eq!(*line, expected);
    }
    let (status, campbell) = common::post_json("/v1/campbell", &sweep).await;
    assert_eq!(status, 200);
    let criticals: Vec<String> = campbell["critical_speeds"]
        .as_array()
        .unwrap()
        .iter()
        .map(|w| {
            let w = (w.as_f64().unwrap() * 10.0).round() / 10.0;
            // Python's repr of a float rounded to one decimal.
            if w.fract() == 0.0 {
                format!("{w:.1}")
            } else {
                format!("{w}")
            }
        })
        .collect();
    // Example 1's first critical speed: 370.7 rad/s with hysteretic damping
    // (tests/it/example1.rs); its nonviscous model, fitted over a band, within 1% of it.
    let first = campbell["critical_speeds"][0].as_f64().unwrap();
    assert!((first - 370.7).abs() < 0.01 * 370.7, "{first}");
    assert_eq!(
        lines[2],
        format!("critical speeds, rad/s: [{}]", criticals.join(", "))
    );

    // Each bad field on its own line, with its path.
    let errors = &lines[3..];
    assert!(errors.iter().all(|l| l.starts_with("422 ")), "{errors:?}");
    assert!(
        errors.iter().any(|l| l.starts_with("422 spead - ")),
        "{errors:?}"
    );
}
