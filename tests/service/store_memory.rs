//! A server's memory does not grow with the results it keeps: they live in the store and are
//! served from it chunk by chunk. Measured on the built server: 40 large results (about 5 MB
//! gzipped each, 200 MB in all) computed, kept and fetched; the resident size, read from
//! `/proc/<pid>/status`, stays within 100 MB of where it started.

use crate::cluster;

use std::time::Duration;

use cluster::{Database, Server, finished, large_result_job};

const JOBS: usize = 40;
const SAMPLES: usize = 250_000;

fn measure(server: &Server, store: &str) {
    let start = server.rss_kib();
    let ids: Vec<String> = (0..JOBS)
        .map(|_| server.submit(&large_result_job(SAMPLES)))
        .collect();
    for id in &ids {
        let v = server.wait(id, finished, Duration::from_secs(120));
        assert_eq!(v["status"], "succeeded", "{v}");
    }
    let kept = server.metric("whirl_job_results_bytes");
    let finished_rss = server.rss_kib();
    let mut served = 0;
    for id in &ids {
        let r = server.get(&format!("/v1/jobs/{id}/result"));
        assert_eq!(r.status, 200);
        served += r.body.len();
    }
    let fetched_rss = server.rss_kib();
    eprintln!(
        "{store}: {JOBS} results kept, {:.0} MB gzipped ({:.0} MB of JSON served); RSS {} MB \
         at start, {} MB with them all finished, {} MB after serving them all",
        kept / 1e6,
        served as f64 / 1e6,
        start / 1024,
        finished_rss / 1024,
        fetched_rss / 1024
    );
    assert!(
        kept > 150e6,
        "the results must be large enough to show: {kept} B"
    );
    for rss in [finished_rss, fetched_rss] {
        assert!(
            rss < start + 100 * 1024,
            "RSS grew from {start} KiB to {rss} KiB"
        );
    }
}

const KEEP_ALL: [(&str, &str); 2] = [
    ("WHIRL_JOB_RESULT_BYTES", "2G"),
    ("WHIRL_MAX_FINISHED_JOBS", "1000"),
];

#[test]
fn kept_results_do_not_grow_the_server_on_the_embedded_store() {
    let dir = tempfile::tempdir().unwrap();
    let mut env = vec![("WHIRL_DATA_DIR", dir.path().to_str().unwrap())];
    env.extend_from_slice(&KEEP_ALL);
    measure(&Server::start(&env), "SQLite");
}

#[test]
fn kept_results_do_not_grow_the_server_on_postgres() {
    let db = Database::create();
    let mut env = vec![("WHIRL_DATABASE_URL", db.url.as_str())];
    env.extend_from_slice(&KEEP_ALL);
    measure(&Server::start(&env), "PostgreSQL");
}
