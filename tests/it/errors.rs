//! Error answers: every unknown field with its path, no cascades from one bad field into
//! false ones, and grids whose points print as the decimals they are.

use crate::common;

use common::post_json;
use serde_json::{Value, json};

fn example(name: &str) -> Value {
    let text = std::fs::read_to_string(format!("examples/{name}")).unwrap();
    serde_json::from_str(&text).unwrap()
}

/// Status and `(path, message)` of every error.
async fn errors(uri: &str, body: &Value) -> (u16, Vec<(String, String)>) {
    let (status, v) = post_json(uri, body).await;
    let list = v["errors"]
        .as_array()
        .unwrap_or_else(|| panic!("no errors in {v}"))
        .iter()
        .map(|e| {
            let s = |k: &str| e[k].as_str().unwrap().to_string();
            (s("path"), s("message"))
        })
        .collect();
    (status, list)
}

fn paths(list: &[(String, String)]) -> Vec<&str> {
    list.iter().map(|(p, _)| p.as_str()).collect()
}

#[tokio::test]
async fn every_unknown_field_is_reported_with_its_path() {
    let mut body = example("example1-nvd.campbell.json");
    body["rotor"]["colour"] = json!("red");
    body["rotor"]["shape"] = json!(1);
    body["rotor"]["shaft"][0]["lenght"] = json!(1.5);
    body["rotor"]["supports"][1]["stifness"] = json!(1e6);
    body["damping"]["rotating"]["brnaches"] = json!(3);
    body["damping"]["mode"] = json!(3);
    body["speeds"]["step"] = json!(10);
    body["spead"] = json!(1);
    body["extra"] = json!({"a": 1});
    let (status, list) = errors("/v1/campbell", &body).await;
    assert_eq!(status, 422, "{list:?}");
    let p = paths(&list);
    for expected in [
        "rotor.colour",
        "rotor.shape",
        "rotor.shaft[0].lenght",
        "rotor.supports[1].stifness",
        "damping.rotating.brnaches",
        "damping.mode",
        "speeds.step",
        "spead",
        "extra",
    ] {
        assert!(p.contains(&expected), "{expected} missing from {list:?}");
    }
    assert_eq!(list.len(), 9, "{list:?}");
    for (path, message) in &list {
        let key = path.rsplit(['.', ']']).next().unwrap();
        assert!(
            message.starts_with(&format!("unknown field `{key}`")),
            "{path}: {message}"
        );
    }
}

#[tokio::test]
async fn unknown_fields_then_the_first_other_error() {
    let body = json!({"rotor": {"type": "jeffcott", "mass": 1, "stiffness": 1, "mas": 2},
                      "damping": {"model": "viscous"}, "speed": "fast", "sped": 1});
    let (status, list) = errors("/v1/modal", &body).await;
    assert_eq!(status, 422);
    assert_eq!(paths(&list), ["rotor.mas", "sped", "speed"], "{list:?}");
    assert!(
        list[2]
            .1
            .contains("must be a number in rad/s or {\"value\", \"unit\"}"),
        "{list:?}"
    );
    // A typo of a required field: named as unknown, and the field as missing.
    let body = json!({"rotor": {"type": "jeffcott", "mass": 1, "stiffnes": 1},
                      "damping": {"model": "viscous"}});
    let (_, list) = errors("/v1/modal", &body).await;
    assert_eq!(list[0].0, "rotor.stiffnes", "{list:?}");
    assert!(
        list[0].1.contains("expected one of: mass, stiffness"),
        "{list:?}"
    );
    assert!(
        list.iter()
            .skip(1)
            .all(|(_, m)| m.contains("missing field `stiffness`")),
        "{list:?}"
    );
}

#[tokio::test]
async fn unknown_fields_are_bounded() {
    let mut body = json!({"rotor": {"type": "jeffcott", "mass": 1, "stiffness": 1},
                          "damping": {"model": "viscous"}});
    for i in 0..50 {
        body[format!("x{i:02}")] = json!(i);
    }
    let (status, list) = errors("/v1/modal", &body).await;
    assert_eq!(status, 422);
    // 32 taken out and looked past, and the 33rd reported where the search stopped.
    assert_eq!(list.len(), 33, "{list:?}");
    assert!(
        list.iter()
            .all(|(p, m)| p.starts_with('x') && m.starts_with("unknown field"))
    );
}

