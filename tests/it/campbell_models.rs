//! Campbell branches under every damping model against `/v1/modal` at every speed of the sweep:
//! on isotropic, anisotropic, cross-coupled, tabulated (linear and ROSS's) and sealed rotors of
//! our own, each pole
//! the modal analysis returns below the bound is on a branch (a branch is a mode: the lower
//! twin of an anisotropic pair turns backward above rest and stays one branch), each branch
//! value is such a pole, and only the hysteretic model leaves values undefined (where it has no
//! consistent pole). Overdamped poles are reported apart, crossings at rest are none, and mode
//! numbers pair the two branches of each mode.

use crate::common;

use common::post_json;
use serde_json::{Value, json};

const STEEL_LOSS: f64 = 0.003;

fn shaft(elements: usize, loss: f64) -> Value {
    json!({"type": "beam",
        "materials": {"steel": {"young_modulus": 2.11e11, "density": 7810.0,
                                "poisson_ratio": 0.3, "loss_factor": loss}},
        "shaft": [{"length": 1.2, "outer_diameter": 0.05, "inner_diameter": 0.0,
                   "material": "steel", "elements": elements}],
        "disks": [{"node": elements / 2, "mass": 20.0, "polar_inertia": 0.2,
                   "transverse_inertia": 0.1}]})
}

/// Rotors: name, rotor, top speed, bound.
fn rotors() -> Vec<(&'static str, Value, f64, f64)> {
    let mut iso = shaft(12, STEEL_LOSS);
    iso["supports"] = json!([
        {"node": 0, "stiffness": 3e6, "damping": 300, "loss_factor": 0.05},
        {"node": 12, "stiffness": 3e6, "damping": 300, "loss_factor": 0.05}]);
    let mut aniso = shaft(12, STEEL_LOSS);
    aniso["supports"] = json!([
        {"node": 0, "kxx": 4e6, "kyy": 2e6, "cxx": 500, "cyy": 500, "loss_factor": 0.04},
        {"node": 12, "kxx": 4e6, "kyy": 2e6, "cxx": 500, "cyy": 500, "loss_factor": 0.04}]);
    let mut cross = shaft(16, STEEL_LOSS);
    cross["supports"] = json!([
        {"node": 0, "kxx": 1e6, "kxy": 5e5, "kyx": -8e5, "kyy": 2e6,
         "cxx": 3e3, "cxy": 400, "cyx": 600, "cyy": 4.5e3},
        {"node": 16, "kxx": 1.2e6, "kxy": 6e5, "kyx": -9e5, "kyy": 2.4e6,
         "cxx": 3.5e3, "cxy": 500, "cyx": 700, "cyy": 5e3}]);
    let mut tab = shaft(10, STEEL_LOSS);
    tab["supports"] = json!([
        {"node": 0, "speeds": [200, 600, 1000, 1500, 2500],
         "kxx": [1e6, 1.3e6, 1.7e6, 2.2e6, 3e6], "kxy": [3e5, 6e5, 9e5, 1.3e6, 2e6],
         "kyx": [-5e5, -8e5, -1.1e6, -1.5e6, -2.2e6], "kyy": [2e6, 2.3e6, 2.8e6, 3.4e6, 4.5e6],
         "cxx": [800, 700, 600, 500, 400], "cyy": [900, 800, 700, 600, 500]},
        {"node": 10, "speeds": [200, 600, 1000, 1500, 2500],
         "kxx": [1.5e6, 1.8e6, 2.1e6, 2.6e6, 3.2e6], "kyy": [1.2e6, 1.5e6, 1.9e6, 2.4e6, 3e6],
         "cxx": [500, 450, 400, 350, 300], "cyy": [600, 550, 500, 450, 400]}]);
    // The tabulated bearings read with ROSS's interpolation (splines, extrapolated below
    // 200 rad/s), and a seal of 3 speeds (quadratic).
    let mut ross = shaft(10, STEEL_LOSS);
    ross["supports"] = tab["supports"].clone();
    for s in ross["supports"].as_array_mut().unwrap() {
        s["interpolation"] = json!("ross");
    }
    ross["seals"] = json!([
        {"node": 7, "speeds": [300, 1200, 2400], "kxx": [2e5, 5e5, 6e5], "kyy": [2e5, 5e5, 6e5],
         "kxy": [1e5, 3e5, 8e5], "kyx": [-1e5, -3e5, -8e5], "cxx": 300, "cyy": 300,
         "interpolation": "ross"}]);
    let mut seal = shaft(10, STEEL_LOSS);
    seal["supports"] = json!([
        {"node": 0, "stiffness": 5e6, "damping": 800},
        {"node": 10, "stiffness": 5e6, "damping": 800}]);
    seal["seals"] = json!([
        {"node": 7, "kxx": 4e5, "kyy": 4e5, "kxy": 2.5e5, "kyx": -2.5e5,
         "cxx": 1.5e3, "cyy": 1.5e3}]);
    vec![
        ("isotropic", iso, 2000.0, 2500.0),
        ("anisotropic", aniso, 1500.0, 1500.0),
        ("cross-coupled", cross, 3000.0, 3500.0),
        ("tabulated", tab, 3000.0, 3500.0),
        ("ross-tabulated", ross, 3000.0, 3500.0),
        ("sealed", seal, 3000.0, 3500.0),
    ]
}

