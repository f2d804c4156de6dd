//! Campbell diagrams on real bearings against ROSS 2.3.0 (`tests/data/ross/campbell.json`, made
//! by `campbell.py` beside it): every lateral pole ROSS lists below the bound is on a branch at
//! every speed (no `null`, no pole left out, none made up), and the critical speeds, forward and
//! backward, are the exact crossings and ROSS's `run_critical_speed(rtol=1e-10)` to 1e-6. The
//! rotors: the six seeded held-out rotors (58 to 189 elements, three anisotropic and
//! cross-coupled), the 12-element rotor with `kxx = 2 kyy`, rotor A on tabulated
//! cross-coupled bearings, and rotor A with a seal (which ROSS leaves out of `run_ucs` and
//! `run_static`, and so must Whirl).

use crate::common;

use common::post_json;
use serde_json::{Value, json};

fn data() -> Value {
    let path = format!(
        "{}/tests/data/ross/campbell.json",
        env!("CARGO_MANIFEST_DIR")
    );
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn floats(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// `(re, im)` pairs of a JSON list of `[re, im]`.
fn poles(v: &Value) -> Vec<(f64, f64)> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|z| (z[0].as_f64().unwrap(), z[1].as_f64().unwrap()))
        .collect()
}

fn dist(a: (f64, f64), b: (f64, f64)) -> f64 {
    ((a.0 - b.0).powi(2) + (a.1 - b.1).powi(2)).sqrt() / b.0.hypot(b.1)
}

async fn campbell(case: &Value) -> Value {
    let body = json!({
        "rotor": case["rotor"],
        "damping": {"model": "viscous"},
        "speeds": case["speeds"],
        "max_frequency": case["bound"],
    });
    let (status, c) = post_json("/v1/campbell", &body).await;
    assert_eq!(status, 200, "{}: {c}", case["name"]);
    c
}

/// Each mode once, as ROSS lists it: `(decay rate, |frequency|)`.
fn value(b: &Value, k: usize) -> Option<(f64, f64)> {
    let f = b["frequency"][k].as_f64()?;
    Some((b["decay_rate"][k].as_f64().unwrap(), f.abs()))
}

#[tokio::test]
async fn every_pole_ross_lists_is_on_a_branch_at_every_speed() {
    for case in data()["cases"].as_array().unwrap() {
        let name = case["name"].as_str().unwrap();
        let bound = case["bound"].as_f64().unwrap();
        let c = campbell(case).await;
        let branches = c["branches"].as_array().unwrap();
        let (mut worst, mut nulls, mut points) = (0.0f64, 0, 0);
        for (k, at) in case["points"].as_array().unwrap().iter().enumerate() {
            let ross = poles(&at["poles"]);
            let ours: Vec<(f64, f64)> = branches.iter().filter_map(|b| value(b, k)).collect();
            nulls += branches.iter().filter(|b| value(b, k).is_none()).count();
            for z in &ross {
                let d = ours
                    .iter()
                    .map(|o| dist(*o, *z))
                    .fold(f64::INFINITY, f64::min);
                assert!(
                    d < 1e-6,
                    "{name}: ROSS's {z:?} at speed {k} not on a branch ({d:e})"
                );
                worst = worst.max(d);
            }
            // None made up: each branch value below the bound is one of ROSS's poles.
            for o in ours.iter().filter(|o| o.1 <= bound * (1.0 - 1e-6)) {
                let d = ross
                    .iter()
                    .map(|z| dist(*o, *z))
                    .fold(f64::INFINITY, f64::min);
                assert!(
                    d < 1e-6,
                    "{name}: branch value {o:?} at speed {k} is no pole ({d:e})"
                );
            }
            points += ross.len();
        }
        println!(
            "{name}: {} branches, {points} ROSS points, worst {worst:.1e}, {nulls} nulls",
            branches.len()
        );
        assert_eq!(nulls, 0, "{name}: branches with null values");
    }
}

