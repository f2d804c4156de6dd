//! The README's examples, run as it runs them (the bundled `examples/` bodies POSTed through the
//! app), with every figure it prints about them asserted as printed.

use crate::common;

use common::{assert_printed, post_json};
use serde_json::{Value, json};

fn example(name: &str) -> Value {
    let text = std::fs::read_to_string(format!("examples/{name}")).unwrap();
    serde_json::from_str(&text).unwrap()
}

/// POSTs `examples/NAME.ENDPOINT.json` to `/v1/ENDPOINT`, as the README's curl lines do.
async fn run(name: &str) -> Value {
    let endpoint = name.split('.').nth(1).unwrap();
    let (status, v) = post_json(&format!("/v1/{endpoint}"), &example(name)).await;
    assert_eq!(status, 200, "{name}: {v}");
    v
}

fn num(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

fn numbers(v: &Value) -> Vec<f64> {
    v.as_array().unwrap().iter().map(num).collect()
}

fn poles<'a>(v: &'a Value, whirl: &str) -> Vec<&'a Value> {
    let all = v["poles"].as_array().unwrap();
    all.iter().filter(|p| p["whirl"] == whirl).collect()
}

/// Nodes of a beam rotor as its segments count them.
fn nodes(rotor: &Value) -> u64 {
    let shaft = rotor["shaft"].as_array().unwrap();
    shaft
        .iter()
        .map(|s| s["elements"].as_u64().unwrap_or(1))
        .sum::<u64>()
        + 1
}

#[test]
fn the_bundled_rotors_are_the_ones_described() {
    // "Example 1, an annular steel tube on two hysteretically damped supports, with 3
    // Timoshenko elements and Guyan reduction to 4 degrees of freedom".
    let e1 = example("example1-nvd.modal.json")["rotor"].clone();
    assert_eq!(nodes(&e1), 4);
    assert_eq!(e1["reduction"]["guyan"], "translations");
    assert_eq!(e1["supports"].as_array().unwrap().len(), 2);
    assert!(num(&e1["shaft"][0]["inner_diameter"]) > 0.0);
    // "a 2 m compressor rotor of 100 elements carrying six impellers, a coupling hub and a
    // thrust collar, on two damped bearings (101 degrees of freedom after Guyan reduction)".
    let c = example("compressor-nvd.campbell.json")["rotor"].clone();
    let length: f64 = c["shaft"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| num(&s["length"]))
        .sum();
    assert!((length - 2.0).abs() < 1e-12, "{length}");
    assert_eq!(nodes(&c), 101);
    assert_eq!(c["disks"].as_array().unwrap().len(), 8);
    let bearings = c["supports"].as_array().unwrap();
    assert_eq!(bearings.len(), 2);
    assert!(bearings.iter().all(|b| num(&b["damping"]) > 0.0));
    assert_eq!(c["reduction"]["guyan"], "translations");
    // "The paper's shock on Example 1 at 1400 rad/s (Fig. 6): 10 kN ramped over 11 ms, then
    // released."
    for name in [
        "example1-shock-nvd.time-response.json",
        "example1-shock-equivalent.time-response.json",
    ] {
        let s = example(name);
        assert_eq!(num(&s["speed"]), 1400.0);
        assert_eq!(
            s["forces"][0]["history"],
            json!([[0, 0], [0.011, 10000], [0.011, 0]])
        );
    }
    // "A run-up through the first critical speed (0 to 600 rad/s in 3 s, unbalance at node 1)."
    let r = example("example1-runup-nvd.time-response.json");
    assert_eq!(r["speed_profile"], json!([[0, 0], [3, 600]]));
    assert_eq!(r["unbalances"][0]["node"], 1);
    // "Blade loss on the compressor: 2 g m of unbalance appears at node 45 at t = 50 ms, at
    // 1000 rad/s."
    let b = example("compressor-bladeloss-nvd.time-response.json");
    assert_eq!(num(&b["speed"]), 1000.0);
    let u = &b["unbalances"][0];
    assert_eq!(
        (u["node"].as_u64(), num(&u["amount"]), num(&u["from"])),
        (Some(45), 0.002, 0.05)
    );
    // "A shaft on two fluid-film bearings tabulated at five speeds".
    let f = example("fluid-film.unbalance-response.json");
    let s = f["rotor"]["supports"].as_array().unwrap();
    assert_eq!(s.len(), 2);
    assert!(s.iter().all(|b| b["speeds"].as_array().unwrap().len() == 5));
    // "ROSS's compressor example with its 14 tabulated bearings and seals".
    for name in [
        "ross-compressor.campbell.json",
        "ross-compressor.modal.json",
    ] {
        let s = example(name)["rotor"]["supports"]
            .as_array()
            .unwrap()
            .clone();
        assert_eq!(s.len(), 14);
        assert!(s.iter().all(|b| b["speeds"].is_array()));
    }
    // "a 1.5 m shaft with a 32.6 kg disk (ROSS's run_ucs): the 4 lowest modes against support
    // stiffness 1e6 to 1e11 N/m".
    let m = example("rotor-a.critical-speed-map.json");
    assert_eq!(num(&m["rotor"]["shaft"][0]["length"]), 1.5);
    assert_eq!(num(&m["rotor"]["disks"][0]["mass"]), 32.6);
    assert_eq!(m["modes"], 4);
    assert_eq!(
        (num(&m["stiffness"]["start"]), num(&m["stiffness"]["stop"])),
        (1e6, 1e11)
    );
    // "Level I screen (API 617) of Example 1 at 600 rad/s under hysteretic damping ... at node 2"
    let l = example("example1-hysteretic.level1.json");
    assert_eq!(
        (num(&l["speed"]), &l["node"], &l["damping"]["model"]),
        (600.0, &json!(2), &json!("hysteretic"))
    );
    let fr = example("example1-hysteretic.frequency-response.json");
    assert_eq!(num(&fr["speed"]), 600.0);
}

