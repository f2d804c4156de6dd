//! Single speeds and frequencies typed in rpm, Hz or cpm (`{value, unit}`), and speed profiles
//! in a unit (`{points, unit}`): the same answer as the rad/s request. Hand numbers:
//! 3000 rpm = 3000 pi / 30 = 314.1592653589793 rad/s; 50 Hz = 100 pi = the same;
//! 5729.5779513 rpm = 600 rad/s.

use crate::common;

use serde_json::{Value, json};

const W_3000_RPM: f64 = 314.1592653589793;

fn example(name: &str) -> Value {
    let path = format!("{}/examples/{name}", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// Every number of `a` within `tol` of `b`'s, relative to the largest magnitude among the
/// numbers of the same array or object (poles of very different sizes sit together).
fn same(a: &Value, b: &Value, tol: f64, at: &str) {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap(), y.as_f64().unwrap());
            assert!(
                (x - y).abs() <= tol * x.abs().max(y.abs()).max(1e-300),
                "{at}: {x} vs {y}"
            );
        }
        (Value::Array(x), Value::Array(y)) => {
            assert_eq!(x.len(), y.len(), "{at}: lengths");
            let scale = magnitude(a).max(magnitude(b));
            for (i, (p, q)) in x.iter().zip(y).enumerate() {
                match (p, q) {
                    (Value::Number(u), Value::Number(v)) => {
                        let (u, v) = (u.as_f64().unwrap(), v.as_f64().unwrap());
                        assert!((u - v).abs() <= tol * scale, "{at}[{i}]: {u} vs {v}");
                    }
                    _ => same(p, q, tol, &format!("{at}[{i}]")),
                }
            }
        }
        (Value::Object(x), Value::Object(y)) => {
            assert_eq!(
                x.keys().collect::<Vec<_>>(),
                y.keys().collect::<Vec<_>>(),
                "{at}: fields"
            );
            for (k, p) in x {
                same(p, &y[k], tol, &format!("{at}.{k}"));
            }
        }
        _ => assert_eq!(a, b, "{at}"),
    }
}

/// Every number of `v`, in order (arrays of different lengths differ too).
fn numbers(v: &Value) -> Vec<f64> {
    match v {
        Value::Number(x) => vec![x.as_f64().unwrap()],
        Value::Array(a) => a.iter().flat_map(numbers).collect(),
        Value::Object(o) => o.values().flat_map(numbers).collect(),
        _ => vec![],
    }
}

fn magnitude(v: &Value) -> f64 {
    match v {
        Value::Number(x) => x.as_f64().unwrap().abs(),
        Value::Array(a) => a.iter().map(magnitude).fold(0.0, f64::max),
        Value::Object(o) => o.values().map(magnitude).fold(0.0, f64::max),
        _ => 0.0,
    }
}

/// `uri` with `field` as typed in rad/s and as `{value, unit}`: equal answers (the speed
/// differs from the typed rad/s one by the rounding of `value * rad_s(unit)` only).
async fn typed_both_ways(uri: &str, body: &Value, field: &str, rad_s: f64, typed: Value) {
    let mut plain = body.clone();
    plain[field] = json!(rad_s);
    let mut other = body.clone();
    other[field] = typed;
    let b = both(uri, &plain, &other).await;
    // The typed speed matters: 0.7 times it answers differently (beyond the echoed speed).
    let mut slower = body.clone();
    slower[field] = json!(0.7 * rad_s);
    let (s, c) = common::post_json(uri, &slower).await;
    assert_eq!(s, 200, "{uri}: {c}");
    let mut c = c;
    c[field] = b[field].clone();
    assert!(numbers(&c) != numbers(&b), "{uri}: {field} changes nothing");
    if let Some(w) = b.get(field).and_then(Value::as_f64) {
        assert!((w - rad_s).abs() <= 1e-12 * rad_s, "{uri}: answered {w}");
    }
}

/// The answers to two requests that mean the same, equal to 1e-9; the second one.
async fn both(uri: &str, plain: &Value, typed: &Value) -> Value {
    let (s, a) = common::post_json(uri, plain).await;
    assert_eq!(s, 200, "{uri}: {a}");
    let (s, b) = common::post_json(uri, typed).await;
    assert_eq!(s, 200, "{uri}: {b}");
    same(&a, &b, 1e-9, uri);
    b
}

