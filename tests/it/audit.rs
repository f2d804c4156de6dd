//! The audit analyses against closed forms, through HTTP: Level I's `q0` of a Jeffcott rotor
//! under the viscous, hysteretic and equivalent models, the amplification factor of a single
//! mode, the frequency response of a Jeffcott rotor, and the frequency response at the spin
//! speed against the unbalance response on anisotropic supports.

use crate::common;

use common::{post_as, post_json};
use serde_json::{Value, json};

fn num(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

fn jeffcott(extra: Value) -> Value {
    let mut r = json!({"type": "jeffcott", "mass": 1.0, "stiffness": 1.0});
    for (k, v) in extra.as_object().unwrap() {
        r[k] = v.clone();
    }
    r
}

#[tokio::test]
async fn level1_q0_of_a_viscous_jeffcott_rotor_is_c_sqrt_k_over_m() {
    // m s^2 + c s + k - i q = 0 crosses Re s = 0 at s = i sqrt(k/m), q0 = c sqrt(k/m).
    let (m, k, c): (f64, f64, f64) = (2.0, 1e6, 200.0);
    let rotor = json!({"type": "jeffcott", "mass": m, "stiffness": k, "damping_nonrotating": c});
    for speed in [0.0, 300.0] {
        let body = json!({"rotor": rotor, "damping": {"model": "viscous"}, "speed": speed,
                          "node": 0, "cross_coupling": {"start": 0, "stop": 3e5, "count": 7}});
        let (status, v) = post_json("/v1/level1", &body).await;
        assert_eq!(status, 200, "{v}");
        let exact = c * (k / m).sqrt();
        let q0 = num(&v["q0"]);
        assert!((q0 / exact - 1.0).abs() < 1e-6, "q0 {q0} vs {exact}");
        // Below q0 stable, above unstable; the first point is the rotor without it.
        let ld = v["log_decrement"].as_array().unwrap();
        assert!((num(&ld[0]) - num(&v["log_decrement_0"])).abs() < 1e-12);
        assert!(num(&ld[2]) > 0.0 && num(&ld[3]) < 0.0, "{v}");
    }
    // Without a range, 21 values up to about twice q0, found first.
    let body = json!({"rotor": rotor, "damping": {"model": "viscous"}, "speed": 0, "node": 0});
    let (status, v) = post_json("/v1/level1", &body).await;
    assert_eq!(status, 200, "{v}");
    let q = v["cross_coupling"].as_array().unwrap();
    let exact = c * (k / m).sqrt();
    assert_eq!(q.len(), 21);
    assert!((num(&v["q0"]) / exact - 1.0).abs() < 1e-6, "{v}");
    let top = num(&q[20]) / exact;
    assert!((1.0..=8.0).contains(&top), "range ends at {top} q0");
}

#[tokio::test]
async fn level1_margins_differ_between_hysteretic_and_equivalent_damping() {
    // At s = i omega with omega_n = 1, spun at Omega = 0.5 < omega_n:
    //   hysteretic: q0 = (eta_n + eta_r) k (the rotor material sees omega - Omega > 0);
    //   equivalent: q0 = eta_n k + eta_r k (1 - Omega / omega_n) (its circulatory term).
    let (er, en, speed) = (0.01, 0.02, 0.5);
    let rotor = jeffcott(json!({"loss_factor_rotating": er, "loss_factor_nonrotating": en}));
    let mut q0 = std::collections::BTreeMap::new();
    for model in ["hysteretic", "equivalent", "nonviscous"] {
        let body = json!({"rotor": rotor, "damping": {"model": model}, "speed": speed,
                          "node": 0, "cross_coupling": {"start": 0, "stop": 0.05, "count": 6}});
        let (status, v) = post_json("/v1/level1", &body).await;
        assert_eq!(status, 200, "{model}: {v}");
        q0.insert(model, num(&v["q0"]));
    }
    let h = en + er;
    let e = en + er * (1.0 - speed);
    assert!((q0["hysteretic"] / h - 1.0).abs() < 1e-6, "{q0:?}");
    assert!((q0["equivalent"] / e - 1.0).abs() < 1e-6, "{q0:?}");
    // The nonviscous model approximates the hysteretic one (3 branches a decade apart).
    assert!((q0["nonviscous"] / h - 1.0).abs() < 0.1, "{q0:?}");
}

#[tokio::test]
async fn level1_with_machine_data_gives_api_617_qa() {
    let rotor =
        json!({"type": "jeffcott", "mass": 2.0, "stiffness": 1e6, "damping_nonrotating": 200.0});
    // One stage: 2 MW, D = 0.4 m, H = 20 mm, at 10,000 rpm (1047.198 rad/s). The stage torque
    // T = P / Omega = 2e6 W / 1047.198 rad/s = 1909.86 N m; Wachel's q_A = B_c T / (D H) =
    // 3 x 1909.86 N m / (0.4 m x 0.02 m) = 716,197 N/m (N m / m^2 = N/m). API 617's form,
    // 9.55 P[kW] / N[rpm] = 1.91 kN m = 1910 kN mm over D H = 8000 mm^2, times B_c: 0.716
    // kN/mm, the same.
    let speed = 10_000.0 * std::f64::consts::PI / 30.0;
    let torque = 2e6 / speed;
    assert!((torque - 1909.859).abs() < 1e-3);
    let qa = 3.0 * torque / (0.4 * 0.02);
    assert!((qa - 716_197.2).abs() < 0.1, "{qa}");
    let kn_per_mm = 3.0 * 9.549_296_6 * 2000.0 / 10_000.0 * 1000.0 / (400.0 * 20.0);
    assert!((kn_per_mm * 1e6 / qa - 1.0).abs() < 1e-8);
    let body = json!({"rotor": rotor, "damping": {"model": "viscous"}, "speed": speed,
                      "cross_coupling": {"start": 0, "stop": 3e5, "count": 4},
                      "machine": {"stages": [{"node": 0, "power": 2e6, "diameter": 0.4, "width": 0.02}]}});
    let (status, v) = post_json("/v1/level1", &body).await;
    assert_eq!(status, 200, "{v}");
    assert!((num(&v["qa"]) / qa - 1.0).abs() < 1e-12, "{v}");
    // q0 = c sqrt(k/m) = 200 N s/m x 707.107 1/s = 141,421 N/m: q0 / q_A = 0.197 < 2, and the
    // log decrement at q_A is negative: Level II is required, for both reasons.
    assert!(
        (num(&v["q0"]) / (200.0 * 500_000f64.sqrt()) - 1.0).abs() < 1e-6,
        "{v}"
    );
    assert!((num(&v["ratio"]) - 0.19746).abs() < 1e-4, "{v}");
    assert_eq!(v["level2_required"], json!(true), "{v}");
    assert_eq!(v["passes"], json!(false), "{v}");
    let reasons: Vec<&str> = v["level2_reasons"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r.as_str().unwrap())
        .collect();
    assert!(reasons[0].starts_with("q0 / q_A = 0.197"), "{reasons:?}");
    assert!(reasons[1].contains("log decrement at q_A"), "{reasons:?}");
    // A stage a hundredth as strong: q0 / q_A = 19.7, log decrement at q_A well above 0.1.
    let mut body = body;
    body["machine"]["stages"][0]["power"] = json!(2e4);
    let (_, v) = post_json("/v1/level1", &body).await;
    assert_eq!(v["level2_required"], json!(false), "{v}");
    assert!(v["level2_reasons"].is_null(), "{v}");
}

#[tokio::test]
async fn level1_screens_the_critical_speed_ratio_against_region_b() {
    // A uniform steel shaft 2 m long, 50 mm, 40 elements, pinned at its ends: the first
    // critical speed on rigid supports is pi^2 sqrt(E I / (rho A L^4)) = 9.8696 x
    // sqrt(2.11e11 Pa x 3.068e-7 m^4 / (7810 kg/m^3 x 1.963e-3 m^2 x 16 m^4)) = 160.31 rad/s
    // (Euler-Bernoulli; shear and rotary inertia lower it by (pi r / L)^2-order terms, 1e-3).
    let d: f64 = 0.05;
    let (e, rho, l): (f64, f64, f64) = (2.11e11, 7810.0, 2.0);
    let (i, a) = (
        std::f64::consts::PI * d.powi(4) / 64.0,
        std::f64::consts::PI * d * d / 4.0,
    );
    let pinned = std::f64::consts::PI.powi(2) * (e * i / (rho * a * l.powi(4))).sqrt();
    assert!((pinned - 160.31).abs() < 0.01, "{pinned}");
    let rotor = json!({"type": "beam",
        "materials": {"steel": {"young_modulus": e, "density": rho, "poisson_ratio": 0.3,
                                "loss_factor": 0.0}},
        "shaft": [{"length": l, "outer_diameter": d, "inner_diameter": 0.0, "material": "steel",
                   "elements": 40}],
        "supports": [{"node": 0, "stiffness": 1e6, "damping": 1e4},
                     {"node": 40, "stiffness": 1e6, "damping": 1e4}]});
    // MCS 3.2 x the rigid critical speed; a stage that leaves 2 <= q0 / q_A < 10.
    let speed = 3.2 * pinned;
    let mut body = json!({"rotor": rotor, "damping": {"model": "viscous"}, "speed": speed,
                          "machine": {"stages": [{"node": 20, "power": 1e4, "diameter": 0.3,
                                                  "width": 0.02}],
                                      "mean_gas_density": 10.0}});
    let (status, v) = post_json("/v1/level1", &body).await;
    assert_eq!(status, 200, "{v}");
    let rigid = num(&v["rigid_critical_speed"]);
    assert!((rigid / pinned - 1.0).abs() < 2e-3, "{rigid} vs {pinned}");
    let csr = num(&v["critical_speed_ratio"]);
    assert!((csr - speed / rigid).abs() < 1e-12);
    // q_A = 3 x (10 kW / 513.0 rad/s) / (0.3 m x 0.02 m) = 3 x 19.49 N m / 0.006 m^2 = 9747 N/m.
    assert!((num(&v["qa"]) / 9746.6 - 1.0).abs() < 1e-4, "{v}");
    let ratio = num(&v["ratio"]);
    assert!(
        (2.0..10.0).contains(&ratio),
        "pick a stage for 2 <= q0/qa < 10: {v}"
    );
    // 10 kg/m^3: the boundary is 2.5, CSR 3.2 > 2.5: Region B, Level II.
    assert_eq!(v["region"], "B", "{v}");
    assert_eq!(v["level2_required"], json!(true), "{v}");
    // 16.53 to 60 kg/m^3: 2.69 - 0.0115 rho; at 30 kg/m^3 2.345. A CSR of 2.2 is Region A.
    body["speed"] = json!(2.2 * rigid);
    body["machine"]["mean_gas_density"] = json!(30.0);
    let (_, v) = post_json("/v1/level1", &body).await;
    assert!((2.0..10.0).contains(&num(&v["ratio"])), "{v}");
    assert!(num(&v["log_decrement_at_qa"]) >= 0.1, "{v}");
    assert_eq!(v["region"], "A", "{v}");
    assert_eq!(v["level2_required"], json!(false), "{v}");
    // Without a density the screen cannot clear a ratio below 10.
    body["machine"]["mean_gas_density"] = Value::Null;
    let (_, v) = post_json("/v1/level1", &body).await;
    assert!(v["region"].is_null());
    assert!((2.0..10.0).contains(&num(&v["ratio"])), "{v}");
    assert_eq!(v["level2_required"], json!(true), "{v}");
}

#[test]
fn region_boundary_is_api_617s_line() {
    use whirl::analysis::audit::level1::region_boundary;
    assert_eq!(region_boundary(0.0), 2.5);
    assert_eq!(region_boundary(16.53), 2.5);
    // 2.69 - 0.0115 x 30 = 2.345; at 60 kg/m^3 2.0; past it nothing is Region A.
    assert!((region_boundary(30.0) - 2.345).abs() < 1e-12);
    assert!((region_boundary(60.0) - 2.0).abs() < 1e-12);
    assert_eq!(region_boundary(61.0), 0.0);
    // Continuous at 16.53 to the line's rounding: 2.69 - 0.0115 x 16.53 = 2.4999.
    assert!((2.69 - 0.0115 * 16.53 - 2.5f64).abs() < 1e-3);
}

/// The peak and half-power points of `Omega^2 / |k - m Omega^2 + i c Omega|` (m = k = 1) by
/// bisection on the closed form.
fn single_mode_af(c: f64) -> (f64, f64, f64) {
    let h = |w: f64| w * w / ((1.0 - w * w).powi(2) + (c * w).powi(2)).sqrt();
    let zeta = c / 2.0;
    let peak = 1.0 / (1.0 - 2.0 * zeta * zeta).sqrt();
    let target = h(peak) / std::f64::consts::SQRT_2;
    let bisect = |mut a: f64, mut b: f64| {
        for _ in 0..200 {
            let m = 0.5 * (a + b);
            if (h(m) - target).signum() == (h(a) - target).signum() {
                a = m;
            } else {
                b = m;
            }
        }
        0.5 * (a + b)
    };
    (peak, bisect(0.5, peak), bisect(peak, 2.0))
}

#[tokio::test]
async fn a_single_mode_amplification_factor_is_one_over_two_zeta() {
    let c = 0.04; // zeta = 0.02
    let body = json!({"rotor": jeffcott(json!({"damping_nonrotating": c})),
                      "damping": {"model": "viscous"},
                      "speeds": {"start": 0, "stop": 2, "count": 41},
                      "unbalances": [{"node": 0, "amount": 1e-3}],
                      "operating_range": {"min": 1.2, "max": 1.5}});
    let (status, v) = post_json("/v1/unbalance-response", &body).await;
    assert_eq!(status, 200, "{v}");
    let peaks = v["nodes"][0]["peaks"].as_array().unwrap();
    assert_eq!(peaks.len(), 1, "{v}");
    let p = &peaks[0];
    let (nc, n1, n2) = single_mode_af(c);
    // Refined off the 0.05 grid onto the curve itself.
    assert!((num(&p["speed"]) - nc).abs() < 1e-7, "{p}");
    assert!((num(&p["half_power"][0]) - n1).abs() < 1e-8, "{p}");
    assert!((num(&p["half_power"][1]) - n2).abs() < 1e-8, "{p}");
    let af = num(&p["amplification_factor"]);
    assert!((af / (nc / (n2 - n1)) - 1.0).abs() < 1e-7, "{p}");
    assert!(
        (af * 2.0 * 0.02 - 1.0).abs() < 0.02,
        "AF {af} vs 1/(2 zeta) = 25"
    );
    // Below the range: SM = 100 (1.2 - N_c) / 1.2, required min(16, 17 (1 - 1 / (AF - 1.5))).
    let sm = 100.0 * (1.2 - nc) / 1.2;
    assert!((num(&p["separation_margin"]) - sm).abs() < 1e-5, "{p}");
    let req = (17.0 * (1.0 - 1.0 / (af - 1.5))).min(16.0);
    assert!((num(&p["required_margin"]) - req).abs() < 1e-9, "{p}");
    assert_eq!(p["passes"], json!(sm >= req));
}

#[tokio::test]
async fn frequency_response_of_a_jeffcott_rotor() {
    use num_complex::Complex64 as C;
    let i = C::new(0.0, 1.0);
    let sgn = |x: f64| {
        if x > 0.0 {
            1.0
        } else if x < 0.0 {
            -1.0
        } else {
            0.0
        }
    };
    let ws = [0.2, 0.7, 1.0, 1.3];
    // Hysteretic (exact in the frequency domain), spun at 0.5.
    let (er, en, speed) = (0.01, 0.02, 0.5);
    let h = |w: f64| C::new(1.0 - w * w, 0.0) + i * en * sgn(w) + i * er * sgn(w - speed);
    // Viscous with rotating damping, spun at 2: its circulatory term -i Omega c_r.
    let (cr, cn, speed2) = (0.05, 0.03, 2.0);
    let v = |w: f64| C::new(1.0 - w * w, 0.0) + i * (cn + cr) * w - i * speed2 * cr;
    type Denominator<'a> = &'a dyn Fn(f64) -> C;
    let cases: [(Value, f64, Denominator); 2] = [
        (
            json!({"rotor": jeffcott(json!({"loss_factor_rotating": er, "loss_factor_nonrotating": en})),
                   "damping": {"model": "hysteretic"}}),
            speed,
            &h,
        ),
        (
            json!({"rotor": jeffcott(json!({"damping_rotating": cr, "damping_nonrotating": cn})),
                   "damping": {"model": "viscous"}}),
            speed2,
            &v,
        ),
    ];
    for (base, spin, d) in cases {
        for (direction, fwd, bwd) in [(json!("forward"), 1.0, 0.0), (json!(0.0), 0.5, 0.5)] {
            let mut body = base.clone();
            body["speed"] = json!(spin);
            body["input"] = json!({"node": 0, "direction": direction});
            body["output"] = json!({"node": 0});
            body["frequencies"] = json!(ws);
            let (status, r) = post_json("/v1/frequency-response", &body).await;
            assert_eq!(status, 200, "{r}");
            for (k, &w) in ws.iter().enumerate() {
                let f = fwd / d(w).norm();
                let b = bwd / d(-w).norm();
                let got_f = num(&r["forward"][k]);
                let got_b = num(&r["backward"][k]);
                assert!(
                    (got_f - f).abs() <= 1e-12 * f.max(1.0),
                    "{w}: {got_f} vs {f}"
                );
                assert!(
                    (got_b - b).abs() <= 1e-12 * b.max(1.0),
                    "{w}: {got_b} vs {b}"
                );
            }
        }
    }
}

#[tokio::test]
async fn frequency_response_at_the_spin_speed_is_the_unbalance_response() {
    // Anisotropic, cross-coupled bearings (doubled coordinates): a unit forward force at
    // omega = Omega, scaled by m e Omega^2, is the unbalance's load.
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/ross/aniso.json");
    let data: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let rotor = &data["rotor"];
    let me = 1e-4;
    for speed in [124.0, 700.0] {
        let body = json!({"rotor": rotor, "damping": {"model": "viscous"},
                          "speeds": [speed, speed * 1.01], "nodes": [0, 5],
                          "unbalances": [{"node": 5, "amount": me}]});
        let (status, u) = post_json("/v1/unbalance-response", &body).await;
        assert_eq!(status, 200, "{u}");
        for (k, node) in [0, 5].into_iter().enumerate() {
            let body = json!({"rotor": rotor, "damping": {"model": "viscous"}, "speed": speed,
                              "input": {"node": 5, "direction": "forward"},
                              "output": {"node": node}, "frequencies": [speed]});
            let (status, f) = post_json("/v1/frequency-response", &body).await;
            assert_eq!(status, 200, "{f}");
            let scale = me * speed * speed;
            for (a, b) in [
                ("x_amplitude", "x_amplitude"),
                ("y_amplitude", "y_amplitude"),
            ] {
                let fr = num(&f[a][0]) * scale;
                let ub = num(&u["nodes"][k][b][0]);
                // Two solves of the same system with differently scaled loads: round-off times
                // its condition number at the 124 rad/s peak (about 1e6).
                assert!(
                    (fr / ub - 1.0).abs() < 1e-9,
                    "{speed} node {node} {a}: {fr} vs {ub}"
                );
            }
            let dphase = num(&f["x_phase"][0]) - num(&u["nodes"][k]["x_phase"][0]);
            assert!(dphase.sin().abs() < 1e-10 && dphase.cos() > 0.0);
        }
    }
}

#[tokio::test]
async fn audit_endpoints_name_the_bad_field() {
    let jeff = jeffcott(json!({}));
    let cases = [
        (
            "/v1/critical-speed-map",
            json!({"rotor": jeff, "stiffness": {"start": 1e5, "stop": 1e9, "count": 5}}),
            "rotor.type",
        ),
        (
            "/v1/level1",
            json!({"rotor": jeff, "damping": {"model": "viscous"}, "speed": 1,
                   "cross_coupling": {"start": 0, "stop": 1, "count": 3}}),
            "node",
        ),
        (
            "/v1/level1",
            json!({"rotor": jeff, "damping": {"model": "viscous"}, "speed": 1, "node": 3,
                   "cross_coupling": {"start": 0, "stop": 1, "count": 3}}),
            "node",
        ),
        (
            "/v1/frequency-response",
            json!({"rotor": jeff, "damping": {"model": "viscous"}, "input": {"node": 0, "direction": "up"},
                   "output": {"node": 0}, "frequencies": [1.0]}),
            "input.direction",
        ),
        (
            "/v1/frequency-response",
            json!({"rotor": jeff, "damping": {"model": "viscous"}, "input": {"node": 0},
                   "output": {"node": 0}, "frequencies": {"start": 0, "stop": 2, "count": 3}}),
            "frequencies",
        ),
        (
            "/v1/unbalance-response",
            json!({"rotor": jeff, "damping": {"model": "viscous"}, "speeds": [1, 2],
                   "unbalances": [{"node": 0, "amount": 1e-3}],
                   "operating_range": {"min": 2, "max": 1}}),
            "operating_range.max",
        ),
    ];
    for (uri, body, path) in cases {
        let (status, v) = post_json(uri, &body).await;
        assert_eq!(status, 422, "{uri}: {v}");
        let paths: Vec<&str> = v["errors"]
            .as_array()
            .unwrap()
            .iter()
            .map(|e| e["path"].as_str().unwrap())
            .collect();
        assert!(paths.contains(&path), "{uri}: {paths:?} lacks {path}: {v}");
    }
    // A report is JSON or HTML, never a table.
    let (status, _, _) = post_as(
        "/v1/level1",
        &json!({"rotor": jeff, "damping": {"model": "viscous"}, "speed": 1, "node": 0,
                "cross_coupling": {"start": 0, "stop": 1, "count": 3}}),
        "text/html",
    )
    .await;
    assert_eq!(status, 406);
}

#[tokio::test]
async fn the_report_gathers_the_audit_and_renders_as_a_page() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/rotor-a-nvd.report.json"
    );
    let body: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let (status, v) = post_json("/v1/report", &body).await;
    assert_eq!(status, 200, "{v}");
    let models: Vec<&str> = v["models"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m["model"].as_str().unwrap())
        .collect();
    assert_eq!(
        models,
        ["hysteretic", "equivalent", "nonviscous", "viscous"]
    );
    // The report's own model (nonviscous) is the one its Campbell and Level I show.
    assert_eq!(v["level1"]["model"], "nonviscous");
    assert_eq!(
        v["models"][2]["critical_speeds"], v["campbell"]["critical_speeds"],
        "the primary model's sweep is the report's"
    );
    // Every model finds the first critical speed below the operating range with an AF and
    // a margin, and each check has a verdict.
    for m in v["models"].as_array().unwrap() {
        let p = &m["peaks"][0];
        assert!(
            num(&p["speed"]) < 250.0 && num(&p["amplification_factor"]) > 2.5,
            "{m}"
        );
        assert!(num(&m["q0"]) > 0.0, "{m}");
    }
    let checks = v["checks"].as_array().unwrap();
    assert!(checks.len() >= 3 * models.len(), "{checks:?}");
    // Reactions balance the weight; the map has 4 modes over 31 stiffnesses.
    let s = &v["static_deflection"];
    let sum: f64 = s["supports"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| num(&r["reaction"]))
        .sum();
    assert!((sum / num(&s["weight"]) - 1.0).abs() < 1e-9, "{s}");
    assert_eq!(
        v["critical_speed_map"]["frequencies"]
            .as_array()
            .unwrap()
            .len(),
        4
    );
    assert_eq!(
        v["critical_speed_map"]["stiffness"]
            .as_array()
            .unwrap()
            .len(),
        31
    );

    let (status, ctype, page) = post_as("/v1/report", &body, "text/html").await;
    assert_eq!(status, 200);
    assert!(ctype.starts_with("text/html"), "{ctype}");
    let page = String::from_utf8(page).unwrap();
    assert!(page.starts_with("<!DOCTYPE html>"), "{}", &page[..100]);
    // Sketch, map, static, Campbell, unbalance, Level I: each an inline SVG.
    assert!(
        page.matches("<svg").count() >= 6,
        "{} plots",
        page.matches("<svg").count()
    );
    for m in &models {
        assert!(page.contains(m), "{m} missing from the page");
    }
    // One verdict row per check.
    assert_eq!(page.matches("<tr class=\"check ").count(), checks.len());
    assert!(
        !page.contains("NaN") && !page.contains("inf "),
        "non-finite number on the page"
    );
    assert!(!page.contains("http://") && !page.contains("https://") || page.contains("xmlns"));
}

