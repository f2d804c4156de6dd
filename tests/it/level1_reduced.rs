//! API 617 Level I on the checked modal reduction equals Level I on the full model: every
//! point of the curve and q0, on isotropic and cross-coupled anisotropic bearings, under the
//! viscous, hysteretic and equivalent models, and under the nonviscous model (its check compares
//! the rotor poles, the full model's found by shift-invert Arnoldi).

use crate::common;

use common::{assemble, heldout};
use serde_json::{Value, json};
use whirl::analysis::audit::level1::level1;
use whirl::analysis::audit::level1_reduced::level1_reduced;
use whirl::analysis::control::Control;
use whirl::damping::DampedModel;
use whirl::model::api::DampingInput;
use whirl::model::damping::DampingModel;

/// The 45-element stepped shaft on the anisotropic, cross-coupled first bearing of
/// `aniso.json`.
fn anisotropic() -> Value {
    let path = format!("{}/tests/data/ross/aniso.json", env!("CARGO_MANIFEST_DIR"));
    let v: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    common::stepped_rotor(45, v["rotor"]["supports"][0].clone(), 0.002)
}

fn case(name: &str, rotor: Value, nodes: &[usize]) {
    let models = [
        json!({"model": "viscous"}),
        json!({"model": "hysteretic"}),
        json!({"model": "equivalent"}),
    ];
    case_of(name, rotor, nodes, &models);
}

fn case_of(name: &str, rotor: Value, nodes: &[usize], models: &[Value]) {
    let system = assemble(rotor);
    for d in models {
        let input: DampingInput = serde_json::from_value(d.clone()).unwrap();
        let model = DampingModel::parse(&input, Some(system.n())).unwrap();
        let full = DampedModel::build(&system, &model).unwrap();
        let speed = 1.5 * full.basis.omega[0];
        let share = 1.0 / nodes.len() as f64;
        let at: Vec<(usize, f64)> = nodes
            .iter()
            .map(|&n| (system.translation(n).unwrap(), share))
            .collect();
        let control = Control::default();
        let t = std::time::Instant::now();
        let r = level1_reduced(
            &system,
            &model,
            speed,
            &at,
            &[],
            11,
            None,
            true,
            false,
            &control,
        )
        .unwrap();
        let reduced_time = t.elapsed();
        let info = r
            .reduction
            .clone()
            .unwrap_or_else(|| panic!("{name} {d}: not reduced"));
        let t = std::time::Instant::now();
        let exact = level1(&system, &model, speed, &at, &r.qs, &control).unwrap();
        let full_time = t.elapsed();
        eprintln!(
            "{name} {d}: {} of {} states, checked at q = {:.4e} ({:.1e}); q0 {:?} vs {:?}; \
             {reduced_time:?} vs {full_time:?}",
            info.states,
            info.full_states,
            info.checked_q,
            info.max_relative_error,
            r.result.q0,
            exact.q0
        );
        assert!(2 * info.states <= info.full_states);
        for (a, b) in exact.curve.iter().zip(&r.result.curve) {
            let (a, b) = (a.unwrap(), b.unwrap());
            let modulus = (a.0 * a.0 + a.1 * a.1).sqrt();
            let d = ((a.0 - b.0).powi(2) + (a.1 - b.1).powi(2)).sqrt();
            assert!(d <= 1e-6 * modulus, "{name} {d}: {a:?} vs {b:?}");
        }
        match (exact.q0, r.result.q0) {
            (Some(a), Some(b)) => assert!((a - b).abs() <= 1e-5 * a, "{name} {d}: {a} vs {b}"),
            (None, None) => {}
            other => panic!("{name} {d}: q0 {other:?}"),
        }
    }
}

#[test]
fn isotropic_rotor() {
    case("rotor_6", heldout(6, 0.002), &[12, 40]);
}

#[test]
fn cross_coupled_anisotropic_bearings() {
    case("anisotropic", anisotropic(), &[20]);
}

#[test]
fn nonviscous_model() {
    case_of(
        "rotor_6",
        heldout(6, 0.002),
        &[12, 40],
        &[json!({"model": "nonviscous"})],
    );
}
