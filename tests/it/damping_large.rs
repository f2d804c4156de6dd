//! The equivalent and nonviscous models of rotors held sparse (`damping::dampers`): their
//! dampers on the lowest modes as a low-rank term of the sparse second-order system, solved
//! through sparse factors and the Woodbury identity. Against the dense models on the same
//! rotors (isotropic, cross-coupled constant and tabulated bearings): exact when every mode is
//! damped, and the truncation to the modes up to 16 times the bound measured; then over HTTP the
//! bundled train at 1080 elements, its bounded Campbell diagram against `/v1/modal` at one
//! speed and its threshold against coarser meshes.

use crate::common;

use common::post_json;
use serde_json::{Value, json};
use whirl::analysis::audit::frequency::Excitation;
use whirl::analysis::control::Control;
use whirl::analysis::modal::{ModalResult, modal_bounded, modal_large};
use whirl::analysis::response::{Full, Held, frequency_sweep, unbalance_sweep};
use whirl::analysis::unbalance::SteadyUnbalance;
use whirl::damping::DampedModel;
use whirl::linalg::c64;
use whirl::model::api::DampingInput;
use whirl::model::damping::DampingModel;
use whirl::system::RotorSystem;

fn damping(v: Value, n: usize) -> DampingModel {
    let d: DampingInput = serde_json::from_value(v).unwrap();
    DampingModel::parse(&d, Some(n)).unwrap()
}

/// Largest relative distance from a rotor pole of either set to the nearest of the other.
fn distance(a: &ModalResult, b: &ModalResult) -> f64 {
    let near = |p: &ModalResult, q: &ModalResult| {
        p.poles
            .rotor
            .iter()
            .map(|x| {
                q.poles
                    .rotor
                    .iter()
                    .map(|y| (x.s - y.s).norm() / x.s.norm())
                    .fold(f64::MAX, f64::min)
            })
            .fold(0.0, f64::max)
    };
    near(a, b).max(near(b, a))
}

/// A bound halfway between the `k`-th and `k+1`-th |frequency| of the dense model's poles.
fn bound_between(system: &RotorSystem, dense: &DampedModel, speed: f64, k: usize) -> f64 {
    let all = modal_bounded(system, dense, speed, f64::INFINITY).unwrap();
    let mut f: Vec<f64> = all.poles.rotor.iter().map(|p| p.s.im.abs()).collect();
    f.sort_by(f64::total_cmp);
    f.dedup_by(|a, b| (*a - *b).abs() <= 1e-9 * *b);
    0.5 * (f[k - 1] + f[k])
}

/// The poles in a box of both models with `modes` given, dense and held sparse: `(distance,
/// dense poles, sparse poles)`.
fn both(system: &RotorSystem, d: &Value, speed: f64) -> (f64, usize, usize) {
    let model = damping(d.clone(), system.n());
    let full = DampedModel::build(system, &model).unwrap();
    let bound = bound_between(system, &full, speed, 8);
    let dense = modal_bounded(system, &full, speed, bound).unwrap();
    let sparse = modal_large(system, &model, speed, bound).unwrap();
    (
        distance(&dense, &sparse),
        dense.poles.rotor.len(),
        sparse.poles.rotor.len(),
    )
}

/// 30 elements (62 coordinates), every mode damped (`modes`: all of them): the sparse model
/// (dampers as a low-rank term, the nonviscous branches as internal coordinates of the
/// shift-invert) is the dense one, on isotropic bearings (coordinates `r`), on cross-coupled
/// anisotropic ones (doubled: the dampers on the x/y modes) and on those tabulated over speed
/// (the nonrotating dampers' loss read at the speed). Measured 8.8e-12 to 1.3e-10.
#[test]
fn every_mode_damped_sparse_is_the_dense_model() {
    let speed = 700.0;
    let (iso, tabulated, constant) = common::stepped_three(30, speed);
    for system in [&iso, &constant, &tabulated] {
        let n = system.n();
        for d in [
            json!({"model": "equivalent", "modes": n}),
            json!({"model": "nonviscous", "modes": n}),
        ] {
            let (dist, a, b) = both(system, &d, speed);
            eprintln!("{:?} {d}: {a} / {b} poles, {dist:.1e}", system.layout());
            assert_eq!(a, b);
            assert!(a >= 8);
            assert!(dist <= 1e-9, "{d}: {dist:e}");
        }
    }
}

