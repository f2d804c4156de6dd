//! The pass that makes the assembled document generate complete, typed clients.
//!
//! It works on the document as JSON and changes what generators cannot read, never the wire
//! format:
//! - Tagged unions (`RotorInput` on `type`, `DampingInput` on `model`): utoipa writes each
//!   variant as an inline `allOf` of the variant's struct and an object holding the tag, which
//!   openapi-python-client refuses ("Invalid property in union") and openapi-typescript types
//!   as an empty record when the struct has no fields. Each variant becomes a named object
//!   schema, `<Tag>Input` (its tag a required one-value enum, then its fields), and the union a
//!   `oneOf` of references with a `discriminator`. `viscous` and `hysteretic`, which share
//!   the Rust struct `NoOptions`, get a schema each.
//! - Jobs: `POST /v1/jobs` is a union on `analysis` of `<Analysis>Job` objects pairing each
//!   analysis with the request schema of its endpoint, and a job's result (`JobResult`) is a
//!   union on `analysis` of `<Analysis>Result` objects: each endpoint's answer, which names
//!   its analysis in `analysis` (required there, optional in the answer's own schema because
//!   a report's parts are answers without it).
//! - Inputs: every object schema a request reaches gets `additionalProperties: false`, as the
//!   server refuses unknown fields everywhere (variant structs cannot say so to serde, because
//!   of the tag beside their fields).
//! - Request examples from `examples/` (see [`super::examples`]).
//! - Schemas no longer referenced (`NoOptions`, `AnalysisName`) are dropped.
//!
//! The pass is idempotent, and a failure here is a bug in it (caught by `tests/it/openapi.rs`).

use std::collections::BTreeSet;

use serde_json::{Map, Value, json};

const REF: &str = "#/components/schemas/";

/// The document, finished for client generators.
pub fn for_clients(mut doc: Value) -> Value {
    tagged_unions(&mut doc);
    jobs(&mut doc);
    let job_schemas: Vec<(String, String)> = analyses(&doc)
        .into_iter()
        .map(|(a, _, _)| {
            let name = format!("{}Job", camel(&a));
            (a, name)
        })
        .collect();
    super::examples::add(&mut doc, &job_schemas);
    strict_inputs(&mut doc);
    prune(&mut doc);
    doc
}

fn schemas(doc: &mut Value) -> &mut Map<String, Value> {
    doc["components"]["schemas"]
        .as_object_mut()
        .expect("the document has component schemas")
}

/// `time-response` -> `TimeResponse`.
fn camel(name: &str) -> String {
    name.split(['-', '_'])
        .map(|w| {
            let mut c = w.chars();
            c.next()
                .map(|f| f.to_uppercase().chain(c).collect::<String>())
                .unwrap_or_default()
        })
        .collect()
}

fn reference(name: &str) -> Value {
    json!({ "$ref": format!("{REF}{name}") })
}

/// A union variant as utoipa writes a serde-tagged one:
/// `{"allOf": [{"$ref": X}, {"type": "object", "required": [tag], "properties": {tag: {"enum": [value]}}}]}`.
struct Variant {
    schema: String,
    tag: String,
    value: String,
    description: Option<Value>,
}

fn tagged_variant(member: &Value) -> Option<Variant> {
    let [target, tag_object] = member.get("allOf")?.as_array()?.as_slice() else {
        return None;
    };
    let schema = target.get("$ref")?.as_str()?.strip_prefix(REF)?.to_string();
    let props = tag_object.get("properties")?.as_object()?;
    if props.len() != 1 {
        return None;
    }
    let (tag, spec) = props.iter().next()?;
    let [value] = spec.get("enum")?.as_array()?.as_slice() else {
        return None;
    };
    let description = member
        .get("description")
        .or_else(|| target.get("description"))
        .cloned();
    Some(Variant {
        schema,
        tag: tag.clone(),
        value: value.as_str()?.to_string(),
        description,
    })
}

