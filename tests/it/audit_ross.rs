//! The undamped critical speed map and the static deflection against ROSS 2.3.0's `run_ucs`
//! and `run_static` (`tests/data/ross/ucs.json`, `static.json`), and against beam theory.

use crate::common;
use common::{beam, floats};

use serde_json::{Value, json};
use whirl::analysis::AnalysisError;
use whirl::analysis::audit::critical_map::{CriticalMap, critical_speed_map};
use whirl::analysis::audit::statics::{Held, StaticResult, static_deflection};
use whirl::analysis::control::Control;
use whirl::model::rotor::BeamRotor;

const G: f64 = 9.8065;

fn data(name: &str) -> Value {
    let path = format!("{}/tests/data/ross/{name}", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn map(rotor: &BeamRotor, stiffness: &[f64], modes: usize) -> CriticalMap {
    critical_speed_map(rotor, stiffness, modes, &Control::default()).unwrap()
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

#[test]
fn critical_speed_map_is_rosss_run_ucs() {
    let file = data("ucs.json");
    for case in file["cases"].as_array().unwrap() {
        let name = case["rotor_name"].as_str().unwrap();
        let rotor = beam(&case["rotor"]);
        let stiffness = floats(&case["stiffness"]);
        let ours = map(&rotor, &stiffness, 4);
        // ROSS (ARPACK) and an independent dense eigh (8 lowest: each pair twice, the two
        // members equal to 6e-10, its own round-off).
        let (mut vs_arpack, mut vs_eigh, mut vs_pair) = (0.0f64, 0.0f64, 0.0f64);
        for m in 0..4 {
            let arpack = floats(&case["frequencies"][m]);
            let eigh = floats(&case["lowest_8_natural_frequencies"][2 * m]);
            let pair = floats(&case["lowest_8_natural_frequencies"][2 * m + 1]);
            for i in 0..stiffness.len() {
                let w = ours.frequencies[m][i];
                vs_arpack = vs_arpack.max(rel(w, arpack[i]));
                vs_eigh = vs_eigh.max(rel(w, eigh[i]));
                vs_pair = vs_pair.max(rel(w, pair[i]));
            }
        }
        println!(
            "{name}: frequencies vs ROSS {vs_arpack:.2e}, vs eigh {vs_eigh:.2e} \
             (other member {vs_pair:.2e})"
        );
        assert!(vs_arpack < 1e-6, "{name}: {vs_arpack:e}");
        assert!(
            vs_eigh < 1e-9 && vs_pair < 1e-9,
            "{name}: {vs_eigh:e} {vs_pair:e}"
        );

        // ROSS intersects the first bearing's vertical line with the sampled polyline (linear
        // in k between map points), so it agrees only loosely; ours are the eigen solve at k.
        let node = case["intersection_bearing_node"].as_u64().unwrap() as usize;
        let mut worst = 0.0f64;
        for r in case["intersections"].as_array().unwrap() {
            let mode = r["mode"].as_u64().unwrap() as usize + 1;
            let coefficient = r["coefficient"].as_str().unwrap();
            let i = ours
                .intersections
                .iter()
                .find(|i| i.support == 0 && i.mode == mode && i.coefficient == coefficient)
                .unwrap_or_else(|| panic!("{name}: no {coefficient} mode {mode}"));
            assert_eq!(i.node, node);
            assert_eq!(i.stiffness, r["stiffness"].as_f64().unwrap());
            let e = rel(i.frequency, r["frequency"].as_f64().unwrap());
            worst = worst.max(e);
            assert!(e < 5e-2, "{name}: {coefficient} mode {mode}: {e:e}");
        }
        println!("{name}: intersections vs ROSS's polyline {worst:.2e}");
        // Every intersection is the map's own eigen solve at that stiffness, exactly.
        for i in &ours.intersections {
            let at = map(&rotor, &[i.stiffness], 4);
            assert_eq!(i.frequency, at.frequencies[i.mode - 1][0], "{name}: {i:?}");
        }
        // Both supports, kxx and kyy (they differ on both rotors), 4 modes each: ROSS has only
        // the first support's, and only those inside its stiffness range.
        assert_eq!(ours.intersections.len(), 16, "{name}");
    }
}

#[test]
fn tabulated_supports_meet_the_map_at_a_critical_speed() {
    // Case C: both bearings tabulated at 200..2500 rad/s. The first mode (~120 rad/s) is below
    // the table, where k is held at its first value; the others are inside it.
    let rotor = beam(&data("speed_dependent.json")["rotor"]);
    let ours = map(&rotor, &[1e6], 4);
    let mut below = 0;
    for i in &ours.intersections {
        let s = rotor
            .general_supports()
            .iter()
            .find(|g| g.index == i.support)
            .unwrap();
        let c = s.at(i.frequency).k;
        let k = if i.coefficient == "kxx" { c.xx } else { c.yy };
        assert_eq!(i.stiffness, k, "{i:?}");
        // The mode's frequency at k(w) is w: a critical speed.
        let at = map(&rotor, &[k], 4).frequencies[i.mode - 1][0];
        assert!(rel(at, i.frequency) < 1e-9, "{i:?}: {at}");
        below += usize::from(i.frequency < 200.0);
        println!("{i:?}");
    }
    // 2 supports x (kxx, kyy) x 4 modes, one root each here; mode 1 below the table.
    assert_eq!(ours.intersections.len(), 16);
    assert_eq!(below, 4);

    // A table entirely below the modes: each root is the frequency at its last (held) value.
    let mut v = data("speed_dependent.json")["rotor"].clone();
    for s in v["supports"].as_array_mut().unwrap() {
        s["speeds"] = json!([10.0, 20.0, 30.0, 40.0, 50.0]);
    }
    let low = beam(&v);
    let ours = map(&low, &[1e6], 4);
    assert_eq!(ours.intersections.len(), 16);
    for i in &ours.intersections {
        let at = map(&low, &[i.stiffness], 4).frequencies[i.mode - 1][0];
        assert_eq!(at, i.frequency);
        let s = &low.general_supports()[i.support];
        let k = if i.coefficient == "kxx" {
            s.at(50.0).k.xx
        } else {
            s.at(50.0).k.yy
        };
        assert_eq!(i.stiffness, k);
    }
}

#[test]
fn the_map_stops_when_cancelled() {
    let rotor = beam(&data("ucs.json")["cases"][0]["rotor"]);
    let control = Control::default();
    control.cancel();
    let r = critical_speed_map(&rotor, &[1e6, 1e7], 4, &control);
    assert_eq!(r.err(), Some(AnalysisError::Cancelled));
}

fn by_node(v: &Value, key: &str) -> Vec<(usize, f64)> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|r| {
            (
                r["node"].as_u64().unwrap() as usize,
                r[key].as_f64().unwrap(),
            )
        })
        .collect()
}

#[test]
fn static_deflection_is_rosss_run_static() {
    let file = data("static.json");
    for case in file["cases"].as_array().unwrap() {
        let name = case["rotor_name"].as_str().unwrap();
        let rotor = beam(&case["rotor"]);
        let ours = static_deflection(&rotor, G, Held::Rigid).unwrap();
        let ross = floats(&case["deformation_y"]);
        let pinned = floats(&case["own_pinned_solution"]["deformation_y"]);
        let max = ross.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let (mut vs_ross, mut vs_pinned) = (0.0f64, 0.0f64);
        for (i, d) in ours.nodes.iter().enumerate() {
            assert_eq!(d.node, i);
            assert!((d.position - floats(&case["nodes_pos"])[i]).abs() < 1e-14);
            assert_eq!(d.x, 0.0);
            vs_ross = vs_ross.max((d.y - ross[i]).abs() / max);
            vs_pinned = vs_pinned.max((d.y - pinned[i]).abs() / max);
        }
        println!("{name}: deflection vs ROSS {vs_ross:.2e}, vs pinned {vs_pinned:.2e} of max");
        assert!(vs_ross < 1e-6 && vs_pinned < 1e-6, "{name}");

        let mut vs_reactions = 0.0f64;
        for ((node, y), r) in by_node(&case["bearing_reactions"], "force_y")
            .into_iter()
            .zip(&ours.reactions)
        {
            assert_eq!(r.node, node);
            assert_eq!(r.x, 0.0);
            vs_reactions = vs_reactions.max(rel(r.y, y));
        }
        println!("{name}: reactions vs ROSS {vs_reactions:.2e}");
        assert!(vs_reactions < 1e-6, "{name}");
        let disks: f64 = by_node(&case["disk_forces"], "value")
            .iter()
            .map(|d| d.1)
            .sum();
        let weight = case["shaft_weight"].as_f64().unwrap() + disks;
        assert!(rel(ours.weight, weight) < 1e-12, "{name}");

        // ROSS's recursion is exact for uniform elements (every element here): every station.
        let (shear, moment) = stations_vs_ross(case, &ours);
        println!("{name}: shear vs ROSS {shear:.2e}, moment {moment:.2e} of max");
        assert!(shear < 1e-9 && moment < 1e-9, "{name}");
    }
}

/// Largest station differences, relative to the largest |shear| and |moment|.
fn stations_vs_ross(case: &Value, ours: &StaticResult) -> (f64, f64) {
    let x = floats(&case["shear_force"]["x"]);
    let v = floats(&case["shear_force"]["value"]);
    let m = floats(&case["bending_moment"]["value"]);
    assert_eq!(ours.stations.len(), v.len());
    let max = |a: &[f64]| a.iter().fold(0.0f64, |s, v| s.max(v.abs()));
    let (mut dv, mut dm) = (0.0f64, 0.0f64);
    for (k, s) in ours.stations.iter().enumerate() {
        assert_eq!(s.element, k / 2);
        assert!((s.position - x[k]).abs() < 1e-14);
        dv = dv.max((s.shear - v[k]).abs());
        dm = dm.max((s.bending_moment - m[k]).abs());
    }
    (dv / max(&v), dm / max(&m))
}

fn uniform(supports: Value, disks: Value, elements: usize, length: f64, diameter: f64) -> Value {
    json!({
        "type": "beam",
        "materials": {"steel": {"young_modulus": 2.1e11, "density": 7800.0,
                                "poisson_ratio": 0.3, "loss_factor": 0.0}},
        "shaft": [{"length": length, "outer_diameter": diameter, "inner_diameter": 0.0,
                   "material": "steel", "elements": elements}],
        "disks": disks,
        "supports": supports,
    })
}

#[test]
fn a_symmetric_shaft_on_two_equal_supports_carries_half_its_weight_on_each() {
    let disk = json!([{"node": 4, "mass": 20.0, "polar_inertia": 0.2, "transverse_inertia": 0.1}]);
    let isotropic = json!([{"node": 1, "stiffness": 3e7}, {"node": 7, "stiffness": 3e7}]);
    let general = json!([{"node": 1, "kxx": 2e7, "kyy": 5e7}, {"node": 7, "kxx": 2e7, "kyy": 5e7}]);
    for supports in [isotropic, general] {
        let rotor = beam(&uniform(supports, disk.clone(), 8, 1.2, 0.06));
        for held in [Held::Rigid, Held::Elastic { speed: 0.0 }] {
            let r = static_deflection(&rotor, G, held).unwrap();
            for s in &r.reactions {
                assert!(rel(s.y, 0.5 * r.weight) < 1e-12, "{held:?}: {s:?}");
                assert_eq!(s.x, 0.0);
            }
            assert_eq!((r.reactions[0].support, r.reactions[1].support), (0, 1));
        }
    }
}

#[test]
fn a_simply_supported_shaft_deflects_and_bends_as_beam_theory() {
    // Slender (L/d = 100): the shear part of the deflection is 1e-4 of the bending part.
    let (l, d, e, nu, rho) = (2.0, 0.02, 2.1e11, 0.3, 7800.0);
    let supports = json!([{"node": 0, "stiffness": 1e9}, {"node": 10, "stiffness": 1e9}]);
    let rotor = beam(&uniform(supports, json!([]), 10, l, d));
    let r = static_deflection(&rotor, G, Held::Rigid).unwrap();
    let area = std::f64::consts::PI * d * d / 4.0;
    let inertia = std::f64::consts::PI * d.powi(4) / 64.0;
    let w = rho * area * G;
    let bending = 5.0 * w * l.powi(4) / (384.0 * e * inertia);
    // Timoshenko: + w L^2 / (8 kappa G A), Cowper's kappa for a solid section.
    let kappa = 6.0 * (1.0 + nu) / (7.0 + 6.0 * nu);
    let shear = w * l * l / (8.0 * kappa * e / (2.0 * (1.0 + nu)) * area);
    let mid = -r.nodes[5].y;
    println!(
        "midspan {mid:e}, beam theory {bending:e} ({:.2e}), with shear ({:.2e})",
        rel(mid, bending),
        rel(mid, bending + shear)
    );
    assert!(rel(mid, bending) < 2e-4);
    // The element is exact for a uniform load with its consistent load vector.
    assert!(rel(mid, bending + shear) < 1e-9);
    // Midspan: the right end of element 4; sagging is negative.
    let m = &r.stations[9];
    assert_eq!((m.element, m.position), (4, 1.0));
    assert!(rel(m.bending_moment, -w * l * l / 8.0) < 1e-9, "{m:?}");
    assert!(rel(r.weight, w * l) < 1e-12);
    // Shear: minus the left reaction at the left end, zero at midspan.
    assert!(rel(r.stations[0].shear, -0.5 * w * l) < 1e-12);
    assert!(m.shear.abs() < 1e-9 * w * l);
    assert!(r.stations.last().unwrap().bending_moment.abs() < 1e-9 * w * l * l);
}

#[test]
fn an_elastic_support_deflects_by_its_reaction_over_its_stiffness() {
    let disks = json!([{"node": 2, "mass": 30.0, "polar_inertia": 0.3, "transverse_inertia": 0.2}]);
    let supports = json!([{"node": 0, "stiffness": 2e6}, {"node": 6, "stiffness": 5e6}]);
    let rotor = beam(&uniform(supports, disks, 6, 1.0, 0.05));
    let r = static_deflection(&rotor, G, Held::Elastic { speed: 0.0 }).unwrap();
    for (s, k) in r.reactions.iter().zip([2e6, 5e6]) {
        let u = r.nodes[s.node].y;
        assert!(rel(u, -s.y / k) < 1e-12, "{s:?}: {u}");
    }
    let sum: f64 = r.reactions.iter().map(|s| s.y).sum();
    assert!(rel(sum, r.weight) < 1e-12);
    // The disk is nearer the softer support: it carries more.
    assert!(r.reactions[0].y > r.reactions[1].y);
}

#[test]
fn cross_coupled_supports_still_carry_the_weight() {
    let disks = json!([{"node": 3, "mass": 25.0, "polar_inertia": 0.3, "transverse_inertia": 0.2}]);
    let supports = json!([
        {"node": 0, "kxx": 1e6, "kxy": 5e5, "kyx": -8e5, "kyy": 2e6},
        {"node": 5, "kxx": 2e7, "kxy": -3e6, "kyx": 4e6, "kyy": 1e7, "cxx": 100.0},
        {"node": 10, "kxx": 1.2e6, "kxy": 6e5, "kyx": -9e5, "kyy": 2.4e6}
    ]);
    let rotor = beam(&uniform(supports, disks, 10, 1.5, 0.05));
    let r = static_deflection(&rotor, G, Held::Elastic { speed: 100.0 }).unwrap();
    let (y, x): (f64, f64) = r
        .reactions
        .iter()
        .fold((0.0, 0.0), |(y, x), s| (y + s.y, x + s.x));
    println!(
        "sum y {:.2e}, sum x {:.2e} of the weight",
        rel(y, r.weight),
        x / r.weight
    );
    assert!(rel(y, r.weight) < 1e-9);
    assert!(x.abs() < 1e-9 * r.weight);
    // Cross-coupling moves the shaft sideways, and three supports share x loads.
    assert!(r.nodes.iter().any(|n| n.x.abs() > 1e-3 * n.y.abs()));
    assert!(r.reactions.iter().any(|s| s.x.abs() > 1e-3 * s.y.abs()));
    let s = &r.reactions[1];
    let (ux, uy) = (r.nodes[5].x, r.nodes[5].y);
    assert!((s.y + (4e6 * ux + 1e7 * uy)).abs() < 1e-12 * r.weight);
    assert!((s.x + (2e7 * ux - 3e6 * uy)).abs() < 1e-12 * r.weight);
}

#[test]
fn a_shaft_its_supports_cannot_hold_is_an_error_not_nan() {
    let one = json!([{"node": 3, "stiffness": 1e7}]);
    let rotor = beam(&uniform(one, json!([]), 6, 1.0, 0.05));
    for held in [Held::Rigid, Held::Elastic { speed: 0.0 }] {
        assert!(matches!(
            static_deflection(&rotor, G, held),
            Err(AnalysisError::Linalg(_))
        ));
    }
    // Two supports at one node, or no stiffness in x: a free rigid motion.
    for supports in [
        json!([{"node": 2, "stiffness": 1e7}, {"node": 2, "stiffness": 1e7}]),
        json!([{"node": 0, "kxx": 0.0, "kyy": 1e7}, {"node": 6, "kxx": 0.0, "kyy": 1e7}]),
        json!([{"node": 0, "stiffness": 0.0}, {"node": 6, "stiffness": 0.0}]),
    ] {
        let rotor = beam(&uniform(supports, json!([]), 6, 1.0, 0.05));
        assert!(static_deflection(&rotor, G, Held::Elastic { speed: 0.0 }).is_err());
    }
    // Pinned, two supports at zero stiffness still hold it.
    let zero = json!([{"node": 0, "stiffness": 0.0}, {"node": 6, "stiffness": 0.0}]);
    let r = static_deflection(
        &beam(&uniform(zero, json!([]), 6, 1.0, 0.05)),
        G,
        Held::Rigid,
    );
    assert!(r.unwrap().nodes.iter().all(|n| n.y.is_finite()));
}

#[test]
fn example_1s_moment_peaks_at_midspan_inside_an_element() {
    // Example 1: a tube 1.5 m, 60/50 mm, steel 7810 kg/m^3, three elements on two equal end
    // supports. w = 7810 kg/m^3 x 8.639e-4 m^2 x 9.80665 m/s^2 = 66.17 N/m; the moment peaks at
    // mid-span, inside the middle element (no node there), at w L^2 / 8 = 18.61 N m; the shear
    // is w L / 2 = 49.63 N at the supports and vanishes at mid-span.
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/example1-hysteretic.modal.json"
    ))
    .unwrap();
    let v: Value = serde_json::from_str(&text).unwrap();
    let rotor = beam(&v["rotor"]);
    let r = static_deflection(&rotor, G, Held::Rigid).unwrap();
    let area = std::f64::consts::PI / 4.0 * (0.06f64.powi(2) - 0.05f64.powi(2));
    let w = 7810.0 * area * G;
    assert!((w - 66.17).abs() < 0.01, "{w}");
    let (l, m) = (1.5, &r.max_moment);
    assert!((w * l * l / 8.0 - 18.61).abs() < 0.01);
    println!("max moment {:?}", m);
    assert_eq!(m.element, 1);
    assert!((m.position - 0.75).abs() < 1e-9, "{m:?}");
    assert!(rel(m.bending_moment, -w * l * l / 8.0) < 1e-9, "{m:?}");
    assert!(rel(r.max_shear.shear.abs(), 0.5 * w * l) < 1e-9);
    // The diagram: 9 points per element, the moment quadratic and the shear linear between.
    assert_eq!(r.diagram.len(), 3 * 9);
    for p in &r.diagram {
        let x = p.position;
        assert!(
            (p.bending_moment + 0.5 * w * x * (l - x)).abs() < 1e-9 * w * l * l,
            "{p:?}"
        );
        assert!((p.shear + w * (0.5 * l - x)).abs() < 1e-9 * w * l, "{p:?}");
    }
}

