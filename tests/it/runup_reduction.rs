//! Run-ups on the checked modal reduction against the full model integrated at a tight
//! tolerance, on rotors built here for nothing in particular: stiff heavily damped and soft
//! lightly damped bearings, isotropic and cross-coupled anisotropic, with material loss
//! (so that the nonviscous model has rotating branches) and without.
//!
//! The full model's responses at tolerance 1e-8 (minutes of TR-BDF2 on every coordinate) are
//! computed once and kept in `tests/data/runup/`; `make_runup_references` (ignored; run it with
//! `cargo test --release --test it -- --ignored make_runup_references`) writes them again.
//! Each file carries the request it answers, checked here before it is read.

use crate::common;

use common::stepped_rotor as rotor;
use serde_json::{Value, json};
use whirl::analysis::control::Control;
use whirl::analysis::time::{SpeedLaw, TimeResult, TimeSpec, reduced, time_response};
use whirl::damping::DampedModel;
use whirl::linalg::c64;
use whirl::model::api::{DampingInput, RotorInput};
use whirl::model::damping::DampingModel;
use whirl::model::error::Invalid;
use whirl::model::loads::{Pwl, Unbalance};
use whirl::model::rotor::{Limits, Rotor};
use whirl::system::RotorSystem;

fn system(rotor: Value) -> RotorSystem {
    let input: RotorInput = serde_json::from_value(rotor).unwrap();
    RotorSystem::assemble(&Rotor::parse(&input, &Limits::default()).unwrap()).unwrap()
}

fn damping(model: &str) -> DampingModel {
    let j: DampingInput = serde_json::from_value(json!({ "model": model })).unwrap();
    DampingModel::parse(&j, None).unwrap()
}

/// The largest radial amplitude and its time.
fn peak(r: &TimeResult) -> (f64, f64) {
    r.nodes[0]
        .1
        .iter()
        .zip(&r.time)
        .map(|(z, t)| (z.norm(), *t))
        .fold((0.0, 0.0), |m, v| if v.0 > m.0 { v } else { m })
}

/// The run-up of `system` from rest to 1.7 times its first natural frequency at 5000 rad/s^2
/// with 1e-4 kg m at `node`, at tolerance 1e-6: the spec and its top speed.
fn run_up(full: &DampedModel, node: usize) -> (TimeSpec, f64) {
    let top = 1.7 * full.natural_frequencies[0];
    let duration = top / 5000.0;
    let speed = SpeedLaw::Profile(
        Pwl::parse(
            &[[0.0, 0.0], [duration, top]],
            "p",
            true,
            &mut Invalid::default(),
        )
        .unwrap(),
    );
    let spec = TimeSpec {
        speed,
        forces: vec![],
        unbalances: vec![Unbalance {
            node,
            amount: 1e-4,
            phase: 0.0,
            from: 0.0,
        }],
        duration,
        output_interval: 1e-4,
        nodes: vec![node],
        tolerance: 1e-6,
        max_steps: 20_000_000,
        reduce: true,
        generated: Default::default(),
    };
    (spec, top)
}

/// Where the full model's response to `name`'s run-up under `model` is kept.
fn reference_path(name: &str, model: &str) -> String {
    format!(
        "{}/tests/data/runup/{}-{model}.json",
        env!("CARGO_MANIFEST_DIR"),
        name.replace(' ', "-")
    )
}

/// The full model's response to `spec` (at its tolerance, 1e-8), as kept: the file's request
/// must be `spec`'s (top speed, duration, node, tolerance, sampling), to round-off.
fn reference(name: &str, model: &str, spec: &TimeSpec, top: f64) -> TimeResult {
    let path = reference_path(name, model);
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("{path}: {e} (make_runup_references writes it)"));
    let v: Value = serde_json::from_str(&text).unwrap();
    let num = |k: &str| v[k].as_f64().unwrap();
    let same = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs().max(1e-300);
    assert!(
        same(num("top_speed"), top)
            && same(num("duration"), spec.duration)
            && same(num("tolerance"), spec.tolerance)
            && same(num("output_interval"), spec.output_interval)
            && v["node"] == json!(spec.nodes[0])
            && v["model"] == json!(model),
        "{path} answers another run-up: make_runup_references writes it again"
    );
    let floats = |k: &str| -> Vec<f64> {
        v[k].as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    };
    let (re, im) = (floats("x"), floats("y"));
    TimeResult {
        time: floats("time"),
        nodes: vec![(
            spec.nodes[0],
            re.iter().zip(&im).map(|(&a, &b)| c64::new(a, b)).collect(),
        )],
        method: whirl::analysis::time::Method::Implicit,
        steps: v["steps"].as_u64().unwrap() as usize,
        states: v["states"].as_u64().unwrap() as usize,
        train: None,
    }
}

