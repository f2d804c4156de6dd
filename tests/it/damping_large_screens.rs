//! API 617 Level I and time responses of the equivalent and nonviscous models held sparse
//! (`damping::dampers`: dampers on the full rotor's lowest modes, the reduction carrying them
//! projected): against the dense full models on rotors both can hold, the same modes damped.

use crate::common;

use serde_json::{Value, json};
use whirl::analysis::audit::level1_reduced::level1_reduced;
use whirl::analysis::control::Control;
use whirl::analysis::time::{reduced, time_response};
use whirl::damping::DampedModel;
use whirl::model::api::DampingInput;
use whirl::model::damping::DampingModel;

fn damping(v: Value, n: usize) -> DampingModel {
    let d: DampingInput = serde_json::from_value(v).unwrap();
    DampingModel::parse(&d, Some(n)).unwrap()
}

/// Level I at 700 rad/s with the cross-coupling at mid-span, 30 elements, the 12 lowest modes
/// damped (x/y modes: 24; with every mode the nonviscous model's reduction would not halve the
/// states, its branches on modes its basis partly holds): held sparse (a reduction checked through sparse factors, the dampers projected on it)
/// against the dense full model solved without reduction, on isotropic bearings and on
/// cross-coupled anisotropic ones (doubled coordinates). `q0` (N/m, refined to 1e-9) and the
/// first forward pole at rest and at half of `q0` (rad/s) agree within the reductions' 1e-6
/// (measured: q0 4.3e-10 to 3.3e-9, the poles 1.9e-11 to 1.2e-10).
#[test]
fn level1_held_sparse_is_the_dense_full_model() {
    let speed = 700.0;
    let (iso, _, constant) = common::stepped_three(30, speed);
    let control = Control::default();
    for system in [&iso, &constant] {
        let n = system.n();
        let at = [(system.translation(15).unwrap(), 1.0)];
        for d in [
            json!({"model": "equivalent", "modes": 12}),
            json!({"model": "nonviscous", "modes": 12}),
        ] {
            let model = damping(d.clone(), n);
            let screen = |qa: Option<f64>, reduce: bool, held: bool| {
                level1_reduced(
                    system,
                    &model,
                    speed,
                    &at,
                    &[],
                    11,
                    qa,
                    reduce,
                    held,
                    &control,
                )
                .unwrap()
            };
            let probe = screen(None, false, false);
            let q0 = probe.result.q0.expect("a threshold");
            let dense = screen(Some(0.5 * q0), false, false);
            let held = screen(Some(0.5 * q0), true, true);
            let red = held.reduction.as_ref().expect("reduced");
            assert!(red.sparse && red.dampers.is_some(), "{d}");
            let pole = |p: Option<(f64, f64)>| p.expect("a forward pole");
            let rel = |a: (f64, f64), b: (f64, f64)| (a.0 - b.0).hypot(a.1 - b.1) / b.0.hypot(b.1);
            let dq0 = (held.result.q0.unwrap() - q0).abs() / q0;
            let d0 = rel(pole(held.result.base), pole(dense.result.base));
            let dqa = rel(pole(held.qa.unwrap().1), pole(dense.qa.unwrap().1));
            eprintln!(
                "{:?} {d}: q0 {q0:.6e} N/m ({dq0:.1e}), pole at 0 {d0:.1e}, at q0/2 {dqa:.1e}; \
                 {} of {} states, check {:.1e}",
                system.layout(),
                red.states,
                red.full_states,
                red.max_relative_error
            );
            assert!(dq0 <= 1e-6 && d0 <= 1e-6 && dqa <= 1e-6, "{d}");
        }
    }
}

/// `tests/it/time_large.rs`'s shock (the 150-element rotor at 700 rad/s on soft cross-coupled
/// bearings, 604 coordinates, a 10 kN blow ramped over 11 ms at node 40) under the equivalent
/// and nonviscous models, their 40 lowest x/y modes damped: integrated on the reduction held
/// sparse against the exact solution of the dense full model (its modes' closed forms), within
/// 1e-4 of the largest amplitude at the loaded node as the viscous model's is there (measured
/// 3.6e-5 and 3.5e-5; the viscous model 4.2e-5).
#[test]
fn a_shock_held_sparse_matches_the_exact_dense_model() {
    let (system, spec) = common::shock_case(&[[0.0, 0.0], [0.011, 1e4], [0.022, 0.0]]);
    let control = Control::default();
    for d in [
        json!({"model": "equivalent", "modes": 20}),
        json!({"model": "nonviscous", "modes": 20}),
    ] {
        let model = damping(d.clone(), system.n());
        let (r, info) = reduced::solve_sparse(&system, &model, &spec, true, true, &control)
            .unwrap()
            .expect("a reduction");
        assert!(info.sparse && info.dampers.is_some(), "{info:?}");
        let full = DampedModel::build(&system, &model).unwrap();
        let exact = time_response(&system, &full, &spec, false, &control).unwrap();
        let (dev, _) = common::deviation(&r, &exact);
        eprintln!(
            "{d}: {} of {} states ({} modes, {:?} damped); {dev:.1e} of the largest amplitude",
            info.states, info.full_states, info.modes, info.dampers
        );
        assert!(dev <= 1e-4, "{d}: {dev:e}");
    }
}
