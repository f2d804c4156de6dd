//! Assembly of a finite-element rotor into a [`RotorSystem`], and of any validated rotor
//! ([`RotorSystem::assemble`]: the system's type is in `system`, below `fem`).
//!
//! Two complex degrees of freedom per node, `(r, phi)` at `2 node` and `2 node + 1`.
//! The shaft's stiffness and its material loss (`K''_r = eta K_e` per element) are rotating;
//! supports act on translations and are nonrotating (stiffness, viscous damping,
//! `K''_n = eta k`). Disks add mass on `r`, transverse inertia on `phi` and polar inertia to
//! the gyroscopic matrix. A coupling (`model::coupling`) joins two nodes of the shaft line
//! like an element, with rotating springs and dampers and its halves' masses lumped.

use super::conical::{self, Cone};
use super::element::{self, Mat4, Section};
use super::guyan;
use crate::linalg::{LinalgError, Sparse};
use crate::model::api::GuyanKeep;
use crate::model::rotor::{BeamRotor, Coupling, Element, MatrixRotor, Rotor, ShaftElement};
use crate::system::{Dof, DofKind, PlacedSupport, Placement, RotorSystem};

/// The section of a uniform element (of a conical one, its mean diameters), with Cowper's
/// shear factor where none was given.
pub fn section(e: &ShaftElement) -> Section {
    let outer = 0.5 * (e.outer_diameter + e.outer_diameter_right);
    let inner = 0.5 * (e.inner_diameter + e.inner_diameter_right);
    Section {
        length: e.length,
        outer_diameter: outer,
        inner_diameter: inner,
        young_modulus: e.young_modulus,
        density: e.density,
        poisson_ratio: e.poisson_ratio,
        shear_factor: e
            .shear_factor
            .unwrap_or_else(|| element::cowper_shear_factor(outer, inner, e.poisson_ratio)),
    }
}

/// The matrices of one element: bending stiffness `k`, mass, gyroscopic, and shear parameter.
/// Without rotary inertia the mass is the translational part alone; without gyroscopic
/// moments `G = 0` (ROSS's element options).
pub fn element_matrices(e: &ShaftElement) -> (Mat4, Mat4, Mat4, f64) {
    let (k, mt, mr, g, p) = if e.conical() {
        let c = cone(e);
        (
            conical::stiffness(&c),
            conical::translational_mass(&c),
            conical::rotary_mass(&c),
            conical::gyroscopic(&c),
            conical::shear_parameter(&c),
        )
    } else {
        let sec = section(e);
        (
            element::stiffness(&sec),
            element::translational_mass(&sec),
            element::rotary_mass(&sec),
            element::gyroscopic(&sec),
            sec.shear_parameter(),
        )
    };
    let mut m = mt;
    if e.rotary_inertia {
        for (row, r) in m.iter_mut().zip(mr) {
            for (x, y) in row.iter_mut().zip(r) {
                *x += y;
            }
        }
    }
    let g = if e.gyroscopic { g } else { [[0.0; 4]; 4] };
    (k, m, g, p)
}

/// A conical element, with Cowper's factor of its mean diameters where none was given (ROSS).
fn cone(e: &ShaftElement) -> Cone {
    let c = Cone {
        length: e.length,
        outer_left: e.outer_diameter,
        inner_left: e.inner_diameter,
        outer_right: e.outer_diameter_right,
        inner_right: e.inner_diameter_right,
        young_modulus: e.young_modulus,
        density: e.density,
        poisson_ratio: e.poisson_ratio,
        shear_factor: 1.0,
    };
    let (o, i) = conical::mean_diameters(&c);
    Cone {
        shear_factor: e
            .shear_factor
            .unwrap_or_else(|| element::cowper_shear_factor(o, i, e.poisson_ratio)),
        ..c
    }
}

/// Adds an element on the degrees of freedom from `at` on: its stiffness and geometric
/// stiffness are rotating, its loss `eta K_e` rotating hysteretic, its torque circulatory, its
/// proportional damping in the frame it names.
fn add_element(s: &mut Parts, at: usize, e: &ShaftElement) {
    let (k, m, g, p) = element_matrices(e);
    add(&mut s.stiffness_rotating, at, &k, 1.0);
    add(&mut s.hysteretic_rotating, at, &k, e.loss_factor);
    add(&mut s.mass, at, &m, 1.0);
    add(&mut s.gyroscopic, at, &g, 1.0);
    let kaf = conical::axial_force(e.axial_force, e.length, p);
    add(&mut s.stiffness_rotating, at, &kaf, 1.0);
    if e.torque != 0.0 {
        add(
            &mut s.circulatory,
            at,
            &conical::torque(e.torque, e.length),
            1.0,
        );
    }
    if let Some(r) = e.rayleigh {
        let target = if r.rotating {
            &mut s.damping_rotating
        } else {
            &mut s.damping_nonrotating
        };
        add(target, at, &m, r.alpha);
        add(target, at, &k, r.beta);
        add(target, at, &kaf, r.beta);
    }
}

