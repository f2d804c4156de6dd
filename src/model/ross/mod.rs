//! ROSS's rotor files: the TOML that ROSS 2.3.0's `Rotor.save` writes, read into its elements
//! here and converted into a Whirl beam rotor by [`convert`] (`POST /v1/convert/ross`).
//!
//! What the file holds (checked against ROSS 2.3.0's `save` and `load`, `rotor_assembly.py`,
//! `element.py`, `shaft_element.py`, `bearing_seal_element.py`): `ross_version`, a
//! `[parameters]` table (`min_w`, `max_w`, `rated_w`, each only when set) and one table per
//! element named `"<Class>_<tag>"`, the class being the text before the first `_` (how
//! `Rotor.load` reads it), in the order of the rotor's elements: shaft elements by node, disks,
//! bearings and seals by node, point masses. A shaft element's material is a subtable of it
//! (`name`, `rho`, `E`, `G_s`, `color`); a bearing's coefficients are arrays, of one value when
//! constant, with `frequency` when tabulated; `None` values are left out (TOML has no null).
//!
//! Reading is bounded: the parser's size is the body's (the service's body limit), and the
//! elements are counted against the model limits before any of them is read.

pub mod convert;

use std::ops::Range;

use serde::{Deserialize, Serialize};
use toml::Spanned;
use toml::de::{DeTable, DeValue};
use utoipa::ToSchema;

mod coupling;
mod elements;

use super::Invalid;
use super::Limits;
pub use coupling::Coupling;
use elements::{bearing, disk, point_mass, shaft_element};

pub use convert::Converted;

/// Answer of `POST /v1/convert/ross`.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
pub struct ConvertRossResponse {
    /// The Whirl beam rotor: post it unchanged as the `rotor` of any analysis. ROSS's node
    /// numbers are kept (nodes off the shaft numbered on from the shaft's last node, as ROSS
    /// numbers them), so loads and outputs placed by node mean the same node.
    #[schema(value_type = super::api::RotorInput)]
    pub rotor: serde_json::Value,
    /// What the conversion changed or left out, and how the rotor reads where that matters
    /// (damping frames, interpolation, what has no place).
    pub warnings: Vec<String>,
}

/// Why a file was not converted.
#[derive(Debug)]
pub enum ConvertError {
    /// Not TOML (400): where and why, with its line and column.
    Malformed(String),
    /// TOML, but not a rotor that can be converted (422): each bad table or key, named by its
    /// TOML table (and key), with its line.
    Invalid(Invalid),
}

impl From<Invalid> for ConvertError {
    fn from(e: Invalid) -> Self {
        ConvertError::Invalid(e)
    }
}

/// Converts the text of a file ROSS's `Rotor.save` wrote into a Whirl beam rotor.
pub fn convert(text: &str, limits: &Limits) -> Result<Converted, ConvertError> {
    let file = RossFile::read(text, limits)?;
    Ok(convert::to_whirl(&file, limits)?)
}

/// The file format this converter reads.
pub const ROSS_VERSION: &str = "2.3.0";

/// A shaft element's material: ROSS's `Material`.
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    pub name: String,
    pub density: f64,
    pub young_modulus: f64,
    /// `E / (2 G_s) - 1` when the file gives `E` and `G_s` (as ROSS computes it).
    pub poisson_ratio: f64,
}

/// How ROSS computes a shaft element's shear coefficient (`shear_method_calc`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ShearMethod {
    Cowper,
    Hutchinson,
}

/// ROSS's `ShaftElement`: a Timoshenko element from node `n` to `n + 1`, conical when its
/// right diameters differ from its left ones.
#[derive(Debug, Clone)]
pub struct ShaftElement {
    pub table: String,
    pub line: usize,
    pub n: usize,
    pub length: f64,
    pub idl: f64,
    pub odl: f64,
    pub idr: f64,
    pub odr: f64,
    pub material: Material,
    pub axial_force: f64,
    pub torque: f64,
    pub alpha: f64,
    pub beta: f64,
    pub shear: ShearMethod,
    pub shear_effects: bool,
    pub rotary_inertia: bool,
    pub gyroscopic: bool,
}

