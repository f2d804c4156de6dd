//! The service driven in process (no socket): the paper's numbers through HTTP, every error
//! class, the OpenAPI document against the committed one, and the bundled examples.

use crate::common;

use axum::Router;
use axum::body::Body;
use axum::http::{Request, StatusCode, header};
use common::{assert_printed, matrix};
use http_body_util::BodyExt;
use serde_json::{Value, json};
use tower::ServiceExt;
use whirl::service::{Config, app};

fn test_app() -> Router {
    app(Config::default())
}

async fn send(
    app: Router,
    method: &str,
    uri: &str,
    body: Option<Vec<u8>>,
) -> (StatusCode, String, Vec<u8>) {
    let req = Request::builder()
        .method(method)
        .uri(uri)
        .header(header::CONTENT_TYPE, "application/json")
        .body(body.map(Body::from).unwrap_or_else(Body::empty))
        .unwrap();
    let resp = app.oneshot(req).await.unwrap();
    let status = resp.status();
    let ctype = resp
        .headers()
        .get(header::CONTENT_TYPE)
        .map(|v| v.to_str().unwrap().to_string())
        .unwrap_or_default();
    let bytes = resp
        .into_body()
        .collect()
        .await
        .unwrap()
        .to_bytes()
        .to_vec();
    (status, ctype, bytes)
}

async fn post(uri: &str, body: Value) -> (StatusCode, Value) {
    let (status, _, bytes) =
        send(test_app(), "POST", uri, Some(body.to_string().into_bytes())).await;
    (status, serde_json::from_slice(&bytes).expect("JSON body"))
}

fn nondimensional(eta_r: f64, eta_n: f64) -> Value {
    json!({"type": "jeffcott", "mass": 1.0, "stiffness": 1.0,
           "loss_factor_rotating": eta_r, "loss_factor_nonrotating": eta_n})
}

fn poles_of<'a>(v: &'a Value, whirl: &str) -> Vec<&'a Value> {
    v["poles"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|p| p["whirl"] == whirl)
        .collect()
}

