//! The memory estimate of every kind of task (`model::limits`) against the heap the analysis
//! really holds at its peak, measured with a counting allocator. The estimate must be an upper
//! bound (the budget relies on it) and not a wild one (it would refuse work for nothing).
//!
//! One test in this binary: the allocator counts the whole process.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

use serde_json::{Value, json};
use whirl::analysis::control::Control;
use whirl::model::Limits;
use whirl::model::api::{
    DampingMatricesRequest, ModalRequest, SweepRequest, TimeResponseRequest,
    UnbalanceResponseRequest,
};
use whirl::model::task::Task;
use whirl::service::task::{Format, execute, render};

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
        _ => unreachable!(),
    }
    .unwrap()
}

#[test]
fn every_estimate_bounds_the_measured_peak_heap() {
    let limits = Limits::default();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(limits.threads)
        .build()
        .unwrap();
    // faer's matrix products keep a scratch buffer per thread (twice the L3 cache, reserved
    // and touched only as far as a product needs): allocate it on every thread first, so that
    // what is measured is the analysis's own heap.
    let warm = || {
        let a = whirl::linalg::CMat::from_fn(64, 64, |i, j| {
            whirl::linalg::c64::new((i * 3 + j) as f64, (i + j * 5) as f64 % 7.0)
        });
        whirl::linalg::eigen(&a).unwrap();
    };
    warm();
    pool.broadcast(|_| warm());
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
    println!(
        "{:<40} {:>12} {:>12} {:>7}",
        "case", "measured MB", "estimate MB", "ratio"
    );
    for (name, kind, body) in cases {
        let task = parse(kind, body, &limits);
        let estimate = task.cost.peak_bytes as f64;
        let measured = measure(|| {
            pool.install(|| {
                let out = execute(&task, &Control::default(), limits.max_response_bytes).unwrap();
                let body = render(&out, &[Format::Json]).unwrap();
                assert!(!body.body.is_empty());
            })
        }) as f64;
        let mb = |x: f64| x / (1u64 << 20) as f64;
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
    }
}
