//! Supports whose coefficients depend on the whirl frequency (issue 31): poles consistent with
//! the frequency they read their supports at, and harmonic responses read at the excitation
//! frequency, against closed forms and against constant-coefficient models read by hand.

use crate::common;

use common::over_whirl::*;
use common::post_json;
use num_complex::Complex64 as C;
use serde_json::{Value, json};

/// The pole `s = sigma + i w` of `m s^2 + c(w) s + k_s + k(w) = 0` read at its own `w`:
/// the imaginary part gives `sigma = -c(w) / 2m`, the real part the quadratic
/// `-(m + c1^2/4m) w^2 + (k1 - c0 c1 / 2m) w + (k_s + k0 - c0^2/4m) = 0`.
fn closed_form() -> C {
    let a = -(M + C1 * C1 / (4.0 * M));
    let b = K1 - C0 * C1 / (2.0 * M);
    let c = KS + K0 - C0 * C0 / (4.0 * M);
    let w = (-b - (b * b - 4.0 * a * c).sqrt()) / (2.0 * a);
    C::new(-(C0 + C1 * w) / (2.0 * M), w)
}

#[tokio::test]
async fn a_mass_on_a_frequency_dependent_support_has_the_closed_form_poles() {
    let want = closed_form();
    // 372.0 rad/s; the support read at rest would give sqrt(1.2e6 / 10) = 346.4.
    assert!((want.im - 372.0).abs() < 0.05, "{want}");
    for (speed_table, speed) in [(false, 0.0), (false, 300.0), (true, 700.0)] {
        let body = json!({"rotor": one_mass(speed_table), "damping": {"model": "viscous"},
                          "speed": speed});
        let (status, r) = post_json("/v1/modal", &body).await;
        assert_eq!(status, 200, "{r}");
        let poles = r["poles"].as_array().unwrap();
        assert_eq!(poles.len(), 2, "{r}");
        for p in poles {
            let s = C::new(num(&p["decay_rate"]), num(&p["frequency"]));
            // Forward and backward alike read the table at |w|: a conjugate pair.
            let t = if s.im > 0.0 { want } else { want.conj() };
            assert!(
                (s - t).norm() <= 1e-10 * t.norm(),
                "speed {speed}: {s} against {t}"
            );
            assert!(num(&p["residual"]) < 1e-12, "{p}");
        }
        let c = &r["consistency"];
        assert_eq!(c["lost"], json!(0), "{c}");
        assert!(num(&c["max_residual"]) < 1e-12, "{c}");
    }
}

#[tokio::test]
async fn a_frequency_response_reads_the_support_at_the_excitation_frequency() {
    let ws = [50.0, 300.0, 353.0, 420.0, 700.0];
    for direction in [json!("forward"), json!(0.0)] {
        let body = json!({"rotor": one_mass(false), "damping": {"model": "viscous"},
                          "speed": 100.0, "input": {"node": 0, "direction": direction},
                          "output": {"node": 0}, "frequencies": ws});
        let (status, r) = post_json("/v1/frequency-response", &body).await;
        assert_eq!(status, 200, "{r}");
        let planar = direction != json!("forward");
        for (k, &w) in ws.iter().enumerate() {
            // The dynamic stiffness at +w and -w, the table read at |w| for both (m, N/m, N s/m).
            let d = |l: f64| C::new(KS + K0 + K1 * w - M * w * w, l * (C0 + C1 * w));
            let (f, b) = match planar {
                false => (1.0 / d(w).norm(), 0.0),
                true => (0.5 / d(w).norm(), 0.5 / d(-w).norm()),
            };
            let got_f = num(&r["forward"][k]);
            let got_b = num(&r["backward"][k]);
            assert!((got_f - f).abs() <= 1e-12 * f, "{w}: {got_f} vs {f}");
            assert!((got_b - b).abs() <= 1e-12 * f, "{w}: {got_b} vs {b}");
        }
        // 700 rad/s is past the table's 500: said.
        let warnings = r["warnings"].to_string();
        assert!(
            warnings.contains("rotor.supports[0].frequencies") && warnings.contains("extrapolated"),
            "{warnings}"
        );
    }
}

