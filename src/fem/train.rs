//! A train's torsional or axial system: one real coordinate per shaft node (its twist
//! `theta`, rad, or its axial displacement `w`, m), written in the complex coordinates of
//! [`RotorSystem`] (a real motion is a complex coordinate whose poles come in conjugate pairs).
//!
//! Shaft element of length `l` (ROSS's 6-dof element, torsional and axial parts), with `J` the
//! mean of its ends' polar second moments and `A` the mean of their areas:
//!
//! ```text
//! torsion:  K = G J / l [[1, -1], [-1, 1]],   M = rho J l / 6 [[2, 1], [1, 2]]
//! axial:    K = E A / l [[1, -1], [-1, 1]],   M = rho A l / 6 [[2, 1], [1, 2]]
//! ```
//!
//! A disk adds its polar inertia (torsion) or mass (axial) on its node, a coupling a spring and
//! damper between its nodes and its halves' inertias or masses, a thrust bearing (`kzz`, `czz`)
//! its coefficients on its node. A gear mesh joins the driving gear's twist `theta_1` to the
//! driven gear's `theta_2` (each shaft in its own angles, turning `ratio` times as fast): its
//! spring acts on `theta_1 - theta_2 / ratio`, so its matrix is `k [[1, -1/n], [-1/n, 1/n^2]]`.
//!
//! In torsion and axially the rotating and fixed frames see the same vibration frequency, so
//! every part's damping and loss go in the nonrotating matrices: a material loss acts with
//! `sgn(omega)`, with no circulatory term and no dependence on speed; there are no gyroscopic
//! moments.

use crate::linalg::Sparse;
use crate::model::api::Motion;
use crate::model::rotor::{Element, ShaftElement, TrainRotor};
use crate::system::{Dof, DofKind, PlacedSupport, RotorSystem};

type Triplets = Vec<(usize, usize, f64)>;

/// An element's stiffness and mass per unit of `[[1, -1], [-1, 1]]` and `[[2, 1], [1, 2]] / 6`.
pub fn element_constants(e: &ShaftElement, motion: Motion) -> (f64, f64) {
    let l = e.length;
    match motion {
        Motion::Axial => {
            let a = e.mean_area();
            (e.young_modulus * a / l, e.density * a * l)
        }
        _ => {
            let j = e.mean_polar_moment();
            (e.shear_modulus() * j / l, e.density * j * l)
        }
    }
}

/// The torsional or axial system of a train.
pub fn assemble(t: &TrainRotor) -> RotorSystem {
    let n = t.nodes();
    let axial = t.motion == Motion::Axial;
    let (mut k, mut m, mut c, mut h) = (vec![], vec![], vec![], vec![]);
    let element = |k: &mut Triplets,
                   m: &mut Triplets,
                   c: &mut Triplets,
                   h: &mut Triplets,
                   at: usize,
                   e: &ShaftElement| {
        let (ke, me) = element_constants(e, t.motion);
        pair(k, at, [1.0, -1.0], ke);
        pair(h, at, [1.0, -1.0], e.loss_factor * ke);
        m.extend([
            (at, at, me / 3.0),
            (at + 1, at + 1, me / 3.0),
            (at, at + 1, me / 6.0),
            (at + 1, at, me / 6.0),
        ]);
        if let Some(r) = e.rayleigh {
            pair(c, at, [1.0, -1.0], r.beta * ke);
            c.extend([
                (at, at, r.alpha * me / 3.0),
                (at + 1, at + 1, r.alpha * me / 3.0),
                (at, at + 1, r.alpha * me / 6.0),
                (at + 1, at, r.alpha * me / 6.0),
            ]);
        }
    };
    for (i, el) in t.beam.elements().iter().enumerate() {
        match el {
            Element::Beam(b) => element(&mut k, &mut m, &mut c, &mut h, i, b),
            Element::Coupling(cp) => {
                let (kk, cc) = if axial {
                    (cp.axial_stiffness, cp.axial_damping)
                } else {
                    (cp.torsional_stiffness, cp.torsional_damping)
                };
                pair(&mut k, i, [1.0, -1.0], kk);
                pair(&mut h, i, [1.0, -1.0], cp.loss_factor * kk);
                pair(&mut c, i, [1.0, -1.0], cc);
                let halves = if axial { cp.mass } else { cp.polar_inertia };
                m.push((i, i, halves[0]));
                m.push((i + 1, i + 1, halves[1]));
            }
            Element::Gear(g) => {
                if axial {
                    pair(&mut k, i, [1.0, -1.0], g.axial_stiffness);
                } else {
                    let w = [1.0, -1.0 / g.ratio];
                    pair(&mut k, i, w, g.mesh_stiffness);
                    pair(&mut c, i, w, g.mesh_damping);
                }
            }
        }
    }
    for s in t.beam.sleeves() {
        element(&mut k, &mut m, &mut c, &mut h, s.over, &s.element);
    }
    for d in t.beam.disks() {
        let v = if axial { d.mass } else { d.polar_inertia };
        m.push((d.node, d.node, v));
    }
    let kind = if axial {
        DofKind::Axial
    } else {
        DofKind::Twist
    };
    let z = |t: Triplets| Sparse::from_triplets(n, n, &t);
    RotorSystem {
        mass: z(m),
        gyroscopic: Sparse::zeros(n, n),
        stiffness_rotating: Sparse::zeros(n, n),
        stiffness_nonrotating: z(k),
        damping_rotating: Sparse::zeros(n, n),
        damping_nonrotating: z(c),
        hysteretic_rotating: Sparse::zeros(n, n),
        hysteretic_nonrotating: z(h),
        circulatory: Sparse::zeros(n, n),
        dofs: (0..n).map(|node| Dof { node, kind }).collect(),
        supports: t
            .axial_supports
            .iter()
            .map(PlacedSupport::on_nodes)
            .collect(),
    }
}

