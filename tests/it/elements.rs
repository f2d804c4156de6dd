//! Shaft elements beyond uniform segments (issue 29): conical elements, axial force and
//! torque, proportional damping and sleeves, against ROSS 2.3.0's lateral poles and unbalance
//! response on the same rotors (`tests/data/ross/elements.py`), and a conical element against
//! a fine stepped mesh.

use crate::common;

use common::ross::*;
use serde_json::{Value, json};
use whirl::analysis::poles::{Whirl, poles_at};
use whirl::damping::DampedModel;
use whirl::model::Limits;
use whirl::model::api::RotorInput;
use whirl::model::rotor::Rotor;

#[test]
fn conical_elements_give_rosss_poles_and_unbalance_response() {
    poles_match("tapered.json", 1e-6);
    unbalance_match("tapered.json", 1e-6);
}

#[test]
fn axial_force_torque_and_proportional_damping_give_rosss_poles_and_response() {
    poles_match("loaded.json", 1e-6);
    unbalance_match("loaded.json", 1e-6);
}

#[test]
fn sleeves_on_the_shafts_nodes_give_rosss_poles_and_response() {
    poles_match("sleeved.json", 1e-6);
    unbalance_match("sleeved.json", 1e-6);
}

/// A train of three shafts joined by two flexible couplings (masses, inertias, lateral and
/// angular springs), on six anisotropic cross-coupled bearings: ROSS's `CouplingElement` in the
/// same shaft line gives the same poles at five speeds and the same unbalance response at eight
/// nodes, on all three shafts (tests/data/ross/elements.py, `train`).
#[test]
fn a_train_of_three_shafts_joined_by_couplings_gives_rosss_poles_and_response() {
    let d = common::ross::data("train.json");
    assert_eq!(system(&d["rotor"]).n(), 42, "21 nodes");
    poles_match("train.json", 1e-6);
    unbalance_match("train.json", 1e-6);
}

/// The couplings' dampers turn with the shafts (rotating damping): at rest they are ROSS's
/// nonrotating ones, and every pole agrees there; spun at 1500 rad/s, above the lowest modes,
/// a rotating damper works on the whirl relative to the shaft, `omega - Omega`: it damps a
/// forward mode below the speed less than a standing damper does, and a backward mode more
/// (the circulatory stiffness `-i Omega c`). Each of the lowest poles moves that way from
/// ROSS's, by more than a thousandth of its decay rate.
#[test]
fn coupling_dampers_are_rotating_damping() {
    let d = common::ross::data("train_damped.json");
    let s = system(&d["rotor"]);
    let model = DampedModel::build(&s, &damping(json!({"model": "viscous"}), s.n())).unwrap();
    let cases = d["poles"].as_array().unwrap();
    let at_rest = eigenvalues(&cases[0]["eigenvalues"]);
    let rest = spectrum(&poles_at(&model, 0.0).unwrap(), true);
    let e = distance(&at_rest, &rest);
    assert!(e <= 1e-6, "at rest: {e:.2e}");
    let speed = cases[1]["speed"].as_f64().unwrap();
    let ross = eigenvalues(&cases[1]["eigenvalues"]);
    let (mut forward, mut backward) = (0, 0);
    for p in poles_at(&model, speed).unwrap().rotor.iter() {
        if !(p.s.im.abs() > 1.0 && p.s.im.abs() < 0.5 * speed) {
            continue;
        }
        let theirs = ross
            .iter()
            .min_by(|a, b| (*a - p.s).norm().total_cmp(&(*b - p.s).norm()))
            .copied()
            .unwrap();
        let shift = (p.s.re - theirs.re) / theirs.re.abs();
        println!(
            "{:?} {:.2}: Whirl {:.4}, ROSS {:.4} ({shift:+.2e})",
            p.whirl, p.s.im, p.s.re, theirs.re
        );
        match p.whirl {
            Whirl::Forward => {
                assert!(shift > 1e-3, "{} less damped", p.s);
                forward += 1;
            }
            Whirl::Backward => {
                assert!(shift < -1e-3, "{} more damped", p.s);
                backward += 1;
            }
            Whirl::Internal => {}
        }
    }
    assert!(
        forward >= 2 && backward >= 2,
        "{forward} forward, {backward} backward"
    );
}

