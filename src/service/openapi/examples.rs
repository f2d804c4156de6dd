//! Request examples in the document, taken from `examples/` at build time: Swagger UI's
//! "Try it out" fills in a body the server accepts, and generators and fuzzers get a valid
//! one (`tests/it/openapi.rs` posts every one of them). For each endpoint the quickest of its
//! bundled examples (`examples/<name>.<endpoint>.json`, the body of `POST /v1/<endpoint>`).
//!
//! The Docker build compiles these in: `.dockerignore` lets `examples/` into the context.

use serde_json::{Value, json};

/// `(endpoint, body)`: the example of `POST /v1/<endpoint>`.
const EXAMPLES: &[(&str, &str)] = &[
    (
        "modal",
        include_str!("../../../examples/jeffcott-nvd.modal.json"),
    ),
    (
        "campbell",
        include_str!("../../../examples/jeffcott-hysteretic.campbell.json"),
    ),
    (
        "stability",
        include_str!("../../../examples/jeffcott-hysteretic.stability.json"),
    ),
    (
        "damping",
        include_str!("../../../examples/example1-nvd-fit.damping.json"),
    ),
    (
        "time-response",
        include_str!("../../../examples/example1-shock-equivalent.time-response.json"),
    ),
    (
        "unbalance-response",
        include_str!("../../../examples/example1-nvd.unbalance-response.json"),
    ),
    (
        "critical-speed-map",
        include_str!("../../../examples/rotor-a.critical-speed-map.json"),
    ),
    (
        "static",
        include_str!("../../../examples/ross-rotor-example.static.json"),
    ),
    (
        "level1",
        include_str!("../../../examples/example1-hysteretic.level1.json"),
    ),
    (
        "frequency-response",
        include_str!("../../../examples/example1-hysteretic.frequency-response.json"),
    ),
    (
        "report",
        include_str!("../../../examples/rotor-a-nvd.report.json"),
    ),
];

/// The analysis whose example a job submission shows.
const JOB_EXAMPLE: &str = "campbell";

fn example(endpoint: &str) -> Option<Value> {
    EXAMPLES
        .iter()
        .find(|(e, _)| *e == endpoint)
        .map(|(_, text)| serde_json::from_str(text).expect("a bundled example is JSON"))
}

/// Sets the media type's `example` of each request body, and `examples` of its schema (the
/// first endpoint's, where endpoints share a schema), and of each job's schema (`jobs`:
/// `(analysis, schema name)`).
pub(super) fn add(doc: &mut Value, jobs: &[(String, String)]) {
    for (endpoint, _) in EXAMPLES {
        let body = example(endpoint).expect("listed");
        set(doc, &format!("/v1/{endpoint}"), body);
    }
    for (a, name) in jobs {
        let input = example(a).unwrap_or_else(|| panic!("no example for analysis {a}"));
        if let Some(s) = doc["components"]["schemas"].get_mut(name) {
            s["examples"] = json!([{ "analysis": a, "input": input }]);
        }
    }
    let input = example(JOB_EXAMPLE).expect("listed");
    set(
        doc,
        "/v1/jobs",
        json!({ "analysis": JOB_EXAMPLE, "input": input }),
    );
    set(doc, "/v1/studies", study());
}

/// A study's example: the equivalent Jeffcott threshold over eta_n (eq. 10: 1 + eta_n/eta_r).
fn study() -> Value {
    let input: Value = serde_json::from_str(include_str!(
        "../../../examples/jeffcott-equivalent.stability.json"
    ))
    .expect("a bundled example is JSON");
    json!({
        "analysis": "stability",
        "input": input,
        "parameters": [{"pointer": "/rotor/loss_factor_nonrotating", "values": [0.0, 0.01, 0.02, 0.03]}],
        "design": "grid",
        "outputs": ["/threshold"]
    })
}

fn set(doc: &mut Value, path: &str, body: Value) {
    let media = &mut doc["paths"][path]["post"]["requestBody"]["content"]["application/json"];
    assert!(media.is_object(), "POST {path} takes no JSON body");
    media["example"] = body.clone();
    let name = media["schema"]["$ref"]
        .as_str()
        .and_then(|r| r.strip_prefix("#/components/schemas/"))
        .map(str::to_string);
    if let Some(name) = name {
        let schema = &mut doc["components"]["schemas"][&name];
        if schema.get("examples").is_none() {
            schema["examples"] = json!([body]);
        }
    }
}
