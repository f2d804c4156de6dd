//! Replicas on one PostgreSQL: the built server, several processes on loopback ports, each
//! test on a database of its own. A job submitted to one replica is read, cancelled and
//! fetched on another; a replica killed in mid-job loses nothing (its job runs again on the
//! other, or fails with the reason); a restart keeps finished jobs; a burst of jobs over two
//! replicas runs each job exactly once.
//!
//! Needs PostgreSQL (`WHIRL_TEST_POSTGRES`, default the local server); `.ci/run` checks it.

use crate::cluster;

use std::sync::Mutex;
use std::time::{Duration, Instant};

use cluster::{Database, Server, claimed_again, finished, gunzip, quick_job, running, sweep_job};

/// The tests here share the machine's cores: one at a time, so that timings mean something.
static ONE_AT_A_TIME: Mutex<()> = Mutex::new(());

fn serial() -> std::sync::MutexGuard<'static, ()> {
    ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner())
}

fn replica(db: &Database, extra: &[(&str, &str)]) -> Server {
    let mut env = vec![("WHIRL_DATABASE_URL", db.url.as_str())];
    env.extend_from_slice(extra);
    Server::start(&env)
}

#[test]
fn a_job_submitted_to_one_replica_is_read_cancelled_and_fetched_on_another() {
    let _one = serial();
    let db = Database::create();
    let a = replica(&db, &[]);
    let b = replica(&db, &[]);

    // Submitted to A, followed and fetched on B.
    let id = a.submit(&quick_job());
    let v = b.wait(&id, finished, Duration::from_secs(30));
    assert_eq!(v["status"], "succeeded", "{v}");
    let plain = b.get(&format!("/v1/jobs/{id}/result"));
    assert_eq!(plain.status, 200);
    assert_eq!(plain.header("content-type"), Some("application/json"));
    let sync = b.request("POST", "/v1/campbell", Some(&quick_job()["input"]), &[]);
    assert_eq!(
        plain.json(),
        sync.json(),
        "the result is the synchronous body"
    );
    // The stored gzip as it is, from either replica.
    for r in [&a, &b] {
        let gz = r.request(
            "GET",
            &format!("/v1/jobs/{id}/result"),
            None,
            &[("accept-encoding", "gzip")],
        );
        assert_eq!(gz.header("content-encoding"), Some("gzip"));
        assert_eq!(gunzip(&gz.body), plain.body);
    }
    let csv = b.request(
        "GET",
        &format!("/v1/jobs/{id}/result"),
        None,
        &[("accept", "text/csv")],
    );
    assert!(String::from_utf8_lossy(&csv.body).starts_with("speed [rad/s],"));

    // A long job: it runs on one replica and is cancelled on the other.
    let id = a.submit(&sweep_job(1500));
    let v = b.wait(&id, running, Duration::from_secs(30));
    assert!(running(&v), "B sees A's progress: {v}");
    let (runner, other) = if a.metric("whirl_jobs_running_here") == 1.0 {
        (&a, &b)
    } else {
        (&b, &a)
    };
    assert_eq!(runner.metric("whirl_analyses_running"), 1.0);
    let t0 = Instant::now();
    let (s, v) = other.json("DELETE", &format!("/v1/jobs/{id}"), None);
    assert_eq!(s, 200, "{v}");
    assert_eq!(v["status"], "cancelled", "recorded at once: {v}");
    // The replica running it stops it within a second.
    while runner.metric("whirl_analyses_running") != 0.0 {
        assert!(
            t0.elapsed() < Duration::from_secs(1),
            "still running {:?} after the cancel",
            t0.elapsed()
        );
        std::thread::sleep(Duration::from_millis(10));
    }
    eprintln!("cancel on the other replica: stopped in {:?}", t0.elapsed());
    let (_, v) = runner.json("GET", &format!("/v1/jobs/{id}"), None);
    assert_eq!(v["status"], "cancelled");
    assert!(v["error"]["detail"].as_str().unwrap().contains("client"));
    assert_eq!(
        runner.get(&format!("/v1/jobs/{id}/result")).status,
        409,
        "no result for a cancelled job"
    );
}

