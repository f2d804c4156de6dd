//! Speeds and frequencies answered in rpm, Hz or cpm (`output_unit`): the answer says which
//! unit it used (`output_unit`, rad/s by default), every speed and whirl or natural frequency
//! is in it and nothing else changes (decay rates stay 1/s); CSV headers name it; plots are
//! the rad/s ones. Hand numbers: 1 rad/s = 30/pi = 9.549296585513721 rpm (and cpm) =
//! 1/(2 pi) = 0.15915494309189535 Hz.

use crate::common;

use serde_json::{Value, json};

const RPM: f64 = 9.549296585513721;
const HZ: f64 = 0.15915494309189535;

fn example(name: &str) -> Value {
    let path = format!("{}/examples/{name}", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn close(got: &Value, want: f64, what: &str) {
    let got = got.as_f64().unwrap_or_else(|| panic!("{what}: {got}"));
    assert!(
        (got - want).abs() <= 1e-9 * want.abs().max(1e-12),
        "{what}: {got}, want {want}"
    );
}

/// Numbers of an array, a `null` (undefined there) as 0.
fn floats(v: &Value) -> Vec<f64> {
    let a = v.as_array().unwrap_or_else(|| panic!("not an array: {v}"));
    a.iter().map(|x| x.as_f64().unwrap_or(0.0)).collect()
}

/// A 10 kg Jeffcott rotor on 1e6 N/m, undamped: its natural frequency is sqrt(k/m) =
/// 316.2278 rad/s = 3019.7527 rpm = 50.3292 Hz at every speed (no gyroscopic coupling).
#[tokio::test]
async fn modal_in_rpm_hz_and_cpm() {
    let body = |unit: Option<&str>| {
        let mut b = json!({
            "rotor": {"type": "jeffcott", "mass": 10.0, "stiffness": 1e6},
            "damping": {"model": "viscous"},
            "speed": 100.0
        });
        if let Some(u) = unit {
            b["output_unit"] = json!(u);
        }
        b
    };
    let wn = 1e5f64.sqrt();
    let (s, rad) = common::post_json("/v1/modal", &body(None)).await;
    assert_eq!(s, 200, "{rad}");
    assert_eq!(rad["output_unit"], "rad/s");
    close(&rad["natural_frequencies"][0], 316.22776601683796, "rad/s");
    for (unit, scale, wn_there, speed) in [
        ("rpm", RPM, 3019.7527, 954.9297),
        ("cpm", RPM, 3019.7527, 954.9297),
        ("Hz", HZ, 50.3292, 15.9155),
        ("rad/s", 1.0, 316.2278, 100.0),
    ] {
        let (s, a) = common::post_json("/v1/modal", &body(Some(unit))).await;
        assert_eq!(s, 200, "{a}");
        assert_eq!(a["output_unit"], unit);
        close(&a["natural_frequencies"][0], wn * scale, unit);
        assert!((a["natural_frequencies"][0].as_f64().unwrap() - wn_there).abs() < 1e-4);
        assert!(
            (a["speed"].as_f64().unwrap() - speed).abs() < 1e-4,
            "{unit}"
        );
        for (p, q) in a["poles"]
            .as_array()
            .unwrap()
            .iter()
            .zip(rad["poles"].as_array().unwrap())
        {
            close(
                &p["frequency"],
                q["frequency"].as_f64().unwrap() * scale,
                unit,
            );
            assert_eq!(p["decay_rate"], q["decay_rate"], "decay rates stay 1/s");
            assert_eq!(p["log_decrement"], q["log_decrement"]);
        }
    }
}

/// The paper's Jeffcott rotor (equivalent damping, eta_r = 0.01, eta_n = 0.02) is unstable
/// from 3 sqrt(k/m) (eq. 10) whirling at 1: in Hz 0.477465 and 0.159155; the range 0 to 5 is
/// 0 to 0.795775 Hz. The Campbell diagram's critical speed 1 is 9.5493 rpm.
#[tokio::test]
async fn stability_and_campbell_in_hz_and_rpm() {
    let mut st = example("jeffcott-equivalent.stability.json");
    st["output_unit"] = json!("Hz");
    let (s, a) = common::post_json("/v1/stability", &st).await;
    assert_eq!(s, 200, "{a}");
    assert_eq!(a["output_unit"], "Hz");
    assert!(
        (a["threshold"].as_f64().unwrap() - 0.477465).abs() < 1e-6,
        "{a}"
    );
    assert!(
        (a["frequency"].as_f64().unwrap() - 0.159155).abs() < 1e-6,
        "{a}"
    );
    close(&a["range"][1], 5.0 * HZ, "range");
    close(&a["speeds"][20], 5.0 * HZ, "speeds");

    let mut c = example("jeffcott-equivalent.campbell.json");
    let (s, rad) = common::post_json("/v1/campbell", &c).await;
    assert_eq!(s, 200, "{rad}");
    assert_eq!(rad["output_unit"], "rad/s");
    c["output_unit"] = json!("rpm");
    let (s, rpm) = common::post_json("/v1/campbell", &c).await;
    assert_eq!(s, 200, "{rpm}");
    assert_eq!(rpm["output_unit"], "rpm");
    close(&rpm["speeds"][60], 3.0 * RPM, "last speed");
    let crit = rpm["critical_speeds"][0].as_f64().unwrap();
    assert!((crit - 9.5493).abs() < 1e-3, "{crit}");
    close(&rpm["criticals"][0]["speed"], crit, "criticals");
    for (b, r) in rpm["branches"]
        .as_array()
        .unwrap()
        .iter()
        .zip(rad["branches"].as_array().unwrap())
    {
        for (x, y) in floats(&b["frequency"]).iter().zip(floats(&r["frequency"])) {
            assert!((x - y * RPM).abs() <= 1e-12 * x.abs().max(1.0), "{x} {y}");
        }
        assert_eq!(b["decay_rate"], r["decay_rate"]);
        assert_eq!(b["log_decrement"], r["log_decrement"]);
    }
    // The CSV says rpm where the JSON is in rpm, 1/s where it is not.
    let (s, _, csv) = common::post_as("/v1/campbell", &c, "text/csv").await;
    assert_eq!(s, 200);
    let csv = String::from_utf8(csv).unwrap();
    assert!(
        csv.starts_with(
            "speed [rpm],mode1_forward_frequency [rpm],mode1_forward_decay_rate [1/s],"
        ),
        "{}",
        csv.lines().next().unwrap()
    );
    let row: Vec<f64> = csv
        .lines()
        .nth(61)
        .unwrap()
        .split(',')
        .take(2)
        .map(|x| x.parse().unwrap())
        .collect();
    assert!((row[0] - 28.6479).abs() < 1e-4, "{row:?}");
    // The plot is the rad/s one whatever the JSON's unit.
    let (_, _, plot_rpm) = common::post_as("/v1/campbell", &c, "image/svg+xml").await;
    c["output_unit"] = json!("rad/s");
    let (_, _, plot_rad) = common::post_as("/v1/campbell", &c, "image/svg+xml").await;
    assert!(plot_rpm == plot_rad, "the plots differ");
}

/// Unbalance peaks, the critical speed map, a frequency response and Level I in cpm, rpm and
/// Hz against the rad/s answers.
#[tokio::test]
async fn responses_and_map_in_other_units() {
    let mut u = example("example1-nvd.unbalance-response.json");
    u["speeds"] = json!({"start": 0, "stop": 12000, "count": 121, "unit": "rpm"});
    let (s, rad) = common::post_json("/v1/unbalance-response", &u).await;
    assert_eq!(s, 200, "{rad}");
    u["output_unit"] = json!("cpm");
    let (s, cpm) = common::post_json("/v1/unbalance-response", &u).await;
    assert_eq!(s, 200, "{cpm}");
    assert_eq!(cpm["output_unit"], "cpm");
    // The grid typed in rpm comes back in rpm: 0, 100, ..., 12 000.
    for (i, w) in floats(&cpm["speeds"]).iter().enumerate() {
        assert!((w - 100.0 * i as f64).abs() < 1e-9, "{i}: {w}");
    }
    let (p, q) = (&cpm["nodes"][0]["peaks"][0], &rad["nodes"][0]["peaks"][0]);
    close(&p["speed"], q["speed"].as_f64().unwrap() * RPM, "peak");
    assert_eq!(p["amplitude"], q["amplitude"]);
    assert_eq!(cpm["nodes"][0]["amplitude"], rad["nodes"][0]["amplitude"]);

    let mut m = example("rotor-a.critical-speed-map.json");
    let (s, rad) = common::post_json("/v1/critical-speed-map", &m).await;
    assert_eq!(s, 200, "{rad}");
    m["output_unit"] = json!("rpm");
    let (s, rpm) = common::post_json("/v1/critical-speed-map", &m).await;
    assert_eq!(s, 200, "{rpm}");
    assert_eq!(rpm["output_unit"], "rpm");
    assert_eq!(rpm["stiffness"], rad["stiffness"]);
    close(
        &rpm["frequencies"][0][3],
        rad["frequencies"][0][3].as_f64().unwrap() * RPM,
        "map",
    );
    close(
        &rpm["intersections"][0]["frequency"],
        rad["intersections"][0]["frequency"].as_f64().unwrap() * RPM,
        "intersection",
    );

    // Frequencies typed in Hz come back in Hz: 10, 50, 100.
    let mut f = example("example1-hysteretic.frequency-response.json");
    f["frequencies"] = json!({"values": [10, 50, 100], "unit": "Hz"});
    f["output_unit"] = json!("Hz");
    let (s, hz) = common::post_json("/v1/frequency-response", &f).await;
    assert_eq!(s, 200, "{hz}");
    assert_eq!(hz["output_unit"], "Hz");
    for (got, want) in floats(&hz["frequencies"]).iter().zip([10.0, 50.0, 100.0]) {
        assert!((got - want).abs() < 1e-12 * want, "{got} {want}");
    }
    close(&hz["speed"], f["speed"].as_f64().unwrap() * HZ, "speed");

    // Level I at 600 rad/s = 5729.578 rpm: its speed, frequencies and the rigid critical
    // speed in rpm, the cross-coupling (N/m) and log decrements as they were.
    let mut l = example("example1-hysteretic.level1.json");
    let (s, rad) = common::post_json("/v1/level1", &l).await;
    assert_eq!(s, 200, "{rad}");
    l["output_unit"] = json!("rpm");
    let (s, rpm) = common::post_json("/v1/level1", &l).await;
    assert_eq!(s, 200, "{rpm}");
    assert_eq!(rpm["output_unit"], "rpm");
    assert!(
        (rpm["speed"].as_f64().unwrap() - 5729.578).abs() < 1e-3,
        "{rpm}"
    );
    for k in ["frequency_0", "rigid_critical_speed"] {
        close(&rpm[k], rad[k].as_f64().unwrap() * RPM, k);
    }
    close(
        &rpm["frequency"][2],
        rad["frequency"][2].as_f64().unwrap() * RPM,
        "frequency",
    );
    for k in ["q0", "cross_coupling", "log_decrement"] {
        assert_eq!(rpm[k], rad[k], "{k}");
    }
}

/// An unknown output unit: 422 naming the field.
#[tokio::test]
async fn a_bad_output_unit_names_its_field() {
    let mut j = example("jeffcott-nvd.campbell.json");
    j["output_unit"] = json!("rps");
    let (s, e) = common::post_json("/v1/campbell", &j).await;
    assert_eq!(s, 422, "{e}");
    assert!(e.to_string().contains("output_unit"), "{e}");
}

/// A job answers in its input's `output_unit`: the stored result in Hz (the threshold
/// 0.477465 Hz), its CSV in Hz, its plot the rad/s one (threshold Omega* = 3.00).
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_job_answers_in_its_output_unit() {
    use http_body_util::BodyExt;
    use tower::ServiceExt;
    let dir = tempfile::tempdir().unwrap();
    let config = whirl::service::Config {
        data_dir: dir.path().to_path_buf(),
        ..whirl::service::Config::default()
    };
    let app = whirl::service::app(config);
    let call = |method: &str, uri: String, body: Option<Value>, accept: &str| {
        let req = axum::http::Request::builder()
            .method(method)
            .uri(uri)
            .header("content-type", "application/json")
            .header("accept", accept)
            .body(axum::body::Body::from(
                body.map_or(String::new(), |b| b.to_string()),
            ))
            .unwrap();
        let app = app.clone();
        async move {
            let resp = app.oneshot(req).await.unwrap();
            let status = resp.status().as_u16();
            let bytes = resp
                .into_body()
                .collect()
                .await
                .unwrap()
                .to_bytes()
                .to_vec();
            (status, bytes)
        }
    };
    let mut input = example("jeffcott-equivalent.stability.json");
    input["output_unit"] = json!("Hz");
    let job = json!({"analysis": "stability", "input": input});
    let (s, b) = call("POST", "/v1/jobs".into(), Some(job), "application/json").await;
    assert_eq!(s, 202, "{}", String::from_utf8_lossy(&b));
    let id = serde_json::from_slice::<Value>(&b).unwrap()["id"]
        .as_str()
        .unwrap()
        .to_string();
    let t0 = std::time::Instant::now();
    loop {
        let (_, b) = call("GET", format!("/v1/jobs/{id}"), None, "application/json").await;
        let v: Value = serde_json::from_slice(&b).unwrap();
        if v["status"] == "succeeded" {
            break;
        }
        assert!(
            v["status"] != "failed" && t0.elapsed().as_secs() < 60,
            "{v}"
        );
        tokio::time::sleep(std::time::Duration::from_millis(20)).await;
    }
    let result = format!("/v1/jobs/{id}/result");
    let (s, b) = call("GET", result.clone(), None, "application/json").await;
    assert_eq!(s, 200);
    let a: Value = serde_json::from_slice(&b).unwrap();
    assert_eq!(a["output_unit"], "Hz");
    assert!(
        (a["threshold"].as_f64().unwrap() - 0.477465).abs() < 1e-6,
        "{a}"
    );
    let (_, csv) = call("GET", result.clone(), None, "text/csv").await;
    assert!(
        String::from_utf8(csv)
            .unwrap()
            .starts_with("speed [Hz],max_decay_rate [1/s]\n")
    );
    let (_, svg) = call("GET", result, None, "image/svg+xml").await;
    assert!(
        String::from_utf8(svg)
            .unwrap()
            .contains("threshold Ω* = 3.00")
    );
}