#[tokio::test]
async fn jeffcott_nvd_poles_at_four() {
    // "Poles at Ω* = 4 with 4 rotating Maxwell branches (paper section 4): the forward whirl is
    // unstable (0.0049 + 1.0183i), and there are 4 internal poles near -d_j + 4i."
    let v = run("jeffcott-nvd.modal.json").await;
    let f = poles(&v, "forward");
    assert_eq!(f.len(), 1);
    assert_printed(num(&f[0]["decay_rate"]), "0.0049", "forward decay rate");
    assert_printed(num(&f[0]["frequency"]), "1.0183", "forward frequency");
    let internal = poles(&v, "internal");
    assert_eq!(internal.len(), 4);
    for p in internal {
        assert!(num(&p["decay_rate"]) < 0.0);
        assert!((num(&p["frequency"]) - 4.0).abs() < 2e-3, "{p}");
    }
}

#[tokio::test]
async fn jeffcott_thresholds() {
    // "Threshold of instability with equivalent damping, η_r = 0.01, η_n = 0.02: eq. (10)
    // gives 3." and the answer printed beneath it.
    let v = run("jeffcott-equivalent.stability.json").await;
    assert_printed(num(&v["threshold"]), "3.0", "threshold");
    assert_eq!((&v["mode"], &v["whirl"]), (&json!(1), &json!("forward")));
    assert_printed(num(&v["frequency"]), "1.0000000000000002", "frequency");
    assert_eq!(v["range"], json!([0.0, 5.0]));
    // "The same rotor with hysteretic damping is stable at every speed (η_n > η_r)".
    let v = run("jeffcott-hysteretic.stability.json").await;
    for k in ["threshold", "mode", "whirl", "frequency"] {
        assert_eq!(v[k], Value::Null, "{k}");
    }
    assert_eq!(v["range"], json!([0.0, 5.0]));
    // "the forward decay rate steps from -0.005 to +0.005 at the critical speed, which is
    // also the threshold."
    let v = run("jeffcott-hysteretic.campbell.json").await;
    let crit = numbers(&v["critical_speeds"]);
    assert_eq!(crit.len(), 1);
    let threshold = num(&v["threshold"]);
    assert!(
        (threshold - crit[0]).abs() < 1e-6 * crit[0],
        "{threshold} {crit:?}"
    );
    let speeds = numbers(&v["speeds"]);
    let forward = v["branches"]
        .as_array()
        .unwrap()
        .iter()
        .find(|b| b["whirl"] == "forward");
    let d = numbers(&forward.unwrap()["decay_rate"]);
    for (w, d) in speeds.iter().zip(&d) {
        let printed = if *w < crit[0] { "-0.005" } else { "0.005" };
        assert_printed(*d, printed, &format!("forward decay rate at {w}"));
    }
}

