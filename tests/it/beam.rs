//! Finite-element rotors: convergence to the analytic Timoshenko beam, branch tracking through
//! crossings and veering, the `matrices` rotor, and validation of beam and matrix inputs.

use axum::body::Body;
use axum::http::{Request, StatusCode};
use http_body_util::BodyExt;
use serde_json::{Value, json};
use tower::ServiceExt;
use whirl::analysis::campbell::campbell;
use whirl::analysis::control::Control;
use whirl::analysis::poles::{Whirl, poles_at};
use whirl::damping::DampedModel;
use whirl::fem::modal::ModalBasis;
use whirl::model::api::RotorInput;
use whirl::model::damping::DampingModel;
use whirl::model::rotor::{Limits, Rotor};
use whirl::service::{Config, app};
use whirl::system::RotorSystem;

fn system(rotor: Value) -> RotorSystem {
    let input: RotorInput = serde_json::from_value(rotor).unwrap();
    RotorSystem::assemble(&Rotor::parse(&input, &Limits::default()).unwrap()).unwrap()
}

/// Flexural frequencies of a simply supported Timoshenko beam: with `w = sin(k z)`,
/// `rho A rho I X^2 - (kGA rho I k^2 + rho A E I k^2 + rho A kGA) X + kGA E I k^4 = 0`,
/// `X = w^2`, lower root, `k = n pi / L`, `kGA = G A / chi`.
fn timoshenko_pinned(n: usize, l: f64, e: f64, rho: f64, nu: f64, chi: f64, d: f64) -> f64 {
    let a = std::f64::consts::PI * d * d / 4.0;
    let i = std::f64::consts::PI * d.powi(4) / 64.0;
    let kga = e / (2.0 * (1.0 + nu)) * a / chi;
    let k = n as f64 * std::f64::consts::PI / l;
    let qa = rho * a * rho * i;
    let qb = kga * rho * i * k * k + rho * a * e * i * k * k + rho * a * kga;
    let qc = kga * e * i * k.powi(4);
    ((qb - (qb * qb - 4.0 * qa * qc).sqrt()) / (2.0 * qa)).sqrt()
}

#[test]
fn a_pinned_beam_converges_to_the_analytic_timoshenko_frequencies() {
    // A stubby shaft (L/d = 5), where shear and rotary inertia matter: Euler-Bernoulli would
    // be off by several per cent. Supports 1e6 times stiffer than the beam pin the ends.
    let (l, d, e, rho, nu, chi) = (0.5, 0.1, 2.1e11, 7800.0, 0.3, 10.0 / 9.0);
    let exact: Vec<f64> = (1..=3)
        .map(|n| timoshenko_pinned(n, l, e, rho, nu, chi, d))
        .collect();
    let i = std::f64::consts::PI * d.powi(4) / 64.0;
    let k_support = 1e6 * 48.0 * e * i / l.powi(3);
    let mut errors = vec![];
    let mut freqs: Vec<Vec<f64>> = vec![];
    for elements in [2, 4, 8, 16, 32, 64] {
        let s = system(json!({
            "type": "beam",
            "materials": {"steel": {"young_modulus": e, "density": rho, "poisson_ratio": nu}},
            "shaft": [{"length": l, "outer_diameter": d, "material": "steel",
                       "elements": elements, "shear_factor": chi}],
            "supports": [{"node": 0, "stiffness": k_support}, {"node": elements, "stiffness": k_support}]
        }));
        // The lowest modes of a pinned-pinned beam on stiff springs are the flexural ones.
        let w = ModalBasis::of(&s).unwrap().omega[..3].to_vec();
        errors.push(
            (0..3)
                .map(|m| (w[m] - exact[m]).abs() / exact[m])
                .fold(0.0, f64::max),
        );
        freqs.push(w);
    }
    // Monotonic, and at least second order: short elements of a stubby shaft are
    // shear-dominated (P grows as 1/l^2), so the rate is h^2, not the slender beam's h^4.
    assert!(errors.windows(2).all(|w| w[1] < w[0]), "{errors:?}");
    let last = errors.len() - 1;
    assert!(errors[last - 1] / errors[last] > 3.5, "{errors:?}");
    assert!(errors[last] < 5e-4, "{errors:?}");
    // Richardson extrapolation of the last two meshes lands on the analytic frequencies.
    for m in 0..3 {
        let extrapolated = (4.0 * freqs[last][m] - freqs[last - 1][m]) / 3.0;
        let err = (extrapolated - exact[m]).abs() / exact[m];
        assert!(
            err < 1e-5,
            "mode {}: extrapolated {extrapolated} vs {} ({err})",
            m + 1,
            exact[m]
        );
    }
    // And shear matters here: Euler-Bernoulli's first frequency is 2% and more off.
    let eb = (std::f64::consts::PI / l).powi(2)
        * (e * i / (rho * std::f64::consts::PI * d * d / 4.0)).sqrt();
    assert!((eb - exact[0]) / exact[0] > 0.02);
}

