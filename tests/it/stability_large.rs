//! The threshold of instability of rotors held sparse (`analysis::stability::stability_large`):
//! the poles in the box below `max_frequency`, the grid searched on a reduction checked through
//! sparse factors and the crossing closed on the full model, against the dense full model's
//! threshold over every pole on the same rotor, on cross-coupled bearings whose coupling grows
//! with speed, isotropic (coordinates `r`) and anisotropic (doubled); then over HTTP, the
//! bundled train held sparse at 1080 elements against its coarser meshes.

use crate::common;

use common::{assemble, post_json};
use serde_json::{Value, json};
use whirl::analysis::control::Control;
use whirl::analysis::modal::in_box;
use whirl::analysis::poles::poles_at;
use whirl::analysis::refine::{Full, nearest_pole};
use whirl::analysis::stability::curve_of;
use whirl::analysis::stability_large::stability_large;
use whirl::damping::DampedModel;
use whirl::model::damping::DampingModel;

/// A bearing whose cross-coupling grows with speed (a fluid film's, much simplified):
/// `kxy = -kyx` from 0 to `top` N/m over 0 to 3000 rad/s, direct stiffness and damping constant
/// (`kyy`, `cyy` apart from `kxx`, `cxx` where `anisotropic`).
fn bearing(top: f64, anisotropic: bool) -> Value {
    let speeds = [0.0, 1000.0, 2000.0, 3000.0];
    let k: Vec<f64> = speeds.iter().map(|w| top * w / 3000.0).collect();
    let minus: Vec<f64> = k.iter().map(|k| -k).collect();
    let (kyy, cyy) = if anisotropic { (3e7, 4e3) } else { (2e7, 3e3) };
    let all = |v: f64| vec![v; 4];
    json!({"speeds": speeds, "kxx": all(2e7), "kyy": all(kyy), "kxy": k, "kyx": minus,
           "cxx": all(3e3), "cyy": all(cyy)})
}

/// 100 elements (202 complex coordinates, 404 doubled): the threshold held sparse over the
/// poles below 3000 rad/s is the dense full model's over the same box, closed on the full
/// model: measured 4.8e-10 (isotropic) and 1.8e-8 (anisotropic) from the dense QR's threshold,
/// and the dense model's own matrices (shift-invert at the pole) put the decay rate there at
/// -8.9e-14 and 1.8e-11 of |s| (below). The dense threshold over every pole is another: a mode
/// near 9e5 rad/s whose decay rate's round-off passes the margin (seen at 150 elements: a
/// `threshold` at 250 rad/s for a pole with decay rate -7e-6 1/s); a bound is what keeps it out.
#[test]
#[ignore = "heavy: a dense reference of a large rotor (cargo test --release -- --ignored)"]
fn sparse_threshold_is_the_dense_one() {
    let speeds: Vec<f64> = (0..=30).map(|i| 100.0 * i as f64).collect();
    let control = Control::default();
    for anisotropic in [false, true] {
        let system = assemble(common::stepped_rotor(
            100,
            bearing(1.2e7, anisotropic),
            0.002,
        ));
        let model = DampingModel::Viscous;
        let t = std::time::Instant::now();
        let dense = DampedModel::build(&system, &model).unwrap();
        let bound = 3000.0;
        let in_bound = |w: f64| {
            poles_at(&dense, w)
                .map(|mut set| {
                    set.rotor.retain(|p| in_box(p.s, bound));
                    set
                })
                .map_err(Into::into)
        };
        let (exact, _) = curve_of(&in_bound, &speeds, &control).unwrap();
        let dense_s = t.elapsed().as_secs_f64();
        let exact = exact.expect("unstable in the range");
        let t = std::time::Instant::now();
        let held = stability_large(&system, &model, &speeds, bound, 480, &control).unwrap();
        let sparse_s = t.elapsed().as_secs_f64();
        let found = held.threshold.expect("unstable in the range");
        let rel = (found.speed - exact.speed).abs() / exact.speed;
        eprintln!(
            "anisotropic {anisotropic}: threshold {:.9} rad/s dense ({dense_s:.1} s), {:.9} held \
             sparse ({sparse_s:.1} s, {} of {} states, closed {}), {rel:.1e}; frequency {:.6} / {:.6}",
            exact.speed,
            found.speed,
            held.reduction.states,
            held.reduction.full_states,
            held.closed,
            exact.pole.frequency(),
            found.pole.frequency()
        );
        // The dense model's own matrices (shift-invert at the pole, no QR) put the pole's
        // decay rate at the sparse threshold at zero.
        let at = nearest_pole(Full::Dense(&dense), found.speed, found.pole.s)
            .unwrap()
            .unwrap();
        let sigma = at.re / at.norm();
        eprintln!("  the dense model's pole there: {at} (decay rate {sigma:.1e} of |s|)");
        assert!(held.closed);
        // Doubled, the dense model of tabulated bearings is its first-order form with the
        // tables (`M^-1`), whose decay rates are 1.8e-11 of |s| from the sparse model's (as
        // its harmonic responses are 2.5e-9 from the sparse solve, `response_large.rs`): on
        // this slow crossing (the decay rate gains 5e-4 1/s per rad/s) that is 1.8e-8 of the
        // threshold, which bounds the comparison with the dense QR's threshold.
        let agrees = if anisotropic { 1e-10 } else { 1e-12 };
        assert!(sigma.abs() <= agrees, "{sigma:e}");
        assert!(rel <= 1e-7, "{rel:e}");
        assert_eq!(found.mode, exact.mode);
        assert_eq!(found.pole.whirl, exact.pole.whirl);
        assert!((found.pole.s - exact.pole.s).norm() <= 1e-6 * exact.pole.s.norm());
    }
}

