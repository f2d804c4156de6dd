//! The audit on supports whose coefficients depend on the whirl frequency (issue 31): Level I
//! and II with poles consistent with their own frequency, the critical speed map read
//! synchronously, the threshold of a rotor held sparse; against closed forms and against
//! constant-coefficient rotors read by hand.

use crate::common;

use common::over_whirl::*;
use common::post_json;
use num_complex::Complex64 as C;
use serde_json::{Value, json};
use whirl::analysis::audit::critical_map::frequencies_at;

/// The relative residual of `m s^2 + c(w) s + k_s + k(w) - i q = 0` (N/m) at `s`, the mass's
/// support read at `w = |Im s|`: the Jeffcott rotor's forward whirl under cross-coupling `q`.
fn jeffcott_residual(s: C, q: f64) -> f64 {
    let w = s.im.abs();
    let (k, c) = (KS + K0 + K1 * w, C0 + C1 * w);
    let z = M * s * s + c * s + k - C::new(0.0, q);
    z.norm() / (M * s.norm_sqr() + c * s.norm() + k + q)
}

/// The forward pole `(decay rate, frequency)` from a log decrement and a frequency.
fn pole(log_dec: &Value, w: &Value) -> C {
    let w = num(w);
    C::new(-num(log_dec) * w / (2.0 * std::f64::consts::PI), w)
}

/// Level I of a mass on a support with `k(w) = k0 + k1 w`, `c(w) = c0 + c1 w`: its first
/// forward pole crosses `Re s = 0` at `i w*` with `k_s + k(w*) = m w*^2` and `q0 = c(w*) w*`,
/// `w* = (k1 + sqrt(k1^2 + 4 m (k_s + k0))) / 2m` = 372.3 rad/s, `q0` = 1.0655e5 N/m (the support
/// read at rest would give `c0 sqrt((k_s + k0) / m)` = 3.46e4 N/m); every pole of the curve
/// solves the Jeffcott equation with the support read at its own frequency.
#[tokio::test]
async fn level1_on_a_frequency_dependent_support_is_its_closed_form() {
    let body = json!({"rotor": one_mass(false), "damping": {"model": "viscous"}, "speed": 100.0,
                      "node": 0});
    let (status, r) = post_json("/v1/level1", &body).await;
    assert_eq!(status, 200, "{r}");
    let ws = (K1 + (K1 * K1 + 4.0 * M * (KS + K0)).sqrt()) / (2.0 * M);
    let q0 = (C0 + C1 * ws) * ws;
    assert!((q0 - 1.0655e5).abs() < 50.0, "{q0}");
    let got = num(&r["q0"]);
    assert!((got - q0).abs() <= 1e-8 * q0, "q0 {got} against {q0}");
    assert!(num(&r["max_residual"]) < 1e-10, "{r}");
    let qs = r["cross_coupling"].as_array().unwrap();
    assert!(qs.len() >= 20 && num(qs.last().unwrap()) > q0, "{r}");
    for (k, q) in qs.iter().enumerate() {
        let s = pole(&r["log_decrement"][k], &r["frequency"][k]);
        let e = jeffcott_residual(s, num(q));
        assert!(e < 1e-9, "q {q}: {s} residual {e}");
    }
    let s0 = pole(&r["log_decrement_0"], &r["frequency_0"]);
    assert!(jeffcott_residual(s0, 0.0) < 1e-9, "{s0}");
}