/// The train's weight under gravity is its shafts' steel, its four disks and its couplings'
/// halves (these hang on the couplings' nodes): by hand, 7810 kg/m^3 pi/4 (0.06^2 0.8 +
/// 0.05^2 0.6 + 0.07^2 1.0) m^3 = 56.92 kg of shaft, 120 kg of disks, 11 + 8 kg of couplings;
/// and the six bearings' loads add up to it.
#[test]
fn a_trains_weight_and_bearing_loads_count_its_couplings() {
    use whirl::analysis::audit::statics::{Held, static_deflection};
    let d = common::ross::data("train.json");
    let input: RotorInput = serde_json::from_value(d["rotor"].clone()).unwrap();
    let Rotor::Beam(b) = Rotor::parse(&input, &Limits::default()).unwrap() else {
        panic!("a beam rotor")
    };
    let g = 9.80665;
    let shaft = 7810.0 * std::f64::consts::PI / 4.0
        * (0.06f64.powi(2) * 0.8 + 0.05f64.powi(2) * 0.6 + 0.07f64.powi(2) * 1.0);
    let mass = shaft + 120.0 + 19.0;
    let s = static_deflection(&b, g, Held::Elastic { speed: 0.0 }).unwrap();
    assert!(
        (s.weight / (g * mass) - 1.0).abs() < 1e-12,
        "{} N vs {} N",
        s.weight,
        g * mass
    );
    let loads: f64 = s.reactions.iter().map(|r| r.y).sum();
    println!(
        "weight {:.3} N ({mass:.3} kg), bearing loads {loads:.3} N",
        s.weight
    );
    assert!((loads / s.weight - 1.0).abs() < 1e-9, "{loads} N");
}

/// A mode shape is drawn straight across a coupling (a spring between two shaft ends, no
/// beam to interpolate) and as the beam's cubic elsewhere: the report's profile of the train's
/// first forward mode, and the layout every modal answer carries (`couplings`: 6 and 11).
#[test]
fn mode_shapes_are_straight_across_couplings() {
    use whirl::analysis::audit::cases::profile;
    use whirl::analysis::audit::statics::{Held, static_deflection};
    use whirl::answer::convert::shaft_layout;
    let d = common::ross::data("train.json");
    let input: RotorInput = serde_json::from_value(d["rotor"].clone()).unwrap();
    let rotor = Rotor::parse(&input, &Limits::default()).unwrap();
    let Rotor::Beam(b) = &rotor else {
        panic!("a beam rotor")
    };
    assert_eq!(b.couplings(), vec![6, 11]);
    assert_eq!(shaft_layout(&rotor).unwrap().couplings, vec![6, 11]);
    let s = system(&d["rotor"]);
    let model = DampedModel::build(&s, &damping(json!({"model": "viscous"}), s.n())).unwrap();
    let set = poles_at(&model, 0.0).unwrap();
    let first = set
        .rotor
        .iter()
        .filter(|p| p.whirl == Whirl::Forward && p.s.im > 0.0)
        .min_by(|a, b| a.s.im.total_cmp(&b.s.im))
        .unwrap()
        .s;
    let statics = static_deflection(b, 9.80665, Held::Elastic { speed: 0.0 }).unwrap();
    let shape = profile(&s, &set, first, &statics, &b.couplings()).unwrap();
    let z = |n: usize| statics.nodes[n].position;
    let inside = |a: usize| -> Vec<(f64, f64)> {
        shape
            .curve
            .iter()
            .copied()
            .filter(|&(x, _)| x > z(a) + 1e-12 && x < z(a + 1) - 1e-12)
            .collect()
    };
    // Across each coupling no interpolated point (the two nodes joined straight); inside a
    // beam element the cubic's points.
    assert!(inside(6).is_empty() && inside(11).is_empty());
    assert!(!inside(5).is_empty() && !inside(12).is_empty());
}

