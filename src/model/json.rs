//! Request bodies read strictly, naming the path of every bad field: a syntax error makes the
//! body malformed (400); type and value errors, numbers beyond double range and duplicate keys
//! make it invalid (422, each field with its path). The HTTP extractor over this is
//! `service::json`.

use serde::Deserialize;
use serde::de::{DeserializeOwned, Error as _, MapAccess, SeqAccess, Visitor};
use serde_json::error::Category;
use serde_json::{Map, Number, Value};

use super::error::Invalid;
use super::tagged;

/// Why a body does not describe a request.
#[derive(Debug)]
pub enum JsonError {
    /// Not JSON (400).
    Malformed(String),
    /// JSON, but bad fields (422).
    Invalid(Invalid),
}

/// A JSON value read strictly: a key given twice in one object is an error, not last-wins.
struct Strict(Value);

impl<'de> Deserialize<'de> for Strict {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(StrictVisitor)
    }
}

struct StrictVisitor;

impl<'de> Visitor<'de> for StrictVisitor {
    type Value = Strict;

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("a JSON value")
    }
    fn visit_bool<E>(self, v: bool) -> Result<Strict, E> {
        Ok(Strict(Value::Bool(v)))
    }
    fn visit_i64<E>(self, v: i64) -> Result<Strict, E> {
        Ok(Strict(Value::Number(v.into())))
    }
    fn visit_u64<E>(self, v: u64) -> Result<Strict, E> {
        Ok(Strict(Value::Number(v.into())))
    }
    fn visit_f64<E: serde::de::Error>(self, v: f64) -> Result<Strict, E> {
        Number::from_f64(v)
            .map(|n| Strict(Value::Number(n)))
            .ok_or_else(|| E::custom("must be a finite number"))
    }
    fn visit_str<E>(self, v: &str) -> Result<Strict, E> {
        Ok(Strict(Value::String(v.to_string())))
    }
    fn visit_string<E>(self, v: String) -> Result<Strict, E> {
        Ok(Strict(Value::String(v)))
    }
    fn visit_unit<E>(self) -> Result<Strict, E> {
        Ok(Strict(Value::Null))
    }
    fn visit_none<E>(self) -> Result<Strict, E> {
        Ok(Strict(Value::Null))
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Strict, A::Error> {
        let mut out = Vec::with_capacity(seq.size_hint().unwrap_or(0).min(4096));
        while let Some(Strict(v)) = seq.next_element()? {
            out.push(v);
        }
        Ok(Strict(Value::Array(out)))
    }
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Strict, A::Error> {
        let mut out = Map::new();
        while let Some(key) = map.next_key::<String>()? {
            if out.contains_key(&key) {
                return Err(A::Error::custom(tagged::nested_message(
                    &key,
                    "this key appears twice in its object (the JSON would be ambiguous)",
                )));
            }
            let Strict(v) = map.next_value()?;
            out.insert(key, v);
        }
        Ok(Strict(Value::Object(out)))
    }
}

/// The fields of a data error at `outer`, whose message may carry paths inside it.
fn fields_at(outer: &str, msg: &str) -> Vec<(String, String)> {
    match tagged::split_all(msg) {
        Some(inner) => inner
            .into_iter()
            .map(|(p, m)| (tagged::join(outer, p), m.to_string()))
            .collect(),
        None => vec![(tagged::join(outer, "."), tagged::strip_position(msg))],
    }
}

/// A data error at `outer`, whose message may carry paths inside it.
fn at_path(outer: &str, msg: &str) -> JsonError {
    let mut bad = Invalid::default();
    for (path, message) in fields_at(outer, msg) {
        bad.push(path, message);
    }
    JsonError::Invalid(bad)
}

/// Unknown fields reported (and taken out to look further) before the answer stops there.
pub const MAX_UNKNOWN_FIELDS: usize = 32;