/// A coupling from the degrees of freedom `at` (`r`, `phi` of its left node) to `at + 3`: a
/// spring and a rotating damper between the translations and between the rotations, each
/// half's mass and inertias on its node.
fn add_coupling(s: &mut Parts, at: usize, c: &Coupling) {
    let (kt, kr) = (c.translational_stiffness, c.angular_stiffness);
    let (ct, cr) = (c.translational_damping, c.angular_damping);
    let between = |m: &mut Triplets, d: usize, a: f64| spring(m, at + d, Some(at + 2 + d), a);
    between(&mut s.stiffness_rotating, 0, kt);
    between(&mut s.stiffness_rotating, 1, kr);
    between(&mut s.hysteretic_rotating, 0, c.loss_factor * kt);
    between(&mut s.hysteretic_rotating, 1, c.loss_factor * kr);
    between(&mut s.damping_rotating, 0, ct);
    between(&mut s.damping_rotating, 1, cr);
    for side in 0..2 {
        let (r, phi) = (at + 2 * side, at + 2 * side + 1);
        s.mass.push((r, r, c.mass[side]));
        s.mass.push((phi, phi, c.transverse_inertia[side]));
        s.gyroscopic.push((phi, phi, c.polar_inertia[side]));
    }
}

/// The shaft and disks of a beam rotor alone: no point masses, no nodes off the shaft, no
/// supports, no reduction (2 complex degrees of freedom per node). What the audit analyses
/// replace the supports on (as ROSS's `run_ucs` and `run_static` do, which drop point masses).
pub fn beam_shaft(rotor: &BeamRotor) -> RotorSystem {
    structure(rotor, 2 * rotor.shaft_nodes())
}

/// The degree of freedom of a node's translation in an assembled beam rotor: `2 node` on the
/// shaft, then one per node off it.
pub fn translation_dof(rotor: &BeamRotor, node: usize) -> usize {
    let shaft = rotor.shaft_nodes();
    if node < shaft {
        2 * node
    } else {
        2 * shaft + (node - shaft)
    }
}

/// Entries of one matrix as assembled, `(row, column, value)`, summed in order when compressed.
type Triplets = Vec<(usize, usize, f64)>;

/// A rotor's matrices while they are assembled.
#[derive(Default)]
struct Parts {
    mass: Triplets,
    gyroscopic: Triplets,
    stiffness_rotating: Triplets,
    stiffness_nonrotating: Triplets,
    damping_rotating: Triplets,
    damping_nonrotating: Triplets,
    hysteretic_rotating: Triplets,
    hysteretic_nonrotating: Triplets,
    circulatory: Triplets,
}

impl Parts {
    /// The `n x n` system on the beam rotor's degrees of freedom (no supports placed yet).
    fn finish(self, rotor: &BeamRotor, n: usize) -> RotorSystem {
        let shaft = rotor.shaft_nodes();
        let z = |t: Triplets| Sparse::from_triplets(n, n, &t);
        RotorSystem {
            mass: z(self.mass),
            gyroscopic: z(self.gyroscopic),
            stiffness_rotating: z(self.stiffness_rotating),
            stiffness_nonrotating: z(self.stiffness_nonrotating),
            damping_rotating: z(self.damping_rotating),
            damping_nonrotating: z(self.damping_nonrotating),
            hysteretic_rotating: z(self.hysteretic_rotating),
            hysteretic_nonrotating: z(self.hysteretic_nonrotating),
            circulatory: z(self.circulatory),
            dofs: (0..n)
                .map(|i| match i {
                    i if i >= 2 * shaft => Dof {
                        node: shaft + (i - 2 * shaft),
                        kind: DofKind::Translation,
                    },
                    i if i % 2 == 0 => Dof {
                        node: i / 2,
                        kind: DofKind::Translation,
                    },
                    i => Dof {
                        node: i / 2,
                        kind: DofKind::Rotation,
                    },
                })
                .collect(),
            supports: vec![],
        }
    }
}

/// The shaft and disks on `n` degrees of freedom (`n` past the shaft's: nodes off it).
fn structure(rotor: &BeamRotor, n: usize) -> RotorSystem {
    structure_parts(rotor).finish(rotor, n)
}

