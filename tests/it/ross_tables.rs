//! Supports read with ROSS's interpolation (`interpolation: "ross"`), scheduled on one state
//! model (`damping/schedule.rs`): at any speed, inside the table, between its speeds and
//! beyond it, the poles are those of the same rotor on constant supports equal to ROSS's
//! curves there; a linear table beside them is still linear; every analysis path (the full
//! model, the Campbell's checked reduction, the harmonic solve, both time integrators) agrees.
//! ROSS's own results on converted machines are in `convert_ross.rs`.

use crate::common;

use common::kept::{self, kept};
use common::post_json;
use serde_json::{Value, json};
use whirl::model::spline::Curve;

fn fluid_film() -> Value {
    let path = format!(
        "{}/examples/fluid-film.unbalance-response.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let d: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    d["rotor"].clone()
}

const NAMES: [&str; 8] = ["kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy"];

/// The fluid-film rotor with its first bearing on ROSS's curves (5 speeds: splines), a seal
/// of 3 speeds on them too (interp1d, quadratic), its second bearing a linear table, and the
/// shaft hysteretic.
fn rotor() -> Value {
    let mut r = fluid_film();
    r["materials"]["steel"]["loss_factor"] = json!(0.002);
    r["supports"][0]["interpolation"] = json!("ross");
    r["seals"] = json!([{
        "node": 3,
        "speeds": [300.0, 1200.0, 2400.0],
        "kxx": [2e5, 5e5, 6e5], "kxy": [1e5, 3e5, 8e5], "kyx": [-1e5, -3e5, -8e5],
        "kyy": [2e5, 5e5, 6e5], "cxx": [300.0, 250.0, 320.0], "cyy": [300.0, 250.0, 320.0],
        "interpolation": "ross",
    }]);
    r
}

/// `rotor` with every table replaced by its coefficients at `speed` (ROSS's curves, or
/// linear and held), as constants.
fn frozen(rotor: &Value, speed: f64) -> Value {
    let mut r = rotor.clone();
    for key in ["supports", "seals"] {
        for s in r[key].as_array_mut().unwrap() {
            let Some(speeds) = s.get("speeds").cloned() else {
                continue;
            };
            let x: Vec<f64> = serde_json::from_value(speeds).unwrap();
            let ross = s.get("interpolation") == Some(&json!("ross"));
            let o = s.as_object_mut().unwrap();
            o.remove("speeds");
            o.remove("interpolation");
            for name in NAMES {
                let Some(Value::Array(v)) = o.get(name) else {
                    continue;
                };
                let y: Vec<f64> = v.iter().map(|v| v.as_f64().unwrap()).collect();
                let value = if ross {
                    Curve::ross(&x, &y).at(speed)
                } else {
                    linear(&x, &y, speed)
                };
                o.insert(name.into(), json!(value));
            }
        }
    }
    r
}

fn linear(x: &[f64], y: &[f64], at: f64) -> f64 {
    if at <= x[0] {
        return y[0];
    }
    if at >= x[x.len() - 1] {
        return y[y.len() - 1];
    }
    let k = x.partition_point(|&w| w <= at) - 1;
    y[k] + (y[k + 1] - y[k]) * (at - x[k]) / (x[k + 1] - x[k])
}

fn poles(v: &Value) -> Vec<(f64, f64)> {
    let mut p: Vec<(f64, f64)> = v["poles"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| {
            (
                p["decay_rate"].as_f64().unwrap(),
                p["frequency"].as_f64().unwrap(),
            )
        })
        .collect();
    p.sort_by(|a, b| a.1.total_cmp(&b.1).then(a.0.total_cmp(&b.0)));
    p
}

/// Largest distance from a pole of either list to the nearest of the other (lists of one
/// size), relative to the largest |s|.
fn distance(a: &[(f64, f64)], b: &[(f64, f64)]) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = a.iter().map(|p| p.0.hypot(p.1)).fold(0.0, f64::max);
    let one_way = |a: &[(f64, f64)], b: &[(f64, f64)]| {
        a.iter()
            .map(|p| {
                b.iter()
                    .map(|q| (p.0 - q.0).hypot(p.1 - q.1))
                    .fold(f64::INFINITY, f64::min)
            })
            .fold(0.0, f64::max)
    };
    one_way(a, b).max(one_way(b, a)) / scale
}

