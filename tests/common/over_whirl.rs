//! The supports over whirl frequency the tests of issue 31 share: a mass on a support linear
//! in the whirl frequency, and a seal on the 30-element stepped rotor.

use serde_json::{Value, json};

pub fn num(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// A mass of 10 kg on a 1e6 N/m shaft, on a support with `k(w) = 2e5 + 500 w` N/m and
/// `c(w) = 100 + 0.5 w` N s/m, tabulated at whirl frequencies 0..500 rad/s (linear in `w`, so
/// PCHIP reads it exactly).
pub const M: f64 = 10.0;
pub const KS: f64 = 1e6;
pub const K0: f64 = 2e5;
pub const K1: f64 = 500.0;
pub const C0: f64 = 100.0;
pub const C1: f64 = 0.5;

pub fn table() -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let w: Vec<f64> = (0..6).map(|i| 100.0 * i as f64).collect();
    let k = w.iter().map(|w| K0 + K1 * w).collect();
    let c = w.iter().map(|w| C0 + C1 * w).collect();
    (w, k, c)
}

pub fn one_mass(speed_table: bool) -> Value {
    let (w, k, c) = table();
    let (kxx, cxx) = match speed_table {
        // The same at two spin speeds: a list per speed.
        true => (json!([k, k]), json!([c, c])),
        false => (json!(k), json!(c)),
    };
    let mut support = json!({"node": 0, "frequencies": w, "kxx": kxx, "cxx": cxx});
    if speed_table {
        support["speeds"] = json!([0.0, 1000.0]);
    }
    json!({"type": "matrices", "mass": [[M]], "stiffness": [[KS]], "supports": [support]})
}

/// A seal at mid-span of the 30-element stepped rotor, anisotropic and cross-coupled, over
/// whirl frequency and spin speed, each coefficient linear in both (N/m, N s/m; `w`, `W` in
/// rad/s), so that its reading at any point is known by hand.
pub fn seal_at(w: f64, spin: f64) -> [(&'static str, f64); 6] {
    [
        ("kxx", 2e6 + 1000.0 * w + 500.0 * spin),
        ("kyy", 3e6 + 800.0 * w),
        ("kxy", 5e5 + 200.0 * w + 100.0 * spin),
        ("kyx", -(4e5 + 300.0 * w)),
        ("cxx", 500.0 + 0.2 * w),
        ("cyy", 500.0 + 0.2 * w),
    ]
}

pub fn sealed(seal: Value, loss: f64) -> Value {
    let mut rotor = super::stepped_rotor(30, json!({"stiffness": 5e7, "damping": 2e3}), loss);
    rotor["seals"] = json!([seal]);
    rotor
}

pub fn tabulated_seal(loss: f64) -> Value {
    let freqs: Vec<f64> = (0..11).map(|i| 200.0 * i as f64).collect();
    let speeds = [0.0, 1000.0];
    let mut seal = json!({"node": 15, "frequencies": freqs, "speeds": speeds});
    for (k, name) in ["kxx", "kyy", "kxy", "kyx", "cxx", "cyy"]
        .iter()
        .enumerate()
    {
        let rows: Vec<Vec<f64>> = speeds
            .iter()
            .map(|&spin| freqs.iter().map(|&w| seal_at(w, spin)[k].1).collect())
            .collect();
        seal[*name] = json!(rows);
    }
    if loss > 0.0 {
        seal["loss_factor"] = json!(loss);
    }
    seal
}