/// Two uncoupled whirling masses (k = 1 and 4, m = 1); the first has gyroscopic stiffening:
/// its forward frequency `(Omega/2 + sqrt(Omega^2/4 + 4)) / 2` crosses 2 at `Omega = 3`.
fn crossing(coupling: f64) -> RotorSystem {
    system(json!({
        "type": "matrices",
        "mass": [[1.0, 0.0], [0.0, 1.0]],
        "stiffness": [[1.0, coupling], [coupling, 4.0]],
        "gyroscopic": [[0.5, 0.0], [0.0, 0.0]],
        "damping_nonrotating": [[0.01, 0.0], [0.0, 0.01]]
    }))
}

fn forward_branches(s: &RotorSystem, speeds: &[f64]) -> Vec<Vec<f64>> {
    let m = DampedModel::build(s, &DampingModel::Viscous).unwrap();
    let c = campbell(&m, speeds, &Control::default()).unwrap();
    c.branches
        .iter()
        .filter(|b| b.whirl == Whirl::Forward)
        .map(|b| b.poles.iter().map(|p| p.unwrap().im).collect())
        .collect()
}

#[test]
fn tracking_follows_modes_through_a_crossing() {
    let speeds: Vec<f64> = (0..50).map(|i| i as f64 * 6.0 / 49.0).collect();
    let f = forward_branches(&crossing(0.0), &speeds);
    assert_eq!(f.len(), 2);
    let (gyro, plain) = if f[0][0] < f[1][0] {
        (&f[0], &f[1])
    } else {
        (&f[1], &f[0])
    };
    // The gyroscopic mode keeps rising through 2; the other stays at 2: they cross.
    for (w, (g, p)) in speeds.iter().zip(gyro.iter().zip(plain)) {
        let exact = (w / 2.0 + (w * w / 4.0 + 4.0).sqrt()) / 2.0;
        assert!((g - exact).abs() < 1e-3, "at {w}: {g} vs {exact}");
        assert!((p - 2.0).abs() < 1e-3);
    }
    assert!(gyro.last().unwrap() > &3.0);
}

#[test]
fn tracking_follows_modes_through_veering_without_jumps() {
    // With coupling the crossing becomes a veering: neither branch jumps to the other.
    let speeds: Vec<f64> = (0..120).map(|i| i as f64 * 6.0 / 119.0).collect();
    let f = forward_branches(&crossing(0.15), &speeds);
    assert_eq!(f.len(), 2);
    let (low, high) = if f[0][0] < f[1][0] {
        (&f[0], &f[1])
    } else {
        (&f[1], &f[0])
    };
    for k in 0..speeds.len() {
        assert!(low[k] < high[k], "branches swapped at {}", speeds[k]);
        if k > 0 {
            assert!((low[k] - low[k - 1]).abs() < 0.1 && (high[k] - high[k - 1]).abs() < 0.1);
        }
    }
}

#[test]
fn a_jeffcott_given_as_matrices_has_the_jeffcott_poles() {
    let m = system(json!({
        "type": "matrices", "mass": [[1.0]], "stiffness": [[1.0]],
        "hysteretic_rotating": [[0.01]]
    }));
    let j = system(
        json!({"type": "jeffcott", "mass": 1.0, "stiffness": 1.0, "loss_factor_rotating": 0.01}),
    );
    for model in [
        DampingModel::Hysteretic,
        DampingModel::Equivalent { modes: None },
    ] {
        let a = poles_at(&DampedModel::build(&m, &model).unwrap(), 2.5).unwrap();
        let b = poles_at(&DampedModel::build(&j, &model).unwrap(), 2.5).unwrap();
        for (p, q) in a.rotor.iter().zip(&b.rotor) {
            assert!((p.s - q.s).norm() < 1e-14);
        }
    }
}

