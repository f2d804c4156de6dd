//! The exponential integrator (`analysis::time::exponential`) against what we trust: the
//! closed-form modal solution at constant speed, and TR-BDF2 at a tight tolerance along speed
//! profiles, on the full models of small rotors: Example 1 under the paper's nonviscous
//! model (internal poles at -3e4 1/s), and a shaft on fluid-film bearings tabulated against
//! speed (anisotropic and cross-coupled: doubled coordinates; the run-up crosses the table's
//! speeds), with a blade loss and a shock in the same run.

use crate::common;

use common::paper_nvd;
use serde_json::Value;
use whirl::analysis::control::Control;
use whirl::analysis::time::{
    Coordinates, Method, SpeedLaw, TimeResult, TimeSpec, solve_exponential, solve_in,
};
use whirl::damping::DampedModel;
use whirl::model::api::RotorInput;
use whirl::model::damping::DampingModel;
use whirl::model::error::Invalid;
use whirl::model::loads::{Force, Pwl, Unbalance};
use whirl::model::rotor::{Limits, Rotor};
use whirl::system::RotorSystem;

fn example(name: &str) -> Value {
    let path = format!("{}/examples/{name}", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn system(rotor: Value) -> RotorSystem {
    let input: RotorInput = serde_json::from_value(rotor).unwrap();
    RotorSystem::assemble(&Rotor::parse(&input, &Limits::default()).unwrap()).unwrap()
}

fn pwl(points: &[[f64; 2]]) -> Pwl {
    Pwl::parse(points, "p", true, &mut Invalid::default()).unwrap()
}

/// The exponential integrator at the default tolerance against itself at 1e-10 and TR-BDF2
/// at `tight`, on the full model: the largest differences over the whole response, relative
/// to its peak.
fn against_references(
    s: &RotorSystem,
    model: &DampingModel,
    spec: &TimeSpec,
    tight: f64,
) -> (f64, f64, TimeResult) {
    let m = DampedModel::build(s, model).unwrap();
    let c = own(s);
    let control = Control::default();
    let e = solve_exponential(&c, &m, spec, &control).unwrap();
    assert_eq!(e.method, Method::Exponential);
    let at = |tolerance: f64| TimeSpec {
        tolerance,
        ..spec.clone()
    };
    let fine = solve_exponential(&c, &m, &at(1e-10), &control).unwrap();
    let implicit = solve_in(&c, &m, &at(tight), true, &control).unwrap();
    assert_eq!(implicit.method, Method::Implicit);
    (deviation(&e, &fine), deviation(&fine, &implicit), e)
}

/// The rotor's own coordinates (no reduction).
fn own(s: &RotorSystem) -> Coordinates<'_> {
    Coordinates {
        physical: s,
        solved: s,
        basis: None,
        slow: None,
    }
}

fn deviation(a: &TimeResult, b: &TimeResult) -> f64 {
    let (mut dev, mut peak) = (0.0f64, 0.0f64);
    for ((_, x), (_, y)) in a.nodes.iter().zip(&b.nodes) {
        assert_eq!(x.len(), y.len());
        for (p, q) in x.iter().zip(y) {
            dev = dev.max((p - q).norm());
            peak = peak.max(q.norm());
        }
    }
    dev / peak
}

fn unbalance(node: usize, amount: f64, from: f64) -> Unbalance {
    Unbalance {
        node,
        amount,
        phase: 0.3,
        from,
    }
}

fn spec(speed: SpeedLaw, unbalances: Vec<Unbalance>, forces: Vec<Force>, t: f64) -> TimeSpec {
    TimeSpec {
        speed,
        forces,
        unbalances,
        duration: t,
        output_interval: 1e-3,
        nodes: vec![1, 2],
        tolerance: 1e-6,
        max_steps: 5_000_000,
        reduce: false,
        generated: Default::default(),
    }
}

#[test]
fn at_constant_speed_it_is_the_closed_form() {
    let s = system(example("example1-nvd.modal.json")["rotor"].clone());
    let m = DampedModel::build(&s, &paper_nvd()).unwrap();
    let c = own(&s);
    let shock = Force {
        node: 1,
        direction: 0.5,
        history: pwl(&[[0.0, 0.0], [0.01, 100.0], [0.02, 0.0]]),
    };
    let sp = spec(
        SpeedLaw::Constant(800.0),
        vec![unbalance(2, 1e-3, 0.0), unbalance(1, 2e-3, 0.0305)],
        vec![shock],
        0.2,
    );
    let control = Control::default();
    let exact = solve_in(&c, &m, &sp, false, &control).unwrap();
    assert_eq!(exact.method, Method::Exact);
    // The exponential integrator itself (solve_exponential would see a constant speed only
    // through its stages; it is called on any speed law).
    // Fourth order: the error follows the tolerance, which bounds it on the peak.
    for tolerance in [1e-6, 1e-9] {
        let e = solve_exponential(
            &c,
            &m,
            &TimeSpec {
                tolerance,
                ..sp.clone()
            },
            &control,
        )
        .unwrap();
        assert_eq!(e.method, Method::Exponential);
        let dev = deviation(&e, &exact);
        eprintln!(
            "constant speed, tolerance {tolerance:e}: {} states, {} steps, {dev:.1e} of the peak \
             from the closed form",
            e.states, e.steps
        );
        assert!(dev < 2.0 * tolerance, "{dev:e}");
    }
}

#[test]
fn a_nonviscous_run_up_through_resonance_matches_tr_bdf2() {
    let s = system(example("example1-nvd.modal.json")["rotor"].clone());
    let law = SpeedLaw::Profile(pwl(&[[0.0, 250.0], [0.5, 250.0], [1.5, 450.0]]));
    let sp = spec(law, vec![unbalance(1, 1e-4, 0.0)], vec![], 1.5);
    let (dev, implicit, e) = against_references(&s, &paper_nvd(), &sp, 1e-9);
    eprintln!(
        "Example 1 nonviscous run-up: {} states, {} steps, {dev:.1e} of the peak from itself at \
         1e-10, which is {implicit:.1e} from TR-BDF2 at 1e-9",
        e.states, e.steps
    );
    assert!(dev < 2e-6, "{dev:e}");
    assert!(implicit < 1e-4, "{implicit:e}");
}

#[test]
fn a_run_up_on_tabulated_fluid_film_bearings_with_a_blade_loss_and_a_shock_matches_tr_bdf2() {
    let s = system(example("fluid-film.unbalance-response.json")["rotor"].clone());
    // 100 -> 1800 rad/s in 0.3 s: across the table's 200, 600, 1000 and 1500 rad/s.
    let law = SpeedLaw::Profile(pwl(&[[0.0, 100.0], [0.3, 1800.0], [0.4, 1800.0]]));
    let shock = Force {
        node: 5,
        direction: 1.0,
        history: pwl(&[[0.0, 0.0], [0.1, 0.0], [0.1005, 500.0], [0.101, 0.0]]),
    };
    let sp = TimeSpec {
        nodes: vec![0, 5, 10],
        ..spec(
            law,
            vec![unbalance(5, 1e-4, 0.0), unbalance(5, 2e-3, 0.25)],
            vec![shock],
            0.4,
        )
    };
    let (dev, implicit, e) = against_references(&s, &DampingModel::Viscous, &sp, 1e-8);
    eprintln!(
        "fluid film run-up: {} states, {} steps, {dev:.1e} of the peak from itself at 1e-10, \
         which is {implicit:.1e} from TR-BDF2 at 1e-8",
        e.states, e.steps
    );
    assert!(dev < 2e-6, "{dev:e}");
    assert!(implicit < 1e-4, "{implicit:e}");
}

#[test]
fn a_run_up_on_bearings_read_with_rosss_interpolation_matches_tr_bdf2() {
    // The same bearings on ROSS's splines (extrapolated below 200 rad/s): the supports'
    // change over a stage is the schedule's (damping/schedule.rs), in the stage's modal basis
    // for the exponential integrator, on the state matrix for TR-BDF2.
    let mut rotor = example("fluid-film.unbalance-response.json")["rotor"].clone();
    for s in rotor["supports"].as_array_mut().unwrap() {
        s["interpolation"] = serde_json::json!("ross");
    }
    let s = system(rotor);
    let law = SpeedLaw::Profile(pwl(&[[0.0, 100.0], [0.3, 1800.0], [0.4, 1800.0]]));
    let sp = TimeSpec {
        nodes: vec![0, 5, 10],
        ..spec(law, vec![unbalance(5, 1e-4, 0.0)], vec![], 0.4)
    };
    let (dev, implicit, e) = against_references(&s, &DampingModel::Viscous, &sp, 1e-8);
    eprintln!(
        "fluid film run-up, ROSS's interpolation: {} states, {} steps, {dev:.1e} of the peak \
         from itself at 1e-10, which is {implicit:.1e} from TR-BDF2 at 1e-8",
        e.states, e.steps
    );
    assert!(dev < 2e-6, "{dev:e}");
    assert!(implicit < 1e-4, "{implicit:e}");
}

#[test]
fn coarse_output_intervals_give_the_same_samples() {
    // 0 -> 450 rad/s in 0.4 s, sampled every 1 ms and every 0.1 s: the stages cut the long
    // intervals as they cut the speed, so the common samples agree to the tolerance.
    let s = system(example("example1-nvd.modal.json")["rotor"].clone());
    let m = DampedModel::build(&s, &paper_nvd()).unwrap();
    let c = own(&s);
    let law = SpeedLaw::Profile(pwl(&[[0.0, 0.0], [0.4, 450.0]]));
    let fine = spec(law, vec![unbalance(1, 1e-4, 0.0)], vec![], 0.4);
    let coarse = TimeSpec {
        output_interval: 0.1,
        ..fine.clone()
    };
    let control = Control::default();
    let a = solve_exponential(&c, &m, &fine, &control).unwrap();
    let b = solve_exponential(&c, &m, &coarse, &control).unwrap();
    assert_eq!(b.time.len(), 5);
    let peak = a.nodes[0].1.iter().map(|z| z.norm()).fold(0.0, f64::max);
    for (k, t) in b.time.iter().enumerate() {
        let i = (t / 1e-3).round() as usize;
        for node in 0..2 {
            let dev = (a.nodes[node].1[i] - b.nodes[node].1[k]).norm() / peak;
            assert!(dev < 2e-6, "t = {t}: {dev:e}");
        }
    }
}

#[test]
fn a_run_ends_with_the_loads_of_its_last_instant() {
    // 0 -> 600 rad/s in 0.02 s (Omega' = 30000 rad/s^2, the unbalance's -i a Omega' a twelfth
    // of a Omega^2 at the end): the last sample of a run that ends there against the same instant
    // inside a run whose speed law goes on. Taking the loads at the end from the right (where
    // the acceleration has ended) moved the last sample; both now agree to the tolerance.
    let s = system(example("example1-nvd.modal.json")["rotor"].clone());
    let m = DampedModel::build(&s, &paper_nvd()).unwrap();
    let c = own(&s);
    let ends = TimeSpec {
        output_interval: 0.002,
        ..spec(
            SpeedLaw::Profile(pwl(&[[0.0, 0.0], [0.02, 600.0]])),
            vec![unbalance(1, 1e-4, 0.0)],
            vec![],
            0.02,
        )
    };
    let goes_on = TimeSpec {
        speed: SpeedLaw::Profile(pwl(&[[0.0, 0.0], [0.04, 1200.0]])),
        duration: 0.04,
        ..ends.clone()
    };
    let control = Control::default();
    let a = solve_exponential(&c, &m, &ends, &control).unwrap();
    let b = solve_exponential(&c, &m, &goes_on, &control).unwrap();
    assert_eq!(a.time.len(), 11);
    let peak = a.nodes[0].1.iter().map(|z| z.norm()).fold(0.0, f64::max);
    for node in 0..2 {
        let dev = (a.nodes[node].1[10] - b.nodes[node].1[10]).norm() / peak;
        eprintln!(
            "node {node}: the end of a run vs the same instant inside one: {dev:.1e} of the peak"
        );
        assert!(dev < 2e-6, "node {node}: {dev:e}");
    }
}

#[test]
fn outputs_between_steps_are_fourth_order_like_the_steps() {
    // Sampled every 20 us at 800 rad/s, where a step may span 250 us at the default tolerance:
    // twelve outputs of thirteen come from the dense output, against the closed form.
    let s = system(example("example1-nvd.modal.json")["rotor"].clone());
    let m = DampedModel::build(&s, &paper_nvd()).unwrap();
    let c = own(&s);
    let sp = TimeSpec {
        output_interval: 2e-5,
        ..spec(
            SpeedLaw::Constant(800.0),
            vec![unbalance(2, 1e-3, 0.0), unbalance(1, 2e-3, 0.0305)],
            vec![],
            0.1,
        )
    };
    let control = Control::default();
    let exact = solve_in(&c, &m, &sp, false, &control).unwrap();
    assert_eq!(exact.method, Method::Exact);
    for tolerance in [1e-6, 1e-9] {
        let at = TimeSpec {
            tolerance,
            ..sp.clone()
        };
        let e = solve_exponential(&c, &m, &at, &control).unwrap();
        let dev = deviation(&e, &exact);
        eprintln!(
            "dense output, tolerance {tolerance:e}: {} steps for {} samples, {dev:.1e} of the peak",
            e.steps,
            e.time.len()
        );
        // 240 us steps at 1e-6, 40 us at 1e-9 (the step goes as the tolerance's fourth root).
        assert!(e.steps < e.time.len() / if tolerance > 1e-7 { 10 } else { 1 });
        assert!(dev < 2.0 * tolerance, "{dev:e}");
    }
    // Through resonance (0 -> 450 rad/s in 0.4 s), sampled every 50 us: against the same run
    // at tolerance 1e-10.
    let law = SpeedLaw::Profile(pwl(&[[0.0, 0.0], [0.4, 450.0]]));
    let run = TimeSpec {
        output_interval: 5e-5,
        ..spec(law, vec![unbalance(1, 1e-4, 0.0)], vec![], 0.4)
    };
    let e = solve_exponential(&c, &m, &run, &control).unwrap();
    let fine = TimeSpec {
        tolerance: 1e-10,
        ..run.clone()
    };
    let f = solve_exponential(&c, &m, &fine, &control).unwrap();
    let dev = deviation(&e, &f);
    eprintln!(
        "run-up: {} steps for {} samples, {dev:.1e} of the peak",
        e.steps,
        e.time.len()
    );
    assert!(e.steps * 3 < e.time.len(), "{} steps", e.steps);
    assert!(dev < 2e-6, "{dev:e}");
}
