//! A JSON value as a deserializer that refuses an array where a struct is read.
//!
//! serde's derived structs accept a sequence as well as a map, reading the fields by position:
//! `[1e6, 100, 0, 0]` in place of a support would be taken as its first four fields, with no
//! error. The schema says object wherever a struct is read, so [`Objects`] answers such an
//! array with an error at its path. Everything else reads as from `&Value`.

use serde::de::value::BorrowedStrDeserializer;
use serde::de::{self, DeserializeSeed, Error as _, MapAccess, SeqAccess, Visitor};
use serde_json::{Error, Value};

/// What a client is told when it sent an array for an object.
pub const NOT_AN_ARRAY: &str =
    "must be an object with named fields, not an array (fields are never read by position)";

/// `&Value` as a deserializer, arrays refused for structs at any depth.
pub struct Objects<'a>(pub &'a Value);

impl<'de> de::Deserializer<'de> for Objects<'de> {
    type Error = Error;

    fn deserialize_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        match self.0 {
            Value::Array(items) => {
                let mut seq = Seq(items.iter());
                let out = visitor.visit_seq(&mut seq)?;
                match seq.0.len() {
                    0 => Ok(out),
                    _ => Err(Error::invalid_length(
                        items.len(),
                        &"fewer elements in the array",
                    )),
                }
            }
            Value::Object(map) => {
                let mut access = Map {
                    iter: map.iter(),
                    value: None,
                };
                visitor.visit_map(&mut access)
            }
            other => de::Deserializer::deserialize_any(other, visitor),
        }
    }

    fn deserialize_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        _fields: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, Error> {
        match self.0 {
            Value::Array(_) => Err(Error::custom(NOT_AN_ARRAY)),
            _ => self.deserialize_any(visitor),
        }
    }

    fn deserialize_option<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        match self.0 {
            Value::Null => visitor.visit_none(),
            _ => visitor.visit_some(self),
        }
    }

    fn deserialize_newtype_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        visitor: V,
    ) -> Result<V::Value, Error> {
        visitor.visit_newtype_struct(self)
    }

    fn deserialize_enum<V: Visitor<'de>>(
        self,
        name: &'static str,
        variants: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, Error> {
        // The model's enums with content are tagged by hand (`tagged`); these are names.
        de::Deserializer::deserialize_enum(self.0, name, variants, visitor)
    }

    fn deserialize_ignored_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_unit()
    }

    serde::forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes byte_buf
        unit unit_struct seq tuple tuple_struct map identifier
    }
}

struct Seq<'a>(std::slice::Iter<'a, Value>);

impl<'de> SeqAccess<'de> for Seq<'de> {
    type Error = Error;

    fn next_element_seed<T: DeserializeSeed<'de>>(
        &mut self,
        seed: T,
    ) -> Result<Option<T::Value>, Error> {
        self.0
            .next()
            .map(|v| seed.deserialize(Objects(v)))
            .transpose()
    }

    fn size_hint(&self) -> Option<usize> {
        Some(self.0.len())
    }
}

struct Map<'a> {
    iter: serde_json::map::Iter<'a>,
    value: Option<&'a Value>,
}

impl<'de> MapAccess<'de> for Map<'de> {
    type Error = Error;

    fn next_key_seed<K: DeserializeSeed<'de>>(
        &mut self,
        seed: K,
    ) -> Result<Option<K::Value>, Error> {
        match self.iter.next() {
            Some((k, v)) => {
                self.value = Some(v);
                seed.deserialize(BorrowedStrDeserializer::<Error>::new(k))
                    .map(Some)
            }
            None => Ok(None),
        }
    }

    fn next_value_seed<V: DeserializeSeed<'de>>(&mut self, seed: V) -> Result<V::Value, Error> {
        match self.value.take() {
            Some(v) => seed.deserialize(Objects(v)),
            None => Err(Error::custom("a value without its key")),
        }
    }

    fn size_hint(&self) -> Option<usize> {
        Some(self.iter.len())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde::Deserialize;

    #[derive(Debug, Deserialize, PartialEq)]
    struct Support {
        kxx: f64,
        kyy: f64,
        #[serde(default)]
        cxx: Option<f64>,
    }

    #[derive(Debug, Deserialize, PartialEq)]
    struct Rotor {
        supports: Vec<Support>,
        point: [f64; 2],
    }

    fn read(v: Value) -> Result<Rotor, String> {
        serde_path_to_error::deserialize::<_, Rotor>(Objects(&v)).map_err(|e| {
            let path = e.path().to_string();
            format!("{path}: {}", e.into_inner())
        })
    }

    #[test]
    fn arrays_are_refused_where_objects_are_read() {
        let ok = read(serde_json::json!({
            "supports": [{"kxx": 1.0, "kyy": 2.0}], "point": [1.0, 2.0]}));
        assert_eq!(ok.unwrap().supports[0].kyy, 2.0);
        // serde_json alone reads this support by position.
        let by_position = serde_json::json!({"supports": [[1.0, 2.0, 3.0]], "point": [1.0, 2.0]});
        assert!(serde_json::from_value::<Rotor>(by_position.clone()).is_ok());
        let e = read(by_position).unwrap_err();
        assert!(e.starts_with("supports[0]: must be an object"), "{e}");
        let e = read(serde_json::json!([[], [1.0, 2.0]])).unwrap_err();
        assert!(e.starts_with(".: must be an object"), "{e}");
        // Fixed-size arrays are still arrays.
        let e = read(serde_json::json!({"supports": [], "point": [1.0, 2.0, 3.0]})).unwrap_err();
        assert!(e.starts_with("point:"), "{e}");
    }
}