async fn problem(body: Value) -> Vec<(String, String)> {
    let req = Request::post("/v1/modal")
        .header("content-type", "application/json")
        .body(Body::from(body.to_string()))
        .unwrap();
    let resp = app(Config::default()).oneshot(req).await.unwrap();
    assert_eq!(resp.status(), StatusCode::UNPROCESSABLE_ENTITY);
    let v: Value =
        serde_json::from_slice(&resp.into_body().collect().await.unwrap().to_bytes()).unwrap();
    v["errors"]
        .as_array()
        .unwrap()
        .iter()
        .map(|e| {
            (
                e["path"].as_str().unwrap().into(),
                e["message"].as_str().unwrap().into(),
            )
        })
        .collect()
}

fn beam(materials: Value, shaft: Value, disks: Value, supports: Value) -> Value {
    json!({"rotor": {"type": "beam", "materials": materials, "shaft": shaft, "disks": disks,
                     "supports": supports},
           "damping": {"model": "hysteretic"}})
}

#[tokio::test]
async fn beam_validation_names_each_bad_field() {
    let steel = json!({"steel": {"young_modulus": 2.1e11, "density": 7810, "poisson_ratio": 0.3}});
    let seg = json!([{"length": 1.0, "outer_diameter": 0.05, "material": "steel", "elements": 2}]);
    let sup = json!([{"node": 0, "stiffness": 1e7}, {"node": 2, "stiffness": 1e7}]);
    let cases = vec![
        (
            beam(
                steel.clone(),
                json!([{"length": 1.0, "outer_diameter": 0.05, "inner_diameter": 0.05, "material": "steel"}]),
                json!([]),
                json!([{"node": 0, "stiffness": 1e7}]),
            ),
            "rotor.shaft[0].inner_diameter",
        ),
        (
            beam(
                steel.clone(),
                seg.clone(),
                json!([{"node": 3, "mass": 1.0}]),
                sup.clone(),
            ),
            "rotor.disks[0].node",
        ),
        (
            beam(
                steel.clone(),
                seg.clone(),
                json!([]),
                json!([{"node": -1, "stiffness": 1e7}]),
            ),
            "rotor.supports[0].node",
        ),
        (
            beam(
                steel.clone(),
                json!([{"length": 1.0, "outer_diameter": 0.05, "material": "titanium"}]),
                json!([]),
                json!([{"node": 0, "stiffness": 1e7}]),
            ),
            "rotor.shaft[0].material",
        ),
        (
            beam(
                json!({"steel": {"young_modulus": 0.0, "density": 7810, "poisson_ratio": 0.3}}),
                seg.clone(),
                json!([]),
                sup.clone(),
            ),
            "rotor.materials.steel.young_modulus",
        ),
        (
            beam(
                json!({"steel": {"young_modulus": 2e11, "density": -1.0, "poisson_ratio": 0.3}}),
                seg.clone(),
                json!([]),
                sup.clone(),
            ),
            "rotor.materials.steel.density",
        ),
        (
            beam(
                json!({"steel": {"young_modulus": 2e11, "density": 7800, "poisson_ratio": 0.5}}),
                seg.clone(),
                json!([]),
                sup.clone(),
            ),
            "rotor.materials.steel.poisson_ratio",
        ),
        (
            beam(
                json!({"steel": {"young_modulus": 2e11, "density": 7800, "poisson_ratio": -1.0}}),
                seg.clone(),
                json!([]),
                sup.clone(),
            ),
            "rotor.materials.steel.poisson_ratio",
        ),
        (
            beam(steel.clone(), seg.clone(), json!([]), json!([])),
            "rotor.supports",
        ),
        (
            beam(
                steel.clone(),
                json!([{"length": 1.0, "outer_diameter": 0.05, "material": "steel", "elements": 0}]),
                json!([]),
                sup.clone(),
            ),
            "rotor.shaft[0].elements",
        ),
        (
            beam(
                steel.clone(),
                json!([{"length": 1.0, "outer_diameter": 0.05, "material": "steel", "elements": 600}]),
                json!([]),
                sup.clone(),
            ),
            "rotor.shaft[0].elements",
        ),
        (
            beam(
                steel.clone(),
                json!([{"length": 1.0, "outer_diameter": 0.05, "material": "steel", "elements": 400},
                       {"length": 1.0, "outer_diameter": 0.05, "material": "steel", "elements": 400}]),
                json!([]),
                sup.clone(),
            ),
            "rotor.shaft",
        ),
        // Supports that hold nothing: a rigid-body mode, refused rather than divided by.
        (
            beam(
                steel.clone(),
                seg.clone(),
                json!([]),
                json!([{"node": 1, "stiffness": 0.0}]),
            ),
            "rotor.supports",
        ),
    ];
    for (body, path) in cases {
        let errors = problem(body.clone()).await;
        assert!(
            errors.iter().any(|(p, _)| p == path),
            "{path} not in {errors:?} for {body}"
        );
    }
}

