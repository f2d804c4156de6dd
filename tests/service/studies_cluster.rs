//! Studies on replicas sharing PostgreSQL: both replicas compute samples of one study and its
//! result equals a single server's; a replica killed in mid-study loses no sample (its
//! running samples are re-queued when their lease runs out and computed by the other); a
//! study outlives a restart of its only server (embedded store).
//!
//! Needs PostgreSQL (`WHIRL_TEST_POSTGRES`, default the local server), like
//! `tests/service/store_postgres.rs`; each test on a database of its own.

use crate::cluster;

use std::collections::BTreeSet;
use std::sync::Mutex;
use std::time::{Duration, Instant};

use cluster::{Database, Server};
use serde_json::{Value, json};

static ONE_AT_A_TIME: Mutex<()> = Mutex::new(());

fn serial() -> std::sync::MutexGuard<'static, ()> {
    ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner())
}

fn replica(db: &Database, extra: &[(&str, &str)]) -> Server {
    let mut env = vec![("WHIRL_DATABASE_URL", db.url.as_str())];
    env.extend_from_slice(extra);
    Server::start(&env)
}

/// The paper's Example 1 with equivalent damping: its threshold of instability over the
/// scatter of the steel's and a support's loss factors (Latin hypercube, seeded). 2000 speeds:
/// about 0.3 s a sample.
fn study(samples: u64) -> Value {
    let path = format!(
        "{}/examples/example1-equivalent.campbell.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let mut input: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    input["speeds"] = json!({"start": 0, "stop": 4000, "count": 2000});
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
        "seed": 2026,
        "outputs": ["/threshold", "/frequency"]
    })
}

fn submit(s: &Server, body: &Value) -> String {
    let (status, v) = s.json("POST", "/v1/studies", Some(body));
    assert_eq!(status, 202, "{v}");
    v["id"].as_str().unwrap().to_string()
}

fn wait(s: &Server, id: &str, done: impl Fn(&Value) -> bool, limit: Duration) -> Value {
    let t0 = Instant::now();
    loop {
        let (_, v) = s.json("GET", &format!("/v1/studies/{id}"), None);
        if done(&v) || t0.elapsed() > limit {
            return v;
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

fn finished(v: &Value) -> bool {
    v["status"] == "finished"
}

fn result(s: &Server, id: &str) -> Value {
    let (status, r) = s.json("GET", &format!("/v1/studies/{id}/result"), None);
    assert_eq!(status, 200, "{r}");
    r
}

/// The result without the replicas' names (what must not depend on who computed it).
fn computed(r: &Value) -> Value {
    let mut r = r.clone();
    for s in r["samples"].as_array_mut().unwrap() {
        s.as_object_mut().unwrap().remove("server");
    }
    r.as_object_mut().unwrap().remove("id");
    r
}

fn servers(r: &Value) -> BTreeSet<String> {
    r["samples"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["server"].as_str().unwrap().to_string())
        .collect()
}

/// The same study on one server alone (its embedded store).
fn reference(samples: u64) -> Value {
    let dir = tempfile::tempdir().unwrap();
    let one = Server::start(&[("WHIRL_DATA_DIR", dir.path().to_str().unwrap())]);
    let id = submit(&one, &study(samples));
    let v = wait(&one, &id, finished, Duration::from_secs(300));
    assert!(finished(&v), "{v}");
    computed(&result(&one, &id))
}

#[test]
fn two_replicas_share_a_study_and_agree_with_one_server() {
    let _one = serial();
    // The replica that did not take the submission finds queued samples when it next polls
    // (runner::POLL, 0.5 s): the study must outlast that (24 samples took 0.54 s on 2 cores).
    let n = 96;
    let expected = reference(n);
    let db = Database::create();
    let a = replica(&db, &[]);
    let b = replica(&db, &[]);
    let t0 = Instant::now();
    let id = submit(&a, &study(n));
    let v = wait(&b, &id, finished, Duration::from_secs(300));
    assert!(finished(&v), "{v}");
    eprintln!("{n} samples on two replicas: {:?}", t0.elapsed());
    assert_eq!(v["counts"]["done"], n);
    let r = result(&b, &id);
    assert_eq!(
        servers(&r).len(),
        2,
        "both replicas computed samples: {:?}",
        servers(&r)
    );
    assert_eq!(
        computed(&r),
        expected,
        "two replicas' result is one server's"
    );
    assert_eq!(computed(&result(&a, &id)), expected);
    // Every sample has a threshold (882.7 rad/s at the example's own loss factors), lower for
    // a lossier shaft.
    let t = &r["summary"][0];
    assert_eq!(t["count"], n, "{t}");
    let (lo, hi) = (t["min"].as_f64().unwrap(), t["max"].as_f64().unwrap());
    assert!(400.0 < lo && lo < hi && hi < 4000.0, "{t}");
    let s = &r["sensitivity"][0];
    assert_eq!(s["parameter"], "/rotor/materials/steel/loss_factor");
    assert!(s["spearman"].as_f64().unwrap() < -0.5, "{s}");
}

#[test]
fn a_replica_killed_in_mid_study_loses_no_sample() {
    let _one = serial();
    let n = 40;
    let expected = reference(n);
    let db = Database::create();
    let lease = [("WHIRL_JOB_LEASE", "2")];
    let mut a = replica(&db, &lease);
    let b = replica(&db, &lease);
    let id = submit(&a, &study(n));
    // Both at work, a few samples done: A dies with samples in hand.
    let v = wait(
        &b,
        &id,
        |v| v["counts"]["done"].as_u64().unwrap_or(0) >= 3,
        Duration::from_secs(120),
    );
    assert!(v["counts"]["running"].as_u64().unwrap() >= 1, "{v}");
    a.kill();
    let v = wait(&b, &id, finished, Duration::from_secs(300));
    assert!(finished(&v), "{v}");
    assert_eq!(v["counts"]["done"], n, "every sample computed: {v}");
    assert_eq!(v["counts"]["failed"], 0, "{v}");
    let expiries: i64 = db.jobs().iter().map(|j| j.2).sum();
    assert!(
        expiries >= 1,
        "a sample of the killed replica was re-queued: {:?}",
        db.jobs()
    );
    assert!(b.log().contains("lease expired"));
    assert_eq!(computed(&result(&b, &id)), expected);
}

#[test]
fn a_study_survives_a_restart_of_its_only_server() {
    let _one = serial();
    let n = 24;
    let expected = reference(n);
    let dir = tempfile::tempdir().unwrap();
    let data = [("WHIRL_DATA_DIR", dir.path().to_str().unwrap())];
    let mut a = Server::start(&data);
    let id = submit(&a, &study(n));
    let v = wait(
        &a,
        &id,
        |v| v["counts"]["done"].as_u64().unwrap_or(0) >= 2,
        Duration::from_secs(60),
    );
    assert!(
        v["counts"]["queued"].as_u64().unwrap() >= 1,
        "stopped in mid-study: {v}"
    );
    // SIGTERM: running samples go back to the queue; the next server finishes the study.
    assert!(a.terminate().success());
    let b = Server::start(&data);
    let v = wait(&b, &id, finished, Duration::from_secs(120));
    assert!(finished(&v), "{v}");
    assert_eq!(v["counts"]["done"], n, "{v}");
    assert_eq!(computed(&result(&b, &id)), expected);
}
