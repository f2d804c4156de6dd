//! Benchmarks (`cargo bench`): wall time of the workloads the service is judged on, on this
//! machine, with the size of every eigenproblem. Not a test: it asserts nothing, it measures.
//!
//! (a) the 100-element compressor, 100 speeds, branches below 6000 rad/s;
//! (b) Example 1 with nonviscous damping, 400 speeds;
//! (c) 1 s of time response of the compressor at constant speed, and during a run-up;
//! (d) one modal solve of the compressor.

use std::time::{Duration, Instant};

use serde_json::Value;
use whirl::analysis::campbell::campbell;
use whirl::analysis::control::Control;
use whirl::analysis::poles::poles_at;
use whirl::analysis::time::{SpeedLaw, TimeSpec, time_response};
use whirl::damping::DampedModel;
use whirl::linalg;
use whirl::model::api::{DampingInput, RotorInput};
use whirl::model::damping::DampingModel;
use whirl::model::error::Invalid;
use whirl::model::loads::{Pwl, Unbalance};
use whirl::model::rotor::{Limits, Rotor};
use whirl::system::RotorSystem;

fn example(name: &str) -> Value {
    let path = format!("{}/examples/{name}", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn load(name: &str) -> (RotorSystem, DampingModel) {
    let v = example(name);
    let rotor: RotorInput = serde_json::from_value(v["rotor"].clone()).unwrap();
    let rotor = Rotor::parse(&rotor, &Limits::default()).unwrap();
    let damping: DampingInput = serde_json::from_value(v["damping"].clone()).unwrap();
    let damping = DampingModel::parse(&damping, rotor.dof_count()).unwrap();
    (RotorSystem::assemble(&rotor).unwrap(), damping)
}

/// Best of `runs` wall times.
fn best(runs: usize, mut f: impl FnMut()) -> Duration {
    (0..runs)
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed()
        })
        .min()
        .unwrap()
}

fn main() {
    linalg::set_sequential();
    let threads = rayon::current_num_threads();
    println!("whirl benchmarks: {threads} threads for sweeps, faer sequential per problem\n");

    // (a) Compressor Campbell, 100 speeds, viscous (bearing damping, like ROSS) and nonviscous.
    let (system, _) = load("compressor-nvd.campbell.json");
    let speeds: Vec<f64> = (0..100).map(|i| i as f64 * 1500.0 / 99.0).collect();
    for (name, model) in [
        ("viscous", DampingModel::Viscous),
        (
            "equivalent, 8 modes",
            DampingModel::Equivalent { modes: Some(8) },
        ),
        (
            "nonviscous, 8 modes",
            load("compressor-nvd.campbell.json").1,
        ),
        ("hysteretic", DampingModel::Hysteretic),
    ] {
        let m = DampedModel::build(&system, &model).unwrap();
        let t = best(3, || {
            let mut c = campbell(&m, &speeds, &Control::default()).unwrap();
            c.keep_below(6000.0);
        });
        let problems = if matches!(model, DampingModel::Hysteretic) {
            4
        } else {
            1
        };
        println!(
            "(a) compressor Campbell, {name}: {:.3} s for 100 speeds, {:.1} ms per speed, \
             {problems} eigenproblem(s) of {} states per speed",
            t.as_secs_f64(),
            t.as_secs_f64() * 10.0,
            m.states()
        );
    }

    // (b) Example 1, NVD, 400 speeds.
    let (system, model) = load("example1-nvd.campbell.json");
    let m = DampedModel::build(&system, &model).unwrap();
    let speeds: Vec<f64> = (0..400).map(|i| i as f64 * 4000.0 / 399.0).collect();
    let t = best(5, || {
        campbell(&m, &speeds, &Control::default()).unwrap();
    });
    println!(
        "(b) Example 1 NVD Campbell: {:.4} s for 400 speeds, {:.3} ms per speed, eigenproblem of {} states",
        t.as_secs_f64(),
        t.as_secs_f64() * 1e3 / 400.0,
        m.states()
    );

    // (c) Compressor, 1 s of time response (unbalance at mid-span, output every 0.1 ms).
    let (system, _) = load("compressor-nvd.campbell.json");
    let m = DampedModel::build(&system, &DampingModel::Viscous).unwrap();
    let unbalance = Unbalance {
        node: 45,
        amount: 1e-3,
        phase: 0.0,
        from: 0.0,
    };
    let spec = |speed: SpeedLaw| TimeSpec {
        speed,
        forces: vec![],
        unbalances: vec![unbalance.clone()],
        duration: 1.0,
        output_interval: 1e-4,
        nodes: vec![10, 45, 90],
        tolerance: 1e-6,
        max_steps: 5_000_000,
    };
    let constant = spec(SpeedLaw::Constant(1000.0));
    let t = best(3, || {
        time_response(&system, &m, &constant, false, &Control::default()).unwrap();
    });
    println!(
        "(c) compressor time response, constant speed, 1 s, 10001 samples, 3 nodes: {:.3} s (exact, {} states)",
        t.as_secs_f64(),
        m.states()
    );
    let profile = Pwl::parse(
        &[[0.0, 0.0], [1.0, 1500.0]],
        "p",
        false,
        &mut Invalid::default(),
    )
    .unwrap();
    let run_up = spec(SpeedLaw::Profile(profile));
    let t0 = Instant::now();
    let r = time_response(&system, &m, &run_up, false, &Control::default()).unwrap();
    println!(
        "(c) compressor time response, run-up 0 to 1500 rad/s in 1 s: {:.3} s ({} TR-BDF2 steps)",
        t0.elapsed().as_secs_f64(),
        r.steps
    );

    // (d) One modal solve of the compressor.
    let t = best(5, || {
        poles_at(&m, 1000.0).unwrap();
    });
    println!(
        "(d) compressor modal solve: {:.4} s ({} states, eigenvalues and vectors, balanced)",
        t.as_secs_f64(),
        m.states()
    );
}