#[tokio::test]
async fn tables_over_whirl_frequency_are_refused_where_not_yet_read() {
    let rotor = one_mass(false);
    let body = json!({"rotor": rotor, "damping": {"model": "equivalent"}, "speed": 0.0});
    let (status, r) = post_json("/v1/modal", &body).await;
    assert_eq!(status, 422, "{r}");
    assert!(r.to_string().contains("viscous and hysteretic"), "{r}");
}

#[tokio::test]
async fn a_bad_table_over_whirl_frequency_names_its_field() {
    let cases = [
        (
            json!({"node": 0, "frequencies": [0.0, 100.0], "kxx": [1e5]}),
            "rotor.supports[0].kxx",
        ),
        (
            json!({"node": 0, "frequencies": [100.0, 0.0], "kxx": 1e5}),
            "rotor.supports[0].frequencies[1]",
        ),
        (
            json!({"node": 0, "frequencies": [0.0, 100.0], "speeds": [0.0, 1.0],
                   "kxx": [[1e5, 2e5]]}),
            "rotor.supports[0].kxx",
        ),
        (
            json!({"node": 0, "frequencies": [0.0, 100.0], "speeds": [0.0, 1.0],
                   "kxx": [[1e5, 2e5], [1e5]]}),
            "rotor.supports[0].kxx[1]",
        ),
        (
            json!({"node": 0, "frequencies": [0.0, 100.0], "kxx": [1e5, 2e5],
                   "interpolation": "ross"}),
            "rotor.supports[0].interpolation",
        ),
        (
            json!({"node": 0, "speeds": [0.0, 100.0], "kxx": [1e5, 2e5],
                   "interpolation": "pchip"}),
            "rotor.supports[0].interpolation",
        ),
        (
            json!({"node": 0, "kxx": [[1e5, 2e5]]}),
            "rotor.supports[0].kxx",
        ),
    ];
    for (support, path) in cases {
        let body = json!({"rotor": {"type": "matrices", "mass": [[M]], "stiffness": [[KS]],
                                    "supports": [support]},
                          "damping": {"model": "viscous"}, "speed": 0.0});
        let (status, r) = post_json("/v1/modal", &body).await;
        assert_eq!(status, 422, "{support}: {r}");
        assert!(
            r.to_string().contains(path),
            "{support}: wanted {path} in {r}"
        );
    }
}

fn poles(r: &Value) -> Vec<C> {
    r["poles"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| C::new(num(&p["decay_rate"]), num(&p["frequency"])))
        .collect()
}