#[test]
fn the_deflection_between_nodes_is_beam_theory_and_its_largest_is_found_there() {
    // A stubby shaft (L/d = 6) on pins at its ends, three elements: no node at mid-span,
    // where it deflects most. Beam theory with shear, q = rho A g:
    // y(x) = -q x (L^3 - 2 L x^2 + x^3) / (24 E I) - q x (L - x) / (2 kappa G A),
    // at mid-span 5 q L^4 / (384 E I) + q L^2 / (8 kappa G A).
    let (l, d, e, nu, rho) = (0.6, 0.1, 2.1e11, 0.3, 7800.0);
    let supports = json!([{"node": 0, "stiffness": 1e9}, {"node": 3, "stiffness": 1e9}]);
    let rotor = beam(&uniform(supports, json!([]), 3, l, d));
    let r = static_deflection(&rotor, G, Held::Rigid).unwrap();
    let area = std::f64::consts::PI * d * d / 4.0;
    let inertia = std::f64::consts::PI * d.powi(4) / 64.0;
    let q = rho * area * G;
    let kga = 6.0 * (1.0 + nu) / (7.0 + 6.0 * nu) * e / (2.0 * (1.0 + nu)) * area;
    let exact = |x: f64| {
        -q * x * (l.powi(3) - 2.0 * l * x * x + x.powi(3)) / (24.0 * e * inertia)
            - q * x * (l - x) / (2.0 * kga)
    };
    let mid = exact(0.5 * l);
    let shear_part = q * l * l / (8.0 * kga);
    println!(
        "mid-span {mid:e} m, of which shear {:.1}%",
        100.0 * shear_part / -mid
    );
    assert!(shear_part / -mid > 0.02, "the shear term must matter here");
    assert!(
        rel(
            mid,
            -(5.0 * q * l.powi(4) / (384.0 * e * inertia) + shear_part)
        ) < 1e-12
    );
    assert_eq!(r.diagram.len(), 3 * 9);
    for p in &r.diagram {
        assert!((p.y - exact(p.position)).abs() < 1e-9 * mid.abs(), "{p:?}");
        assert_eq!(p.x, 0.0);
    }
    // The slopes at the nodes: dy/dz = -q (L^3 - 6 L z^2 + 4 z^3) / (24 E I) - q (L - 2 z) / (2 kappa G A)
    // is the slope of the centre line; the section's rotation is its bending part alone.
    for n in &r.nodes {
        let z = n.position;
        let bending = -q * (l.powi(3) - 6.0 * l * z * z + 4.0 * z.powi(3)) / (24.0 * e * inertia);
        assert!(
            (n.slope_y - bending).abs() < 1e-9 * bending.abs().max(1e-12),
            "{n:?}"
        );
    }
    let m = &r.max_deflection;
    println!("largest {m:?}");
    assert_eq!(m.element, 1);
    assert!((m.position - 0.5 * l).abs() < 1e-6 * l, "{m:?}");
    assert!(rel(m.y, mid) < 1e-12, "{m:?}");
    // Joined straight, the nodes would give the deflection at z = L/3 there.
    println!(
        "straight between nodes: {:.1}% short at mid-span",
        100.0 * (1.0 - exact(l / 3.0) / mid)
    );
}

#[test]
fn example_1s_largest_deflection_is_at_midspan_between_nodes() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/example1-hysteretic.modal.json"
    ))
    .unwrap();
    let v: Value = serde_json::from_str(&text).unwrap();
    let r = static_deflection(&beam(&v["rotor"]), G, Held::Rigid).unwrap();
    let m = &r.max_deflection;
    let at_nodes = r.nodes.iter().map(|n| n.y.abs()).fold(0.0, f64::max);
    println!(
        "largest {:.4e} m at {:.4} m; largest at a node {:.4e} m ({:.1}% less)",
        m.y.abs(),
        m.position,
        at_nodes,
        100.0 * (1.0 - at_nodes / m.y.abs())
    );
    assert!((m.position - 0.75).abs() < 1e-6, "{m:?}");
    assert!(m.y.abs() > at_nodes);
}