fn num(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

#[tokio::test]
async fn nvd_jeffcott_poles_through_http_match_the_paper() {
    let nvd = json!({"model": "nonviscous", "rotating": {"branches": 4, "spacing": 10}});
    let (status, v) = post(
        "/v1/modal",
        json!({"rotor": nondimensional(0.01, 0.0), "damping": nvd, "speed": 0.0}),
    )
    .await;
    assert_eq!(status, StatusCode::OK, "{v}");
    let f = poles_of(&v, "forward");
    assert_printed(num(&f[0]["decay_rate"]), "-0.0044", "forward decay rate");
    assert_printed(num(&f[0]["frequency"]), "1.0152", "forward frequency");
    let internal: Vec<f64> = poles_of(&v, "internal")
        .iter()
        .map(|p| num(&p["decay_rate"]))
        .collect();
    for (x, p) in internal
        .iter()
        .zip(["-31.6222", "-3.1584", "-0.3124", "-0.0311"])
    {
        assert_printed(*x, p, "internal pole");
    }
    assert_eq!(v["states"], 6);
    assert_eq!(v["natural_frequencies"], json!([1.0]));

    let (_, v) = post(
        "/v1/modal",
        json!({"rotor": nondimensional(0.01, 0.0), "damping": nvd, "speed": 4.0}),
    )
    .await;
    let f = poles_of(&v, "forward");
    let b = poles_of(&v, "backward");
    assert_printed(num(&f[0]["decay_rate"]), "0.0049", "forward decay rate");
    assert_printed(num(&f[0]["frequency"]), "1.0183", "forward frequency");
    assert_printed(num(&b[0]["decay_rate"]), "-0.0048", "backward decay rate");
    assert_printed(num(&b[0]["frequency"]), "-1.0202", "backward frequency");
    let internal = poles_of(&v, "internal");
    let printed = [
        ("-31.6223", "4.0001"),
        ("-3.1626", "4.0016"),
        ("-0.3165", "4.0000"),
        ("-0.0317", "4.0000"),
    ];
    for (p, (re, im)) in internal.iter().zip(printed) {
        assert_printed(num(&p["decay_rate"]), re, "internal decay rate");
        assert_printed(num(&p["frequency"]), im, "internal frequency");
    }
    // Derived quantities are consistent with the pole.
    let (s, w) = (num(&f[0]["decay_rate"]), num(&f[0]["frequency"]));
    assert!((num(&f[0]["damping_ratio"]) + s / s.hypot(w)).abs() < 1e-15);
    assert!((num(&f[0]["log_decrement"]) + 2.0 * std::f64::consts::PI * s / w).abs() < 1e-14);
}

#[tokio::test]
async fn stability_through_http_gives_eq_10_and_the_range() {
    let (status, v) = post(
        "/v1/stability",
        json!({"rotor": nondimensional(0.01, 0.025), "damping": {"model": "equivalent"},
               "speeds": {"start": 0.5, "stop": 6.0, "count": 12}}),
    )
    .await;
    assert_eq!(status, StatusCode::OK, "{v}");
    assert!((num(&v["threshold"]) - 3.5).abs() <= 1e-6 * 3.5, "{v}");
    assert_eq!(v["whirl"], "forward");
    assert_eq!(v["mode"], 1);
    assert_eq!(v["range"], json!([0.5, 6.0]));
    // Hysteretic with eta_n > eta_r: stable at all speeds of the range.
    let (_, v) = post(
        "/v1/stability",
        json!({"rotor": nondimensional(0.01, 0.025), "damping": {"model": "hysteretic"},
               "speeds": [0.0, 1.0, 2.0, 6.0]}),
    )
    .await;
    assert_eq!(v["threshold"], Value::Null);
}

#[tokio::test]
async fn campbell_through_http_has_tracked_branches_critical_speed_and_threshold() {
    let (status, v) = post(
        "/v1/campbell",
        json!({"rotor": nondimensional(0.01, 0.0), "damping": {"model": "hysteretic"},
               "speeds": {"start": 0.0, "stop": 2.0, "count": 41}}),
    )
    .await;
    assert_eq!(status, StatusCode::OK, "{v}");
    let branches = v["branches"].as_array().unwrap();
    assert_eq!(branches.len(), 2);
    let fwd = branches.iter().find(|b| b["whirl"] == "forward").unwrap();
    assert_eq!(fwd["mode"], 1);
    let d = fwd["decay_rate"].as_array().unwrap();
    // H: -eta_r/2 below the critical speed, +eta_r/2 above (eta_n = 0): a step, unstable.
    assert!((num(&d[10]) + 0.005).abs() < 1e-6);
    assert!((num(&d[30]) - 0.005).abs() < 1e-6);
    let crit = v["critical_speeds"].as_array().unwrap();
    assert_eq!(crit.len(), 1);
    assert!((num(&crit[0]) - 1.0).abs() < 1e-4);
    // The threshold of the H Jeffcott with eta_n = 0 coincides with the critical speed.
    assert!((num(&v["threshold"]) - 1.0).abs() < 1e-4);
}

async fn problem(uri: &str, body: Vec<u8>) -> (StatusCode, Value) {
    let (status, ctype, bytes) = send(test_app(), "POST", uri, Some(body)).await;
    assert_eq!(ctype, "application/problem+json", "status {status}");
    let v: Value = serde_json::from_slice(&bytes).unwrap();
    assert_eq!(v["status"], status.as_u16());
    for k in ["type", "title", "detail"] {
        assert!(v[k].is_string(), "{k} in {v}");
    }
    (status, v)
}

fn paths(v: &Value) -> Vec<String> {
    v["errors"]
        .as_array()
        .unwrap()
        .iter()
        .map(|e| e["path"].as_str().unwrap().to_string())
        .collect()
}

#[tokio::test]
async fn malformed_json_is_400() {
    let (status, _) = problem("/v1/modal", b"{\"rotor\": {\"type\": \"jeffcott\"".to_vec()).await;
    assert_eq!(status, StatusCode::BAD_REQUEST);
    let (status, _) = problem("/v1/modal", b"{} trailing".to_vec()).await;
    assert_eq!(status, StatusCode::BAD_REQUEST);
    let (status, _) = problem("/v1/modal", b"{\"speed\": NaN}".to_vec()).await;
    assert_eq!(status, StatusCode::BAD_REQUEST, "NaN is not JSON");
}

#[tokio::test]
async fn invalid_values_are_422_with_the_path_of_each_field() {
    let body = json!({
        "rotor": {"type": "jeffcott", "mass": 0.0, "stiffness": 1.0,
                  "loss_factor_rotating": 1.0, "loss_factor_nonrotating": -0.1,
                  "damping_rotating": -1.0},
        "damping": {"model": "nonviscous", "rotating": {"branches": 13},
                    "nonrotating": {"branches": 0, "spacing": 2}},
        "speeds": {"start": 0.0, "stop": 1.0, "count": 1}
    });
    let (status, v) = problem("/v1/campbell", body.to_string().into_bytes()).await;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    let p = paths(&v);
    for expected in [
        "rotor.mass",
        "rotor.loss_factor_rotating",
        "rotor.loss_factor_nonrotating",
        "rotor.damping_rotating",
        "damping.rotating.branches",
        "damping.nonrotating.branches",
        "speeds.count",
    ] {
        assert!(
            p.iter().any(|x| x == expected),
            "{expected} missing from {p:?}"
        );
    }
}

#[tokio::test]
async fn each_error_class_names_its_field() {
    let cases: Vec<(&str, Value, &str)> = vec![
        (
            "/v1/modal",
            json!({"rotor": {"type": "jeffcott", "mass": -2.0, "stiffness": 1.0}, "damping": {"model": "viscous"}}),
            "rotor.mass",
        ),
        (
            "/v1/modal",
            json!({"rotor": nondimensional(1.5, 0.0), "damping": {"model": "viscous"}}),
            "rotor.loss_factor_rotating",
        ),
        (
            "/v1/modal",
            json!({"rotor": nondimensional(0.0, 0.0), "damping": {"model": "nonviscous", "rotating": {"branches": 0}}}),
            "damping.rotating.branches",
        ),
        (
            "/v1/modal",
            json!({"rotor": nondimensional(0.0, 0.0), "damping": {"model": "nonviscous", "nonrotating": {"spacing": 2.0}}}),
            "damping.nonrotating.spacing",
        ),
        (
            "/v1/modal",
            json!({"rotor": nondimensional(0.0, 0.0), "damping": {"model": "nonviscous", "rotating": {"branches": 2, "nu": [1.0]}}}),
            "damping.rotating.nu",
        ),
        (
            "/v1/modal",
            json!({"rotor": nondimensional(0.0, 0.0), "damping": {"model": "equivalent", "modes": 2}}),
            "damping.modes",
        ),
        (
            "/v1/modal",
            json!({"rotor": nondimensional(0.0, 0.0), "damping": {"model": "viscous"}, "speed": -1.0}),
            "speed",
        ),
        (
            "/v1/modal",
            json!({"rotor": {"type": "jeffcott", "mass": "heavy", "stiffness": 1.0}, "damping": {"model": "viscous"}}),
            "rotor.mass",
        ),
        (
            "/v1/modal",
            json!({"rotor": {"type": "jeffcott", "mass": 1.0, "stiffnes": 1.0}, "damping": {"model": "viscous"}}),
            "rotor.stiffnes",
        ),
        (
            "/v1/modal",
            json!({"rotor": {"type": "disk"}, "damping": {"model": "viscous"}}),
            "rotor.type",
        ),
        (
            "/v1/modal",
            json!({"rotor": nondimensional(0.0, 0.0), "damping": {"model": "magic"}}),
            "damping.model",
        ),
        (
            "/v1/campbell",
            json!({"rotor": nondimensional(0.0, 0.0), "damping": {"model": "viscous"}, "speeds": {"start": 2.0, "stop": 1.0, "count": 5}}),
            "speeds.stop",
        ),
        (
            "/v1/campbell",
            json!({"rotor": nondimensional(0.0, 0.0), "damping": {"model": "viscous"}, "speeds": [0.0, 2.0, 1.0]}),
            "speeds[2]",
        ),
        (
            "/v1/campbell",
            json!({"rotor": nondimensional(0.0, 0.0), "damping": {"model": "viscous"}, "speeds": {"start": 0.0, "stop": 1.0, "count": 1000000}}),
            "speeds.count",
        ),
        (
            "/v1/stability",
            json!({"rotor": nondimensional(0.0, 0.0), "damping": {"model": "viscous"}, "speeds": [1.0]}),
            "speeds",
        ),
    ];
    for (uri, body, path) in cases {
        let (status, v) = problem(uri, body.to_string().into_bytes()).await;
        assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{body}: {v}");
        assert!(paths(&v).iter().any(|p| p == path), "{path} not in {v}");
    }
    // A number that is valid JSON but not a finite double.
    let raw = br#"{"rotor": {"type": "jeffcott", "mass": 1e999, "stiffness": 1}, "damping": {"model": "viscous"}}"#;
    let (status, v) = problem("/v1/modal", raw.to_vec()).await;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{v}");
}

#[tokio::test]
async fn oversized_body_is_413_and_unknown_path_is_404() {
    let small = app(Config {
        max_body_bytes: 1024,
        ..Config::default()
    });
    let big = format!("{{\"pad\": \"{}\"}}", "x".repeat(4096));
    let (status, ctype, _) = send(small, "POST", "/v1/modal", Some(big.into_bytes())).await;
    assert_eq!(status, StatusCode::PAYLOAD_TOO_LARGE);
    assert_eq!(ctype, "application/problem+json");
    let (status, ctype, _) = send(test_app(), "GET", "/v2/everything", None).await;
    assert_eq!(status, StatusCode::NOT_FOUND);
    assert_eq!(ctype, "application/problem+json");
}

#[tokio::test]
async fn no_nan_leaks_when_the_numbers_overflow() {
    // Valid fields whose product overflows: an error, never a NaN in a 200.
    let body = json!({"rotor": {"type": "jeffcott", "mass": 1e-300, "stiffness": 1e300}, "damping": {"model": "viscous"}});
    let (status, _, bytes) = send(
        test_app(),
        "POST",
        "/v1/modal",
        Some(body.to_string().into_bytes()),
    )
    .await;
    let text = String::from_utf8(bytes).unwrap();
    assert!(
        !text.contains("NaN") && !text.contains("null,\"frequency\""),
        "{text}"
    );
    assert!(
        status == StatusCode::UNPROCESSABLE_ENTITY || status == StatusCode::OK,
        "{status}: {text}"
    );
}

#[tokio::test]
async fn health_readiness_and_docs() {
    let (status, _, body) = send(test_app(), "GET", "/healthz", None).await;
    assert_eq!(status, StatusCode::OK);
    assert_eq!(
        serde_json::from_slice::<Value>(&body).unwrap(),
        json!({"status": "ok"})
    );
    // Readiness asks the job store: one of this test's own.
    let store = tempfile::tempdir().unwrap();
    let ready = app(Config {
        data_dir: store.path().to_path_buf(),
        ..Config::default()
    });
    let (status, _, _) = send(ready, "GET", "/readyz", None).await;
    assert_eq!(status, StatusCode::OK);
    let (status, ctype, body) = send(test_app(), "GET", "/docs/", None).await;
    assert_eq!(status, StatusCode::OK);
    assert!(ctype.starts_with("text/html"), "{ctype}");
    assert!(String::from_utf8_lossy(&body).contains("swagger"));
    // The UI's assets are served from the binary: no internet needed.
    let (status, _, body) = send(test_app(), "GET", "/docs/swagger-ui-bundle.js", None).await;
    assert_eq!(status, StatusCode::OK);
    assert!(body.len() > 100_000);
}

#[tokio::test]
async fn served_openapi_is_the_committed_document() {
    let (status, _, body) = send(test_app(), "GET", "/openapi.json", None).await;
    assert_eq!(status, StatusCode::OK);
    let served: Value = serde_json::from_slice(&body).unwrap();
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/openapi/openapi.json");
    let committed: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    assert!(
        served == committed,
        "openapi/openapi.json is stale: regenerate it with \
         `cargo run --release -- openapi > openapi/openapi.json`"
    );
    assert_eq!(served["openapi"], "3.1.0");
    for p in [
        "/healthz",
        "/readyz",
        "/v1/modal",
        "/v1/campbell",
        "/v1/stability",
    ] {
        assert!(served["paths"][p].is_object(), "{p} missing");
    }
}

#[tokio::test]
async fn every_bundled_example_runs() {
    // examples/<name>.<endpoint>.json is POSTed to /v1/<endpoint>, as in the README.
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/examples");
    let mut count = 0;
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_str().unwrap().to_string();
        let Some(stem) = name.strip_suffix(".json") else {
            continue;
        };
        let endpoint = stem.rsplit('.').next().unwrap();
        let body: Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
        let (status, v) = post(&format!("/v1/{endpoint}"), body).await;
        assert_eq!(status, StatusCode::OK, "{name}: {v}");
        count += 1;
    }
    assert!(count >= 5);
}