/// A coupling segment takes no shaft field, its coefficients must be finite and non-negative,
/// and no sleeve may span it: 400s naming each field.
#[test]
fn bad_couplings_are_refused_naming_the_field() {
    let d = common::ross::data("train.json");
    let parse = |rotor: Value| -> Vec<String> {
        let input: RotorInput = serde_json::from_value(rotor).unwrap();
        match Rotor::parse(&input, &Limits::default()) {
            Ok(_) => vec![],
            Err(e) => e.errors().iter().map(|f| f.path.clone()).collect(),
        }
    };
    let mut r = d["rotor"].clone();
    r["shaft"][1]["material"] = json!("steel");
    r["shaft"][1]["coupling"]["translational_stiffness"] = json!(-1.0);
    r["shaft"][3]["coupling"]["mass"] = json!([1.0, -2.0]);
    r["shaft"][3]["coupling"]["loss_factor"] = json!(1.5);
    let fields = parse(r);
    for f in [
        "rotor.shaft[1].material",
        "rotor.shaft[1].coupling.translational_stiffness",
        "rotor.shaft[3].coupling.mass[1]",
        "rotor.shaft[3].coupling.loss_factor",
    ] {
        assert!(fields.iter().any(|g| g == f), "{f} not in {fields:?}");
    }
    let mut r = d["rotor"].clone();
    r["sleeves"] = json!([{"node": 5, "elements": 3, "outer_diameter": 0.09,
                           "inner_diameter": 0.06, "material": "steel"}]);
    assert_eq!(parse(r), vec!["rotor.sleeves[0].node".to_string()]);
}

/// Natural frequencies (rad/s) at rest, undamped, lowest first.
fn frequencies(rotor: &Value, count: usize) -> Vec<f64> {
    let s = system(rotor);
    let model = DampedModel::build(&s, &damping(json!({"model": "viscous"}), s.n())).unwrap();
    let set = poles_at(&model, 0.0).unwrap();
    let mut w: Vec<f64> = set
        .rotor
        .iter()
        .map(|p| p.s.im)
        .filter(|&w| w > 1.0)
        .collect();
    w.sort_by(f64::total_cmp);
    w.dedup_by(|a, b| (*a - *b).abs() < 1e-9 * *b);
    w.truncate(count);
    w
}

/// A 0.8 m solid cone from 40 to 100 mm on two stiff supports, as `n` conical elements or as
/// `n` uniform elements of each element's mean diameter.
fn cone(n: usize, stepped: bool) -> Value {
    let (l, d0, d1) = (0.8, 0.04, 0.1);
    let shaft: Vec<Value> = if stepped {
        (0..n)
            .map(|k| {
                let mid = d0 + (d1 - d0) * (k as f64 + 0.5) / n as f64;
                json!({"length": l / n as f64, "outer_diameter": mid, "material": "steel"})
            })
            .collect()
    } else {
        vec![
            json!({"length": l, "outer_diameter": d0, "outer_diameter_right": d1,
                    "material": "steel", "elements": n}),
        ]
    };
    json!({"type": "beam",
           "materials": {"steel": {"young_modulus": 2.11e11, "density": 7810.0, "poisson_ratio": 0.3}},
           "shaft": shaft,
           "supports": [{"node": 0, "stiffness": 1e9}, {"node": n, "stiffness": 1e9}]})
}

#[test]
fn a_conical_mesh_and_a_fine_stepped_mesh_converge_to_the_same_frequencies() {
    // A stepped mesh converges as 1/n^2 (its steps' error in mass and stiffness is second
    // order in the step): its limit, by Richardson from 160 and 320 steps, is the cone's
    // frequencies. ROSS's conical element converges to the same limit, also as 1/n^2, with a
    // larger constant when shear counts (its shear parameter is the mid section's): 10, 40 and
    // 160 conical elements are 9.9e-3, 6.6e-4 and 4.2e-5 off over the four lowest modes, where
    // 40 steps are 2.6e-4 off in the first (ROSS gives the same numbers for both meshes).
    let (s160, s320) = (
        frequencies(&cone(160, true), 4),
        frequencies(&cone(320, true), 4),
    );
    let limit: Vec<f64> = s160
        .iter()
        .zip(&s320)
        .map(|(a, b)| b + (b - a) / 3.0)
        .collect();
    let error = |w: &[f64]| {
        w.iter()
            .zip(&limit)
            .map(|(a, b)| ((a - b) / b).abs())
            .fold(0.0, f64::max)
    };
    let e: Vec<f64> = [10, 40, 160]
        .iter()
        .map(|&n| error(&frequencies(&cone(n, false), 4)))
        .collect();
    println!("limit {limit:?} rad/s; conical 10/40/160 elements off by {e:?}");
    assert!(e[0] / e[1] > 8.0 && e[1] / e[2] > 8.0, "{e:?}");
    assert!(e[2] < 5e-5, "{e:?}");
}