async fn modal(rotor: &Value, model: Value, speed: f64) -> Value {
    let (status, v) = post_json(
        "/v1/modal",
        &json!({"rotor": rotor, "damping": model, "speed": speed}),
    )
    .await;
    assert_eq!(status, 200, "{v}");
    v
}

#[tokio::test]
async fn poles_at_any_speed_are_those_of_the_curves_values_there() {
    let r = rotor();
    let mut worst: f64 = 0.0;
    // Below the tables (extrapolated), at a table speed, between, beyond every table.
    for speed in [0.0, 200.0, 450.0, 1111.0, 2500.0, 3200.0] {
        let constant = frozen(&r, speed);
        for model in [json!({"model": "viscous"}), json!({"model": "hysteretic"})] {
            let a = poles(&modal(&r, model.clone(), speed).await);
            let b = poles(&modal(&constant, model.clone(), speed).await);
            let e = distance(&a, &b);
            worst = worst.max(e);
            assert!(e < 1e-11, "{model} at {speed} rad/s: {e:.2e}");
        }
    }
    println!("scheduled poles within {worst:.2e} of the frozen supports' (largest |s|)");
}

#[tokio::test]
async fn the_curves_are_not_the_linear_table() {
    // Between table speeds ROSS's spline is not the linear interpolation: the poles move
    // (this is what reading a ROSS table linearly got wrong), and at a table speed the
    // smoothing spline need not pass through the value either.
    let r = rotor();
    let mut linear = r.clone();
    linear["supports"][0]
        .as_object_mut()
        .unwrap()
        .remove("interpolation");
    linear["seals"][0]
        .as_object_mut()
        .unwrap()
        .remove("interpolation");
    let model = json!({"model": "viscous"});
    let a = poles(&modal(&r, model.clone(), 450.0).await);
    let b = poles(&modal(&linear, model, 450.0).await);
    let e = distance(&a, &b);
    assert!(e > 1e-4, "{e:e}");
}

/// `rotor()` meshed with 6 times the elements (the nodes of its disk, bearings and seal
/// moved with them): large enough for the Campbell to reduce.
fn finer() -> Value {
    let mut r = rotor();
    let n = r["shaft"][0]["elements"].as_i64().unwrap_or(1);
    r["shaft"][0]["elements"] = json!(6 * n);
    for key in ["supports", "seals", "disks"] {
        for s in r[key].as_array_mut().unwrap() {
            s["node"] = json!(6 * s["node"].as_i64().unwrap());
        }
    }
    r
}

