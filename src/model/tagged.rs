//! Deserialising tagged enums without losing the path of a bad field.
//!
//! serde buffers the content of an internally tagged enum, so an error inside a variant is
//! reported at the enum (`rotor`), not at the field (`rotor.mass`). Here the tag is split off
//! by hand and the variant deserialised with path tracking; the inner path travels inside the
//! error message behind a marker, and [`split_nested`] puts it back together at the top.

use serde::de::{DeserializeOwned, Error};
use serde_json::Value;

const MARK: char = '\u{1f}';

/// Removes the tag field from an object; errors say what was expected.
pub fn split_tag<E: Error>(
    mut value: Value,
    tag: &str,
    variants: &[&str],
) -> Result<(String, Value), E> {
    let Some(obj) = value.as_object_mut() else {
        return Err(E::custom(format!(
            "expected an object with a `{tag}` field ({})",
            variants.join(", ")
        )));
    };
    match obj.remove(tag) {
        Some(Value::String(s)) => Ok((s, value)),
        Some(_) => Err(nested(
            tag,
            format!("must be a string: one of {}", variants.join(", ")),
        )),
        None => Err(E::custom(format!(
            "missing field `{tag}` (one of {})",
            variants.join(", ")
        ))),
    }
}

/// Deserialises a variant's content, keeping the path of a bad field.
pub fn variant<T: DeserializeOwned, E: Error>(value: Value) -> Result<T, E> {
    serde_path_to_error::deserialize(super::objects::Objects(&value)).map_err(|e| {
        let path = e.path().to_string();
        let msg = e.into_inner().to_string();
        match split_all(&msg) {
            // A tagged enum inside this variant: its paths continue ours.
            Some(inner) => E::custom(nested_all(
                inner.iter().map(|(p, m)| (join(&path, p), m.to_string())),
            )),
            None if path == "." => E::custom(strip_position(&msg)),
            None => nested(&path, strip_position(&msg)),
        }
    })
}

/// [`variant`] for a struct, refusing fields it does not know, before anything else (a typo
/// is named as such, not as a missing field), all of them at once. The variant structs cannot
/// use `deny_unknown_fields`: the OpenAPI schema would then forbid the tag that stands beside
/// them.
pub fn strict_variant<T: DeserializeOwned, E: Error>(value: Value) -> Result<T, E> {
    let known = field_names::<T>();
    if let Some(obj) = value.as_object() {
        let extra: Vec<(String, String)> = obj
            .keys()
            .filter(|k| !known.contains(&k.as_str()))
            .map(|k| {
                let msg = if known.is_empty() {
                    format!("unknown field `{k}`: this takes no options")
                } else {
                    format!("unknown field `{k}`, expected one of: {}", known.join(", "))
                };
                (k.clone(), msg)
            })
            .collect();
        if !extra.is_empty() {
            return Err(E::custom(nested_all(extra)));
        }
    }
    variant(value)
}

/// The field names a struct deserialises, read from what it asks of a deserializer.
pub fn field_names<T: DeserializeOwned>() -> &'static [&'static str] {
    let mut fields: &'static [&'static str] = &[];
    let _ = T::deserialize(Introspect(&mut fields));
    fields
}

struct Introspect<'a>(&'a mut &'static [&'static str]);

impl<'de> serde::Deserializer<'de> for Introspect<'_> {
    type Error = serde::de::value::Error;

    fn deserialize_struct<V: serde::de::Visitor<'de>>(
        self,
        _name: &'static str,
        fields: &'static [&'static str],
        _visitor: V,
    ) -> Result<V::Value, Self::Error> {
        *self.0 = fields;
        Err(Error::custom("introspection only"))
    }

    fn deserialize_any<V: serde::de::Visitor<'de>>(self, _: V) -> Result<V::Value, Self::Error> {
        Err(Error::custom("introspection only"))
    }

    serde::forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes byte_buf
        option unit unit_struct newtype_struct seq tuple tuple_struct map enum identifier
        ignored_any
    }
}

/// An unknown tag value, reported at the tag field.
pub fn unknown<E: Error>(tag: &str, got: &str, variants: &[&str]) -> E {
    nested(
        tag,
        format!(
            "unknown {tag} `{got}`, expected one of: {}",
            variants.join(", ")
        ),
    )
}

fn nested<E: Error>(path: &str, msg: String) -> E {
    E::custom(nested_message(path, &msg))
}

/// Separates the entries of a message that carries several fields.
const NEXT: char = '\u{1e}';

/// The markers cannot appear inside an entry (a key may hold any character).
fn clean(s: &str) -> std::borrow::Cow<'_, str> {
    if s.contains([MARK, NEXT]) {
        s.replace([MARK, NEXT], "\u{fffd}").into()
    } else {
        s.into()
    }
}

/// A message that carries the path of a field inside the one being deserialised (see
/// [`split_nested`]).
pub fn nested_message(path: &str, msg: &str) -> String {
    format!("{MARK}{}{MARK}{}", clean(path), clean(msg))
}

/// A message that carries several fields, each with its path (see [`split_all`]).
pub fn nested_all(entries: impl IntoIterator<Item = (String, String)>) -> String {
    let parts: Vec<String> = entries
        .into_iter()
        .map(|(p, m)| nested_message(&p, &m))
        .collect();
    parts.join(&NEXT.to_string())
}

/// Splits a message made by this module into (inner path, message): its first entry.
pub fn split_nested(msg: &str) -> Option<(&str, &str)> {
    split_all(msg).and_then(|v| v.into_iter().next())
}

/// Splits a message made by this module into its entries, (inner path, message) each.
pub fn split_all(msg: &str) -> Option<Vec<(&str, &str)>> {
    msg.split(NEXT)
        .map(|part| part.strip_prefix(MARK)?.split_once(MARK))
        .collect()
}

/// Joins serde_path_to_error paths (`.` is the root).
pub fn join(outer: &str, inner: &str) -> String {
    match (outer, inner) {
        (".", ".") => "(body)".into(),
        (".", i) => i.into(),
        (o, ".") => o.into(),
        (o, i) if i.starts_with('[') => format!("{o}{i}"),
        (o, i) => format!("{o}.{i}"),
    }
}

/// serde_json appends " at line L column C" to data errors; the path says more.
pub fn strip_position(msg: &str) -> String {
    match msg.rfind(" at line ") {
        Some(i) => msg[..i].to_string(),
        None => msg.to_string(),
    }
}