/// 60 elements (122 coordinates): without `modes` a rotor held sparse damps the modes up to 16
/// times the bound, the dense model every mode. The poles below the bound differ by (measured)
/// 2.6e-9 / 8.6e-9 (equivalent, isotropic / cross-coupled) and 4.5e-8 / 1.5e-7 (nonviscous):
/// within the reduction's own 1e-6. (At 4 times the bound: 1.4e-7 / 2.8e-7 and 1.5e-6 / 3.9e-6;
/// at 8 times 1.8e-8 / 1.6e-7 and 2.7e-7 / 2.3e-6.)
#[test]
fn dampers_on_the_modes_below_sixteen_times_the_bound() {
    let speed = 700.0;
    let (iso, _, constant) = common::stepped_three(60, speed);
    for system in [&iso, &constant] {
        for d in [
            json!({"model": "equivalent"}),
            json!({"model": "nonviscous"}),
        ] {
            let (dist, a, b) = both(system, &d, speed);
            eprintln!("{:?} {d}: {a} / {b} poles, {dist:.1e}", system.layout());
            assert_eq!(a, b);
            assert!(dist <= 1e-6, "{d}: {dist:e}");
        }
    }
}

/// The harmonic responses held sparse (one sparse factor of `Z0(i omega)` per frequency, the
/// dampers through the Woodbury identity, the branches eliminated at `i omega`) against the
/// dense models' `Z X = F`, every mode damped, 30 elements on isotropic and on cross-coupled
/// bearings: the unbalance response over 0 to 1.3 times the third natural frequency and the
/// frequency response at 700 rad/s (a force along 30 degrees), relative to the largest
/// response. Measured (below) within round-off amplified near the resonances.
#[test]
fn harmonic_responses_held_sparse_are_the_dense_ones() {
    let spin = 700.0;
    let (iso, _, constant) = common::stepped_three(30, spin);
    let control = Control::default();
    for system in [&iso, &constant] {
        let n = system.n();
        for d in [
            json!({"model": "equivalent", "modes": n}),
            json!({"model": "nonviscous", "modes": n}),
        ] {
            let model = damping(d.clone(), n);
            let dense = DampedModel::build(system, &model).unwrap();
            let top = 1.3 * dense.basis.omega[2];
            let held = Held::new(system, &model, top).unwrap();
            let speeds: Vec<f64> = (0..60).map(|i| top * i as f64 / 59.0).collect();
            let tr = |node: usize| system.translation(node).unwrap();
            let loads = [SteadyUnbalance {
                dof: tr(8),
                amount: 1e-4,
                phase: 0.3,
            }];
            let out = [tr(8), tr(20), tr(1)];
            let sweep = |full: Full| {
                unbalance_sweep(system, &model, full, &speeds, &loads, &out, false, &control)
                    .unwrap()
                    .0
            };
            let u = common::worst(&sweep(Full::Dense(&dense)), &sweep(Full::Sparse(&held)));
            let force = Excitation::Direction(0.5).at(tr(12), n);
            let freqs: Vec<f64> = (1..=60).map(|i| top * i as f64 / 60.0).collect();
            let response = |full: Full| {
                let (r, _) = frequency_sweep(
                    system,
                    &model,
                    full,
                    spin,
                    &force,
                    tr(20),
                    &freqs,
                    false,
                    &control,
                )
                .unwrap();
                r.into_iter().map(|o| vec![o]).collect::<Vec<_>>()
            };
            let f = common::worst(
                &response(Full::Dense(&dense)),
                &response(Full::Sparse(&held)),
            );
            eprintln!(
                "{:?} {d}: unbalance {u:.1e}, frequency response {f:.1e}",
                system.layout()
            );
            assert!(u <= 1e-9 && f <= 1e-9, "{d}: {u:e} {f:e}");
        }
    }
}

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap()
}

