//! Speeds and frequencies typed in rpm, Hz or cpm (`unit` on `speeds`, `frequencies` and
//! `operating_range`): the same answer as the same speeds typed in rad/s, and CSV headers that
//! carry each column's unit.

use crate::common;

use serde_json::{Value, json};
use std::f64::consts::PI;

fn example(name: &str) -> Value {
    let path = format!("{}/examples/{name}", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// 0 to 12 000 rpm by 50 rpm with the operating range 8 000 to 10 000 rpm, against the same
/// speeds converted by hand (`n pi / 30` rad/s): the same speeds to the bit, the same answer
/// (peaks and margins too) to round-off (1e-10 relative).
#[tokio::test]
async fn rpm_grid_and_range_are_the_rad_s_ones() {
    let mut rpm = example("example1-nvd.unbalance-response.json");
    rpm["speeds"] = json!({"start": 0, "stop": 12000, "count": 241, "unit": "rpm"});
    rpm["operating_range"] = json!({"min": 8000, "max": 10000, "unit": "rpm"});
    let mut rad = rpm.clone();
    let list: Vec<f64> = (0..241).map(|i| (50.0 * i as f64) * (PI / 30.0)).collect();
    rad["speeds"] = json!(list);
    rad["operating_range"] = json!({"min": 8000.0 * (PI / 30.0), "max": 10000.0 * (PI / 30.0)});
    let (s1, a) = common::post_json("/v1/unbalance-response", &rpm).await;
    let (s2, b) = common::post_json("/v1/unbalance-response", &rad).await;
    assert_eq!((s1, s2), (200, 200), "{a} {b}");
    assert_eq!(a["speeds"], b["speeds"]);
    let mut diffs = vec![];
    differ(&a, &b, String::new(), &mut diffs);
    assert!(diffs.is_empty(), "{diffs:?}");
    // 12 000 rpm is 1256.637 rad/s.
    let last = a["speeds"][240].as_f64().unwrap();
    assert!((last - 1256.6370614359173).abs() < 1e-9, "{last}");
    assert!(
        a["nodes"][0]["peaks"]
            .as_array()
            .is_some_and(|p| !p.is_empty())
    );
}

/// Paths where `a` and `b` differ.
fn differ(a: &Value, b: &Value, at: String, out: &mut Vec<String>) {
    match (a, b) {
        (Value::Object(x), Value::Object(y)) => {
            for k in x.keys().chain(y.keys()) {
                let n = Value::Null;
                differ(
                    x.get(k).unwrap_or(&n),
                    y.get(k).unwrap_or(&n),
                    format!("{at}.{k}"),
                    out,
                );
            }
        }
        (Value::Array(x), Value::Array(y)) if x.len() == y.len() => {
            for (i, (p, q)) in x.iter().zip(y).enumerate() {
                differ(p, q, format!("{at}[{i}]"), out);
            }
        }
        // Sums taken in another order (threads) differ by round-off only.
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap(), y.as_f64().unwrap());
            if (x - y).abs() > 1e-10 * x.abs().max(y.abs()) {
                out.push(format!("{at}: {x} vs {y}"));
            }
        }
        _ if a != b => out.push(format!("{at}: {a} vs {b}")),
        _ => {}
    }
}

/// Frequencies in Hz (a list) and in cpm (a grid), the Jeffcott sweep in Hz.
#[tokio::test]
async fn hz_and_cpm() {
    let mut hz = example("example1-hysteretic.frequency-response.json");
    hz["frequencies"] = json!({"values": [10, 50, 100], "unit": "Hz"});
    let (s, a) = common::post_json("/v1/frequency-response", &hz).await;
    assert_eq!(s, 200, "{a}");
    let f: Vec<f64> = serde_json::from_value(a["frequencies"].clone()).unwrap();
    for (got, want) in f
        .iter()
        .zip([62.83185307179586, 314.1592653589793, 628.3185307179587])
    {
        assert!((got - want).abs() < 1e-9 * want, "{got} {want}");
    }
    let mut cpm = hz.clone();
    cpm["frequencies"] = json!({"start": 600, "stop": 6000, "count": 2, "unit": "cpm"});
    let (s, b) = common::post_json("/v1/frequency-response", &cpm).await;
    assert_eq!(s, 200, "{b}");
    // 600 cpm is 10 Hz: the same response as the first frequency above.
    assert_eq!(b["amplitude"][0], a["amplitude"][0]);
    assert!((b["frequencies"][1].as_f64().unwrap() - 628.3185307179587).abs() < 1e-9);
    // One frequency in a unit.
    hz["frequencies"] = json!({"values": [50], "unit": "Hz"});
    let (s, c) = common::post_json("/v1/frequency-response", &hz).await;
    assert_eq!(s, 200, "{c}");
    assert_eq!(c["amplitude"][0], a["amplitude"][1]);

    let mut j = example("jeffcott-nvd.campbell.json");
    j["speeds"] = json!({"start": 0, "stop": 0.5, "count": 11, "unit": "Hz"});
    let (s, c) = common::post_json("/v1/campbell", &j).await;
    assert_eq!(s, 200, "{c}");
    assert!((c["speeds"][10].as_f64().unwrap() - PI).abs() < 1e-15);
}

/// An unknown unit, and a bad value of a list in a unit: 422 naming the field.
#[tokio::test]
async fn bad_units_name_their_field() {
    let mut j = example("jeffcott-nvd.campbell.json");
    j["speeds"] = json!({"start": 0, "stop": 3, "count": 11, "unit": "rps"});
    let (s, e) = common::post_json("/v1/campbell", &j).await;
    assert_eq!(s, 422, "{e}");
    assert!(e.to_string().contains("speeds"), "{e}");
    j["speeds"] = json!({"values": [0, 2, 1], "unit": "rpm"});
    let (s, e) = common::post_json("/v1/campbell", &j).await;
    assert_eq!(s, 422, "{e}");
    assert!(e.to_string().contains("speeds.values[2]"), "{e}");
}

/// Every CSV column says its unit.
#[tokio::test]
async fn csv_headers_carry_units() {
    for (uri, file, header) in [
        (
            "/v1/campbell",
            "jeffcott-nvd.campbell.json",
            "speed [rad/s],mode1_forward_frequency [rad/s],mode1_forward_decay_rate [1/s],\
             mode1_forward_log_decrement [-]",
        ),
        (
            "/v1/frequency-response",
            "example1-hysteretic.frequency-response.json",
            "frequency [rad/s],amplitude [m/N],phase [rad]",
        ),
        (
            "/v1/critical-speed-map",
            "rotor-a.critical-speed-map.json",
            "stiffness [N/m],mode1_frequency [rad/s]",
        ),
    ] {
        let (s, ctype, body) = common::post_as(uri, &example(file), "text/csv").await;
        assert_eq!((s, ctype.as_str()), (200, "text/csv"));
        let csv = String::from_utf8(body).unwrap();
        assert!(
            csv.starts_with(header),
            "{file}: {}",
            csv.lines().next().unwrap()
        );
        let first = csv.lines().next().unwrap();
        for col in first.split(',') {
            assert!(
                col.ends_with(']') || col == "whirl" || col == "node",
                "{file}: {col} has no unit"
            );
        }
    }
}