fn models() -> Vec<Value> {
    vec![
        json!({"model": "viscous"}),
        json!({"model": "hysteretic"}),
        json!({"model": "equivalent"}),
        json!({"model": "nonviscous"}),
    ]
}

fn rel(a: (f64, f64), b: (f64, f64)) -> f64 {
    ((a.0 - b.0).powi(2) + (a.1 - b.1).powi(2)).sqrt() / b.0.hypot(b.1)
}

#[tokio::test]
async fn every_modal_pole_is_on_its_branch_under_every_model() {
    for (name, rotor, top, bound) in rotors() {
        for damping in models() {
            let model = damping["model"].as_str().unwrap();
            let speeds: Vec<f64> = (0..16).map(|i| top * i as f64 / 15.0).collect();
            let body = json!({"rotor": rotor, "damping": damping, "speeds": speeds,
                              "max_frequency": bound});
            let (status, c) = post_json("/v1/campbell", &body).await;
            assert_eq!(status, 200, "{name} {model}: {c}");
            let branches = c["branches"].as_array().unwrap();
            let (mut nulls, mut missing_h, mut worst) = (0, 0, 0.0f64);
            for (k, &w) in speeds.iter().enumerate() {
                let (status, m) = post_json(
                    "/v1/modal",
                    &json!({"rotor": rotor, "damping": damping, "speed": w}),
                )
                .await;
                assert_eq!(status, 200, "{m}");
                missing_h += m["missing_poles"].as_u64().unwrap();
                let modal: Vec<(f64, f64)> = m["poles"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .filter(|p| p["whirl"] != "internal")
                    .map(|p| {
                        (
                            p["decay_rate"].as_f64().unwrap(),
                            p["frequency"].as_f64().unwrap(),
                        )
                    })
                    .filter(|p| p.1.abs() > 0.01 * -p.0)
                    .collect();
                let ours: Vec<(f64, f64)> = branches
                    .iter()
                    .filter_map(|b| {
                        Some((b["decay_rate"][k].as_f64()?, b["frequency"][k].as_f64()?))
                    })
                    .collect();
                nulls += branches.len() - ours.len();
                for p in modal.iter().filter(|p| p.1.abs() <= bound) {
                    // The same pole, the same member of a mirror pair (the sign of frequency).
                    let d = ours
                        .iter()
                        .map(|o| rel(*o, *p))
                        .fold(f64::INFINITY, f64::min);
                    assert!(
                        d < 1e-6,
                        "{name} {model}: modal pole {p:?} at {w} not on a branch ({d:e})"
                    );
                    worst = worst.max(d);
                }
                for o in ours.iter().filter(|o| o.1.abs() < bound * (1.0 - 1e-6)) {
                    let d = modal
                        .iter()
                        .map(|p| rel(*o, *p))
                        .fold(f64::INFINITY, f64::min);
                    assert!(
                        d < 1e-6,
                        "{name} {model}: branch value {o:?} at {w} is no pole"
                    );
                }
            }
            if model != "hysteretic" {
                assert_eq!(nulls, 0, "{name} {model}: null values on branches");
            }
            // Mode numbers: at most the two branches of one mode share one.
            let mut count = std::collections::BTreeMap::new();
            for b in branches {
                *count.entry(b["mode"].as_u64().unwrap()).or_insert(0) += 1;
            }
            assert!(count.values().all(|&n| n <= 2), "{name} {model}: {count:?}");
            // Log decrement and whirl ratio given wherever the pole is.
            for b in branches {
                for k in 0..speeds.len() {
                    let defined = b["frequency"][k].is_number();
                    assert_eq!(b["log_decrement"][k].is_number(), defined, "{name} {model}");
                    assert_eq!(b["whirl_ratio"][k].is_number(), defined, "{name} {model}");
                }
            }
            let crit = c["criticals"].as_array().unwrap();
            assert!(crit.iter().all(|x| x["speed"].as_f64().unwrap() > 0.0));
            println!(
                "{name} {model}: {} branches, worst {worst:.1e} from modal, {nulls} nulls \
                 (hysteretic: {missing_h} poles missing in modal), {} criticals ({} backward), \
                 {} ambiguous hand-overs",
                branches.len(),
                crit.len(),
                crit.iter().filter(|x| x["whirl"] == "backward").count(),
                c["ambiguities"].as_array().map_or(0, |a| a.len())
            );
        }
    }
}

#[tokio::test]
async fn isotropic_branches_pair_forward_with_backward() {
    let (_, rotor, top, bound) = rotors().remove(0);
    let speeds: Vec<f64> = (0..16).map(|i| top * i as f64 / 15.0).collect();
    let body = json!({"rotor": rotor, "damping": {"model": "viscous"}, "speeds": speeds,
                      "max_frequency": bound});
    let (_, c) = post_json("/v1/campbell", &body).await;
    let tags: Vec<String> = c["branches"]
        .as_array()
        .unwrap()
        .iter()
        .map(|b| format!("{}{}", b["mode"], &b["whirl"].as_str().unwrap()[..1]))
        .collect();
    let want: Vec<String> = (1..=tags.len() / 2)
        .flat_map(|m| [format!("{m}f"), format!("{m}b")])
        .collect();
    assert_eq!(tags, want);
}

#[tokio::test]
async fn overdamped_poles_are_reported_apart_and_cross_nothing() {
    // Supports damped far past critical: the support modes' poles are real at rest.
    let mut rotor = shaft(12, 0.0);
    rotor["supports"] = json!([
        {"node": 0, "stiffness": 2e6, "damping": 2e5},
        {"node": 12, "stiffness": 2e6, "damping": 2e5}]);
    let speeds: Vec<f64> = (0..16).map(|i| 100.0 * i as f64).collect();
    let body = json!({"rotor": rotor, "damping": {"model": "viscous"}, "speeds": speeds,
                      "max_frequency": 3000});
    let (_, c) = post_json("/v1/campbell", &body).await;
    let over = c["overdamped"].as_array().unwrap();
    assert!(!over.is_empty(), "{c}");
    for o in over {
        for (s, f) in o["decay_rate"]
            .as_array()
            .unwrap()
            .iter()
            .zip(o["frequency"].as_array().unwrap())
        {
            let (s, f) = (s.as_f64().unwrap(), f.as_f64().unwrap());
            assert!(s < 0.0 && f.abs() <= 0.01 * -s, "{s} {f}");
        }
    }
    // No Campbell branch is a pole that does not oscillate; no crossing at rest.
    for b in c["branches"].as_array().unwrap() {
        for (f, s) in b["frequency"]
            .as_array()
            .unwrap()
            .iter()
            .zip(b["decay_rate"].as_array().unwrap())
        {
            assert!(f.as_f64().unwrap().abs() > 0.01 * -s.as_f64().unwrap());
        }
    }
    for x in c["criticals"].as_array().unwrap() {
        assert!(x["speed"].as_f64().unwrap() > 1.0, "{x}");
    }
}