#[tokio::test]
async fn a_key_holding_dots_or_brackets_is_found() {
    let mut body = example("example1-nvd.modal.json");
    let steel = body["rotor"]["materials"]["steel"].clone();
    body["rotor"]["materials"] = json!({"st.eel[0]": steel});
    body["rotor"]["materials"]["st.eel[0]"]["colour"] = json!(1);
    body["rotor"]["materials"]["st.eel[0]"]["hue"] = json!(1);
    body["rotor"]["shaft"][0]["material"] = json!("st.eel[0]");
    let (status, list) = errors("/v1/modal", &body).await;
    assert_eq!(status, 422);
    assert_eq!(
        paths(&list),
        [
            "rotor.materials.st.eel[0].colour",
            "rotor.materials.st.eel[0].hue"
        ],
        "{list:?}"
    );
}

#[tokio::test]
async fn a_bad_material_name_is_named_and_nothing_else() {
    let mut body = example("example1-nvd.modal.json");
    body["rotor"]["shaft"][0]["material"] = json!("stell");
    let (status, list) = errors("/v1/modal", &body).await;
    assert_eq!(status, 422);
    assert_eq!(paths(&list), ["rotor.shaft[0].material"], "{list:?}");
    assert_eq!(list[0].1, "unknown material `stell` (defined: steel)");
    // On every endpoint, through every bundled beam rotor.
    let mut names: Vec<String> = std::fs::read_dir("examples")
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    for name in names {
        let mut body = example(&name);
        let Some(shaft) = body["rotor"]["shaft"].as_array_mut() else {
            continue;
        };
        let last = shaft.len() - 1;
        shaft[last]["material"] = json!("unobtainium");
        let endpoint = name.split('.').nth(1).unwrap();
        let (status, list) = errors(&format!("/v1/{endpoint}"), &body).await;
        assert_eq!(status, 422, "{name}");
        let at = format!("rotor.shaft[{last}].material");
        assert_eq!(paths(&list), [at.as_str()], "{name}: {list:?}");
    }
    // A material that is itself invalid: its field, and no false unknown-material error.
    let mut body = example("example1-nvd.modal.json");
    body["rotor"]["materials"]["steel"]["density"] = json!(-1);
    let (_, list) = errors("/v1/modal", &body).await;
    assert_eq!(paths(&list), ["rotor.materials.steel.density"], "{list:?}");
}

#[tokio::test]
async fn no_shaft_does_not_make_every_node_false() {
    let mut body = example("example1-nvd.modal.json");
    body["rotor"]["shaft"] = json!([]);
    let (status, list) = errors("/v1/modal", &body).await;
    assert_eq!(status, 422);
    assert_eq!(paths(&list), ["rotor.shaft"], "{list:?}");
    let mut body = example("example1-nvd.modal.json");
    body["rotor"]["supports"][0]["node"] = json!(-1);
    let (_, list) = errors("/v1/modal", &body).await;
    assert_eq!(
        list,
        [(
            "rotor.supports[0].node".into(),
            "must be >= 0 (got -1)".into()
        )]
    );
}

#[tokio::test]
async fn a_segment_past_the_limit_is_named_alone_not_miscounted_in_a_total() {
    // 640 + 960 elements: the second segment alone is past the default 1000 dof (499
    // elements); a total of the first alone ("640 elements give 1282 degrees of freedom") once
    // followed, which misstated the rotor's 1600.
    let mut b = example("example1-nvd.modal.json");
    let seg = b["rotor"]["shaft"][0].clone();
    let mut first = seg.clone();
    first["elements"] = json!(640);
    let mut second = seg;
    second["elements"] = json!(960);
    b["rotor"]["shaft"] = json!([first, second]);
    let (status, list) = errors("/v1/modal", &b).await;
    assert_eq!(status, 422);
    assert_eq!(
        paths(&list),
        ["rotor.shaft[0].elements", "rotor.shaft[1].elements"],
        "{list:?}"
    );
    assert!(
        list[1].1.contains("must be between 1 and 499 (got 960)"),
        "{list:?}"
    );
}

