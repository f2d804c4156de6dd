//! A valid finite-element rotor: its shaft's elements, sleeves, disks, point masses and
//! supports, validated from a `beam` rotor's input.

use super::api::{BeamInput, GuyanKeep};
use super::coupling::Coupling;
use super::error::{Invalid, finite, loss_factor, non_negative, positive};
use super::gear::Gear;
use super::limits::Limits;
use super::point_masses::PointMass;
use super::point_masses::{nodes_off_shaft, parse_point_masses};
use super::shaft::{Element, Sleeve};
use super::shaft::{Material, SectionInput, parse_section, parse_sleeves};
use super::supports::{GeneralSupport, Support, parse_supports};

/// A rigid disk.
#[derive(Debug, Clone, PartialEq)]
pub struct Disk {
    pub node: usize,
    pub mass: f64,
    pub polar_inertia: f64,
    pub transverse_inertia: f64,
}

/// A valid finite-element rotor: element `e` joins nodes `e` and `e + 1`; nodes from
/// `shaft_nodes()` on are off the shaft (translations only, see `point_masses`).
#[derive(Debug, Clone, PartialEq)]
pub struct BeamRotor {
    elements: Vec<Element>,
    /// Elements laid over the shaft's.
    sleeves: Vec<Sleeve>,
    disks: Vec<Disk>,
    point_masses: Vec<PointMass>,
    /// Nodes off the shaft.
    off_shaft: usize,
    supports: Vec<Support>,
    general_supports: Vec<GeneralSupport>,
    guyan: Option<GuyanKeep>,
}

impl BeamRotor {
    pub fn elements(&self) -> &[Element] {
        &self.elements
    }
    /// Left nodes of the couplings (element `e` joins nodes `e` and `e + 1`).
    pub fn couplings(&self) -> Vec<usize> {
        (0..self.elements.len())
            .filter(|&e| self.elements[e].beam().is_none())
            .collect()
    }
    /// Elements laid over the shaft's, their matrices added to those of the element under.
    pub fn sleeves(&self) -> &[Sleeve] {
        &self.sleeves
    }
    /// Each shaft element's mass with the sleeves laid over it, kg.
    pub fn element_masses(&self) -> Vec<f64> {
        let mut m: Vec<f64> = self.elements.iter().map(Element::mass).collect();
        for s in &self.sleeves {
            m[s.over] += s.element.mass();
        }
        m
    }
    /// Mass of the shaft, sleeves included, kg.
    pub fn shaft_mass(&self) -> f64 {
        self.elements.iter().map(Element::mass).sum::<f64>()
            + self.sleeves.iter().map(|s| s.element.mass()).sum::<f64>()
    }
    pub fn disks(&self) -> &[Disk] {
        &self.disks
    }
    /// Isotropic supports (the isotropic form), seals among them.
    pub fn supports(&self) -> &[Support] {
        &self.supports
    }
    /// Supports in the general form, seals among them.
    pub fn general_supports(&self) -> &[GeneralSupport] {
        &self.general_supports
    }
    /// Whether it has seals.
    pub fn has_seals(&self) -> bool {
        self.supports.iter().any(|s| s.seal) || self.general_supports.iter().any(|s| s.seal)
    }
    pub fn guyan(&self) -> Option<GuyanKeep> {
        self.guyan
    }
    pub fn point_masses(&self) -> &[PointMass] {
        &self.point_masses
    }
    /// Every node: the shaft's and those off it.
    pub fn nodes(&self) -> usize {
        self.shaft_nodes() + self.off_shaft
    }
    /// The shaft's nodes, `0..shaft_nodes()`.
    pub fn shaft_nodes(&self) -> usize {
        self.elements.len() + 1
    }
    /// Complex degrees of freedom as assembled: translation and rotation on the shaft,
    /// translation off it.
    pub fn assembled_dofs(&self) -> usize {
        2 * self.shaft_nodes() + self.off_shaft
    }
    /// Whether it has nodes off the shaft or supports between two nodes: the shaft-only
    /// views of the audit (critical speed map, statics) then leave the pedestals out.
    pub fn has_pedestals(&self) -> bool {
        self.off_shaft > 0
            || self.supports.iter().any(|s| s.link.is_some())
            || self.general_supports.iter().any(|s| s.link.is_some())
    }

