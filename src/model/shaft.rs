//! Shaft elements: uniform or conical sections, the loads they carry (axial force, torque),
//! their proportional damping, and sleeves laid over them.
//!
//! A segment of `n` elements is cut into `n` equal lengths; a conical segment's diameters are
//! linear along it, so each element is the frustum between its ends' diameters. A sleeve spans
//! shaft elements from a node on: one sleeve element over each, as long as it, its diameters
//! linear along the sleeve.

use std::collections::BTreeMap;

use super::api::{DampingFrame, RayleighInput, SleeveInput};
use super::coupling::Coupling;
use super::error::{Invalid, finite, non_negative, positive};

/// Proportional damping `alpha M_e + beta K_e` of an element.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rayleigh {
    pub alpha: f64,
    pub beta: f64,
    /// Turns with the shaft (adds the circulatory term), or is nonrotating.
    pub rotating: bool,
}

/// One shaft element, its section and material.
#[derive(Debug, Clone, PartialEq)]
pub struct ShaftElement {
    pub length: f64,
    /// Diameters at the left end.
    pub outer_diameter: f64,
    pub inner_diameter: f64,
    /// Diameters at the right end (equal to the left ones but for a conical element).
    pub outer_diameter_right: f64,
    pub inner_diameter_right: f64,
    pub young_modulus: f64,
    pub density: f64,
    pub poisson_ratio: f64,
    /// Rotating hysteretic damping of the material.
    pub loss_factor: f64,
    /// `None`: Cowper's formula (of the mean diameters for a conical element).
    pub shear_factor: Option<f64>,
    /// N, tension > 0.
    pub axial_force: f64,
    /// N m.
    pub torque: f64,
    pub rayleigh: Option<Rayleigh>,
    /// The sections' rotary (transverse) inertia counted (ROSS's `rotary_inertia`).
    pub rotary_inertia: bool,
    /// Gyroscopic moments counted (ROSS's `gyroscopic`).
    pub gyroscopic: bool,
}

impl ShaftElement {
    /// Shear modulus `E / (2 (1 + nu))`, Pa.
    pub fn shear_modulus(&self) -> f64 {
        self.young_modulus / (2.0 * (1.0 + self.poisson_ratio))
    }

    /// Mean of its ends' areas, m^2 (its axial section, as ROSS takes it).
    pub fn mean_area(&self) -> f64 {
        let a = |o: f64, i: f64| std::f64::consts::PI / 4.0 * (o * o - i * i);
        0.5 * (a(self.outer_diameter, self.inner_diameter)
            + a(self.outer_diameter_right, self.inner_diameter_right))
    }

    /// Mean of its ends' polar second moments of area, m^4 (its torsional section, as ROSS
    /// takes it).
    pub fn mean_polar_moment(&self) -> f64 {
        let j = |o: f64, i: f64| std::f64::consts::PI / 32.0 * (o.powi(4) - i.powi(4));
        0.5 * (j(self.outer_diameter, self.inner_diameter)
            + j(self.outer_diameter_right, self.inner_diameter_right))
    }

    /// Whether its diameters differ between its ends.
    pub fn conical(&self) -> bool {
        self.outer_diameter != self.outer_diameter_right
            || self.inner_diameter != self.inner_diameter_right
    }

    /// Its mass, kg (a frustum's volume times the density).
    pub fn mass(&self) -> f64 {
        let (ol, or) = (self.outer_diameter, self.outer_diameter_right);
        let (il, ir) = (self.inner_diameter, self.inner_diameter_right);
        self.density * std::f64::consts::PI * self.length / 12.0
            * ((ol * ol + ol * or + or * or) - (il * il + il * ir + ir * ir))
    }
}

/// An element of the shaft line, joining nodes `e` and `e + 1`: a beam, or a coupling between
/// two shafts of a train.
#[derive(Debug, Clone, PartialEq)]
pub enum Element {
    Beam(ShaftElement),
    Coupling(Coupling),
    /// A gear mesh between two shafts (torsional and axial analyses).
    Gear(super::gear::Gear),
}

impl Element {
    /// Axial length, m.
    pub fn length(&self) -> f64 {
        match self {
            Element::Beam(b) => b.length,
            Element::Coupling(c) => c.length,
            Element::Gear(g) => g.length,
        }
    }

    /// Mass, kg (a coupling's two halves).
    pub fn mass(&self) -> f64 {
        match self {
            Element::Beam(b) => b.mass(),
            Element::Coupling(c) => c.total_mass(),
            Element::Gear(_) => 0.0,
        }
    }

    /// The beam, unless it is a coupling.
    pub fn beam(&self) -> Option<&ShaftElement> {
        match self {
            Element::Beam(b) => Some(b),
            Element::Coupling(_) | Element::Gear(_) => None,
        }
    }