/// Named variant schemas and a discriminator for every union of tagged `allOf`s.
fn tagged_unions(doc: &mut Value) {
    let unions: Vec<(String, Vec<Variant>)> = schemas(doc)
        .iter()
        .filter_map(|(name, s)| {
            let members = s.get("oneOf")?.as_array()?;
            let variants: Option<Vec<Variant>> = members.iter().map(tagged_variant).collect();
            variants
                .filter(|v| !v.is_empty())
                .map(|v| (name.clone(), v))
        })
        .collect();
    let mut replaced = BTreeSet::new();
    for (union, variants) in unions {
        let tag = variants[0].tag.clone();
        assert!(
            variants.iter().all(|v| v.tag == tag),
            "{union}: variants tagged by different fields"
        );
        let mut refs = vec![];
        let mut mapping = Map::new();
        for v in &variants {
            let name = format!("{}Input", camel(&v.value));
            let body = schemas(doc)
                .get(&v.schema)
                .unwrap_or_else(|| panic!("{union}: no schema {}", v.schema))
                .clone();
            let variant = with_tag(body, &v.tag, &v.value, v.description.clone());
            let all = schemas(doc);
            if name != v.schema {
                assert!(
                    !all.contains_key(&name),
                    "{union}: the variant schema {name} would replace another schema"
                );
            } else {
                replaced.insert(name.clone());
            }
            all.insert(name.clone(), variant);
            mapping.insert(v.value.clone(), json!(format!("{REF}{name}")));
            refs.push(reference(&name));
        }
        let all = schemas(doc);
        let old = all.get(&union).cloned().unwrap_or_default();
        let mut new = json!({
            "oneOf": refs,
            "discriminator": { "propertyName": tag, "mapping": mapping },
        });
        if let Some(d) = old.get("description") {
            new["description"] = d.clone();
        }
        all.insert(union, new);
    }
    // A struct schema that became a variant in place must be referenced by its union only:
    // elsewhere it would now require the tag.
    for name in replaced {
        let uses = count_refs(doc, &name);
        assert_eq!(
            uses, 1,
            "{name} is used outside its union ({uses} references)"
        );
    }
}

/// A variant's struct schema with its tag in front: a required one-value enum.
fn with_tag(mut body: Value, tag: &str, value: &str, description: Option<Value>) -> Value {
    let obj = body.as_object_mut().expect("a variant is an object schema");
    obj.insert("type".into(), json!("object"));
    let mut props = Map::new();
    props.insert(tag.into(), json!({ "type": "string", "enum": [value] }));
    if let Some(Value::Object(old)) = obj.remove("properties") {
        props.extend(old.into_iter().filter(|(k, _)| k != tag));
    }
    obj.insert("properties".into(), Value::Object(props));
    let mut required = vec![json!(tag)];
    if let Some(Value::Array(old)) = obj.remove("required") {
        required.extend(old.into_iter().filter(|r| r != tag));
    }
    obj.insert("required".into(), Value::Array(required));
    if let Some(d) = description {
        obj.insert("description".into(), d);
    }
    body
}

fn count_refs(doc: &Value, name: &str) -> usize {
    let target = format!("{REF}{name}");
    let mut n = 0;
    visit(doc, &mut |v| {
        if v.get("$ref").and_then(Value::as_str) == Some(target.as_str()) {
            n += 1;
        }
    });
    n
}

fn visit(v: &Value, f: &mut impl FnMut(&Value)) {
    f(v);
    match v {
        Value::Object(m) => m.values().for_each(|x| visit(x, f)),
        Value::Array(a) => a.iter().for_each(|x| visit(x, f)),
        _ => {}
    }
}

/// The schema name a media type's schema refers to.
fn body_schema(doc: &Value, path: &str, method: &str, status: Option<&str>) -> Option<String> {
    let op = &doc["paths"][path][method];
    let content = match status {
        None => &op["requestBody"]["content"],
        Some(s) => &op["responses"][s]["content"],
    };
    content["application/json"]["schema"]["$ref"]
        .as_str()?
        .strip_prefix(REF)
        .map(str::to_string)
}

