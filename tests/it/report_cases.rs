//! The report's API 684 unbalance cases: placement from the mode shapes, sizes from the static
//! journal loads (`Ua = 2 x 6350 W / N` g mm), API 617's vibration limit and scale factor, the
//! clearance check, and what ties the report to its input.

use crate::common;

use common::{post_as, post_json};
use serde_json::{Value, json};

fn num(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

fn rpm(w: f64) -> f64 {
    w * 30.0 / std::f64::consts::PI
}

/// A steel shaft 1.2 m, 60 mm, 12 elements, with `disks`, on `supports`.
fn shaft(disks: Value, supports: Value) -> Value {
    json!({"type": "beam",
        "materials": {"steel": {"young_modulus": 2.1e11, "density": 7800.0, "poisson_ratio": 0.3,
                                "loss_factor": 0.0}},
        "shaft": [{"length": 1.2, "outer_diameter": 0.06, "inner_diameter": 0.0,
                   "material": "steel", "elements": 12}],
        "disks": disks, "supports": supports})
}

fn report_body(rotor: Value, range: [f64; 2], clearances: Value) -> Value {
    json!({"rotor": rotor, "damping": {"model": "viscous"},
           "operating_range": {"min": range[0], "max": range[1]},
           "models": [{"model": "viscous"}], "clearances": clearances})
}

fn reactions(v: &Value) -> Vec<(u64, f64)> {
    v["static_deflection"]["supports"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| (r["node"].as_u64().unwrap(), num(&r["reaction"])))
        .collect()
}

#[tokio::test]
async fn a_symmetric_rotor_is_loaded_at_mid_span_then_at_both_ends_in_opposition() {
    // A 30 kg disk at mid-span (node 6), bearings at the ends (nodes 0 and 12), 1e6 N/m with
    // 500 N s/m: a bouncing mode near sqrt(2 k / m) = 188 rad/s with one antinode at the disk,
    // and a conical one near sqrt(2 k (L/2)^2 / I_t) = 455 rad/s with antinodes at the ends.
    let disks = json!([{"node": 6, "mass": 30.0, "polar_inertia": 0.6, "transverse_inertia": 0.3}]);
    let supports = json!([{"node": 0, "stiffness": 1e6, "damping": 500.0},
                          {"node": 12, "stiffness": 1e6, "damping": 500.0}]);
    let body = report_body(
        shaft(disks, supports),
        [700.0, 900.0],
        json!([{"node": 6, "diametral": 400e-6}, {"node": 3, "diametral": 1e-6}]),
    );
    let (status, v) = post_json("/v1/report", &body).await;
    assert_eq!(status, 200, "{v}");
    // The default sweep reaches 1.3 x MCS = 1170 rad/s.
    let speeds = v["unbalance"]["speeds"].as_array().unwrap();
    assert!((num(speeds.last().unwrap()) - 1170.0).abs() < 1e-9);
    let n = rpm(900.0);
    // Shaft 7800 x pi/4 x 0.06^2 x 1.2 = 26.47 kg, + 30 kg: W = 56.47 kg, shared equally.
    let mass = 7800.0 * std::f64::consts::FRAC_PI_4 * 0.06f64.powi(2) * 1.2 + 30.0;
    let r = reactions(&v);
    let g = num(&v["static_deflection"]["gravity"]);
    assert!(
        (r[0].1 + r[1].1 - mass * g).abs() < 1e-9 * mass * g,
        "{r:?}"
    );
    let cases = v["unbalance_cases"].as_array().unwrap();
    println!("{} cases", cases.len());
    for c in cases {
        println!(
            "mode {} at {:.1} rad/s: {}",
            c["mode"],
            num(&c["critical_speed"]),
            c["unbalances"]
        );
    }
    assert!(cases.len() >= 2);
    // Mode 1: one antinode, at the disk; W the sum of the journal loads.
    let u = c_unbalances(&cases[0]);
    assert_eq!(u.len(), 1, "{:?}", cases[0]["unbalances"]);
    assert_eq!(u[0].0, 6);
    let w = (r[0].1 + r[1].1) / g;
    assert!((u[0].3 - w).abs() < 1e-9 * w);
    // Ua = 2 x 6350 x 56.47 kg / 8594 rpm = 83.45 g mm.
    let ua = 2.0 * 6350.0 * w / n * 1e-6;
    assert!((ua - 83.45e-6).abs() < 0.05e-6, "{ua}");
    assert!((u[0].1 - ua).abs() < 1e-12 * ua);
    // Mode 2 (conical): both ends, 180 degrees apart, W each journal's load.
    let u = c_unbalances(&cases[1]);
    assert_eq!(u.len(), 2, "{:?}", cases[1]["unbalances"]);
    assert_eq!((u[0].0, u[1].0), (0, 12));
    assert!(((u[1].2 - u[0].2).abs() - std::f64::consts::PI).abs() < 1e-12);
    for (k, x) in u.iter().enumerate() {
        let w = r[k].1 / g;
        assert!((x.3 - w).abs() < 1e-9 * w);
        assert!((x.1 - 2.0 * 6350.0 * w / n * 1e-6).abs() < 1e-12);
    }
    // API 617: N = 8594 rpm < 12,000: Avl = 25.4 um; Scc = Avl / A1 at most 6.
    for c in cases {
        assert_eq!(num(&c["vibration_limit"]), 25.4e-6);
        let a1 = num(&c["max_bearing_amplitude"]);
        let scc = num(&c["scale_factor"]);
        assert!((scc - (25.4e-6 / a1).min(6.0)).abs() < 1e-12, "{scc} {a1}");
        // Peaks carry pk-pk = 2 x 0-pk.
        for node in c["response"]["nodes"].as_array().unwrap() {
            for p in node["peaks"].as_array().unwrap() {
                let (pp, a) = (num(&p["amplitude_peak_to_peak"]), num(&p["amplitude"]));
                assert!((pp - 2.0 * a).abs() <= 1e-15 * pp);
            }
        }
        // The clearances: node 6 with 400 um, node 3 with 1 um (which no response clears).
        let cl = c["clearances"].as_array().unwrap();
        assert_eq!(cl.len(), 2);
        for k in cl {
            let d = num(&k["diametral"]);
            assert_eq!(num(&k["limit"]), 0.75 * d);
            assert_eq!(k["passes"], json!(num(&k["scaled_amplitude"]) < 0.75 * d));
        }
        assert_eq!(cl[1]["passes"], json!(false));
    }
    let checks = v["checks"].as_array().unwrap();
    assert!(checks.iter().any(
        |c| c["check"].as_str().unwrap().contains("clearance at node 3")
            && c["passes"] == json!(false)
    ));
    // The report says what produced it and from what.
    let p = &v["provenance"];
    assert_eq!(p["software"], "whirl");
    assert_eq!(p["version"], env!("CARGO_PKG_VERSION"));
    let sha = p["input_sha256"].as_str().unwrap();
    assert!(sha.len() == 64 && sha.chars().all(|c| c.is_ascii_hexdigit()));
    // Keys in another order, other spacing: the same canonical input, the same hash.
    let text = serde_json::to_string_pretty(&body).unwrap();
    let again: Value = serde_json::from_str(&text).unwrap();
    let (_, w2) = post_json("/v1/report", &again).await;
    assert_eq!(w2["provenance"]["input_sha256"], p["input_sha256"]);
    let mut other = body.clone();
    other["operating_range"]["max"] = json!(901.0);
    let (_, w3) = post_json("/v1/report", &other).await;
    assert_ne!(w3["provenance"]["input_sha256"], p["input_sha256"]);
    // The page shows the cases, the mode shapes and the hash.
    let (status, _, page) = post_as("/v1/report", &body, "text/html").await;
    let page = String::from_utf8(page).unwrap();
    assert_eq!(status, 200);
    assert!(page.contains("Unbalance cases (API 684)"));
    assert!(page.contains("Mode shapes at the critical speeds"));
    assert!(page.contains(sha));
}

/// `(node, amount, phase, weight, rule)` of a case's unbalances.
fn c_unbalances(c: &Value) -> Vec<(u64, f64, f64, f64, String)> {
    c["unbalances"]
        .as_array()
        .unwrap()
        .iter()
        .map(|u| {
            (
                u["node"].as_u64().unwrap(),
                num(&u["amount"]),
                num(&u["phase"]),
                num(&u["weight"]),
                u["rule"].as_str().unwrap().to_string(),
            )
        })
        .collect()
}

#[tokio::test]
async fn an_overhung_disk_is_loaded_with_the_overhung_mass() {
    // Bearings at nodes 0 and 8 (0.8 m), a 40 kg disk at the free end (node 12, 0.4 m out).
    let disks =
        json!([{"node": 12, "mass": 40.0, "polar_inertia": 0.8, "transverse_inertia": 0.4}]);
    let supports = json!([{"node": 0, "stiffness": 5e7, "damping": 3e3},
                          {"node": 8, "stiffness": 5e7, "damping": 3e3}]);
    let (status, v) = post_json(
        "/v1/report",
        &report_body(shaft(disks, supports), [300.0, 400.0], json!([])),
    )
    .await;
    assert_eq!(status, 200, "{v}");
    let cases = v["unbalance_cases"].as_array().unwrap();
    assert!(!cases.is_empty(), "{v}");
    let u = c_unbalances(&cases[0]);
    println!("{:?} at {}", u, cases[0]["critical_speed"]);
    // The first mode swings the overhang: W = the disk + 4 elements of shaft outboard of
    // node 8 = 40 + 7800 x pi/4 x 0.06^2 x 0.4 = 48.82 kg.
    let over = 40.0 + 7800.0 * std::f64::consts::FRAC_PI_4 * 0.06f64.powi(2) * 0.4;
    assert!((over - 48.82).abs() < 0.01);
    assert_eq!(u[0].0, 12);
    assert!(u[0].4.starts_with("overhung"), "{u:?}");
    assert!((u[0].3 - over).abs() < 1e-9 * over);
    assert!((u[0].1 - 2.0 * 6350.0 * over / rpm(400.0) * 1e-6).abs() < 1e-12);
}

#[tokio::test]
async fn the_bundled_compressor_rotor_a_has_its_first_mode_case() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/rotor-a-nvd.report.json"
    );
    let body: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let (status, v) = post_json("/v1/report", &body).await;
    assert_eq!(status, 200, "{v}");
    // Two journals under standard gravity (9.80665 m/s^2): W = 55.60 kg; N = 350 rad/s = 3342.3 rpm:
    // Ua = 2 x 6350 x 55.60 / 3342.3 = 211.3 g mm, at the disk (node 5, mid-span).
    let r = reactions(&v);
    let g = num(&v["static_deflection"]["gravity"]);
    let w = (r[0].1 + r[1].1) / g;
    assert!((w - 55.60).abs() < 0.005, "{w}");
    let c = &v["unbalance_cases"][0];
    assert!((num(&c["critical_speed"]) - 130.2).abs() < 0.05, "{c}");
    let u = c_unbalances(c);
    assert_eq!(u.len(), 1);
    assert_eq!(u[0].0, 5);
    assert!((u[0].1 * 1e6 - 211.3).abs() < 0.05, "{u:?}");
    // N < 12,000 rpm: Avl = 25.4 um; A1 3.16 um pk-pk: Scc = 8.0, capped at 6.
    assert_eq!(num(&v["vibration_limit"]), 25.4e-6);
    let a1 = num(&c["max_bearing_amplitude"]);
    assert!((a1 * 1e6 - 3.16).abs() < 0.005, "{a1}");
    assert_eq!(num(&c["scale_factor"]), 6.0);
}

