//! General supports (anisotropic, cross-coupled, speed-dependent) against ROSS 2.3.0's lateral
//! results on the same rotors (`tests/data/ross/`, made by its `generate.py`), and the limits
//! that tie them to the isotropic model.

use crate::common;

use common::ross::*;
use serde_json::{Value, json};
use whirl::analysis::poles::poles_at;
use whirl::damping::DampedModel;
use whirl::linalg::c64;
use whirl::model::damping::DampingModel;
use whirl::system::{Layout, RotorSystem};

#[test]
fn anisotropic_cross_coupled_bearings_give_rosss_poles() {
    poles_match("aniso.json", 1e-6);
}

#[test]
fn bearing_mass_coefficients_give_rosss_poles() {
    poles_match("aniso_mass.json", 1e-6);
}

#[test]
fn a_seal_with_skew_cross_coupling_gives_rosss_poles() {
    poles_match("seal.json", 1e-6);
    // Skew cross-coupling alone is isotropic: the seal on isotropic bearings stays in the
    // coordinates r, and still matches.
    let d = data("seal.json");
    let iso = &d["isotropic"];
    let s = system(&iso["rotor"]);
    assert_eq!(s.layout(), Layout::Single);
    let model = DampedModel::build(&s, &damping(json!({"model": "viscous"}), s.n())).unwrap();
    for case in iso["poles"].as_array().unwrap() {
        let speed = case["speed"].as_f64().unwrap();
        let set = poles_at(&model, speed).unwrap();
        // In r alone each pole is its own; ROSS's real system has every conjugate too.
        let mut computed = spectrum(&set, false);
        computed.extend(computed.clone().iter().map(|s| s.conj()));
        let e = distance(&eigenvalues(&case["eigenvalues"]), &computed);
        assert!(e <= 1e-6, "isotropic seal at {speed}: {e:.2e}");
    }
}

#[test]
fn tabulated_coefficients_give_rosss_poles_at_and_between_table_speeds() {
    poles_match("speed_dependent.json", 1e-6);
}

#[test]
fn rosss_rotor_example_and_compressor_give_its_poles() {
    poles_match("rotor_example.json", 1e-6);
    poles_match("compressor_example.json", 1e-6);
}

#[test]
fn unbalance_responses_are_rosss_x_and_y_amplitudes_and_phases() {
    unbalance_match("aniso.json", 1e-6);
    unbalance_match("speed_dependent.json", 1e-6);
    unbalance_match("rotor_example.json", 1e-6);
    unbalance_match("compressor_example.json", 1e-6);
}

