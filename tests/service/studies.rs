//! Studies (`/v1/studies`): a grid over the equivalent-viscous Jeffcott rotor reproduces the
//! closed-form threshold 1 + eta_n/eta_r (eq. 10 of the paper); Monte Carlo and Latin
//! hypercube designs repeat with their seed, and the hypercube has one sample per stratum;
//! bad pointers, designs and sample inputs are refused before any sample is queued; a study
//! is cancelled with its samples; single jobs go before a study's samples; a failed sample
//! keeps its error, samples are not purged as single jobs are, and a study past the retention
//! is forgotten with its samples. In process, each test with an embedded store of its own.
//! Replicas sharing PostgreSQL, and a restart, are in `tests/service/studies_cluster.rs`.

use std::time::{Duration, Instant};

use axum::Router;
use axum::body::Body;
use axum::http::{Request, StatusCode, header};
use http_body_util::BodyExt;
use serde_json::{Value, json};
use tower::ServiceExt;
use whirl::service::{Config, app};

fn config() -> (Config, tempfile::TempDir) {
    let dir = tempfile::tempdir().unwrap();
    let config = Config {
        data_dir: dir.path().to_path_buf(),
        ..Config::default()
    };
    (config, dir)
}

async fn call(
    app: &Router,
    method: &str,
    uri: &str,
    body: Option<&Value>,
    accept: Option<&str>,
) -> (StatusCode, axum::http::HeaderMap, Vec<u8>) {
    let mut req = Request::builder()
        .method(method)
        .uri(uri)
        .header(header::CONTENT_TYPE, "application/json");
    if let Some(a) = accept {
        req = req.header(header::ACCEPT, a);
    }
    let body = body.map_or_else(Body::empty, |b| Body::from(b.to_string()));
    let resp = app.clone().oneshot(req.body(body).unwrap()).await.unwrap();
    let (status, headers) = (resp.status(), resp.headers().clone());
    let bytes = resp
        .into_body()
        .collect()
        .await
        .unwrap()
        .to_bytes()
        .to_vec();
    (status, headers, bytes)
}

async fn json_call(
    app: &Router,
    method: &str,
    uri: &str,
    body: Option<&Value>,
) -> (StatusCode, Value) {
    let (s, _, b) = call(app, method, uri, body, None).await;
    (s, serde_json::from_slice(&b).unwrap_or(Value::Null))
}

/// The paper's nondimensional Jeffcott rotor with equivalent damping, speeds 0 to 10.
fn jeffcott(eta_r: f64, eta_n: f64) -> Value {
    json!({
        "rotor": {"type": "jeffcott", "mass": 1, "stiffness": 1,
                  "loss_factor_rotating": eta_r, "loss_factor_nonrotating": eta_n},
        "damping": {"model": "equivalent"},
        "speeds": {"start": 0, "stop": 10, "count": 41}
    })
}

