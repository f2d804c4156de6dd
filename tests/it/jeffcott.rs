//! The Jeffcott rotor under the four damping models: the paper's printed poles (section 4),
//! MODEL.md's gammas, and closed forms.

use crate::common;

use common::assert_printed;
use whirl::analysis::campbell::campbell;
use whirl::analysis::control::Control;
use whirl::analysis::poles::{PoleSet, Whirl, poles_at};
use whirl::analysis::stability::stability;
use whirl::damping::DampedModel;
use whirl::damping::nonviscous::BranchSet;
use whirl::linalg::c64;
use whirl::model::damping::{DampingModel, NonviscousSpec};
use whirl::model::rotor::Jeffcott;
use whirl::system::RotorSystem;

fn system(eta_r: f64, eta_n: f64) -> RotorSystem {
    RotorSystem::jeffcott(&Jeffcott::nondimensional(eta_r, eta_n).unwrap())
}

fn nvd(m: usize) -> DampingModel {
    let set = BranchSet::new(m, 10.0, vec![1.0; m]).unwrap();
    DampingModel::Nonviscous(NonviscousSpec {
        rotating: set.clone(),
        nonrotating: set,
        modes: None,
    })
}

fn poles(eta_r: f64, eta_n: f64, model: &DampingModel, speed: f64) -> PoleSet {
    let m = DampedModel::build(&system(eta_r, eta_n), model).unwrap();
    poles_at(&m, speed).unwrap()
}

fn one(set: &PoleSet, whirl: Whirl) -> c64 {
    let v: Vec<c64> = set
        .rotor
        .iter()
        .filter(|p| p.whirl == whirl)
        .map(|p| p.s)
        .collect();
    assert_eq!(v.len(), 1, "{whirl:?} poles: {v:?}");
    v[0]
}

#[test]
fn nvd_four_branches_at_rest_gives_the_printed_poles() {
    let set = poles(0.01, 0.0, &nvd(4), 0.0);
    assert_eq!(set.rotor.len(), 2);
    assert_eq!(
        set.internal.len(),
        4,
        "eta_n = 0 adds no nonrotating branches"
    );
    let f = one(&set, Whirl::Forward);
    let b = one(&set, Whirl::Backward);
    assert_printed(f.re, "-0.0044", "forward decay rate");
    assert_printed(f.im, "1.0152", "forward frequency");
    assert_printed(b.re, "-0.0044", "backward decay rate");
    assert_printed(b.im, "-1.0152", "backward frequency");
    for (p, printed) in set
        .internal
        .iter()
        .zip(["-31.6222", "-3.1584", "-0.3124", "-0.0311"])
    {
        assert_printed(p.s.re, printed, "internal pole");
        assert!(
            p.s.im.abs() < 1e-9,
            "internal poles are real at rest: {}",
            p.s
        );
    }
}

#[test]
fn nvd_four_branches_at_speed_four_gives_the_printed_poles() {
    let set = poles(0.01, 0.0, &nvd(4), 4.0);
    let f = one(&set, Whirl::Forward);
    let b = one(&set, Whirl::Backward);
    assert_printed(b.re, "-0.0048", "backward decay rate");
    assert_printed(b.im, "-1.0202", "backward frequency");
    assert_printed(f.re, "0.0049", "forward decay rate (unstable)");
    assert_printed(f.im, "1.0183", "forward frequency");
    let printed = [
        ("-31.6223", "4.0001"),
        ("-3.1626", "4.0016"),
        ("-0.3165", "4.0000"),
        ("-0.0317", "4.0000"),
    ];
    assert_eq!(set.internal.len(), 4);
    for (p, (re, im)) in set.internal.iter().zip(printed) {
        assert_eq!(p.whirl, Whirl::Internal);
        assert_printed(p.s.re, re, "internal decay rate");
        assert_printed(p.s.im, im, "internal frequency");
    }
}

#[test]
fn zero_loss_factors_add_no_branches() {
    let m = DampedModel::build(&system(0.0, 0.0), &nvd(3)).unwrap();
    assert_eq!(m.states(), 2);
    let m = DampedModel::build(&system(0.01, 0.02), &nvd(3)).unwrap();
    assert_eq!(m.states(), 2 + 3 + 3);
}

#[test]
fn equivalent_threshold_is_eq_10() {
    for (eta_n, eta_r) in [
        (0.0, 0.01),
        (0.01, 0.01),
        (0.02, 0.01),
        (0.005, 0.04),
        (0.06, 0.02),
    ] {
        let m = DampedModel::build(
            &system(eta_r, eta_n),
            &DampingModel::Equivalent { modes: None },
        )
        .unwrap();
        let speeds: Vec<f64> = (0..41).map(|i| i as f64 * 0.25).collect();
        let t = stability(&m, &speeds, &Control::default())
            .unwrap()
            .expect("unstable in range");
        let expected = 1.0 + eta_n / eta_r;
        assert!(
            (t.speed - expected).abs() <= 1e-6 * expected,
            "eta_n {eta_n}, eta_r {eta_r}: {} vs {expected}",
            t.speed
        );
        assert_eq!(t.pole.whirl, Whirl::Forward);
        assert_eq!(t.mode, 1);
    }
}

