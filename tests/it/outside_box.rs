//! A reduced Campbell diagram reports the full model's poles outside the box its reduction was
//! checked in too (`analysis::refine`): on a rotor whose heavily damped bearing modes decay
//! faster than the bound (`|Re s| > max_frequency` with `|Im s|` below it), every pole the sweep
//! reports, in the box or not, is compared with `/v1/modal`'s dense solve at that speed. Before
//! the refinement such a pole was 4.7e-3 off (the reduction places a pole of modulus past its
//! modes' band only to about `(|s| / w_k)^2` of the neglected modes).

use crate::common;

use common::kept::{self, kept};
use common::{campbell_poles, floats, post_json};
use serde_json::{Value, json};
use whirl::linalg::c64;

/// benches/mesh_ross.py's rotor: a 1.6 m shaft (0.09 / 0.11 / 0.09 m over 0.32 / 0.96 /
/// 0.32 m), three disks, stiff anisotropic cross-coupled bearings with heavy damping
/// (c = 3e4..5e4 N s/m), meshed with `elements` (a multiple of 10); with `loss`, a material
/// loss factor 0.02 and a bearing loss factor 0.05.
fn bench_rotor(elements: usize, loss: bool) -> Value {
    let steel = json!({"young_modulus": 2.11e11, "density": 7810.0, "poisson_ratio": 0.3,
                       "loss_factor": if loss { 0.02 } else { 0.0 }});
    let at = |x: f64| (x / 1.6 * elements as f64).round() as usize;
    let shaft: Vec<Value> = [(0.32, 0.09), (0.96, 0.11), (0.32, 0.09)]
        .iter()
        .map(|&(l, d)| {
            json!({"length": l, "outer_diameter": d, "material": "steel", "elements": at(l)})
        })
        .collect();
    let disks: Vec<Value> = [(0.48, 30.0, 0.20), (0.80, 45.0, 0.25), (1.12, 30.0, 0.20)]
        .iter()
        .map(|&(x, m, r): &(f64, f64, f64)| {
            let ip = m * r * r / 2.0;
            json!({"node": at(x), "mass": m, "polar_inertia": ip, "transverse_inertia": ip / 2.0})
        })
        .collect();
    let bearing = |node: usize, kxx: f64, kyy: f64, cxx: f64, cyy: f64| {
        let mut b = json!({"node": node, "kxx": kxx, "kyy": kyy, "kxy": 2e7, "kyx": -2e7,
                           "cxx": cxx, "cyy": cyy});
        if loss {
            b["loss_factor"] = json!(0.05);
        }
        b
    };
    json!({
        "type": "beam",
        "materials": {"steel": steel},
        "shaft": shaft,
        "disks": disks,
        "supports": [bearing(0, 1e8, 7e7, 4e4, 3e4), bearing(elements, 1.2e8, 8e7, 5e4, 4e4)]
    })
}

fn poles(list: &Value) -> Vec<c64> {
    list.as_array()
        .unwrap()
        .iter()
        .map(|p| {
            c64::new(
                p["decay_rate"].as_f64().unwrap(),
                p["frequency"].as_f64().unwrap(),
            )
        })
        .collect()
}

