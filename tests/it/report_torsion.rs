//! The report's torsional section on a small direct-drive train (a motor shaft and a driven shaft
//! joined by a flexible coupling, on four bearings): its interference diagram and start-up are
//! the torsional `/v1/campbell` and `/v1/time-response` of the same train, to the bit; each mode
//! within reach of an excitation gets API 684's separation check; the page shows the section.

use serde_json::{Value, json};

use crate::common::{post_as, post_json};

fn train() -> Value {
    json!({"type": "beam",
        "materials": {"steel": {"young_modulus": 2.1e11, "density": 7850, "poisson_ratio": 0.3}},
        "shaft": [
            {"length": 0.5, "outer_diameter": 0.08, "material": "steel", "elements": 2},
            {"length": 0.1, "outer_diameter": 0.12,
             "coupling": {"translational_stiffness": 2e7, "angular_stiffness": 8e4,
                          "torsional_stiffness": 2e4, "loss_factor": 0.1,
                          "mass": [4, 4], "polar_inertia": [0.02, 0.02]}},
            {"length": 0.5, "outer_diameter": 0.08, "material": "steel", "elements": 2,
             "stress_concentration": 1.5}],
        "disks": [{"node": 1, "mass": 50, "polar_inertia": 0.5, "transverse_inertia": 0.3},
                  {"node": 4, "mass": 30, "polar_inertia": 0.3, "transverse_inertia": 0.2}],
        "supports": [{"node": 0, "stiffness": 1e8, "damping": 5e3},
                     {"node": 2, "stiffness": 1e8, "damping": 5e3},
                     {"node": 3, "stiffness": 1e8, "damping": 5e3},
                     {"node": 5, "stiffness": 1e8, "damping": 5e3}]})
}

fn motor() -> Value {
    json!({"node": 1, "load_node": 4, "line_frequency": {"value": 50, "unit": "Hz"},
        "synchronous_speed": {"value": 3000, "unit": "rpm"},
        "average_torque": [[0, 400], [0.9, 600], [1, 500]],
        "pulsating_torque": [[0, 200], [1, 20]], "load_torque": [[0, 20], [1, 150]]})
}

#[tokio::test]
async fn the_torsional_section_is_the_trains_own_analyses() {
    let range = json!({"min": 2950, "max": 3000, "unit": "rpm"});
    let report = json!({"rotor": train(), "damping": {"model": "hysteretic"},
        "operating_range": range, "models": [{"model": "hysteretic"}],
        "speeds": {"start": 0, "stop": 3600, "count": 13, "unit": "rpm"},
        "torsion": {"line_frequency": {"value": 50, "unit": "Hz"}, "motor_start": motor(),
                    "duration": 0.5, "output_interval": 0.001}});
    let (status, r) = post_json("/v1/report", &report).await;
    assert_eq!(status, 200, "{r}");
    let t = &r["torsion"];

    let (_, campbell) = post_json(
        "/v1/campbell",
        &json!({"rotor": train(), "damping": {"model": "hysteretic"}, "motion": "torsional",
                "speeds": {"start": 0, "stop": 3600, "count": 13, "unit": "rpm"},
                "interference": {"line_frequency": {"value": 50, "unit": "Hz"},
                                 "operating_range": [2950, 3000]}}),
    )
    .await;
    assert_eq!(t["campbell"]["branches"], campbell["branches"]);
    assert_eq!(t["campbell"]["interference"], campbell["interference"]);
    // The transient under the hysteretic model's time-domain form, the nonviscous model.
    let (_, start) = post_json(
        "/v1/time-response",
        &json!({"rotor": train(), "damping": {"model": "nonviscous"}, "motion": "torsional",
                "motor_start": motor(), "duration": 0.5, "output_interval": 0.001,
                "nodes": [0]}),
    )
    .await;
    assert_eq!(t["transient"]["elements"], start["elements"]);
    assert_eq!(t["transient"]["rigid_motion"], start["rigid_motion"]);
    // The driven shaft's stress carries its concentration factor: 1.5 x 16 T / (pi d^3).
    let e = &start["elements"][3];
    let peak = e["peak"].as_f64().unwrap();
    let want = 1.5 * 16.0 * peak / (std::f64::consts::PI * 0.08f64.powi(3));
    let got = e["peak_stress"].as_f64().unwrap();
    assert!((got - want).abs() <= 1e-12 * want, "{got} vs {want}");

    // A check per mode within 1.5 times the highest excitation (2 f_L = 2x = 100 Hz), with the
    // margin of its nearest excitation.
    let i = &campbell["interference"];
    let checks: Vec<&Value> = r["checks"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|c| c["check"].as_str().unwrap().starts_with("torsional mode"))
        .collect();
    let reach = 1.5 * 100.0 * std::f64::consts::TAU;
    let mut modes = 0;
    for b in campbell["branches"].as_array().unwrap() {
        let nearest = i["criticals"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|k| k["mode"] == b["mode"])
            .min_by(|a, b| {
                a["margin"]
                    .as_f64()
                    .unwrap()
                    .total_cmp(&b["margin"].as_f64().unwrap())
            })
            .unwrap();
        if nearest["frequency"].as_f64().unwrap() > reach {
            continue;
        }
        let c = checks[modes];
        let value = format!("SM {:.1} %", 100.0 * nearest["margin"].as_f64().unwrap());
        assert_eq!(c["value"], json!(value), "{c}");
        assert_eq!(c["passes"], nearest["passes"]);
        modes += 1;
    }
    assert!(modes >= 1 && modes == checks.len(), "{checks:?}");

    let (status, _, page) = post_as("/v1/report", &report, "text/html").await;
    assert_eq!(status, 200);
    let page = String::from_utf8(page).unwrap();
    for s in [
        "id=\"torsion\"",
        "Torsional interference diagram",
        "Shaft torque",
        "peak shear stress",
    ] {
        assert!(page.contains(s), "{s} missing");
    }
}