/// The analyses a job can run (the `AnalysisName` enum), with their request and answer schemas.
fn analyses(doc: &Value) -> Vec<(String, String, String)> {
    let names: Vec<String> = match doc["components"]["schemas"].get("AnalysisName") {
        Some(s) => s["enum"]
            .as_array()
            .expect("AnalysisName is an enum")
            .iter()
            .filter_map(|v| v.as_str().map(str::to_string))
            .collect(),
        // Already finished: read the job variants back.
        None => doc["components"]["schemas"]["JobRequest"]["discriminator"]["mapping"]
            .as_object()
            .map(|m| m.keys().cloned().collect())
            .unwrap_or_default(),
    };
    names
        .into_iter()
        .map(|a| {
            let path = format!("/v1/{a}");
            let request = body_schema(doc, &path, "post", None)
                .unwrap_or_else(|| panic!("job analysis {a}: no JSON request body at {path}"));
            let answer = body_schema(doc, &path, "post", Some("200"))
                .unwrap_or_else(|| panic!("job analysis {a}: no JSON answer at {path}"));
            (a, request, answer)
        })
        .collect()
}

const JOB_RESULT: &str = "/v1/jobs/{id}/result";

/// `JobRequest` as a union on `analysis`, and the job result typed by the endpoints' answers.
fn jobs(doc: &mut Value) {
    let analyses = analyses(doc);
    let all = schemas(doc);
    let old = all.get("JobRequest").cloned().unwrap_or_default();
    if old.get("oneOf").is_none() {
        let input_doc = old["properties"]["input"]["description"].clone();
        let mut refs = vec![];
        let mut mapping = Map::new();
        for (a, request, _) in &analyses {
            let name = format!("{}Job", camel(a));
            let mut input = reference(request);
            if input_doc.is_string() {
                input["description"] = input_doc.clone();
            }
            let variant = json!({
                "type": "object",
                "description": format!("A `{a}` job: `input` is the body of `POST /v1/{a}`."),
                "required": ["analysis", "input"],
                "properties": {
                    "analysis": { "type": "string", "enum": [a] },
                    "input": input,
                },
                "additionalProperties": false,
            });
            assert!(!all.contains_key(&name), "the job schema {name} exists");
            all.insert(name.clone(), variant);
            mapping.insert(a.clone(), json!(format!("{REF}{name}")));
            refs.push(reference(&name));
        }
        let mut new = json!({
            "oneOf": refs,
            "discriminator": { "propertyName": "analysis", "mapping": mapping },
        });
        if let Some(d) = old.get("description") {
            new["description"] = d.clone();
        }
        all.insert("JobRequest".into(), new);
    }
    // Every answer names its analysis in `analysis` (the report's parts, which are answers
    // too, do not): optional in the answer's schema, and the discriminator of `JobResult`,
    // whose variants `<Analysis>Result` are the answers with `analysis` required.
    let mut refs = vec![];
    let mut mapping = Map::new();
    for (a, _, answer) in &analyses {
        let tag = json!({
            "type": "string",
            "enum": [a],
            "description": "The analysis that answered (absent in a report's parts).",
        });
        let schema = all
            .get_mut(answer)
            .unwrap_or_else(|| panic!("no answer schema {answer}"));
        let mut props = Map::new();
        props.insert("analysis".into(), tag);
        if let Some(Value::Object(old)) = schema.get_mut("properties").map(Value::take) {
            props.extend(old.into_iter().filter(|(k, _)| k != "analysis"));
        }
        schema["properties"] = Value::Object(props);
        let description = format!("A succeeded `{a}` job's result: the answer of `POST /v1/{a}`.");
        let variant = with_tag(schema.clone(), "analysis", a, Some(json!(description)));
        let name = format!("{}Result", camel(a));
        assert!(
            all.get(&name)
                .is_none_or(|s| s["properties"]["analysis"]["enum"] == json!([a])),
            "the result schema {name} would replace another schema"
        );
        all.insert(name.clone(), variant);
        mapping.insert(a.clone(), json!(format!("{REF}{name}")));
        refs.push(reference(&name));
    }
    all.insert(
        "JobResult".into(),
        json!({
            "oneOf": refs,
            "discriminator": { "propertyName": "analysis", "mapping": mapping },
            "description": "A succeeded job's result: the answer of `POST /v1/<analysis>` for the \
                job's `analysis`, which it names.",
        }),
    );
    let media =
        &mut doc["paths"][JOB_RESULT]["get"]["responses"]["200"]["content"]["application/json"];
    assert!(media.is_object(), "{JOB_RESULT} answers JSON");
    media["schema"] = reference("JobResult");
}