/// ROSS's `DiskElement`.
#[derive(Debug, Clone)]
pub struct Disk {
    pub table: String,
    pub line: usize,
    pub n: usize,
    pub mass: f64,
    pub transverse_inertia: f64,
    pub polar_inertia: f64,
}

/// ROSS's `PointMass`.
#[derive(Debug, Clone)]
pub struct PointMass {
    pub table: String,
    pub line: usize,
    pub n: usize,
    pub mx: f64,
    pub my: f64,
    pub mz: f64,
}

/// Names of a bearing's coefficients, as in the file: the 12 lateral ones in Whirl's order,
/// then the 3 axial ones.
pub const COEFFICIENTS: [&str; 15] = [
    "kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy", "mxx", "mxy", "myx", "myy", "kzz",
    "czz", "mzz",
];

/// A bearing or seal (ROSS's `BearingElement` and its subclasses): after construction every
/// one of them is a table of coefficients against the spin speed.
#[derive(Debug, Clone)]
pub struct Bearing {
    pub table: String,
    pub line: usize,
    pub class: String,
    /// A seal (`SealElement` and its subclasses): Whirl's `seals`.
    pub seal: bool,
    pub n: usize,
    pub n_link: Option<usize>,
    /// The table's speeds, rad/s (`frequency`), when it has more than one.
    pub speeds: Option<Vec<f64>>,
    /// The values of each of [`COEFFICIENTS`], one per speed, or one when constant (ROSS's
    /// defaults applied: `kyy = kxx`, `cyy = cxx`, `myy = mxx`, the others 0).
    pub values: Vec<Vec<f64>>,
}

/// A file's elements, in the file's order within each kind.
#[derive(Debug, Clone, Default)]
pub struct RossFile {
    pub version: Option<String>,
    /// The rotor parameters that are set (`min_w`, `max_w`, `rated_w`).
    pub parameters: Vec<String>,
    pub shaft: Vec<ShaftElement>,
    /// Couplings in the shaft line, each on its own node.
    pub couplings: Vec<Coupling>,
    pub disks: Vec<Disk>,
    pub point_masses: Vec<PointMass>,
    pub bearings: Vec<Bearing>,
}

/// Bearing classes, each with the key of its speeds when that is not `frequency`.
const BEARINGS: &[(&str, Option<&str>)] = &[
    ("BearingElement", None),
    ("BallBearingElement", None),
    ("RollerBearingElement", None),
    ("CylindricalBearing", Some("speed")),
    ("BearingFluidFlow", Some("omega")),
    ("PlainJournal", None),
    ("TiltingPad", None),
    ("SqueezeFilmDamper", None),
    ("ThrustPad", None),
];

/// Seal classes.
const SEALS: &[&str] = &[
    "SealElement",
    "LabyrinthSeal",
    "HolePatternSeal",
    "HybridSeal",
];

/// Classes ROSS has that a Whirl rotor cannot hold, and why.
const UNSUPPORTED: &[(&str, &str)] = &[
    (
        "MagneticBearingElement",
        "an active magnetic bearing: its force comes from a controller (PID gains, a transfer \
         function, sensor and amplifier gains), which a Whirl support cannot hold",
    ),
    (
        "GearElement",
        "a gear meshes two shafts; a Whirl beam rotor is one shaft",
    ),
    (
        "GearElementTVMS",
        "a gear meshes two shafts; a Whirl beam rotor is one shaft",
    ),
];

const SHAFT_KEYS: &[&str] = &[
    "L",
    "idl",
    "odl",
    "idr",
    "odr",
    "material",
    "n",
    "axial_force",
    "torque",
    "shear_effects",
    "rotary_inertia",
    "gyroscopic",
    "shear_method_calc",
    "tag",
    "alpha",
    "beta",
];
const DISK_KEYS: &[&str] = &["n", "m", "Id", "Ip", "tag", "scale_factor", "color"];
const POINT_MASS_KEYS: &[&str] = &["n", "m", "mx", "my", "mz", "tag", "scale_factor", "color"];

