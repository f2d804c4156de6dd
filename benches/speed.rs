//! Benchmarks (`cargo bench`): wall time of the workloads the service is judged on, on this
//! machine, with the size of every eigenproblem. Not a test: it asserts nothing, it measures.
//!
//! (a) the 100-element compressor, 100 speeds, branches below 6000 rad/s;
//! (b) Example 1 with nonviscous damping, 400 speeds;
//! (c) 1 s of time response of the compressor at constant speed, and during a run-up (`runup`);
//! (d) one modal solve of the compressor;
//! (e) the cost of doubled coordinates: the compressor on its isotropic bearings, on the same
//!     bearings in the general form (still isotropic: solved in `n` dof), and on anisotropic,
//!     cross-coupled ones (`(r, conj r)`: `2n` dof).

use std::time::{Duration, Instant};

use serde_json::Value;
use whirl::analysis::campbell::{CampbellResult, Keep, campbell, campbell_below};
use whirl::analysis::control::Control;
use whirl::analysis::poles::poles_at;
use whirl::analysis::time::{SpeedLaw, TimeSpec, reduced, time_response};
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

/// The compressor example's rotor, Guyan-reduced to its translations as in the example or not.
fn compressor(guyan: bool) -> RotorSystem {
    compressor_on(guyan, |s| s)
}

/// The compressor with each support rewritten by `support`.
fn compressor_on(guyan: bool, support: impl Fn(Value) -> Value) -> RotorSystem {
    let mut v = example("compressor-nvd.campbell.json")["rotor"].clone();
    if !guyan {
        v.as_object_mut().unwrap().remove("reduction");
    }
    let supports: Vec<Value> = v["supports"].as_array().unwrap().clone();
    v["supports"] = Value::Array(supports.into_iter().map(support).collect());
    let rotor: RotorInput = serde_json::from_value(v).unwrap();
    RotorSystem::assemble(&Rotor::parse(&rotor, &Limits::default()).unwrap()).unwrap()
}

/// An isotropic support `{node, stiffness, damping, loss_factor}` in the general form,
/// scaled in y by `ky` and `cy` and cross-coupled by `q` (kxy = q k, kyx = -q k / 2).
fn general(s: Value, ky: f64, cy: f64, q: f64) -> Value {
    let (k, c) = (
        s["stiffness"].as_f64().unwrap(),
        s["damping"].as_f64().unwrap_or(0.0),
    );
    serde_json::json!({
        "node": s["node"], "loss_factor": s["loss_factor"].as_f64().unwrap_or(0.0),
        "kxx": k, "kyy": ky * k, "kxy": q * k, "kyx": -0.5 * q * k,
        "cxx": c, "cyy": cy * c,
    })
}

