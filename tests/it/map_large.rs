//! The undamped critical speed map of rotors past the dense limits (issue 30): past 600
//! coordinates the shaft is held sparse and each stiffness's lowest modes come from
//! shift-invert Lanczos on a sparse Cholesky factor, work linear in the mesh. Checked against
//! the dense eigensolver on the same 1000-element rotor, and a 4000-element mesh against it.

use crate::common;

use common::{floats, post_json};
use serde_json::{Value, json};
use std::time::Instant;
use whirl::analysis::audit::critical_map::frequencies_at;

/// A stepped steel shaft of `elements` elements per segment (three segments, 1.6 m) with two
/// disks and two bearings.
fn rotor(elements: usize) -> Value {
    let e = elements;
    json!({
        "type": "beam",
        "materials": {"steel": {"density": 7810.0, "young_modulus": 2.11e11, "poisson_ratio": 0.3}},
        "shaft": [
            {"length": 0.4, "outer_diameter": 0.05, "material": "steel", "elements": e},
            {"length": 0.8, "outer_diameter": 0.08, "material": "steel", "elements": 2 * e},
            {"length": 0.4, "outer_diameter": 0.05, "material": "steel", "elements": e}
        ],
        "disks": [{"node": 2 * e, "mass": 30.0, "polar_inertia": 0.3, "transverse_inertia": 0.16},
                  {"node": 3 * e, "mass": 20.0, "polar_inertia": 0.2, "transverse_inertia": 0.11}],
        "supports": [{"node": 0, "stiffness": 1e7}, {"node": 4 * e, "stiffness": 1e7}]
    })
}

/// The domain rotor of `rotor`, within the sparse limits.
fn beam(rotor: &Value) -> whirl::model::rotor::BeamRotor {
    use whirl::model::rotor::Rotor;
    let input: whirl::model::api::RotorInput = serde_json::from_value(rotor.clone()).unwrap();
    let limits = whirl::model::Limits {
        max_dofs: 200_000,
        ..Default::default()
    };
    match Rotor::parse(&input, &limits).unwrap() {
        Rotor::Beam(b) => b,
        _ => panic!("not a beam rotor"),
    }
}

fn relative(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs() / y.abs())
        .fold(0.0, f64::max)
}

/// 1000 elements (2002 complex coordinates): the sparse Lanczos modes against the dense
/// eigensolver's on the same rotor, from soft springs to stiff ones, and on free-free springs
/// (1 N/m: two rigid modes near zero) where the pencil must be shifted. The first mode on soft
/// springs (nearly a rigid motion, already converged on 25 elements) is compared with the
/// 25-element mesh's instead: there the dense solve of the fine mesh loses 7.7e-7 to round-off
/// (its error grows with the largest element frequency), the sparse one 7.6e-9.
#[test]
#[ignore = "heavy: a dense reference of a large rotor (cargo test --release -- --ignored)"]
fn sparse_modes_equal_dense_ones_on_one_rotor() {
    let r = beam(&rotor(250));
    let coarse = beam(&rotor(25));
    for k in [1e5, 1e6, 1e7, 1e8, 1e10] {
        let dense = frequencies_at(&r, k, 4, false).unwrap();
        let sparse = frequencies_at(&r, k, 4, true).unwrap();
        let first = frequencies_at(&coarse, k, 1, false).unwrap()[0];
        let (e1, rest) = (
            relative(&sparse[..1], &[first]),
            relative(&sparse[1..], &dense[1..]),
        );
        println!(
            "k = {k:.0e} N/m: {sparse:.4?} rad/s; modes 2-4 {rest:.1e} from dense, mode 1 {e1:.1e} from 25 elements"
        );
        // Measured: modes 2-4 within 5.9e-8, mode 1 within 1.9e-8 (the 25-element mesh's
        // discretization at stiff springs).
        assert!(rest <= 1e-7, "{k}: {sparse:?} vs {dense:?}");
        assert!(e1 <= 3e-8, "{k}: {} vs {first}", sparse[0]);
    }
    let dense = frequencies_at(&r, 1.0, 6, false).unwrap();
    let sparse = frequencies_at(&r, 1.0, 6, true).unwrap();
    println!("k = 1 N/m: {sparse:.4?} rad/s (dense {dense:.4?})");
    // Two rigid modes (sqrt(k / m) is about 0.1 rad/s); the bending ones as dense.
    assert!(sparse[..2].iter().all(|w| *w < 1.0), "{sparse:?}");
    assert!(
        relative(&sparse[2..], &dense[2..]) <= 1e-7,
        "{sparse:?} vs {dense:?}"
    );
}