/// Submits a study (202), waits until it has finished; its id, final status and result.
async fn run(app: &Router, study: &Value) -> (String, Value, Value) {
    let (s, h, b) = call(app, "POST", "/v1/studies", Some(study), None).await;
    let info: Value = serde_json::from_slice(&b).unwrap();
    assert_eq!(s, StatusCode::ACCEPTED, "{info}");
    let id = info["id"].as_str().unwrap().to_string();
    assert_eq!(h[header::LOCATION], format!("/v1/studies/{id}").as_str());
    let t0 = Instant::now();
    let status = loop {
        let (_, v) = json_call(app, "GET", &format!("/v1/studies/{id}"), None).await;
        if v["status"] == "finished" || t0.elapsed() > Duration::from_secs(120) {
            break v;
        }
        tokio::time::sleep(Duration::from_millis(20)).await;
    };
    assert_eq!(status["status"], "finished", "{status}");
    let (s, r) = json_call(app, "GET", &format!("/v1/studies/{id}/result"), None).await;
    assert_eq!(s, StatusCode::OK, "{r}");
    (id, status, r)
}

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_grid_reproduces_the_equivalent_threshold_1_plus_eta_n_over_eta_r() {
    let (config, _dir) = config();
    let app = app(config);
    let eta_n = [0.0, 0.005, 0.01, 0.02, 0.03, 0.05, 0.12];
    let study = json!({
        "analysis": "stability",
        "input": jeffcott(0.01, 0.02),
        "parameters": [{"pointer": "/rotor/loss_factor_nonrotating", "values": eta_n}],
        "design": "grid",
        "outputs": ["/threshold", "/whirl", "/no/such/field"]
    });
    let (id, status, r) = run(&app, &study).await;
    assert_eq!(status["samples"], 7);
    assert_eq!(status["progress"], 1.0);
    assert_eq!(
        status["counts"],
        json!({"queued": 0, "running": 0, "done": 7, "failed": 0, "cancelled": 0})
    );
    assert_eq!(r["parameters"], json!(["/rotor/loss_factor_nonrotating"]));
    let samples = r["samples"].as_array().unwrap();
    assert_eq!(samples.len(), 7);
    for (k, (s, n)) in samples.iter().zip(eta_n).enumerate() {
        assert_eq!(s["sample"], k);
        assert_eq!(s["status"], "succeeded");
        assert_eq!(f(&s["parameters"][0]), n);
        assert!(!s["server"].as_str().unwrap().is_empty());
        // The pointer that finds nothing is null.
        assert_eq!(s["outputs"][2], Value::Null);
        let expected = 1.0 + n / 0.01;
        if expected <= 10.0 {
            let t = f(&s["outputs"][0]);
            assert!(
                (t - expected).abs() <= 1e-6 * expected,
                "eta_n {n}: {t} vs {expected}"
            );
            assert_eq!(s["outputs"][1], "forward");
        } else {
            // 13 is past the sweep's 10: no threshold in range.
            assert_eq!(s["outputs"][0], Value::Null, "{s}");
        }
    }
    // Thresholds 1, 1.5, 2, 3, 4, 6 and one null.
    let sum = &r["summary"][0];
    assert_eq!(sum["output"], "/threshold");
    assert_eq!(sum["count"], 6);
    assert!((f(&sum["null_fraction"]) - 1.0 / 7.0).abs() < 1e-15);
    assert!((f(&sum["mean"]) - 17.5 / 6.0).abs() < 1e-5);
    assert!((f(&sum["min"]) - 1.0).abs() < 1e-6 && (f(&sum["max"]) - 6.0).abs() < 6e-6);
    assert!((f(&sum["p50"]) - 2.5).abs() < 1e-5, "{sum}");
    // numpy.percentile([1, 1.5, 2, 3, 4, 6], 95) = 5.5.
    assert!((f(&sum["p95"]) - 5.5).abs() < 1e-5, "{sum}");
    let std = (([1.0f64, 1.5, 2.0, 3.0, 4.0, 6.0]
        .iter()
        .map(|t| (t - 17.5 / 6.0).powi(2))
        .sum::<f64>())
        / 5.0)
        .sqrt();
    assert!((f(&sum["std"]) - std).abs() < 1e-5);
    assert_eq!(r["summary"][2]["count"], 0);
    assert_eq!(r["summary"][2]["mean"], Value::Null);
    assert_eq!(r["summary"][2]["null_fraction"], 1.0);
    // The threshold rises with eta_n: rank correlation 1.
    assert_eq!(
        r["sensitivity"][0]["parameter"],
        "/rotor/loss_factor_nonrotating"
    );
    assert_eq!(r["sensitivity"][0]["spearman"], 1.0);
    assert_eq!(r["sensitivity"][0]["count"], 6);

    // CSV: a header and one row per sample.
    let (s, h, b) = call(
        &app,
        "GET",
        &format!("/v1/studies/{id}/result"),
        None,
        Some("text/csv"),
    )
    .await;
    assert_eq!(s, StatusCode::OK);
    assert_eq!(h[header::CONTENT_TYPE], "text/csv");
    let csv = String::from_utf8(b).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(
        lines[0],
        "sample,status,/rotor/loss_factor_nonrotating,/threshold,/whirl,/no/such/field,server,error"
    );
    assert_eq!(lines.len(), 8);
    assert!(lines[4].starts_with("3,succeeded,0.02,3"), "{}", lines[4]);
    assert!(lines[7].starts_with("6,succeeded,0.12,,,,"), "{}", lines[7]);

    // Plots: the histogram of the first output, and its scatter against the parameter.
    let uri = format!("/v1/studies/{id}/result");
    let (s, h, b) = call(&app, "GET", &uri, None, Some("image/svg+xml")).await;
    assert_eq!(
        (s, h[header::CONTENT_TYPE].to_str().unwrap()),
        (StatusCode::OK, "image/svg+xml")
    );
    let svg = String::from_utf8(b).unwrap();
    assert!(
        svg.starts_with("<svg") && svg.contains("/threshold: 6 samples, 1 not numbers"),
        "{svg}"
    );
    let scatter = format!("{uri}?against=/rotor/loss_factor_nonrotating");
    let (s, _, b) = call(&app, "GET", &scatter, None, Some("image/svg+xml")).await;
    assert_eq!(s, StatusCode::OK);
    assert_eq!(String::from_utf8(b).unwrap().matches("<circle").count(), 6);
    let (s, _, b) = call(
        &app,
        "GET",
        &format!("{uri}?against=/rotor/mass"),
        None,
        Some("image/svg+xml"),
    )
    .await;
    assert_eq!(s, StatusCode::UNPROCESSABLE_ENTITY);
    let v: Value = serde_json::from_slice(&b).unwrap();
    assert_eq!(v["errors"][0]["path"], "against", "{v}");
    // A finished study cannot be cancelled.
    let (s, _) = json_call(&app, "DELETE", &format!("/v1/studies/{id}"), None).await;
    assert_eq!(s, StatusCode::CONFLICT);
    // Samples are not single jobs: the job listing does not show them.
    let (_, jobs) = json_call(&app, "GET", "/v1/jobs", None).await;
    assert_eq!(jobs["jobs"], json!([]));
}

