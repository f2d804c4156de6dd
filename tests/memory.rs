//! The memory estimate of every kind of task (`model::limits`) against the heap the analysis
//! really holds at its peak, measured with a counting allocator. The estimate must be an upper
//! bound (the budget relies on it) and not a wild one (it would refuse work for nothing).
//!
//! One test at a time in this binary (the second is ignored by default): the allocator counts
//! the whole process.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

use serde_json::{Value, json};
use whirl::analysis::control::Control;
use whirl::answer::execute;
use whirl::model::Limits;
use whirl::model::api::{
    DampingMatricesRequest, FrequencyResponseRequest, ModalRequest, SweepRequest,
    TimeResponseRequest, UnbalanceResponseRequest,
};
use whirl::model::task::Task;
use whirl::render::{Format, render};

struct Counting;

static CURRENT: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            let now = CURRENT.fetch_add(layout.size(), Ordering::Relaxed) + layout.size();
            PEAK.fetch_max(now, Ordering::Relaxed);
        }
        p
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) };
        CURRENT.fetch_sub(layout.size(), Ordering::Relaxed);
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if !p.is_null() {
            if new_size >= layout.size() {
                let now = CURRENT.fetch_add(new_size - layout.size(), Ordering::Relaxed)
                    + (new_size - layout.size());
                PEAK.fetch_max(now, Ordering::Relaxed);
            } else {
                CURRENT.fetch_sub(layout.size() - new_size, Ordering::Relaxed);
            }
        }
        p
    }
}

#[global_allocator]
static ALLOC: Counting = Counting;

