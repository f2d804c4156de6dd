//! The embedded default store (SQLite under `WHIRL_DATA_DIR`): one server process, restarted.
//! Jobs are read, cancelled and fetched across restarts; a job running at SIGTERM goes back to
//! the queue and runs after the restart; a job whose server was killed runs again after its
//! lease; a burst of jobs runs each job exactly once.

use crate::cluster;

use std::path::Path;
use std::sync::Mutex;
use std::time::{Duration, Instant};

use cluster::{Server, claimed_again, finished, quick_job, running, sqlite_jobs, sweep_job};

/// The tests here share the machine's cores: one at a time, so that timings mean something.
static ONE_AT_A_TIME: Mutex<()> = Mutex::new(());

fn serial() -> std::sync::MutexGuard<'static, ()> {
    ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner())
}

fn server(dir: &Path, extra: &[(&str, &str)]) -> Server {
    let dir = dir.to_str().unwrap();
    let mut env = vec![("WHIRL_DATA_DIR", dir)];
    env.extend_from_slice(extra);
    Server::start(&env)
}

#[test]
fn jobs_are_read_cancelled_and_fetched_across_restarts() {
    let _one = serial();
    let dir = tempfile::tempdir().unwrap();
    let mut s = server(
        dir.path(),
        &[("WHIRL_SHUTDOWN_GRACE", "0"), ("WHIRL_WORKERS", "1")],
    );
    let done = s.submit(&quick_job());
    let v = s.wait(&done, finished, Duration::from_secs(30));
    assert_eq!(v["status"], "succeeded", "{v}");
    let result = s.get(&format!("/v1/jobs/{done}/result")).body;
    // A job running at SIGTERM goes back to the queue, and one queued stays queued.
    let busy = s.submit(&sweep_job(1500));
    assert!(running(&s.wait(&busy, running, Duration::from_secs(30))));
    let waiting = s.submit(&sweep_job(40));
    assert!(s.terminate().success());
    assert!(s.log().contains("job handed back to the queue"));

    let mut s = server(dir.path(), &[]);
    let (status, again) = s.json("GET", &format!("/v1/jobs/{done}"), None);
    assert_eq!(status, 200);
    assert_eq!(again, v, "the same job after the restart");
    assert_eq!(s.get(&format!("/v1/jobs/{done}/result")).body, result);
    // The handed-back job runs again from the start, oldest first; cancel it there.
    let v = s.wait(&busy, running, Duration::from_secs(30));
    assert!(running(&v), "{v}");
    let (code, v) = s.json("DELETE", &format!("/v1/jobs/{busy}"), None);
    assert_eq!(
        (code, v["status"].as_str()),
        (200, Some("cancelled")),
        "{v}"
    );
    // The queued one then runs to its end.
    let v = s.wait(&waiting, finished, Duration::from_secs(120));
    assert_eq!(v["status"], "succeeded", "{v}");
    assert!(s.terminate().success());

    let s = server(dir.path(), &[]);
    let (_, v) = s.json("GET", &format!("/v1/jobs/{busy}"), None);
    assert_eq!(v["status"], "cancelled", "{v}");
    assert_eq!(s.get(&format!("/v1/jobs/{waiting}/result")).status, 200);
    let runs: Vec<(String, i64)> = sqlite_jobs(dir.path())
        .into_iter()
        .map(|(id, attempts, _, _)| (id, attempts))
        .collect();
    assert!(runs.contains(&(busy.clone(), 2)), "{runs:?}");
    assert!(runs.contains(&(waiting.clone(), 1)), "{runs:?}");
}

#[test]
fn a_job_whose_server_was_killed_runs_again_after_the_restart() {
    let _one = serial();
    let dir = tempfile::tempdir().unwrap();
    let lease = [("WHIRL_JOB_LEASE", "2")];
    let mut s = server(dir.path(), &lease);
    let id = s.submit(&sweep_job(60));
    let first = s.wait(&id, running, Duration::from_secs(30));
    assert!(running(&first), "{first}");
    s.kill();
    let t0 = Instant::now();
    let s = server(dir.path(), &lease);
    let v = s.wait(&id, |v| claimed_again(&first, v), Duration::from_secs(10));
    let again = t0.elapsed();
    assert_eq!(v["status"], "running", "{v}");
    assert!(
        again < Duration::from_millis(3500),
        "running again after {again:?} (lease 2 s)"
    );
    let v = s.wait(&id, finished, Duration::from_secs(120));
    assert_eq!(v["status"], "succeeded", "{v}");
    eprintln!(
        "killed server: job running again after {again:?}, done after {:?}",
        t0.elapsed()
    );
    let jobs = sqlite_jobs(dir.path());
    assert_eq!((jobs[0].1, jobs[0].2), (2, 1), "two runs, one expiry");
}

#[test]
fn sixty_four_jobs_run_exactly_once() {
    let _one = serial();
    let dir = tempfile::tempdir().unwrap();
    let s = server(dir.path(), &[("WHIRL_QUEUE", "128")]);
    let t0 = Instant::now();
    let ids: Vec<String> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..64)
            .map(|_| scope.spawn(|| s.submit(&quick_job())))
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    for id in &ids {
        let v = s.wait(id, finished, Duration::from_secs(60));
        assert_eq!(v["status"], "succeeded", "{v}");
    }
    eprintln!("64 jobs on one server: {:?}", t0.elapsed());
    let jobs = sqlite_jobs(dir.path());
    assert_eq!(jobs.len(), 64);
    for (id, attempts, expiries, status) in &jobs {
        assert_eq!(
            (*attempts, *expiries, status.as_str()),
            (1, 0, "succeeded"),
            "{id}"
        );
    }
    assert_eq!(
        s.count("whirl_analysis_duration_seconds_count{analysis=\"campbell\"}"),
        64.0
    );
}