/// Over HTTP: 4000 elements (8002 coordinates, eight times the dense limit) answer with the
/// 1000-element mesh's frequencies within that mesh's discretization (it converges as h^2 on
/// this rotor: the fourth mode at 1e10 N/m moved 2.9e-6, 7.4e-7, 1.2e-7 from 25, 100, 1000
/// elements to 4000), and more than 100 modes of a rotor past the dense limit is a 422 naming
/// `modes`.
#[tokio::test]
async fn a_4000_element_map_over_http() {
    let body = |elements: usize, modes: usize| {
        json!({"rotor": rotor(elements), "modes": modes,
               "stiffness": {"start": 1e5, "stop": 1e10, "count": 12}})
    };
    let start = Instant::now();
    let (status, fine) = post_json("/v1/critical-speed-map", &body(1000, 4)).await;
    let seconds = start.elapsed().as_secs_f64();
    assert_eq!(status, 200, "{fine}");
    let (status, coarse) = post_json("/v1/critical-speed-map", &body(250, 4)).await;
    assert_eq!(status, 200, "{coarse}");
    let mut worst = 0.0f64;
    for m in 0..4 {
        let (a, b) = (
            floats(&fine["frequencies"][m]),
            floats(&coarse["frequencies"][m]),
        );
        worst = worst.max(relative(&b, &a));
    }
    println!(
        "4000 elements, 12 stiffnesses, 4 modes: {seconds:.2} s; 1000 elements within {worst:.1e}"
    );
    assert!(worst <= 2e-7, "{worst}");
    let (status, out) = post_json("/v1/critical-speed-map", &body(1000, 101)).await;
    assert_eq!(status, 422, "{out}");
    assert!(out.to_string().contains("modes"), "{out}");
}

/// The first natural frequency on rigid supports (`rigid_first`, the critical speed ratio's
/// `N_c1`) of a uniform solid steel shaft pinned at its ends, 1.5 m long and 50 mm across,
/// against the Timoshenko beam's closed form: with `k = pi / L` the mode `sin(k x)` is exact and
/// `omega^2` is the smaller root of
/// `(rho^2 I / (kappa G)) w^4 - (rho A + rho I k^2 + E I rho k^2 / (kappa G)) w^2 + E I k^4 = 0`
/// (each term N/m^2 per unit deflection), `kappa = 6 (1 + nu) / (7 + 6 nu)` (Cowper, as the
/// element). 100 elements (202 coordinates) are solved dense, 1000 (2002) by Lanczos on the
/// sparse pencil with the pinned translations removed, in 5 ms.
#[test]
fn rigid_first_on_a_pinned_shaft_is_the_timoshenko_closed_form() {
    use whirl::analysis::audit::critical_map::rigid_first;
    let (l, d, e, rho, nu) = (1.5f64, 0.05f64, 2.11e11f64, 7810.0f64, 0.3f64); // m, m, Pa, kg/m^3
    let area = std::f64::consts::PI * d * d / 4.0; // m^2
    let inertia = std::f64::consts::PI * d.powi(4) / 64.0; // m^4
    let kappa = 6.0 * (1.0 + nu) / (7.0 + 6.0 * nu);
    let kg = kappa * e / (2.0 * (1.0 + nu)); // Pa
    let k = std::f64::consts::PI / l; // 1/m
    let a4 = rho * rho * inertia / kg;
    let a2 = rho * area + rho * inertia * k * k + e * inertia * rho * k * k / kg;
    let a0 = e * inertia * k.powi(4);
    let w2 = (a2 - (a2 * a2 - 4.0 * a4 * a0).sqrt()) / (2.0 * a4); // rad^2/s^2
    let exact = w2.sqrt(); // rad/s
    let mut errors = vec![];
    for elements in [100usize, 1000] {
        let rotor = json!({
            "type": "beam",
            "materials": {"steel": {"density": rho, "young_modulus": e, "poisson_ratio": nu}},
            "shaft": [{"length": l, "outer_diameter": d, "material": "steel", "elements": elements}],
            "supports": [{"node": 0, "stiffness": 1e7}, {"node": elements, "stiffness": 1e7}]
        });
        let t = Instant::now();
        let w = rigid_first(&beam(&rotor)).unwrap();
        let err = (w - exact).abs() / exact;
        println!(
            "{elements} elements: {w:.9} rad/s against {exact:.9} ({err:.1e}), {:.3} s",
            t.elapsed().as_secs_f64()
        );
        errors.push(err);
    }
    // The element converges as h^2 (measured 8.3e-8 at 100 elements, 6.0e-10 at 1000).
    assert!(errors[0] <= 1e-7, "{errors:?}");
    assert!(errors[1] <= 1e-9, "{errors:?}");
}