/// The shaft's and disks' entries.
fn structure_parts(rotor: &BeamRotor) -> Parts {
    let mut s = Parts::default();
    for (e, el) in rotor.elements().iter().enumerate() {
        match el {
            Element::Beam(b) => add_element(&mut s, 2 * e, b),
            Element::Coupling(c) => add_coupling(&mut s, 2 * e, c),
            // Refused by the lateral analyses (`Rotor::parse_motion`).
            Element::Gear(_) => {}
        }
    }
    for sl in rotor.sleeves() {
        add_element(&mut s, 2 * sl.over, &sl.element);
    }
    for d in rotor.disks() {
        let (r, phi) = (2 * d.node, 2 * d.node + 1);
        s.mass.push((r, r, d.mass));
        s.mass.push((phi, phi, d.transverse_inertia));
        s.gyroscopic.push((phi, phi, d.polar_inertia));
    }
    s
}

/// A real coefficient `a` between translations `r` and `link` (ground if `None`).
fn spring(target: &mut Triplets, r: usize, link: Option<usize>, a: f64) {
    target.push((r, r, a));
    if let Some(l) = link {
        target.push((l, l, a));
        target.push((r, l, -a));
        target.push((l, r, -a));
    }
}

impl RotorSystem {
    /// Assembles (and reduces, if asked) a validated rotor.
    pub fn assemble(rotor: &Rotor) -> Result<Self, LinalgError> {
        match rotor {
            Rotor::Jeffcott(j) => Ok(Self::jeffcott(j)),
            Rotor::Beam(b) => beam(b),
            Rotor::Matrices(m) => Ok(matrices(m)),
            Rotor::Train(t) => Ok(super::train::assemble(t)),
        }
    }
}

/// Assembles (and reduces, if asked) a beam rotor.
pub fn beam(rotor: &BeamRotor) -> Result<RotorSystem, LinalgError> {
    let mut s = structure_parts(rotor);
    let at = |node: usize| translation_dof(rotor, node);
    for p in rotor.point_masses() {
        let r = at(p.node);
        s.mass.push((r, r, p.mass));
        s.stiffness_nonrotating.push((r, r, p.stiffness));
        s.damping_nonrotating.push((r, r, p.damping));
    }
    for sup in rotor.supports() {
        let (r, l) = (at(sup.node), sup.link.map(at));
        spring(&mut s.stiffness_nonrotating, r, l, sup.stiffness);
        spring(&mut s.damping_nonrotating, r, l, sup.damping);
        spring(
            &mut s.hysteretic_nonrotating,
            r,
            l,
            sup.loss_factor * sup.stiffness,
        );
    }
    let s = s.finish(rotor, rotor.assembled_dofs());
    let mut s = match rotor.guyan() {
        None => s,
        Some(GuyanKeep::Translations) => {
            let keep: Vec<bool> = s
                .dofs
                .iter()
                .map(|d| d.kind == DofKind::Translation)
                .collect();
            guyan::reduce(&s, &keep)?
        }
    };
    // General supports act on translations, which Guyan reduction keeps: place them after it.
    s.supports = rotor
        .general_supports()
        .iter()
        .map(|g| {
            let t = |node| {
                s.translation(node)
                    .expect("validated: every node has a translation")
            };
            PlacedSupport {
                at: match g.link {
                    None => Placement::Dof(t(g.node)),
                    Some(l) => Placement::Between(t(g.node), t(l)),
                },
                support: g.clone(),
            }
        })
        .collect();
    Ok(s)
}

/// A rotor given as matrices: the stiffness counts as nonrotating (only damping and loss
/// distinguish rotating parts); degree of freedom `i` is reported as node `i`.
pub fn matrices(m: &MatrixRotor) -> RotorSystem {
    let n = m.mass.nrows();
    let s = Sparse::from_dense;
    RotorSystem {
        mass: s(&m.mass),
        gyroscopic: s(&m.gyroscopic),
        stiffness_rotating: Sparse::zeros(n, n),
        stiffness_nonrotating: s(&m.stiffness),
        damping_rotating: s(&m.damping_rotating),
        damping_nonrotating: s(&m.damping_nonrotating),
        hysteretic_rotating: s(&m.hysteretic_rotating),
        hysteretic_nonrotating: s(&m.hysteretic_nonrotating),
        circulatory: Sparse::zeros(n, n),
        dofs: (0..n)
            .map(|i| Dof {
                node: i,
                kind: DofKind::Translation,
            })
            .collect(),
        supports: m
            .general_supports
            .iter()
            .map(PlacedSupport::on_nodes)
            .collect(),
    }
}

fn add(target: &mut Triplets, at: usize, e: &Mat4, factor: f64) {
    if factor == 0.0 {
        return;
    }
    for (i, row) in e.iter().enumerate() {
        for (j, v) in row.iter().enumerate() {
            target.push((at + i, at + j, factor * v));
        }
    }
}