#[test]
fn bad_sections_and_sleeves_name_their_fields() {
    // Each path must be among the errors of the rotor on `shaft` with two bad sleeves.
    let named = |shaft: Value, expected: &[&str]| {
        let rotor = json!({"type": "beam",
            "materials": {"steel": {"young_modulus": 2.11e11, "density": 7810.0, "poisson_ratio": 0.3}},
            "shaft": [shaft],
            "sleeves": [{"node": 4, "outer_diameter": 0.08, "material": "steel"},
                        {"node": 1, "elements": 9, "outer_diameter": 0.08, "material": "gold"}],
            "supports": [{"node": 0, "stiffness": 1e7}]});
        let input: RotorInput = serde_json::from_value(rotor).unwrap();
        let err = Rotor::parse(&input, &Limits::default()).unwrap_err();
        let paths: Vec<&str> = err.errors().iter().map(|e| e.path.as_str()).collect();
        for p in expected {
            assert!(paths.contains(p), "{p} missing from {paths:?}");
        }
    };
    named(
        json!({"length": 1.0, "outer_diameter": 0.05, "inner_diameter": 0.01,
               "inner_diameter_right": 0.06, "outer_diameter_right": 0.055,
               "material": "steel", "elements": 4, "rayleigh_damping": {"alpha": -1.0}}),
        &[
            "rotor.shaft[0].inner_diameter_right",
            "rotor.shaft[0].rayleigh_damping.alpha",
        ],
    );
    // With the shaft valid, the sleeves' own errors (their lengths come from its elements).
    named(
        json!({"length": 1.0, "outer_diameter": 0.05, "material": "steel", "elements": 4}),
        &[
            "rotor.sleeves[0].node",
            "rotor.sleeves[1].elements",
            "rotor.sleeves[1].material",
        ],
    );
}

/// The rotor with proportional damping `beta K` on its shaft in `frame`, on undamped supports.
fn internally_damped(frame: &str) -> Value {
    json!({"type": "beam",
        "materials": {"steel": {"young_modulus": 2.11e11, "density": 7810.0, "poisson_ratio": 0.3}},
        "shaft": [{"length": 1.2, "outer_diameter": 0.05, "material": "steel", "elements": 12,
                   "rayleigh_damping": {"alpha": 0.0, "beta": 2e-4, "frame": frame}}],
        "disks": [{"node": 6, "mass": 20.0, "polar_inertia": 0.2, "transverse_inertia": 0.1}],
        "supports": [{"node": 0, "stiffness": 5e7}, {"node": 12, "stiffness": 5e7}]})
}

fn largest_real_part(rotor: &Value, speed: f64) -> (f64, Vec<whirl::linalg::c64>) {
    let s = system(rotor);
    let model = DampedModel::build(&s, &damping(json!({"model": "viscous"}), s.n())).unwrap();
    let set = poles_at(&model, speed).unwrap();
    let poles: Vec<_> = set.rotor.iter().map(|p| p.s).collect();
    (poles.iter().map(|s| s.re).fold(f64::MIN, f64::max), poles)
}