fn example(name: &str) -> Value {
    let path = format!("{}/examples/{name}", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn unreduced(mut v: Value) -> Value {
    v["rotor"].as_object_mut().unwrap().remove("reduction");
    v
}

/// Peak heap above the start while `f` runs.
fn measure(f: impl FnOnce()) -> usize {
    let base = CURRENT.load(Ordering::SeqCst);
    PEAK.store(base, Ordering::SeqCst);
    f();
    PEAK.load(Ordering::SeqCst).saturating_sub(base)
}

fn parse(kind: &str, body: Value, limits: &Limits) -> Task {
    match kind {
        "modal" => serde_json::from_value::<ModalRequest>(body)
            .unwrap()
            .parse(limits),
        "campbell" => serde_json::from_value::<SweepRequest>(body)
            .unwrap()
            .parse_campbell(limits),
        "stability" => serde_json::from_value::<SweepRequest>(body)
            .unwrap()
            .parse_stability(limits),
        "damping" => serde_json::from_value::<DampingMatricesRequest>(body)
            .unwrap()
            .parse(limits),
        "time" => serde_json::from_value::<TimeResponseRequest>(body)
            .unwrap()
            .parse(limits),
        "unbalance" => serde_json::from_value::<UnbalanceResponseRequest>(body)
            .unwrap()
            .parse(limits),
        "frequency" => serde_json::from_value::<FrequencyResponseRequest>(body)
            .unwrap()
            .parse(limits),
        _ => unreachable!(),
    }
    .unwrap()
}

/// The service's pool, with faer's per-thread scratch allocated on every thread first (twice
/// the L3 cache, reserved and touched only as far as a product needs), so that what is
/// measured is the analysis's own heap.
fn warm_pool(limits: &Limits) -> rayon::ThreadPool {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(limits.threads)
        .build()
        .unwrap();
    let warm = || {
        let a = whirl::linalg::CMat::from_fn(64, 64, |i, j| {
            whirl::linalg::c64::new((i * 3 + j) as f64, (i + j * 5) as f64 % 7.0)
        });
        whirl::linalg::eigen(&a).unwrap();
    };
    warm();
    pool.broadcast(|_| warm());
    pool
}

/// Runs one case as the service would and returns (measured, estimated) peak bytes, after
/// asserting that the estimate bounds the measure and is not more than 8x it.
fn check(
    pool: &rayon::ThreadPool,
    limits: &Limits,
    name: &str,
    kind: &str,
    body: Value,
) -> (f64, f64) {
    let task = parse(kind, body, limits);
    let estimate = task.cost.peak_bytes as f64;
    let measured = measure(|| {
        pool.install(|| {
            let out = execute(&task, &Control::default(), limits.max_response_bytes).unwrap();
            let body = render(&out, &[Format::Json]).unwrap();
            assert!(!body.body.is_empty());
        })
    }) as f64;
    println!(
        "{name:<40} {:>12.2} {:>12.2} {:>7.2}",
        mb(measured),
        mb(estimate),
        estimate / measured
    );
    assert!(
        measured <= estimate,
        "{name}: measured {} MB above the estimate {} MB",
        mb(measured),
        mb(estimate)
    );
    assert!(
        estimate <= 8.0 * measured.max(1e6),
        "{name}: estimate {} MB is more than 8x the measured {} MB",
        mb(estimate),
        mb(measured)
    );
    (measured, estimate)
}

fn mb(x: f64) -> f64 {
    x / (1u64 << 20) as f64
}

#[test]
fn every_estimate_bounds_the_measured_peak_heap() {
    let limits = Limits::default();
    let pool = warm_pool(&limits);
    let compressor = example("compressor-nvd.campbell.json");
    let mut cases: Vec<(&str, &str, Value)> = vec![];
    let mut c = unreduced(compressor.clone());
    c["damping"] = json!({"model": "viscous"});
    c["speeds"] = json!({"start": 0, "stop": 1500, "count": 40});
    c["modal_reduction"] = json!(false);
    cases.push(("campbell, full compressor, viscous", "campbell", c.clone()));
    c["damping"] = json!({"model": "nonviscous", "modes": 8});
    cases.push(("campbell, Guyan compressor, NVD", "campbell", {
        let mut g = compressor.clone();
        g["speeds"] = json!({"start": 0, "stop": 1500, "count": 40});
        g["modal_reduction"] = json!(false);
        g
    }));
    cases.push(("campbell, reduced below 6000 rad/s", "campbell", {
        let mut g = unreduced(compressor.clone());
        g["damping"] = json!({"model": "viscous"});
        g
    }));
    let mut h = example("compressor-hysteretic.campbell.json");
    h["speeds"] = json!({"start": 0, "stop": 3000, "count": 24});
    h.as_object_mut().unwrap().remove("max_frequency");
    cases.push(("stability, compressor, hysteretic", "stability", h));
    cases.push((
        "modal, compressor NVD",
        "modal",
        example("compressor-nvd.modal.json"),
    ));
    cases.push((
        "modal, full compressor viscous",
        "modal",
        json!({"rotor": unreduced(compressor.clone())["rotor"], "damping": {"model": "viscous"}, "speed": 500}),
    ));
    cases.push((
        "time, blade loss (exact)",
        "time",
        example("compressor-bladeloss-nvd.time-response.json"),
    ));
    let mut run_up = example("example1-runup-nvd.time-response.json");
    run_up["duration"] = json!(0.3);
    cases.push(("time, run-up (implicit)", "time", run_up));
    cases.push((
        "unbalance, compressor, 300 speeds",
        "unbalance",
        json!({"rotor": compressor["rotor"], "damping": {"model": "nonviscous", "modes": 8},
               "speeds": {"start": 10, "stop": 2000, "count": 300},
               "unbalances": [{"node": 45, "amount": 1e-3}]}),
    ));
    cases.push((
        "damping, compressor NVD, state form",
        "damping",
        json!({"rotor": compressor["rotor"], "damping": {"model": "nonviscous", "modes": 8}, "form": "state"}),
    ));
    // A large rotor held sparse (`analysis::large`): 800 elements on cross-coupled bearings,
    // 6408 states, bounded.
    let steel_plain =
        json!({"steel": {"young_modulus": 2.11e11, "density": 7810.0, "poisson_ratio": 0.3}});
    let bearing = |node: usize| json!({"node": node, "kxx": 2.0e7, "kyy": 1.4e7, "kxy": 4.0e6, "kyx": -4.0e6, "cxx": 3.0e3, "cyy": 2.0e3});
    cases.push((
        "campbell, 800 elements held sparse",
        "campbell",
        json!({"rotor": {"type": "beam", "materials": steel_plain,
                 "shaft": [{"length": 1.2, "outer_diameter": 0.08, "material": "steel", "elements": 800}],
                 "disks": [{"node": 400, "mass": 20.0, "polar_inertia": 0.3, "transverse_inertia": 0.16}],
                 "supports": [bearing(0), bearing(800)]},
               "damping": {"model": "viscous"}, "max_frequency": 6000.0,
               "speeds": {"start": 0, "stop": 2000, "count": 20}}),
    ));
    // The nonviscous model of that rotor (lossy steel) held sparse: its dampers on the modes
    // up to 16 times the bound, a column of the rotor's size each and a solve per damper in
    // each factor.
    let steel_lossy = json!({"steel": {"young_modulus": 2.11e11, "density": 7810.0,
                                       "poisson_ratio": 0.3, "loss_factor": 0.002}});
    cases.push((
        "campbell, 800 elements held sparse, nonviscous",
        "campbell",
        json!({"rotor": {"type": "beam", "materials": steel_lossy,
                 "shaft": [{"length": 1.2, "outer_diameter": 0.08, "material": "steel", "elements": 800}],
                 "disks": [{"node": 400, "mass": 20.0, "polar_inertia": 0.3, "transverse_inertia": 0.16}],
                 "supports": [bearing(0), bearing(800)]},
               "damping": {"model": "nonviscous"}, "max_frequency": 6000.0,
               "speeds": {"start": 0, "stop": 2000, "count": 20}}),
    ));
    // Harmonic responses of a large rotor held sparse: one sparse factor per frequency.
    let shaft = |elements: usize| {
        json!({"type": "beam", "materials": steel_plain,
               "shaft": [{"length": 1.2, "outer_diameter": 0.08, "material": "steel", "elements": elements}],
               "disks": [{"node": elements / 2, "mass": 20.0, "polar_inertia": 0.3, "transverse_inertia": 0.16}],
               "supports": [bearing(0), bearing(elements)]})
    };
    cases.push((
        "unbalance, 2000 elements held sparse",
        "unbalance",
        json!({"rotor": shaft(2000), "damping": {"model": "hysteretic"},
               "speeds": {"start": 10, "stop": 2000, "count": 100},
               "unbalances": [{"node": 1000, "amount": 1e-4}], "nodes": [1000]}),
    ));
    cases.push((
        "frequency, 2000 elements held sparse",
        "frequency",
        json!({"rotor": shaft(2000), "damping": {"model": "viscous"}, "speed": 500,
               "input": {"node": 1000, "direction": 0}, "output": {"node": 1000},
               "frequencies": {"start": 10, "stop": 2000, "count": 100}}),
    ));
    cases.push((
        "time, 2000 elements held sparse (run-up)",
        "time",
        json!({"rotor": shaft(2000), "damping": {"model": "viscous"},
               "speed_profile": [[0, 0], [2, 1500]],
               "unbalances": [{"node": 1000, "amount": 1e-4}],
               "duration": 2, "output_interval": 0.001, "nodes": [1000]}),
    ));
    // Hostile sizes are refused by counting, with nothing proportional allocated: a beam at
    // the dof limit with 12 + 12 branches per mode (26,000 states), and ten million elements.
    let steel = json!({"steel": {"young_modulus": 2.1e11, "density": 7800, "poisson_ratio": 0.3, "loss_factor": 0.01}});
    let hostile = [
        json!({"rotor": {"type": "beam", "materials": steel,
                 "shaft": [{"length": 2, "outer_diameter": 0.1, "material": "steel", "elements": 499}],
                 "supports": [{"node": 0, "stiffness": 1e8, "loss_factor": 0.1}, {"node": 499, "stiffness": 1e8, "loss_factor": 0.1}]},
               "damping": {"model": "nonviscous", "rotating": {"branches": 12}, "nonrotating": {"branches": 12}},
               "speeds": {"start": 0, "stop": 1000, "count": 10}}),
        json!({"rotor": {"type": "beam", "materials": steel,
                 "shaft": [{"length": 2, "outer_diameter": 0.1, "material": "steel", "elements": 10_000_000}],
                 "supports": [{"node": 0, "stiffness": 1e8}]},
               "damping": {"model": "viscous"}, "speeds": {"start": 0, "stop": 1000, "count": 10}}),
        // Bounded, so that it could be held sparse: refused by the sparse limit's count.
        json!({"rotor": {"type": "beam", "materials": steel,
                 "shaft": [{"length": 2, "outer_diameter": 0.1, "material": "steel", "elements": 10_000_000}],
                 "supports": [{"node": 0, "stiffness": 1e8}]},
               "damping": {"model": "viscous"}, "max_frequency": 5000,
               "speeds": {"start": 0, "stop": 1000, "count": 10}}),
    ];
    for body in hostile {
        let req: SweepRequest = serde_json::from_value(body).unwrap();
        let t0 = std::time::Instant::now();
        let mut refused = None;
        let peak = measure(|| refused = req.parse_campbell(&limits).err());
        let refused = refused.expect("refused");
        println!(
            "refused in {:.2} ms with {} kB of heap: {}",
            t0.elapsed().as_secs_f64() * 1e3,
            peak / 1024,
            refused
        );
        assert!(peak < 256 * 1024, "{peak} bytes allocated to refuse it");
    }
    println!(
        "{:<40} {:>12} {:>12} {:>7}",
        "case", "measured MB", "estimate MB", "ratio"
    );
    for (name, kind, body) in cases {
        check(&pool, &limits, name, kind, body);
    }
}

/// A sweep holds speeds x branches, not speeds x states x dofs: the pole sets in flight are a
/// bounded batch. Measured 66.4 MB (estimate 151 MB) for 2000 speeds of the unreduced
/// compressor, 404 states, every branch. About 9 minutes on 2 cores (tracking 404 branches by
/// their shapes at every speed dominates), so not in the default run:
/// `cargo test --release --test memory -- --ignored`.
#[test]
#[ignore = "about 9 minutes on 2 cores"]
fn a_2000_speed_sweep_of_a_404_state_rotor_stays_under_200_mb() {
    let limits = Limits::default();
    let pool = warm_pool(&limits);
    let mut c = unreduced(example("compressor-nvd.campbell.json"));
    c["damping"] = json!({"model": "viscous"});
    c["speeds"] = json!({"start": 0, "stop": 1500, "count": 2000});
    c["modal_reduction"] = json!(false);
    let (measured, _) = check(
        &pool,
        &limits,
        "campbell, full compressor, 2000 speeds",
        "campbell",
        c,
    );
    assert!(mb(measured) < 200.0, "{} MB", mb(measured));
}
