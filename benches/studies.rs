//! A 1000-sample study on one replica and on two sharing PostgreSQL (a benchmark, not a test):
//! the built server as separate processes, each with `WHIRL_WORKERS` workers, on a database of
//! its own. The figure is the ratio of the two wall times. The samples: Example 1's threshold
//! with equivalent damping over its shaft's and a bearing's loss factors (Latin hypercube),
//! 201 speeds each by default.
//!
//! `cargo bench --bench studies [-- SAMPLES [WORKERS [SPEEDS]]]` (default 1000 samples, 1
//! worker per replica: on 2 cores, two one-worker replicas have a core each; 201 speeds).
//! `-- --pin` pins each replica to a core of its own (as if on a machine of its own: an
//! analysis otherwise spreads its speeds over every core, so replicas on one small machine
//! share the same cores). Needs PostgreSQL as the tests do (`WHIRL_TEST_POSTGRES`, default
//! the local server), which runs unpinned.

#[path = "../tests/cluster/mod.rs"]
mod cluster;

use std::collections::BTreeMap;
use std::time::{Duration, Instant};

use cluster::{Database, Server};
use serde_json::{Value, json};

fn study(samples: u64, speeds: u64) -> Value {
    let path = format!(
        "{}/examples/example1-equivalent.campbell.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let mut input: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    input["speeds"] = json!({"start": 0, "stop": 4000, "count": speeds});
    json!({
        "analysis": "stability",
        "input": input,
        "parameters": [
            {"pointer": "/rotor/materials/steel/loss_factor",
             "distribution": {"type": "uniform", "low": 0.01, "high": 0.03}},
            {"pointer": "/rotor/supports/0/loss_factor",
             "distribution": {"type": "normal", "mean": 0.06, "std": 0.01, "min": 0.02}}
        ],
        "design": "latin-hypercube",
        "samples": samples,
        "seed": 1,
        "outputs": ["/threshold"]
    })
}

/// Runs `start` with this process pinned to `cpu` (its child inherits the mask at fork: a
/// replica on one core, as on a machine of its own), then unpins.
fn pinned(cpu: Option<usize>, start: impl FnOnce() -> Server) -> Server {
    let Some(cpu) = cpu else { return start() };
    // SAFETY: sched_{get,set}affinity on this process with a cpu_set_t of our own.
    unsafe {
        let mut all: libc::cpu_set_t = std::mem::zeroed();
        libc::sched_getaffinity(0, std::mem::size_of::<libc::cpu_set_t>(), &mut all);
        let mut one: libc::cpu_set_t = std::mem::zeroed();
        libc::CPU_SET(cpu, &mut one);
        libc::sched_setaffinity(0, std::mem::size_of::<libc::cpu_set_t>(), &one);
        let server = start();
        libc::sched_setaffinity(0, std::mem::size_of::<libc::cpu_set_t>(), &all);
        server
    }
}

/// Submits the study to the first replica and waits on it; wall time and samples per replica.
fn run(replicas: &[Server], samples: u64, speeds: u64) -> (Duration, Value) {
    let t0 = Instant::now();
    let (s, v) = replicas[0].json("POST", "/v1/studies", Some(&study(samples, speeds)));
    assert_eq!(s, 202, "{v}");
    let id = v["id"].as_str().unwrap().to_string();
    let submitted = t0.elapsed();
    loop {
        let (_, v) = replicas[0].json("GET", &format!("/v1/studies/{id}"), None);
        if v["status"] == "finished" {
            break;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let wall = t0.elapsed();
    let (s, r) = replicas[0].json("GET", &format!("/v1/studies/{id}/result"), None);
    assert_eq!(s, 200);
    let mut per: BTreeMap<String, u64> = BTreeMap::new();
    for x in r["samples"].as_array().unwrap() {
        *per.entry(x["server"].as_str().unwrap_or("-").to_string())
            .or_default() += 1;
    }
    println!(
        "  submitted (every sample checked and queued) in {:.2} s; done in {:.2} s; per replica {:?}; threshold {}",
        submitted.as_secs_f64(),
        wall.as_secs_f64(),
        per.values().collect::<Vec<_>>(),
        r["summary"][0]
    );
    (wall, r["summary"].clone())
}

fn main() {
    let args: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with('-'))
        .collect();
    let samples: u64 = args.first().and_then(|a| a.parse().ok()).unwrap_or(1000);
    let workers = args.get(1).cloned().unwrap_or_else(|| "1".into());
    let speeds: u64 = args.get(2).and_then(|a| a.parse().ok()).unwrap_or(201);
    println!(
        "cores: {}; {samples} samples of {speeds} speeds; WHIRL_WORKERS={workers} per replica",
        std::thread::available_parallelism().map_or(0, |n| n.get())
    );
    // `pin`: each replica on a core of its own (replica i on core i), else unpinned.
    let pin = std::env::args().any(|a| a == "--pin");
    let env = |db: &Database, i: usize| {
        pinned(pin.then_some(i), || {
            Server::start(&[
                ("WHIRL_DATABASE_URL", db.url.as_str()),
                ("WHIRL_WORKERS", workers.as_str()),
            ])
        })
    };
    println!("one replica{}:", if pin { " (on core 0)" } else { "" });
    let db = Database::create();
    let one = [env(&db, 0)];
    let (t1, s1) = run(&one, samples, speeds);
    drop(one);
    println!(
        "two replicas{}:",
        if pin { " (on cores 0 and 1)" } else { "" }
    );
    let db2 = Database::create();
    let two = [env(&db2, 0), env(&db2, 1)];
    let (t2, s2) = run(&two, samples, speeds);
    assert_eq!(s1, s2, "the same summary on one and two replicas");
    println!(
        "speed-up of two replicas: {:.2} ({:.1} ms a sample on one, {:.1} on two)",
        t1.as_secs_f64() / t2.as_secs_f64(),
        t1.as_secs_f64() * 1e3 / samples as f64,
        t2.as_secs_f64() * 1e3 / samples as f64
    );
}
