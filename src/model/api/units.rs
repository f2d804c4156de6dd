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