#[tokio::test]
async fn the_campbell_on_its_reduction_gives_the_full_models_poles() {
    let r = finer();
    let speeds = [0.0, 450.0, 1111.0, 2500.0, 3200.0];
    let (status, v) = post_json(
        "/v1/campbell",
        &json!({"rotor": r, "damping": {"model": "nonviscous"}, "speeds": speeds,
                "max_frequency": 1500.0}),
    )
    .await;
    assert_eq!(status, 200, "{v}");
    assert!(v["reduction"].is_object(), "{}", v["reduction"]);
    // Tabulated supports: checked at the top, the lowest and the middle speed.
    assert_eq!(
        v["reduction"]["checked_speeds"],
        json!([3200.0, 0.0, 1111.0])
    );
    println!("campbell reduction: {}", v["reduction"]);
    for (i, &speed) in speeds.iter().enumerate() {
        // The full model's dense solves (minutes in all) are kept: tests/data/kept/ross_tables/.
        let body = json!({"rotor": r, "damping": {"model": "nonviscous"}, "speed": speed});
        let full = kept("ross_tables", "/v1/modal", &body, kept::poles).await;
        let all = poles(&full);
        let reported: Vec<(f64, f64)> = v["branches"]
            .as_array()
            .unwrap()
            .iter()
            .filter_map(|b| Some((b["decay_rate"][i].as_f64()?, b["frequency"][i].as_f64()?)))
            .collect();
        // Relative to the pole's |s|: the reduction's check (1e-6).
        let nearest = |p: (f64, f64), among: &[(f64, f64)]| {
            among
                .iter()
                .map(|q| (p.0 - q.0).hypot(p.1 - q.1) / p.0.hypot(p.1))
                .fold(f64::INFINITY, f64::min)
        };
        // The reduction's guarantee: poles in the box |Re s|, |Im s| <= max_frequency.
        let boxed = |p: &&(f64, f64)| p.0.abs() <= 1500.0 && p.1.abs() < 1500.0 * (1.0 - 1e-6);
        // And every full-model pole there on a branch: at 1111 rad/s two close, heavily damped
        // backward poles (-1283 - 1237i, -1294 - 1297i 1/s), one of them born of two real
        // poles that met between 450 and 1111 rad/s, whose branches had ended.
        let on_branches: Vec<(f64, f64)> = full["poles"]
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
        for &p in on_branches.iter().filter(boxed) {
            let d = nearest(p, &reported);
            assert!(
                d < 1e-6,
                "at {speed} rad/s the full model's {p:?} is on no branch ({d:e})"
            );
        }
        for &p in reported.iter().filter(boxed) {
            let d = nearest(p, &all);
            assert!(
                d < 1e-6,
                "at {speed} rad/s the Campbell's {p:?} is no pole ({d:e})"
            );
        }
    }
}

#[tokio::test]
async fn warnings_say_the_curves_extrapolate() {
    let (status, v) = post_json(
        "/v1/modal",
        &json!({"rotor": rotor(), "damping": {"model": "viscous"}, "speed": 3200.0}),
    )
    .await;
    assert_eq!(status, 200, "{v}");
    let w = v["warnings"].to_string();
    assert!(w.contains("rotor.supports[0]: outside its table"), "{w}");
    assert!(w.contains("extrapolated by ROSS's curves"), "{w}");
    assert!(w.contains("rotor.supports[1]: above its table"), "{w}");
}

/// The 422 a modal analysis of `rotor` answers, as text.
async fn refused(rotor: Value) -> String {
    let (status, v) = post_json(
        "/v1/modal",
        &json!({"rotor": rotor, "damping": {"model": "viscous"}, "speed": 100.0}),
    )
    .await;
    assert_eq!(status, 422, "{v}");
    v.to_string()
}

#[tokio::test]
async fn what_rosss_interpolation_cannot_take_is_named() {
    let mut r = rotor();
    r["supports"][0]["mxx"] = json!([1.0, 1.0, 2.0, 2.0, 2.0]);
    let s = refused(r).await;
    assert!(s.contains("rotor.supports[0].interpolation"), "{s}");

    let mut r = rotor();
    r["supports"][0]["loss_factor"] = json!(0.1);
    let s = refused(r).await;
    assert!(s.contains("rotor.supports[0].loss_factor"), "{s}");

    // A linear table with a loss factor beside a ROSS one: named, with the ROSS one.
    let mut r = rotor();
    r["supports"][1]["loss_factor"] = json!(0.1);
    let s = refused(r).await;
    assert!(s.contains("rotor.supports[1].loss_factor"), "{s}");
    assert!(s.contains("rotor.supports[0] reads its table"), "{s}");

    // `interpolation` without a table.
    let mut r = fluid_film();
    r["supports"][0] = json!({"node": 0, "kxx": 1e6, "interpolation": "ross"});
    let s = refused(r).await;
    assert!(s.contains("rotor.supports[0].interpolation"), "{s}");
}
