//! Torsional and axial motion against ROSS 2.3.0 (`tests/data/ross/torsion.py`): machines saved
//! by ROSS's own `Rotor.save` with 6 dof per node (ROSS's `rotor_example_6dof()`, Euler-Bernoulli
//! elements without rotary inertia, and a damped two-shaft train with a coupling's torsional and
//! axial stiffness and damping and a thrust bearing), converted by `/v1/convert/ross` and solved
//! by `/v1/modal` with `motion` torsional, axial and lateral: every pole of ROSS's within 1e-6 of
//! its |s|, log decrements of the damped train within 1e-6 too.

use serde_json::{Value, json};

use crate::common::post_json;

const TOLERANCE: f64 = 1e-6;

fn dir() -> String {
    format!("{}/tests/data/ross/torsion", env!("CARGO_MANIFEST_DIR"))
}

fn reference(name: &str) -> Value {
    serde_json::from_str(&std::fs::read_to_string(format!("{}/{name}.json", dir())).unwrap())
        .unwrap()
}

async fn converted(name: &str) -> Value {
    use http_body_util::BodyExt;
    use tower::ServiceExt;
    let text = std::fs::read(format!("{}/{name}.toml", dir())).unwrap();
    let req = axum::http::Request::builder()
        .method("POST")
        .uri("/v1/convert/ross")
        .header("content-type", "application/toml")
        .body(axum::body::Body::from(text))
        .unwrap();
    let resp = whirl::service::app(whirl::service::Config::default())
        .oneshot(req)
        .await
        .unwrap();
    assert_eq!(resp.status().as_u16(), 200);
    let bytes = resp.into_body().collect().await.unwrap().to_bytes();
    let v: Value = serde_json::from_slice(&bytes).unwrap();
    v["rotor"].clone()
}

type C = (f64, f64);

fn norm(s: C) -> f64 {
    s.0.hypot(s.1)
}

/// Whirl's poles of `motion` (lateral ones with their conjugates, as ROSS's real system has
/// them; a free train's rigid pole at 0, which ROSS leaves out, dropped).
async fn whirl_poles(rotor: &Value, motion: &str, speed: f64) -> Vec<C> {
    let (status, v) = post_json(
        "/v1/modal",
        &json!({"rotor": rotor, "damping": {"model": "viscous"}, "speed": speed,
                "motion": motion}),
    )
    .await;
    assert_eq!(status, 200, "{motion} at {speed}: {v}");
    assert_eq!(v["motion"], motion);
    let mut out = vec![];
    for p in v["poles"].as_array().unwrap() {
        let s = (
            p["decay_rate"].as_f64().unwrap(),
            p["frequency"].as_f64().unwrap(),
        );
        if motion != "lateral" && s == (0.0, 0.0) {
            continue;
        }
        out.push(s);
        if motion == "lateral" && s.1.abs() > 1e-9 * norm(s) {
            out.push((s.0, -s.1));
        }
    }
    out
}

/// The largest distance of a ROSS pole from the nearest of Whirl's, relative to its |s|, and the
/// log decrements' largest difference.
fn compare(want: &[C], got: &[C]) -> (f64, f64) {
    let (mut e, mut d) = (0.0f64, 0.0f64);
    for w in want {
        let g = got
            .iter()
            .min_by(|a, b| norm((a.0 - w.0, a.1 - w.1)).total_cmp(&norm((b.0 - w.0, b.1 - w.1))))
            .unwrap();
        e = e.max(norm((g.0 - w.0, g.1 - w.1)) / norm(*w).max(1.0));
        if w.1.abs() > 1e-6 * norm(*w) {
            let dec = |s: &C| -2.0 * std::f64::consts::PI * s.0 / s.1.abs();
            d = d.max((dec(g) - dec(w)).abs());
        }
    }
    (e, d)
}

async fn machine(name: &str) {
    let rotor = converted(name).await;
    let d = reference(name);
    for case in d["poles"].as_array().unwrap() {
        let speed = case["speed"].as_f64().unwrap();
        for motion in ["torsional", "axial", "lateral"] {
            let want: Vec<C> = case[motion]
                .as_array()
                .unwrap()
                .iter()
                .map(|p| (p[0].as_f64().unwrap(), p[1].as_f64().unwrap()))
                .collect();
            let got = whirl_poles(&rotor, motion, speed).await;
            assert_eq!(
                got.len(),
                want.len(),
                "{name}, {motion} at {speed}: pole count"
            );
            let (e, dec) = compare(&want, &got);
            println!("{name}, {motion} at {speed} rad/s: poles within {e:.1e}, log dec {dec:.1e}");
            assert!(e <= TOLERANCE, "{name}, {motion} at {speed}: {e:.2e}");
            assert!(
                dec <= TOLERANCE,
                "{name}, {motion} at {speed}: log dec {dec:.2e}"
            );
        }
    }
}

#[tokio::test]
async fn rosss_rotor_example_6dof_in_every_motion() {
    machine("rotor_example_6dof").await;
}

#[tokio::test]
async fn a_damped_train_with_a_coupling_and_a_thrust_bearing_in_every_motion() {
    machine("damped_train").await;
}