#[tokio::test]
async fn matrices_validation_names_each_bad_field() {
    let req = |rotor: Value| json!({"rotor": rotor, "damping": {"model": "viscous"}});
    let cases = vec![
        (
            json!({"type": "matrices", "mass": [[1.0, 0.0], [0.0, 1.0]], "stiffness": [[1.0]]}),
            "rotor.stiffness",
        ),
        (
            json!({"type": "matrices", "mass": [[1.0, 0.0], [0.0, 1.0]], "stiffness": [[2.0, 1.0], [0.0, 2.0]]}),
            "rotor.stiffness[1][0]",
        ),
        (
            json!({"type": "matrices", "mass": [[1.0, 0.0], [0.0, -1.0]], "stiffness": [[2.0, 0.0], [0.0, 2.0]]}),
            "rotor.mass",
        ),
        (
            json!({"type": "matrices", "mass": [], "stiffness": []}),
            "rotor.mass",
        ),
        (
            json!({"type": "matrices", "mass": [[1.0]], "stiffness": [[0.0]]}),
            "rotor.stiffness",
        ),
    ];
    for (rotor, path) in cases {
        let errors = problem(req(rotor.clone())).await;
        assert!(
            errors.iter().any(|(p, _)| p == path),
            "{path} not in {errors:?} for {rotor}"
        );
    }
}

fn compressor() -> RotorSystem {
    let path = format!(
        "{}/examples/compressor-nvd.campbell.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let v: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    system(v["rotor"].clone())
}

#[test]
fn a_nonrotating_rotor_is_never_unstable_under_any_model() {
    // M > 0, C >= 0, K symmetric: every decay rate is <= 0 at rest. On the 100-element
    // compressor (101 dof after Guyan, frequencies to 1e6 rad/s) an unbalanced eigensolver
    // leaves round-off of eps w_max^2 ~ 1e-4 in the decay rates, and reported a threshold at
    // 0 rad/s; balancing brings it to eps w_max.
    let s = compressor();
    assert_eq!(s.n(), 101);
    for model in [
        DampingModel::Viscous,
        DampingModel::Hysteretic,
        DampingModel::Equivalent { modes: Some(8) },
        DampingModel::Equivalent { modes: None },
    ] {
        let set = poles_at(&DampedModel::build(&s, &model).unwrap(), 0.0).unwrap();
        assert!(set.growth() <= 0.0, "{model:?}: growth {}", set.growth());
        let worst = set
            .all()
            .map(|p| p.s.re / p.s.norm())
            .fold(f64::NEG_INFINITY, f64::max);
        assert!(worst < 1e-12, "{model:?}: sigma/|s| = {worst}");
    }
}

#[test]
fn the_compressor_threshold_with_equivalent_damping_is_supercritical_in_mode_1() {
    let model =
        DampedModel::build(&compressor(), &DampingModel::Equivalent { modes: Some(8) }).unwrap();
    let speeds: Vec<f64> = (0..=30).map(|i| i as f64 * 100.0).collect();
    let t = whirl::analysis::stability::stability(&model, &speeds, &Control::default())
        .unwrap()
        .unwrap();
    assert_eq!((t.mode, t.pole.whirl), (1, Whirl::Forward));
    assert!(t.speed > 2000.0 && t.speed < 3000.0, "{}", t.speed);
    // The hysteretic model is stable over the same range.
    let h = DampedModel::build(&compressor(), &DampingModel::Hysteretic).unwrap();
    let coarse: Vec<f64> = (0..=10).map(|i| i as f64 * 300.0).collect();
    assert!(
        whirl::analysis::stability::stability(&h, &coarse, &Control::default())
            .unwrap()
            .is_none()
    );
}