/// The cross-coupled seal over whirl frequency and speed at mid-span of the 30-element rotor:
/// at `q0` the first forward pole whirls at some `w*` on the axis, so the same rotor with the
/// seal read by hand at `w*` (and the speed) as constants has the same `q0`.
#[tokio::test]
#[ignore = "heavy: a dense reference of a large rotor (cargo test --release -- --ignored)"]
async fn level1_of_a_beam_rotor_is_that_of_the_rotor_read_at_its_first_forward_frequency() {
    let speed = 600.0;
    let level1 = |rotor: &Value, range: Option<Value>| {
        let mut body = json!({"rotor": rotor, "damping": {"model": "viscous"}, "speed": speed,
                              "node": 15, "modal_reduction": false});
        if let Some(r) = range {
            body["cross_coupling"] = r;
        }
        async move {
            let (status, r) = post_json("/v1/level1", &body).await;
            assert_eq!(status, 200, "{r}");
            r
        }
    };
    // The seal's cross-coupling a tenth of the helper's (which alone makes the rotor unstable
    // at this speed).
    let weaker = |name: &str, v: f64| {
        if name == "kxy" || name == "kyx" {
            0.1 * v
        } else {
            v
        }
    };
    let mut seal = tabulated_seal(0.0);
    for name in ["kxy", "kyx"] {
        for row in seal[name].as_array_mut().unwrap() {
            for v in row.as_array_mut().unwrap() {
                *v = json!(weaker(name, num(v)));
            }
        }
    }
    let tabulated = sealed(seal, 0.002);
    let r = level1(&tabulated, None).await;
    let q0 = num(&r["q0"]);
    assert!(num(&r["max_residual"]) < 1e-10, "{r}");
    // The first forward pole at q0: on the axis, at w*.
    let at = level1(
        &tabulated,
        Some(json!({"start": 0.0, "stop": q0, "count": 2})),
    )
    .await;
    let s = pole(&at["log_decrement"][1], &at["frequency"][1]);
    assert!(s.re.abs() <= 1e-7 * s.im, "{s}");
    let mut seal = json!({"node": 15});
    for (name, v) in seal_at(s.im, speed) {
        seal[name] = json!(weaker(name, v));
    }
    let by_hand = level1(&sealed(seal, 0.002), None).await;
    let q0_hand = num(&by_hand["q0"]);
    assert!(
        (q0 - q0_hand).abs() <= 1e-7 * q0,
        "q0 {q0} against {q0_hand} read at {s}"
    );
    // The seal read at the speed instead: another q0 (what a table over speed alone gives).
    let mut synchronous = json!({"node": 15});
    for (name, v) in seal_at(speed, speed) {
        synchronous[name] = json!(weaker(name, v));
    }
    let q0_sync = num(&level1(&sealed(synchronous, 0.002), None).await["q0"]);
    eprintln!(
        "q0 {q0:.6e} (w* {:.3}; by hand {:.1e} relative) read at the speed {q0_sync:.6e}",
        s.im,
        (q0 - q0_hand).abs() / q0
    );
    assert!((q0_sync - q0).abs() > 1e-4 * q0, "{q0_sync} {q0}");
}

/// Level II with the seal over whirl frequency: the configuration with everything (the seal
/// and the stage's q_A) is Level I's pole at q_A, the seal alone Level I's at q = 0, and the
/// bearings alone Level I's at q = 0 of the rotor without the seal.
#[tokio::test]
async fn level2_with_a_seal_over_whirl_frequency_agrees_with_level1() {
    let machine = json!({"stages": [{"node": 15, "power": 2e6, "diameter": 0.3, "width": 0.02}]});
    let body = json!({"rotor": sealed(tabulated_seal(0.0), 0.002),
                      "damping": {"model": "viscous"}, "speed": 600.0, "node": 15,
                      "machine": machine});
    let (status, r) = post_json("/v1/level1", &body).await;
    assert_eq!(status, 200, "{r}");
    let level2: Vec<(String, f64)> = r["level2"]["sources"]
        .as_array()
        .unwrap_or_else(|| panic!("{r}"))
        .iter()
        .map(|s| {
            (
                s["source"].as_str().unwrap().to_string(),
                num(&s["log_decrement"]),
            )
        })
        .collect();
    let of = |name: &str| {
        level2
            .iter()
            .find(|s| s.0 == name)
            .unwrap_or_else(|| panic!("{name}: {level2:?}"))
            .1
    };
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-8 * a.abs().max(b.abs()).max(1e-3);
    let at_qa = num(&r["log_decrement_at_qa"]);
    assert!(close(of("all together"), at_qa), "{level2:?} {at_qa}");
    assert!(
        close(of("seals"), num(&r["log_decrement_0"])),
        "{level2:?} {r}"
    );
    let mut bare = sealed(tabulated_seal(0.0), 0.002);
    bare.as_object_mut().unwrap().remove("seals");
    let body = json!({"rotor": bare, "damping": {"model": "viscous"}, "speed": 600.0, "node": 15,
                      "cross_coupling": {"start": 0.0, "stop": 1e5, "count": 2}});
    let (status, b) = post_json("/v1/level1", &body).await;
    assert_eq!(status, 200, "{b}");
    assert!(
        close(of("bearings alone"), num(&b["log_decrement_0"])),
        "{level2:?} {b}"
    );
}