#[tokio::test]
async fn example1_nvd_poles() {
    // "Example 1 at rest with nonviscous damping: the paper's 32 poles (8 rotor, 24 internal),
    // with mode shapes."
    let v = run("example1-nvd.modal.json").await;
    assert_eq!(v["poles"].as_array().unwrap().len(), 32);
    let rotor = poles(&v, "forward").len() + poles(&v, "backward").len();
    assert_eq!(rotor, 8);
    let internal = poles(&v, "internal");
    assert_eq!(internal.len(), 24);
    assert!(poles(&v, "forward").iter().all(|p| p["shape"].is_array()));
    assert_eq!(v["natural_frequencies"].as_array().unwrap().len(), 4);
    // "Stiffness is no problem: the nonviscous internal poles reach −30,000 1/s in Example 1."
    let fastest = internal
        .iter()
        .map(|p| num(&p["decay_rate"]))
        .fold(0.0, f64::min);
    assert!((fastest / -30_000.0 - 1.0).abs() < 0.02, "{fastest}");
}

#[tokio::test]
async fn train_criticals_and_stability() {
    // "forward critical speeds 426.7, 468.9, 712.1 and 1348.7 rad/s, stable to 1500 rad/s"
    let v = run("train-hysteretic.campbell.json").await;
    let crit = numbers(&v["critical_speeds"]);
    assert_eq!(crit.len(), 4, "{crit:?}");
    for (c, printed) in crit.iter().zip(["426.7", "468.9", "712.1", "1348.7"]) {
        assert_printed(*c, printed, "train critical speed");
    }
    assert_eq!(v["threshold"], Value::Null);
    // "each forward mode loses damping where it crosses the 1x line": the decay rate of
    // modes 1F to 3F jumps up between the speeds either side of their critical speed.
    let speeds = numbers(&v["speeds"]);
    for (mode, c) in (1..=3).zip(&crit) {
        let b = v["branches"]
            .as_array()
            .unwrap()
            .iter()
            .find(|b| b["mode"] == mode && b["whirl"] == "forward")
            .unwrap();
        let sigma = numbers(&b["decay_rate"]);
        let k = speeds.iter().position(|w| w > c).unwrap();
        let (below, above) = (sigma[k - 1], sigma[k]);
        let step = sigma[k - 2] - sigma[k - 1];
        println!("{mode}F at {c:.1} rad/s: decay rate {below:.3} -> {above:.3} 1/s");
        assert!(
            above - below > 10.0 * step.abs(),
            "{mode}F: {below} -> {above}"
        );
    }
}

#[tokio::test]
async fn compressor_branches_criticals_and_threshold() {
    // "The compressor: branches below 6000 rad/s, critical speeds 450 and 1347 rad/s; stable
    // with nonviscous damping, unstable from 2931 rad/s with equivalent damping."
    let v = run("compressor-nvd.campbell.json").await;
    for b in v["branches"].as_array().unwrap() {
        for f in b["frequency"]
            .as_array()
            .unwrap()
            .iter()
            .flat_map(Value::as_f64)
        {
            assert!(f.abs() < 6000.0, "{f}");
        }
    }
    let crit = numbers(&v["critical_speeds"]);
    assert_eq!(crit.len(), 2, "{crit:?}");
    assert_printed(crit[0], "450", "first critical speed");
    assert_printed(crit[1], "1347", "second critical speed");
    assert_eq!(v["threshold"], Value::Null);
    let v = run("compressor-equivalent.stability.json").await;
    assert_printed(
        num(&v["threshold"]),
        "2931",
        "threshold, equivalent damping",
    );
}

