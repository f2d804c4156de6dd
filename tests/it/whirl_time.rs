//! Supports over whirl frequency in the time domain (issue 31): each table fitted by Maxwell
//! branches (`damping/whirl_fit.rs`), the fitted model exported by `/v1/damping`, and the time
//! response's steady state against that model's harmonic solution and against the table read
//! exactly at the spin speed.

use crate::common;

use common::{matrix, post_json};
use serde_json::{Value, json};
use whirl::linalg::{CMat, c64, solve_complex};

fn num(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// A mass of 10 kg on a 1e6 N/m shaft, on an anisotropic support with skew cross-coupling
/// whose coefficients are those of one Maxwell branch: per coefficient
/// `H(w) = K0 + i w C0 + G i w / (i w + d)` (N/m, N s/m, N/m; d = 300 1/s), tabulated at 41
/// frequencies 0..1000 rad/s.
const M: f64 = 10.0;
const KS: f64 = 1e6;
const K0: [f64; 4] = [2e5, 4e4, -4e4, 3e5];
const C0: [f64; 4] = [100.0, 0.0, 0.0, 150.0];
const G: [f64; 4] = [3e5, 5e4, 5e4, 2e5];
const D: f64 = 300.0;

/// `(k(w), c(w))` of coefficient `e` (xx, xy, yx, yy).
fn coefficient(e: usize, w: f64) -> (f64, f64) {
    let den = w * w + D * D;
    (K0[e] + G[e] * w * w / den, C0[e] + G[e] * D / den)
}

fn maxwell_mass() -> Value {
    let w: Vec<f64> = (0..=40).map(|i| 25.0 * i as f64).collect();
    let mut support = json!({"node": 0, "frequencies": w});
    for (e, name) in ["xx", "xy", "yx", "yy"].iter().enumerate() {
        support[format!("k{name}")] =
            json!(w.iter().map(|&w| coefficient(e, w).0).collect::<Vec<_>>());
        support[format!("c{name}")] =
            json!(w.iter().map(|&w| coefficient(e, w).1).collect::<Vec<_>>());
    }
    json!({"type": "matrices", "mass": [[M]], "stiffness": [[KS]], "supports": [support]})
}

/// The steady whirl `r(t) = x + i y` of coordinate `at` under the forward unbalance force
/// `F e^{i W t}` there, of the model the second-order matrices `so` describe
/// (`M q'' + (C_n + C_r - i W S G) q' + (K - i W S C_r) q = F`): `Z(iW) X = F`; in doubled
/// coordinates `q = (r, conj r, y_j)` the conjugate rows' forcing at `-W` adds
/// `conj(X_conj) e^{-iWt}`, `conj` the position of `at`'s copy.
fn fitted_steady(
    so: &Value,
    speed: f64,
    force: f64,
    at: usize,
    conj: Option<usize>,
) -> impl Fn(f64) -> c64 {
    let part = |name: &str| -> (Vec<Vec<f64>>, Vec<Vec<f64>>) {
        let re = matrix(&so[name]);
        let im = match so.get("imaginary") {
            Some(i) => matrix(&i[name]),
            None => vec![vec![0.0; re.len()]; re.len()],
        };
        (re, im)
    };
    let spin: Vec<f64> = match so.get("spin") {
        Some(s) => s.as_array().unwrap().iter().map(num).collect(),
        None => vec![1.0; matrix(&so["mass"]).len()],
    };
    let (m, g, k, cr, cn) = (
        part("mass"),
        part("gyroscopic"),
        part("stiffness"),
        part("damping_rotating"),
        part("damping_nonrotating"),
    );
    let n = m.0.len();
    let c = |p: &(Vec<Vec<f64>>, Vec<Vec<f64>>), i: usize, j: usize| c64::new(p.0[i][j], p.1[i][j]);
    let s = c64::new(0.0, speed);
    let iw = c64::new(0.0, speed);
    let z = CMat::from_fn(n, n, |i, j| {
        let damping = c(&cn, i, j) + c(&cr, i, j) - iw * spin[i] * c(&g, i, j);
        let stiffness = c(&k, i, j) - iw * spin[i] * c(&cr, i, j);
        s * s * c(&m, i, j) + s * damping + stiffness
    });
    let f = CMat::from_fn(n, 1, |i, _| {
        c64::new(if i == at { force } else { 0.0 }, 0.0)
    });
    let x = solve_complex(&z, &f).unwrap();
    let x0 = x[(at, 0)];
    let x1 = conj.map_or(c64::new(0.0, 0.0), |c| x[(c, 0)]);
    move |t: f64| {
        let e = c64::new(0.0, speed * t).exp();
        x0 * e + (x1 * e).conj()
    }
}

/// The steady whirl with the table read exactly at `W`: `[X, Y] = H(W)^-1 [F, -i F]` for
/// `f_x = F cos W t`, `f_y = F sin W t`, `H = KS - M W^2 + K(W) + i W C(W)`.
fn table_steady(speed: f64, force: f64) -> impl Fn(f64) -> c64 {
    let h = CMat::from_fn(2, 2, |a, b| {
        let (k, c) = coefficient(2 * a + b, speed);
        let own = if a == b { KS - M * speed * speed } else { 0.0 };
        c64::new(own + k, speed * c)
    });
    let f = CMat::from_fn(2, 1, |a, _| match a {
        0 => c64::new(force, 0.0),
        _ => c64::new(0.0, -force),
    });
    let x = solve_complex(&h, &f).unwrap();
    let (x0, y0) = (x[(0, 0)], x[(1, 0)]);
    move |t: f64| {
        let e = c64::new(0.0, speed * t).exp();
        c64::new((x0 * e).re, (y0 * e).re)
    }
}

#[tokio::test]
async fn the_steady_state_on_a_fitted_support_is_the_fitted_models_and_within_the_fit_of_the_table()
{
    let (speed, amount) = (350.0, 1e-3);
    let force = amount * speed * speed;
    let rotor = maxwell_mass();
    let body = json!({"rotor": rotor, "damping": {"model": "viscous"}, "speed": speed,
                      "unbalances": [{"node": 0, "amount": amount}], "duration": 2.5,
                      "output_interval": 2e-4, "nodes": [0]});
    let (status, r) = post_json("/v1/time-response", &body).await;
    assert_eq!(status, 200, "{r}");
    let fit = &r["support_fits"][0];
    assert_eq!(fit["support"], json!("rotor.supports[0]"), "{fit}");
    let deviation = num(&fit["max_deviation"]);
    assert!(deviation <= 1e-3, "{fit}");
    let branches = fit["rates"].as_array().unwrap().len();
    // The fitted model as matrices: the rotor's two coordinates and two per branch.
    let (status, d) = post_json(
        "/v1/damping",
        &json!({"rotor": rotor, "damping": {"model": "viscous"}, "speed": speed}),
    )
    .await;
    assert_eq!(status, 200, "{d}");
    assert_eq!(
        d["added_states"],
        json!(2 * branches),
        "{}",
        d["coordinates"]
    );
    assert_eq!(d["support_fits"][0], *fit);
    let fitted = fitted_steady(&d["second_order"], speed, force, 0, Some(1));
    let table = table_steady(speed, force);
    // The last 0.02 s (a bit more than one turn): the slowest branch (12.5 1/s, half the
    // band's first frequency) has decayed by e^-31.
    let time: Vec<f64> = r["time"].as_array().unwrap().iter().map(num).collect();
    let node = &r["nodes"][0];
    let (x, y) = (&node["x"], &node["y"]);
    let (mut to_fitted, mut to_table, mut size) = (0.0_f64, 0.0_f64, 0.0_f64);
    for (k, &t) in time.iter().enumerate().filter(|(_, t)| **t >= 2.48) {
        let got = c64::new(num(&x[k]), num(&y[k]));
        to_fitted = to_fitted.max((got - fitted(t)).norm());
        to_table = to_table.max((got - table(t)).norm());
        size = size.max(table(t).norm());
    }
    eprintln!(
        "{branches} branches, deviation {deviation:.3e}; steady state to the fitted model {:.3e}, \
         to the table {:.3e} (amplitude {size:.4e} m)",
        to_fitted / size,
        to_table / size
    );
    assert!(to_fitted <= 1e-8 * size, "{to_fitted} of {size}");
    // X - X~ = Z^-1 (Z~ - Z) X~ with Z the table's dynamic stiffness at W (a knot of the
    // table, where the fit's deviation is measured): each of the four entries of Z~ - Z is at
    // most `deviation` times the support's largest direct |H| over the band, so
    // |dZ|_F <= 2 deviation scale; |X~| <= sqrt 2 of the largest |r~| and |dr| <= sqrt 2 |dX|.
    let scale = (0..=1000)
        .map(|w| {
            let w = w as f64;
            [0, 3]
                .iter()
                .map(|&e| {
                    let (k, c) = coefficient(e, w);
                    c64::new(k, w * c).norm()
                })
                .fold(0.0, f64::max)
        })
        .fold(0.0, f64::max);
    let z = CMat::from_fn(2, 2, |a, b| {
        let (k, c) = coefficient(2 * a + b, speed);
        let own = if a == b { KS - M * speed * speed } else { 0.0 };
        c64::new(own + k, speed * c)
    });
    let identity = CMat::from_fn(2, 2, |a, b| c64::new(if a == b { 1.0 } else { 0.0 }, 0.0));
    let inverse = solve_complex(&z, &identity).unwrap();
    let inverse_norm = (0..4)
        .map(|e| inverse[(e / 2, e % 2)].norm_sqr())
        .sum::<f64>()
        .sqrt();
    let bound = 4.0 * inverse_norm * deviation * scale;
    eprintln!("bound {bound:.3e}");
    assert!(
        to_table <= bound * size,
        "{to_table} of {size}, bound {bound}"
    );
}

/// The bundled seal example with a lossy shaft (loss factor 0.01) under the nonviscous model:
/// the shaft's Maxwell branches and the seal's fitted ones side by side.
fn lossy_seal_example() -> Value {
    let path = format!(
        "{}/examples/seal-over-frequency.time-response.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let mut body: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    body["rotor"]["materials"]["steel"]["loss_factor"] = json!(0.01);
    body["damping"] = json!({"model": "nonviscous"});
    body
}

#[tokio::test]
async fn the_nonviscous_model_and_a_fitted_seal_integrate_together() {
    let body = lossy_seal_example();
    // Held at 472 rad/s: the steady state is the exported model's harmonic solution, its
    // internal coordinates of both kinds included.
    let (speed, amount) = (472.0, 1e-4);
    let mut held = body.clone();
    let obj = held.as_object_mut().unwrap();
    obj.remove("speed_profile");
    held["speed"] = json!(speed);
    held["duration"] = json!(1.5);
    let (status, r) = post_json("/v1/time-response", &held).await;
    assert_eq!(status, 200, "{r}");
    assert_eq!(r["method"], json!("exact"), "{}", r["method"]);
    let (status, d) = post_json(
        "/v1/damping",
        &json!({"rotor": body["rotor"], "damping": body["damping"], "speed": speed}),
    )
    .await;
    assert_eq!(status, 200, "{d}");
    let coordinates = d["coordinates"].as_array().unwrap();
    let kinds = |k: &str| coordinates.iter().filter(|c| c["kind"] == json!(k)).count();
    let support = kinds("support branch");
    assert_eq!(
        support,
        r["support_fits"][0]["rates"].as_array().unwrap().len()
    );
    assert!(kinds("internal") > 0, "{}", d["coordinates"]);
    // The seal's node (15) translation: single coordinates (isotropic supports).
    let at = coordinates
        .iter()
        .position(|c| c["kind"] == json!("translation") && c["node"] == json!(15))
        .unwrap();
    let steady = fitted_steady(&d["second_order"], speed, amount * speed * speed, at, None);
    let time: Vec<f64> = r["time"].as_array().unwrap().iter().map(num).collect();
    let (x, y) = (&r["nodes"][0]["x"], &r["nodes"][0]["y"]);
    let (mut off, mut size) = (0.0_f64, 0.0_f64);
    for (k, &t) in time.iter().enumerate().filter(|(_, t)| **t >= 1.48) {
        let got = c64::new(num(&x[k]), num(&y[k]));
        off = off.max((got - steady(t)).norm());
        size = size.max(steady(t).norm());
    }
    eprintln!("held: {:.3e} of {size:.4e} m", off / size);
    assert!(off <= 1e-8 * size, "{off} of {size}");
    // The run-up: integrated on a checked reduction (the seal's branch poles compared with the
    // rotor's, the shaft's apart).
    let (status, u) = post_json("/v1/time-response", &body).await;
    assert_eq!(status, 200, "{u}");
    let reduction = &u["reduction"];
    assert!(num(&reduction["max_relative_error"]) <= 1e-3, "{reduction}");
    assert!(
        num(&reduction["states"]) < num(&reduction["full_states"]),
        "{reduction}"
    );
}

#[tokio::test]
async fn a_rotor_held_sparse_with_a_fitted_seal_names_the_seal() {
    // The example on 1600 elements: past the dense limits, and its sparse model has no internal
    // coordinates for the seal's branches.
    let mut body = lossy_seal_example();
    body["damping"] = json!({"model": "viscous"});
    let n = 1600;
    common::seal_example_on(&mut body["rotor"], n);
    body["nodes"] = json!([n / 2]);
    body["unbalances"][0]["node"] = json!(n / 2);
    let (status, r) = post_json("/v1/time-response", &body).await;
    assert_eq!(status, 422, "{r}");
    assert!(r.to_string().contains("rotor.seals[0].frequencies"), "{r}");
}