/// Line (from 1) and column (from 1) of byte `at` of `text`.
pub fn position(text: &str, at: usize) -> (usize, usize) {
    let before = &text.as_bytes()[..at.min(text.len())];
    let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
    let start = before
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(0, |i| i + 1);
    let column = String::from_utf8_lossy(&before[start..]).chars().count() + 1;
    (line, column)
}

/// One element table of the file.
struct Tab<'a, 'i> {
    name: &'a str,
    line: usize,
    entries: &'a DeTable<'i>,
}

impl<'i> Tab<'_, 'i> {
    fn get(&self, key: &str) -> Option<&Spanned<DeValue<'i>>> {
        self.entries.get(key)
    }
}

/// Reads values, recording every bad one with its table, key and line.
struct Reader<'t> {
    text: &'t str,
    bad: Invalid,
}

impl Reader<'_> {
    fn line(&self, span: Range<usize>) -> usize {
        position(self.text, span.start).0
    }

    fn push(&mut self, tab: &Tab, key: Option<&str>, line: usize, message: impl AsRef<str>) {
        let path = match key {
            Some(k) => format!("{}.{k}", tab.name),
            None => tab.name.to_string(),
        };
        self.bad
            .push(path, format!("{} (line {line})", message.as_ref()));
    }

    /// A number (a TOML integer or float), finite; `default` when the key is absent (an
    /// error when there is none).
    fn number(&mut self, tab: &Tab, key: &str, default: Option<f64>) -> Option<f64> {
        let Some(v) = tab.get(key) else {
            if default.is_none() {
                self.push(tab, Some(key), tab.line, "is missing");
            }
            return default;
        };
        let line = self.line(v.span());
        match number(v.get_ref()) {
            Ok(x) => Some(x),
            Err(why) => {
                self.push(tab, Some(key), line, why);
                None
            }
        }
    }

    /// A node number: a TOML integer >= 0.
    fn node(&mut self, tab: &Tab, key: &str, required: bool) -> Option<Option<usize>> {
        let Some(v) = tab.get(key) else {
            if required {
                self.push(tab, Some(key), tab.line, "is missing");
                return None;
            }
            return Some(None);
        };
        let line = self.line(v.span());
        let n = match v.get_ref() {
            DeValue::Integer(i) => i64::from_str_radix(i.as_str(), i.radix()).ok(),
            _ => None,
        };
        match n {
            Some(n) if (0..=i64::from(u32::MAX)).contains(&n) => Some(Some(n as usize)),
            _ => {
                self.push(
                    tab,
                    Some(key),
                    line,
                    "must be a node number (an integer >= 0)",
                );
                None
            }
        }
    }

    fn flag(&mut self, tab: &Tab, key: &str, default: bool) -> Option<bool> {
        match tab.get(key) {
            None => Some(default),
            Some(v) => match v.get_ref() {
                DeValue::Boolean(b) => Some(*b),
                _ => {
                    let line = self.line(v.span());
                    self.push(tab, Some(key), line, "must be true or false");
                    None
                }
            },
        }
    }

    fn string(&mut self, tab: &Tab, key: &str) -> Option<Option<String>> {
        match tab.get(key) {
            None => Some(None),
            Some(v) => match v.get_ref() {
                DeValue::String(s) => Some(Some(s.to_string())),
                _ => {
                    let line = self.line(v.span());
                    self.push(tab, Some(key), line, "must be a string");
                    None
                }
            },
        }
    }

    /// A number or an array of numbers; `Some(None)` when absent.
    fn numbers(&mut self, tab: &Tab, key: &str) -> Option<Option<Vec<f64>>> {
        let Some(v) = tab.get(key) else {
            return Some(None);
        };
        let line = self.line(v.span());
        match v.get_ref() {
            DeValue::Array(items) => {
                let mut out = Vec::with_capacity(items.len());
                for (i, item) in items.iter().enumerate() {
                    match number(item.get_ref()) {
                        Ok(x) => out.push(x),
                        Err(why) => {
                            let line = self.line(item.span());
                            self.push(tab, Some(&format!("{key}[{i}]")), line, why);
                            return None;
                        }
                    }
                }
                Some(Some(out))
            }
            other => match number(other) {
                Ok(x) => Some(Some(vec![x])),
                Err(_) => {
                    self.push(
                        tab,
                        Some(key),
                        line,
                        "must be a number or an array of numbers",
                    );
                    None
                }
            },
        }
    }

    /// Keys a constructor does not take (ROSS's own `load` fails on them too).
    fn only(&mut self, tab: &Tab, keys: &[&str], class: &str) {
        for (k, v) in tab.entries.iter() {
            if !keys.contains(&k.get_ref().as_ref()) {
                let line = self.line(v.span());
                self.push(
                    tab,
                    Some(k.get_ref()),
                    line,
                    format!(
                        "is not an argument of ROSS's {class} (it takes {})",
                        keys.join(", ")
                    ),
                );
            }
        }
    }
}

