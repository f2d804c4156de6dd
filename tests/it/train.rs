//! Torsional and axial motion of trains against closed forms: a two-inertia train (natural
//! frequency, its receptance to a harmonic torque, its response to opposed step torques), the
//! hysteretic and equivalent models' poles of a uniform material loss factor, the interference
//! diagram's crossings, a geared train against the single-shaft train referred through the
//! ratio, and the refusals.

use serde_json::{Value, json};

use crate::common::post_json;

/// Two disks `J1 = 2`, `J2 = 3` kg m^2 on a massless coupling of torsional stiffness `1e5`
/// N m/rad (its lateral part on one bearing only: the lateral analyses are not asked).
fn two_inertia(loss: f64, damping: f64) -> Value {
    json!({"type": "beam", "materials": {},
        "shaft": [{"length": 0.1, "outer_diameter": 0.1,
                   "coupling": {"torsional_stiffness": 1e5, "torsional_damping": damping,
                                "loss_factor": loss}}],
        "disks": [{"node": 0, "mass": 10, "polar_inertia": 2.0},
                  {"node": 1, "mass": 10, "polar_inertia": 3.0}],
        "supports": [{"node": 0, "stiffness": 1e6}]})
}

/// `sqrt(k (J1 + J2) / (J1 J2))`, rad/s.
fn two_inertia_omega() -> f64 {
    (1e5_f64 * 5.0 / 6.0).sqrt()
}

async fn ok(uri: &str, body: Value) -> Value {
    let (status, v) = post_json(uri, &body).await;
    assert_eq!(status, 200, "{uri}: {v}");
    v
}

fn poles(v: &Value) -> Vec<(f64, f64)> {
    v["poles"]
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
        .collect()
}

#[tokio::test]
async fn a_two_inertia_train_turns_freely_and_twists_at_its_closed_form_frequency() {
    for speed in [0.0, 500.0] {
        let v = ok(
            "/v1/modal",
            json!({"rotor": two_inertia(0.0, 0.0), "damping": {"model": "viscous"},
                   "speed": speed, "motion": "torsional"}),
        )
        .await;
        let p = poles(&v);
        // The free train's rigid turning, exactly 0, then the twisting mode.
        assert_eq!(p.len(), 2, "{p:?}");
        assert_eq!(p[0], (0.0, 0.0));
        let w = two_inertia_omega();
        assert!((p[1].1 - w).abs() <= 1e-9 * w, "{} vs {w}", p[1].1);
        assert!(p[1].0.abs() <= 1e-9 * w);
        // The shape: the disks turn opposite, inversely to their inertias.
        let shape = &v["poles"][1]["shape"];
        let ratio = shape[1]["re"].as_f64().unwrap() / shape[0]["re"].as_f64().unwrap();
        assert!((ratio + 2.0 / 3.0).abs() < 1e-9, "{ratio}");
    }
}

/// A steel shaft of 5 elements with three disks, its material loss factor `eta`: every
/// nonzero pole is `i w_n sqrt(1 + i eta)` (hysteretic) or `w_n (-eta/2 + i sqrt(1 -
/// eta^2/4))` (equivalent) of the undamped natural frequencies `w_n`, at rest and at speed.
#[tokio::test]
async fn a_material_loss_factor_gives_the_closed_form_poles_in_both_models() {
    let eta = 0.05;
    let rotor = |eta: f64| {
        json!({"type": "beam",
            "materials": {"steel": {"young_modulus": 2.1e11, "density": 7850, "poisson_ratio": 0.3,
                                     "loss_factor": eta}},
            "shaft": [{"length": 1.0, "outer_diameter": 0.06, "material": "steel", "elements": 5}],
            "disks": [{"node": 0, "mass": 20, "polar_inertia": 0.3},
                      {"node": 3, "mass": 10, "polar_inertia": 0.1},
                      {"node": 5, "mass": 15, "polar_inertia": 0.2}],
            "supports": [{"node": 0, "stiffness": 1e7}, {"node": 5, "stiffness": 1e7}]})
    };
    let undamped = ok(
        "/v1/modal",
        json!({"rotor": rotor(0.0), "damping": {"model": "viscous"}, "motion": "torsional"}),
    )
    .await;
    let wn: Vec<f64> = poles(&undamped)
        .iter()
        .map(|p| p.1)
        .filter(|w| *w > 0.0)
        .collect();
    assert_eq!(wn.len(), 5);
    for speed in [0.0, 800.0] {
        for model in ["hysteretic", "equivalent"] {
            let v = ok(
                "/v1/modal",
                json!({"rotor": rotor(eta), "damping": {"model": model}, "speed": speed,
                       "motion": "torsional"}),
            )
            .await;
            let got: Vec<(f64, f64)> = poles(&v).into_iter().filter(|p| p.1 > 0.0).collect();
            assert_eq!(got.len(), wn.len(), "{model}: {got:?}");
            for (&w, s) in wn.iter().zip(&got) {
                let want = match model {
                    // i w sqrt(1 + i eta), the root with Re < 0.
                    "hysteretic" => {
                        let r = (1.0 + eta * eta).sqrt();
                        let (a, b) = (((r + 1.0) / 2.0).sqrt(), ((r - 1.0) / 2.0).sqrt());
                        (-w * b, w * a)
                    }
                    _ => (-w * eta / 2.0, w * (1.0 - eta * eta / 4.0).sqrt()),
                };
                let e = (s.0 - want.0).hypot(s.1 - want.1) / w;
                assert!(e <= 1e-9, "{model} at {speed}: {s:?} vs {want:?} ({e:.1e})");
            }
        }
    }
}

