//! The served OpenAPI document generates complete, typed clients (issue 13): tagged unions
//! with a discriminator and named variants, `additionalProperties: false` on every input,
//! typed jobs, a license identifier, and an example on every request that the server accepts.
//! `.ci/clients` runs the generators themselves on the committed document.

use std::collections::BTreeSet;

use axum::Router;
use axum::body::Body;
use axum::http::{Request, StatusCode, header};
use http_body_util::BodyExt;
use serde_json::{Value, json};
use tower::ServiceExt;
use whirl::service::{Config, app, openapi_document};

const REF: &str = "#/components/schemas/";

fn test_app(dir: &tempfile::TempDir) -> Router {
    app(Config {
        data_dir: dir.path().to_path_buf(),
        ..Config::default()
    })
}

async fn send(app: Router, method: &str, uri: &str, body: Option<&Value>) -> (StatusCode, Value) {
    let req = Request::builder()
        .method(method)
        .uri(uri)
        .header(header::CONTENT_TYPE, "application/json")
        .body(body.map_or_else(Body::empty, |b| Body::from(b.to_string())))
        .unwrap();
    let resp = app.oneshot(req).await.unwrap();
    let status = resp.status();
    let bytes = resp.into_body().collect().await.unwrap().to_bytes();
    (
        status,
        serde_json::from_slice(&bytes).unwrap_or(Value::Null),
    )
}

async fn served() -> Value {
    let dir = tempfile::tempdir().unwrap();
    let (status, doc) = send(test_app(&dir), "GET", "/openapi.json", None).await;
    assert_eq!(status, StatusCode::OK);
    doc
}

fn schema<'a>(doc: &'a Value, reference: &str) -> &'a Value {
    let name = reference
        .strip_prefix(REF)
        .unwrap_or_else(|| panic!("not a component reference: {reference}"));
    doc["components"]["schemas"]
        .get(name)
        .unwrap_or_else(|| panic!("dangling reference {reference}"))
}

fn visit<'a>(v: &'a Value, at: &str, f: &mut impl FnMut(&'a Value, &str)) {
    f(v, at);
    match v {
        Value::Object(m) => m
            .iter()
            .for_each(|(k, x)| visit(x, &format!("{at}/{k}"), f)),
        Value::Array(a) => a
            .iter()
            .enumerate()
            .for_each(|(i, x)| visit(x, &format!("{at}/{i}"), f)),
        _ => {}
    }
}

fn is_object(s: &Value) -> bool {
    s["type"] == "object"
        || s["type"]
            .as_array()
            .is_some_and(|t| t.contains(&json!("object")))
}

/// POST bodies of the document: (path, request schema reference, media type example).
fn requests(doc: &Value) -> Vec<(String, String, Value)> {
    let mut out = vec![];
    for (path, item) in doc["paths"].as_object().unwrap() {
        let Some(body) = item["post"].get("requestBody") else {
            continue;
        };
        // A body that is not JSON (a ROSS rotor file, `application/toml`) has no schema here.
        let Some(media) = body["content"].get("application/json") else {
            continue;
        };
        let reference = media["schema"]["$ref"]
            .as_str()
            .unwrap_or_else(|| panic!("POST {path}: the request is not a named schema"))
            .to_string();
        out.push((path.clone(), reference, media["example"].clone()));
    }
    out
}

#[tokio::test]
async fn the_served_document_is_finished_for_clients() {
    let doc = served().await;
    let again = whirl::service::openapi::for_clients(openapi_document());
    assert_eq!(again, doc);
    assert_eq!(doc["info"]["license"]["identifier"], "MIT");
    let mut refs = 0;
    visit(&doc, "", &mut |v, _| {
        if let Some(r) = v.get("$ref").and_then(Value::as_str) {
            schema(&doc, r);
            refs += 1;
        }
    });
    assert!(refs > 100);
}

#[tokio::test]
async fn every_union_of_objects_has_a_discriminator_and_named_variants() {
    let doc = served().await;
    let mut unions = BTreeSet::new();
    visit(&doc, "", &mut |v, at| {
        let Some(members) = v.get("oneOf").and_then(Value::as_array) else {
            return;
        };
        let objects = members
            .iter()
            .all(|m| match m.get("$ref").and_then(Value::as_str) {
                Some(r) => is_object(schema(&doc, r)),
                None => is_object(m) || m.get("allOf").is_some(),
            });
        if !objects {
            return;
        }
        unions.insert(at.to_string());
        let d = &v["discriminator"];
        let tag = d["propertyName"]
            .as_str()
            .unwrap_or_else(|| panic!("{at}: a oneOf of objects without a discriminator"));
        let mapping = d["mapping"].as_object().expect("a discriminator mapping");
        assert_eq!(
            mapping.len(),
            members.len(),
            "{at}: one mapping per variant"
        );
        for (value, target) in mapping {
            let target = target.as_str().unwrap();
            assert!(
                members.iter().any(|m| m["$ref"] == target),
                "{at}: {value} maps to {target}, not a variant"
            );
            let variant = schema(&doc, target);
            assert!(is_object(variant), "{target} is an object schema");
            assert_eq!(
                variant["properties"][tag]["enum"],
                json!([value]),
                "{target}"
            );
            assert!(
                variant["required"]
                    .as_array()
                    .unwrap()
                    .contains(&json!(tag)),
                "{target}: the tag is required"
            );
        }
    });
    for union in [
        "/components/schemas/RotorInput",
        "/components/schemas/DampingInput",
        "/components/schemas/JobRequest",
    ] {
        assert!(unions.contains(union), "{union} is not a union: {unions:?}");
    }
    // `viscous` and `hysteretic` share a Rust struct but not a schema.
    let mapping = &doc["components"]["schemas"]["DampingInput"]["discriminator"]["mapping"];
    assert_ne!(mapping["viscous"], mapping["hysteretic"]);
}

