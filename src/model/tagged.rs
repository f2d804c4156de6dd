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
    serde_path_to_error::deserialize(value).map_err(|e| {
        let path = e.path().to_string();
        let msg = e.into_inner().to_string();
        match split_nested(&msg) {
            // A tagged enum inside this variant: its path continues ours.
            Some((inner, m)) => nested(&join(&path, inner), m.to_string()),
            None if path == "." => E::custom(strip_position(&msg)),
            None => nested(&path, strip_position(&msg)),
        }
    })
}

/// [`variant`] for a struct, refusing fields it does not know, before anything else (a typo
/// is named as such, not as a missing field). The variant structs cannot use
/// `deny_unknown_fields`: the OpenAPI schema would then forbid the tag that stands beside them.
pub fn strict_variant<T: DeserializeOwned, E: Error>(value: Value) -> Result<T, E> {
    let known = field_names::<T>();
    if let Some(obj) = value.as_object()
        && let Some(extra) = obj.keys().find(|k| !known.contains(&k.as_str()))
    {
        let msg = if known.is_empty() {
            format!("unknown field `{extra}`: this takes no options")
        } else {
            format!(
                "unknown field `{extra}`, expected one of: {}",
                known.join(", ")
            )
        };
        return Err(nested(extra, msg));
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

/// A message that carries the path of a field inside the one being deserialised (see
/// [`split_nested`]).
pub fn nested_message(path: &str, msg: &str) -> String {
    format!("{MARK}{path}{MARK}{msg}")
}

/// Splits a message made by this module into (inner path, message).
pub fn split_nested(msg: &str) -> Option<(&str, &str)> {
    let rest = msg.strip_prefix(MARK)?;
    rest.split_once(MARK)
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