#[tokio::test]
async fn level1_on_anisotropic_bearings_agrees_with_a_modal_analysis_at_q0() {
    // Rotor A: two anisotropic, cross-coupled bearings (doubled coordinates). At q0 the first
    // forward pole of the rotor with a skew support kxy = q0, kyx = -q0 at node 5 is on the
    // imaginary axis.
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/ross/aniso.json");
    let data: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let rotor = data["rotor"].clone();
    let speed = 500.0;
    let body = json!({"rotor": rotor, "damping": {"model": "viscous"}, "speed": speed, "node": 5});
    let (status, v) = post_json("/v1/level1", &body).await;
    assert_eq!(status, 200, "{v}");
    let q0 = num(&v["q0"]);
    assert!(q0 > 0.0 && num(&v["log_decrement_0"]) > 0.0, "{v}");
    for (q, sign) in [(q0, 0.0), (0.9 * q0, -1.0), (1.1 * q0, 1.0)] {
        let mut r = rotor.clone();
        r["supports"]
            .as_array_mut()
            .unwrap()
            .push(json!({"node": 5, "kxx": 0.0, "kxy": q, "kyx": -q, "kyy": 0.0}));
        let (status, m) = post_json(
            "/v1/modal",
            &json!({"rotor": r, "damping": {"model": "viscous"}, "speed": speed}),
        )
        .await;
        assert_eq!(status, 200, "{m}");
        let first = m["poles"]
            .as_array()
            .unwrap()
            .iter()
            // Overdamped poles (frequency ~ 0) do not whirl.
            .filter(|p| {
                p["whirl"] == "forward" && num(&p["frequency"]) > 1e-6 * num(&p["decay_rate"]).abs()
            })
            .min_by(|a, b| num(&a["frequency"]).total_cmp(&num(&b["frequency"])))
            .unwrap();
        let (sigma, w) = (num(&first["decay_rate"]), num(&first["frequency"]));
        assert!((w - num(&v["frequency_0"])).abs() < 0.05 * w, "{first}");
        if sign == 0.0 {
            assert!(sigma.abs() < 1e-8 * w, "at q0 {q0}: {first}");
        } else {
            assert_eq!(sigma.signum(), sign, "at {q}: {first}");
        }
    }
}

