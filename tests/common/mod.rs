//! Helpers shared by the integration tests.
#![allow(dead_code)]

pub mod kept;
pub mod over_whirl;
pub mod ross;
pub mod server;

/// Asserts that `value` rounds to `printed` at the printed number of decimals, i.e. agrees to
/// every printed digit: `|value - printed| <= 0.5 ulp(printed)` (plus round-off).
pub fn assert_printed(value: f64, printed: &str, what: &str) {
    let p: f64 = printed.parse().unwrap();
    let decimals = printed.split('.').nth(1).map_or(0, |d| d.len());
    let half = 0.5 * 10f64.powi(-(decimals as i32));
    assert!(
        (value - p).abs() <= half * (1.0 + 1e-9),
        "{what}: computed {value}, printed {printed}"
    );
}

/// POSTs `body` to the in-process app (no socket) and returns the status and the JSON answer.
pub async fn post_json(uri: &str, body: &serde_json::Value) -> (u16, serde_json::Value) {
    let (status, _, bytes) = post_as(uri, body, "application/json").await;
    (
        status,
        serde_json::from_slice(&bytes).expect("a JSON answer"),
    )
}

/// POSTs `body` asking for `accept`: status, content type and body.
/// The synchronous time limit is an operator's setting, not what these tests check: long enough
/// here that two large analyses sharing 2 cores are not stopped at the default 60 s.
pub async fn post_as(uri: &str, body: &serde_json::Value, accept: &str) -> (u16, String, Vec<u8>) {
    let config = whirl::service::Config {
        request_time_limit: std::time::Duration::from_secs(600),
        ..whirl::service::Config::default()
    };
    post_to(config, uri, body, accept).await
}

/// POSTs `body` to the in-process app of `config`: status, content type and body.
pub async fn post_to(
    config: whirl::service::Config,
    uri: &str,
    body: &serde_json::Value,
    accept: &str,
) -> (u16, String, Vec<u8>) {
    use http_body_util::BodyExt;
    use tower::ServiceExt;
    let req = axum::http::Request::builder()
        .method("POST")
        .uri(uri)
        .header("content-type", "application/json")
        .header("accept", accept)
        .body(axum::body::Body::from(body.to_string()))
        .unwrap();
    let resp = whirl::service::app(config).oneshot(req).await.unwrap();
    let status = resp.status().as_u16();
    let ctype = resp
        .headers()
        .get("content-type")
        .map(|v| v.to_str().unwrap().to_string())
        .unwrap_or_default();
    let bytes = resp
        .into_body()
        .collect()
        .await
        .unwrap()
        .to_bytes()
        .to_vec();
    (status, ctype, bytes)
}

/// A stepped 1.2 m shaft of `elements` elements with two disks, on two bearings `bearing`
/// (the rotor built for nothing in particular of `runup_reduction.rs` and `nearest.rs`).
#[allow(dead_code)]
pub fn stepped_rotor(elements: usize, bearing: serde_json::Value, loss: f64) -> serde_json::Value {
    let e = elements / 3;
    let at = |node: usize| {
        let mut b = bearing.clone();
        b["node"] = serde_json::json!(node);
        b
    };
    serde_json::json!({
        "type": "beam",
        "materials": {"steel": {"young_modulus": 2.11e11, "density": 7810.0, "poisson_ratio": 0.3,
                                "loss_factor": loss}},
        "shaft": [
            {"length": 0.35, "outer_diameter": 0.06, "inner_diameter": 0.0, "material": "steel", "elements": e},
            {"length": 0.5, "outer_diameter": 0.08, "inner_diameter": 0.03, "material": "steel", "elements": elements - 2 * e},
            {"length": 0.35, "outer_diameter": 0.06, "inner_diameter": 0.0, "material": "steel", "elements": e}
        ],
        "disks": [
            {"node": e + 2, "mass": 25.0, "polar_inertia": 0.35, "transverse_inertia": 0.18},
            {"node": elements - e - 3, "mass": 12.0, "polar_inertia": 0.15, "transverse_inertia": 0.08}
        ],
        "supports": [at(1), at(elements - 1)]
    })
}

/// The bundled seal example's rotor (`examples/seal-over-frequency.*`) remeshed on `n`
/// elements, its disks, far bearing and seal moved with the mesh (the seal to node `n / 2`).
#[allow(dead_code)]
pub fn seal_example_on(rotor: &mut serde_json::Value, n: usize) {
    let e = n / 3;
    for (i, k) in [e, n - 2 * e, e].iter().enumerate() {
        rotor["shaft"][i]["elements"] = serde_json::json!(k);
    }
    rotor["disks"][0]["node"] = serde_json::json!(e + 2);
    rotor["disks"][1]["node"] = serde_json::json!(n - e - 3);
    rotor["supports"][1]["node"] = serde_json::json!(n - 1);
    rotor["seals"][0]["node"] = serde_json::json!(n / 2);
}