    /// Its rotating hysteretic loss factor.
    pub fn loss_factor(&self) -> f64 {
        match self {
            Element::Beam(b) => b.loss_factor,
            Element::Coupling(c) => c.loss_factor,
            Element::Gear(_) => 0.0,
        }
    }
}

/// An element laid over shaft element `over` (nodes `over`, `over + 1`).
#[derive(Debug, Clone, PartialEq)]
pub struct Sleeve {
    pub over: usize,
    pub element: ShaftElement,
}

/// A material as validated: `(E, rho, nu, eta)`.
pub type Material = (f64, f64, f64, f64);

/// A section as given by a segment or a sleeve, before it is cut into elements.
pub struct SectionInput<'a> {
    pub outer: f64,
    pub inner: f64,
    pub outer_right: Option<f64>,
    pub inner_right: Option<f64>,
    pub material: &'a str,
    pub shear_factor: Option<f64>,
    pub axial_force: Option<f64>,
    pub torque: Option<f64>,
    pub rayleigh: Option<&'a RayleighInput>,
    /// `(shear_effects, rotary_inertia, gyroscopic)` as given.
    pub flags: [Option<bool>; 3],
}

/// A validated section: an element of length `length` taken from `t0` to `t1` (fractions of
/// the section's length) with [`Section::element`].
#[derive(Debug, Clone, PartialEq)]
pub struct Section {
    outer: (f64, f64),
    inner: (f64, f64),
    material: Material,
    shear_factor: Option<f64>,
    axial_force: f64,
    torque: f64,
    rayleigh: Option<Rayleigh>,
    /// `(rotary_inertia, gyroscopic)`.
    inertia: (bool, bool),
}

impl Section {
    /// The element between fractions `t0` and `t1` of the section, `length` long.
    pub fn element(&self, length: f64, t0: f64, t1: f64) -> ShaftElement {
        let at = |(a, b): (f64, f64), t: f64| if a == b { a } else { a + (b - a) * t };
        let (e, rho, nu, eta) = self.material;
        ShaftElement {
            length,
            outer_diameter: at(self.outer, t0),
            inner_diameter: at(self.inner, t0),
            outer_diameter_right: at(self.outer, t1),
            inner_diameter_right: at(self.inner, t1),
            young_modulus: e,
            density: rho,
            poisson_ratio: nu,
            loss_factor: eta,
            shear_factor: self.shear_factor,
            axial_force: self.axial_force,
            torque: self.torque,
            rayleigh: self.rayleigh,
            rotary_inertia: self.inertia.0,
            gyroscopic: self.inertia.1,
        }
    }
}

/// Validates a section at `at` (`rotor.shaft[i]` or `rotor.sleeves[i]`).
pub fn parse_section(
    s: &SectionInput,
    at: &str,
    materials: &BTreeMap<String, Material>,
    defined: &[&str],
    bad: &mut Invalid,
) -> Option<Section> {
    let outer = bad.check(&format!("{at}.outer_diameter"), positive(s.outer));
    let inner = bad.check(&format!("{at}.inner_diameter"), non_negative(s.inner));
    let outer_r = match s.outer_right {
        None => outer,
        Some(x) => bad.check(&format!("{at}.outer_diameter_right"), positive(x)),
    };
    let inner_r = match s.inner_right {
        None => inner,
        Some(x) => bad.check(&format!("{at}.inner_diameter_right"), non_negative(x)),
    };
    let mut hollow_ok = true;
    for (o, i, name) in [
        (outer, inner, "inner_diameter"),
        (outer_r, inner_r, "inner_diameter_right"),
    ] {
        if let (Some(o), Some(i)) = (o, i)
            && i >= o
        {
            bad.push(
                format!("{at}.{name}"),
                format!("must be smaller than the outer diameter {o} at that end (got {i})"),
            );
            hollow_ok = false;
        }
    }
    let [shear_effects, rotary, gyro] = s.flags;
    let shear = match s.shear_factor {
        // An Euler-Bernoulli element: no shear deformation, `P = 0`.
        _ if shear_effects == Some(false) => {
            if s.shear_factor.is_some() {
                bad.push(
                    format!("{at}.shear_factor"),
                    "an element without `shear_effects` takes no shear factor",
                );
            }
            Some(Some(0.0))
        }
        None => Some(None),
        Some(x) => bad
            .check(&format!("{at}.shear_factor"), positive(x))
            .map(Some),
    };
    let axial = bad.check(
        &format!("{at}.axial_force"),
        finite(s.axial_force.unwrap_or(0.0)),
    );
    let torque = bad.check(&format!("{at}.torque"), finite(s.torque.unwrap_or(0.0)));
    let rayleigh = match s.rayleigh {
        None => Some(None),
        Some(r) => {
            let a = bad.check(
                &format!("{at}.rayleigh_damping.alpha"),
                non_negative(r.alpha),
            );
            let b = bad.check(&format!("{at}.rayleigh_damping.beta"), non_negative(r.beta));
            a.zip(b).map(|(alpha, beta)| {
                Some(Rayleigh {
                    alpha,
                    beta,
                    rotating: r.frame == DampingFrame::Rotating,
                })
            })
        }
    };
    let material = materials.get(s.material).copied();
    if material.is_none() && !defined.contains(&s.material) {
        bad.push(
            format!("{at}.material"),
            format!(
                "unknown material `{}` (defined: {})",
                s.material,
                if defined.is_empty() {
                    "none".into()
                } else {
                    defined.join(", ")
                }
            ),
        );
    }
    Some(Section {
        outer: (outer?, outer_r?),
        inner: (inner?, inner_r?),
        material: material?,
        shear_factor: shear?,
        axial_force: axial?,
        torque: torque?,
        rayleigh: rayleigh?,
        inertia: (rotary.unwrap_or(true), gyro.unwrap_or(true)),
    })
    .filter(|_| hollow_ok)
}