#[tokio::test]
async fn each_pole_of_a_beam_rotor_is_a_pole_of_the_rotor_read_at_its_frequency() {
    let (speed, bound) = (600.0, 8000.0);
    for (model, loss) in [("viscous", 0.0), ("hysteretic", 0.1)] {
        let body = json!({"rotor": sealed(tabulated_seal(loss), 0.002), "damping": {"model": model},
                          "speed": speed, "max_frequency": bound});
        let (status, r) = post_json("/v1/modal", &body).await;
        assert_eq!(status, 200, "{r}");
        let found = poles(&r);
        assert!(found.len() >= 6, "{model}: {:?}", found);
        assert_eq!(
            r["consistency"]["lost"],
            json!(0),
            "{model}: {}",
            r["consistency"]
        );
        let mut moved: f64 = 0.0;
        for (i, s) in found.iter().enumerate() {
            // The seal read by hand at this pole's |frequency|, constant.
            let mut seal = json!({"node": 15});
            for (name, v) in seal_at(s.im.abs(), speed) {
                seal[name] = json!(v);
            }
            if loss > 0.0 {
                seal["loss_factor"] = json!(loss);
            }
            let body = json!({"rotor": sealed(seal, 0.002), "damping": {"model": model},
                              "speed": speed, "max_frequency": bound});
            let (status, c) = post_json("/v1/modal", &body).await;
            assert_eq!(status, 200, "{c}");
            let nearest = poles(&c)
                .into_iter()
                .flat_map(|t| [t, t.conj()])
                .map(|t| (t - s).norm())
                .fold(f64::INFINITY, f64::min);
            assert!(
                nearest <= 1e-8 * s.norm(),
                "{model}: pole {s} is {nearest:e} from the rotor read at its frequency"
            );
            assert!(num(&r["poles"][i]["residual"]) < 1e-10, "{}", r["poles"][i]);
            // How far the synchronous reading (frequency = speed) puts it.
            let mut seal = json!({"node": 15});
            for (name, v) in seal_at(speed, speed) {
                seal[name] = json!(v);
            }
            if loss > 0.0 {
                seal["loss_factor"] = json!(loss);
            }
            let body = json!({"rotor": sealed(seal, 0.002), "damping": {"model": model},
                              "speed": speed, "max_frequency": bound});
            let (_, sync) = post_json("/v1/modal", &body).await;
            let d = poles(&sync)
                .into_iter()
                .flat_map(|t| [t, t.conj()])
                .map(|t| (t - s).norm() / s.norm())
                .fold(f64::INFINITY, f64::min);
            moved = moved.max(d);
        }
        println!(
            "{model}: {} poles, solves {}, max residual {:.2e}, largest move from the synchronous reading {moved:.2e}",
            found.len(),
            r["consistency"]["solves"],
            num(&r["consistency"]["max_residual"])
        );
        assert!(
            moved > 1e-3,
            "{model}: the frequency dependence moved nothing"
        );
    }
}

/// An unbalance whirls at the spin speed: the seal over whirl frequency and speed, read there,
/// is the seal tabulated over speed alone at the synchronous values (exact at its speeds).
#[tokio::test]
async fn an_unbalance_response_reads_the_seal_at_the_spin_speed() {
    let speeds = [200.0, 450.0, 480.0, 700.0, 1000.0];
    let mut synchronous = json!({"node": 15, "speeds": speeds});
    for (k, name) in ["kxx", "kyy", "kxy", "kyx", "cxx", "cyy"]
        .iter()
        .enumerate()
    {
        let v: Vec<f64> = speeds.iter().map(|&w| seal_at(w, w)[k].1).collect();
        synchronous[*name] = json!(v);
    }
    let mut answers = vec![];
    for seal in [tabulated_seal(0.0), synchronous] {
        let body = json!({"rotor": sealed(seal, 0.002), "damping": {"model": "viscous"},
                          "speeds": speeds, "nodes": [15, 29],
                          "unbalances": [{"node": 12, "amount": 1e-4, "phase": 0.0}],
                          "modal_reduction": false});
        let (status, r) = post_json("/v1/unbalance-response", &body).await;
        assert_eq!(status, 200, "{r}");
        answers.push(r);
    }
    let amplitudes = |r: &Value| -> Vec<f64> {
        r["nodes"]
            .as_array()
            .unwrap()
            .iter()
            .flat_map(|n| common::floats(&n["major"]))
            .collect()
    };
    let (a, b) = (amplitudes(&answers[0]), amplitudes(&answers[1]));
    assert_eq!(a.len(), 2 * speeds.len());
    // The speed table is solved on the dense first-order model of a tabulated rotor, which
    // loses about 2.5e-9 against a sparse solve (`response_large.rs`'s bound, 1e-8); the table
    // over whirl frequency is solved sparse, read at each speed.
    let scale = b.iter().copied().fold(0.0, f64::max);
    let worst = a
        .iter()
        .zip(&b)
        .map(|(x, y)| (x - y).abs() / scale)
        .fold(0.0, f64::max);
    println!("unbalance: tabulated over whirl frequency vs over speed {worst:.1e}");
    assert!(worst <= 1e-8, "{worst:e}");
}