#[tokio::test]
async fn a_bounded_campbell_reports_its_modal_reduction() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/compressor-nvd.campbell.json"
    );
    let mut body: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    body["speeds"] = json!({"start": 0, "stop": 1500, "count": 4});
    let (status, v) = post("/v1/campbell", body.clone()).await;
    assert_eq!(status, StatusCode::OK, "{v}");
    let r = &v["reduction"];
    // The 8 modes below twice the 6000 rad/s bound, with their static corrections.
    assert_eq!(r["modes"], 8, "{r}");
    assert!(r["vectors"].as_u64().unwrap() > 8, "{r}");
    assert!(
        2 * r["states"].as_u64().unwrap() <= r["full_states"].as_u64().unwrap(),
        "{r}"
    );
    assert_eq!(num(&r["checked_speed"]), 1500.0);
    assert!(num(&r["max_relative_error"]) <= 1e-6, "{r}");
    body["modal_reduction"] = json!(false);
    let (status, full) = post("/v1/campbell", body).await;
    assert_eq!(status, StatusCode::OK, "{full}");
    assert!(full["reduction"].is_null());
    assert_eq!(
        full["branches"].as_array().unwrap().len(),
        v["branches"].as_array().unwrap().len()
    );
}

#[tokio::test]
async fn damping_matrices_of_the_nvd_jeffcott_are_eqs_20_to_22() {
    let (status, v) = post(
        "/v1/damping",
        json!({"rotor": nondimensional(0.01, 0.0),
               "damping": {"model": "nonviscous", "rotating": {"branches": 4}}}),
    )
    .await;
    assert_eq!(status, StatusCode::OK, "{v}");
    let gamma = [1.700088, 1.360036, 1.360036, 1.700088];
    let d: Vec<f64> = (1..=4)
        .map(|j| 10f64.powf((2.0 * j as f64 - 5.0) / 2.0))
        .collect();
    let so = &v["second_order"];
    let k = matrix(&so["stiffness"]);
    let c_r = matrix(&so["damping_rotating"]);
    let m = matrix(&so["mass"]);
    assert_eq!(k.len(), 5);
    // K* = [[1 + eta sum gamma, -eta gamma_j], [-eta gamma_j, diag(eta gamma_j)]].
    assert!((k[0][0] - (1.0 + 0.01 * gamma.iter().sum::<f64>())).abs() < 1e-8);
    for j in 0..4 {
        assert!((k[0][j + 1] + 0.01 * gamma[j]).abs() < 1e-8);
        assert!((k[j + 1][j + 1] - 0.01 * gamma[j]).abs() < 1e-8);
        // C_r* = eta diag(0, gamma_j / d_j); no mass on the internal coordinates.
        // (relative 1e-6: the printed gammas carry 7 digits)
        let c = 0.01 * gamma[j] / d[j];
        assert!((c_r[j + 1][j + 1] - c).abs() < 1e-6 * c);
        assert_eq!(m[j + 1][j + 1], 0.0);
    }
    assert_eq!(c_r[0][0], 0.0);
    assert_eq!(v["added_states"], 4);
    let coords = v["coordinates"].as_array().unwrap();
    assert_eq!(coords[0]["kind"], "translation");
    assert_eq!(coords[1]["kind"], "internal");
    assert_eq!(coords[1]["rotating"], true);
    assert_eq!(coords[4]["branch"], 4);
    assert!((num(&coords[4]["relaxation_rate"]) - d[3]).abs() < 1e-12);
    // The fit report: the branches restore eta at the relaxation rates, not in between.
    let dampers = v["dampers"].as_array().unwrap();
    assert_eq!(dampers.len(), 1);
    let r = &dampers[0];
    assert_eq!(r["rotating"], true);
    assert!((num(&r["loss_factor"]) - 0.01).abs() < 1e-12);
    assert!(num(&r["max_deviation"]) > 0.0 && num(&r["rms_deviation"]) <= num(&r["max_deviation"]));
    assert_eq!(r["added_states"], 4);
}