/// A TOML integer or float as a finite `f64`.
fn number(v: &DeValue) -> Result<f64, String> {
    let x = match v {
        DeValue::Integer(i) => match i64::from_str_radix(i.as_str(), i.radix()) {
            Ok(n) => n as f64,
            Err(_) => return Err("must be a number (this integer is out of range)".into()),
        },
        DeValue::Float(f) => f
            .as_str()
            .parse::<f64>()
            .map_err(|_| "must be a number".to_string())?,
        other => return Err(format!("must be a number (got a {})", other.type_str())),
    };
    if x.is_finite() {
        Ok(x)
    } else {
        Err(format!("must be a finite number (got {x})"))
    }
}

impl RossFile {
    /// Reads the file: its syntax (400 when it is not TOML), then every table (422 naming each
    /// bad one), the element counts checked against `limits` first.
    pub fn read(text: &str, limits: &Limits) -> Result<RossFile, ConvertError> {
        let root = DeTable::parse(text).map_err(|e| malformed(text, &e))?;
        let root = root.get_ref();
        let mut r = Reader {
            text,
            bad: Invalid::default(),
        };
        let mut file = RossFile::default();
        // Count first: nothing proportional to the elements is built past the limits.
        let mut tables: Vec<(&str, Tab)> = vec![];
        for (key, value) in root.iter() {
            let name = key.get_ref().as_ref();
            let line = position(text, key.span().start).0;
            match (name, value.get_ref()) {
                ("ross_version", DeValue::String(v)) => file.version = Some(v.to_string()),
                ("parameters", DeValue::Table(t)) => {
                    file.parameters = t.iter().map(|(k, _)| k.get_ref().to_string()).collect();
                }
                (n, _) if n.starts_with('_') => {}
                (n, DeValue::Table(entries)) => {
                    let class = n.split('_').next().unwrap_or("");
                    tables.push((
                        class,
                        Tab {
                            name: n,
                            line,
                            entries,
                        },
                    ));
                }
                (n, _) => r.bad.push(
                    n,
                    format!(
                        "is not an element table (line {line}): ROSS's file holds \
                         `ross_version`, `[parameters]` and one table per element, \
                         `[\"<Class>_<tag>\"]`"
                    ),
                ),
            }
        }
        count(&tables, limits, &mut r.bad);
        if !r.bad.is_empty() {
            return Err(ConvertError::Invalid(r.bad));
        }
        for (class, tab) in &tables {
            match *class {
                "ShaftElement" => {
                    if let Some(e) = shaft_element(&mut r, tab) {
                        file.shaft.push(e);
                    }
                }
                "CouplingElement" => {
                    if let Some(c) = coupling::coupling(&mut r, tab) {
                        file.couplings.push(c);
                    }
                }
                "DiskElement" => {
                    if let Some(d) = disk(&mut r, tab) {
                        file.disks.push(d);
                    }
                }
                "PointMass" => {
                    if let Some(p) = point_mass(&mut r, tab) {
                        file.point_masses.push(p);
                    }
                }
                c => {
                    let speeds_key = BEARINGS
                        .iter()
                        .find(|(b, _)| *b == c)
                        .map(|(_, k)| *k)
                        .or(SEALS.contains(&c).then_some(None));
                    if let Some(speeds_key) = speeds_key {
                        if let Some(b) = bearing(&mut r, tab, c, speeds_key) {
                            file.bearings.push(b);
                        }
                    } else if let Some((_, why)) = UNSUPPORTED.iter().find(|(u, _)| *u == c) {
                        r.push(tab, None, tab.line, format!("ROSS's {c}: {why}"));
                    } else {
                        let known: Vec<&str> = [
                            "ShaftElement",
                            "CouplingElement",
                            "DiskElement",
                            "PointMass",
                        ]
                        .into_iter()
                        .chain(BEARINGS.iter().map(|(b, _)| *b))
                        .chain(SEALS.iter().copied())
                        .collect();
                        r.push(
                            tab,
                            None,
                            tab.line,
                            format!(
                                "`{c}` is not an element class the converter knows (the class \
                                 is the table name before its first `_`; it reads {})",
                                known.join(", ")
                            ),
                        );
                    }
                }
            }
        }
        if file.shaft.is_empty() && r.bad.is_empty() {
            r.bad.push(
                "ShaftElement",
                "the file has no ShaftElement table: a rotor needs a shaft",
            );
        }
        r.bad.into_result(|| file).map_err(ConvertError::Invalid)
    }
}