    pub fn parse(b: &BeamInput, limits: &Limits) -> Result<Self, Invalid> {
        let mut bad = Invalid::default();
        let mut materials = std::collections::BTreeMap::new();
        for (name, m) in &b.materials {
            let at = format!("rotor.materials.{name}");
            let e = bad.check(&format!("{at}.young_modulus"), positive(m.young_modulus));
            let rho = bad.check(&format!("{at}.density"), positive(m.density));
            let nu = bad.check(
                &format!("{at}.poisson_ratio"),
                finite(m.poisson_ratio).and_then(|v| {
                    if v > -1.0 && v < 0.5 {
                        Ok(v)
                    } else {
                        Err(format!("must be in (-1, 0.5) (got {v})"))
                    }
                }),
            );
            let eta = bad.check(&format!("{at}.loss_factor"), loss_factor(m.loss_factor));
            if let (Some(e), Some(rho), Some(nu), Some(eta)) = (e, rho, nu, eta) {
                materials.insert(name.clone(), (e, rho, nu, eta));
            }
        }
        if b.shaft.is_empty() {
            bad.push("rotor.shaft", "needs at least one segment");
        }
        // Count the elements first: a body of a few bytes may ask for millions, and nothing
        // is built until the count is within the limit.
        let max_elements = (limits.max_dofs / 2).saturating_sub(1).max(1) as u64;
        let counts: Vec<Option<u64>> = b
            .shaft
            .iter()
            .enumerate()
            .map(|(i, seg)| match seg.elements {
                None => Some(1),
                Some(n) if n >= 1 && n as u64 <= max_elements => Some(n as u64),
                Some(n) => {
                    bad.push(
                        format!("rotor.shaft[{i}].elements"),
                        format!(
                            "must be between 1 and {max_elements} (got {n}): each element adds 2 \
                             degrees of freedom and the limit is {} ({})",
                            limits.max_dofs, limits.dofs_setting
                        ),
                    );
                    None
                }
            })
            .collect();
        let element_count: u64 = counts.iter().flatten().sum();
        // A total of the segments within the limit only: with one refused above it would
        // count the others alone (1600 elements reported as 640).
        let too_many =
            counts.iter().all(Option::is_some) && 2 * (element_count + 1) > limits.max_dofs as u64;
        if too_many {
            bad.push(
                "rotor.shaft",
                format!(
                    "{} elements give {} degrees of freedom, more than the limit of {} ({})",
                    element_count,
                    2 * (element_count + 1),
                    limits.max_dofs,
                    limits.dofs_setting
                ),
            );
        }
        let defined: Vec<&str> = b.materials.keys().map(String::as_str).collect();
        let materials: std::collections::BTreeMap<String, Material> = materials;
        let mut elements = vec![];
        for (i, seg) in b.shaft.iter().enumerate() {
            let at = format!("rotor.shaft[{i}]");
            if let Some(c) = &seg.coupling {
                if seg.gear.is_some() {
                    bad.push(
                        format!("{at}.gear"),
                        "a segment is a coupling or a gear, not both",
                    );
                }
                if let Some(c) = Coupling::parse(seg, c, &at, &mut bad)
                    && !too_many
                {
                    elements.push(Element::Coupling(c));
                }
                continue;
            }
            if let Some(g) = &seg.gear {
                if let Some(g) = Gear::parse(seg, g, &at, &mut bad)
                    && !too_many
                {
                    elements.push(Element::Gear(g));
                }
                continue;
            }
            let length = bad.check(&format!("{at}.length"), positive(seg.length));
            let section = parse_section(
                &SectionInput {
                    outer: seg.outer_diameter,
                    inner: seg.inner_diameter,
                    outer_right: seg.outer_diameter_right,
                    inner_right: seg.inner_diameter_right,
                    material: &seg.material,
                    shear_factor: seg.shear_factor,
                    axial_force: seg.axial_force,
                    torque: seg.torque,
                    rayleigh: seg.rayleigh_damping.as_ref(),
                    flags: [seg.shear_effects, seg.rotary_inertia, seg.gyroscopic],
                },
                &at,
                &materials,
                &defined,
                &mut bad,
            );
            if let (Some(l), Some(sec), Some(n)) = (length, section, counts[i])
                && !too_many
            {
                for k in 0..n {
                    let (t0, t1) = (k as f64 / n as f64, (k + 1) as f64 / n as f64);
                    elements.push(Element::Beam(sec.element(l / n as f64, t0, t1)));
                }
            }
        }
        // Nodes as the segments count them, valid or not, so that a bad segment does not
        // also make every later node look missing.
        let nodes = element_count as usize + 1;
        // With no shaft, or a segment's count invalid, the nodes are unknown: check only the
        // sign then.
        let mut nodes_known =
            !b.shaft.is_empty() && counts.iter().all(Option::is_some) && !too_many;
        let off_shaft = if nodes_known {
            nodes_off_shaft(&b.point_masses, nodes, &mut bad)
        } else {
            Some(0)
        };
        nodes_known &= off_shaft.is_some();
        let off_shaft = off_shaft.unwrap_or(0);
        if nodes_known && 2 * nodes as u64 + off_shaft as u64 > limits.max_dofs as u64 {
            bad.push(
                "rotor.point_masses",
                format!(
                    "{} nodes off the shaft give {} degrees of freedom, more than the limit of \
                     {} ({})",
                    off_shaft,
                    2 * nodes + off_shaft,
                    limits.max_dofs,
                    limits.dofs_setting
                ),
            );
            nodes_known = false;
        }
        let node_check = |bad: &mut Invalid, at: String, node: i64, all: usize| {
            if node >= 0 && (!nodes_known || (node as u64) < all as u64) {
                Some(node as usize)
            } else {
                let why = if node < 0 {
                    format!("must be >= 0 (got {node})")
                } else if all == nodes {
                    format!("node {node} is not on the shaft (nodes 0 to {})", nodes - 1)
                } else {
                    format!(
                        "node {node} does not exist (shaft nodes 0 to {}, nodes off the shaft \
                         {} to {}: those of `point_masses`)",
                        nodes - 1,
                        nodes,
                        all - 1
                    )
                };
                bad.push(at, why);
                None
            }
        };
        let all_nodes = nodes + off_shaft;
        let mut node_ok = |bad: &mut Invalid, at: String, node: i64| -> Option<usize> {
            node_check(bad, at, node, all_nodes)
        };
        let point_masses = parse_point_masses(&b.point_masses, nodes, &mut bad, &mut node_ok);
        let mut disks = vec![];
        for (i, d) in b.disks.iter().enumerate() {
            let at = format!("rotor.disks[{i}]");
            let node = node_check(&mut bad, format!("{at}.node"), d.node, nodes);
            let mass = bad.check(&format!("{at}.mass"), non_negative(d.mass));
            let jp = bad.check(
                &format!("{at}.polar_inertia"),
                non_negative(d.polar_inertia),
            );
            let jt = bad.check(
                &format!("{at}.transverse_inertia"),
                non_negative(d.transverse_inertia),
            );
            if let (Some(node), Some(mass), Some(jp), Some(jt)) = (node, mass, jp, jt) {
                disks.push(Disk {
                    node,
                    mass,
                    polar_inertia: jp,
                    transverse_inertia: jt,
                });
            }
        }
        if b.supports.is_empty() {
            bad.push(
                "rotor.supports",
                "a rotor needs at least one support (bearing) to hold it",
            );
        }
        let (mut supports, mut general_supports) =
            parse_supports(&b.supports, false, &mut bad, &mut node_ok);
        let (seals, general_seals) = parse_supports(&b.seals, true, &mut bad, &mut node_ok);
        supports.extend(seals);
        general_supports.extend(general_seals);
        super::supports::check_schedule(&general_supports, &mut bad);
        let sleeves = if bad.is_empty() {
            parse_sleeves(
                &b.sleeves,
                &elements,
                max_elements,
                &materials,
                &defined,
                &mut bad,
            )
        } else {
            vec![]
        };
        bad.into_result(|| BeamRotor {
            elements,
            sleeves,
            disks,
            point_masses,
            off_shaft,
            supports,
            general_supports,
            guyan: b.reduction.as_ref().map(|r| r.guyan),
        })
    }
}
