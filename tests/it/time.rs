//! Time responses: free decay against the poles, exact against implicit integration, the
//! paper's shock, run-ups through the first critical speed, blade loss, and the steady
//! unbalance response against the closed form.

use crate::common;

use common::paper_nvd;
use serde_json::{Value, json};
use whirl::analysis::control::Control;
use whirl::analysis::poles::{Whirl, poles_at};
use whirl::analysis::time::{Method, SpeedLaw, TimeResult, TimeSpec, time_response};
use whirl::analysis::unbalance::{SteadyUnbalance, unbalance_response};
use whirl::damping::DampedModel;
use whirl::fem::modal::ModalBasis;
use whirl::linalg::c64;
use whirl::model::api::RotorInput;
use whirl::model::damping::DampingModel;
use whirl::model::error::Invalid;
use whirl::model::loads::{Force, Pwl, Unbalance};
use whirl::model::rotor::{Limits, Rotor};
use whirl::system::RotorSystem;

fn system(rotor: Value) -> RotorSystem {
    let input: RotorInput = serde_json::from_value(rotor).unwrap();
    RotorSystem::assemble(&Rotor::parse(&input, &Limits::default()).unwrap()).unwrap()
}

fn example1() -> RotorSystem {
    let path = format!(
        "{}/examples/example1-nvd.modal.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let v: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    system(v["rotor"].clone())
}

fn pwl(points: &[[f64; 2]]) -> Pwl {
    Pwl::parse(points, "h", true, &mut Invalid::default()).unwrap()
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
        tolerance: 1e-6,
        max_steps: 5_000_000,
        reduce: false,
        generated: Default::default(),
    }
}

fn run(s: &RotorSystem, model: &DampingModel, spec: &TimeSpec, implicit: bool) -> TimeResult {
    time_response(
        s,
        &DampedModel::build(s, model).unwrap(),
        spec,
        implicit,
        &Control::default(),
    )
    .unwrap()
}

/// Decay rate and frequency of a damped cosine, from its peaks after `from`.
fn decay_and_frequency(time: &[f64], x: &[f64], from: f64) -> (f64, f64) {
    let mut peaks = vec![];
    for i in 1..x.len() - 1 {
        if time[i] >= from && x[i] > x[i - 1] && x[i] >= x[i + 1] && x[i] > 0.0 {
            // Parabola through the three samples.
            let (a, b, c) = (x[i - 1], x[i], x[i + 1]);
            let d = 0.5 * (a - c) / (a - 2.0 * b + c);
            let h = time[i + 1] - time[i];
            peaks.push((time[i] + d * h, b - 0.25 * (a - c) * d));
        }
    }
    let fit = |pts: &[(f64, f64)]| {
        let n = pts.len() as f64;
        let (sx, sy) = pts.iter().fold((0.0, 0.0), |(a, b), p| (a + p.0, b + p.1));
        let (mx, my) = (sx / n, sy / n);
        let (num, den) = pts.iter().fold((0.0, 0.0), |(a, b), p| {
            (a + (p.0 - mx) * (p.1 - my), b + (p.0 - mx).powi(2))
        });
        num / den
    };
    let sigma = fit(&peaks.iter().map(|p| (p.0, p.1.ln())).collect::<Vec<_>>());
    let period = fit(&peaks
        .iter()
        .enumerate()
        .map(|(i, p)| (i as f64, p.0))
        .collect::<Vec<_>>());
    (sigma, 2.0 * std::f64::consts::PI / period)
}

fn amplitude(r: &TimeResult) -> Vec<f64> {
    r.nodes[0].1.iter().map(|z| z.norm()).collect()
}

fn shock() -> Force {
    // The paper's shock: 0 to 10 kN in 11 ms at node 1 (z = 0.5 m), then released.
    Force {
        node: 1,
        direction: 0.0,
        history: pwl(&[[0.0, 0.0], [0.011, 1e4], [0.011, 0.0]]),
    }
}

#[test]
fn exact_and_implicit_agree_at_constant_speed() {
    // Two independent methods on the paper's shock plus an unbalance, NVD at 1400 rad/s.
    let s = example1();
    let unb = Unbalance {
        node: 2,
        amount: 1e-3,
        phase: 0.3,
        from: 0.02,
    };
    let mut sp = spec(
        SpeedLaw::Constant(1400.0),
        vec![shock()],
        vec![unb],
        0.1,
        1e-4,
        vec![1, 2],
    );
    let exact = run(&s, &paper_nvd(), &sp, false);
    assert_eq!(exact.method, Method::Exact);
    sp.tolerance = 1e-10;
    let implicit = run(&s, &paper_nvd(), &sp, true);
    assert_eq!(implicit.method, Method::Implicit);
    for k in 0..2 {
        let (a, b) = (&exact.nodes[k].1, &implicit.nodes[k].1);
        let peak = a.iter().map(|z| z.norm()).fold(0.0, f64::max);
        let err = a
            .iter()
            .zip(b)
            .map(|(x, y)| (x - y).norm())
            .fold(0.0, f64::max);
        assert!(err <= 1e-6 * peak, "node {}: {err:e} of {peak:e}", k + 1);
    }
}