fn load(name: &str) -> (RotorSystem, DampingModel) {
    let v = example(name);
    let rotor: RotorInput = serde_json::from_value(v["rotor"].clone()).unwrap();
    let rotor = Rotor::parse(&rotor, &Limits::default()).unwrap();
    let damping: DampingInput = serde_json::from_value(v["damping"].clone()).unwrap();
    let damping = DampingModel::parse(&damping, Some(rotor.dof_count())).unwrap();
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

/// Best of 3 bounded Campbell sweeps (branches below 6000 rad/s), model build included: the
/// time, the full model's states and the last result.
fn bounded_sweep(
    system: &RotorSystem,
    model: &DampingModel,
    speeds: &[f64],
    reduce: bool,
) -> (Duration, usize, CampbellResult) {
    let mut out = None;
    let t = best(3, || {
        let full = DampedModel::build(system, model).unwrap();
        let c = campbell_below(
            system,
            model,
            &full,
            speeds,
            Keep {
                below: 6000.0,
                lowest: None,
            },
            reduce,
            &Control::default(),
        )
        .unwrap();
        out = Some((full.states(), c));
    });
    let (states, c) = out.unwrap();
    (t, states, c)
}

/// One dense complex eigendecomposition (values and vectors) of the matrix in `path`
/// (`{"re": [[..]], "im": [[..]]}`, as `/v1/damping` returns it), single-threaded.
fn eigen_of_file(path: &str) {
    let v: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let rows = |k: &str| -> Vec<Vec<f64>> { serde_json::from_value(v[k].clone()).unwrap() };
    let (re, im) = (rows("re"), rows("im"));
    let n = re.len();
    let a = linalg::CMat::from_fn(n, n, |i, j| linalg::c64::new(re[i][j], im[i][j]));
    let t = best(7, || {
        linalg::eigen(&a).unwrap();
    });
    println!(
        "eigen: {:.2} ms for one {n} x {n} complex eigendecomposition (values and vectors, balanced, 1 thread)",
        t.as_secs_f64() * 1e3
    );
}

fn main() {
    linalg::set_sequential();
    let args: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| a != "--bench")
        .collect();
    if let Some(i) = args.iter().position(|a| a == "--matrix") {
        eigen_of_file(&args[i + 1]);
        return;
    }
    // Sections to run: `cargo bench --bench speed -- a c` runs (a) and (c); none: all.
    let wanted = |k: &str| args.is_empty() || args.iter().any(|a| a == k);
    let threads = rayon::current_num_threads();
    println!("whirl benchmarks: {threads} threads for sweeps, faer sequential per problem\n");

    // (a) Compressor Campbell, 100 speeds, branches below 6000 rad/s: the example (Guyan
    // reduced to the translations) and the same rotor unreduced (as ROSS models it).
    if wanted("a") {
        let speeds: Vec<f64> = (0..100).map(|i| i as f64 * 1500.0 / 99.0).collect();
        for guyan in [true, false] {
            let system = compressor(guyan);
            for (name, model, reduce) in [
                ("viscous, full model", DampingModel::Viscous, false),
                ("viscous", DampingModel::Viscous, true),
                (
                    "equivalent, 8 modes",
                    DampingModel::Equivalent { modes: Some(8) },
                    true,
                ),
                (
                    "nonviscous, 8 modes",
                    load("compressor-nvd.campbell.json").1,
                    true,
                ),
                ("hysteretic", DampingModel::Hysteretic, true),
            ] {
                if !guyan && !reduce {
                    continue; // 100 eigenproblems of 404 states: tens of seconds, shown by (d)
                }
                let (t, full_states, c) = bounded_sweep(&system, &model, &speeds, reduce);
                let problems = if matches!(model, DampingModel::Hysteretic) {
                    4
                } else {
                    1
                };
                let size = match &c.reduction {
                    Some(r) => format!(
                        "{} states ({} modes to {:.0} rad/s + {} static corrections, full {}; \
                         checked at {} rad/s: {:.1e})",
                        r.states,
                        r.modes,
                        r.band,
                        r.vectors - r.modes,
                        r.full_states,
                        r.checked_speed,
                        r.max_relative_error
                    ),
                    None => format!("{full_states} states"),
                };
                println!(
                    "(a) compressor ({} dof) Campbell, {name}: {:.3} s for 100 speeds, {:.2} ms per speed, \
                     {problems} eigenproblem(s) of {size}, {} branches",
                    system.n(),
                    t.as_secs_f64(),
                    t.as_secs_f64() * 10.0,
                    c.branches.len()
                );
            }
        }
    }

    // (b) Example 1, NVD, 400 speeds.
    if wanted("b") {
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
    }

    // (c) Compressor, 1 s of time response (unbalance at mid-span, output every 0.1 ms), at
    // constant speed (exact) and during a run-up (on the checked reduction; `runup` runs it).
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
        reduce: false,
        generated: Default::default(),
    };
    if wanted("c") {
        for guyan in [true, false] {
            let system = compressor(guyan);
            let m = DampedModel::build(&system, &DampingModel::Viscous).unwrap();
            let constant = spec(SpeedLaw::Constant(1000.0));
            let t = best(3, || {
                time_response(&system, &m, &constant, false, &Control::default()).unwrap();
            });
            println!(
                "(c) compressor ({} dof) time response, constant speed, 1 s, 10001 samples, 3 nodes: \
                 {:.3} s (exact: one eigenproblem of {} states)",
                system.n(),
                t.as_secs_f64(),
                m.states()
            );
        }
    }
    if std::env::args().any(|a| a == "runup") {
        // The compressor unreduced (202 dof), 0 to 1500 rad/s in 1 s through both of its
        // first critical speeds, on the checked modal reduction and on the full model.
        let system = compressor(false);
        let profile = Pwl::parse(
            &[[0.0, 0.0], [1.0, 1500.0]],
            "p",
            false,
            &mut Invalid::default(),
        )
        .unwrap();
        let run_up = TimeSpec {
            reduce: true,
            ..spec(SpeedLaw::Profile(profile))
        };
        for name in ["viscous", "equivalent", "nonviscous"] {
            let input: DampingInput =
                serde_json::from_value(serde_json::json!({"model": name})).unwrap();
            let model = DampingModel::parse(&input, Some(system.n())).unwrap();
            let mut out = None;
            let t = best(3, || {
                let m = DampedModel::build(&system, &model).unwrap();
                out = Some(
                    reduced::solve(&system, &model, &m, &run_up, true, &Control::default())
                        .unwrap(),
                );
            });
            let (r, info) = out.unwrap();
            let info = info.map_or("none".into(), |i| {
                format!(
                    "{} of {} states, {} modes, checked {:.1e}",
                    i.states, i.full_states, i.modes, i.max_relative_error
                )
            });
            println!(
                "(c) compressor ({} dof) run-up 0 to 1500 rad/s in 1 s, {name}: {:.3} s ({} {:?} steps; reduction: {info})",
                system.n(),
                t.as_secs_f64(),
                r.steps,
                r.method,
            );
        }
    }

    // (d) One modal solve of the compressor (all poles, values and vectors).
    if wanted("d") {
        for guyan in [true, false] {
            let system = compressor(guyan);
            let m = DampedModel::build(&system, &DampingModel::Viscous).unwrap();
            let t = best(5, || {
                poles_at(&m, 1000.0).unwrap();
            });
            println!(
                "(d) compressor ({} dof) modal solve: {:.4} s ({} states, eigenvalues and vectors, balanced)",
                system.n(),
                t.as_secs_f64(),
                m.states()
            );
        }
    }

    // (e) Doubled coordinates: what anisotropy costs. The compressor (Guyan), 100 speeds,
    // branches below 6000 rad/s, and one modal solve.
    if wanted("e") {
        let speeds: Vec<f64> = (0..100).map(|i| i as f64 * 1500.0 / 99.0).collect();
        let cases: [(&str, RotorSystem); 3] = [
            ("isotropic", compressor(true)),
            (
                "general form, isotropic",
                compressor_on(true, |s| general(s, 1.0, 1.0, 0.0)),
            ),
            (
                "anisotropic, cross-coupled",
                compressor_on(true, |s| general(s, 1.5, 1.3, 0.2)),
            ),
        ];
        for (name, system) in &cases {
            for (model_name, model, reduce) in [
                ("viscous, full model", DampingModel::Viscous, false),
                ("viscous", DampingModel::Viscous, true),
                ("hysteretic", DampingModel::Hysteretic, true),
            ] {
                let (t, states, c) = bounded_sweep(system, &model, &speeds, reduce);
                let reduced_states = c.reduction.map(|r| r.states);
                println!(
                    "(e) compressor on {name} supports, Campbell {model_name}: {:.3} s for 100 speeds \
                     ({states} states, reduced to {reduced_states:?})",
                    t.as_secs_f64()
                );
            }
            let m = DampedModel::build(system, &DampingModel::Viscous).unwrap();
            let t = best(5, || {
                poles_at(&m, 1000.0).unwrap();
            });
            println!(
                "(e) compressor on {name} supports, modal solve: {:.4} s ({} states)",
                t.as_secs_f64(),
                m.states()
            );
        }
    }
}