/// Bearings over whirl frequency with `k(w) = 2e7 + 2e4 w` N/m (kxx; kyy 1.5 times it):
/// every intersection of the map is a critical speed on the bearing read synchronously, where
/// the map's spring `k(w)` has the natural frequency `w`; within the table they are those of
/// the same bearing tabulated over speed, and past it the table is read along its end slope.
#[tokio::test]
async fn the_critical_speed_map_reads_a_bearing_over_whirl_frequency_synchronously() {
    let freqs: Vec<f64> = (0..6).map(|i| 200.0 * i as f64).collect();
    let k = |w: f64| 2e7 + 2e4 * w;
    let kxx: Vec<f64> = freqs.iter().map(|&w| k(w)).collect();
    let kyy: Vec<f64> = kxx.iter().map(|k| 1.5 * k).collect();
    let over_frequency = json!({"frequencies": freqs, "kxx": kxx, "kyy": kyy, "cxx": 1e3,
                                "cyy": 1e3});
    let over_speed = json!({"speeds": freqs, "kxx": kxx, "kyy": kyy, "cxx": 1e3, "cyy": 1e3});
    let map = |bearing: Value| async move {
        let body = json!({"rotor": common::stepped_rotor(30, bearing, 0.0),
                          "stiffness": {"start": 1e6, "stop": 1e10, "count": 9}, "modes": 3});
        let (status, r) = post_json("/v1/critical-speed-map", &body).await;
        assert_eq!(status, 200, "{r}");
        r["intersections"].as_array().unwrap().clone()
    };
    let shaft = common::beam(&common::stepped_rotor(30, json!({"kxx": 1e7}), 0.0));
    let found = map(over_frequency).await;
    let tabulated = map(over_speed).await;
    assert!(!found.is_empty());
    let mut past = 0;
    for i in &found {
        let (w, stiffness) = (num(&i["frequency"]), num(&i["stiffness"]));
        let scale = if i["coefficient"] == "kyy" { 1.5 } else { 1.0 };
        // The bearing read at w (by hand, N/m), and the map's spring there whirling at w.
        assert!((stiffness - scale * k(w)).abs() <= 1e-12 * stiffness, "{i}");
        let mode = i["mode"].as_u64().unwrap() as usize - 1;
        let at = frequencies_at(&shaft, stiffness, 3, false).unwrap()[mode];
        assert!((at - w).abs() <= 1e-9 * w, "{i}: {at}");
        if w > 1000.0 {
            past += 1;
            continue;
        }
        let same = tabulated.iter().find(|t| {
            t["mode"] == i["mode"]
                && t["coefficient"] == i["coefficient"]
                && t["support"] == i["support"]
        });
        let t = same.unwrap_or_else(|| panic!("{i}: {tabulated:?}"));
        assert!((num(&t["frequency"]) - w).abs() <= 1e-9 * w, "{i} {t}");
    }
    eprintln!("{} intersections, {past} past the table", found.len());
}

/// The pole nearest whirling at `w` (rad/s) of `rotor` with its seal replaced by `seal`
/// (constants) at `speed`, held sparse in the box of 1000 rad/s.
async fn read_by_hand(rotor: &Value, seal: Value, speed: f64, w: f64) -> C {
    let mut rotor = rotor.clone();
    let mut seal = seal;
    seal["node"] = rotor["seals"][0]["node"].clone();
    rotor["seals"] = json!([seal]);
    let body = json!({"rotor": rotor, "damping": {"model": "viscous"}, "speed": speed,
                      "max_frequency": 1000.0});
    let (status, m) = post_json("/v1/modal", &body).await;
    assert_eq!(status, 200, "{m}");
    m["poles"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| C::new(num(&p["decay_rate"]), num(&p["frequency"])))
        .min_by(|a, b| (a.im.abs() - w).abs().total_cmp(&(b.im.abs() - w).abs()))
        .unwrap()
}

/// The bundled seal example's rotor on 900 elements (held sparse).
fn example_on_900() -> Value {
    let mut rotor = example("seal-over-frequency.campbell.json")["rotor"].clone();
    common::seal_example_on(&mut rotor, 900);
    rotor
}