#[tokio::test]
async fn the_receptance_to_a_harmonic_torque_is_the_closed_forms() {
    let freqs: [f64; 3] = [50.0, 200.0, 400.0];
    let v = ok(
        "/v1/frequency-response",
        json!({"rotor": two_inertia(0.0, 0.0), "damping": {"model": "viscous"},
               "motion": "torsional", "input": {"node": 0}, "output": {"node": 0},
               "frequencies": {"values": freqs, "unit": "rad/s"}}),
    )
    .await;
    for (i, w) in freqs.iter().enumerate() {
        // Theta_1 / T = (k - J2 w^2) / (J1 J2 w^4 - k (J1 + J2) w^2), rad/(N m).
        let (k, j1, j2): (f64, f64, f64) = (1e5, 2.0, 3.0);
        let want = ((k - j2 * w * w) / (j1 * j2 * w.powi(4) - k * (j1 + j2) * w * w)).abs();
        let got = v["amplitude"][i].as_f64().unwrap();
        assert!((got - want).abs() <= 1e-9 * want, "{w}: {got} vs {want}");
    }
}

#[tokio::test]
async fn opposed_step_torques_twist_the_train_as_the_closed_form_says() {
    // +T on J1 and -T on J2 from t = 0: the train does not turn as a whole, and the twist
    // u = theta_1 - theta_2 follows (T / k) (1 - cos w t) (undamped).
    let t = 100.0;
    let v = ok(
        "/v1/time-response",
        json!({"rotor": two_inertia(0.0, 0.0), "damping": {"model": "viscous"},
               "motion": "torsional", "speed": 0,
               "forces": [{"node": 0, "history": [[0, t], [1, t]]},
                          {"node": 1, "history": [[0, -t], [1, -t]]}],
               "duration": 0.05, "output_interval": 0.001, "tolerance": 1e-10}),
    )
    .await;
    let w = two_inertia_omega();
    let static_twist = t / 1e5;
    let times = v["time"].as_array().unwrap();
    let (a, b) = (&v["nodes"][0]["x"], &v["nodes"][1]["x"]);
    let mut worst: f64 = 0.0;
    for (i, time) in times.iter().enumerate() {
        let time = time.as_f64().unwrap();
        let u = a[i].as_f64().unwrap() - b[i].as_f64().unwrap();
        let want = static_twist * (1.0 - (w * time).cos());
        worst = worst.max((u - want).abs() / static_twist);
        // Turning as a whole: J1 theta_1 + J2 theta_2 stays 0.
        let momentum = 2.0 * a[i].as_f64().unwrap() + 3.0 * b[i].as_f64().unwrap();
        assert!(momentum.abs() <= 1e-6 * static_twist, "{momentum}");
    }
    assert!(
        worst <= 1e-6,
        "twist off the closed form by {worst:.1e} of T/k"
    );
}

