//! Modal reduction of sweeps: the reduced Campbell diagram equals the full one, at every speed
//! of the sweep (not only where the reduction was checked), under every damping model.

use serde_json::Value;
use whirl::analysis::campbell::{CampbellResult, Keep, campbell_below};
use whirl::analysis::control::Control;
use whirl::damping::DampedModel;
use whirl::fem::modal::ModalBasis;
use whirl::model::api::{DampingInput, RotorInput};
use whirl::model::damping::DampingModel;
use whirl::model::rotor::{Limits, Rotor};
use whirl::system::RotorSystem;

const BOUND: f64 = 6000.0;

fn compressor(guyan: bool) -> RotorSystem {
    let path = format!(
        "{}/examples/compressor-nvd.campbell.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let v: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let mut rotor = v["rotor"].clone();
    if !guyan {
        rotor.as_object_mut().unwrap().remove("reduction");
    }
    let rotor: RotorInput = serde_json::from_value(rotor).unwrap();
    RotorSystem::assemble(&Rotor::parse(&rotor, &Limits::default()).unwrap()).unwrap()
}

fn damping(v: Value, n: usize) -> DampingModel {
    let d: DampingInput = serde_json::from_value(v).unwrap();
    DampingModel::parse(&d, Some(n)).unwrap()
}

fn sweep(system: &RotorSystem, model: &DampingModel, reduce: bool) -> CampbellResult {
    let full = DampedModel::build(system, model).unwrap();
    let speeds: Vec<f64> = (0..6).map(|i| i as f64 * 300.0).collect();
    campbell_below(
        system,
        model,
        &full,
        &speeds,
        Keep {
            below: BOUND,
            lowest: None,
        },
        reduce,
        &Control::default(),
    )
    .unwrap()
}

/// Every branch of the reduced sweep is a branch of the full one, value by value, within the
/// reduction's tolerance of 1e-6 relative; same branches, same mode numbers, same criticals.
fn assert_same(system: &RotorSystem, model: &DampingModel) {
    let full = sweep(system, model, false);
    let reduced = sweep(system, model, true);
    let r = reduced.reduction.as_ref().expect("the compressor reduces");
    assert!(r.max_relative_error <= 1e-6, "{r:?}");
    assert!(2 * r.states <= r.full_states, "{r:?}");
    assert!(full.reduction.is_none());
    assert_eq!(full.branches.len(), reduced.branches.len());
    let mut worst = 0.0f64;
    for (a, b) in full.branches.iter().zip(&reduced.branches) {
        assert_eq!((a.mode, a.whirl), (b.mode, b.whirl));
        for (p, q) in a.poles.iter().zip(&b.poles) {
            match (p, q) {
                (Some(p), Some(q)) => worst = worst.max((p - q).norm() / p.norm()),
                (None, None) => {}
                _ => panic!("{model:?}: a pole defined in one model only"),
            }
        }
    }
    assert!(worst <= 1e-6, "{model:?}: {worst:e}");
    assert_eq!(full.critical_speeds.len(), reduced.critical_speeds.len());
    for (a, b) in full.critical_speeds.iter().zip(&reduced.critical_speeds) {
        assert!((a - b).abs() <= 1e-6 * a, "critical speed {a} vs {b}");
    }
}

#[test]
fn reduced_sweeps_equal_full_ones_under_every_model() {
    let system = compressor(true);
    let n = system.n();
    for d in [
        serde_json::json!({"model": "viscous"}),
        serde_json::json!({"model": "hysteretic"}),
        serde_json::json!({"model": "equivalent"}),
        serde_json::json!({"model": "nonviscous", "modes": 8}),
    ] {
        assert_same(&system, &damping(d, n));
    }
}

/// The unreduced shaft (rotations kept) is where a projected stiffness cancels: K phi for a
/// 442 rad/s mode of a shaft whose rotations reach 1e6 rad/s loses about 5e-6 relative, more
/// than the tolerance. The reduction avoids forming it.
#[test]
fn the_unreduced_shaft_reduces_without_cancellation() {
    let system = compressor(false);
    let model = DampingModel::Viscous;
    assert_same(&system, &model);
    let reduced = sweep(&system, &model, true);
    let r = reduced.reduction.unwrap();
    assert!(r.max_relative_error < 1e-6, "{r:?}");
    // The modes up to twice the bound suffice with their static corrections.
    let basis = ModalBasis::of(&system).unwrap();
    let kept = basis.omega.iter().filter(|&&w| w <= 2.0 * BOUND).count();
    assert_eq!(r.modes, kept);
}

/// The augmented basis keeps the exact modes it started from, is M-orthonormal and
/// K-diagonal, so the reduced mass is the identity.
#[test]
fn the_augmented_basis_keeps_the_exact_modes() {
    let system = compressor(true);
    let basis = ModalBasis::of(&system).unwrap();
    let aug = basis.augmented(&system, 6).unwrap();
    assert!(aug.len() > 6);
    for k in 0..6 {
        let rel = (aug.omega[k] - basis.omega[k]).abs() / basis.omega[k];
        assert!(
            rel < 1e-10,
            "mode {k}: {} vs {}",
            aug.omega[k],
            basis.omega[k]
        );
    }
    let mr = aug.project(&system.mass);
    for i in 0..aug.len() {
        for j in 0..aug.len() {
            let expect = if i == j { 1.0 } else { 0.0 };
            assert!(
                (mr[(i, j)] - expect).abs() < 1e-9,
                "M[{i},{j}] = {}",
                mr[(i, j)]
            );
        }
    }
}