#[tokio::test]
async fn no_count_in_a_message_underflows() {
    let mut bodies = vec![];
    let mut b = example("example1-nvd.modal.json");
    b["rotor"]["shaft"] = json!([]);
    b["damping"]["modes"] = json!(3);
    bodies.push(("/v1/modal", b));
    let mut b = example("example1-nvd.modal.json");
    b["rotor"]["shaft"][0]["elements"] = json!(0);
    bodies.push(("/v1/modal", b));
    let mut b = example("example1-nvd.modal.json");
    b["rotor"] = json!({"type": "matrices", "mass": [], "stiffness": []});
    bodies.push(("/v1/modal", b));
    let mut b = example("example1-nvd.modal.json");
    b["rotor"]["supports"][1] = json!({"node": 3, "kxx": 1e6, "speeds": []});
    bodies.push(("/v1/modal", b));
    // A sample count beyond any integer (it saturates inside).
    let mut b = example("example1-shock-nvd.time-response.json");
    b["duration"] = json!(1e300);
    bodies.push(("/v1/time-response", b));
    let mut b = example("example1-shock-nvd.time-response.json");
    b["output_interval"] = json!(1e-300);
    bodies.push(("/v1/time-response", b));
    for (uri, body) in bodies {
        let (status, v) = post_json(uri, &body).await;
        assert_eq!(status, 422, "{v}");
        let text = v.to_string();
        assert!(!text.contains("18446744073709551615"), "{text}");
    }
    let mut b = example("example1-shock-nvd.time-response.json");
    b["duration"] = json!(1e300);
    let (_, list) = errors("/v1/time-response", &b).await;
    assert_eq!(list[0].0, "output_interval");
    assert!(
        list[0]
            .1
            .starts_with("duration / output_interval gives 2.000e303 samples"),
        "{list:?}"
    );
}

fn numbers(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

#[tokio::test]
async fn grids_are_decimals_and_end_at_stop() {
    let jeffcott =
        json!({"type": "jeffcott", "mass": 1, "stiffness": 1, "loss_factor_rotating": 0.01});
    let body = json!({"rotor": jeffcott, "damping": {"model": "viscous"},
                      "speeds": {"start": 0, "stop": 1, "count": 21}});
    let (status, v) = post_json("/v1/campbell", &body).await;
    assert_eq!(status, 200, "{v}");
    let speeds = numbers(&v["speeds"]);
    let expected: Vec<f64> = (0..21).map(|i| i as f64 / 20.0).collect();
    assert_eq!(speeds, expected);
    assert_eq!(speeds[3].to_string(), "0.15");
    assert!(
        !v["speeds"].to_string().contains("0000000"),
        "{}",
        v["speeds"]
    );
    let body = json!({"rotor": jeffcott, "damping": {"model": "viscous"},
                      "speeds": {"start": 0.1, "stop": 0.3, "count": 5}});
    let (_, v) = post_json("/v1/stability", &body).await;
    assert_eq!(v["speeds"].to_string(), "[0.1,0.15,0.2,0.25,0.3]");
    // Time samples.
    let body = json!({"rotor": jeffcott, "damping": {"model": "viscous"}, "speed": 0.5,
                      "forces": [{"node": 0, "direction": 0, "history": [[0, 1]]}],
                      "duration": 0.003, "output_interval": 0.0001});
    let (status, v) = post_json("/v1/time-response", &body).await;
    assert_eq!(status, 200, "{v}");
    let t = numbers(&v["time"]);
    assert_eq!(t.len(), 31);
    assert_eq!(t[3].to_string(), "0.0003");
    assert_eq!(t[30], 0.003);
    assert!(!v["time"].to_string().contains("0000000"), "{}", v["time"]);
    // A log grid of support stiffness: decades.
    let mut body = example("rotor-a.critical-speed-map.json");
    body["stiffness"] = json!({"start": 1e6, "stop": 1e11, "count": 11});
    let (status, v) = post_json("/v1/critical-speed-map", &body).await;
    assert_eq!(status, 200, "{v}");
    let k = numbers(&v["stiffness"]);
    assert_eq!(k[2], 1e7, "{k:?}");
    assert_eq!(k[10], 1e11);
    assert!(
        k.iter().step_by(2).all(|x| x.log10().fract() == 0.0),
        "{k:?}"
    );
}
