//! A section property in a case file: a number, or a piecewise-linear table over the span.
//!
//! Written by hand rather than as an `untagged` enum so that a malformed property gets a message
//! that says what is wrong ("table is missing `value`") instead of "data did not match any
//! variant".

use std::fmt;

use flexwing::beam::Profile;
use serde::de::{self, Deserialize, Deserializer, MapAccess, Visitor};
use serde::ser::{Serialize, SerializeStruct, Serializer};

/// `EI = 2.0e4` or `EI = { x = [0.0, 10.0], value = [4.0e4, 1.0e4] }`: the library's
/// [`Profile`], written as a number or a table.
#[derive(Debug, Clone, PartialEq)]
pub struct Property(pub Profile);

impl<'de> Deserialize<'de> for Property {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(PropertyVisitor)
    }
}

impl Serialize for Property {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match &self.0 {
            Profile::Uniform(v) => s.serialize_f64(*v),
            Profile::Table { x, value } => {
                let mut table = s.serialize_struct("Property", 2)?;
                table.serialize_field("x", x)?;
                table.serialize_field("value", value)?;
                table.end()
            }
        }
    }
}

struct PropertyVisitor;

const TABLE_KEYS: &[&str] = &["x", "value"];

impl<'de> Visitor<'de> for PropertyVisitor {
    type Value = Property;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a number, or a table { x = [...], value = [...] }")
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Property, E> {
        Ok(Property(Profile::Uniform(v)))
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Property, E> {
        Ok(Property(Profile::Uniform(v as f64)))
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Property, E> {
        Ok(Property(Profile::Uniform(v as f64)))
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Property, A::Error> {
        let mut x: Option<Vec<f64>> = None;
        let mut value: Option<Vec<f64>> = None;
        while let Some(key) = map.next_key::<String>()? {
            let slot = match key.as_str() {
                "x" => &mut x,
                "value" => &mut value,
                other => return Err(de::Error::unknown_field(other, TABLE_KEYS)),
            };
            if slot.is_some() {
                return Err(de::Error::custom(format_args!("duplicate key `{key}`")));
            }
            *slot = Some(map.next_value()?);
        }
        match (x, value) {
            (Some(x), Some(value)) => Ok(Property(Profile::Table { x, value })),
            (None, Some(_)) => Err(de::Error::custom(
                "table is missing `x` (stations along the span, m); \
                 a table is { x = [...], value = [...] }",
            )),
            (Some(_), None) => Err(de::Error::custom(
                "table is missing `value` (the property at each station); \
                 a table is { x = [...], value = [...] }",
            )),
            (None, None) => Err(de::Error::custom(
                "empty table; a property is a number or a table { x = [...], value = [...] }",
            )),
        }
    }
}