#[tokio::test]
async fn critical_speeds_are_the_exact_crossings_and_rosss() {
    for case in data()["cases"].as_array().unwrap() {
        let name = case["name"].as_str().unwrap();
        let c = campbell(case).await;
        let ours = c["criticals"].as_array().unwrap();
        let exact: Vec<Vec<f64>> = case["criticals"]["exact"]
            .as_array()
            .unwrap()
            .iter()
            .map(floats)
            .collect();
        assert_eq!(ours.len(), exact.len(), "{name}: {ours:?} vs {exact:?}");
        let mut worst = 0.0f64;
        for (o, e) in ours.iter().zip(&exact) {
            let w = o["speed"].as_f64().unwrap();
            worst = worst.max((w - e[0]).abs() / e[0]);
            assert!((w - e[0]).abs() < 1e-6 * e[0], "{name}: {w} vs {}", e[0]);
            // The pole there: its decay rate to 1e-6 of |s|.
            let sigma = o["decay_rate"].as_f64().unwrap();
            assert!(
                (sigma - e[1]).abs() < 1e-6 * e[1].hypot(e[2]),
                "{name}: {o}"
            );
            let ld = -2.0 * std::f64::consts::PI * e[1] / e[2];
            let ours_ld = o["log_decrement"].as_f64().unwrap();
            assert!(
                (ours_ld - ld).abs() < 1e-5 * ld.abs().max(1e-2),
                "{name}: {o}"
            );
        }
        // ROSS's own (Newton on each mode index, ARPACK): each is one of ours to 1e-6, and the
        // whirl agrees where ROSS calls the mode Forward or Backward (not Mixed).
        let mut matched = 0;
        for r in case["criticals"]["ross"].as_array().into_iter().flatten() {
            let w = r["speed"].as_f64().unwrap();
            let o = ours
                .iter()
                .min_by(|a, b| {
                    let d = |x: &Value| (x["speed"].as_f64().unwrap() - w).abs();
                    d(a).total_cmp(&d(b))
                })
                .unwrap();
            let d = (o["speed"].as_f64().unwrap() - w).abs() / w;
            assert!(d < 1e-6, "{name}: ROSS's critical {w} ({d:e} from ours)");
            match r["whirl"].as_str().unwrap() {
                "Forward" => assert_eq!(o["whirl"], "forward", "{name}: {w}"),
                "Backward" => assert_eq!(o["whirl"], "backward", "{name}: {w}"),
                _ => {}
            }
            matched += 1;
        }
        println!(
            "{name}: {} criticals ({} forward), worst {worst:.1e} from the exact crossings; \
             {matched} of ROSS's matched",
            ours.len(),
            ours.iter().filter(|o| o["whirl"] == "forward").count()
        );
        // The legacy list: the forward crossings not critically damped.
        let forward: Vec<f64> = ours
            .iter()
            .filter(|o| o["whirl"] == "forward" && o["critically_damped"] == false)
            .map(|o| o["speed"].as_f64().unwrap())
            .collect();
        assert_eq!(floats(&c["critical_speeds"]), forward, "{name}");
    }
}

#[tokio::test]
async fn seals_are_left_out_of_the_map_and_the_static_analysis_as_ross_does() {
    let file = data();
    let case = file["cases"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["name"] == "seal")
        .unwrap();
    let stiffness = floats(&case["ucs"]["stiffness"]);
    let range = json!({"start": stiffness[0], "stop": stiffness[stiffness.len() - 1],
                       "count": stiffness.len()});
    let (status, m) = post_json(
        "/v1/critical-speed-map",
        &json!({"rotor": case["rotor"], "stiffness": range, "modes": 4}),
    )
    .await;
    for (a, b) in floats(&m["stiffness"]).iter().zip(&stiffness) {
        assert!((a - b).abs() < 1e-12 * b, "the same grid: {a} vs {b}");
    }
    assert_eq!(status, 200, "{m}");
    let mut worst = 0.0f64;
    for (mode, row) in case["ucs"]["frequencies"]
        .as_array()
        .unwrap()
        .iter()
        .enumerate()
    {
        let ross = floats(row);
        let ours = floats(&m["frequencies"][mode]);
        for (a, b) in ours.iter().zip(&ross) {
            worst = worst.max((a - b).abs() / b);
        }
    }
    println!("map with a seal: {worst:.1e} from run_ucs");
    assert!(worst < 1e-6, "{worst:e}");
    assert!(
        m["warnings"][0].as_str().unwrap().contains("rotor.seals"),
        "{m}"
    );

    let (status, s) = post_json(
        "/v1/static",
        // ROSS's run_static uses g = 9.8065 m/s^2 (Whirl's default is standard gravity).
        &json!({"rotor": case["rotor"], "supports": "rigid", "gravity": 9.8065}),
    )
    .await;
    assert_eq!(status, 200, "{s}");
    let ross = floats(&case["static"]["deformation_y"]);
    let ours: Vec<f64> = s["nodes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|n| n["deflection"].as_f64().unwrap())
        .collect();
    let scale = ross.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    let dev = ours
        .iter()
        .zip(&ross)
        .fold(0.0f64, |a, (x, y)| a.max((x - y).abs()));
    println!(
        "static with a seal: deflection {:.1e} of the largest",
        dev / scale
    );
    assert!(dev < 1e-6 * scale, "{dev:e}");
    let reactions = s["supports"].as_array().unwrap();
    assert_eq!(reactions.len(), 2, "the seal carries no load: {s}");
    for r in reactions {
        let node = r["node"].as_u64().unwrap();
        let ross = case["static"]["bearing_forces"][format!("node_{node}")]
            .as_f64()
            .unwrap();
        let ours = r["reaction"].as_f64().unwrap();
        assert!((ours - ross).abs() < 1e-6 * ross.abs(), "{ours} vs {ross}");
    }
    assert!(
        s["warnings"][0].as_str().unwrap().contains("rotor.seals"),
        "{s}"
    );
}