#[test]
fn a_free_decay_has_the_decay_rate_and_frequency_of_its_pole() {
    // Viscous Jeffcott.
    let j = system(
        json!({"type": "jeffcott", "mass": 2.0, "stiffness": 5e4, "damping_nonrotating": 12.0}),
    );
    let pulse = Force {
        node: 0,
        direction: 0.0,
        history: pwl(&[[0.0, 0.0], [0.001, 100.0], [0.002, 0.0]]),
    };
    let r = run(
        &j,
        &DampingModel::Viscous,
        &spec(
            SpeedLaw::Constant(0.0),
            vec![pulse],
            vec![],
            1.0,
            1e-4,
            vec![0],
        ),
        false,
    );
    let x: Vec<f64> = r.nodes[0].1.iter().map(|z| z.re).collect();
    let (sigma, omega) = decay_and_frequency(&r.time, &x, 0.01);
    let (s_exact, w_exact) = (-3.0, (2.5e4f64 - 9.0).sqrt());
    assert!(
        (sigma - s_exact).abs() <= 0.005 * s_exact.abs(),
        "{sigma} vs {s_exact}"
    );
    assert!(
        (omega - w_exact).abs() <= 0.005 * w_exact,
        "{omega} vs {w_exact}"
    );

    // Example 1, E and NVD: a modal force M phi_1 excites the first mode alone at rest.
    let s = example1();
    let basis = ModalBasis::of(&s).unwrap();
    let f1 = basis.participation(&s.mass);
    for model in [DampingModel::Equivalent { modes: None }, paper_nvd()] {
        let forces: Vec<Force> = (0..4)
            .map(|node| {
                let a = 1e4 * f1[(node, 0)];
                Force {
                    node,
                    direction: 0.0,
                    history: pwl(&[[0.0, 0.0], [0.001, a], [0.002, 0.0]]),
                }
            })
            .collect();
        let r = run(
            &s,
            &model,
            &spec(SpeedLaw::Constant(0.0), forces, vec![], 1.2, 5e-5, vec![1]),
            false,
        );
        let x: Vec<f64> = r.nodes[0].1.iter().map(|z| z.re).collect();
        // After 0.4 s the internal poles (-35 1/s and faster) have died out.
        let (sigma, omega) = decay_and_frequency(&r.time, &x, 0.4);
        let pole = poles_at(&DampedModel::build(&s, &model).unwrap(), 0.0)
            .unwrap()
            .rotor
            .iter()
            .find(|p| p.whirl == Whirl::Forward)
            .unwrap()
            .s;
        assert!(
            (sigma - pole.re).abs() <= 0.005 * pole.re.abs(),
            "{model:?}: {sigma} vs {}",
            pole.re
        );
        assert!(
            (omega - pole.im).abs() <= 0.005 * pole.im,
            "{model:?}: {omega} vs {}",
            pole.im
        );
    }
}

#[test]
fn the_paper_shock_grows_with_equivalent_damping_and_decays_with_nonviscous() {
    let s = example1();
    let sp = spec(
        SpeedLaw::Constant(1400.0),
        vec![shock()],
        vec![],
        2.0,
        1e-3,
        vec![1],
    );
    // E: above its threshold, the whirl grows at the rate of the unstable pole.
    let e = DampingModel::Equivalent { modes: None };
    let unstable = poles_at(&DampedModel::build(&s, &e).unwrap(), 1400.0)
        .unwrap()
        .least_stable()
        .unwrap()
        .s;
    assert!(unstable.re > 0.0);
    let r = run(&s, &e, &sp, false);
    let a = amplitude(&r);
    let at = |t: f64| a[(t / 1e-3).round() as usize];
    let rate = (at(2.0) / at(1.0)).ln() / 1.0;
    assert!(
        (rate - unstable.re).abs() <= 0.01 * unstable.re,
        "growth {rate} vs pole {}",
        unstable.re
    );
    // NVD: bounded, and decaying.
    let r = run(&s, &paper_nvd(), &sp, false);
    let a = amplitude(&r);
    let peak = a.iter().cloned().fold(0.0, f64::max);
    let late = a[a.len() - 200..].iter().cloned().fold(0.0, f64::max);
    assert!(late < 0.5 * peak, "late {late} vs peak {peak}");
    assert!(
        a.windows(2).skip(1000).all(|w| w[1] <= w[0] * 1.01),
        "decaying after 1 s"
    );
}

