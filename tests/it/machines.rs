//! Machines as engineers model them (issue 29): point masses off the shaft (pedestals) and
//! bearings linked to them (`n_link`), against ROSS 2.3.0's lateral poles and unbalance
//! response on the same rotors (`tests/data/ross/machines.py`), and a point mass on the shaft
//! against the same mass given as a disk without inertia.

use crate::common;

use common::ross::*;
use serde_json::{Value, json};
use whirl::analysis::poles::poles_at;
use whirl::damping::DampedModel;
use whirl::model::Limits;
use whirl::model::api::RotorInput;
use whirl::model::rotor::Rotor;
use whirl::system::Layout;

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

#[test]
fn a_table_of_300_speeds_is_read_linearly_and_513_are_refused() {
    // kxx linear in the speed, 1e6 + 2e3 w N/m, tabulated at 300 speeds: at 1234.5 rad/s the
    // rotor is the one on constant supports with kxx = 3.469e6 N/m (linear interpolation is
    // exact on a line).
    let speeds: Vec<f64> = (0..300).map(|i| 10.0 * i as f64).collect();
    let kxx: Vec<f64> = speeds.iter().map(|w| 1e6 + 2e3 * w).collect();
    let rotor = |k: Value, w: Value| {
        json!({"type": "beam",
            "materials": {"steel": {"young_modulus": 2.11e11, "density": 7810.0, "poisson_ratio": 0.3}},
            "shaft": [{"length": 1.2, "outer_diameter": 0.05, "material": "steel", "elements": 8}],
            "disks": [{"node": 4, "mass": 20.0, "polar_inertia": 0.2, "transverse_inertia": 0.1}],
            "supports": [{"node": 0, "kxx": k, "kyy": 2e6, "cxx": 500.0, "speeds": w},
                         {"node": 8, "kxx": 2e6, "cxx": 500.0}]})
    };
    let w = 1234.5;
    let poles = |r: Value| {
        let s = system(&r);
        let model = DampedModel::build(&s, &damping(json!({"model": "viscous"}), s.n())).unwrap();
        spectrum(&poles_at(&model, w).unwrap(), true)
    };
    let tabulated = poles(rotor(json!(kxx), json!(speeds)));
    let constant = poles(rotor(json!(1e6 + 2e3 * w), Value::Null));
    let e = distance(&constant, &tabulated);
    assert!(e < 1e-11, "{e:.2e}");
    let mut long = speeds.clone();
    long.extend((300..513).map(|i| 10.0 * i as f64));
    let bad = rotor(json!(1e6), json!(long));
    let input: RotorInput = serde_json::from_value(bad).unwrap();
    let err = Rotor::parse(&input, &Limits::default()).unwrap_err();
    assert_eq!(err.errors()[0].path, "rotor.supports[0].speeds");
    assert!(
        err.errors()[0].message.contains("2 to 512"),
        "{:?}",
        err.errors()
    );
}
