//! The full model's poles within a disc by shift-invert Arnoldi (what the check of a reduction
//! reads) against the dense eigensolve, on rotors built for nothing in particular: the
//! compressor unreduced, stiff heavily damped and soft lightly damped cross-coupled bearings,
//! 12 and 100 elements, under every damping model and at several speeds.

use crate::common;

use common::stepped_rotor as rotor;
use serde_json::{Value, json};
use whirl::analysis::nearest::{Wanted, poles_within};
use whirl::analysis::poles::poles_at;
use whirl::damping::{DampedModel, ModelKind};
use whirl::linalg::{self, c64};
use whirl::model::api::{DampingInput, RotorInput};
use whirl::model::damping::DampingModel;
use whirl::model::rotor::{Limits, Rotor};
use whirl::system::{Layout, RotorSystem};

fn system(rotor: Value) -> RotorSystem {
    let input: RotorInput = serde_json::from_value(rotor).unwrap();
    RotorSystem::assemble(&Rotor::parse(&input, &Limits::default()).unwrap()).unwrap()
}

fn damping(model: &str, n: usize) -> DampingModel {
    let j: DampingInput = serde_json::from_value(json!({ "model": model })).unwrap();
    DampingModel::parse(&j, Some(n)).unwrap()
}

fn compressor() -> RotorSystem {
    let path = format!(
        "{}/examples/compressor-nvd.campbell.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let v: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let mut rotor = v["rotor"].clone();
    rotor.as_object_mut().unwrap().remove("reduction");
    system(rotor)
}

/// The dense reference: every eigenvalue (consistent roots), or the rotor poles.
fn dense(model: &DampedModel, speed: f64, wanted: Wanted) -> Vec<c64> {
    match (&model.kind, wanted) {
        (ModelKind::Linear(_), Wanted::Rotor) => {
            // Doubled, poles_at keeps one of each mirror pair `(s, conj s)`.
            let rotor = poles_at(model, speed).unwrap().rotor;
            let doubled = model.layout == Layout::Doubled;
            let mirrors = rotor.iter().filter(|_| doubled).map(|p| p.s.conj());
            rotor.iter().map(|p| p.s).chain(mirrors).collect()
        }
        (ModelKind::Linear(m), Wanted::All) => linalg::eigenvalues(&m.at(speed)).unwrap(),
        (ModelKind::Hysteretic(signed), _) => signed
            .iter()
            .flat_map(|sm| {
                linalg::eigenvalues(&sm.model.at(speed))
                    .unwrap()
                    .into_iter()
                    .filter(|&s| sm.consistent(s, speed))
            })
            .collect(),
    }
}

/// Every eigenvalue from the dense eigensolve of `T = (A - sigma I)^-1` itself (formed column by
/// column): the same spectral transformation as Arnoldi's, without the round-off of `A`'s own
/// entries, which grows with the shaft's highest frequencies.
fn dense_inverse(model: &DampedModel, speed: f64) -> Option<Vec<c64>> {
    let ModelKind::Linear(m) = &model.kind else {
        return None;
    };
    let sigma = c64::new(3.0, 5.0);
    let op = m.shift_invert(speed, sigma);
    let n = m.size();
    let mut t = linalg::CMat::zeros(n, n);
    for j in 0..n {
        let mut e = vec![c64::new(0.0, 0.0); n];
        e[j] = c64::new(1.0, 0.0);
        for (i, v) in op.solve(&e).into_iter().enumerate() {
            t[(i, j)] = v;
        }
    }
    let theta = linalg::eigenvalues(&t).unwrap();
    Some(
        theta
            .into_iter()
            .filter(|z| z.norm() > 0.0)
            .map(|z| sigma + 1.0 / z)
            .collect(),
    )
}

fn nearest(s: c64, set: &[c64]) -> f64 {
    set.iter()
        .map(|t| (s - t).norm())
        .fold(f64::INFINITY, f64::min)
        / s.norm()
}

/// The largest relative distance, both ways, between the Arnoldi poles and a reference's in
/// the disc (away from its edge), asserted within `tolerance`; and how many were compared.
fn same_sets(
    found: &[c64],
    reference: &[c64],
    radius: f64,
    tolerance: f64,
    label: &str,
) -> (f64, usize) {
    let mut worst = 0.0f64;
    let mut count = 0;
    for &s in reference.iter().filter(|s| s.norm() <= 0.98 * radius) {
        let e = nearest(s, found);
        assert!(
            e <= tolerance,
            "{label}: reference pole {s} missed ({e:.1e})"
        );
        worst = worst.max(e);
        count += 1;
    }
    for &s in found {
        let e = nearest(s, reference);
        assert!(
            e <= tolerance,
            "{label}: {s} is not a reference pole ({e:.1e})"
        );
        worst = worst.max(e);
    }
    (worst, count)
}

/// Both ways, within `tolerance` relative: every dense pole in the disc (away from its edge)
/// has an Arnoldi one, and every Arnoldi pole is a dense one; and for every eigenvalue of a
/// model without internal coordinates, the same against [`dense_inverse`].
/// Returns the number compared.
fn check(
    name: &str,
    system: &RotorSystem,
    model: &str,
    speeds: &[f64],
    bound: f64,
    tolerance: f64,
) -> usize {
    let d = damping(model, system.n());
    let full = DampedModel::build(system, &d).unwrap();
    let wanted = match &full.kind {
        ModelKind::Linear(m) if m.p() > 0 => vec![Wanted::Rotor],
        _ => vec![Wanted::All],
    };
    let radius = 1.5 * bound;
    let mut compared = 0;
    for &speed in speeds {
        for &w in &wanted {
            let t0 = std::time::Instant::now();
            let Some(found) = poles_within(&full, speed, radius, w).unwrap() else {
                println!("{name} {model} {w:?} at {speed}: dense (Arnoldi past half the state)");
                continue;
            };
            let t1 = t0.elapsed().as_secs_f64();
            let t0 = std::time::Instant::now();
            let reference = dense(&full, speed, w);
            let t2 = t0.elapsed().as_secs_f64();
            let label = format!("{name} {model} {w:?} at {speed}");
            let (worst, count) = same_sets(&found, &reference, radius, tolerance, &label);
            compared += count;
            let inverse_worst = match (w, dense_inverse(&full, speed)) {
                (Wanted::All, Some(inverse)) => {
                    same_sets(&found, &inverse, radius, tolerance, &format!("{label}, T")).0
                }
                _ => 0.0,
            };
            println!(
                "{name} {model} {w:?} at {speed}: {} poles of {} states, worst {worst:.1e} \
                 ({inverse_worst:.1e} against the dense T); \
                 Arnoldi {t1:.4} s, dense {t2:.4} s",
                found.len(),
                full.states()
            );
        }
    }
    compared
}

#[test]
#[ignore = "heavy: a dense reference of a large rotor (cargo test --release -- --ignored)"]
fn arnoldi_finds_the_dense_poles_of_the_unreduced_compressor() {
    let s = compressor();
    for model in ["viscous", "equivalent", "hysteretic", "nonviscous"] {
        assert!(
            check(
                "compressor",
                &s,
                model,
                &[0.0, 1500.0, 3000.0],
                2500.0,
                1e-8
            ) > 0
        );
    }
}

#[test]
fn arnoldi_finds_the_dense_poles_of_stiff_heavily_damped_bearings() {
    let bearing = json!({"stiffness": 1e8, "damping": 5e4});
    for elements in [100] {
        let s = system(rotor(elements, bearing.clone(), 0.002));
        for model in ["viscous", "nonviscous", "hysteretic"] {
            let name = format!("stiff heavy {elements}");
            let tolerance = 1e-8;
            assert!(check(&name, &s, model, &[0.0, 2000.0], 3000.0, tolerance) > 0);
        }
    }
}

#[test]
#[ignore = "heavy: a dense reference of a large rotor (cargo test --release -- --ignored)"]
fn arnoldi_finds_the_dense_poles_of_soft_cross_coupled_anisotropic_bearings() {
    let bearing = json!({"kxx": 4e6, "kxy": 8e5, "kyx": -1.2e6, "kyy": 7e6,
                         "cxx": 300.0, "cxy": 40.0, "cyx": -25.0, "cyy": 500.0,
                         "loss_factor": 0.01});
    let s = system(rotor(48, bearing, 0.002));
    for model in ["viscous", "nonviscous", "equivalent", "hysteretic"] {
        assert!(
            check(
                "soft anisotropic 48",
                &s,
                model,
                &[0.0, 800.0],
                1500.0,
                1e-8
            ) > 0
        );
    }
}

/// The x/y natural frequencies of a rotor on anisotropic cross-coupled supports, from the real
/// symmetric pencil without its modes (what viscous and hysteretic models report), equal the
/// Hermitian pencil's of the doubled coordinates (what the equivalent and nonviscous models are
/// built on), every one of them to 1e-10 relative; and a rotor held in x only is refused by
/// both, at the same mode.
#[test]
fn xy_natural_frequencies_without_the_modes_are_the_hermitian_ones() {
    use whirl::fem::modal::{HermitianBasis, ModalError};
    let bearing = json!({"kxx": 4e6, "kxy": 8e5, "kyx": -1.2e6, "kyy": 7e6,
                         "cxx": 300.0, "cxy": 40.0, "cyx": -25.0, "cyy": 500.0});
    let s = system(rotor(48, bearing, 0.002));
    assert_eq!(s.layout(), Layout::Doubled);
    let modes = HermitianBasis::of(&s).unwrap().omega;
    let alone = HermitianBasis::frequencies(&s).unwrap();
    assert_eq!(modes.len(), alone.len());
    let worst = modes
        .iter()
        .zip(&alone)
        .map(|(a, b)| (a - b).abs() / a)
        .fold(0.0, f64::max);
    println!(
        "{} x/y frequencies, lowest {:.3} rad/s, worst {worst:.1e}",
        modes.len(),
        modes[0]
    );
    assert!(worst <= 1e-10, "{worst:.1e}");
    let x_only = json!({"kxx": 4e6, "kxy": 0.0, "kyx": 0.0, "kyy": 0.0, "cxx": 300.0});
    let s = system(rotor(48, x_only, 0.002));
    let mode = |e: ModalError| match e {
        ModalError::RigidBody { mode, .. } => mode,
        e => panic!("{e}"),
    };
    let a = HermitianBasis::of(&s).map(|_| ()).map_err(mode);
    let b = HermitianBasis::frequencies(&s).map(|_| ()).map_err(mode);
    println!("held in x only: {a:?}, {b:?}");
    assert!(a.is_err() && a == b);
}

/// The second-order shift-invert against a dense solve of `(A - sigma I) z = b`, on a
/// nonviscous Jeffcott rotor (m = 2 kg, k = 8 N/m, loss factors 0.02 / 0.05, c_r = 0.1,
/// c_n = 0.3 N s/m: internal coordinates, rotating and not), spun at 1.3 rad/s.
#[test]
fn second_order_shift_invert_is_the_state_matrix_one() {
    use whirl::damping::state::ShiftInvert;
    use whirl::linalg::CMat;
    use whirl::model::api::{JeffcottInput, NonviscousInput};
    use whirl::model::rotor::Jeffcott;
    let input = JeffcottInput {
        mass: 2.0,
        stiffness: 8.0,
        loss_factor_rotating: 0.02,
        loss_factor_nonrotating: 0.05,
        damping_rotating: 0.1,
        damping_nonrotating: 0.3,
    };
    let system = RotorSystem::jeffcott(&Jeffcott::parse(&input, "rotor").unwrap());
    let damping = DampingInput::Nonviscous(NonviscousInput::default());
    let model = DampingModel::parse(&damping, Some(system.n())).unwrap();
    let full = DampedModel::build(&system, &model).unwrap();
    let ModelKind::Linear(state) = &full.kind else {
        panic!("the nonviscous model is linear")
    };
    assert!(state.p() > 0);
    let speed = 1.3;
    let a = state.at(speed);
    let size = a.nrows();
    let b: Vec<c64> = (0..size)
        .map(|i| c64::new(1.0 + i as f64, 0.5 - 0.3 * i as f64))
        .collect();
    for sigma in [
        c64::new(0.01, 0.02),
        c64::new(-0.1, 2.0),
        c64::new(0.3, -1.7),
    ] {
        let op = state.shift_invert(speed, sigma);
        assert!(matches!(op, ShiftInvert::Physical(_)));
        let z = op.solve(&b);
        let lhs = CMat::from_fn(size, size, |i, j| {
            a[(i, j)] - if i == j { sigma } else { c64::new(0.0, 0.0) }
        });
        let rhs = CMat::from_fn(size, 1, |i, _| b[i]);
        let dense = linalg::solve_complex(&lhs, &rhs).unwrap();
        let scale = (0..size).map(|i| dense[(i, 0)].norm()).fold(0.0, f64::max);
        for i in 0..size {
            assert!(
                (z[i] - dense[(i, 0)]).norm() <= 1e-13 * scale,
                "{sigma}: entry {i}: {} vs {}",
                z[i],
                dense[(i, 0)]
            );
        }
    }
}