fn train(k: usize) -> Value {
    let example: Value = serde_json::from_str(
        &std::fs::read_to_string("examples/train-hysteretic.campbell.json").unwrap(),
    )
    .unwrap();
    common::refined(&example["rotor"], k).0
}

/// The bundled train (hysteretic) over 0 to 3000 rad/s: at 1080 elements (2166 coordinates,
/// past WHIRL_MAX_DOFS dense) held sparse with `max_frequency`, its threshold within 1e-6 of
/// the 180-element mesh's (held sparse too) and near the 18-element dense full model's; without
/// `max_frequency` a 422.
#[tokio::test]
#[ignore = "heavy: a dense reference of a large rotor (cargo test --release -- --ignored)"]
async fn train_threshold_held_sparse() {
    let body = |rotor: Value, bound: Option<f64>| {
        let mut b = json!({"rotor": rotor, "damping": {"model": "hysteretic"},
                           "speeds": {"start": 0, "stop": 3000, "count": 31}});
        if let Some(f) = bound {
            b["max_frequency"] = json!(f);
        }
        b
    };
    let mut out = vec![];
    for (k, bound) in [(1, None), (10, Some(3000.0)), (60, Some(3000.0))] {
        let t = std::time::Instant::now();
        let (status, r) = post_json("/v1/stability", &body(train(k), bound)).await;
        assert_eq!(status, 200, "{r}");
        eprintln!(
            "train x{k}: threshold {} rad/s, frequency {}, mode {} {}, closed {}, reduction {} \
             of {} states, {:.2} s",
            r["threshold"],
            r["frequency"],
            r["mode"],
            r["whirl"],
            r["threshold_closed"],
            r["reduction"]["states"],
            r["reduction"]["full_states"],
            t.elapsed().as_secs_f64()
        );
        if bound.is_some() {
            assert_eq!(r["max_frequency"], json!(3000.0));
            assert_eq!(r["reduction"]["full_model"], "sparse");
        }
        out.push(r);
    }
    let t = |r: &Value| r["threshold"].as_f64().expect("a threshold in the range");
    let fine = (t(&out[2]) - t(&out[1])).abs() / t(&out[2]);
    let coarse = (t(&out[2]) - t(&out[0])).abs() / t(&out[2]);
    eprintln!("1080 vs 180 elements {fine:.1e}, vs 18 (dense) {coarse:.1e}");
    assert_eq!(out[2]["threshold_closed"], true);
    assert!(fine <= 1e-6, "{fine:e}");
    assert!(coarse <= 1e-3, "{coarse:e}");
    let (status, err) = post_json("/v1/stability", &body(train(60), None)).await;
    assert_eq!(status, 422, "{err}");
}
