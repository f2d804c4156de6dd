//! Units of the speeds and frequencies a request types (`unit`), and of those an answer gives.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// Unit of a speed or frequency: `rad/s` (the default), `rpm` (revolutions per minute, as data
/// sheets give speeds), `Hz`, or `cpm` (cycles per minute, as vibration analysts give
/// frequencies: the same scale as rpm).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize, Serialize, ToSchema)]
pub enum SpeedUnit {
    #[default]
    #[serde(rename = "rad/s")]
    RadPerSecond,
    #[serde(rename = "rpm")]
    Rpm,
    #[serde(rename = "Hz")]
    Hz,
    #[serde(rename = "cpm")]
    Cpm,
}

impl SpeedUnit {
    /// rad/s in one of this unit.
    pub fn rad_s(self) -> f64 {
        use std::f64::consts::PI;
        match self {
            SpeedUnit::RadPerSecond => 1.0,
            SpeedUnit::Rpm | SpeedUnit::Cpm => PI / 30.0,
            SpeedUnit::Hz => 2.0 * PI,
        }
    }

    /// `x` of this unit in rad/s (exact for rad/s).
    pub fn to_rad_s(self, x: f64) -> f64 {
        match self {
            SpeedUnit::RadPerSecond => x,
            _ => x * self.rad_s(),
        }
    }

    /// `w` rad/s in this unit (exact for rad/s).
    pub fn from_rad_s(self, w: f64) -> f64 {
        match self {
            SpeedUnit::RadPerSecond => w,
            _ => w / self.rad_s(),
        }
    }

    /// As written in JSON and in labels.
    pub fn symbol(self) -> &'static str {
        match self {
            SpeedUnit::RadPerSecond => "rad/s",
            SpeedUnit::Rpm => "rpm",
            SpeedUnit::Hz => "Hz",
            SpeedUnit::Cpm => "cpm",
        }
    }
}

/// One speed or frequency: a number in rad/s, or `{value, unit}` (e.g.
/// `{"value": 3600, "unit": "rpm"}`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, ToSchema)]
#[serde(untagged)]
pub enum SpeedInput {
    RadPerSecond(f64),
    Valued(SpeedValue),
}

/// A speed or frequency in `unit`.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct SpeedValue {
    pub value: f64,
    pub unit: SpeedUnit,
}

impl SpeedInput {
    /// The speed in rad/s (exactly as typed when given in rad/s).
    pub fn rad_s(self) -> f64 {
        match self {
            SpeedInput::RadPerSecond(w) => w,
            SpeedInput::Valued(v) => v.unit.to_rad_s(v.value),
        }
    }

    /// The path of the number as typed: `name`, or `name.value`, for a 422.
    pub fn field(self, name: &str) -> String {
        match self {
            SpeedInput::RadPerSecond(_) => name.to_string(),
            SpeedInput::Valued(_) => format!("{name}.value"),
        }
    }

    /// The number as typed, whatever its unit.
    pub fn value(self) -> f64 {
        match self {
            SpeedInput::RadPerSecond(w) => w,
            SpeedInput::Valued(v) => v.value,
        }
    }
}

impl Default for SpeedInput {
    fn default() -> Self {
        SpeedInput::RadPerSecond(0.0)
    }
}

impl From<f64> for SpeedInput {
    fn from(w: f64) -> Self {
        SpeedInput::RadPerSecond(w)
    }
}

impl<'de> Deserialize<'de> for SpeedInput {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        match serde_json::Value::deserialize(d)? {
            serde_json::Value::Number(n) => n
                .as_f64()
                .map(SpeedInput::RadPerSecond)
                .ok_or_else(|| serde::de::Error::custom("must be a finite number")),
            v @ serde_json::Value::Object(_) => {
                crate::model::tagged::variant(v).map(SpeedInput::Valued)
            }
            _ => Err(serde::de::Error::custom(
                "must be a number in rad/s or {\"value\", \"unit\"} (unit rad/s, rpm, Hz or cpm)",
            )),
        }
    }
}