#[tokio::test]
async fn state_form_of_the_one_branch_jeffcott_is_the_matrix_under_eq_26() {
    // With the sign MODEL.md section 7 corrects: +2 eta_r in the first row.
    let (en, er) = (0.02, 0.01);
    let (status, v) = post(
        "/v1/damping",
        json!({"rotor": nondimensional(er, en), "form": "state",
               "damping": {"model": "nonviscous", "rotating": {"branches": 1}, "nonrotating": {"branches": 1}}}),
    )
    .await;
    assert_eq!(status, StatusCode::OK, "{v}");
    let a0 = matrix(&v["state"]["constant"]["re"]);
    let a0_im = matrix(&v["state"]["constant"]["im"]);
    let a1_im = matrix(&v["state"]["per_speed"]["im"]);
    let expected = [
        [0.0, -1.0 - 2.0 * en - 2.0 * er, 2.0 * en, 2.0 * er],
        [1.0, 0.0, 0.0, 0.0],
        [0.0, 1.0, -1.0, 0.0],
        [0.0, 1.0, 0.0, -1.0],
    ];
    for i in 0..4 {
        for j in 0..4 {
            assert!(
                (a0[i][j] - expected[i][j]).abs() < 1e-12,
                "A0[{i}][{j}] = {}",
                a0[i][j]
            );
            assert_eq!(a0_im[i][j], 0.0);
            // i Omega on the rotating branch's internal coordinate only.
            let e = if i == 3 && j == 3 { 1.0 } else { 0.0 };
            assert_eq!(a1_im[i][j], e);
        }
    }
}

