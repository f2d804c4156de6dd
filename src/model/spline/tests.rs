//! Against scipy's own values (tests/data/ross/splines.py writes them): UnivariateSpline's
//! knots, coefficients and values inside and outside the table, and interp1d's for 2 and 3
//! points.

use super::*;

fn cases() -> Vec<serde_json::Value> {
    let text = include_str!("../../../tests/data/ross/splines.json");
    let v: serde_json::Value = serde_json::from_str(text).unwrap();
    v["cases"].as_array().unwrap().clone()
}

fn floats(v: &serde_json::Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

#[test]
fn every_table_is_interpolated_as_scipy_does_for_ross() {
    for case in cases() {
        let name = case["name"].as_str().unwrap();
        let (x, y) = (floats(&case["x"]), floats(&case["y"]));
        let curve = Curve::ross(&x, &y);
        let scale = y.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if let Curve::Spline { t, c } = &curve {
            let (tt, cc) = (floats(&case["t"]), floats(&case["c"]));
            assert_eq!(t.len(), tt.len(), "{name}: knots {t:?} against {tt:?}");
            for (a, b) in t.iter().zip(&tt) {
                assert!(
                    (a - b).abs() <= 1e-12 * b.abs().max(1.0),
                    "{name}: knot {a} vs {b}"
                );
            }
            for (a, b) in c.iter().zip(&cc) {
                assert!(
                    (a - b).abs() <= 1e-9 * scale,
                    "{name}: coefficient {a} vs {b}"
                );
            }
        }
        let mut worst: f64 = 0.0;
        for (at, want) in floats(&case["at"]).iter().zip(floats(&case["values"])) {
            let got = curve.at(*at);
            worst = worst.max((got - want).abs() / scale);
        }
        println!("{name}: within {worst:.1e} of scipy's largest |y|");
        assert!(worst <= 1e-9, "{name}: {worst:.2e}");
    }
}