/// Validates the sleeves over `shaft` (the shaft's elements, already cut).
pub fn parse_sleeves(
    inputs: &[SleeveInput],
    shaft: &[Element],
    max_elements: u64,
    materials: &BTreeMap<String, Material>,
    defined: &[&str],
    bad: &mut Invalid,
) -> Vec<Sleeve> {
    // Count first: each sleeve may span the whole shaft, and nothing is built past the limit.
    let pieces: u64 = inputs
        .iter()
        .map(|s| s.elements.unwrap_or(1).clamp(0, shaft.len() as i64) as u64)
        .sum();
    if pieces > max_elements {
        bad.push(
            "rotor.sleeves",
            format!(
                "{pieces} sleeve elements, more than the limit of {max_elements} (one per shaft \
                 element a sleeve spans; WHIRL_MAX_DOFS / 2)"
            ),
        );
        return vec![];
    }
    let mut sleeves = vec![];
    for (i, s) in inputs.iter().enumerate() {
        let at = format!("rotor.sleeves[{i}]");
        let span = s.elements.unwrap_or(1);
        let first = s.node;
        let last_node = shaft.len() as i64;
        if first < 0 || first >= last_node {
            bad.push(
                format!("{at}.node"),
                format!(
                    "must be a shaft node with an element to its right (0 to {}; got {first})",
                    last_node - 1
                ),
            );
        } else if span < 1 || first + span > last_node {
            bad.push(
                format!("{at}.elements"),
                format!(
                    "must be between 1 and {} (the shaft elements from node {first} to the \
                     last node {last_node}; got {span})",
                    last_node - first
                ),
            );
        }
        let section = parse_section(
            &SectionInput {
                outer: s.outer_diameter,
                inner: s.inner_diameter,
                outer_right: s.outer_diameter_right,
                inner_right: s.inner_diameter_right,
                material: &s.material,
                shear_factor: s.shear_factor,
                axial_force: s.axial_force,
                torque: s.torque,
                rayleigh: s.rayleigh_damping.as_ref(),
                flags: [None; 3],
            },
            &at,
            materials,
            defined,
            bad,
        );
        let Some(section) = section else { continue };
        if first < 0 || span < 1 || first + span > last_node {
            continue;
        }
        let range = first as usize..(first + span) as usize;
        if let Some(c) = range.clone().find(|&e| shaft[e].beam().is_none()) {
            bad.push(
                format!("{at}.node"),
                format!(
                    "spans the coupling between nodes {c} and {}: a sleeve lies on a shaft",
                    c + 1
                ),
            );
            continue;
        }
        let total: f64 = shaft[range.clone()].iter().map(Element::length).sum();
        let mut z = 0.0;
        for e in range {
            let l = shaft[e].length();
            sleeves.push(Sleeve {
                over: e,
                element: section.element(l, z / total, (z + l) / total),
            });
            z += l;
        }
    }
    sleeves
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_conical_segment_cut_in_two_is_two_frustums_of_its_mass() {
        let s = Section {
            outer: (0.1, 0.2),
            inner: (0.0, 0.05),
            material: (2e11, 7800.0, 0.3, 0.0),
            shear_factor: None,
            axial_force: 0.0,
            torque: 0.0,
            rayleigh: None,
            inertia: (true, true),
        };
        let (a, b) = (s.element(0.5, 0.0, 0.5), s.element(0.5, 0.5, 1.0));
        assert!((a.outer_diameter_right - 0.15).abs() < 1e-16);
        assert_eq!(a.outer_diameter_right, b.outer_diameter);
        assert_eq!(b.inner_diameter_right, 0.05);
        // The whole frustum, by hand: 7800 pi 1 / 12 ((0.01 + 0.02 + 0.04) - 0.0025) kg.
        let whole = 7800.0 * std::f64::consts::PI / 12.0 * (0.07 - 0.0025);
        assert!((a.mass() + b.mass() - whole).abs() < 1e-12 * whole);
    }
}