/// The bundled seal example on 900 elements (held sparse) with its seal's cross-coupling
/// tripled (900 N/m per rad/s of speed): its threshold of instability on the poles consistent
/// with their own frequency, where the rotor with the seal read by hand at that speed and the
/// unstable pole's frequency `w*` (constants) has a pole at `i w*`.
#[tokio::test]
async fn the_threshold_of_a_rotor_held_sparse_reads_its_seal_at_the_poles_frequency() {
    let mut rotor = example_on_900();
    for name in ["kxy", "kyx"] {
        for row in rotor["seals"][0][name].as_array_mut().unwrap() {
            for v in row.as_array_mut().unwrap() {
                *v = json!(3.0 * num(v));
            }
        }
    }
    let speeds: Vec<f64> = (0..=24).map(|i| 100.0 * i as f64).collect();
    let body = json!({"rotor": rotor, "damping": {"model": "viscous"}, "speeds": speeds,
                      "max_frequency": 1000.0});
    let t = std::time::Instant::now();
    let (status, r) = post_json("/v1/stability", &body).await;
    assert_eq!(status, 200, "{r}");
    eprintln!(
        "held sparse stability {:.1} s: {r}",
        t.elapsed().as_secs_f64()
    );
    assert_eq!(r["max_frequency"], json!(1000.0), "{r}");
    let (speed, w) = (num(&r["threshold"]), num(&r["frequency"]).abs());
    // The example's seal read by hand (its table is linear in the frequency and the speed):
    // kxx = 2e6 + 1500 w N/m, cxx = 3000 - w N s/m, kxy = -kyx = 900 W N/m.
    let seal = json!({"kxx": 2e6 + 1500.0 * w, "cxx": 3000.0 - w, "kxy": 900.0 * speed,
                      "kyx": -900.0 * speed});
    let nearest = read_by_hand(&rotor, seal, speed, w).await;
    eprintln!("threshold {speed} rad/s at {w} rad/s: read by hand {nearest}");
    assert!(
        (nearest.im.abs() - w).abs() <= 1e-6 * w,
        "{nearest} against {w}"
    );
    // The threshold is found to 1e-6 relative, where the decay rate grows by about 0.019 1/s
    // per rad/s of speed: 2.5e-5 1/s, 5e-8 of w.
    assert!(nearest.re.abs() <= 1e-6 * w, "{nearest}");
}

/// Level I of the example on 900 elements (held sparse) at 800 rad/s: at q0 the rotor with the
/// seal read by hand at the first forward pole's frequency `w*` and the cross-coupling `q0` at
/// the seal (constants) has a pole at `i w*`.
#[tokio::test]
#[ignore = "heavy: a dense reference of a large rotor (cargo test --release -- --ignored)"]
async fn level1_of_a_rotor_held_sparse_reads_its_seal_at_the_poles_frequency() {
    let rotor = example_on_900();
    let node = rotor["seals"][0]["node"].clone();
    let speed = 800.0;
    let level1 = |range: Option<Value>| {
        let mut body = json!({"rotor": rotor, "damping": {"model": "viscous"}, "speed": speed,
                              "node": node});
        if let Some(r) = range {
            body["cross_coupling"] = r;
        }
        async move {
            let t = std::time::Instant::now();
            let (status, r) = post_json("/v1/level1", &body).await;
            assert_eq!(status, 200, "{r}");
            eprintln!("level1 held sparse {:.1} s: {r}", t.elapsed().as_secs_f64());
            r
        }
    };
    let r = level1(None).await;
    let q0 = num(&r["q0"]);
    assert!(num(&r["max_residual"]) < 1e-10, "{r}");
    let at = level1(Some(json!({"start": 0.0, "stop": q0, "count": 2}))).await;
    let s = pole(&at["log_decrement"][1], &at["frequency"][1]);
    let w = s.im;
    assert!(s.re.abs() <= 1e-7 * w, "{s}");
    // kxx = 2e6 + 1500 w N/m, cxx = 3000 - w N s/m, kxy = -kyx = 300 W N/m; q0 beside it.
    let seal = json!({"kxx": 2e6 + 1500.0 * w, "cxx": 3000.0 - w,
                      "kxy": 300.0 * speed + q0, "kyx": -300.0 * speed - q0});
    let nearest = read_by_hand(&rotor, seal, speed, w).await;
    eprintln!("q0 {q0} at {w} rad/s: read by hand {nearest}");
    assert!((nearest.im - w).abs() <= 1e-7 * w, "{nearest} against {w}");
    assert!(nearest.re.abs() <= 1e-7 * w, "{nearest}");
}