#[tokio::test]
async fn example1_nonviscous_fit() {
    // "The branches per damper are chosen so that the loss factor stays within 15% over 30 to
    // 40000 rad/s (5 here), and there is a fit report for every damper."
    let v = run("example1-nvd-fit.damping.json").await;
    assert_eq!(
        (&v["branches_rotating"], &v["branches_nonrotating"]),
        (&json!(5), &json!(5))
    );
    let dampers = v["dampers"].as_array().unwrap();
    // 4 modes, a rotating and a nonrotating damper each.
    assert_eq!(dampers.len(), 8);
    for d in dampers {
        assert_eq!(d["band"], json!([30.0, 40000.0]));
        assert!(num(&d["max_deviation"]) <= 0.15, "{d}");
        assert_eq!(d["branches"], 5);
    }
}

/// Whirl radius `|x + i y|` of the first reported node, with the output times.
fn whirl(v: &Value) -> (Vec<f64>, Vec<f64>) {
    let t = numbers(&v["time"]);
    let n = &v["nodes"][0];
    let r = numbers(&n["x"])
        .iter()
        .zip(numbers(&n["y"]))
        .map(|(x, y)| x.hypot(y))
        .collect();
    (t, r)
}

#[tokio::test]
async fn example1_shock() {
    // "With nonviscous damping the whirl builds to 12.6 mm (at 11.5 ms, node 1) and decays."
    let v = run("example1-shock-nvd.time-response.json").await;
    assert_eq!(v["nodes"][0]["node"], 1);
    let (t, r) = whirl(&v);
    let (i, peak) = r
        .iter()
        .enumerate()
        .fold((0, 0.0), |m, (i, &x)| if x > m.1 { (i, x) } else { m });
    assert_printed(peak * 1e3, "12.6", "shock peak, mm");
    assert_printed(t[i] * 1e3, "11.5", "time of the peak, ms");
    let last = r[r.len() - 1];
    assert!(last < 0.5 * peak, "decays: {last} of {peak}");
    // "With equivalent damping the rotor is above its threshold and the whirl grows without
    // bound": each tenth of the run whirls wider than the one before, after the release.
    let v = run("example1-shock-equivalent.time-response.json").await;
    let (_, r) = whirl(&v);
    let tenth = r.len() / 10;
    let maxima: Vec<f64> = r
        .chunks(tenth)
        .map(|c| c.iter().cloned().fold(0.0, f64::max))
        .collect();
    assert!(maxima[1..].windows(2).all(|w| w[1] > w[0]), "{maxima:?}");
    assert!(maxima[maxima.len() - 1] > 2.0 * peak, "{maxima:?}");
}

#[tokio::test]
async fn example1_unbalance_peak() {
    // "The steady unbalance response against speed (peak at the first critical speed, 373
    // rad/s)."
    let v = run("example1-nvd.unbalance-response.json").await;
    let campbell = run("example1-nvd.campbell.json").await;
    let first_critical = numbers(&campbell["critical_speeds"])[0];
    for node in v["nodes"].as_array().unwrap() {
        let peak = num(&node["peaks"][0]["speed"]);
        assert_printed(peak, "373", "unbalance peak, rad/s");
        assert!(
            (peak / first_critical - 1.0).abs() < 0.01,
            "{peak} {first_critical}"
        );
    }
}

#[tokio::test]
async fn bearings_and_seals() {
    // "elliptical orbits, with x and y amplitudes and phases and the semi-axes of each node's
    // orbit."
    let v = run("fluid-film.unbalance-response.json").await;
    let node = &v["nodes"][0];
    for k in [
        "x_amplitude",
        "x_phase",
        "y_amplitude",
        "y_phase",
        "major",
        "minor",
    ] {
        assert!(node[k].is_array(), "{k} in {node}");
    }
    // "as a Campbell diagram and at one speed (each pole with its whirl ratio)."
    let v = run("ross-compressor.modal.json").await;
    let rotor = v["poles"].as_array().unwrap();
    assert!(
        rotor
            .iter()
            .all(|p| p["whirl"] == "internal" || p["whirl_ratio"].is_number())
    );
}