/// Run-up from 250 rad/s (held 2 s, so the start transient dies) to 450 rad/s at `accel`.
fn run_up(accel: f64) -> (f64, f64) {
    let s = example1();
    let t1 = 2.0 + 200.0 / accel;
    let profile = pwl(&[[0.0, 250.0], [2.0, 250.0], [t1, 450.0]]);
    let law = SpeedLaw::Profile(profile);
    let unb = Unbalance {
        node: 1,
        amount: 1e-4,
        phase: 0.0,
        from: 0.0,
    };
    let sp = spec(law.clone(), vec![], vec![unb], t1, 1e-3, vec![1]);
    let r = run(&s, &paper_nvd(), &sp, false);
    assert_eq!(r.method, Method::Implicit);
    let a = amplitude(&r);
    let (i, peak) = a
        .iter()
        .enumerate()
        .skip(2000)
        .fold((0, 0.0), |m, (i, &v)| if v > m.1 { (i, v) } else { m });
    (peak, law.omega(r.time[i]))
}

#[test]
fn run_ups_through_the_first_critical_speed() {
    let s = example1();
    let model = DampedModel::build(&s, &paper_nvd()).unwrap();
    let speeds: Vec<f64> = (0..=400).map(|i| 300.0 + i as f64 * 0.25).collect();
    let dof = whirl::analysis::time::translation(&s, 1);
    let steady = unbalance_response(
        &s,
        &model,
        &speeds,
        &[SteadyUnbalance {
            dof,
            amount: 1e-4,
            phase: 0.0,
        }],
        &[dof],
        &Control::default(),
    )
    .unwrap();
    let (steady_peak, crit) = steady.iter().zip(&speeds).fold((0.0, 0.0), |m, (q, &w)| {
        if q[0].major() > m.0 {
            (q[0].major(), w)
        } else {
            m
        }
    });
    let (slow, w_slow) = run_up(10.0);
    let (medium, w_medium) = run_up(50.0);
    let (fast, w_fast) = run_up(500.0);
    eprintln!(
        "steady {steady_peak:e} at {crit}; slow {slow:e} at {w_slow}; medium {medium:e} at {w_medium}; fast {fast:e} at {w_fast}"
    );
    // A resonance peak, lower and later for faster run-ups; the slow one nears the steady one.
    assert!(fast < medium && medium < slow, "{fast} {medium} {slow}");
    assert!(
        w_fast > w_medium && w_medium > w_slow && w_slow >= crit - 2.0,
        "{w_fast} {w_medium} {w_slow} vs {crit}"
    );
    assert!(
        (slow - steady_peak).abs() < 0.05 * steady_peak,
        "slow {slow} vs steady {steady_peak}"
    );
    assert!((slow - steady_peak).abs() < (medium - steady_peak).abs());
}

#[test]
fn a_blade_loss_leaves_the_response_untouched_before_it_happens() {
    let s = example1();
    let unb = Unbalance {
        node: 2,
        amount: 5e-3,
        phase: 0.0,
        from: 0.05,
    };
    for implicit in [false, true] {
        let r = run(
            &s,
            &paper_nvd(),
            &spec(
                SpeedLaw::Constant(1000.0),
                vec![],
                vec![unb.clone()],
                0.1,
                1e-4,
                vec![1, 2],
            ),
            implicit,
        );
        for (_, h) in &r.nodes {
            for (t, z) in r.time.iter().zip(h) {
                if *t <= 0.05 {
                    assert_eq!(*z, c64::new(0.0, 0.0), "t = {t}");
                }
            }
            assert!(h.last().unwrap().norm() > 1e-6);
        }
    }
}

#[test]
fn unbalance_response_of_a_viscous_jeffcott_is_the_closed_form() {
    let (m, k, cn, cr, me) = (3.0, 1.2e6, 90.0, 40.0, 2e-4);
    let j = system(json!({"type": "jeffcott", "mass": m, "stiffness": k,
                          "damping_nonrotating": cn, "damping_rotating": cr}));
    let speeds: Vec<f64> = (0..=300).map(|i| i as f64 * 4.0).collect();
    for model in [DampingModel::Viscous, DampingModel::Hysteretic] {
        let dm = DampedModel::build(&j, &model).unwrap();
        let q = unbalance_response(
            &j,
            &dm,
            &speeds,
            &[SteadyUnbalance {
                dof: 0,
                amount: me,
                phase: 0.5,
            }],
            &[0],
            &Control::default(),
        )
        .unwrap();
        for (w, row) in speeds.iter().zip(&q) {
            // (k - m W^2 + i W c_n) Q = m e W^2 e^{i phase}: rotating damping does no work.
            let exact = c64::from_polar(me * w * w, 0.5) / c64::new(k - m * w * w, w * cn);
            assert!(
                (row[0].a - exact).norm() <= 1e-9 * exact.norm().max(1e-300),
                "{w}: {} vs {exact}",
                row[0].a
            );
            assert_eq!(
                row[0].b,
                c64::new(0.0, 0.0),
                "circular on isotropic supports"
            );
        }
    }
}