#[tokio::test]
async fn equivalent_damping_matrix_of_the_jeffcott_is_k_loss_over_omega_n() {
    let (status, v) = post(
        "/v1/damping",
        json!({"rotor": {"type": "jeffcott", "mass": 4.0, "stiffness": 100.0,
                         "loss_factor_rotating": 0.02, "loss_factor_nonrotating": 0.05},
               "damping": {"model": "equivalent"}}),
    )
    .await;
    assert_eq!(status, StatusCode::OK, "{v}");
    // c_eq = k'' / w_n = eta k / 5.
    assert!((num(&v["equivalent_rotating"][0][0]) - 0.02 * 100.0 / 5.0).abs() < 1e-12);
    assert!((num(&v["equivalent_nonrotating"][0][0]) - 0.05 * 100.0 / 5.0).abs() < 1e-12);
    assert_eq!(v["added_states"], 0);
    let (status, v) = post(
        "/v1/damping",
        json!({"rotor": nondimensional(0.01, 0.0), "damping": {"model": "hysteretic"}}),
    )
    .await;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(paths(&v), vec!["damping.model"]);
}

#[tokio::test]
async fn the_fit_chooses_the_fewest_branches_that_meet_the_bound() {
    let body = |dev: f64| {
        json!({"rotor": nondimensional(0.01, 0.03),
               "damping": {"model": "nonviscous"},
               "fit": {"band": [0.01, 100.0], "max_deviation": dev}})
    };
    // Spacing 10 ripples by about 10.4% between relaxation rates whatever the count: 0.15
    // is reachable over four decades, 0.1 is not.
    let (status, v) = post("/v1/damping", body(0.15)).await;
    assert_eq!(status, StatusCode::OK, "{v}");
    let m = v["branches_rotating"].as_u64().unwrap();
    assert_eq!(v["branches_nonrotating"].as_u64().unwrap(), m);
    for d in v["dampers"].as_array().unwrap() {
        assert!(num(&d["max_deviation"]) <= 0.15);
        assert_eq!(d["band"], json!([0.01, 100.0]));
    }
    // One branch fewer would not do: ask for the bound that count achieves, minus a bit.
    let (_, fewer) = post(
        "/v1/damping",
        json!({"rotor": nondimensional(0.01, 0.03),
               "damping": {"model": "nonviscous", "rotating": {"branches": m - 1}, "nonrotating": {"branches": m - 1}},
               "fit": {"band": [0.01, 100.0]}}),
    )
    .await;
    assert!(num(&fewer["dampers"][0]["max_deviation"]) > 0.15);
    // Unreachable targets and contradictory requests are 422 with the field.
    let (status, v) = post("/v1/damping", body(0.1)).await;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(paths(&v), vec!["fit.max_deviation"]);
    let (status, v) = post(
        "/v1/damping",
        json!({"rotor": nondimensional(0.01, 0.0),
               "damping": {"model": "nonviscous", "rotating": {"branches": 3}},
               "fit": {"band": [0.1, 10.0], "max_deviation": 0.1}}),
    )
    .await;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(paths(&v), vec!["damping.rotating"]);
}