#[tokio::test]
async fn dimensional_jeffcott() {
    // The inline request of docs/physics.md, as printed.
    let body = json!({
      "rotor": {"type": "jeffcott", "mass": 12, "stiffness": 2e6,
                "loss_factor_rotating": 0.004, "damping_nonrotating": 150},
      "damping": {"model": "nonviscous"},
      "speeds": {"start": 0, "stop": 2000, "count": 101}});
    let (status, v) = post_json("/v1/campbell", &body).await;
    assert_eq!(status, 200, "{v}");
    // sqrt(k/m) = 408.2 rad/s.
    let crit = numbers(&v["critical_speeds"]);
    assert!((crit[0] - (2e6f64 / 12.0).sqrt()).abs() < 1.0, "{crit:?}");
}

#[tokio::test]
async fn audit_examples() {
    // "bearing reactions (432.4 N each)".
    let v = run("ross-rotor-example.static.json").await;
    let supports = v["supports"].as_array().unwrap();
    assert_eq!(supports.len(), 2);
    for s in supports {
        assert_printed(num(&s["reaction"]), "432.4", "reaction, N");
    }
    // "the 4 lowest modes ... and where each meets the actual bearings' kxx and kyy."
    let v = run("rotor-a.critical-speed-map.json").await;
    assert_eq!(v["frequencies"].as_array().unwrap().len(), 4);
    assert!(!v["intersections"].as_array().unwrap().is_empty());
    let k = numbers(&v["stiffness"]);
    assert_eq!((k[0], k[k.len() - 1]), (1e6, 1e11));
    // "the first forward mode's log decrement as cross-coupling kxy = q, kyx = -q is added at
    // node 2, and q0."
    let v = run("example1-hysteretic.level1.json").await;
    assert_eq!(v["nodes"], json!([2]));
    let q0 = num(&v["q0"]);
    let q = numbers(&v["cross_coupling"]);
    let d = numbers(&v["log_decrement"]);
    let i = q.iter().position(|&x| x > q0).unwrap();
    assert!(d[i - 1] > 0.0 && d[i] < 0.0, "{q0} {d:?}");
}

#[tokio::test]
async fn seal_over_frequency() {
    let r = run("seal-over-frequency.modal.json").await;
    let poles = r["poles"].as_array().unwrap();
    assert_eq!(poles.len(), 4);
    let c = &r["consistency"];
    assert!(num(&c["max_residual"]) < 1e-12, "{c}");
    assert_eq!(c["solves"], json!(14), "{c}");
    assert_eq!(c["lost"], json!(0), "{c}");
    let first = poles.iter().find(|p| p["whirl"] == "forward").unwrap();
    assert_printed(num(&first["frequency"]), "471.2", "first forward frequency");
    assert_printed(
        num(&first["decay_rate"]),
        "-18.94",
        "first forward decay rate",
    );
    // The seal read at the speed, 800 rad/s, as constants (N/m, N s/m).
    let mut body = example("seal-over-frequency.modal.json");
    body["rotor"]["seals"] = json!([{"node": 15, "kxx": 2e6 + 1.5e3 * 800.0,
        "kxy": 300.0 * 800.0, "kyx": -300.0 * 800.0, "cxx": 3000.0 - 800.0}]);
    let (status, s) = post_json("/v1/modal", &body).await;
    assert_eq!(status, 200, "{s}");
    let sync = s["poles"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["whirl"] == "forward")
        .unwrap()
        .clone();
    assert_printed(
        num(&sync["frequency"]),
        "480.8",
        "synchronous reading's frequency",
    );
    assert_printed(
        num(&sync["decay_rate"]),
        "-15.99",
        "synchronous reading's decay rate",
    );
}