#[test]
fn rotating_proportional_damping_destabilises_exactly_at_the_forward_critical_speed() {
    // With damping only in the rotating shaft, a pole s = i w on the axis needs
    // (K - w^2 M + w Omega G) x + i (w - Omega) C_r x = 0: the damping vanishes only at w = Omega,
    // so the threshold is the speed at which a forward whirl is synchronous (Jeffcott: the
    // critical speed sqrt(k / m)), and nonrotating damping of the same size never destabilises.
    let rotating = internally_damped("rotating");
    let nonrotating = internally_damped("nonrotating");
    let (at_rest_r, poles_r) = largest_real_part(&rotating, 0.0);
    let (at_rest_n, poles_n) = largest_real_part(&nonrotating, 0.0);
    assert!(at_rest_r < 0.0);
    assert!((at_rest_r - at_rest_n).abs() < 1e-9 * at_rest_r.abs());
    assert!(
        distance(&poles_r, &poles_n) < 1e-9,
        "at rest the frames agree"
    );
    let (mut lo, mut hi) = (0.0, 2000.0);
    assert!(
        largest_real_part(&rotating, hi).0 > 0.0,
        "unstable at {hi} rad/s"
    );
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if largest_real_part(&rotating, mid).0 > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let threshold = 0.5 * (lo + hi);
    let (_, poles) = largest_real_part(&rotating, threshold);
    let synchronous = poles
        .iter()
        .map(|s| ((s.im - threshold) / threshold).abs() + (s.re / threshold).abs())
        .fold(f64::INFINITY, f64::min);
    println!("threshold {threshold:.6} rad/s; nearest pole off synchronous by {synchronous:.2e}");
    assert!(synchronous < 1e-6, "{synchronous:.2e}");
    assert!(largest_real_part(&nonrotating, 2.0 * threshold).0 < 0.0);
}

#[test]
fn the_rotor_sketch_draws_cones_and_sleeves() {
    use whirl::render::plot_audit::rotor_sketch;
    for file in ["tapered.json", "sleeved.json"] {
        let rotor: RotorInput = serde_json::from_value(data(file)["rotor"].clone()).unwrap();
        let svg = rotor_sketch(&rotor).unwrap();
        // A cone is a trapezium: a polygon whose two vertical edges differ in height.
        assert!(svg.contains("<polygon"), "{file}");
        let png = whirl::render::png::png(&svg).unwrap();
        let out = format!("{}/{file}.sketch.png", env!("CARGO_TARGET_TMPDIR"));
        std::fs::write(&out, png).unwrap();
        println!("{out}");
    }
}

#[test]
fn sleeves_and_cones_weigh_what_their_volumes_do() {
    use whirl::analysis::audit::statics::{Held, static_deflection};
    // The sleeved rotor by hand, kg: shaft 7810 pi/4 0.05^2 1.5 = 23.00; steel sleeve
    // 7810 pi/4 (0.09^2 - 0.05^2) 0.45 = 15.46; soft conical sleeve (a frustum)
    // 7833.4 pi 0.3/12 ((0.12^2 + 0.12 0.1 + 0.1^2) - 3 0.05^2) = 17.78; disk 32.6: 88.84 kg,
    // 871.2 N at g = 9.8065 m/s^2.
    let pi = std::f64::consts::PI;
    let kg = 7810.0 * pi / 4.0 * 0.05f64.powi(2) * 1.5
        + 7810.0 * pi / 4.0 * (0.09f64.powi(2) - 0.05f64.powi(2)) * 0.45
        + 7833.4 * pi * 0.3 / 12.0 * ((0.0144 + 0.012 + 0.01) - 3.0 * 0.0025)
        + 32.6;
    let rotor: RotorInput = serde_json::from_value(data("sleeved.json")["rotor"].clone()).unwrap();
    let Rotor::Beam(b) = Rotor::parse(&rotor, &Limits::default()).unwrap() else {
        unreachable!()
    };
    let s = static_deflection(&b, 9.8065, Held::Rigid).unwrap();
    let reactions: f64 = s.reactions.iter().map(|r| r.y).sum();
    println!(
        "weight {} N, reactions {reactions} N, by hand {} N",
        s.weight,
        kg * 9.8065
    );
    assert!((s.weight - kg * 9.8065).abs() < 1e-9 * s.weight);
    assert!((reactions - s.weight).abs() < 1e-9 * s.weight);
}