/// The component schemas that request bodies reach, following references.
fn request_schemas(doc: &Value) -> BTreeSet<String> {
    let mut todo: Vec<String> = vec![];
    if let Some(paths) = doc["paths"].as_object() {
        for item in paths.values() {
            for op in item.as_object().into_iter().flat_map(|m| m.values()) {
                visit(&op["requestBody"], &mut |v| collect_ref(v, &mut todo));
            }
        }
    }
    reach(doc, todo)
}

fn collect_ref(v: &Value, into: &mut Vec<String>) {
    if let Some(name) = v
        .get("$ref")
        .and_then(Value::as_str)
        .and_then(|r| r.strip_prefix(REF))
    {
        into.push(name.to_string());
    }
}

fn reach(doc: &Value, mut todo: Vec<String>) -> BTreeSet<String> {
    let mut seen = BTreeSet::new();
    while let Some(name) = todo.pop() {
        if seen.insert(name.clone())
            && let Some(s) = doc["components"]["schemas"].get(&name)
        {
            visit(s, &mut |v| collect_ref(v, &mut todo));
        }
    }
    seen
}

/// `additionalProperties: false` on every object schema a request reaches (maps keep theirs).
fn strict_inputs(doc: &mut Value) {
    let inputs = request_schemas(doc);
    let all = schemas(doc);
    for name in inputs {
        if let Some(s) = all.get_mut(&name) {
            close_objects(s);
        }
    }
}

fn is_object(v: &Value) -> bool {
    match v.get("type") {
        Some(Value::String(t)) => t == "object",
        Some(Value::Array(ts)) => ts.iter().any(|t| t == "object"),
        _ => false,
    }
}

fn close_objects(v: &mut Value) {
    if is_object(v) && v.get("additionalProperties").is_none() {
        // An object without properties is any object (a study's `input`): closing it would
        // leave nothing a client could send.
        v["additionalProperties"] = json!(v.get("properties").is_none());
    }
    let Some(m) = v.as_object_mut() else { return };
    for (key, sub) in m.iter_mut() {
        match key.as_str() {
            // Values are schemas here, or maps / lists of schemas.
            "properties" | "patternProperties" | "$defs" => {
                if let Some(props) = sub.as_object_mut() {
                    props.values_mut().for_each(close_objects);
                }
            }
            "items" | "additionalProperties" | "not" | "contains" => close_objects(sub),
            "oneOf" | "anyOf" | "allOf" | "prefixItems" => {
                if let Some(list) = sub.as_array_mut() {
                    list.iter_mut().for_each(close_objects);
                }
            }
            _ => {}
        }
    }
}

/// Drops the component schemas that nothing outside the components refers to.
fn prune(doc: &mut Value) {
    let mut roots = vec![];
    for (key, part) in doc.as_object().into_iter().flatten() {
        if key != "components" {
            visit(part, &mut |v| collect_ref(v, &mut roots));
        }
    }
    if let Some(comps) = doc["components"].as_object() {
        for (key, part) in comps {
            if key != "schemas" {
                visit(part, &mut |v| collect_ref(v, &mut roots));
            }
        }
    }
    let keep = reach(doc, roots);
    schemas(doc).retain(|name, _| keep.contains(name));
}
