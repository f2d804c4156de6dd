//! Machines as engineers model them (issue 29): point masses off the shaft (pedestals) and
//! bearings linked to them (`n_link`), against ROSS 2.3.0's lateral poles and unbalance
//! response on the same rotors (`tests/data/ross/machines.py`), and a point mass on the shaft
//! against the same mass given as a disk without inertia.

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

fn data(name: &str) -> Value {
    let path = format!("{}/tests/data/ross/{name}", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn system(rotor: &Value) -> RotorSystem {
    let input: RotorInput = serde_json::from_value(rotor.clone()).unwrap();
    RotorSystem::assemble(&Rotor::parse(&input, &Limits::default()).unwrap()).unwrap()
}

fn damping(v: Value, n: usize) -> DampingModel {
    DampingModel::parse(&serde_json::from_value(v).unwrap(), Some(n)).unwrap()
}

/// Every eigenvalue of the lateral system: the reported poles and their mirrors (a real pole
/// is its own).
fn spectrum(set: &PoleSet, doubled: bool) -> Vec<c64> {
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
fn distance(reference: &[c64], computed: &[c64]) -> f64 {
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

fn eigenvalues(v: &Value) -> Vec<c64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|p| c64::new(p[0].as_f64().unwrap(), p[1].as_f64().unwrap()))
        .collect()
}

/// Poles of a file's rotor (viscous) at each of its reference speeds, against ROSS's.
fn poles_match(file: &str, tolerance: f64) -> f64 {
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
fn unbalance_match(file: &str, tolerance: f64) {
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

#[test]
fn bearings_on_anisotropic_pedestals_give_rosss_poles_and_unbalance_response() {
    let d = data("pedestals.json");
    assert_eq!(system(&d["rotor"]).layout(), Layout::Doubled);
    // 11 shaft nodes (2 dofs each) and 2 pedestal nodes (a translation each).
    assert_eq!(system(&d["rotor"]).n(), 24);
    poles_match("pedestals.json", 1e-6);
    unbalance_match("pedestals.json", 1e-6);
}

#[test]
fn isotropic_pedestals_held_by_their_point_masses_give_rosss_poles_and_response() {
    let d = data("pedestals_isotropic.json");
    let s = system(&d["rotor"]);
    assert_eq!(s.layout(), Layout::Single);
    let model = DampedModel::build(&s, &damping(json!({"model": "viscous"}), s.n())).unwrap();
    let mut worst: f64 = 0.0;
    for case in d["poles"].as_array().unwrap() {
        let speed = case["speed"].as_f64().unwrap();
        let set = poles_at(&model, speed).unwrap();
        // In r alone each pole is its own; ROSS's real system has every conjugate too.
        let mut computed = spectrum(&set, false);
        computed.extend(computed.clone().iter().map(|s| s.conj()));
        let e = distance(&eigenvalues(&case["eigenvalues"]), &computed);
        worst = worst.max(e);
        assert!(e <= 1e-6, "isotropic pedestals at {speed}: {e:.2e}");
    }
    println!("pedestals_isotropic.json: poles within {worst:.2e} of ROSS");
    unbalance_match("pedestals_isotropic.json", 1e-6);
}

/// A point mass on a shaft node is a disk without inertia; to ground it is an isotropic
/// support beside it.
#[test]
fn a_point_mass_on_the_shaft_is_a_disk_without_inertia() {
    let d = data("pedestals_isotropic.json");
    let mut a = d["rotor"].clone();
    a["point_masses"]
        .as_array_mut()
        .unwrap()
        .push(json!({"node": 3, "mass": 4.0, "stiffness": 2.0e5, "damping": 40.0}));
    let mut b = d["rotor"].clone();
    b["disks"]
        .as_array_mut()
        .unwrap()
        .push(json!({"node": 3, "mass": 4.0}));
    b["supports"]
        .as_array_mut()
        .unwrap()
        .push(json!({"node": 3, "stiffness": 2.0e5, "damping": 40.0}));
    let (sa, sb) = (system(&a), system(&b));
    let ma = DampedModel::build(&sa, &damping(json!({"model": "viscous"}), sa.n())).unwrap();
    let mb = DampedModel::build(&sb, &damping(json!({"model": "viscous"}), sb.n())).unwrap();
    for speed in [0.0, 500.0, 2000.0] {
        let pa = spectrum(&poles_at(&ma, speed).unwrap(), false);
        let pb = spectrum(&poles_at(&mb, speed).unwrap(), false);
        let e = distance(&pa, &pb);
        assert!(e <= 1e-12, "at {speed}: {e:.2e}");
    }
}

/// Every bad value of the new fields is named by its path.
#[test]
fn bad_point_masses_and_links_name_their_fields() {
    let d = data("pedestals_isotropic.json");
    let paths = |edit: &dyn Fn(&mut Value)| -> Vec<String> {
        let mut r = d["rotor"].clone();
        edit(&mut r);
        let input: RotorInput = serde_json::from_value(r).unwrap();
        Rotor::parse(&input, &Limits::default())
            .unwrap_err()
            .errors()
            .iter()
            .map(|e| format!("{}: {}", e.path, e.message))
            .collect()
    };
    // Node 13 without 12 before it: a gap.
    let e = paths(&|r| r["point_masses"][1]["node"] = json!(13));
    assert!(
        e[0].starts_with("rotor.point_masses[1].node: node 13 is off the shaft"),
        "{e:?}"
    );
    // A node off the shaft needs mass.
    let e = paths(&|r| r["point_masses"][0]["mass"] = json!(0.0));
    assert!(
        e[0].starts_with("rotor.point_masses[0].mass: must be > 0 on node 11"),
        "{e:?}"
    );
    let e = paths(&|r| r["point_masses"][0]["stiffness"] = json!(-1.0));
    assert!(
        e[0].starts_with("rotor.point_masses[0].stiffness: must be >= 0"),
        "{e:?}"
    );
    // Links: to itself, to a node that does not exist; a disk off the shaft.
    let e = paths(&|r| r["supports"][0]["n_link"] = json!(0));
    assert!(
        e[0].starts_with("rotor.supports[0].n_link: must differ"),
        "{e:?}"
    );
    let e = paths(&|r| r["supports"][1]["n_link"] = json!(14));
    assert!(
        e[0].starts_with("rotor.supports[1].n_link: node 14 does not exist"),
        "{e:?}"
    );
    let e = paths(&|r| r["disks"][0]["node"] = json!(11));
    assert!(
        e[0].starts_with("rotor.disks[0].node: node 11 is not on the shaft"),
        "{e:?}"
    );
}
