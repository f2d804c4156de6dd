//! The paper's Example 1 (section 6.1, Figs. 5 and 7; MODEL.md section 6): an annular steel
//! tube on two hysteretically damped supports, 3 Timoshenko elements, rotations condensed by
//! Guyan reduction: 4 complex degrees of freedom.

use crate::common;

use axum::body::Body;
use axum::http::{Request, StatusCode};
use common::assert_printed;
use http_body_util::BodyExt;
use serde_json::{Value, json};
use tower::ServiceExt;
use whirl::analysis::poles::{PoleSet, Whirl, poles_at};
use whirl::damping::nonviscous::{self, BranchSet};
use whirl::damping::{DampedModel, ModelKind};
use whirl::fem::modal::ModalBasis;
use whirl::linalg::c64;
use whirl::model::api::RotorInput;
use whirl::model::damping::{DampingModel, NonviscousSpec};
use whirl::model::rotor::{Limits, Rotor};
use whirl::service::{Config, app};
use whirl::system::{Layout, RotorSystem};

fn example_file(name: &str) -> Value {
    let path = format!("{}/examples/{name}", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn example1() -> RotorSystem {
    let rotor: RotorInput =
        serde_json::from_value(example_file("example1-nvd.modal.json")["rotor"].clone()).unwrap();
    RotorSystem::assemble(&Rotor::parse(&rotor, &Limits::default()).unwrap()).unwrap()
}

/// The paper's NVD: 3 branches a decade apart; nonrotating dampers with sum nu_j gamma_j = m.
fn paper_nvd() -> DampingModel {
    let rot = BranchSet::new(3, 10.0, vec![1.0; 3]).unwrap();
    let gamma = rot.gamma().to_vec();
    let nonrot = BranchSet::new(3, 10.0, gamma.iter().map(|g| 1.0 / g).collect()).unwrap();
    DampingModel::Nonviscous(NonviscousSpec {
        rotating: rot,
        nonrotating: nonrot,
        modes: None,
    })
}

fn poles(model: &DampingModel, speed: f64) -> PoleSet {
    poles_at(&DampedModel::build(&example1(), model).unwrap(), speed).unwrap()
}

fn upper(set: &PoleSet) -> Vec<c64> {
    let mut v: Vec<c64> = set
        .rotor
        .iter()
        .filter(|p| p.whirl == Whirl::Forward)
        .map(|p| p.s)
        .collect();
    v.sort_by(|a, b| a.im.total_cmp(&b.im));
    v
}

#[test]
fn natural_frequencies_are_model_md_section_6() {
    let basis = ModalBasis::of(&example1()).unwrap();
    for (w, expected) in basis
        .omega
        .iter()
        .zip([370.2221, 979.6196, 1718.6236, 3029.8022])
    {
        assert!((w - expected).abs() < 1e-3, "{w} vs {expected}");
    }
    assert_eq!(example1().n(), 4);
}

#[test]
fn hysteretic_poles_at_rest_are_the_printed_ones() {
    let set = poles(&DampingModel::Hysteretic, 0.0);
    assert_eq!(set.rotor.len(), 8);
    let printed = [
        ("-6.0", "370.3"),
        ("-25.2", "980.1"),
        ("-40.7", "1719.1"),
        ("-43.1", "3030.1"),
    ];
    for (s, (re, im)) in upper(&set).iter().zip(printed) {
        assert_printed(s.re, re, "H decay rate");
        assert_printed(s.im, im, "H frequency");
    }
    // The backward poles mirror the forward ones at rest.
    for p in set.rotor.iter().filter(|p| p.whirl == Whirl::Backward) {
        assert!(
            set.rotor
                .iter()
                .any(|q| (q.s - p.s.conj()).norm() < 1e-9 * p.s.norm())
        );
    }
}

#[test]
fn equivalent_poles_at_rest_are_the_printed_ones() {
    let set = poles(&DampingModel::Equivalent { modes: None }, 0.0);
    let printed = [
        ("-6.0", "370.2"),
        ("-25.3", "979.3"),
        ("-40.7", "1718.1"),
        ("-43.1", "3029.5"),
    ];
    for (s, (re, im)) in upper(&set).iter().zip(printed) {
        assert_printed(s.re, re, "E decay rate");
        assert_printed(s.im, im, "E frequency");
    }
}

#[test]
fn nonviscous_poles_at_rest_are_the_32_printed_ones() {
    let set = poles(&paper_nvd(), 0.0);
    assert_eq!(
        set.rotor.len() + set.internal.len(),
        32,
        "28 degrees of freedom, 32 states"
    );
    assert_eq!(set.internal.len(), 24);
    // Three printed values lie just past a rounding boundary of ours: 3098.7505 (printed
    // 3098.7), -2973.4764 (-2973.47) and -158.1351 (-158.13), i.e. 1.6e-7, 4.6e-7 and 8.7e-7
    // relative. No single input variant (rounded gammas, shear factor, density, Poisson ratio)
    // moves all three across while keeping the other 29, and the paper's inputs carry far
    // less precision (rho = 7810 alone moves -2973.48 by 2e-2 per unit). Those three are
    // checked to the printed digit within 1e-6 relative; the other 29 strictly.
    let at_boundary = |printed: &str| ["3098.7", "-2973.47", "-158.13"].contains(&printed);
    let check = |v: f64, printed: &str, what: &str| {
        if at_boundary(printed) {
            let p: f64 = printed.parse().unwrap();
            let decimals = printed.split('.').nth(1).map_or(0, |d| d.len());
            let half = 0.5 * 10f64.powi(-(decimals as i32));
            assert!(
                (v - p).abs() <= half + 1e-6 * p.abs(),
                "{what}: {v} vs {printed}"
            );
        } else {
            assert_printed(v, printed, what);
        }
    };
    let complex = [
        ("-6.0", "378.5"),
        ("-25.2", "999.7"),
        ("-40.6", "1754.6"),
        ("-42.5", "3098.7"),
    ];
    for (s, (re, im)) in upper(&set).iter().zip(complex) {
        check(s.re, re, "NVD decay rate");
        check(s.im, im, "NVD frequency");
    }
    let real = [
        "-30298.02",
        "-30283.49",
        "-17186.24",
        "-17172.50",
        "-9796.20",
        "-9787.68",
        "-3702.22",
        "-3700.19",
        "-3029.80",
        "-2973.47",
        "-1718.62",
        "-1664.95",
        "-979.62",
        "-946.28",
        "-370.22",
        "-362.32",
        "-302.98",
        "-288.74",
        "-171.86",
        "-158.13",
        "-97.96",
        "-89.41",
        "-37.02",
        "-35.02",
    ];
    for (p, printed) in set.internal.iter().zip(real) {
        assert!(
            p.s.im.abs() < 1e-6,
            "internal poles are real at rest: {}",
            p.s
        );
        check(p.s.re, printed, "NVD internal pole");
    }
}

#[test]
fn physical_and_modal_nonviscous_forms_have_the_same_poles() {
    let system = example1();
    let DampingModel::Nonviscous(spec) = paper_nvd() else {
        unreachable!()
    };
    let basis = ModalBasis::of(&system).unwrap();
    let modal = nonviscous::modal_form(&system, &basis, &spec).unwrap();
    let modal = DampedModel {
        kind: ModelKind::Linear(Box::new(modal)),
        natural_frequencies: basis.omega.clone(),
        basis,
        layout: Layout::Single,
    };
    let physical = DampedModel::build(&system, &paper_nvd()).unwrap();
    for speed in [0.0, 1400.0, 3500.0] {
        let a: Vec<c64> = poles_at(&physical, speed)
            .unwrap()
            .all()
            .map(|p| p.s)
            .collect();
        let b: Vec<c64> = poles_at(&modal, speed)
            .unwrap()
            .all()
            .map(|p| p.s)
            .collect();
        assert_eq!(a.len(), b.len());
        for s in &a {
            let d = b
                .iter()
                .map(|t| (t - s).norm())
                .fold(f64::INFINITY, f64::min);
            assert!(
                d <= 1e-9 * s.norm().max(1.0),
                "{s} at {speed}: nearest modal pole {d} away"
            );
        }
    }
}

async fn campbell(file: &str, speeds: Value) -> Value {
    let mut body = example_file(file);
    body["speeds"] = speeds;
    let req = Request::post("/v1/campbell")
        .header("content-type", "application/json")
        .body(Body::from(body.to_string()))
        .unwrap();
    let resp = app(Config::default()).oneshot(req).await.unwrap();
    assert_eq!(resp.status(), StatusCode::OK);
    serde_json::from_slice(&resp.into_body().collect().await.unwrap().to_bytes()).unwrap()
}

/// (speeds, decay rates) of the branch `mode`, `whirl`.
fn branch(v: &Value, mode: u64, whirl: &str) -> (Vec<f64>, Vec<Option<f64>>) {
    let speeds = v["speeds"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    let b = v["branches"]
        .as_array()
        .unwrap()
        .iter()
        .find(|b| b["mode"] == mode && b["whirl"] == whirl)
        .unwrap();
    (
        speeds,
        b["decay_rate"]
            .as_array()
            .unwrap()
            .iter()
            .map(Value::as_f64)
            .collect(),
    )
}

fn at(speeds: &[f64], values: &[Option<f64>], speed: f64) -> f64 {
    let i = speeds
        .iter()
        .position(|s| (*s - speed).abs() < 1e-9)
        .unwrap();
    values[i].unwrap()
}

#[tokio::test]
async fn fig5_decay_rate_plot_has_the_features_the_paper_describes() {
    // The paper's plotted range: 0 to 3000 rad/s.
    let grid = json!({"start": 0.0, "stop": 3000.0, "count": 151});
    let h = campbell("example1-hysteretic.campbell.json", grid.clone()).await;
    let e = campbell("example1-equivalent.campbell.json", grid.clone()).await;
    let nv = campbell("example1-nvd.campbell.json", grid).await;
    let crit = h["critical_speeds"][0].as_f64().unwrap();
    assert!((crit - 370.7).abs() < 1.0, "first critical speed {crit}");

    // H: an abrupt step of the first forward decay rate at the critical speed, staying
    // negative; stable over the range.
    let (sp, hd) = branch(&h, 1, "forward");
    let before = at(&sp, &hd, 360.0);
    let after = at(&sp, &hd, 380.0);
    assert!(
        (before - at(&sp, &hd, 200.0)).abs() < 0.01,
        "flat below the critical speed"
    );
    assert!(after - before > 4.5, "step {before} -> {after}");
    assert!(after < 0.0);
    assert_eq!(h["threshold"], Value::Null);

    // E: the forward decay rate rises steadily through zero: a threshold in the supercritical
    // range, where H has none.
    let (sp, ed) = branch(&e, 1, "forward");
    let ed: Vec<f64> = ed.into_iter().map(Option::unwrap).collect();
    assert!(ed.windows(2).all(|w| w[1] > w[0]), "monotonic rise");
    let threshold = e["threshold"].as_f64().unwrap();
    assert!(
        threshold > 2.0 * crit && threshold < 1000.0,
        "E threshold {threshold}"
    );
    assert!(ed[0] < 0.0 && *ed.last().unwrap() > 0.0);
    // At rest E and H agree.
    assert!((ed[0] - hd[0].unwrap()).abs() < 0.05);
    let _ = sp;

    // NVD: the step is there but smoothed, and no threshold in the range.
    assert_eq!(nv["threshold"], Value::Null);
    let (sp, nd) = branch(&nv, 1, "forward");
    let low = at(&sp, &nd, 200.0);
    let high = at(&sp, &nd, 600.0);
    assert!(high - low > 4.0, "NVD step {low} -> {high}");
    let fine = campbell(
        "example1-nvd.campbell.json",
        json!({"start": 340.0, "stop": 400.0, "count": 61}),
    )
    .await;
    let (fs, fd) = branch(&fine, 1, "forward");
    let fd: Vec<f64> = fd.into_iter().map(Option::unwrap).collect();
    // Smoothed: the rise is spread over the band, no single 1 rad/s step carries most of it.
    let rise = fd.last().unwrap() - fd[0];
    let largest = fd.windows(2).map(|w| w[1] - w[0]).fold(0.0, f64::max);
    assert!(
        rise > 2.0 && largest < 0.5 * rise,
        "rise {rise}, largest step {largest}"
    );
    let _ = fs;
}

#[test]
fn gyroscopic_effect_stiffens_forward_and_softens_backward_whirl() {
    // An overhung disk with a large polar inertia on a cantilever-like shaft.
    let rotor: RotorInput = serde_json::from_value(json!({
        "type": "beam",
        "materials": {"steel": {"young_modulus": 2.1e11, "density": 7800, "poisson_ratio": 0.3}},
        "shaft": [{"length": 0.6, "outer_diameter": 0.04, "material": "steel", "elements": 6}],
        "disks": [{"node": 6, "mass": 20.0, "polar_inertia": 0.4, "transverse_inertia": 0.2}],
        "supports": [{"node": 0, "stiffness": 1e8}, {"node": 2, "stiffness": 1e8}]
    }))
    .unwrap();
    let system = RotorSystem::assemble(&Rotor::parse(&rotor, &Limits::default()).unwrap()).unwrap();
    let model = DampedModel::build(&system, &DampingModel::Viscous).unwrap();
    let rest = poles_at(&model, 0.0).unwrap();
    let spin = poles_at(&model, 2000.0).unwrap();
    let first = |set: &PoleSet, w: Whirl| {
        set.rotor
            .iter()
            .filter(|p| p.whirl == w)
            .map(|p| p.s.im.abs())
            .fold(f64::INFINITY, f64::min)
    };
    let w0 = first(&rest, Whirl::Forward);
    assert!((w0 - first(&rest, Whirl::Backward)).abs() < 1e-9 * w0);
    assert!(first(&spin, Whirl::Forward) > 1.05 * w0, "forward stiffens");
    assert!(
        first(&spin, Whirl::Backward) < 0.95 * w0,
        "backward softens"
    );
}

#[test]
fn equivalent_damping_on_a_reduced_mode_set_damps_only_those_modes() {
    let full = poles(&DampingModel::Equivalent { modes: None }, 0.0);
    let two = poles(&DampingModel::Equivalent { modes: Some(2) }, 0.0);
    let (f, t) = (upper(&full), upper(&two));
    // The retained modes keep their damping (the truncation only drops small off-diagonal
    // couplings to the others); the dropped ones have none: no viscous damping in Example 1.
    for m in 0..2 {
        assert!(
            (f[m] - t[m]).norm() < 1e-3 * f[m].norm(),
            "mode {}: {} vs {}",
            m + 1,
            f[m],
            t[m]
        );
    }
    for (m, s) in t.iter().enumerate().skip(2) {
        assert!(
            s.re.abs() < 1e-9 * s.norm(),
            "mode {} should be undamped: {s}",
            m + 1
        );
    }
}
