//! Time responses of rotors held sparse (past the dense limits): integrated on a modal
//! reduction found and checked through sparse factors (`time::reduced::solve_sparse`), at a
//! varying speed as every run-up of the viscous model already was and, held sparse, at a
//! constant speed too (a shock, a blade loss), where a small rotor is solved exactly on its
//! full model. Checked against that exact solution on a rotor both can hold, then over HTTP on
//! the 1080-element train.

use crate::common;

use common::post_json;
use serde_json::{Value, json};
use whirl::analysis::control::Control;
use whirl::analysis::time::{reduced, time_response};
use whirl::damping::DampedModel;
use whirl::model::api::DampingInput;
use whirl::model::damping::DampingModel;

/// The 150-element stepped rotor spun at 700 rad/s on soft, lightly damped, cross-coupled
/// anisotropic bearings (604 coordinates), viscous, struck along x at node 40 by `history`:
/// the response on the reduction held sparse against the exact solution of the full model (its
/// modes' closed forms, `time::exact`), relative to the largest amplitude at that node.
fn shock(history: &[[f64; 2]]) -> f64 {
    let (system, spec) = common::shock_case(history);
    let d: DampingInput = serde_json::from_value(json!({"model": "viscous"})).unwrap();
    let damping = DampingModel::parse(&d, None).unwrap();
    let control = Control::default();
    // A rotor not held sparse is solved exactly at a constant speed.
    assert!(
        reduced::solve_sparse(&system, &damping, &spec, true, false, &control)
            .unwrap()
            .is_none()
    );
    let (r, info) = reduced::solve_sparse(&system, &damping, &spec, true, true, &control)
        .unwrap()
        .expect("a reduction");
    assert!(
        info.sparse && 2 * info.states <= info.full_states,
        "{info:?}"
    );
    let full = DampedModel::build(&system, &damping).unwrap();
    let exact = time_response(&system, &full, &spec, false, &control).unwrap();
    let (dev, top) = common::deviation(&r, &exact);
    println!(
        "shock held sparse: {} of {} states ({} modes); {dev:.1e} of the largest amplitude \
         {top:.4e} m from the exact full model",
        info.states, info.full_states, info.modes
    );
    dev
}

/// A 10 kN blow ramped up over 11 ms and released over as long is reproduced as a run-up is
/// (measured 4.2e-5 of the peak); released at once (the bundled example's blow), every mode
/// above the band rings at about its static deflection: measured 2.5e-3 at the loaded node.
#[test]
fn a_shock_held_sparse_matches_the_exact_full_model() {
    let smooth = shock(&[[0.0, 0.0], [0.011, 1e4], [0.022, 0.0]]);
    assert!(smooth <= 1e-4, "{smooth:e}");
    let sudden = shock(&[[0.0, 0.0], [0.011, 1e4], [0.011, 0.0]]);
    assert!(sudden <= 3e-3, "{sudden:e}");
}

/// The bundled train meshed with 1080 elements (4336 coordinates), viscous: a run-up through
/// its first criticals and a shock answer on sparse reductions, their peaks within 1e-3 of the
/// 180-element mesh's, and so does the nonviscous model's run-up (measured 2.0e-6);
/// `modal_reduction: false` past the dense limits is a 422 naming the setting.
#[tokio::test]
#[ignore = "heavy: a dense reference of a large rotor (cargo test --release -- --ignored)"]
async fn train_of_1080_elements() {
    let example: Value = serde_json::from_str(
        &std::fs::read_to_string("examples/train-hysteretic.campbell.json").unwrap(),
    )
    .unwrap();
    let mut peaks = vec![];
    for k in [10usize, 60] {
        let (rotor, map) = common::refined(&example["rotor"], k);
        let runup = json!({
            "rotor": rotor, "damping": {"model": "viscous"},
            "speed_profile": [[0, 0], [3, 600]],
            "unbalances": [{"node": map[3], "amount": 1e-4, "phase": 0}],
            "duration": 3, "output_interval": 0.002, "nodes": [map[3]]
        });
        let shock = json!({
            "rotor": runup["rotor"], "damping": {"model": "viscous"}, "speed": 600,
            "forces": [{"node": map[3], "direction": 0.0,
                        "history": [[0, 0], [0.011, 1e4], [0.011, 0]]}],
            "duration": 0.5, "output_interval": 0.0005, "nodes": [map[3]]
        });
        let mut row = vec![];
        for (name, body) in [("run-up", &runup), ("shock", &shock)] {
            let t = std::time::Instant::now();
            let (status, out) = post_json("/v1/time-response", body).await;
            let seconds = t.elapsed().as_secs_f64();
            assert_eq!(status, 200, "{name} x{k}: {out}");
            let red = &out["reduction"];
            let peak = common::radial_peak(&out);
            println!(
                "train x{k} {name}: {seconds:.2} s, {} of {} states ({} held), peak {peak:.6e} m",
                red["states"], red["full_states"], red["full_model"]
            );
            assert_eq!(red["full_model"], "sparse", "{name} x{k}");
            assert!(peak.is_finite() && peak > 0.0);
            row.push(peak);
        }
        // The nonviscous model held sparse: its dampers on the modes up to 16 times the band,
        // projected on the reduction, each branch a state.
        let mut body = runup.clone();
        body["damping"] = json!({"model": "nonviscous"});
        let t = std::time::Instant::now();
        let (status, out) = post_json("/v1/time-response", &body).await;
        assert_eq!(status, 200, "nonviscous x{k}: {out}");
        let red = &out["reduction"];
        let peak = common::radial_peak(&out);
        println!(
            "train x{k} nonviscous run-up: {:.2} s, {} of {} states ({} modes damped), peak \
             {peak:.6e} m",
            t.elapsed().as_secs_f64(),
            red["states"],
            red["full_states"],
            red["damped_modes"]
        );
        assert_eq!(red["full_model"], "sparse");
        row.push(peak);
        peaks.push(row);
        if k == 60 {
            let mut body = runup;
            body["modal_reduction"] = json!(false);
            let (status, out) = post_json("/v1/time-response", &body).await;
            assert_eq!(status, 422, "{out}");
            assert!(out.to_string().contains("WHIRL_MAX_DOFS"), "{out}");
        }
    }
    for (i, name) in ["run-up", "shock", "nonviscous run-up"].iter().enumerate() {
        let (a, b) = (peaks[0][i], peaks[1][i]);
        assert!(
            (a - b).abs() <= 1e-3 * a,
            "{name}: {a:e} (180 el) against {b:e} (1080 el)"
        );
    }
}