/// `a w w^T` on coordinates `at`, `at + 1`.
fn pair(target: &mut Triplets, at: usize, w: [f64; 2], a: f64) {
    if a == 0.0 {
        return;
    }
    for (i, wi) in w.iter().enumerate() {
        for (j, wj) in w.iter().enumerate() {
            target.push((at + i, at + j, a * wi * wj));
        }
    }
}

/// Each element's torque (torsion, N m) or axial force (N) per unit of the coordinates: the
/// row `t_e` with `T_e = t_e . q`, tension or twist of the right end over the left one
/// positive. `None` for an element that carries none (a coupling or mesh without stiffness
/// along the motion).
pub fn element_loads(t: &TrainRotor) -> Vec<[(usize, f64); 2]> {
    let axial = t.motion == Motion::Axial;
    t.beam
        .elements()
        .iter()
        .enumerate()
        .map(|(i, el)| {
            let (k, w) = match el {
                Element::Beam(b) => {
                    let mut k = element_constants(b, t.motion).0;
                    for s in t.beam.sleeves().iter().filter(|s| s.over == i) {
                        k += element_constants(&s.element, t.motion).0;
                    }
                    (k, [-1.0, 1.0])
                }
                Element::Coupling(c) if axial => (c.axial_stiffness, [-1.0, 1.0]),
                Element::Coupling(c) => (c.torsional_stiffness, [-1.0, 1.0]),
                Element::Gear(g) if axial => (g.axial_stiffness, [-1.0, 1.0]),
                Element::Gear(g) => (g.mesh_stiffness, [-1.0, 1.0 / g.ratio]),
            };
            [(i, k * w[0]), (i + 1, k * w[1])]
        })
        .collect()
}

/// Each element's stress per unit load at its more stressed end, its stress concentration
/// included: torsion `T (D / 2) / J` with `J = pi (D^4 - d^4) / 32` (Pa per N m), axially
/// `F / A` (Pa per N). `None` for a coupling or mesh, whose section is not a shaft's.
pub fn stress_per_load(t: &TrainRotor) -> Vec<Option<f64>> {
    let axial = t.motion == Motion::Axial;
    t.beam
        .elements()
        .iter()
        .enumerate()
        .map(|(i, el)| {
            let b = el.beam()?;
            let end = |o: f64, d: f64| {
                if axial {
                    4.0 / (std::f64::consts::PI * (o * o - d * d))
                } else {
                    16.0 * o / (std::f64::consts::PI * (o.powi(4) - d.powi(4)))
                }
            };
            let worst = end(b.outer_diameter, b.inner_diameter)
                .max(end(b.outer_diameter_right, b.inner_diameter_right));
            let scf = t.stress_concentration.get(i).copied().unwrap_or(1.0);
            Some(scf * worst)
        })
        .collect()
}
