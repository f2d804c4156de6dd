//! The static analysis of rotors past the dense limits (issue 30): `/v1/static` holds the
//! shaft sparse (a beam couples neighbouring nodes only), so a shaft of thousands of elements
//! and a train of shafts joined by couplings answer with work linear in the mesh. Checked
//! against closed forms of a uniform Timoshenko beam (whose nodal values the element gives
//! exactly) and, on a train, a coarse mesh on the dense path against the same train meshed
//! 60 times finer on the sparse one.

use crate::common;

use common::{floats, post_json};
use serde_json::{Value, json};
use std::time::Instant;

const E: f64 = 2.11e11; // Pa
const RHO: f64 = 7810.0; // kg/m^3
const NU: f64 = 0.3;
/// Standard gravity, m/s^2: what `/v1/static` uses when the request gives none.
const G: f64 = 9.80665;
const L: f64 = 2.0; // m
const D: f64 = 0.06; // m

/// The round-off of a beam's static solve, relative: its stiffness's condition number grows as
/// `(L / h)^4`, and the midspan deflection of this shaft pinned at its ends moved from the
/// closed form by 1.4e-14 at 10 elements, 6.1e-13 at 100, 1.2e-9 at 1000 and 3.6e-9 at 4000
/// (its largest moment 8.1e-9), on the dense path and the sparse one alike.
const ROUND_OFF: f64 = 1e-8;

/// A uniform solid steel shaft of `elements` elements between supports at its two ends.
fn shaft(elements: usize, support: Value) -> Value {
    let at = |node: usize| {
        let mut s = support.clone();
        s["node"] = json!(node);
        s
    };
    json!({
        "type": "beam",
        "materials": {"steel": {"density": RHO, "young_modulus": E, "poisson_ratio": NU}},
        "shaft": [{"length": L, "outer_diameter": D, "material": "steel", "elements": elements}],
        "supports": [at(0), at(elements)],
    })
}

/// The uniform shaft's weight per length `w` (N/m) and its midspan deflection under it pinned
/// at both ends (m, downward positive): bending `5 w L^4 / (384 E I)` plus shear
/// `w L^2 / (8 kappa G A)`, `kappa = 6 (1 + nu) / (7 + 6 nu)` (Cowper, solid section).
fn closed_form() -> (f64, f64) {
    let area = std::f64::consts::PI * D * D / 4.0; // m^2
    let inertia = std::f64::consts::PI * D.powi(4) / 64.0; // m^4
    let w = RHO * area * G; // N/m
    let kappa = 6.0 * (1.0 + NU) / (7.0 + 6.0 * NU);
    let shear_modulus = E / (2.0 * (1.0 + NU)); // Pa
    let bending = 5.0 * w * L.powi(4) / (384.0 * E * inertia); // m
    let shear = w * L * L / (8.0 * kappa * shear_modulus * area); // m
    (w, bending + shear)
}

async fn statics(body: &Value) -> (Value, f64) {
    let start = Instant::now();
    let (status, out) = post_json("/v1/static", body).await;
    let seconds = start.elapsed().as_secs_f64();
    assert_eq!(status, 200, "{out}");
    (out, seconds)
}

fn node(out: &Value, i: usize) -> &Value {
    &out["nodes"][i]
}

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap()
}

/// 4000 elements pinned at their ends (8002 complex degrees of freedom, eight times the dense
/// limit): midspan deflection, reactions and largest moment as the closed forms give them.
#[tokio::test]
async fn pinned_shaft_of_4000_elements() {
    let n = 4000;
    let body = json!({"rotor": shaft(n, json!({"stiffness": 1e9})), "supports": "rigid"});
    let (out, seconds) = statics(&body).await;
    let (w, delta) = closed_form();
    let mid = f(&node(&out, n / 2)["deflection"]);
    println!(
        "{n} elements, pinned: midspan {mid:.6e} m (closed form {:.6e}), {seconds:.3} s",
        -delta
    );
    assert!(
        (mid + delta).abs() <= ROUND_OFF * delta,
        "{mid} vs {}",
        -delta
    );
    // Each end carries half the weight, N; the moment's extreme is w L^2 / 8 at midspan, N m.
    for r in out["supports"].as_array().unwrap() {
        let reaction = f(&r["reaction"]);
        assert!((reaction - w * L / 2.0).abs() <= ROUND_OFF * w * L, "{r}");
    }
    let moment = f(&out["max_moment"]);
    let wl2 = w * L * L / 8.0;
    assert!(
        (moment.abs() - wl2).abs() <= 2.0 * ROUND_OFF * wl2,
        "{moment}"
    );
    assert!((f(&out["max_moment_position"]) - L / 2.0).abs() <= 1e-9);
    assert!((f(&out["weight"]) - w * L).abs() <= 1e-9 * w * L);
}