/// The parser's error as a problem's detail: line, column and what it expected.
fn malformed(text: &str, e: &toml::de::Error) -> ConvertError {
    let at = e.span().map(|s| position(text, s.start));
    ConvertError::Malformed(match at {
        Some((line, column)) => format!(
            "the body is not TOML: line {line}, column {column}: {}",
            e.message()
        ),
        None => format!("the body is not TOML: {}", e.message()),
    })
}

/// Element counts against the limits of the rotor parser (`rotor::Beam::parse`): the shaft's
/// elements give 2 complex degrees of freedom per node, each node off the shaft one.
fn count(tables: &[(&str, Tab)], limits: &Limits, bad: &mut Invalid) {
    let of = |c: &str| tables.iter().filter(|(k, _)| *k == c).count() as u64;
    let max_dofs = limits.max_dofs as u64;
    // The shaft elements on distinct nodes make the dofs (checked once their nodes are read);
    // sleeves add none, but at most one per shaft element's worth is read.
    let max_elements = (limits.max_dofs / 2).saturating_sub(1).max(1) as u64;
    let shaft = of("ShaftElement") + of("CouplingElement");
    if shaft > 2 * max_elements {
        bad.push(
            "ShaftElement",
            format!(
                "{shaft} shaft elements: more than {} (twice the {max_elements} elements of \
                 the shaft that the limit of {max_dofs} degrees of freedom allows, \
                 WHIRL_MAX_DOFS)",
                2 * max_elements
            ),
        );
    }
    let point_masses = of("PointMass");
    if point_masses > max_dofs {
        bad.push(
            "PointMass",
            format!(
                "{point_masses} point masses: more than the limit of {max_dofs} degrees of \
                 freedom (WHIRL_MAX_DOFS)"
            ),
        );
    }
    let others = tables.len() as u64 - shaft - point_masses;
    if others > 4 * max_dofs {
        bad.push(
            "BearingElement",
            format!(
                "{others} disks, bearings and seals: more than {} (4 per degree of freedom of \
                 the limit, WHIRL_MAX_DOFS)",
                4 * max_dofs
            ),
        );
    }
}

#[cfg(test)]
mod tests;