#[tokio::test]
async fn bearing_sets_repeat_the_audit_each_with_its_own_checks() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/rotor-a-nvd.report.json"
    );
    let mut body: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    body["models"] = json!([{"model": "nonviscous"}]);
    // Minimum clearance stiffens and damps more; maximum softens.
    let set = |k: f64, c: f64| {
        json!([{"node": 0, "stiffness": k, "damping": c, "loss_factor": 0.05},
               {"node": 10, "stiffness": k, "damping": c, "loss_factor": 0.05}])
    };
    body["cases"] = json!([{"name": "minimum clearance", "supports": set(3e6, 2000.0)},
                           {"name": "maximum clearance", "supports": set(1.2e6, 1000.0)}]);
    let (status, v) = post_json("/v1/report", &body).await;
    assert_eq!(status, 200, "{v}");
    let sets = v["bearing_sets"].as_array().unwrap();
    assert_eq!(sets.len(), 2);
    // Each set is the report of the rotor with those supports: the same numbers.
    for (s, (k, c)) in sets.iter().zip([(3e6, 2000.0), (1.2e6, 1000.0)]) {
        let mut alone = body.clone();
        alone["cases"] = Value::Null;
        alone["rotor"]["supports"] = set(k, c);
        let (_, a) = post_json("/v1/report", &alone).await;
        assert_eq!(
            s["campbell"]["critical_speeds"],
            a["campbell"]["critical_speeds"]
        );
        assert_eq!(
            s["level1"]["log_decrement_0"],
            a["level1"]["log_decrement_0"]
        );
        assert_eq!(s["unbalance_cases"], a["unbalance_cases"]);
        let name = s["name"].as_str().unwrap();
        let prefixed = v["checks"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|c| {
                c["check"]
                    .as_str()
                    .unwrap()
                    .starts_with(&format!("[{name}] "))
            })
            .count();
        assert_eq!(prefixed, s["checks"].as_array().unwrap().len());
    }
    // Stiffer bearings, a higher first critical speed.
    let first = |s: &Value| num(&s["campbell"]["critical_speeds"][0]);
    assert!(first(&sets[0]) > num(&v["campbell"]["critical_speeds"][0]));
    assert!(first(&sets[1]) < num(&v["campbell"]["critical_speeds"][0]));
    // A bad set is named where it is wrong.
    body["cases"][1]["supports"][0]["stiffness"] = json!(-1.0);
    let (status, e) = post_json("/v1/report", &body).await;
    assert_eq!(status, 422, "{e}");
    assert!(
        e.to_string().contains("cases[1].supports[0].stiffness"),
        "{e}"
    );
    // The page has the sets' table.
    body["cases"][1]["supports"][0]["stiffness"] = json!(1.2e6);
    let (_, _, page) = post_as("/v1/report", &body, "text/html").await;
    let page = String::from_utf8(page).unwrap();
    assert!(page.contains("Bearing sets") && page.contains("maximum clearance"));
}