#[tokio::test]
async fn seal_over_frequency_campbell() {
    let r = run("seal-over-frequency.campbell.json").await;
    let critical = numbers(&r["critical_speeds"]);
    assert_eq!(critical.len(), 2, "{critical:?}");
    assert_printed(critical[0], "470.5", "first critical speed");
    assert_printed(critical[1], "1797.9", "second critical speed");
    assert!(r["threshold"].is_null(), "{}", r["threshold"]);
    // The seal read at the speed: a table over speed alone at the synchronous values (linear
    // in the speed, so exact between its points): N/m, N s/m.
    // (examples/seal-at-speed.campbell.json, the same rotor and grid otherwise).
    let body = example("seal-at-speed.campbell.json");
    let mut same = example("seal-over-frequency.campbell.json");
    same["rotor"]["seals"] = body["rotor"]["seals"].clone();
    assert_eq!(same, body);
    let ts = [0.0, 250.0, 500.0, 750.0, 1000.0, 1500.0, 2000.0, 2400.0];
    let col = |f: &dyn Fn(f64) -> f64| ts.iter().map(|&w| f(w)).collect::<Vec<f64>>();
    let seal = json!([{"node": 15, "speeds": ts,
        "kxx": col(&|w| 2e6 + 1.5e3 * w), "kxy": col(&|w| 300.0 * w),
        "kyx": col(&|w| -300.0 * w), "cxx": col(&|w| 3000.0 - w)}]);
    assert_eq!(body["rotor"]["seals"], seal);
    let (status, s) = post_json("/v1/campbell", &body).await;
    assert_eq!(status, 200, "{s}");
    let sync = numbers(&s["critical_speeds"]);
    assert_printed(sync[0], "470.5", "synchronous first critical speed");
    assert_printed(sync[1], "1797.9", "synchronous second critical speed");
    let t = num(&s["threshold"]);
    assert_printed(t, "1925.2", "synchronous threshold");
    assert_printed(
        3000.0 - t,
        "1075",
        "seal damping read at the threshold speed",
    );
    let first = num(&r["branches"][0]["frequency"][0]).abs();
    assert!((first - 470.0).abs() < 5.0, "{first}");
    assert_printed(3000.0 - 470.0, "2530", "seal damping read at 470 rad/s");
}

#[tokio::test]
async fn seal_over_frequency_run_up() {
    let r = run("seal-over-frequency.time-response.json").await;
    let fit = &r["support_fits"][0];
    assert_eq!(fit["support"], json!("rotor.seals[0]"), "{fit}");
    let branches = fit["rates"].as_array().unwrap().len();
    let deviation = num(&fit["max_deviation"]);
    let reduction = &r["reduction"];
    // The run-up's peak at the seal (m) and the speed there (200 rad/s^2 from rest).
    let time = numbers(&r["time"]);
    let (x, y) = (numbers(&r["nodes"][0]["x"]), numbers(&r["nodes"][0]["y"]));
    let (k, peak) = x
        .iter()
        .zip(&y)
        .map(|(a, b)| a.hypot(*b))
        .enumerate()
        .fold((0, 0.0), |m, (k, a)| if a > m.1 { (k, a) } else { m });
    let peak_speed = 200.0 * time[k];
    // The steady unbalance response, the seal read exactly at the speed.
    let mut steady = example("seal-over-frequency.time-response.json");
    let obj = steady.as_object_mut().unwrap();
    for key in ["speed_profile", "duration", "output_interval"] {
        obj.remove(key);
    }
    steady["speeds"] = json!((0..=200).map(|i| 400.0 + i as f64).collect::<Vec<f64>>());
    let (status, u) = post_json("/v1/unbalance-response", &steady).await;
    assert_eq!(status, 200, "{u}");
    let p = &u["nodes"][0]["peaks"][0];
    let (steady_peak, steady_speed) = (num(&p["amplitude"]), num(&p["speed"]));
    // The time response at that speed, held: its steady state against the frequency domain's.
    let mut held = example("seal-over-frequency.time-response.json");
    let obj = held.as_object_mut().unwrap();
    obj.remove("speed_profile");
    held["speed"] = json!(steady_speed);
    held["duration"] = json!(1.5);
    let (status, h) = post_json("/v1/time-response", &held).await;
    assert_eq!(status, 200, "{h}");
    let ht = numbers(&h["time"]);
    let (hx, hy) = (numbers(&h["nodes"][0]["x"]), numbers(&h["nodes"][0]["y"]));
    let held_amplitude = ht
        .iter()
        .enumerate()
        .filter(|(_, t)| **t >= 1.48)
        .map(|(k, _)| hx[k].hypot(hy[k]))
        .fold(0.0, f64::max);
    assert_eq!(branches, 16, "{fit}");
    assert_printed(100.0 * deviation, "5.4", "the seal's fit deviation, %");
    assert_eq!(reduction["modes"], json!(4), "{reduction}");
    assert_eq!(reduction["states"], json!(38), "{reduction}");
    assert_eq!(reduction["full_states"], json!(140), "{reduction}");
    assert_printed(1e6 * peak, "20.1", "run-up peak, um");
    assert_printed(peak_speed, "486.6", "run-up peak speed");
    assert_printed(1e6 * steady_peak, "20.75", "steady peak, um");
    assert_printed(steady_speed, "472.2", "steady peak speed");
    // The fit held to the table at the speed: the frequency domain's amplitude.
    let held_off = (held_amplitude / steady_peak - 1.0).abs();
    assert!(held_off <= 1e-4, "{held_off}");
}