#[tokio::test]
async fn level2_applies_each_source_alone_then_all_as_level_1_would() {
    // The 40-element shaft of the Region test; a stage, a seal with cross-coupling only and a
    // further cross-coupling, all at mid-span (node 20). Each configuration must equal Level I
    // on the bare rotor at the same total q: 0; the seal's 5000 N/m; q_A = 3 x (10 kW /
    // 513 rad/s) / (0.3 m x 0.02 m) = 9746.6 N/m; the further 3000 N/m; and their sum.
    let bare = json!({"type": "beam",
        "materials": {"steel": {"young_modulus": 2.11e11, "density": 7810.0, "poisson_ratio": 0.3,
                                "loss_factor": 0.0}},
        "shaft": [{"length": 2.0, "outer_diameter": 0.05, "inner_diameter": 0.0,
                   "material": "steel", "elements": 40}],
        "supports": [{"node": 0, "stiffness": 1e6, "damping": 1e4},
                     {"node": 40, "stiffness": 1e6, "damping": 1e4}]});
    let mut rotor = bare.clone();
    rotor["seals"] = json!([{"node": 20, "kxx": 0.0, "kxy": 5000.0, "kyx": -5000.0, "kyy": 0.0}]);
    let speed = 513.0;
    let body = json!({"rotor": rotor, "damping": {"model": "viscous"}, "speed": speed,
        "machine": {"stages": [{"node": 20, "power": 1e4, "diameter": 0.3, "width": 0.02}],
                    "additional_cross_coupling": [{"node": 20, "q": 3000.0}]}});
    let (status, v) = post_json("/v1/level1", &body).await;
    assert_eq!(status, 200, "{v}");
    let qa = num(&v["qa"]);
    assert!((qa - 3.0 * (1e4 / speed) / (0.3 * 0.02)).abs() < 1e-9 * qa);
    // Level I ran on a checked reduction of the 164-state shaft, checked at q0.
    let red = &v["reduction"];
    assert!(num(&red["states"]) < num(&red["full_states"]), "{red}");
    assert_eq!(num(&red["full_states"]), 164.0, "{red}");
    assert!(num(&red["max_relative_error"]) <= 1e-5, "{red}");
    assert_eq!(num(&red["checked_cross_coupling"]), num(&v["q0"]), "{red}");
    assert!((qa - 9746.6).abs() < 0.1, "{qa}");
    let l2 = &v["level2"];
    let sources: Vec<(&str, f64)> = l2["sources"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| (s["source"].as_str().unwrap(), num(&s["log_decrement"])))
        .collect();
    println!("{sources:?}");
    let names: Vec<&str> = sources.iter().map(|s| s.0).collect();
    assert_eq!(
        names,
        [
            "bearings alone",
            "seals",
            "stages' q_A",
            "additional cross-coupling",
            "all together"
        ]
    );
    for ((name, d), q) in sources
        .iter()
        .zip([0.0, 5000.0, qa, 3000.0, 5000.0 + qa + 3000.0])
    {
        // Level II is solved on the full model: so is this Level I (Level I's checked
        // reduction is within 1e-6 of it, tests/it/level1_reduced.rs).
        let at = json!({"rotor": bare, "damping": {"model": "viscous"}, "speed": speed,
                        "node": 20, "cross_coupling": {"start": 0.0, "stop": q.max(1.0), "count": 2},
                        "modal_reduction": false});
        let (_, l) = post_json("/v1/level1", &at).await;
        assert!(l.get("reduction").is_none(), "{l}");
        let want = if q == 0.0 {
            num(&l["log_decrement"][0])
        } else {
            num(&l["log_decrement"][1])
        };
        assert!(
            (d - want).abs() < 1e-9 * want.abs().max(1e-3),
            "{name}: {d} vs {want}"
        );
    }
    // Each source lowers the log decrement; together they lower it most.
    assert!(sources[1..4].iter().all(|s| s.1 < sources[0].1));
    assert!(sources[4].1 < sources[2].1);
    assert_eq!(l2["passes"], json!(sources.iter().all(|s| s.1 >= 0.1)));
}