#[tokio::test]
async fn mode_shapes_follow_the_elements_shape_functions_between_nodes() {
    // The symmetric rotor's first mode on 4 elements, against the same rotor on 24: the coarse
    // shape's cubic interpolation at mid-element (0.15, 0.45, 0.75, 1.05 m) meets the fine
    // mesh's nodes there; joining the coarse nodes straight would miss by the sag between them.
    let body = |elements: u64, disk: u64, last: u64| {
        let mut rotor = shaft(
            json!([{"node": disk, "mass": 30.0, "polar_inertia": 0.6, "transverse_inertia": 0.3}]),
            json!([{"node": 0, "stiffness": 1e6, "damping": 500.0},
                   {"node": last, "stiffness": 1e6, "damping": 500.0}]),
        );
        rotor["shaft"][0]["elements"] = json!(elements);
        report_body(rotor, [700.0, 900.0], json!([]))
    };
    let (_, coarse) = post_json("/v1/report", &body(4, 2, 4)).await;
    let (_, fine) = post_json("/v1/report", &body(24, 12, 24)).await;
    let curve: Vec<(f64, f64)> = coarse["unbalance_cases"][0]["shape_curve"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| (num(&p[0]), num(&p[1])))
        .collect();
    assert_eq!(curve.len(), 4 * 9);
    let nodes = coarse["unbalance_cases"][0]["shape"].as_array().unwrap();
    // At the nodes the curve is the nodal shape.
    for (e, w) in nodes.windows(2).enumerate() {
        assert!((curve[9 * e].1 - num(&w[0]["value"])).abs() < 1e-12);
        assert!((curve[9 * e + 8].1 - num(&w[1]["value"])).abs() < 1e-12);
    }
    let fine_at = |z: f64| {
        let s = fine["unbalance_cases"][0]["shape"].as_array().unwrap();
        let p = s
            .iter()
            .find(|p| (num(&p["position"]) - z).abs() < 1e-9)
            .unwrap();
        num(&p["value"])
    };
    for e in 0..4 {
        let (z, v) = curve[9 * e + 4];
        let straight = 0.5 * (curve[9 * e].1 + curve[9 * e + 8].1);
        let want = fine_at(z);
        println!("{z:.2} m: cubic {v:.5}, straight {straight:.5}, fine {want:.5}");
        assert!((v - want).abs() < 2e-3, "{z}: {v} vs {want}");
        assert!((v - want).abs() < 0.5 * (straight - want).abs());
    }
}
