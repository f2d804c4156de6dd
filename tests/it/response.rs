//! Harmonic responses on the checked modal reduction (`analysis::response`) equal the full
//! model's at every frequency of the sweep, not only where the reduction was checked: within
//! 1e-6 of the largest response, on isotropic, cross-coupled anisotropic and tabulated
//! supports, under every damping model; their refined peaks within 1e-4.

use crate::common;

use common::{assemble, heldout};
use serde_json::{Value, json};
use whirl::analysis::audit::frequency::{Excitation, Orbit, frequency_response};
use whirl::analysis::audit::peaks::{self, Peak};
use whirl::analysis::control::Control;
use whirl::analysis::response::{Responses, frequency_sweep, unbalance_force, unbalance_sweep};
use whirl::analysis::unbalance::{SteadyUnbalance, unbalance_response};
use whirl::damping::DampedModel;
use whirl::model::api::DampingInput;
use whirl::model::damping::DampingModel;
use whirl::system::RotorSystem;

/// The 60-element stepped shaft on two bearings tabulated against speed (cross-coupled,
/// anisotropic, the first bearing of `speed_dependent.json`).
fn tabulated() -> Value {
    let path = format!(
        "{}/tests/data/ross/speed_dependent.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let v: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    common::stepped_rotor(60, v["rotor"]["supports"][0].clone(), 0.002)
}

fn damping(v: Value, n: usize) -> DampingModel {
    let d: DampingInput = serde_json::from_value(v).unwrap();
    DampingModel::parse(&d, Some(n)).unwrap()
}

fn models() -> Vec<Value> {
    vec![
        json!({"model": "viscous"}),
        json!({"model": "hysteretic"}),
        json!({"model": "equivalent"}),
        json!({"model": "nonviscous", "modes": 8}),
    ]
}

fn translation(system: &RotorSystem, node: usize) -> usize {
    system.translation(node).unwrap()
}

/// Largest `|a - a'| + |b - b'|` over every orbit, relative to the largest `|a| + |b|`.
fn worst(full: &[Vec<Orbit>], reduced: &[Vec<Orbit>]) -> f64 {
    let mut diff = 0.0f64;
    let mut top = 0.0f64;
    for (f, r) in full.iter().zip(reduced) {
        assert_eq!(f.len(), r.len());
        for (f, r) in f.iter().zip(r) {
            diff = diff.max((f.a - r.a).norm() + (f.b - r.b).norm());
            top = top.max(f.a.norm() + f.b.norm());
        }
    }
    diff / top
}

/// The first forward peaks of `amp` refined with `eval`.
fn refined(
    speeds: &[f64],
    amp: &[f64],
    eval: &mut dyn FnMut(f64) -> Result<f64, whirl::analysis::AnalysisError>,
) -> Vec<Peak> {
    let mut budget = 1_000_000;
    peaks::peaks(speeds, amp, eval, &mut budget).unwrap()
}

/// The unbalance response of `rotor` up to 1.3 times its third natural frequency at rest, on
/// the reduction and on the full model: orbits within 1e-6, refined peaks within 1e-4; the
/// state at least halved. Returns the reduction's error and the state sizes.
fn unbalance_case(name: &str, rotor: Value, d: Value, unbalance: usize, out: &[usize]) {
    let system = assemble(rotor);
    let model = damping(d.clone(), system.n());
    let full = DampedModel::build(&system, &model).unwrap();
    let top = 1.3 * full.basis.omega[2];
    let speeds: Vec<f64> = (0..40).map(|i| top * i as f64 / 39.0).collect();
    let loads = [SteadyUnbalance {
        dof: translation(&system, unbalance),
        amount: 1e-4,
        phase: 0.3,
    }];
    let out: Vec<usize> = out.iter().map(|&n| translation(&system, n)).collect();
    let control = Control::default();
    let exact = unbalance_response(&system, &full, &speeds, &loads, &out, &control).unwrap();
    let (approx, responses) = unbalance_sweep(
        &system, &model, &full, &speeds, &loads, &out, true, &control,
    )
    .unwrap();
    let info = responses
        .reduction()
        .unwrap_or_else(|| panic!("{name} {d}: not reduced"))
        .clone();
    assert!(2 * info.states <= info.full_states, "{name} {d}: {info:?}");
    let err = worst(&exact, &approx);
    eprintln!(
        "{name} {d}: {} of {} states, {} vectors, checked {:?} ({:.1e}), sweep error {err:.2e}",
        info.states, info.full_states, info.vectors, info.checked, info.max_relative_error
    );
    assert!(err <= 1e-6, "{name} {d}: {err:e} {info:?}");
    // Peaks at the first output, refined on either model.
    let amp = |o: &[Vec<Orbit>]| o.iter().map(|o| o[0].major()).collect::<Vec<f64>>();
    let n = system.n();
    let one = [out[0]];
    let p_full = refined(&speeds, &amp(&exact), &mut |w| {
        Ok(
            Responses::full(&system, &full).orbits(w, w, &unbalance_force(&loads, n, w), &one)?[0]
                .major(),
        )
    });
    let p_red = refined(&speeds, &amp(&approx), &mut |w| {
        Ok(responses.orbits(w, w, &unbalance_force(&loads, n, w), &one)?[0].major())
    });
    assert_eq!(p_full.len(), p_red.len(), "{name} {d}");
    assert!(!p_full.is_empty(), "{name} {d}: no peak");
    for (a, b) in p_full.iter().zip(&p_red) {
        assert!((a.speed - b.speed).abs() <= 1e-4 * a.speed, "{a:?} {b:?}");
        assert!((a.amplitude - b.amplitude).abs() <= 1e-4 * a.amplitude);
        match (a.amplification_factor, b.amplification_factor) {
            (Some(x), Some(y)) => assert!((x - y).abs() <= 1e-4 * x, "{a:?} {b:?}"),
            (None, None) => {}
            _ => panic!("{name} {d}: AF in one model only"),
        }
    }
}

#[test]
fn isotropic_rotor_under_every_damping_model() {
    for d in models() {
        unbalance_case("rotor_6", heldout(6, 0.002), d, 12, &[0, 12, 40]);
    }
}

#[test]
fn cross_coupled_anisotropic_rotor_under_every_damping_model() {
    for d in models() {
        unbalance_case("rotor_2", heldout(2, 0.002), d, 38, &[1, 38, 75]);
    }
}

/// benches/forced_ross.py's soft heavily damped cross-coupled rotor (held-out seed 9, 113
/// elements, `heldout/soft_heavy_seed9.json`, written by `heldout_rotor(9, disks=True,
/// stiff=False, heavy=True, anisotropic=True, bearings=2)`): its static corrections nearly lie
/// in the span of the soft supports' modes, and a basis whose stiffness was the tracked `K v`
/// drifted from the full model as it grew (1.7e-7 at 4 modes, 1e-3 at 40) and was never used;
/// with `K V` formed (`ModalBasis::augmented_formed`) it reduces like the others.
#[test]
fn soft_heavily_damped_cross_coupled_rotor_under_every_damping_model() {
    let path = format!(
        "{}/tests/data/ross/heldout/soft_heavy_seed9.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let mut rotor: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    rotor["materials"]["steel"]["loss_factor"] = json!(0.002);
    for d in models() {
        unbalance_case("soft_heavy", rotor.clone(), d, 16, &[1, 16, 48]);
    }
}

/// Outputs at every node: their static responses alone would keep any basis from halving
/// the state; the sweep is reduced on the loads' and supports' corrections instead, and
/// still equals the full model at every node and speed.
#[test]
fn outputs_at_every_node_are_read_off_the_reduction() {
    let rotor = heldout(6, 0.002);
    let system = assemble(rotor.clone());
    let every: Vec<usize> = (0..)
        .take_while(|&n| system.translation(n).is_some())
        .collect();
    assert_eq!(every.len(), 59);
    for d in models() {
        unbalance_case("rotor_6 at every node", rotor.clone(), d, 12, &every);
    }
}

#[test]
fn tabulated_supports_under_every_damping_model() {
    for d in models() {
        unbalance_case("tabulated", tabulated(), d, 22, &[1, 22, 59]);
    }
}

/// The non-synchronous frequency response at a fixed speed: a force along x at one end,
/// the orbit at a disk, on the reduction and on the full model.
#[test]
fn frequency_responses_equal_the_full_model() {
    for (name, rotor, input, output) in [
        ("rotor_6", heldout(6, 0.002), 0, 12),
        ("rotor_2", heldout(2, 0.002), 1, 38),
    ] {
        let system = assemble(rotor);
        for d in models() {
            let model = damping(d.clone(), system.n());
            let full = DampedModel::build(&system, &model).unwrap();
            let speed = 0.5 * full.basis.omega[0];
            let top = 1.3 * full.basis.omega[2];
            let freqs: Vec<f64> = (1..=40).map(|i| top * i as f64 / 40.0).collect();
            let (i, o) = (translation(&system, input), translation(&system, output));
            let excitation = Excitation::Direction(0.4);
            let control = Control::default();
            let exact =
                frequency_response(&system, &full, speed, (i, excitation), o, &freqs, &control)
                    .unwrap();
            let force = excitation.at(i, system.n());
            let (approx, responses) = frequency_sweep(
                &system, &model, &full, speed, &force, o, &freqs, true, &control,
            )
            .unwrap();
            let info = responses
                .reduction()
                .unwrap_or_else(|| panic!("{name} {d}: not reduced"));
            let wrap = |v: &[Orbit]| v.iter().map(|o| vec![*o]).collect::<Vec<_>>();
            let err = worst(&wrap(&exact), &wrap(&approx));
            eprintln!(
                "{name} {d} frequency response: {} of {} states, error {err:.2e}",
                info.states, info.full_states
            );
            assert!(err <= 1e-6, "{name} {d}: {err:e}");
        }
    }
}