/// The same shaft on cross-coupled elastic bearings: each bearing carries half the weight, so
/// its journal sits at `[x, y]` with `K [x, y] = [0, -w L / 2]` (the x plane unloaded, the
/// cross-coupling moves it sideways), and the shaft bends between them as when pinned.
#[tokio::test]
async fn cross_coupled_bearings_of_a_2000_element_shaft() {
    let n = 2000;
    let (kxx, kxy, kyx, kyy) = (3.0e7, 6.0e6, -4.0e6, 2.0e7); // N/m
    let bearing = json!({"kxx": kxx, "kxy": kxy, "kyx": kyx, "kyy": kyy, "cxx": 1e3, "cyy": 1e3});
    let (out, seconds) = statics(&json!({"rotor": shaft(n, bearing)})).await;
    let (w, delta) = closed_form();
    let r = w * L / 2.0; // N
    let det = kxx * kyy - kxy * kyx;
    let (x, y) = (kxy * r / det, -kxx * r / det); // m
    let end = node(&out, 0);
    let mid = node(&out, n / 2);
    println!(
        "{n} elements, cross-coupled: journal ({:.6e}, {:.6e}) m (closed form ({x:.6e}, \
         {y:.6e})), midspan y {:.6e}, {seconds:.3} s",
        f(&end["deflection_x"]),
        f(&end["deflection"]),
        f(&mid["deflection"])
    );
    let scale = delta + y.abs();
    assert!((f(&end["deflection_x"]) - x).abs() <= ROUND_OFF * scale);
    assert!((f(&end["deflection"]) - y).abs() <= ROUND_OFF * scale);
    assert!((f(&mid["deflection_x"]) - x).abs() <= ROUND_OFF * scale);
    assert!((f(&mid["deflection"]) - (y - delta)).abs() <= ROUND_OFF * scale);
    for s in out["supports"].as_array().unwrap() {
        assert!((f(&s["reaction"]) - r).abs() <= ROUND_OFF * r, "{s}");
        assert!(f(&s["reaction_x"]).abs() <= ROUND_OFF * r, "{s}");
    }
}

/// The bundled train (three shafts, two couplings, six cross-coupled bearings): 18 elements on
/// the dense path against 1080 on the sparse one. A uniform segment's element is exact at its
/// nodes, so the two agree at every coarse node; the reactions hold the whole weight.
#[tokio::test]
async fn train_of_1080_elements_against_its_coarse_mesh() {
    let example: Value = serde_json::from_str(
        &std::fs::read_to_string("examples/train-hysteretic.campbell.json").unwrap(),
    )
    .unwrap();
    let coarse = example["rotor"].clone();
    let (fine, map) = common::refined(&coarse, 60);
    let (a, _) = statics(&json!({"rotor": coarse})).await;
    let (b, seconds) = statics(&json!({"rotor": fine})).await;
    // Each quantity relative to its largest value on the coarse mesh (m, rad).
    let peak = f(&a["max_deflection"]);
    let largest = |key: &str| {
        let nodes = a["nodes"].as_array().unwrap();
        nodes.iter().map(|n| f(&n[key]).abs()).fold(0.0, f64::max)
    };
    let mut worst = 0.0f64;
    for key in ["deflection", "deflection_x", "slope", "slope_x"] {
        let scale = largest(key);
        for (i, &j) in map.iter().enumerate() {
            worst = worst.max((f(&node(&a, i)[key]) - f(&node(&b, j)[key])).abs() / scale);
        }
    }
    let elements = b["nodes"].as_array().unwrap().len() - 1 - 2;
    println!(
        "train, {elements} elements: {seconds:.3} s; nodes within {worst:.1e} of the 18-element \
         mesh's deflection peak {peak:.4e} m"
    );
    assert!(elements >= 1000);
    assert!(worst <= 1e-9, "{worst}");
    for (ra, rb) in a["supports"]
        .as_array()
        .unwrap()
        .iter()
        .zip(b["supports"].as_array().unwrap())
    {
        let (ya, yb) = (f(&ra["reaction"]), f(&rb["reaction"]));
        assert!((ya - yb).abs() <= 1e-9 * f(&a["weight"]), "{ra} {rb}");
    }
    let total: f64 = floats(&Value::Array(
        b["supports"]
            .as_array()
            .unwrap()
            .iter()
            .map(|s| s["reaction"].clone())
            .collect(),
    ))
    .iter()
    .sum();
    assert!(
        (total - f(&b["weight"])).abs() <= 1e-9 * f(&b["weight"]),
        "{total}"
    );
}

/// Past `WHIRL_MAX_SPARSE_DOFS` the request is refused before any work, naming the setting.
#[tokio::test]
async fn past_the_sparse_limit_is_a_422() {
    let body = json!({"rotor": shaft(150_000, json!({"stiffness": 1e8}))});
    let (status, out) = post_json("/v1/static", &body).await;
    assert_eq!(status, 422, "{out}");
    let text = out.to_string();
    assert!(text.contains("WHIRL_MAX_SPARSE_DOFS"), "{text}");
}

/// Without `gravity` the static analysis uses standard gravity, 9.80665 m/s^2 (ROSS's constant,
/// 9.8065, only when a request gives it).
#[tokio::test]
async fn the_default_gravity_is_standard_gravity() {
    // m = 7810 kg/m^3 x pi/4 x (0.06 m)^2 x L: the reactions carry m g, N.
    let mass = RHO * std::f64::consts::FRAC_PI_4 * D * D * L;
    let support = json!({"stiffness": 1e9});
    for (given, g) in [(None, 9.80665), (Some(9.8065), 9.8065)] {
        let mut body = json!({"rotor": shaft(10, support.clone())});
        if let Some(g) = given {
            body["gravity"] = json!(g);
        }
        let (out, _) = statics(&body).await;
        assert_eq!(f(&out["gravity"]), g, "{given:?}");
        let total: f64 = out["supports"]
            .as_array()
            .unwrap()
            .iter()
            .map(|s| f(&s["reaction"]))
            .sum();
        assert!(
            (total - mass * g).abs() < 1e-9 * mass * g,
            "{given:?}: {total} N against {} N",
            mass * g
        );
    }
}