/// docs/trains.md on the direct-drive train's report: "Its modes at 31.07 and 80.61 Hz lie 37.9%
/// below the motor's 1x and 19.4% below 2x and 2 f_L; every check of the report passes".
#[tokio::test]
#[ignore = "heavy: a report of a 20-element train, run once in the fast tier by http.rs (cargo test --release -- --ignored)"]
async fn train_torsion_report() {
    let r = run("train-torsion.report.json").await;
    let checks = r["checks"].as_array().unwrap();
    assert!(checks.iter().all(|c| c["passes"] == true), "{checks:?}");
    let torsional: Vec<&Value> = checks
        .iter()
        .filter(|c| c["check"].as_str().unwrap().starts_with("torsional mode"))
        .collect();
    assert_eq!(torsional.len(), 2);
    for (c, (f, sm)) in torsional.iter().zip([("31.07", "37.9"), ("80.61", "19.4")]) {
        let text = c["check"].as_str().unwrap();
        assert!(text.contains(&format!("({f} Hz)")), "{text}");
        assert_eq!(c["value"], json!(format!("SM {sm} %")));
    }
    let i = &r["torsion"]["campbell"]["interference"];
    let margins: Vec<f64> = i["criticals"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|k| k["mode"] == 2)
        .map(|k| 100.0 * num(&k["margin"]))
        .collect();
    // 2x and 2 f_L are one frequency at the synchronous speed: both 19.4%.
    assert_eq!(
        margins.iter().filter(|m| (**m - 19.4).abs() < 0.05).count(),
        2,
        "{margins:?}"
    );
}

