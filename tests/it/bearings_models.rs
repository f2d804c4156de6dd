//! The damping models and the time domain on rotors whose supports are not isotropic:
//! nonviscous branches approaching the hysteretic model, free decay at the least-damped pole,
//! the exact and the implicit time responses agreeing, and a slow run-up through tabulated
//! bearings following the steady unbalance response.

use serde_json::{Value, json};
use whirl::analysis::control::Control;
use whirl::analysis::poles::{Whirl, poles_at};
use whirl::analysis::time::{Method, SpeedLaw, TimeSpec, time_response};
use whirl::analysis::unbalance::{SteadyUnbalance, unbalance_response};
use whirl::damping::DampedModel;
use whirl::linalg::c64;
use whirl::model::Invalid;
use whirl::model::Limits;
use whirl::model::api::RotorInput;
use whirl::model::damping::DampingModel;
use whirl::model::loads::{Force, Pwl, Unbalance};
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

/// ROSS's anisotropic rotor A with a lossy shaft (0.02) and lossy bearings (0.05).
fn lossy_aniso() -> RotorSystem {
    let mut r = data("aniso.json")["rotor"].clone();
    r["materials"]["steel"]["loss_factor"] = json!(0.02);
    for s in r["supports"].as_array_mut().unwrap() {
        s["loss_factor"] = json!(0.05);
    }
    let s = system(&r);
    assert_eq!(s.layout(), Layout::Doubled);
    s
}

/// Rotor A on bearings that are anisotropic (kyy = 2 kxx) but hold no viscous damping nor
/// cross-coupling: all damping is the loss factors (`shaft`, 0.05 bearings), so the modal
/// (equivalent and nonviscous) models hold to second order in the loss.
fn hysteretic_aniso(shaft: f64) -> RotorSystem {
    let mut r = data("aniso.json")["rotor"].clone();
    r["materials"]["steel"]["loss_factor"] = json!(shaft);
    for s in r["supports"].as_array_mut().unwrap() {
        let (kxx, kyy) = (s["kxx"].clone(), s["kyy"].clone());
        *s = json!({"node": s["node"], "kxx": kxx, "kyy": kyy, "loss_factor": 0.05});
    }
    let s = system(&r);
    assert_eq!(s.layout(), Layout::Doubled);
    s
}

#[test]
fn the_equivalent_model_on_x_y_modes_has_the_hysteretic_decay_rates_at_rest() {
    // Both losses (0.02 shaft, 0.05 bearings) on the x/y modes: the same first-order decay as
    // H, mode by mode, although the shaft's share differs between a mode's x and y partners.
    let s = hysteretic_aniso(0.02);
    let at =
        |m: Value| poles_at(&DampedModel::build(&s, &damping(m, s.n())).unwrap(), 0.0).unwrap();
    let (h, e) = (
        at(json!({"model": "hysteretic"})),
        at(json!({"model": "equivalent"})),
    );
    for p in h.rotor.iter().filter(|p| p.s.im.abs() < 2000.0) {
        let q = e
            .rotor
            .iter()
            .min_by(|a, b| (a.s - p.s).norm().total_cmp(&(b.s - p.s).norm()))
            .unwrap();
        let err = (q.s.re - p.s.re).abs() / p.s.re.abs();
        // eta = 0.05 for the bearings: second order is a few 1e-3.
        assert!(err < 5e-3, "{} against {}: {err:.2e}", q.s, p.s);
    }
}