#[test]
fn hysteretic_forward_decay_rate_steps_at_the_critical_speed() {
    for (eta_n, eta_r) in [(0.0, 0.01), (0.01, 0.02), (0.03, 0.01)] {
        let eps = eta_n + eta_r;
        let h = DampingModel::Hysteretic;
        let below = one(&poles(eta_r, eta_n, &h, 0.5), Whirl::Forward);
        let above = one(&poles(eta_r, eta_n, &h, 2.0), Whirl::Forward);
        // sqrt(1 + i e) = 1 + i e/2 + e^2/8 - i e^3/16 + ...: the error is e^3/16.
        assert!((below.re + (eta_n + eta_r) / 2.0).abs() <= eps.powi(3) / 8.0);
        assert!((above.re + (eta_n - eta_r) / 2.0).abs() <= eps.powi(3) / 8.0);
        // The backward pole does not see the critical speed.
        let back = one(&poles(eta_r, eta_n, &h, 2.0), Whirl::Backward);
        assert!((back.re + (eta_n + eta_r) / 2.0).abs() <= eps.powi(3) / 8.0);
    }
}

#[test]
fn hysteretic_poles_are_the_exact_sign_consistent_roots() {
    // s = i sqrt(1 + i (a eta_n + b eta_r)) exactly, for the consistent signs.
    let (eta_n, eta_r) = (0.02, 0.05);
    let exact = |a: f64, b: f64| c64::new(0.0, 1.0) * c64::new(1.0, a * eta_n + b * eta_r).sqrt();
    let below = poles(eta_r, eta_n, &DampingModel::Hysteretic, 0.3);
    assert!((one(&below, Whirl::Forward) - exact(1.0, 1.0)).norm() < 1e-14);
    let above = poles(eta_r, eta_n, &DampingModel::Hysteretic, 3.0);
    assert!((one(&above, Whirl::Forward) - exact(1.0, -1.0)).norm() < 1e-14);
    // Backward: a = b = -1, s = -i sqrt(1 - i (eta_n + eta_r)).
    let back = c64::new(0.0, -1.0) * c64::new(1.0, -(eta_n + eta_r)).sqrt();
    assert!((one(&above, Whirl::Backward) - back).norm() < 1e-14);
}

#[test]
fn hysteretic_threshold_is_where_the_unstable_root_becomes_consistent() {
    // eta_r > eta_n: above the critical speed the forward root with b = -1,
    // s = i sqrt(1 - i (eta_r - eta_n)), has sigma > 0; it is a pole once Omega > its omega.
    let (eta_n, eta_r) = (0.005, 0.01);
    let m = DampedModel::build(&system(eta_r, eta_n), &DampingModel::Hysteretic).unwrap();
    let speeds: Vec<f64> = (0..21).map(|i| i as f64 * 0.1).collect();
    let t = stability(&m, &speeds, &Control::default())
        .unwrap()
        .expect("unstable");
    let s = c64::new(0.0, 1.0) * c64::new(1.0, -(eta_r - eta_n)).sqrt();
    assert!(s.re > 0.0);
    assert!((t.speed - s.im).abs() <= 1e-9, "{} vs {}", t.speed, s.im);
    // eta_n > eta_r: stable at all speeds (section 2.3).
    let m = DampedModel::build(&system(0.01, 0.02), &DampingModel::Hysteretic).unwrap();
    assert!(
        stability(&m, &speeds, &Control::default())
            .unwrap()
            .is_none()
    );
}

#[test]
fn equivalent_and_hysteretic_agree_at_rest_to_second_order() {
    for (eta_n, eta_r) in [(0.01, 0.02), (0.05, 0.0), (0.03, 0.03)] {
        let eps: f64 = eta_n + eta_r;
        let e = poles(eta_r, eta_n, &DampingModel::Equivalent { modes: None }, 0.0);
        let h = poles(eta_r, eta_n, &DampingModel::Hysteretic, 0.0);
        for whirl in [Whirl::Forward, Whirl::Backward] {
            let d = (one(&e, whirl) - one(&h, whirl)).norm();
            assert!(
                d <= eps * eps,
                "{whirl:?}: |E - H| = {d} > eta^2 = {}",
                eps * eps
            );
        }
    }
}

#[test]
fn forward_and_backward_mirror_each_other_at_rest() {
    for model in [
        DampingModel::Viscous,
        DampingModel::Hysteretic,
        DampingModel::Equivalent { modes: None },
        nvd(3),
    ] {
        let set = poles(0.02, 0.01, &model, 0.0);
        let f = one(&set, Whirl::Forward);
        let b = one(&set, Whirl::Backward);
        assert!((f - b.conj()).norm() < 1e-12, "{model:?}: {f} vs {b}");
    }
}