/// The Campbell diagram of `rotor` under `damping` (20 speeds up to 1.5 w1, bound 1.3 w3, as
/// the benchmark), every reported pole against `/v1/modal` at the first, middle and last speed.
/// Returns the answer's `reduction`.
async fn every_pole_against_modal(rotor: Value, damping: &str) -> Value {
    let d = json!({"model": damping});
    // The dense solves are kept: tests/data/kept/outside_box/.
    let m0 = kept(
        "outside_box",
        "/v1/modal",
        &json!({"rotor": rotor, "damping": {"model": "viscous"}, "speed": 0.0}),
        kept::poles,
    )
    .await;
    let w = floats(&m0["natural_frequencies"]);
    let (stop, bound) = (1.5 * w[0], 1.3 * w[2]);
    let body = json!({"rotor": rotor, "damping": d, "max_frequency": bound,
                      "speeds": {"start": 0.0, "stop": stop, "count": 20}});
    let (status, camp) = post_json("/v1/campbell", &body).await;
    assert_eq!(status, 200, "{camp}");
    let red = camp["reduction"].clone();
    let mut outside = 0;
    for i in [0, 10, 19] {
        let speed = camp["speeds"][i].as_f64().unwrap();
        let modal = kept(
            "outside_box",
            "/v1/modal",
            &json!({"rotor": rotor, "damping": d, "speed": speed}),
            kept::poles,
        )
        .await;
        let dense = poles(&modal["poles"]);
        for s in campbell_poles(&camp, i) {
            let off = dense
                .iter()
                .map(|t| (s - t).norm())
                .fold(f64::INFINITY, f64::min)
                / s.norm();
            let out = s.re.abs() > bound || s.im.abs() > bound;
            outside += out as usize;
            // In the box: the reduction's check (1e-6 at the last speed, about that elsewhere,
            // as tests/it/large.rs). Outside: the refinement's own residual, far below.
            let tolerance = match (out, i) {
                (true, _) => 1e-8,
                (false, 19) => 1e-6,
                (false, _) => 2e-6,
            };
            assert!(
                off <= tolerance,
                "{damping}, speed {speed}: reported pole {s} is {off:.2e} off the dense ones \
                 ({} the box of {bound})",
                if out { "outside" } else { "inside" }
            );
        }
    }
    assert!(outside > 0, "no pole outside the box: {red}");
    let o = &red["outside_box"];
    assert!(o["poles"].as_u64().unwrap() > 0, "{red}");
    assert_eq!(o["refined"], o["poles"], "{red}");
    assert_eq!(o["removed"], 0, "{red}");
    println!("{damping}: {red}");
    red
}

#[tokio::test]
async fn a_heavily_damped_bearing_mode_past_the_bound_is_the_full_models() {
    // 100 elements, doubled: 808 coordinates held dense.
    let red = every_pole_against_modal(bench_rotor(100, false), "viscous").await;
    assert_eq!(red["full_model"], "dense");
    // The reduced model had placed the bearing mode 4.7e-3 off (measured before the change).
    let change = red["outside_box"]["largest_change"].as_f64().unwrap();
    assert!(change > 1e-3, "{red}");
}

#[tokio::test]
async fn a_large_rotor_held_sparse_refines_through_its_sparse_factors() {
    // 150 elements: 1208 doubled coordinates, past SPARSE_FROM.
    let red = every_pole_against_modal(bench_rotor(150, false), "viscous").await;
    assert_eq!(red["full_model"], "sparse");
}

#[tokio::test]
async fn hysteretic_poles_past_the_bound_are_consistent_roots() {
    every_pole_against_modal(bench_rotor(100, true), "hysteretic").await;
}

#[tokio::test]
async fn the_equivalent_model_refines_on_its_dense_full_model() {
    every_pole_against_modal(bench_rotor(70, true), "equivalent").await;
}

#[tokio::test]
#[ignore = "heavy: a dense reference of a large rotor (cargo test --release -- --ignored)"]
async fn crossings_past_the_bound_are_closed_on_the_full_model() {
    // Speeds past the bound: the bearing mode crosses the 1x line critically damped near 1430
    // rad/s at -8526 1/s, and a backward branch crosses above the bound near 3243 rad/s.
    let rotor = bench_rotor(100, false);
    let bound = 3187.0;
    let body = json!({"rotor": rotor, "damping": {"model": "viscous"}, "max_frequency": bound,
                      "speeds": {"start": 0.0, "stop": 4000.0, "count": 40}});
    let (status, camp) = post_json("/v1/campbell", &body).await;
    assert_eq!(status, 200, "{camp}");
    let mut outside = 0;
    for c in camp["criticals"].as_array().unwrap() {
        let speed = c["speed"].as_f64().unwrap();
        let s = c64::new(c["decay_rate"].as_f64().unwrap(), speed);
        if s.re.abs() <= bound && s.im.abs() <= bound {
            continue;
        }
        outside += 1;
        let (status, modal) = post_json(
            "/v1/modal",
            &json!({"rotor": rotor, "damping": {"model": "viscous"}, "speed": speed}),
        )
        .await;
        assert_eq!(status, 200, "{modal}");
        // The pole there whirls at the spin speed (either member of its mirror pair).
        let off = poles(&modal["poles"])
            .iter()
            .map(|t| (s - t).norm().min((s.conj() - t).norm()))
            .fold(f64::INFINITY, f64::min)
            / s.norm();
        println!("crossing at {speed:.4} rad/s, pole {s:.4}: {off:.1e} off /v1/modal");
        assert!(off <= 1e-9, "crossing at {speed}: {off:.2e}");
    }
    assert!(outside >= 2, "{}", camp["criticals"]);
}