#[test]
fn dense_nonviscous_branches_reach_the_hysteretic_decay_rates_to_the_causal_limit() {
    // Bearing loss (0.05) on anisotropic bearings: the nonrotating dampers serve the x/y
    // modes. Dense branches make the loss factor flat; the decay rates then differ from H's
    // only by what causality requires: a flat loss eta comes with a storage stiffness rising
    // as (2 eta / pi) ln(omega) (Kramers-Kronig), which H, not causal, lacks; it slows the
    // decay by a relative eta/pi at most (1.6 %). That difference scales with eta (0.54 % at
    // eta = 0.02 on this rotor, 1.35 % at 0.05). nu_j = 1 / (1 + (w0/d_j)^2) keeps the storage
    // at each damper's tuning frequency (plain Maxwell branches would add about eta per
    // decade they span).
    let s = hysteretic_aniso(0.0);
    let eta: f64 = 0.05;
    let nu = |m: usize, a: f64| -> Vec<f64> {
        (1..=m)
            .map(|j| 1.0 / (1.0 + a.powf(m as f64 + 1.0 - 2.0 * j as f64)))
            .collect()
    };
    let (m, a) = (9, 3.0);
    let nvd = damping(
        json!({"model": "nonviscous",
               "rotating": {"branches": m, "spacing": a, "nu": nu(m, a)},
               "nonrotating": {"branches": m, "spacing": a, "nu": nu(m, a)}}),
        s.n(),
    );
    let h = DampedModel::build(&s, &damping(json!({"model": "hysteretic"}), s.n())).unwrap();
    let nvd = DampedModel::build(&s, &nvd).unwrap();
    // At speed the gyroscopic coupling mixes x/y modes of close frequencies (1556 and 1659
    // rad/s here), and the loss between them, which every modal model (E and NVD, as the
    // paper's eq. 28) drops, acts at first order: E is 10 % off H there too. At rest the x/y
    // modes are the modes.
    for speed in [0.0] {
        let reference = poles_at(&h, speed).unwrap();
        let set = poles_at(&nvd, speed).unwrap();
        let mut worst: f64 = 0.0;
        for p in reference.rotor.iter().filter(|p| p.s.im.abs() < 2000.0) {
            let q = set
                .rotor
                .iter()
                .min_by(|a, b| (a.s - p.s).norm().total_cmp(&(b.s - p.s).norm()))
                .unwrap();
            worst = worst.max((q.s.re - p.s.re).abs() / p.s.re.abs());
            assert!(
                (q.s.im - p.s.im).abs() <= 1e-3 * p.s.im.abs(),
                "{} against {}",
                q.s,
                p.s
            );
        }
        println!("at {speed} rad/s: NVD decay rates within {worst:.2e} of H's");
        assert!(worst <= eta / std::f64::consts::PI, "{worst}");
    }
}

fn pwl(points: &[[f64; 2]]) -> Pwl {
    let mut bad = Invalid::default();
    Pwl::parse(points, "h", true, &mut bad).unwrap()
}

fn spec(
    speed: SpeedLaw,
    forces: Vec<Force>,
    unbalances: Vec<Unbalance>,
    duration: f64,
    dt: f64,
    nodes: Vec<usize>,
) -> TimeSpec {
    TimeSpec {
        speed,
        forces,
        unbalances,
        duration,
        output_interval: dt,
        nodes,
        tolerance: 1e-8,
        max_steps: 2_000_000,
        reduce: false,
        generated: Default::default(),
    }
}

/// Decay rate from the peaks of `|r|` after `from` (a straight line through their logs).
fn decay(time: &[f64], amp: &[f64], from: f64) -> f64 {
    let pts: Vec<(f64, f64)> = (1..amp.len() - 1)
        .filter(|&i| time[i] >= from && amp[i] > amp[i - 1] && amp[i] >= amp[i + 1])
        .map(|i| (time[i], amp[i].ln()))
        .collect();
    let n = pts.len() as f64;
    let (mx, my) = pts
        .iter()
        .fold((0.0, 0.0), |(a, b), p| (a + p.0 / n, b + p.1 / n));
    let (num, den) = pts.iter().fold((0.0, 0.0), |(a, b), p| {
        (a + (p.0 - mx) * (p.1 - my), b + (p.0 - mx).powi(2))
    });
    num / den
}

#[test]
fn a_free_decay_on_anisotropic_bearings_has_the_rate_of_the_least_damped_pole() {
    let s = system(&data("aniso.json")["rotor"]);
    for (model, speed) in [
        (json!({"model": "viscous"}), 300.0),
        (json!({"model": "viscous"}), 0.0),
    ] {
        let model = damping(model, s.n());
        let m = DampedModel::build(&s, &model).unwrap();
        let least = poles_at(&m, speed)
            .unwrap()
            .rotor
            .iter()
            .map(|p| p.s)
            .max_by(|a, b| a.re.total_cmp(&b.re))
            .unwrap();
        // A short kick at the disk, then free motion for many periods of the slowest mode.
        let kick = Force {
            node: 5,
            direction: 0.4,
            history: pwl(&[[0.0, 0.0], [0.002, 500.0], [0.004, 0.0]]),
        };
        let r = time_response(
            &s,
            &m,
            &spec(
                SpeedLaw::Constant(speed),
                vec![kick],
                vec![],
                8.0,
                2e-4,
                vec![5],
            ),
            false,
            &Control::default(),
        )
        .unwrap();
        assert_eq!(r.method, Method::Exact);
        // |r| of an elliptical orbit pulses at twice its frequency; its peaks still decay at
        // the pole's rate.
        let amp: Vec<f64> = r.nodes[0].1.iter().map(|z| z.norm()).collect();
        let sigma = decay(&r.time, &amp, 3.0);
        println!("at {speed} rad/s: measured decay {sigma:.5}, least-damped pole {least:.5}");
        assert!(
            (sigma - least.re).abs() <= 0.01 * least.re.abs(),
            "{sigma} against {}",
            least.re
        );
    }
}