/// The cases: a name, the rotor's bearing and the node of the unbalance.
fn cases() -> [(&'static str, Value); 2] {
    [
        (
            "stiff heavy isotropic",
            json!({"stiffness": 1e8, "damping": 5e4}),
        ),
        (
            "soft light anisotropic",
            json!({"kxx": 4e6, "kxy": 8e5, "kyx": -1.2e6, "kyy": 7e6,
                   "cxx": 300.0, "cxy": 40.0, "cyx": -25.0, "cyy": 500.0,
                   "loss_factor": 0.01}),
        ),
    ]
}

/// Writes the full model's responses of [`cases`] at tolerance 1e-8 (minutes).
#[test]
#[ignore = "writes tests/data/runup/ (minutes of full-model integration)"]
fn make_runup_references() {
    for (name, bearing) in cases() {
        let system = system(rotor(12, bearing, 0.002));
        for model in ["viscous", "nonviscous"] {
            let damping = damping(model);
            let full = DampedModel::build(&system, &damping).unwrap();
            let (spec, top) = run_up(&full, 6);
            let tight = TimeSpec {
                tolerance: 1e-8,
                reduce: false,
                generated: Default::default(),
                ..spec
            };
            let f = time_response(&system, &full, &tight, true, &Control::default()).unwrap();
            let z = &f.nodes[0].1;
            let v = json!({
                "what": format!("{name} run-up, {model}: the full model's response at node 6, \
                                 TR-BDF2 at tolerance 1e-8 (tests/it/runup_reduction.rs)"),
                "model": model, "node": 6, "top_speed": top, "duration": tight.duration,
                "tolerance": tight.tolerance, "output_interval": tight.output_interval,
                "steps": f.steps, "states": f.states,
                "time": f.time, "x": z.iter().map(|c| c.re).collect::<Vec<_>>(),
                "y": z.iter().map(|c| c.im).collect::<Vec<_>>(),
            });
            let path = reference_path(name, model);
            std::fs::create_dir_all(std::path::Path::new(&path).parent().unwrap()).unwrap();
            std::fs::write(&path, serde_json::to_string(&v).unwrap()).unwrap();
            println!("{path}: {} samples, {} steps", f.time.len(), f.steps);
        }
    }
}

/// Runs the run-up of `system` ([`run_up`]) reduced (default tolerance 1e-6, and 1e-8) against
/// the full model's kept response (1e-8): the peak and its time at the default tolerance, the
/// whole response at the reference's.
fn compare(name: &str, system: &RotorSystem, model: &str, node: usize) {
    let damping = damping(model);
    let full = DampedModel::build(system, &damping).unwrap();
    let (spec, top) = run_up(&full, node);
    let control = Control::default();
    let (r, info) = reduced::solve(system, &damping, &full, &spec, true, &control).unwrap();
    let info = info.unwrap_or_else(|| panic!("{name} {model}: no reduction"));
    assert!(2 * info.states <= info.full_states, "{name}: {info:?}");
    // The reduction's own error, apart from the integrator's: the reduced model at the
    // reference's tolerance.
    let tight = TimeSpec {
        tolerance: 1e-8,
        ..spec.clone()
    };
    let (rt, _) = reduced::solve(system, &damping, &full, &tight, true, &control).unwrap();
    let f = reference(name, model, &tight, top);
    let (p, tp) = peak(&r);
    let (pf, tpf) = peak(&f);
    let deviation = |r: &TimeResult| {
        r.nodes[0]
            .1
            .iter()
            .zip(&f.nodes[0].1)
            .map(|(a, b)| (a - b).norm())
            .fold(0.0, f64::max)
            / pf
    };
    let (dev, dev_tight) = (deviation(&r), deviation(&rt));
    println!(
        "{name} {model}: {} of {} states ({} modes), {} steps against {}; peak {p:.6e} at {tp:.4} s, \
         full {pf:.6e} at {tpf:.4} s: peak {:.1e}; largest deviation {dev:.1e} of the peak \
         (tolerance 1e-6), {dev_tight:.1e} (1e-8)",
        info.states,
        info.full_states,
        info.modes,
        r.steps,
        f.steps,
        (p - pf).abs() / pf
    );
    assert!(
        (p - pf).abs() <= 1e-3 * pf,
        "{name} {model}: peak {p} against {pf}"
    );
    assert!(
        (tp - tpf).abs() <= 1e-3,
        "{name} {model}: peak at {tp} against {tpf}"
    );
    assert!(
        dev_tight <= 1e-3,
        "{name} {model}: deviation {dev_tight:.2e} of the peak"
    );
    // The viscous model reduces without its dense full model (Lanczos modes, the check through
    // sparse factors): the same reduction, so the same response to round-off of the basis.
    if model == "viscous" {
        let sparse = reduced::solve_sparse(system, &damping, &spec, true, false, &control).unwrap();
        if info.full_states < whirl::analysis::large::SPARSE_FROM_STATES {
            assert!(sparse.is_none(), "{name}: {info:?}");
            return;
        }
        let (rs, si) = sparse.unwrap_or_else(|| panic!("{name}: no sparse reduction"));
        assert!(
            si.sparse && si.modes == info.modes && si.states == info.states,
            "{si:?}"
        );
        let (rst, _) = reduced::solve_sparse(system, &damping, &tight, true, false, &control)
            .unwrap()
            .unwrap();
        let apart = rs.nodes[0]
            .1
            .iter()
            .zip(&r.nodes[0].1)
            .map(|(a, b)| (a - b).norm())
            .fold(0.0, f64::max)
            / pf;
        let (ds, ds_tight) = (deviation(&rs), deviation(&rst));
        println!(
            "{name} {model}, sparse: check {:.1e}; {ds:.1e} / {ds_tight:.1e} of the peak from the \
             full model, {apart:.1e} from the dense reduction",
            si.max_relative_error
        );
        assert!(
            apart <= 1e-9,
            "{name}: sparse and dense reductions {apart:.2e} apart"
        );
        assert!(ds_tight <= 1e-3, "{name}: sparse deviation {ds_tight:.2e}");
    }
}

#[test]
fn reduced_run_ups_match_the_full_model_on_stiff_heavily_damped_isotropic_bearings() {
    let (name, bearing) = cases()[0].clone();
    let s = system(rotor(12, bearing, 0.002));
    for model in ["viscous", "nonviscous"] {
        compare(name, &s, model, 6);
    }
}

#[test]
fn reduced_run_ups_match_the_full_model_on_soft_lightly_damped_anisotropic_bearings() {
    let (name, bearing) = cases()[1].clone();
    let s = system(rotor(12, bearing, 0.002));
    for model in ["viscous", "nonviscous"] {
        compare(name, &s, model, 6);
    }
}
