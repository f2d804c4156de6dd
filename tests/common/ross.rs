//! ROSS 2.3.0 reference files (`tests/data/ross/`): their rotors, and Whirl's poles and
//! unbalance response on them compared with ROSS's.

use serde_json::{Value, json};
use whirl::analysis::control::Control;
use whirl::analysis::poles::{PoleSet, poles_at};
use whirl::analysis::run::{Outcome, run};
use whirl::damping::DampedModel;
use whirl::linalg::c64;
use whirl::model::Limits;
use whirl::model::api::{RotorInput, UnbalanceResponseRequest};
use whirl::model::damping::DampingModel;
use whirl::model::rotor::Rotor;
use whirl::system::{Layout, RotorSystem};

pub fn data(name: &str) -> Value {
    let path = format!("{}/tests/data/ross/{name}", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

pub fn system(rotor: &Value) -> RotorSystem {
    let input: RotorInput = serde_json::from_value(rotor.clone()).unwrap();
    RotorSystem::assemble(&Rotor::parse(&input, &Limits::default()).unwrap()).unwrap()
}

pub fn damping(v: Value, n: usize) -> DampingModel {
    DampingModel::parse(&serde_json::from_value(v).unwrap(), Some(n)).unwrap()
}

/// Every eigenvalue of the lateral system: the reported poles and their mirrors (a real pole
/// is its own).
pub fn spectrum(set: &PoleSet, doubled: bool) -> Vec<c64> {
    let mut out = vec![];
    for p in &set.rotor {
        out.push(p.s);
        if doubled && p.s.im.abs() > 1e-9 * p.s.norm() {
            out.push(p.s.conj());
        }
    }
    out
}

/// Largest relative distance from each reference to the nearest computed value, and back.
pub fn distance(reference: &[c64], computed: &[c64]) -> f64 {
    let one_way = |a: &[c64], b: &[c64]| {
        a.iter()
            .map(|s| {
                b.iter()
                    .map(|t| (s - t).norm())
                    .fold(f64::INFINITY, f64::min)
                    / s.norm().max(1e-300)
            })
            .fold(0.0, f64::max)
    };
    one_way(reference, computed).max(one_way(computed, reference))
}

pub fn eigenvalues(v: &Value) -> Vec<c64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|p| c64::new(p[0].as_f64().unwrap(), p[1].as_f64().unwrap()))
        .collect()
}

/// Poles of a file's rotor (viscous) at each of its reference speeds, against ROSS's.
pub fn poles_match(file: &str, tolerance: f64) -> f64 {
    let d = data(file);
    let s = system(&d["rotor"]);
    let doubled = s.layout() == Layout::Doubled;
    let model = DampedModel::build(&s, &damping(json!({"model": "viscous"}), s.n())).unwrap();
    let mut worst: f64 = 0.0;
    for case in d["poles"].as_array().unwrap() {
        let speed = case["speed"].as_f64().unwrap();
        let reference = eigenvalues(&case["eigenvalues"]);
        let set = poles_at(&model, speed).unwrap();
        assert_eq!(set.missing(), 0);
        let computed = spectrum(&set, doubled);
        assert_eq!(computed.len(), reference.len(), "{file} at {speed}");
        let e = distance(&reference, &computed);
        worst = worst.max(e);
        assert!(e <= tolerance, "{file} at {speed} rad/s: {e:.2e}");
    }
    println!("{file}: poles within {worst:.2e} of ROSS");
    worst
}

/// The unbalance response of a file's rotor against ROSS's X and Y at its nodes.
pub fn unbalance_match(file: &str, tolerance: f64) {
    let d = data(file);
    let u = &d["unbalance_response"];
    let req: UnbalanceResponseRequest = serde_json::from_value(json!({
        "rotor": d["rotor"],
        "damping": {"model": "viscous"},
        "speeds": u["speeds"],
        "unbalances": u["unbalances"],
        "nodes": u["nodes"].as_array().unwrap().iter().map(|n| n["node"].clone()).collect::<Vec<_>>(),
    }))
    .unwrap();
    let task = req.parse(&Limits::default()).unwrap();
    let Outcome::Unbalance {
        response, speeds, ..
    } = run(&task, &Control::default()).unwrap()
    else {
        unreachable!()
    };
    let mut worst: f64 = 0.0;
    for (k, node) in u["nodes"].as_array().unwrap().iter().enumerate() {
        for (axis, key) in [(0, "x"), (1, "y")] {
            let reference = eigenvalues(&node[key]);
            let peak = reference.iter().map(|z| z.norm()).fold(0.0, f64::max);
            for (i, want) in reference.iter().enumerate() {
                let got = response[i][k].xy()[axis];
                let e = (got - want).norm() / peak;
                worst = worst.max(e);
                assert!(
                    e <= tolerance,
                    "{file} node {} {key} at {} rad/s: {got} against {want}",
                    node["node"],
                    speeds[i]
                );
            }
        }
    }
    println!("{file}: unbalance response within {worst:.2e} of ROSS's peak");
}