#[test]
fn exact_and_implicit_agree_on_doubled_coordinates_under_nvd() {
    let s = lossy_aniso();
    let m = DampedModel::build(
        &s,
        &damping(json!({"model": "nonviscous", "modes": 4}), s.n()),
    )
    .unwrap();
    let mut sp = spec(
        SpeedLaw::Constant(400.0),
        vec![Force {
            node: 3,
            direction: 1.0,
            history: pwl(&[[0.0, 0.0], [0.01, 2e3], [0.01, 0.0]]),
        }],
        vec![Unbalance {
            node: 5,
            amount: 1e-4,
            phase: 0.2,
            from: 0.03,
        }],
        0.1,
        1e-4,
        vec![2, 5],
    );
    let exact = time_response(&s, &m, &sp, false, &Control::default()).unwrap();
    sp.tolerance = 1e-10;
    let implicit = time_response(&s, &m, &sp, true, &Control::default()).unwrap();
    assert_eq!(
        (exact.method, implicit.method),
        (Method::Exact, Method::Implicit)
    );
    for k in 0..2 {
        let (a, b) = (&exact.nodes[k].1, &implicit.nodes[k].1);
        let peak = a.iter().map(|z| z.norm()).fold(0.0, f64::max);
        let err = a
            .iter()
            .zip(b)
            .map(|(x, y)| (x - y).norm())
            .fold(0.0, f64::max);
        println!(
            "node {}: exact against implicit {:.2e} of the peak",
            exact.nodes[k].0,
            err / peak
        );
        assert!(err <= 1e-6 * peak, "{err:e} of {peak:e}");
    }
}

#[test]
fn a_slow_run_up_through_tabulated_bearings_follows_the_steady_response() {
    // Case C: both bearings tabulated from 200 to 2500 rad/s; a run-up from 300 to 900 rad/s
    // in 10 s, far from the critical speeds, is quasi-steady.
    let s = system(&data("speed_dependent.json")["rotor"]);
    assert!(s.speed_dependent());
    let m = DampedModel::build(&s, &damping(json!({"model": "viscous"}), s.n())).unwrap();
    let (w0, w1, duration) = (300.0, 900.0, 10.0);
    let law = SpeedLaw::Profile(pwl(&[[0.0, w0], [1.0, w0], [1.0 + duration, w1]]));
    let unb = Unbalance {
        node: 5,
        amount: 1e-4,
        phase: 0.0,
        from: 0.0,
    };
    let mut sp = spec(
        law.clone(),
        vec![],
        vec![unb],
        1.0 + duration,
        1e-3,
        vec![5],
    );
    sp.tolerance = 1e-6;
    let r = time_response(&s, &m, &sp, false, &Control::default()).unwrap();
    assert_eq!(r.method, Method::Implicit);
    for target in [400.0, 600.0, 800.0] {
        let t = 1.0 + duration * (target - w0) / (w1 - w0);
        // The largest |r| over the revolutions around t: the semi-major axis there.
        let window = 2.0 * std::f64::consts::TAU / target;
        let major = r
            .time
            .iter()
            .zip(&r.nodes[0].1)
            .filter(|(ti, _)| (**ti - t).abs() <= window)
            .map(|(_, z)| z.norm())
            .fold(0.0, f64::max);
        let steady = unbalance_response(
            &s,
            &m,
            &[target],
            &[SteadyUnbalance {
                dof: s.translation(5).unwrap(),
                amount: 1e-4,
                phase: 0.0,
            }],
            &[s.translation(5).unwrap()],
            &Control::default(),
        )
        .unwrap()[0][0]
            .major();
        println!("at {target} rad/s: run-up {major:.4e}, steady {steady:.4e}");
        assert!(
            (major - steady).abs() <= 0.02 * steady,
            "{major} against {steady}"
        );
    }
    let _ = (c64::new(0.0, 0.0), Whirl::Forward);
}