/// The bundled seal example on 900 elements (1802 coordinates, held sparse): each pole is a
/// pole of the same rotor with the seal read by hand at its frequency (N/m, N s/m).
#[tokio::test]
async fn a_rotor_held_sparse_reads_its_seal_at_each_poles_frequency() {
    let text = std::fs::read_to_string("examples/seal-over-frequency.modal.json").unwrap();
    let mut body: Value = serde_json::from_str(&text).unwrap();
    let (n, speed) = (900, 800.0);
    common::seal_example_on(&mut body["rotor"], n);
    let (status, r) = post_json("/v1/modal", &body).await;
    assert_eq!(status, 200, "{r}");
    assert_eq!(r["full_model"], "sparse");
    assert_eq!(r["consistency"]["lost"], json!(0), "{}", r["consistency"]);
    let found = poles(&r);
    assert_eq!(found.len(), 4, "{found:?}");
    for s in found {
        let w = s.im.abs();
        let mut constant = body.clone();
        constant["rotor"]["seals"] = json!([{"node": n / 2, "kxx": 2e6 + 1.5e3 * w,
            "kxy": 300.0 * speed, "kyx": -300.0 * speed, "cxx": 3000.0 - w}]);
        let (status, c) = post_json("/v1/modal", &constant).await;
        assert_eq!(status, 200, "{c}");
        let nearest = poles(&c)
            .into_iter()
            .map(|t| (t - s).norm())
            .fold(f64::INFINITY, f64::min);
        assert!(nearest <= 1e-8 * s.norm(), "{s}: {nearest:e}");
    }
}

/// The mass on k(w), c(w): its pole does not move with the speed, so its branch is flat at the
/// closed-form frequency and crosses the 1x line there.
#[tokio::test]
async fn the_campbell_of_a_mass_on_a_frequency_dependent_support_is_its_closed_form() {
    let want = closed_form();
    let speeds: Vec<f64> = (0..=20).map(|i| 50.0 * i as f64).collect();
    let body = json!({"rotor": one_mass(false), "damping": {"model": "viscous"},
                      "speeds": speeds});
    let (status, r) = post_json("/v1/campbell", &body).await;
    assert_eq!(status, 200, "{r}");
    for b in r["branches"].as_array().unwrap() {
        for (f, d) in b["frequency"]
            .as_array()
            .unwrap()
            .iter()
            .zip(b["decay_rate"].as_array().unwrap())
        {
            let s = C::new(num(d), num(f).abs());
            assert!(
                (s - want).norm() <= 1e-10 * want.norm(),
                "{s} against {want}"
            );
        }
    }
    let critical = common::floats(&r["critical_speeds"]);
    assert_eq!(critical.len(), 1, "{}", r["critical_speeds"]);
    assert!(
        (critical[0] - want.im).abs() <= 1e-9 * want.im,
        "{critical:?} against {want}"
    );
}