/// Removes the object key that `path` (as serde_path_to_error prints it) ends with. A key may
/// itself hold `.` or `[`: every key of an object that begins the path is tried.
fn remove_at(value: &mut Value, path: &str) -> bool {
    match value {
        Value::Object(map) => {
            if map.remove(path).is_some() {
                return true;
            }
            let mut keys: Vec<String> = map
                .keys()
                .filter(|k| {
                    path.len() > k.len()
                        && path.starts_with(k.as_str())
                        && matches!(path.as_bytes()[k.len()], b'.' | b'[')
                })
                .cloned()
                .collect();
            keys.sort_by_key(|k| std::cmp::Reverse(k.len()));
            keys.into_iter().any(|k| {
                let rest = &path[k.len()..];
                let rest = rest.strip_prefix('.').unwrap_or(rest);
                map.get_mut(&k).is_some_and(|v| remove_at(v, rest))
            })
        }
        Value::Array(items) => {
            let Some((index, rest)) = path
                .strip_prefix('[')
                .and_then(|p| p.split_once(']'))
                .and_then(|(i, rest)| Some((i.parse::<usize>().ok()?, rest)))
            else {
                return false;
            };
            let rest = rest.strip_prefix('.').unwrap_or(rest);
            !rest.is_empty() && items.get_mut(index).is_some_and(|v| remove_at(v, rest))
        }
        _ => false,
    }
}

/// Parses a body, naming the path of the first bad field. Two passes: the JSON itself (400 for
/// syntax; 422 with the path for a number beyond double range or a duplicate key), then the
/// typed content (422 with the path).
pub fn parse<T: DeserializeOwned>(bytes: &[u8]) -> Result<T, JsonError> {
    let mut de = serde_json::Deserializer::from_slice(bytes);
    let value = match serde_path_to_error::deserialize::<_, Strict>(&mut de) {
        Ok(Strict(v)) => {
            de.end()
                .map_err(|e| JsonError::Malformed(format!("the body is not valid JSON: {e}")))?;
            v
        }
        Err(e) => {
            let outer = e.path().to_string();
            let inner = e.into_inner();
            let msg = inner.to_string();
            return Err(if msg.starts_with("number out of range") {
                at_path(
                    &outer,
                    "must be a finite number (this one is beyond double range)",
                )
            } else if inner.classify() == Category::Data {
                at_path(&outer, &msg)
            } else {
                JsonError::Malformed(format!("the body is not valid JSON: {msg}"))
            });
        }
    };
    if !value.is_object() {
        return Err(JsonError::Invalid(Invalid::one(
            "(body)",
            "the body must be a JSON object",
        )));
    }
    from_value(value)
}

/// The typed content of a JSON value, naming the path of the bad fields (an array where an
/// object is read is one, see [`super::objects`]): every unknown field
/// (up to [`MAX_UNKNOWN_FIELDS`]: each is taken out and the content read again), then the
/// first other error.
pub fn from_value<T: DeserializeOwned>(mut value: Value) -> Result<T, JsonError> {
    let mut bad = Invalid::default();
    let mut removed = 0;
    loop {
        let e = match serde_path_to_error::deserialize::<_, T>(super::objects::Objects(&value)) {
            Ok(v) if bad.is_empty() => return Ok(v),
            Ok(_) => return Err(JsonError::Invalid(bad)),
            Err(e) => e,
        };
        let outer = e.path().to_string();
        let inner = e.into_inner();
        if inner.classify() != Category::Data {
            return Err(JsonError::Malformed(format!(
                "the body is not valid JSON: {inner}"
            )));
        }
        let mut again = true;
        for (path, message) in fields_at(&outer, &inner.to_string()) {
            let unknown = message.starts_with("unknown field `");
            if unknown && removed < MAX_UNKNOWN_FIELDS && remove_at(&mut value, &path) {
                removed += 1;
            } else {
                again = false;
            }
            bad.push(path, message);
        }
        if !again {
            return Err(JsonError::Invalid(bad));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn path_of(body: &str) -> (String, String) {
        match parse::<Value>(body.as_bytes()) {
            Err(JsonError::Invalid(inv)) => {
                let e = &inv.errors()[0];
                (e.path.clone(), e.message.clone())
            }
            other => panic!("{:?}", other.map(|_| ())),
        }
    }

    #[test]
    fn duplicate_keys_and_huge_numbers_are_named() {
        let (p, m) = path_of(r#"{"rotor": {"mass": 1, "mass": 2}}"#);
        assert_eq!(p, "rotor.mass");
        assert!(m.contains("twice"), "{m}");
        let (p, m) = path_of(r#"{"speeds": [1, 2, 1e999]}"#);
        assert_eq!(p, "speeds[2]");
        assert!(m.contains("finite"), "{m}");
    }
}