/// The bundled Example 1 rotor with its supports written in the general form, and a copy
/// whose first support is anisotropic by `epsilon` (so that it is solved in doubled
/// coordinates).
fn example1_general(epsilon: f64) -> (RotorSystem, RotorSystem) {
    let path = format!(
        "{}/examples/example1-nvd.modal.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let v: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let mut rotor = v["rotor"].clone();
    let iso = rotor.clone();
    for s in rotor["supports"].as_array_mut().unwrap() {
        let k = s["stiffness"].as_f64().unwrap();
        let eta = s["loss_factor"].as_f64().unwrap();
        *s = json!({"node": s["node"], "kxx": k, "kxy": 0.0, "kyx": 0.0, "kyy": k,
                    "cxx": 150.0, "cyy": 150.0, "loss_factor": eta});
    }
    let mut anisotropic = rotor.clone();
    let k = anisotropic["supports"][0]["kxx"].as_f64().unwrap();
    anisotropic["supports"][0]["kyy"] = json!(k * (1.0 + epsilon));
    let mut iso = iso;
    for s in iso["supports"].as_array_mut().unwrap() {
        s["damping"] = json!(150.0);
    }
    let general = system(&rotor);
    assert_eq!(general.layout(), Layout::Single);
    let a = system(&anisotropic);
    assert_eq!(a.layout(), Layout::Doubled);
    // The isotropic form and the general form with equal, uncoupled coefficients.
    let isotropic = system(&iso);
    assert!(isotropic.supports.is_empty() && !general.supports.is_empty());
    for model in all_models(isotropic.n()) {
        let p = DampedModel::build(&isotropic, &model).unwrap();
        let q = DampedModel::build(&general, &model).unwrap();
        for speed in [0.0, 1400.0, 3500.0] {
            let (a, b) = (poles_at(&p, speed).unwrap(), poles_at(&q, speed).unwrap());
            let e = distance(
                &a.all().map(|p| p.s).collect::<Vec<_>>(),
                &b.all().map(|p| p.s).collect::<Vec<_>>(),
            );
            assert!(e <= 1e-9, "{} at {speed}: {e:.2e}", model.name());
        }
    }
    (general, a)
}

fn all_models(n: usize) -> Vec<DampingModel> {
    vec![
        damping(json!({"model": "viscous"}), n),
        damping(json!({"model": "hysteretic"}), n),
        damping(json!({"model": "equivalent"}), n),
        damping(json!({"model": "nonviscous"}), n),
    ]
}

#[test]
fn isotropic_limits_of_the_general_form_and_of_doubled_coordinates() {
    // The general form with 8 equal-and-uncoupled coefficients gives the isotropic form's
    // poles (checked inside), and the doubled problem of a barely anisotropic rotor reports
    // the single problem's poles, each once, under every model.
    let (single, doubled) = example1_general(1e-10);
    for model in all_models(single.n()) {
        let p = DampedModel::build(&single, &model).unwrap();
        let q = DampedModel::build(&doubled, &model).unwrap();
        for speed in [0.0, 1400.0, 3500.0] {
            let (a, b) = (poles_at(&p, speed).unwrap(), poles_at(&q, speed).unwrap());
            // At rest forward and backward whirl are degenerate, and any two orbits of the
            // pair are modes: compare frequencies without their sign there.
            let key = |s: c64| {
                if speed == 0.0 {
                    c64::new(s.re, s.im.abs())
                } else {
                    s
                }
            };
            let ra: Vec<c64> = a.rotor.iter().map(|p| key(p.s)).collect();
            let rb: Vec<c64> = b.rotor.iter().map(|p| key(p.s)).collect();
            assert_eq!(ra.len(), rb.len(), "{} at {speed}", model.name());
            let e = distance(&ra, &rb);
            assert!(
                e <= 1e-7,
                "{} at {speed}: rotor poles {e:.2e}",
                model.name()
            );
            for p in b.rotor.iter().filter(|_| speed > 0.0) {
                assert!(
                    (p.whirl_ratio.abs() - 1.0).abs() < 1e-4,
                    "{}: circular whirl, got ratio {}",
                    model.name(),
                    p.whirl_ratio
                );
            }
            // Internal poles: the single problem's, each once.
            let ia: Vec<c64> = a.internal.iter().map(|p| p.s).collect();
            let ib: Vec<c64> = b.internal.iter().map(|p| p.s).collect();
            if !ia.is_empty() {
                assert!(
                    distance(&ia, &ib) <= 1e-6,
                    "{} internal at {speed}",
                    model.name()
                );
            }
        }
    }
}

async fn post(path: &str, body: Value) -> (u16, Value) {
    use http_body_util::BodyExt;
    use tower::ServiceExt;
    let req = axum::http::Request::post(path)
        .header("content-type", "application/json")
        .body(axum::body::Body::from(body.to_string()))
        .unwrap();
    let resp = whirl::service::app(whirl::service::Config::default())
        .oneshot(req)
        .await
        .unwrap();
    let status = resp.status().as_u16();
    let bytes = resp.into_body().collect().await.unwrap().to_bytes();
    (status, serde_json::from_slice(&bytes).unwrap())
}

#[tokio::test]
async fn bad_supports_are_422_naming_the_field() {
    let rotor = data("aniso.json")["rotor"].clone();
    let with = |support: Value| {
        let mut r = rotor.clone();
        r["supports"][0] = support;
        json!({"rotor": r, "damping": {"model": "viscous"}, "speed": 100})
    };
    let cases = [
        (
            json!({"node": 0, "stiffness": 1e6, "kxx": 1e6}),
            "rotor.supports[0].stiffness",
        ),
        (
            json!({"node": 0, "kxx": [1e6, 2e6]}),
            "rotor.supports[0].kxx",
        ),
        (
            json!({"node": 0, "kxx": [1e6, 2e6], "kyy": [1e6, 2e6, 3e6], "speeds": [100, 200]}),
            "rotor.supports[0].kyy",
        ),
        (
            json!({"node": 0, "kxx": [1e6, 2e6], "speeds": [200, 100]}),
            "rotor.supports[0].speeds[1]",
        ),
        (
            json!({"node": 0, "kxx": 1e6, "cxy": "a lot"}),
            "rotor.supports[0].cxy",
        ),
        (
            json!({"node": 0, "kxx": 1e6, "loss_factor": 1.5}),
            "rotor.supports[0].loss_factor",
        ),
        (json!({"node": 0}), "rotor.supports[0].stiffness"),
        (json!({"node": 99, "kxx": 1e6}), "rotor.supports[0].node"),
    ];
    for (support, path) in cases {
        let (status, v) = post("/v1/modal", with(support.clone())).await;
        assert_eq!(status, 422, "{support}: {v}");
        let paths: Vec<&str> = v["errors"]
            .as_array()
            .unwrap()
            .iter()
            .map(|e| e["path"].as_str().unwrap())
            .collect();
        assert!(paths.contains(&path), "{support}: {path} not in {paths:?}");
    }
}

#[tokio::test]
async fn answers_carry_whirl_ratios_elliptical_orbits_and_table_warnings() {
    // Tabulated bearings from 200 rad/s: a sweep from 50 rad/s holds them below the table.
    let mut body = serde_json::from_str::<Value>(
        &std::fs::read_to_string(format!(
            "{}/examples/fluid-film.unbalance-response.json",
            env!("CARGO_MANIFEST_DIR")
        ))
        .unwrap(),
    )
    .unwrap();
    body["speeds"] = json!({"start": 50, "stop": 400, "count": 8});
    let (status, v) = post("/v1/unbalance-response", body).await;
    assert_eq!(status, 200, "{v}");
    let warnings = v["warnings"].as_array().unwrap();
    assert_eq!(warnings.len(), 2, "{warnings:?}");
    assert!(
        warnings[0]
            .as_str()
            .unwrap()
            .contains("rotor.supports[0]: below its table")
    );
    let node = &v["nodes"][1];
    for i in 0..8 {
        let (major, minor) = (
            node["major"][i].as_f64().unwrap(),
            node["minor"][i].as_f64().unwrap(),
        );
        let (x, y) = (
            node["x_amplitude"][i].as_f64().unwrap(),
            node["y_amplitude"][i].as_f64().unwrap(),
        );
        assert!(minor < major && node["amplitude"][i] == node["major"][i]);
        // The axes bound the x and y amplitudes.
        assert!(x <= major * (1.0 + 1e-12) && y <= major * (1.0 + 1e-12) && x.max(y) >= minor);
    }
    let (status, v) = post(
        "/v1/modal",
        json!({"rotor": data("aniso.json")["rotor"], "damping": {"model": "viscous"}, "speed": 300}),
    )
    .await;
    assert_eq!(status, 200);
    for p in v["poles"].as_array().unwrap() {
        let r = p["whirl_ratio"].as_f64().unwrap();
        let w = p["frequency"].as_f64().unwrap();
        assert!(
            (-1.0..=1.0).contains(&r) && (r * w >= -1e-9 || r.abs() < 1e-6),
            "{p}"
        );
    }
}

#[test]
fn the_compressors_log_decrement_is_rosss_and_averaging_its_supports_doubles_it() {
    // ROSS's compressor (mapped, 14 tabulated bearings and seals) at 10,000 rpm: the first
    // forward mode's log decrement, with the real supports and with every support averaged
    // to isotropic (the seals' skew cross-coupling dropped), as ROSS gives them.
    let d = data("compressor_example.json");
    let speed = d["log_decrement"]["speed"].as_f64().unwrap();
    let reference = &d["log_decrement"]["variant_frozen"];
    let mut averaged = d["rotor"].clone();
    for s in averaged["supports"].as_array_mut().unwrap() {
        let avg = |a: &Value, b: &Value| -> Value {
            match (a, b) {
                (Value::Array(x), Value::Array(y)) => Value::Array(
                    x.iter()
                        .zip(y)
                        .map(|(p, q)| json!(0.5 * (p.as_f64().unwrap() + q.as_f64().unwrap())))
                        .collect(),
                ),
                _ => json!(0.5 * (a.as_f64().unwrap_or(0.0) + b.as_f64().unwrap_or(0.0))),
            }
        };
        let (k, c) = (avg(&s["kxx"], &s["kyy"]), avg(&s["cxx"], &s["cyy"]));
        for (f, v) in [("kxx", &k), ("kyy", &k), ("cxx", &c), ("cyy", &c)] {
            s[f] = v.clone();
        }
        for f in ["kxy", "kyx", "cxy", "cyx"] {
            s[f] = json!(0.0);
        }
    }
    for (rotor, variant) in [(&d["rotor"], "real"), (&averaged, "all_supports_averaged")] {
        let s = system(rotor);
        let model = DampedModel::build(&s, &damping(json!({"model": "viscous"}), s.n())).unwrap();
        let want = &reference[variant]["eigenvalue"];
        let want = c64::new(want[0].as_f64().unwrap(), want[1].as_f64().unwrap());
        let set = poles_at(&model, speed).unwrap();
        let p = set
            .rotor
            .iter()
            .min_by(|a, b| (a.s - want).norm().total_cmp(&(b.s - want).norm()))
            .unwrap();
        let log_dec = p.log_decrement().unwrap();
        let ross = reference[variant]["log_dec"].as_f64().unwrap();
        println!(
            "{variant}: log decrement {log_dec:.6} (ROSS {ross:.6}), whirl ratio {:.3}",
            p.whirl_ratio
        );
        assert!((p.s - want).norm() <= 1e-8 * want.norm());
        assert!((log_dec - ross).abs() <= 1e-6 * ross);
    }
}