/// The bundled seal example over a sweep: every pole the Campbell reports is the one
/// `/v1/modal` reports at that speed, and each forward critical speed is where the rotor with
/// the seal read (by hand) at that speed as constants whirls at it.
#[tokio::test]
async fn the_campbell_of_the_seal_example_is_its_modal_analysis_at_each_speed() {
    let text = std::fs::read_to_string("examples/seal-over-frequency.modal.json").unwrap();
    let base: Value = serde_json::from_str(&text).unwrap();
    let speeds: Vec<f64> = (0..=24).map(|i| 100.0 * i as f64).collect();
    let mut body = base.clone();
    body.as_object_mut().unwrap().remove("speed");
    body["speeds"] = json!(speeds);
    let (status, r) = post_json("/v1/campbell", &body).await;
    assert_eq!(status, 200, "{r}");
    let branches = r["branches"].as_array().unwrap();
    assert!(branches.len() >= 4, "{}", branches.len());
    for (i, &w) in speeds.iter().enumerate() {
        let mut m = base.clone();
        m["speed"] = json!(w);
        let (status, modal) = post_json("/v1/modal", &m).await;
        assert_eq!(status, 200, "{modal}");
        let at = poles(&modal);
        let mut reported = 0;
        for b in branches {
            let (f, d) = (&b["frequency"][i], &b["decay_rate"][i]);
            if f.is_null() {
                continue;
            }
            reported += 1;
            let s = C::new(num(d), num(f));
            let nearest = at
                .iter()
                .flat_map(|t| [*t, t.conj()])
                .map(|t| (t - s).norm())
                .fold(f64::INFINITY, f64::min);
            assert!(
                nearest <= 1e-10 * s.norm(),
                "{w} rad/s: {s} is {nearest:e} from modal"
            );
        }
        assert_eq!(
            reported,
            at.len(),
            "{w} rad/s: every modal pole on a branch"
        );
    }
    let critical = common::floats(&r["critical_speeds"]);
    assert!(!critical.is_empty(), "{}", r["critical_speeds"]);
    for &w in &critical {
        let mut constant = base.clone();
        constant["speed"] = json!(w);
        constant["rotor"]["seals"] = json!([{"node": 15, "kxx": 2e6 + 1.5e3 * w,
            "kxy": 300.0 * w, "kyx": -300.0 * w, "cxx": 3000.0 - w}]);
        let (status, c) = post_json("/v1/modal", &constant).await;
        assert_eq!(status, 200, "{c}");
        let nearest = poles(&c)
            .into_iter()
            .map(|t| (t.im.abs() - w).abs())
            .fold(f64::INFINITY, f64::min);
        assert!(nearest <= 1e-8 * w, "critical {w}: {nearest:e}");
    }
    println!(
        "seal example Campbell: critical speeds {critical:?}, threshold {}",
        r["threshold"]
    );
}

/// The mass on k(w), c(w) with skew cross-coupling `q(W) = 100 W` N/m growing with the speed:
/// at the threshold the pole `i w` satisfies `k_s + k(w) = m w^2` and `q = c(w) w`, so
/// `w* = (k1 + sqrt(k1^2 + 4 m (k_s + k0))) / 2m` and `W* = c(w*) w* / 100`.
#[tokio::test]
async fn the_threshold_on_a_frequency_dependent_support_is_its_closed_form() {
    let (w, k, c) = table();
    let speeds = [0.0, 2000.0];
    let rows = |v: &Vec<f64>| json!([v, v]);
    let q: Vec<Vec<f64>> = speeds.iter().map(|&s| vec![100.0 * s; w.len()]).collect();
    let minus: Vec<Vec<f64>> = q.iter().map(|r| r.iter().map(|x| -x).collect()).collect();
    let support = json!({"node": 0, "frequencies": w, "speeds": speeds, "kxx": rows(&k),
                         "cxx": rows(&c), "kxy": q, "kyx": minus});
    let rotor = json!({"type": "matrices", "mass": [[M]], "stiffness": [[KS]],
                       "supports": [support]});
    let grid: Vec<f64> = (0..=20).map(|i| 100.0 * i as f64).collect();
    let body = json!({"rotor": rotor, "damping": {"model": "viscous"}, "speeds": grid});
    let (status, r) = post_json("/v1/stability", &body).await;
    assert_eq!(status, 200, "{r}");
    let ws = (K1 + (K1 * K1 + 4.0 * M * (KS + K0)).sqrt()) / (2.0 * M);
    let threshold = (C0 + C1 * ws) * ws / 100.0;
    assert!(
        (ws - 372.3).abs() < 0.05 && (threshold - 1065.5).abs() < 0.5,
        "{ws} {threshold}"
    );
    let got = num(&r["threshold"]);
    assert!(
        (got - threshold).abs() <= 1e-8 * threshold,
        "{got} against {threshold}"
    );
    assert!((num(&r["frequency"]).abs() - ws).abs() <= 1e-6 * ws, "{r}");
}
