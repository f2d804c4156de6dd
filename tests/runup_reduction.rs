//! Run-ups on the checked modal reduction against the full model integrated at a tight
//! tolerance, on rotors built here for nothing in particular: stiff heavily damped and soft
//! lightly damped bearings, isotropic and cross-coupled anisotropic, with material loss
//! (so that the nonviscous model has rotating branches) and without.

mod common;

use common::stepped_rotor as rotor;
use serde_json::{Value, json};
use whirl::analysis::control::Control;
use whirl::analysis::time::{SpeedLaw, TimeResult, TimeSpec, reduced, time_response};
use whirl::damping::DampedModel;
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

/// Runs `system` up from rest to 1.7 times its first natural frequency at 5000 rad/s^2 with
/// 1e-4 kg m at `node`, reduced (default tolerance 1e-6, and 1e-8) and full (1e-8): the peak
/// and its time at the default tolerance, the whole response at the reference's.
fn compare(name: &str, system: &RotorSystem, model: &str, node: usize) {
    let damping = damping(model);
    let full = DampedModel::build(system, &damping).unwrap();
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
    };
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
    let f = time_response(
        system,
        &full,
        &TimeSpec {
            reduce: false,
            ..tight.clone()
        },
        true,
        &control,
    )
    .unwrap();
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
    let bearing = json!({"stiffness": 1e8, "damping": 5e4});
    let s = system(rotor(12, bearing, 0.002));
    for model in ["viscous", "nonviscous"] {
        compare("stiff heavy isotropic", &s, model, 6);
    }
}

#[test]
fn reduced_run_ups_match_the_full_model_on_soft_lightly_damped_anisotropic_bearings() {
    let bearing = json!({"kxx": 4e6, "kxy": 8e5, "kyx": -1.2e6, "kyy": 7e6,
                         "cxx": 300.0, "cxy": 40.0, "cyx": -25.0, "cyy": 500.0,
                         "loss_factor": 0.01});
    let s = system(rotor(12, bearing, 0.002));
    for model in ["viscous", "nonviscous"] {
        compare("soft light anisotropic", &s, model, 6);
    }
}
