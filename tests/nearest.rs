//! The full model's poles within a disc by shift-invert Arnoldi (what the check of a reduction
//! reads) against the dense eigensolve, on rotors built for nothing in particular: the
//! compressor unreduced, stiff heavily damped and soft lightly damped cross-coupled bearings,
//! 12 and 100 elements, under every damping model and at several speeds.

mod common;

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