/// A random study over both loss factors of the equivalent Jeffcott rotor.
fn random_study(design: &str, samples: u64, seed: u64) -> Value {
    json!({
        "analysis": "stability",
        "input": jeffcott(0.01, 0.02),
        "parameters": [
            {"pointer": "/rotor/loss_factor_rotating",
             "distribution": {"type": "uniform", "low": 0.005, "high": 0.02}},
            {"pointer": "/rotor/loss_factor_nonrotating",
             "distribution": {"type": "lognormal", "mu": -4.6, "sigma": 0.3, "max": 0.04}}
        ],
        "design": design,
        "samples": samples,
        "seed": seed,
        "outputs": ["/threshold"]
    })
}

fn params(r: &Value) -> Vec<Vec<f64>> {
    r["samples"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["parameters"].as_array().unwrap().iter().map(f).collect())
        .collect()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn random_designs_repeat_with_their_seed_and_the_hypercube_is_stratified() {
    let (config, _dir) = config();
    let app = app(config);
    for design in ["monte-carlo", "latin-hypercube"] {
        let n = 40;
        let (_, _, a) = run(&app, &random_study(design, n, 7)).await;
        let (_, _, b) = run(&app, &random_study(design, n, 7)).await;
        let (_, _, c) = run(&app, &random_study(design, n, 8)).await;
        assert_eq!(a["seed"], 7);
        assert_eq!(
            params(&a),
            params(&b),
            "{design}: the same seed, the same samples"
        );
        assert_eq!(a["samples"], b["samples"]);
        assert_ne!(
            params(&a),
            params(&c),
            "{design}: another seed, other samples"
        );
        let p = params(&a);
        assert_eq!(p.len(), n as usize);
        for (s, x) in a["samples"].as_array().unwrap().iter().zip(&p) {
            let (eta_r, eta_n) = (x[0], x[1]);
            assert!((0.005..=0.02).contains(&eta_r), "{x:?}");
            assert!(eta_n > 0.0 && eta_n <= 0.04, "truncated at 0.04: {x:?}");
            // Every sample is the closed form, or null past the sweep's 10.
            let expected = 1.0 + eta_n / eta_r;
            match s["outputs"][0].as_f64() {
                Some(t) => assert!((t - expected).abs() <= 1e-6 * expected, "{t} vs {expected}"),
                None => assert!(expected > 10.0, "{s}"),
            }
        }
        let sens = &a["sensitivity"];
        assert!(
            f(&sens[0]["spearman"]) < -0.3,
            "threshold falls with eta_r: {sens}"
        );
        assert!(
            f(&sens[1]["spearman"]) > 0.3,
            "threshold rises with eta_n: {sens}"
        );
        if design == "latin-hypercube" {
            // One sample in each of the n equal strata of eta_r's range.
            let mut seen = vec![0; n as usize];
            for x in &p {
                let k = ((x[0] - 0.005) / 0.015 * n as f64).floor() as usize;
                seen[k.min(n as usize - 1)] += 1;
            }
            assert!(seen.iter().all(|&c| c == 1), "strata of eta_r: {seen:?}");
        }
    }
}

async fn refused(app: &Router, study: &Value) -> Value {
    let (s, v) = json_call(app, "POST", "/v1/studies", Some(study)).await;
    assert_eq!(s, StatusCode::UNPROCESSABLE_ENTITY, "{v}");
    v
}

fn paths(v: &Value) -> Vec<String> {
    v["errors"]
        .as_array()
        .unwrap()
        .iter()
        .map(|e| e["path"].as_str().unwrap().to_string())
        .collect()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn bad_pointers_designs_and_samples_are_refused_before_any_sample_is_queued() {
    let (config, dir) = config();
    let app = app(Config {
        max_study_samples: 100,
        ..config
    });
    let grid = |pointer: &str, values: Value| {
        json!({"analysis": "stability", "input": jeffcott(0.01, 0.02),
               "parameters": [{"pointer": "/rotor/mass", "values": [1, 2]},
                              {"pointer": pointer, "values": values}],
               "design": "grid", "outputs": ["/threshold"]})
    };
    let v = refused(&app, &grid("/rotor/loss_factor_nonrotatin", json!([0.01]))).await;
    assert_eq!(paths(&v), ["parameters[1].pointer"]);
    assert!(
        v["errors"][0]["message"]
            .as_str()
            .unwrap()
            .contains("names nothing in `input`"),
        "{v}"
    );
    let v = refused(&app, &grid("rotor/mass", json!([0.01]))).await;
    assert_eq!(paths(&v), ["parameters[1].pointer"]);
    let v = refused(&app, &grid("/rotor/mass", json!([1]))).await;
    assert_eq!(
        paths(&v),
        ["parameters[1].pointer"],
        "the same parameter twice"
    );
    let mut bad_output = grid("/rotor/stiffness", json!([1]));
    bad_output["outputs"] = json!(["/threshold", "threshold"]);
    assert_eq!(paths(&refused(&app, &bad_output).await), ["outputs[1]"]);
    // A value the analysis refuses: sample 1 (mass 1, stiffness -1) is named with its field.
    let v = refused(&app, &grid("/rotor/stiffness", json!([1, -1]))).await;
    assert_eq!(paths(&v)[0], "samples[1].input.rotor.stiffness", "{v}");
    assert!(paths(&v).contains(&"samples[1]".to_string()), "{v}");
    // Too many samples (the limit is 100 here): 11 x 11 = 121.
    let many: Vec<f64> = (1..=11).map(f64::from).collect();
    let mut big = grid("/rotor/stiffness", json!(many));
    big["parameters"][0]["values"] = json!(many);
    assert_eq!(paths(&refused(&app, &big).await), ["parameters"]);
    let v = refused(&app, &random_study("monte-carlo", 101, 1)).await;
    assert_eq!(paths(&v), ["samples"]);
    // A design and parameters that do not fit, and a distribution's own fields.
    let mut mixed = random_study("grid", 10, 1);
    mixed["samples"] = Value::Null;
    assert_eq!(
        paths(&refused(&app, &mixed).await),
        ["parameters[0]", "parameters[1]"]
    );
    let mut bad = random_study("monte-carlo", 10, 1);
    bad["parameters"][0]["distribution"] = json!({"type": "normal", "mean": 0.01, "std": -1});
    bad["parameters"][1]["distribution"] = json!({"type": "uniform", "low": 0.01});
    assert_eq!(
        paths(&refused(&app, &bad).await),
        [
            "parameters[0].distribution.std",
            "parameters[1].distribution.high"
        ]
    );
    bad["parameters"][1]["distribution"] =
        json!({"type": "normal", "mean": 0, "std": 1, "min": 40, "max": 50});
    assert_eq!(
        paths(&refused(&app, &bad).await)[1],
        "parameters[1].distribution.min"
    );
    // Nothing was queued: the store (connected at its first use) was never even opened.
    assert!(!dir.path().join("whirl.sqlite").exists());
    let (s, _) = json_call(
        &app,
        "GET",
        "/v1/studies/01890a5d-ac96-774b-bcce-b302099a8057",
        None,
    )
    .await;
    assert_eq!(s, StatusCode::NOT_FOUND);
    let (s, _) = json_call(&app, "GET", "/v1/studies/nonsense", None).await;
    assert_eq!(s, StatusCode::NOT_FOUND);
    // The samples' inputs and estimated results must fit the bytes of results kept: 200
    // Jeffcott samples do not fit 64 KiB.
    let (small, _dir2) = self::config();
    let app = whirl::service::app(Config {
        job_result_bytes: 64 << 10,
        ..small
    });
    let values: Vec<f64> = (0..100).map(|i| 0.0002 * f64::from(i)).collect();
    let v = refused(&app, &grid("/rotor/loss_factor_nonrotating", json!(values))).await;
    assert_eq!(paths(&v), ["samples"]);
    let m = v["errors"][0]["message"].as_str().unwrap();
    assert!(
        m.starts_with("200 samples whose inputs and results")
            && m.contains("WHIRL_JOB_RESULT_BYTES"),
        "{m}"
    );
}

/// A Campbell sweep of a few hundred ms: a sample that is still queued or running for a while.
fn slow_input(speeds: usize) -> Value {
    let path = format!(
        "{}/examples/compressor-hysteretic.campbell.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let mut input: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    input["damping"] = json!({"model": "viscous"});
    input["speeds"] = json!({"start": 0.0, "stop": 1500.0, "count": speeds});
    input["modal_reduction"] = json!(false);
    input
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn single_jobs_go_first_and_a_cancelled_study_stops_its_samples() {
    let (config, _dir) = config();
    let app = app(Config {
        workers: 1,
        ..config
    });
    let study = json!({
        "analysis": "campbell",
        "input": slow_input(8),
        "parameters": [{"pointer": "/rotor/supports/0/damping", "values": [1000, 1100, 1200, 1300, 1400, 1500, 1600, 1700, 1800, 1900]}],
        "design": "grid",
        "outputs": ["/speeds/0"]
    });
    let (s, v) = json_call(&app, "POST", "/v1/studies", Some(&study)).await;
    assert_eq!(s, StatusCode::ACCEPTED, "{v}");
    let id = v["id"].as_str().unwrap().to_string();
    // A single job submitted now runs before the study's remaining samples.
    let job = json!({"analysis": "campbell", "input": slow_input(8)});
    let (s, j) = json_call(&app, "POST", "/v1/jobs", Some(&job)).await;
    assert_eq!(s, StatusCode::ACCEPTED, "{j}");
    let jid = j["id"].as_str().unwrap();
    let t0 = Instant::now();
    loop {
        let (_, j) = json_call(&app, "GET", &format!("/v1/jobs/{jid}"), None).await;
        if j["status"] == "succeeded" || t0.elapsed() > Duration::from_secs(60) {
            assert_eq!(j["status"], "succeeded", "{j}");
            break;
        }
        tokio::time::sleep(Duration::from_millis(10)).await;
    }
    let (_, st) = json_call(&app, "GET", &format!("/v1/studies/{id}"), None).await;
    let c = &st["counts"];
    assert!(
        f(&c["queued"]) >= 7.0,
        "the job ran before most samples: {st}"
    );
    assert_eq!(st["status"], "running", "{st}");
    let (s, r) = json_call(&app, "GET", &format!("/v1/studies/{id}/result"), None).await;
    assert_eq!(s, StatusCode::CONFLICT, "{r}");

    // Cancelled: its queued and running samples with it.
    let (s, st) = json_call(&app, "DELETE", &format!("/v1/studies/{id}"), None).await;
    assert_eq!(s, StatusCode::OK, "{st}");
    assert_eq!(st["status"], "cancelled");
    assert_eq!(st["counts"]["queued"], 0);
    assert_eq!(st["counts"]["running"], 0);
    assert!(f(&st["counts"]["cancelled"]) >= 7.0, "{st}");
    assert_eq!(st["error"]["status"], 409);
    let (s, r) = json_call(&app, "GET", &format!("/v1/studies/{id}/result"), None).await;
    assert_eq!(s, StatusCode::OK, "{r}");
    let cancelled: Vec<&Value> = r["samples"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|s| s["status"] == "cancelled")
        .collect();
    assert_eq!(cancelled.len() as f64, f(&st["counts"]["cancelled"]));
    assert!(cancelled.iter().all(|s| {
        s["outputs"][0].is_null()
            && s["error"]["detail"]
                .as_str()
                .unwrap()
                .contains("study was cancelled")
    }));
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn failed_samples_keep_their_error_and_a_study_is_forgotten_with_its_samples() {
    let (config, _dir) = config();
    // Samples past the job time limit fail (once: not retried); few finished jobs kept, a
    // short retention.
    let app = app(Config {
        job_time_limit: Duration::from_millis(30),
        max_finished_jobs: 2,
        job_retention: Duration::from_secs(1),
        job_lease: Duration::from_secs(1),
        ..config
    });
    let slow = json!({
        "analysis": "campbell",
        "input": slow_input(200),
        "parameters": [{"pointer": "/rotor/supports/0/damping", "values": [1000, 2000, 3000]}],
        "design": "grid",
        "outputs": ["/speeds/0"]
    });
    let (id, status, r) = run(&app, &slow).await;
    assert_eq!(status["counts"]["failed"], 3, "{status}");
    assert_eq!(status["progress"], 1.0);
    for s in r["samples"].as_array().unwrap() {
        assert_eq!(s["status"], "failed");
        assert_eq!(s["outputs"], json!([null]));
        assert!(
            s["error"]["detail"]
                .as_str()
                .unwrap()
                .contains("time limit"),
            "{s}"
        );
    }
    assert_eq!(r["summary"][0]["null_fraction"], 1.0);
    assert_eq!(r["summary"][0]["count"], 0);
    // A grid of 7 samples outlives the bound of 2 finished jobs: samples are the study's.
    let quick = json!({
        "analysis": "stability",
        "input": jeffcott(0.01, 0.02),
        "parameters": [{"pointer": "/rotor/loss_factor_nonrotating", "values": [0.0, 0.01, 0.02, 0.03, 0.04, 0.05, 0.06]}],
        "design": "grid",
        "outputs": ["/threshold"]
    });
    let (quick_id, _, r) = run(&app, &quick).await;
    let thresholds: Vec<f64> = r["samples"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| f(&s["outputs"][0]))
        .collect();
    for (t, expected) in thresholds.iter().zip([1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0]) {
        assert!((t - expected).abs() <= 1e-6 * expected, "{t} vs {expected}");
    }
    tokio::time::sleep(Duration::from_millis(600)).await;
    let (s, r) = json_call(&app, "GET", &format!("/v1/studies/{quick_id}/result"), None).await;
    assert_eq!(s, StatusCode::OK, "{r}");
    assert_eq!(
        r["samples"].as_array().unwrap().len(),
        7,
        "no sample purged by the job bound"
    );
    // Past the retention, a finished study goes with its samples.
    let t0 = Instant::now();
    loop {
        let (s, _) = json_call(&app, "GET", &format!("/v1/studies/{id}"), None).await;
        if s == StatusCode::NOT_FOUND {
            break;
        }
        assert!(
            t0.elapsed() < Duration::from_secs(10),
            "study {id} still kept"
        );
        tokio::time::sleep(Duration::from_millis(100)).await;
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_study_of_many_samples_is_read_back_whole_and_in_order() {
    let (config, _dir) = config();
    let app = app(config);
    // 15 x 30 = 450 samples: the result is read from the store in pages of 200.
    let eta_r: Vec<f64> = (1..=15).map(|i| 0.002 * f64::from(i)).collect();
    // (Steps that put no threshold at the sweep's end, 10, where it is found or not.)
    let eta_n: Vec<f64> = (0..30).map(|i| 0.0011 * f64::from(i)).collect();
    let study = json!({
        "analysis": "stability",
        "input": jeffcott(0.01, 0.02),
        "parameters": [
            {"pointer": "/rotor/loss_factor_rotating", "values": eta_r},
            {"pointer": "/rotor/loss_factor_nonrotating", "values": eta_n}
        ],
        "design": "grid",
        "outputs": ["/threshold"]
    });
    let (_, _, r) = run(&app, &study).await;
    let samples = r["samples"].as_array().unwrap();
    assert_eq!(samples.len(), 450);
    let mut nulls = 0;
    for (k, s) in samples.iter().enumerate() {
        assert_eq!(s["sample"], k);
        let (r_, n) = (eta_r[k / 30], eta_n[k % 30]);
        // (serde_json reads a decimal to within an ulp: not always the f64 written.)
        let (pr, pn) = (f(&s["parameters"][0]), f(&s["parameters"][1]));
        assert!(
            (pr - r_).abs() <= 1e-15 * r_ && (pn - n).abs() <= 1e-15 * n.max(1e-3),
            "{s}"
        );
        let expected = 1.0 + n / r_;
        match s["outputs"][0].as_f64() {
            Some(t) => assert!(
                (t - expected).abs() <= 1e-6 * expected,
                "{k}: {t} vs {expected}"
            ),
            None => {
                assert!(expected > 10.0, "{k}: {s}");
                nulls += 1;
            }
        }
    }
    // No threshold in range where 1 + n/r > 10 (the sweep ends at 10).
    let expected_nulls = eta_r
        .iter()
        .flat_map(|r_| eta_n.iter().map(move |n| 1.0 + n / r_))
        .filter(|t| *t > 10.0)
        .count();
    assert_eq!(nulls, expected_nulls);
    assert_eq!(r["summary"][0]["count"], 450 - expected_nulls);
    assert!(
        f(&r["sensitivity"][0]["spearman"]) < -0.3,
        "{}",
        r["sensitivity"]
    );
    assert!(
        f(&r["sensitivity"][1]["spearman"]) > 0.3,
        "{}",
        r["sensitivity"]
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_samples_of_all_studies_waiting_are_bounded() {
    let (config, _dir) = config();
    let app = app(Config {
        workers: 1,
        study_queue: 12,
        ..config
    });
    let study = |n: usize| {
        json!({
            "analysis": "campbell",
            "input": slow_input(8),
            "parameters": [{"pointer": "/rotor/supports/0/damping",
                            "values": (0..n).map(|i| 1000 + 100 * i).collect::<Vec<_>>()}],
            "design": "grid",
            "outputs": ["/speeds/0"]
        })
    };
    // Larger than the queue could ever hold: the request's fault.
    let v = refused(&app, &study(13)).await;
    assert_eq!(paths(&v), ["samples"], "{v}");
    assert!(
        v["errors"][0]["message"]
            .as_str()
            .unwrap()
            .contains("WHIRL_STUDY_QUEUE"),
        "{v}"
    );
    let (s, first) = json_call(&app, "POST", "/v1/studies", Some(&study(10))).await;
    assert_eq!(s, StatusCode::ACCEPTED, "{first}");
    // At least 8 of its samples still wait (one worker, slow samples): 8 + 5 > 12.
    let (s, h, body) = call(&app, "POST", "/v1/studies", Some(&study(5)), None).await;
    assert_eq!(s, StatusCode::SERVICE_UNAVAILABLE);
    assert!(h.contains_key(header::RETRY_AFTER));
    let v: Value = serde_json::from_slice(&body).unwrap();
    assert_eq!(v["status"], 503, "{v}");
    // Once the first is cancelled, the queue has room again.
    let id = first["id"].as_str().unwrap();
    let (s, _) = json_call(&app, "DELETE", &format!("/v1/studies/{id}"), None).await;
    assert_eq!(s, StatusCode::OK);
    let (s, second) = json_call(&app, "POST", "/v1/studies", Some(&study(5))).await;
    assert_eq!(s, StatusCode::ACCEPTED, "{second}");
    let id = second["id"].as_str().unwrap();
    let (s, _) = json_call(&app, "DELETE", &format!("/v1/studies/{id}"), None).await;
    assert_eq!(s, StatusCode::OK);
}