/// The paper's nonviscous model of Example 1: 3 rotating branches over a decade at 10 rad/s,
/// unit weights, and 3 nonrotating ones weighted by the reciprocals of the rotating gammas.
pub fn paper_nvd() -> whirl::model::damping::DampingModel {
    use whirl::damping::nonviscous::BranchSet;
    let rot = BranchSet::new(3, 10.0, vec![1.0; 3]).unwrap();
    let nonrot = BranchSet::new(3, 10.0, rot.gamma().iter().map(|g| 1.0 / g).collect()).unwrap();
    whirl::model::damping::DampingModel::Nonviscous(whirl::model::damping::NonviscousSpec {
        rotating: rot,
        nonrotating: nonrot,
        modes: None,
    })
}

/// The domain beam rotor of a JSON rotor known to be valid.
pub fn beam(rotor: &serde_json::Value) -> whirl::model::rotor::BeamRotor {
    use whirl::model::rotor::Rotor;
    let input: whirl::model::api::RotorInput = serde_json::from_value(rotor.clone()).unwrap();
    match Rotor::parse(&input, &whirl::model::Limits::default()).unwrap() {
        Rotor::Beam(b) => b,
        _ => panic!("not a beam rotor"),
    }
}

/// A JSON array of numbers.
pub fn floats(v: &serde_json::Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// A JSON matrix (rows of numbers).
pub fn matrix(v: &serde_json::Value) -> Vec<Vec<f64>> {
    v.as_array().unwrap().iter().map(floats).collect()
}

/// The rotor of a JSON body, assembled.
pub fn assemble(v: serde_json::Value) -> whirl::system::RotorSystem {
    let rotor: whirl::model::api::RotorInput = serde_json::from_value(v).unwrap();
    let limits = whirl::model::rotor::Limits::default();
    whirl::system::RotorSystem::assemble(
        &whirl::model::rotor::Rotor::parse(&rotor, &limits).unwrap(),
    )
    .unwrap()
}

/// A held-out rotor of the speed benchmark (tests/data/ross/heldout), its shaft's loss factor
/// set to `loss`.
pub fn heldout(i: usize, loss: f64) -> serde_json::Value {
    let path = format!(
        "{}/tests/data/ross/heldout/rotor_{i}.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    v["materials"]["steel"]["loss_factor"] = serde_json::json!(loss);
    v
}

/// Every pole of a Campbell answer at speed index `i`: its branches' and its overdamped ones.
pub fn campbell_poles(camp: &serde_json::Value, i: usize) -> Vec<whirl::linalg::c64> {
    let branches = camp["branches"].as_array().unwrap().iter();
    branches
        .chain(camp["overdamped"].as_array().into_iter().flatten())
        .filter(|b| !b["frequency"][i].is_null())
        .map(|b| {
            whirl::linalg::c64::new(
                b["decay_rate"][i].as_f64().unwrap(),
                b["frequency"][i].as_f64().unwrap(),
            )
        })
        .collect()
}

/// `rotor` with every shaft segment's elements multiplied by `k`, its nodes renumbered: the
/// fine rotor and the fine node of each coarse one.
#[allow(dead_code)]
pub fn refined(rotor: &serde_json::Value, k: usize) -> (serde_json::Value, Vec<usize>) {
    let mut fine = rotor.clone();
    let mut map = vec![0];
    for seg in fine["shaft"].as_array_mut().unwrap() {
        let last = *map.last().unwrap();
        if seg.get("coupling").is_some() {
            map.push(last + 1);
            continue;
        }
        let e = seg["elements"].as_u64().unwrap() as usize;
        seg["elements"] = serde_json::json!(e * k);
        map.extend((1..=e).map(|i| last + i * k));
    }
    for list in ["disks", "supports"] {
        for item in fine[list].as_array_mut().unwrap() {
            let n = item["node"].as_u64().unwrap() as usize;
            item["node"] = serde_json::json!(map[n]);
        }
    }
    (fine, map)
}

/// The cross-coupled, anisotropic bearing tabulated over speed (`speed_dependent.json`).
#[allow(dead_code)]
pub fn tabulated_bearing() -> serde_json::Value {
    let path = format!(
        "{}/tests/data/ross/speed_dependent.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    v["rotor"]["supports"][0].clone()
}

/// The first bearing's coefficients at `speed` as constants: its table read there.
#[allow(dead_code)]
pub fn constant_at(system: &whirl::system::RotorSystem, speed: f64) -> serde_json::Value {
    let c = system.supports[0].support.at(speed);
    serde_json::json!({
        "kxx": c.k.xx, "kxy": c.k.xy, "kyx": c.k.yx, "kyy": c.k.yy,
        "cxx": c.c.xx, "cxy": c.c.xy, "cyx": c.c.yx, "cyy": c.c.yy,
    })
}

/// The stepped rotor of `elements` elements (loss factor 0.002) on isotropic bearings, on the
/// tabulated cross-coupled ones, and on those read at `speed` as constants (a dense model's
/// `Z` as the sparse one forms it there).
#[allow(dead_code)]
pub fn stepped_three(
    elements: usize,
    speed: f64,
) -> (
    whirl::system::RotorSystem,
    whirl::system::RotorSystem,
    whirl::system::RotorSystem,
) {
    let isotropic = serde_json::json!({"kxx": 2e7, "kyy": 2e7, "cxx": 3e3, "cyy": 3e3});
    let tabulated = assemble(stepped_rotor(elements, tabulated_bearing(), 0.002));
    let constant = assemble(stepped_rotor(
        elements,
        constant_at(&tabulated, speed),
        0.002,
    ));
    let iso = assemble(stepped_rotor(elements, isotropic, 0.002));
    (iso, tabulated, constant)
}

/// Largest `|a - a'| + |b - b'|` over every orbit, relative to the largest `|a| + |b|`.
#[allow(dead_code)]
pub fn worst(
    dense: &[Vec<whirl::analysis::audit::frequency::Orbit>],
    sparse: &[Vec<whirl::analysis::audit::frequency::Orbit>],
) -> f64 {
    let (mut diff, mut top) = (0.0f64, 0.0f64);
    for (d, s) in dense.iter().zip(sparse) {
        assert_eq!(d.len(), s.len());
        for (d, s) in d.iter().zip(s) {
            diff = diff.max((d.a - s.a).norm() + (d.b - s.b).norm());
            top = top.max(d.a.norm() + d.b.norm());
        }
    }
    assert!(top > 0.0);
    diff / top
}

/// The largest difference between two time histories at the first output, relative to the
/// reference `f`'s largest radial amplitude: `(relative difference, that amplitude)`.
#[allow(dead_code)]
pub fn deviation(
    r: &whirl::analysis::time::TimeResult,
    f: &whirl::analysis::time::TimeResult,
) -> (f64, f64) {
    let top = f.nodes[0].1.iter().map(|z| z.norm()).fold(0.0, f64::max);
    let worst = r.nodes[0]
        .1
        .iter()
        .zip(&f.nodes[0].1)
        .map(|(a, b)| (a - b).norm())
        .fold(0.0, f64::max);
    (worst / top, top)
}

/// The 150-element stepped rotor on soft, lightly damped, cross-coupled anisotropic bearings
/// (604 coordinates) spun at 700 rad/s and struck along x at node 40 by `history` (N over s):
/// 0.2 s read at nodes 40 and 100 every 0.2 ms.
#[allow(dead_code)]
pub fn shock_case(
    history: &[[f64; 2]],
) -> (whirl::system::RotorSystem, whirl::analysis::time::TimeSpec) {
    use whirl::model::error::Invalid;
    use whirl::model::loads::{Force, Pwl};
    let bearing = serde_json::json!({"kxx": 4e6, "kxy": 8e5, "kyx": -1.2e6, "kyy": 7e6,
                                     "cxx": 300.0, "cxy": 40.0, "cyx": -25.0, "cyy": 500.0});
    let system = assemble(stepped_rotor(150, bearing, 0.002));
    let history = Pwl::parse(history, "history", true, &mut Invalid::default()).unwrap();
    let spec = whirl::analysis::time::TimeSpec {
        speed: whirl::analysis::time::SpeedLaw::Constant(700.0),
        forces: vec![Force {
            node: 40,
            direction: 0.0,
            history,
        }],
        unbalances: vec![],
        duration: 0.2,
        output_interval: 2e-4,
        nodes: vec![40, 100],
        tolerance: 1e-6,
        max_steps: 500_000,
        reduce: true,
        generated: Default::default(),
    };
    (system, spec)
}

/// The largest radial amplitude of a time response's first output node, m.
#[allow(dead_code)]
pub fn radial_peak(out: &serde_json::Value) -> f64 {
    let (x, y) = (floats(&out["nodes"][0]["x"]), floats(&out["nodes"][0]["y"]));
    x.iter()
        .zip(&y)
        .map(|(a, b)| a.hypot(*b))
        .fold(0.0, f64::max)
}

/// The amplitude of `x(t) ~ a cos(w t) + b sin(w t)` fitted by least squares over `t >= from`.
pub fn sine_amplitude(time: &[f64], x: &[f64], w: f64, from: f64) -> f64 {
    let (mut cc, mut ss, mut cs, mut xc, mut xs) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for (t, x) in time.iter().zip(x).filter(|(t, _)| **t >= from) {
        let (c, s) = ((w * t).cos(), (w * t).sin());
        cc += c * c;
        ss += s * s;
        cs += c * s;
        xc += x * c;
        xs += x * s;
    }
    let det = cc * ss - cs * cs;
    ((xc * ss - xs * cs) / det).hypot((xs * cc - xc * cs) / det)
}