/// The bundled train at 1080 elements (2166 coordinates; its bearings anisotropic and
/// cross-coupled, so doubled): its bounded Campbell diagram of each model held sparse, every
/// pole at 750 rad/s one of `/v1/modal`'s there within the reduction's 1e-6 and the other way
/// round; the equivalent model's threshold against the train meshed with 180 elements (held
/// sparse too) and 18 (dense, every mode damped).
#[tokio::test]
async fn train_equivalent_and_nonviscous_held_sparse() {
    let example: Value = serde_json::from_str(
        &std::fs::read_to_string("examples/train-hysteretic.campbell.json").unwrap(),
    )
    .unwrap();
    let (rotor, _) = common::refined(&example["rotor"], 60);
    let (bound, speed) = (1500.0, 750.0);
    for model in ["equivalent", "nonviscous"] {
        let d = json!({"model": model});
        let t = std::time::Instant::now();
        let (status, camp) = post_json(
            "/v1/campbell",
            &json!({"rotor": rotor, "damping": d,
                    "speeds": {"start": 0, "stop": 1500, "count": 3}, "max_frequency": bound}),
        )
        .await;
        let seconds = t.elapsed().as_secs_f64();
        assert_eq!(status, 200, "{camp}");
        let reduction = &camp["reduction"];
        assert_eq!(reduction["full_model"], "sparse");
        // Every mode up to 16 times the bound damped: the highest of them below it, and more
        // than the reduction keeps.
        assert!(f(&reduction["damped_band"]) <= 16.0 * bound, "{reduction}");
        assert!(
            reduction["damped_modes"].as_u64().unwrap() > 2 * reduction["modes"].as_u64().unwrap()
        );
        let (status, out) = post_json(
            "/v1/modal",
            &json!({"rotor": rotor, "damping": d, "speed": speed, "max_frequency": bound}),
        )
        .await;
        assert_eq!(status, 200, "{out}");
        let modal: Vec<c64> = out["poles"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|p| p["whirl"] != "internal")
            .map(|p| c64::new(f(&p["decay_rate"]), f(&p["frequency"])))
            .collect();
        let sweep = common::campbell_poles(&camp, 1);
        let near = |s: c64, set: &[c64]| {
            set.iter()
                .map(|t| (t - s).norm() / s.norm())
                .fold(f64::MAX, f64::min)
        };
        let inside =
            |s: &&c64| s.re.abs() <= bound * (1.0 - 1e-6) && s.im.abs() <= bound * (1.0 - 1e-6);
        let a = sweep
            .iter()
            .filter(inside)
            .map(|&s| near(s, &modal))
            .fold(0.0, f64::max);
        let b = modal
            .iter()
            .filter(inside)
            .map(|&s| near(s, &sweep))
            .fold(0.0, f64::max);
        eprintln!(
            "train x60 {model}: Campbell {seconds:.2} s ({} damped modes up to {:.0} rad/s, \
             error {:.1e}), {} poles at {speed}: {a:.1e} / {b:.1e}",
            reduction["damped_modes"],
            f(&reduction["damped_band"]),
            f(&reduction["max_relative_error"]),
            modal.len()
        );
        assert!(modal.len() >= 6);
        assert!(
            a <= 1e-6 && b <= 1e-6,
            "{model}: Campbell vs modal {a:e} {b:e}"
        );
    }
    // The equivalent model's threshold at three meshes.
    let mut thresholds = vec![];
    for k in [60, 10, 1] {
        let (rotor, _) = common::refined(&example["rotor"], k);
        let (status, out) = post_json(
            "/v1/stability",
            &json!({"rotor": rotor, "damping": {"model": "equivalent"},
                    "speeds": {"start": 0, "stop": 3000, "count": 31}, "max_frequency": 3000}),
        )
        .await;
        assert_eq!(status, 200, "{out}");
        thresholds.push(f(&out["threshold"]));
    }
    let d180 = (thresholds[0] - thresholds[1]).abs() / thresholds[0];
    let d18 = (thresholds[0] - thresholds[2]).abs() / thresholds[0];
    eprintln!(
        "train equivalent threshold {:.6} rad/s at 1080 elements: {d180:.1e} from 180, \
         {d18:.1e} from 18",
        thresholds[0]
    );
    assert!(d180 <= 1e-5 && d18 <= 1e-4, "{thresholds:?}");
}