#[tokio::test]
async fn every_input_object_refuses_unknown_fields() {
    let doc = served().await;
    let mut todo: Vec<String> = requests(&doc).into_iter().map(|(_, r, _)| r).collect();
    let mut seen = BTreeSet::new();
    while let Some(r) = todo.pop() {
        if !seen.insert(r.clone()) {
            continue;
        }
        visit(schema(&doc, &r), &r, &mut |v, at| {
            if let Some(inner) = v.get("$ref").and_then(Value::as_str) {
                todo.push(inner.to_string());
            }
            if is_object(v) {
                let extra = &v["additionalProperties"];
                // An object without properties is any body (a study's `input`, which the
                // server checks against its analysis's request before any sample runs).
                let open_any = *extra == json!(true) && v.get("properties").is_none();
                assert!(
                    *extra == json!(false) || extra.is_object() || open_any,
                    "{at}: an input object without additionalProperties: false"
                );
            }
        });
    }
    for name in [
        "JeffcottInput",
        "ViscousInput",
        "NonviscousInput",
        "SweepRequest",
    ] {
        assert!(seen.contains(&format!("{REF}{name}")), "{name} not reached");
    }
}

#[tokio::test]
async fn jobs_are_typed_by_their_analysis() {
    let doc = served().await;
    let s = &doc["components"]["schemas"];
    let mapping = s["JobRequest"]["discriminator"]["mapping"]
        .as_object()
        .unwrap();
    assert_eq!(s["JobRequest"]["discriminator"]["propertyName"], "analysis");
    let result = &doc["paths"]["/v1/jobs/{id}/result"]["get"]["responses"]["200"]["content"]["application/json"]
        ["schema"]["$ref"];
    // A union on `analysis`, as `JobRequest` is: every generator picks the variant by it.
    let results = schema(&doc, result.as_str().unwrap());
    assert_eq!(results["discriminator"]["propertyName"], "analysis");
    let variants = &results["discriminator"]["mapping"];
    assert_eq!(
        results["oneOf"].as_array().unwrap().len(),
        mapping.len(),
        "one result variant per analysis"
    );
    for (analysis, target) in mapping {
        let op = &doc["paths"][format!("/v1/{analysis}")]["post"];
        let request = &op["requestBody"]["content"]["application/json"]["schema"]["$ref"];
        let job = schema(&doc, target.as_str().unwrap());
        assert_eq!(&job["properties"]["input"]["$ref"], request, "{analysis}");
        // The variant is the endpoint's answer with `analysis` required and naming it.
        let answer = schema(
            &doc,
            op["responses"]["200"]["content"]["application/json"]["schema"]["$ref"]
                .as_str()
                .unwrap(),
        );
        let variant = schema(&doc, variants[analysis].as_str().unwrap());
        assert_eq!(variant["properties"]["analysis"]["enum"], json!([analysis]));
        assert_eq!(variant["required"][0], "analysis", "{analysis}");
        assert_eq!(answer["properties"]["analysis"]["enum"], json!([analysis]));
        let fields = |s: &Value| {
            let mut k: Vec<String> = s["properties"]
                .as_object()
                .unwrap()
                .keys()
                .cloned()
                .collect();
            k.sort();
            k
        };
        assert_eq!(fields(variant), fields(answer), "{analysis}");
    }
    assert!(mapping.len() >= 11, "{mapping:?}");
}

/// Every request has an example in its media type and in its schema (and each job variant in
/// its schema); the server accepts each, and refuses it with an unknown field added.
#[tokio::test]
async fn every_request_example_is_accepted() {
    let doc = served().await;
    let dir = tempfile::tempdir().unwrap();
    let mut posted = 0;
    for (path, reference, example) in requests(&doc) {
        assert!(example.is_object(), "POST {path}: no example");
        let examples = schema(&doc, &reference)["examples"]
            .as_array()
            .unwrap_or_else(|| panic!("{reference}: no examples"))
            .clone();
        let mut bodies = vec![example.clone()];
        bodies.extend(examples);
        if path == "/v1/jobs" {
            for member in schema(&doc, &reference)["oneOf"].as_array().unwrap() {
                let variant = schema(&doc, member["$ref"].as_str().unwrap());
                let ex = variant["examples"].as_array();
                bodies.extend(
                    ex.unwrap_or_else(|| panic!("{member}: no examples"))
                        .clone(),
                );
            }
        }
        let expected = if path == "/v1/jobs" || path == "/v1/studies" {
            StatusCode::ACCEPTED
        } else {
            StatusCode::OK
        };
        for body in &bodies {
            let (status, answer) = send(test_app(&dir), "POST", &path, Some(body)).await;
            assert_eq!(status, expected, "POST {path} {body}: {answer}");
            posted += 1;
        }
        let mut extra = example.clone();
        extra["not_a_field"] = json!(1);
        let (status, _) = send(test_app(&dir), "POST", &path, Some(&extra)).await;
        assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "POST {path}");
    }
    assert!(posted >= 30, "{posted}");
}