#[test]
fn viscous_jeffcott_matches_the_closed_form() {
    // m s^2 + (c_n + c_r) s + k - i Omega c_r = 0.
    let j = whirl::model::api::JeffcottInput {
        mass: 3.0,
        stiffness: 1.2e6,
        loss_factor_rotating: 0.3,
        loss_factor_nonrotating: 0.1,
        damping_rotating: 40.0,
        damping_nonrotating: 90.0,
    };
    let sys = RotorSystem::jeffcott(&Jeffcott::parse(&j, "rotor").unwrap());
    let m = DampedModel::build(&sys, &DampingModel::Viscous).unwrap();
    for speed in [0.0, 300.0, 900.0, 2000.0] {
        let set = poles_at(&m, speed).unwrap();
        let b = c64::new(130.0 / 3.0, 0.0);
        let c = c64::new(1.2e6, -speed * 40.0) / 3.0;
        let disc = (b * b - 4.0 * c).sqrt();
        let roots = [(-b + disc) / 2.0, (-b - disc) / 2.0];
        for p in &set.rotor {
            let d = roots
                .iter()
                .map(|r| (r - p.s).norm())
                .fold(f64::INFINITY, f64::min);
            assert!(d < 1e-9 * p.s.norm(), "{} at {speed}", p.s);
        }
    }
    // Threshold of viscous rotating damping: Omega = w_n (1 + c_n / c_r) = 2055.5 rad/s.
    let t = stability(&m, &[0.0, 1000.0, 2000.0, 3000.0], &Control::default())
        .unwrap()
        .unwrap();
    let expected = (1.2e6f64 / 3.0).sqrt() * (1.0 + 90.0 / 40.0);
    assert!((t.speed - expected).abs() < 1e-6 * expected);
}

#[test]
fn campbell_tracks_forward_and_backward_and_keeps_internal_poles_out() {
    let m = DampedModel::build(&system(0.01, 0.0), &nvd(4)).unwrap();
    let speeds: Vec<f64> = (0..=40).map(|i| i as f64 * 0.1).collect();
    let c = campbell(&m, &speeds, &Control::default()).unwrap();
    assert_eq!(c.branches.len(), 2);
    let fwd = c
        .branches
        .iter()
        .find(|b| b.whirl == Whirl::Forward)
        .unwrap();
    let bwd = c
        .branches
        .iter()
        .find(|b| b.whirl == Whirl::Backward)
        .unwrap();
    assert!(
        fwd.poles
            .iter()
            .all(|p| p.is_some_and(|s| s.im > 0.9 && s.im < 1.1))
    );
    assert!(
        bwd.poles
            .iter()
            .all(|p| p.is_some_and(|s| s.im < -0.9 && s.im > -1.1))
    );
    assert_printed(
        fwd.poles[40].unwrap().re,
        "0.0049",
        "forward decay rate at 4",
    );
    assert_eq!(c.critical_speeds.len(), 1);
    assert!((c.critical_speeds[0] - 1.0).abs() < 0.03);
    // NVD with rotating damping only has a threshold, smoothed, above the critical speed.
    let t = c.threshold.unwrap();
    assert!(t.speed > 1.0 && t.speed < 4.0);
}

#[test]
fn hysteretic_campbell_reports_undefined_values_as_missing_not_invented() {
    // eta_n > 0, eta_r > 0 gives a band where two forward roots are consistent; and a grid
    // point inside a band with no consistent root must stay None. Check that every defined
    // forward value is one of the exact consistent roots.
    let (eta_n, eta_r) = (0.02, 0.04);
    let m = DampedModel::build(&system(eta_r, eta_n), &DampingModel::Hysteretic).unwrap();
    let speeds: Vec<f64> = (0..=200).map(|i| 0.9 + i as f64 * 0.001).collect();
    let c = campbell(&m, &speeds, &Control::default()).unwrap();
    let fwd = c
        .branches
        .iter()
        .find(|b| b.whirl == Whirl::Forward)
        .unwrap();
    let exact = |b: f64| c64::new(0.0, 1.0) * c64::new(1.0, eta_n + b * eta_r).sqrt();
    for (w, p) in speeds.iter().zip(&fwd.poles) {
        let s = p.expect("eta_n, eta_r > 0: a forward root is consistent everywhere");
        let b = if s.im > *w { 1.0 } else { -1.0 };
        assert!((s - exact(b)).norm() < 1e-12);
    }
    // The decay rate steps from -(eta_n + eta_r)/2 to -(eta_n - eta_r)/2 near Omega = 1.
    assert!((fwd.poles[0].unwrap().re + 0.03).abs() < 1e-4);
    assert!((fwd.poles[200].unwrap().re - 0.01).abs() < 1e-4);
}
