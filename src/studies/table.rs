//! A study's samples as CSV: one row per sample, its parameters then its outputs (the
//! pointers as column names), the replica that computed it and its error.

use serde_json::Value;

use crate::model::api::StudyResult;

/// A CSV field, quoted when it holds a comma, a quote or a line break (RFC 4180).
fn field(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// A value as a cell: numbers and strings as they are, null empty, anything else as JSON.
fn cell(v: &Value) -> String {
    match v {
        Value::Null => String::new(),
        Value::String(s) => field(s),
        Value::Number(n) => n.to_string(),
        other => field(&other.to_string()),
    }
}

pub fn csv(r: &StudyResult) -> String {
    let mut head = vec!["sample".to_string(), "status".to_string()];
    head.extend(r.parameters.iter().map(|p| field(p)));
    head.extend(r.outputs.iter().map(|o| field(o)));
    head.extend(["server".to_string(), "error".to_string()]);
    let mut out = head.join(",") + "\n";
    for s in &r.samples {
        let status = serde_json::to_value(s.status).unwrap_or_default();
        let mut row = vec![s.sample.to_string(), cell(&status)];
        row.extend(s.parameters.iter().map(cell));
        row.extend(s.outputs.iter().map(cell));
        row.push(field(s.server.as_deref().unwrap_or("")));
        row.push(field(s.error.as_ref().map_or("", |e| e.detail.as_str())));
        out.push_str(&row.join(","));
        out.push('\n');
    }
    out
}