#[test]
fn the_job_of_a_killed_replica_runs_again_on_the_other_within_the_lease() {
    let _one = serial();
    let db = Database::create();
    let lease = [("WHIRL_JOB_LEASE", "2")];
    let mut a = replica(&db, &lease);
    let id = a.submit(&sweep_job(60));
    let first = a.wait(&id, running, Duration::from_secs(30));
    assert!(running(&first), "{first}");
    let b = replica(&db, &lease);
    a.kill();
    let t0 = Instant::now();
    // Re-queued when the lease runs out, and claimed by B.
    let v = b.wait(&id, |v| claimed_again(&first, v), Duration::from_secs(10));
    let again = t0.elapsed();
    assert_eq!(v["status"], "running", "{v}");
    assert!(
        again < Duration::from_secs(2) + Duration::from_millis(1500),
        "running again after {again:?} (lease 2 s)"
    );
    let v = b.wait(&id, finished, Duration::from_secs(120));
    assert_eq!(v["status"], "succeeded", "{v}");
    eprintln!(
        "killed replica: job running again after {again:?}, done after {:?}",
        t0.elapsed()
    );
    let jobs = db.jobs();
    assert_eq!(jobs.len(), 1);
    let (_, attempts, expiries, _) = &jobs[0];
    assert_eq!((*attempts, *expiries), (2, 1));
    assert!(b.log().contains("lease expired"), "the takeover is logged");
    assert_eq!(b.metric("whirl_store_lease_expiries_total"), 1.0);
}

#[test]
fn a_job_whose_replica_dies_twice_fails_with_the_reason() {
    let _one = serial();
    let db = Database::create();
    let lease = [("WHIRL_JOB_LEASE", "1")];
    let mut a = replica(&db, &lease);
    let id = a.submit(&sweep_job(1500));
    let first = a.wait(&id, running, Duration::from_secs(30));
    assert!(running(&first), "{first}");
    let mut b = replica(&db, &lease);
    a.kill();
    let v = b.wait(&id, |v| claimed_again(&first, v), Duration::from_secs(10));
    assert_eq!(v["status"], "running", "{v}");
    b.kill();
    let c = replica(&db, &lease);
    let v = c.wait(&id, finished, Duration::from_secs(10));
    assert_eq!(v["status"], "failed", "{v}");
    let detail = v["error"]["detail"].as_str().unwrap();
    assert!(detail.contains("stopped responding twice"), "{detail}");
    let jobs = db.jobs();
    assert_eq!((jobs[0].1, jobs[0].2), (2, 2), "two runs, two expiries");
}

#[test]
fn a_restart_keeps_finished_jobs_and_their_results() {
    let _one = serial();
    let db = Database::create();
    let mut a = replica(&db, &[]);
    let done = a.submit(&quick_job());
    let v = a.wait(&done, finished, Duration::from_secs(30));
    assert_eq!(v["status"], "succeeded");
    let result = a.get(&format!("/v1/jobs/{done}/result")).body;
    let stopped = a.submit(&sweep_job(1500));
    assert_eq!(
        a.json("DELETE", &format!("/v1/jobs/{stopped}"), None).0,
        200
    );
    assert!(a.terminate().success());

    let a = replica(&db, &[]);
    let (s, again) = a.json("GET", &format!("/v1/jobs/{done}"), None);
    assert_eq!(s, 200);
    assert_eq!(again, v, "the same job after the restart");
    assert_eq!(a.get(&format!("/v1/jobs/{done}/result")).body, result);
    let (_, v) = a.json("GET", &format!("/v1/jobs/{stopped}"), None);
    assert_eq!(v["status"], "cancelled");
}

#[test]
fn sixty_four_jobs_on_two_replicas_run_exactly_once() {
    let _one = serial();
    let db = Database::create();
    let env = [("WHIRL_QUEUE", "128")];
    let replicas = [replica(&db, &env), replica(&db, &env)];
    let t0 = Instant::now();
    let ids: Vec<String> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..64)
            .map(|i| {
                let r = &replicas[i % 2];
                s.spawn(move || r.submit(&quick_job()))
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    for (i, id) in ids.iter().enumerate() {
        let v = replicas[(i + 1) % 2].wait(id, finished, Duration::from_secs(60));
        assert_eq!(v["status"], "succeeded", "{v}");
    }
    eprintln!("64 jobs on two replicas: {:?}", t0.elapsed());
    let jobs = db.jobs();
    assert_eq!(jobs.len(), 64);
    for (id, attempts, expiries, status) in &jobs {
        assert_eq!(
            (*attempts, *expiries, status.as_str()),
            (1, 0, "succeeded"),
            "{id}"
        );
    }
    // And each replica counted its own executions: 64 in all.
    let runs: f64 = replicas
        .iter()
        .map(|r| r.count("whirl_analysis_duration_seconds_count{analysis=\"campbell\"}"))
        .sum();
    assert_eq!(runs, 64.0);
}