/// docs/trains.md and the README on the motor-compressor train: "first torsional mode is 30.02
/// Hz (log decrement 0.41), 20.1% above the motor's 1x ... 40.0% below the line frequency; the
/// second, 291.05 Hz, is 81.9% above 2x of the pinion shaft"; its start-up "pulls into step at
/// 2.23 s; ... (30.0 Hz, at 70% speed, 1.49 s), and the motor shaft's torque peaks at 1.45 s at
/// 4600 N m (13.6 MPa), twice its steady 2370 N m".
#[tokio::test]
async fn motor_compressor_train() {
    let v = run("motor-compressor.campbell.json").await;
    let b = &v["branches"][0];
    assert_printed(num(&b["frequency"][0]), "30.02", "first torsional mode, Hz");
    assert_printed(num(&b["log_decrement"][0]), "0.41", "its log decrement");
    let margin = |mode: u64, kind: &str, order: f64, ratio: f64| {
        let i = &v["interference"];
        let e = i["excitations"]
            .as_array()
            .unwrap()
            .iter()
            .position(|e| e["kind"] == kind && e["order"] == order && e["ratio"] == ratio)
            .unwrap();
        let c = i["criticals"]
            .as_array()
            .unwrap()
            .iter()
            .find(|c| c["mode"] == mode && c["excitation"] == e)
            .unwrap();
        100.0 * num(&c["margin"])
    };
    assert_printed(margin(1, "order", 1.0, 1.0), "20.1", "mode 1 over 1x, %");
    assert_printed(margin(1, "line", 1.0, 0.0), "40.0", "mode 1 under f_L, %");
    assert_printed(
        num(&v["branches"][1]["frequency"][0]),
        "291.05",
        "mode 2, Hz",
    );
    assert_printed(
        margin(2, "order", 2.0, 3.2),
        "81.9",
        "mode 2 over 2x pinion, %",
    );

    let s = run("motor-compressor-start.time-response.json").await;
    let time = numbers(&s["time"]);
    let rate = numbers(&s["rigid_motion"]["rate"]);
    let synchronous = 1500.0 / whirl::model::speeds::RPM;
    let k = rate
        .iter()
        .position(|w| *w >= synchronous * (1.0 - 1e-12))
        .unwrap();
    assert_printed(time[k], "2.23", "pull-in, s");
    let shaft = &s["elements"][3];
    assert_printed(
        num(&shaft["peak"]),
        "4600",
        "motor shaft's peak torque, N m",
    );
    assert_printed(num(&shaft["peak_stress"]) / 1e6, "13.6", "its stress, MPa");
    assert_printed(num(&shaft["peak_time"]), "1.45", "when, s");
    let steady = numbers(&shaft["load"]).last().unwrap().abs();
    assert_printed(steady, "2370", "steady torque, N m");
    // The pulsation 2 f_L (1 - n) is the first mode's 30.0 Hz at n = 0.7.
    let f1 = num(&b["frequency"][0]);
    let k = rate
        .iter()
        .position(|w| 100.0 * (1.0 - w / synchronous) <= f1)
        .unwrap();
    assert_printed(time[k], "1.49", "the pulsation at the first mode, s");
    assert_printed(100.0 * rate[k] / synchronous, "70", "at this speed, %");
}

/// The README and the pages of `docs/`, as files.
fn pages() -> Vec<(String, String)> {
    let root = env!("CARGO_MANIFEST_DIR");
    let mut out = vec![(
        "README.md".to_string(),
        std::fs::read_to_string(format!("{root}/README.md")).unwrap(),
    )];
    let mut docs: Vec<_> = std::fs::read_dir(format!("{root}/docs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    docs.sort();
    for p in docs {
        let name = format!("docs/{}", p.file_name().unwrap().to_string_lossy());
        out.push((name, std::fs::read_to_string(&p).unwrap()));
    }
    out
}

/// The relative link targets `](target)` of a page, anchors dropped.
fn links(text: &str) -> Vec<String> {
    text.split("](")
        .skip(1)
        .filter_map(|rest| rest.split(')').next())
        .map(|t| t.split('#').next().unwrap().to_string())
        .filter(|t| !t.is_empty() && !t.contains("://") && !t.starts_with("mailto:"))
        .collect()
}

#[test]
fn the_readme_is_a_front_door_to_every_docs_page() {
    let pages = pages();
    let readme = &pages[0].1;
    let lines = readme.lines().count();
    assert!(lines <= 400, "README.md has {lines} lines");
    for (name, _) in &pages[1..] {
        assert!(
            readme.contains(&format!("]({name})")),
            "README.md links no {name}"
        );
    }
    assert!(pages.len() >= 8, "{} pages", pages.len());
}

#[test]
fn every_relative_link_of_the_readme_and_docs_resolves() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    for (name, text) in pages() {
        let dir = root.join(name.rsplit_once('/').map_or("", |(d, _)| d));
        for target in links(&text) {
            assert!(
                dir.join(&target).exists(),
                "{name} links {target}, which does not exist"
            );
        }
    }
}

#[test]
fn the_docs_speak_to_users_not_of_the_projects_history() {
    for (name, text) in pages() {
        let lower = text.to_lowercase();
        for (i, _) in lower.match_indices("issue ") {
            let next = lower[i + 6..].chars().next().unwrap_or(' ');
            assert!(
                !next.is_ascii_digit() && next != '#',
                "{name} names an issue: {}",
                &text[i..(i + 20).min(text.len())]
            );
        }
        assert!(!lower.contains("session "), "{name} names a session");
    }
}