/// An undamped free train: no threshold (neither the rigid turning's round-off nor the twisting
/// mode's is growth), one branch per mode, `modes` counting modes.
#[tokio::test]
async fn a_free_undamped_train_is_stable_with_one_branch_per_mode() {
    for modes in [None, Some(1)] {
        let mut body = json!({"rotor": two_inertia(0.0, 0.0), "damping": {"model": "viscous"},
               "motion": "torsional", "speeds": {"start": 0, "stop": 400, "count": 5}});
        if let Some(m) = modes {
            body["modes"] = json!(m);
        }
        let v = ok("/v1/campbell", body).await;
        assert_eq!(v["threshold"], Value::Null, "{v}");
        let branches = v["branches"].as_array().unwrap();
        assert_eq!(branches.len(), 1, "{v}");
        assert_eq!(branches[0]["mode"], 1);
        let w = two_inertia_omega();
        for f in branches[0]["frequency"].as_array().unwrap() {
            assert!((f.as_f64().unwrap() - w).abs() <= 1e-9 * w);
        }
    }
}

/// Opposed harmonic torques `+-T sin(w t)` on the two disks (the train does not turn as a whole)
/// through a damped coupling: once the start has died away, the twist at disk 1 is the
/// frequency response's `(H_00 - H_01) T`. The torques are tabulated every 0.1 ms, whose
/// piecewise-linear error is `(w dt)^2 / 8 = 5e-5` of `T`: the tolerance is 2e-4.
#[tokio::test]
async fn a_harmonic_torques_steady_state_is_the_frequency_response() {
    let (t, w, dt) = (100.0, 200.0_f64, 1e-4);
    let rotor = two_inertia(0.0, 60.0);
    let n = (0.7 / dt) as usize;
    let sine = |sign: f64| -> Vec<[f64; 2]> {
        (0..=n)
            .map(|i| {
                let time = i as f64 * dt;
                [time, sign * t * (w * time).sin()]
            })
            .collect()
    };
    let v = ok(
        "/v1/time-response",
        json!({"rotor": rotor, "damping": {"model": "viscous"}, "motion": "torsional",
               "speed": 0, "forces": [{"node": 0, "history": sine(1.0)},
                                      {"node": 1, "history": sine(-1.0)}],
               "duration": 0.7, "output_interval": 2e-4, "tolerance": 1e-10, "nodes": [0]}),
    )
    .await;
    // The start decays at 25 1/s; the last 0.1 s (about 3 periods) fitted by a cos + b sin.
    let times: Vec<f64> = v["time"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    let x: Vec<f64> = v["nodes"][0]["x"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    let got = crate::common::sine_amplitude(&times, &x, w, 0.6);
    let h = |input: usize| async move {
        ok(
            "/v1/frequency-response",
            json!({"rotor": two_inertia(0.0, 60.0), "damping": {"model": "viscous"},
                   "motion": "torsional", "input": {"node": input}, "output": {"node": 0},
                   "frequencies": {"values": [w], "unit": "rad/s"}}),
        )
        .await
    };
    let (h0, h1) = (h(0).await, h(1).await);
    let c = |v: &Value| {
        let (a, p) = (
            v["amplitude"][0].as_f64().unwrap(),
            v["phase"][0].as_f64().unwrap(),
        );
        (a * p.cos(), a * p.sin())
    };
    let ((r0, i0), (r1, i1)) = (c(&h0), c(&h1));
    let want = t * (r0 - r1).hypot(i0 - i1);
    println!("steady twist {got:.6e}, frequency response {want:.6e}");
    assert!(
        (got - want).abs() <= 2e-4 * want,
        "steady twist {got:.6e} vs the frequency response's {want:.6e}"
    );
}

/// The interference diagram's crossings of order `k` sit at `w_n / k` (the natural frequency
/// does not move with speed in torsion), refined to 1e-9.
#[tokio::test]
async fn interference_crossings_of_order_k_sit_at_the_natural_frequency_over_k() {
    let v = ok(
        "/v1/campbell",
        json!({"rotor": two_inertia(0.02, 0.0), "damping": {"model": "hysteretic"},
               "motion": "torsional", "speeds": {"start": 0, "stop": 400, "count": 9},
               "interference": {"orders": [1, 2, 3], "line_frequency": {"value": 50, "unit": "Hz"},
                                "operating_range": [100, 180]}}),
    )
    .await;
    assert_eq!(
        v["branches"].as_array().unwrap().len(),
        1,
        "one branch per mode"
    );
    let i = &v["interference"];
    // The hysteretic pole i w_n sqrt(1 + i eta): its frequency w_n sqrt((r + 1) / 2), r =
    // sqrt(1 + eta^2).
    let r = (1.0 + 0.02_f64.powi(2)).sqrt();
    let w = two_inertia_omega() * ((r + 1.0) / 2.0).sqrt();
    let mut orders_seen = vec![];
    for c in i["criticals"].as_array().unwrap() {
        let e = &i["excitations"][c["excitation"].as_u64().unwrap() as usize];
        let f = c["frequency"].as_f64().unwrap();
        assert!((f - w).abs() <= 1e-9 * w, "{c}");
        match e["kind"].as_str().unwrap() {
            "order" => {
                let k = e["order"].as_f64().unwrap();
                let speed = c["speed"].as_f64().unwrap();
                assert!(
                    (speed - w / k).abs() <= 1e-9 * w,
                    "order {k}: {speed} vs {}",
                    w / k
                );
                // API 684: 10% from the excitation over [100, 180] rad/s.
                let margin = if speed < 100.0 {
                    1.0 - speed / 100.0
                } else if speed > 180.0 {
                    speed / 180.0 - 1.0
                } else {
                    -(speed / 100.0 - 1.0).min(1.0 - speed / 180.0)
                };
                assert!((c["margin"].as_f64().unwrap() - margin).abs() < 1e-9);
                assert_eq!(c["passes"], margin >= 0.1);
                orders_seen.push(k);
            }
            _ => {
                let line = e["frequency"].as_f64().unwrap();
                assert!((c["margin"].as_f64().unwrap() - (f - line).abs() / line).abs() < 1e-9);
            }
        }
    }
    // 288.7 rad/s: order 1 at 288.7 (60% above 180), 2 at 144.3 (inside), 3 at 96.2 (3.8%
    // below 100).
    orders_seen.sort_by(f64::total_cmp);
    assert_eq!(orders_seen, vec![1.0, 2.0, 3.0]);
}

/// Shaft A (J1 -- kA -- pinion Jp) meshes with shaft B (gear Jg -- kB -- J2) turning `n` times
/// as fast: the same natural frequencies as the single shaft referred to A (Jg n^2, kB n^2,
/// J2 n^2, the mesh a coupling), and true angles `n` times the referred ones.
#[tokio::test]
async fn a_geared_train_is_the_single_shaft_train_referred_through_the_ratio() {
    let (n, km) = (2.5, 3e6);
    let coupling = |k: f64| json!({"length": 0.1, "outer_diameter": 0.1, "coupling": {"torsional_stiffness": k}});
    let disks = |j: [f64; 4]| -> Vec<Value> {
        (0..4)
            .map(|i| json!({"node": i, "mass": 5, "polar_inertia": j[i]}))
            .collect()
    };
    let supports = json!([{"node": 0, "stiffness": 1e6}, {"node": 3, "stiffness": 1e6}]);
    let (j1, jp, jg, j2, ka, kb) = (1.5, 0.1, 0.3, 0.8, 2e5, 5e4);
    let geared = json!({"type": "beam", "materials": {},
        "shaft": [coupling(ka),
                  {"length": 0.1, "outer_diameter": 0.2,
                   "gear": {"ratio": n, "mesh_stiffness": km}},
                  coupling(kb)],
        "disks": disks([j1, jp, jg, j2]), "supports": supports});
    let referred = json!({"type": "beam", "materials": {},
        "shaft": [coupling(ka), coupling(km), coupling(kb * n * n)],
        "disks": disks([j1, jp, jg * n * n, j2 * n * n]), "supports": supports});
    let modal = |rotor: Value| async move {
        ok(
            "/v1/modal",
            json!({"rotor": rotor, "damping": {"model": "viscous"}, "motion": "torsional"}),
        )
        .await
    };
    let (g, r) = (modal(geared).await, modal(referred).await);
    let (pg, pr) = (poles(&g), poles(&r));
    assert_eq!(pg.len(), 4);
    assert_eq!(pg.len(), pr.len());
    for (i, (a, b)) in pg.iter().zip(&pr).enumerate() {
        assert!((a.1 - b.1).abs() <= 1e-9 * b.1.max(1.0), "{a:?} vs {b:?}");
        if i == 0 {
            continue;
        }
        // Shapes in true angles: the driven shaft's nodes n times the referred ones.
        let shape = |v: &Value, node: usize| v["poles"][i]["shape"][node]["re"].as_f64().unwrap();
        let scale = shape(&g, 0) / shape(&r, 0);
        for node in 0..4 {
            let factor = if node >= 2 { n } else { 1.0 };
            let want = shape(&r, node) * factor * scale;
            assert!(
                (shape(&g, node) - want).abs() <= 1e-8 * (1.0 + want.abs()),
                "mode {i} node {node}: {} vs {want}",
                shape(&g, node)
            );
        }
    }
    // The interference diagram's orders run on both shafts' speeds.
    let v = ok(
        "/v1/campbell",
        json!({"rotor": g_rotor_again(n, km), "damping": {"model": "viscous"},
               "motion": "torsional", "speeds": {"start": 0, "stop": 100, "count": 3},
               "interference": {"orders": [1]}}),
    )
    .await;
    let ratios: Vec<f64> = v["interference"]["excitations"]
        .as_array()
        .unwrap()
        .iter()
        .map(|e| e["ratio"].as_f64().unwrap())
        .collect();
    assert_eq!(ratios, vec![1.0, n]);
}

fn g_rotor_again(n: f64, km: f64) -> Value {
    json!({"type": "beam", "materials": {},
        "shaft": [{"length": 0.1, "outer_diameter": 0.1, "coupling": {"torsional_stiffness": 2e5}},
                  {"length": 0.1, "outer_diameter": 0.2, "gear": {"ratio": n, "mesh_stiffness": km}},
                  {"length": 0.1, "outer_diameter": 0.1, "coupling": {"torsional_stiffness": 5e4}}],
        "disks": [{"node": 0, "mass": 5, "polar_inertia": 1.5}, {"node": 1, "mass": 5, "polar_inertia": 0.1},
                  {"node": 2, "mass": 5, "polar_inertia": 0.3}, {"node": 3, "mass": 5, "polar_inertia": 0.8}],
        "supports": [{"node": 0, "stiffness": 1e6}]})
}

fn paths(v: &Value) -> Vec<String> {
    v["errors"]
        .as_array()
        .map(|a| {
            a.iter()
                .map(|e| e["path"].as_str().unwrap().to_string())
                .collect()
        })
        .unwrap_or_default()
}

async fn refused(uri: &str, body: Value, path: &str) {
    let (status, v) = post_json(uri, &body).await;
    assert_eq!(status, 422, "{uri}: {v}");
    assert!(paths(&v).iter().any(|p| p == path), "{path} not in {v}");
}

#[tokio::test]
async fn bad_trains_are_refused_naming_the_field() {
    let viscous = json!({"model": "viscous"});
    let mut zero_ratio = g_rotor_again(0.0, 1e6);
    refused(
        "/v1/modal",
        json!({"rotor": zero_ratio.clone(), "damping": viscous, "motion": "torsional"}),
        "rotor.shaft[1].gear.ratio",
    )
    .await;
    zero_ratio["shaft"][0]["coupling"]["torsional_stiffness"] = json!(-1.0);
    refused(
        "/v1/modal",
        json!({"rotor": zero_ratio, "damping": viscous, "motion": "torsional"}),
        "rotor.shaft[0].coupling.torsional_stiffness",
    )
    .await;
    refused(
        "/v1/modal",
        json!({"rotor": {"type": "jeffcott", "mass": 1, "stiffness": 1}, "damping": viscous,
               "motion": "torsional"}),
        "motion",
    )
    .await;
    // A gear has no lateral model.
    refused(
        "/v1/modal",
        json!({"rotor": g_rotor_again(2.0, 1e6), "damping": viscous}),
        "rotor.shaft[1].gear",
    )
    .await;
    refused(
        "/v1/time-response",
        json!({"rotor": two_inertia(0.0, 0.0), "damping": viscous, "motion": "torsional",
               "speed": 10, "unbalances": [{"node": 0, "amount": 1e-4}],
               "duration": 0.01, "output_interval": 0.001}),
        "unbalances",
    )
    .await;
    refused(
        "/v1/campbell",
        json!({"rotor": two_inertia(0.0, 0.0), "damping": viscous,
               "speeds": {"start": 0, "stop": 10, "count": 2}, "interference": {}}),
        "interference",
    )
    .await;
    let mut thrust = two_inertia(0.0, 0.0);
    // A table of axial stiffness without the speeds it is read at.
    thrust["supports"][0]["kzz"] = json!([1e6, 2e6]);
    let (status, v) = post_json(
        "/v1/modal",
        &json!({"rotor": thrust, "damping": viscous, "motion": "axial"}),
    )
    .await;
    assert_eq!(status, 422, "{v}");
    assert!(
        paths(&v)
            .iter()
            .any(|p| p.starts_with("rotor.supports[0].kzz")),
        "{v}"
    );
}