#[tokio::test]
async fn time_response_refuses_the_hysteretic_model_and_says_why() {
    let body = json!({"rotor": nondimensional(0.01, 0.0), "damping": {"model": "hysteretic"},
                      "speed": 0.5, "duration": 1.0, "output_interval": 0.1});
    let (status, v) = problem("/v1/time-response", body.to_string().into_bytes()).await;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    let e = &v["errors"][0];
    assert_eq!(e["path"], "damping.model");
    let msg = e["message"].as_str().unwrap();
    assert!(
        msg.contains("harmonic motion") && msg.contains("nonviscous"),
        "{msg}"
    );
}

#[tokio::test]
async fn time_response_validation_names_each_bad_field() {
    let base = || {
        json!({"rotor": nondimensional(0.01, 0.0), "damping": {"model": "nonviscous"},
                         "speed": 0.5, "duration": 1.0, "output_interval": 0.1})
    };
    let with = |k: &str, v: Value| {
        let mut b = base();
        b[k] = v;
        b
    };
    let mut both = base();
    both["speed_profile"] = json!([[0.0, 0.0], [1.0, 2.0]]);
    let mut jump = base();
    jump.as_object_mut().unwrap().remove("speed");
    jump["speed_profile"] = json!([[0.0, 0.0], [1.0, 2.0], [1.0, 3.0]]);
    let cases = vec![
        (with("duration", json!(0.0)), "duration"),
        (with("output_interval", json!(-1.0)), "output_interval"),
        (with("output_interval", json!(1e-9)), "output_interval"),
        (
            with("forces", json!([{"node": 3, "history": [[0.0, 1.0]]}])),
            "forces[0].node",
        ),
        (
            with(
                "forces",
                json!([{"node": 0, "history": [[1.0, 1.0], [0.5, 2.0]]}]),
            ),
            "forces[0].history[1]",
        ),
        (
            with("unbalances", json!([{"node": 0, "amount": -1.0}])),
            "unbalances[0].amount",
        ),
        (with("nodes", json!([0, 7])), "nodes[1]"),
        (with("tolerance", json!(0.5)), "tolerance"),
        (both, "speed"),
        (jump, "speed_profile[2]"),
    ];
    for (body, path) in cases {
        let (status, v) = problem("/v1/time-response", body.to_string().into_bytes()).await;
        assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{body}");
        assert!(paths(&v).iter().any(|p| p == path), "{path} not in {v}");
    }
}