fn example(name: &str) -> Value {
    let text = std::fs::read_to_string(format!("examples/{name}")).unwrap();
    serde_json::from_str(&text).unwrap()
}

/// The hysteretic model with a lossy shaft (loss factor 0.01) on the seal example: at a
/// forward critical speed the rotating loss's sign is 0 (it flips there), so its forward
/// critical speeds and their poles are the viscous model's (which ignores the loss); backward,
/// the loss damps the mode more. Before, each forward crossing was lost (a guess on the wrong
/// side of the 1x line found no pole with its problem's signs).
#[tokio::test]
async fn the_hysteretic_campbell_on_a_seal_over_whirl_frequency_keeps_its_forward_criticals() {
    let mut body = example("seal-over-frequency.campbell.json");
    body["rotor"]["materials"]["steel"]["loss_factor"] = json!(0.01);
    let mut criticals = vec![];
    for model in ["viscous", "hysteretic"] {
        body["damping"] = json!({"model": model});
        let (status, r) = post_json("/v1/campbell", &body).await;
        assert_eq!(status, 200, "{r}");
        criticals.push(r["criticals"].as_array().unwrap().clone());
    }
    let (viscous, hysteretic) = (&criticals[0], &criticals[1]);
    assert_eq!(viscous.len(), 4, "{viscous:?}");
    assert_eq!(hysteretic.len(), 4, "{hysteretic:?}");
    for (v, h) in viscous.iter().zip(hysteretic) {
        assert_eq!(v["whirl"], h["whirl"], "{v} {h}");
        let (sv, sh) = (num(&v["speed"]), num(&h["speed"]));
        let (dv, dh) = (num(&v["decay_rate"]), num(&h["decay_rate"]));
        if v["whirl"] == "forward" {
            assert!((sv - sh).abs() <= 1e-9 * sv, "{v} {h}");
            assert!((dv - dh).abs() <= 1e-7 * dv.abs(), "{v} {h}");
        } else {
            assert!(dh < dv - 1.0, "{v} {h}");
        }
    }
}

/// The report of the seal example: Level I, the map, the Campbell diagram and the unbalance
/// cases all read the seal over whirl frequency, the models compared the two that read it in
/// the frequency domain (hysteretic and viscous); its q0 is Level I's.
#[tokio::test]
async fn the_report_of_a_rotor_with_a_seal_over_whirl_frequency() {
    let rotor = example("seal-over-frequency.campbell.json")["rotor"].clone();
    let body = json!({"rotor": rotor, "damping": {"model": "viscous"},
                      "operating_range": {"min": 600.0, "max": 800.0}});
    let (status, r) = post_json("/v1/report", &body).await;
    assert_eq!(status, 200, "{r}");
    let models: Vec<&str> = r["models"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m["model"].as_str().unwrap())
        .collect();
    assert_eq!(models, ["hysteretic", "viscous"], "{}", r["models"]);
    assert!(num(&r["level1"]["max_residual"]) < 1e-10, "{}", r["level1"]);
    let level1 = json!({"rotor": rotor, "damping": {"model": "viscous"}, "speed": 800.0,
                        "nodes": r["level1"]["nodes"]});
    let (status, l) = post_json("/v1/level1", &level1).await;
    assert_eq!(status, 200, "{l}");
    let (q0, report_q0) = (num(&l["q0"]), num(&r["level1"]["q0"]));
    assert!((q0 - report_q0).abs() <= 1e-12 * q0, "{q0} {report_q0}");
    // The Campbell's forward critical speeds are the bundled example's (470.5 rad/s first).
    let first = num(&r["campbell"]["critical_speeds"][0]);
    assert!(
        (first - 470.4736).abs() < 1e-3,
        "{}",
        r["campbell"]["critical_speeds"]
    );
    assert!(!r["unbalance_cases"].as_array().unwrap().is_empty(), "{r}");
    // The page's model table lists the seal and what its table is over: speed and frequency.
    let (status, _, page) = common::post_as("/v1/report", &body, "text/html").await;
    assert_eq!(status, 200);
    let page = String::from_utf8(page).unwrap();
    assert!(
        page.contains("<th>seals</th><td>1: node 15: k 2.00e6..5.00e6 (Ω, ω) N/m"),
        "no seal row"
    );
}