#[tokio::test]
async fn modal_at_3000_rpm_is_modal_at_314_rad_s() {
    let j = example("example1-hysteretic.modal.json");
    let rpm = json!({"value": 3000, "unit": "rpm"});
    typed_both_ways("/v1/modal", &j, "speed", W_3000_RPM, rpm).await;
    let hz = json!({"value": 50, "unit": "Hz"});
    typed_both_ways("/v1/modal", &j, "speed", W_3000_RPM, hz).await;
    let cpm = json!({"value": 3000, "unit": "cpm"});
    typed_both_ways("/v1/modal", &j, "speed", W_3000_RPM, cpm).await;
    let rad = json!({"value": 314.1592653589793, "unit": "rad/s"});
    typed_both_ways("/v1/modal", &j, "speed", W_3000_RPM, rad).await;
}

#[tokio::test]
async fn level1_and_frequency_response_speed_in_rpm() {
    // 600 rad/s = 5729.577951308232 rpm.
    let rpm = json!({"value": 600.0 * 30.0 / std::f64::consts::PI, "unit": "rpm"});
    let j = example("example1-hysteretic.level1.json");
    typed_both_ways("/v1/level1", &j, "speed", 600.0, rpm.clone()).await;
    let j = example("example1-hysteretic.frequency-response.json");
    typed_both_ways("/v1/frequency-response", &j, "speed", 600.0, rpm).await;
}

/// Tabulated fluid-film bearings read at 1000 rad/s (a table speed): the static deflection on
/// them and the damping matrices there, typed in Hz.
#[tokio::test]
async fn static_and_damping_speed_in_hz() {
    let mut rotor = example("fluid-film.unbalance-response.json")["rotor"].clone();
    rotor["materials"]["steel"]["loss_factor"] = json!(0.002);
    let hz = json!({"value": 1000.0 / (2.0 * std::f64::consts::PI), "unit": "Hz"});
    let statics = json!({"rotor": rotor, "supports": "elastic"});
    typed_both_ways("/v1/static", &statics, "speed", 1000.0, hz.clone()).await;
    let damping = json!({"rotor": rotor, "damping": {"model": "equivalent"}});
    typed_both_ways("/v1/damping", &damping, "speed", 1000.0, hz).await;
}

/// `max_frequency` in Hz bounds the Campbell as the same bound in rad/s.
#[tokio::test]
async fn campbell_bound_in_hz() {
    let j = example("anisotropic.campbell.json");
    let hz = json!({"value": 1500.0 / (2.0 * std::f64::consts::PI), "unit": "Hz"});
    typed_both_ways("/v1/campbell", &j, "max_frequency", 1500.0, hz).await;
}

/// A constant speed in rpm and a run-up profile in rpm: the rad/s histories.
#[tokio::test]
async fn time_response_speed_and_profile_in_rpm() {
    let mut j = example("example1-runup-nvd.time-response.json");
    j["duration"] = json!(0.5);
    j["output_interval"] = json!(0.01);
    let k = 30.0 / std::f64::consts::PI;
    let mut typed = j.clone();
    typed["speed_profile"] = json!({"points": [[0, 0], [3, 600.0 * k]], "unit": "rpm"});
    both("/v1/time-response", &j, &typed).await;
    j.as_object_mut().unwrap().remove("speed_profile");
    let rpm = json!({"value": 600.0 * k, "unit": "rpm"});
    typed_both_ways("/v1/time-response", &j, "speed", 600.0, rpm).await;
}

/// A typed speed out of range or in an unknown unit: 422 naming the number or the unit.
#[tokio::test]
async fn a_bad_typed_speed_names_its_field() {
    let j = example("example1-hysteretic.modal.json");
    for (speed, field) in [
        (json!({"value": -10, "unit": "rpm"}), "speed.value"),
        (json!({"value": 10, "unit": "rps"}), "speed.unit"),
        (json!({"value": 10}), "speed"),
        (json!("3000 rpm"), "speed"),
    ] {
        let mut b = j.clone();
        b["speed"] = speed.clone();
        let (s, e) = common::post_json("/v1/modal", &b).await;
        assert_eq!(s, 422, "{speed}: {e}");
        let fields: Vec<&str> = e["errors"]
            .as_array()
            .unwrap_or_else(|| panic!("{e}"))
            .iter()
            .filter_map(|x| x["path"].as_str())
            .collect();
        assert!(fields.contains(&field), "{speed}: {e}");
    }
    let mut b = example("anisotropic.campbell.json");
    b["max_frequency"] = json!({"value": 0, "unit": "Hz"});
    let (s, e) = common::post_json("/v1/campbell", &b).await;
    assert_eq!(s, 422, "{e}");
    assert_eq!(e["errors"][0]["path"], "max_frequency.value", "{e}");
    let mut b = example("example1-runup-nvd.time-response.json");
    b["speed_profile"] = json!({"points": [[0, 0], [3, -5]], "unit": "Hz"});
    let (s, e) = common::post_json("/v1/time-response", &b).await;
    assert_eq!(s, 422, "{e}");
    assert!(e.to_string().contains("speed_profile.points"), "{e}");
}