#[tokio::test]
async fn time_and_unbalance_responses_through_http() {
    // Viscous Jeffcott at constant speed, unbalance from t = 0: after the transient the orbit
    // is the steady one, radius m e W^2 / |k - m W^2 + i W c_n|.
    let rotor =
        json!({"type": "jeffcott", "mass": 2.0, "stiffness": 800.0, "damping_nonrotating": 8.0});
    let (status, v) = post(
        "/v1/time-response",
        json!({"rotor": rotor, "damping": {"model": "viscous"}, "speed": 10.0,
               "unbalances": [{"node": 0, "amount": 1e-3}], "duration": 10.0, "output_interval": 0.01}),
    )
    .await;
    assert_eq!(status, StatusCode::OK, "{v}");
    assert_eq!(v["method"], "exact");
    let t = v["time"].as_array().unwrap();
    assert_eq!(t.len(), 1001);
    assert_eq!(num(&t[1000]), 10.0);
    // The transient decays as e^{-c t / 2m}: e^{-20} by t = 10 s.
    let (x, y) = (
        num(&v["nodes"][0]["x"][1000]),
        num(&v["nodes"][0]["y"][1000]),
    );
    let steady = 1e-3 * 100.0 / ((800.0f64 - 200.0).powi(2) + 80.0f64.powi(2)).sqrt();
    assert!(
        (x.hypot(y) - steady).abs() < 1e-6 * steady,
        "{} vs {steady}",
        x.hypot(y)
    );
    let (status, u) = post(
        "/v1/unbalance-response",
        json!({"rotor": rotor, "damping": {"model": "viscous"}, "speeds": [10.0, 20.0],
               "unbalances": [{"node": 0, "amount": 1e-3}]}),
    )
    .await;
    assert_eq!(status, StatusCode::OK, "{u}");
    assert!((num(&u["nodes"][0]["amplitude"][0]) - steady).abs() < 1e-12);
    assert!(u["note"].as_str().unwrap().contains("synchronous"));
}
