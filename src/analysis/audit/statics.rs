//! Static deflection under gravity, support reactions, shear and bending moment (ROSS's
//! `run_static`).
//!
//! The full beam (no Guyan reduction), gravity `g` along -y. In complex coordinates
//! `q = x + i y` (rotations `phi_y - i phi_x`) the real symmetric shaft matrices act alike on
//! the x plane (`Re q`) and the y plane (`Im q`), so the statics is solved in real coordinates
//! `u = [u_x; u_y]`, each plane with the same `K` (shaft) and `M` (shaft and disks):
//!
//! ```text
//! (K_shaft + K_sup) u = [0; W],    W = -g M e_t
//! ```
//!
//! with `e_t` = 1 on every translation: the consistent load, with its moment terms (as ROSS).
//! - `Held::Rigid`: pinned supports, the support nodes' translations removed from `u`
//!   (rotations free); reactions `(K_shaft u - W)` there, shared equally by supports on one
//!   node. The x plane carries no load: `u_x = 0`.
//! - `Held::Elastic { speed }`: each support's `K = [[kxx, kxy], [kyx, kyy]]` at `speed` on its
//!   node's `(x, y)` translations (force on the shaft `-K [x, y]`); reactions `-K [x, y]`.
//!   Support mass is ignored (static). Without cross-coupling the planes separate.
//!
//! A `K` that cannot hold the shaft (one pinned node; supports that leave a rigid motion of
//! the shaft free) is an error, never a NaN: a rigid motion `R a` (translation and tilt of
//! either plane) is held iff the 4 x 4 `R^T K_sup R` is regular, which for supports whose
//! symmetric part is positive semidefinite is exactly `K` regular.
//!
//! `max_moment` is exact: inside an element the moment is quadratic, so its extreme is at an end
//! or where the shear changes sign (Example 1's 18.6 N m = w L^2 / 8 at mid-span, between the
//! nodes); `diagram` samples the exact curves, the deflection with them (exact between the
//! nodes too, [`deflection`](super::deflection)), and `max_deflection` is the largest
//! displacement along the shaft, wherever it is.
//!
//! Stations: shear and moment at both ends of every element, from the equilibrium of the part
//! left of the section (node forces: reactions and disk weights; each element's own weight
//! `g rho A l`, uniform, at its centre). ROSS's signs: shear = minus the upward forces to the
//! left, moment `M(z) = -(sum F_i (z - z_i))`, negative sagging. ROSS's recursion (trapezoid
//! rule on a shear linear in each element, last element closed by equilibrium) is exact for
//! uniform elements, so these values are ROSS's up to round-off (tests/it/audit_ross.rs: 1e-12
//! relative on its two rotors); the moment at the right end is 0 up to the round-off of the
//! reactions, where ROSS sets it to 0.

use super::deflection::{self, Span};
use crate::analysis::AnalysisError;
use crate::fem::assembly;
use crate::linalg::sparse::{Cholesky, DENSE_UP_TO, Lu};
use crate::linalg::{self, LinalgError, RMat, Sparse, c64};
use crate::model::rotor::{BeamRotor, Element};
use crate::model::supports::Matrix2;

/// How the shaft is held.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Held {
    /// By the supports' own stiffness at the given speed.
    Elastic { speed: f64 },
    /// Pinned at the support nodes.
    Rigid,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Reaction {
    /// Index of the support in the request's `rotor.supports`.
    pub support: usize,
    pub node: usize,
    /// Upward force on the shaft, N.
    pub y: f64,
    pub x: f64,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Deflection {
    pub node: usize,
    pub position: f64,
    pub y: f64,
    pub x: f64,
    /// `dy/dz`, `dx/dz` of the section (the bending rotations), rad.
    pub slope_y: f64,
    pub slope_x: f64,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Station {
    pub element: usize,
    pub position: f64,
    /// ROSS's sign: minus the upward forces left of the section, N.
    pub shear: f64,
    /// ROSS's sign: negative sagging, N m.
    pub bending_moment: f64,
    /// The displacement there, m ([`deflection`](super::deflection): exact inside elements).
    pub y: f64,
    pub x: f64,
}

#[derive(Debug, Clone, PartialEq)]
pub struct StaticResult {
    pub reactions: Vec<Reaction>,
    pub nodes: Vec<Deflection>,
    /// Both ends of every element, left to right.
    pub stations: Vec<Station>,
    /// The exact diagrams sampled: [`DIAGRAM_POINTS`] points along every element, ends included.
    pub diagram: Vec<Station>,
    /// The largest |bending moment| along the shaft (inside an element where its shear
    /// vanishes), ROSS's sign.
    pub max_moment: Station,
    /// The largest |shear| (at an element's end: it is linear in each).
    pub max_shear: Station,
    /// The largest displacement `|(x, y)|` along the shaft, between nodes where it is there.
    pub max_deflection: Station,
    /// Weight of shaft and disks, N.
    pub weight: f64,
}

/// Points per element of [`StaticResult::diagram`], ends included (the request's cost counts
/// them too).
pub use crate::model::limits::DIAGRAM_POINTS;

/// The error for a shaft its supports cannot hold: the solve would be singular.
const UNHELD: AnalysisError = AnalysisError::Linalg(LinalgError::NonFinite);

/// The rotor under gravity `gravity` along -y.
pub fn static_deflection(
    rotor: &BeamRotor,
    gravity: f64,
    held: Held,
) -> Result<StaticResult, AnalysisError> {
    let sys = assembly::beam_shaft(rotor);
    let (k, n) = (&sys.stiffness_rotating, sys.n());
    // W = -g M e_t, e_t = 1 on every translation.
    let translations: Vec<f64> = (0..n).map(|i| ((i + 1) % 2) as f64).collect();
    let w: Vec<f64> = sys
        .mass
        .mul_vec(&translations)
        .iter()
        .map(|v| -gravity * v)
        .collect();
    // Every support with its request index, node and stiffness at the speed asked.
    let speed = match held {
        Held::Elastic { speed } => speed,
        Held::Rigid => 0.0,
    };
    // Seals carry no load (API 684, ROSS): left out.
    let supports: Vec<(usize, usize, Matrix2)> = rotor
        .supports()
        .iter()
        .filter(|s| !s.seal && s.node < rotor.shaft_nodes())
        .map(|s| {
            let k = Matrix2 {
                xx: s.stiffness,
                yy: s.stiffness,
                ..Matrix2::default()
            };
            (s.index, s.node, k)
        })
        .chain(
            rotor
                .general_supports()
                .iter()
                .filter(|g| !g.seal && g.node < rotor.shaft_nodes())
                // A static load does not whirl: a table over whirl frequency is read at 0.
                .map(|g| (g.index, g.node, g.at_whirl(speed, 0.0).k)),
        )
        .collect();
    let (ux, uy, reactions) = match held {
        Held::Rigid => rigid(k, &w, &supports)?,
        Held::Elastic { .. } => elastic(rotor, k, &w, &supports)?,
    };
    let mut reactions: Vec<Reaction> = reactions;
    reactions.sort_by_key(|r| r.support);

    let z = positions(rotor);
    let nodes = (0..rotor.shaft_nodes())
        .map(|i| Deflection {
            node: i,
            position: z[i],
            y: uy[2 * i],
            x: ux[2 * i],
            slope_y: uy[2 * i + 1],
            slope_x: ux[2 * i + 1],
        })
        .collect();
    // Upward node forces (reactions, disk weights) and element weights (down).
    let mut force = vec![0.0; rotor.shaft_nodes()];
    for r in &reactions {
        force[r.node] += r.y;
    }
    for d in rotor.disks() {
        force[d.node] -= gravity * d.mass;
    }
    let mut element_weight: Vec<f64> = rotor.element_masses().iter().map(|m| gravity * m).collect();
    let weight = element_weight.iter().sum::<f64>()
        + gravity * rotor.disks().iter().map(|d| d.mass).sum::<f64>();
    // A coupling's halves weigh on its nodes; it carries no distributed weight.
    for (e, el) in rotor.elements().iter().enumerate() {
        if let Element::Coupling(c) = el {
            force[e] -= gravity * c.mass[0];
            force[e + 1] -= gravity * c.mass[1];
            element_weight[e] = 0.0;
        }
    }
    // Inside a conical element, or one with a sleeve, the curve is that of the mid section
    // under the element's whole weight: exact at the nodes, not between them. Across a
    // coupling (no section) the displacement is drawn straight between its nodes.
    let sections: Vec<_> = rotor
        .elements()
        .iter()
        .map(|e| e.beam().map(assembly::section))
        .collect();
    // Each element's deflection curve in each plane: its weight loads the y plane only.
    let curve = |e: usize, t: f64| {
        let ends = |u: &[f64]| [u[2 * e], u[2 * e + 1], u[2 * e + 2], u[2 * e + 3]];
        let Some(s) = &sections[e] else {
            let f = (t - z[e]) / (z[e + 1] - z[e]);
            let line = |u: &[f64]| u[2 * e] + f * (u[2 * e + 2] - u[2 * e]);
            return (line(&uy), line(&ux));
        };
        let (y, x) = (
            Span::new(s, -element_weight[e] / s.length.max(f64::MIN_POSITIVE)),
            Span::new(s, 0.0),
        );
        let d = t - z[e];
        (y.deflection(ends(&uy), d), x.deflection(ends(&ux), d))
    };
    // Left of a section: the upward resultant `up` and its first moment `up_z` about z = 0,
    // so that the moment of the left part about the section at z is `up z - up_z`. Inside
    // element e (from z_e, weight q = w_e / l_e per length) the part of the element left of
    // the section adds `-q (z - z_e)` to the resultant and `-q (z - z_e)^2 / 2` to the moment:
    // the shear is linear and the moment quadratic, extreme where the shear vanishes.
    let (mut up, mut up_z) = (0.0, 0.0);
    let mut stations = Vec::with_capacity(2 * rotor.elements().len());
    let mut diagram = Vec::with_capacity(DIAGRAM_POINTS * rotor.elements().len());
    let mut max_moment: Option<Station> = None;
    let mut max_deflection: Option<Station> = None;
    for (e, &we) in element_weight.iter().enumerate() {
        up += force[e];
        up_z += force[e] * z[e];
        let (z0, l) = (z[e], z[e + 1] - z[e]);
        let q = if l > 0.0 { we / l } else { 0.0 };
        let at = |t: f64| {
            let d = t - z0;
            let (y, x) = curve(e, t);
            Station {
                element: e,
                position: t,
                shear: -(up - q * d),
                bending_moment: -(up * t - up_z - 0.5 * q * d * d),
                y,
                x,
            }
        };
        stations.push(at(z0));
        for k in 0..DIAGRAM_POINTS {
            diagram.push(at(z0 + l * k as f64 / (DIAGRAM_POINTS - 1) as f64));
        }
        let mut candidates = vec![at(z0), at(z[e + 1])];
        if q > 0.0 && up > 0.0 && up / q < l {
            candidates.push(at(z0 + up / q));
        }
        for c in candidates {
            if max_moment
                .as_ref()
                .is_none_or(|m| c.bending_moment.abs() > m.bending_moment.abs())
            {
                max_moment = Some(c);
            }
        }
        // The largest displacement: the best of the element's samples, then refined between
        // its neighbours (the curve is a quartic in each element).
        let size = |t: f64| {
            let (y, x) = curve(e, t);
            y.hypot(x)
        };
        let samples = &diagram[diagram.len() - DIAGRAM_POINTS..];
        let best = (0..DIAGRAM_POINTS)
            .max_by(|&a, &b| size(samples[a].position).total_cmp(&size(samples[b].position)))
            .expect("samples");
        let lo = samples[best.saturating_sub(1)].position;
        let hi = samples[(best + 1).min(DIAGRAM_POINTS - 1)].position;
        let c = at(deflection::refine_max(size, lo, hi));
        if max_deflection
            .as_ref()
            .is_none_or(|m: &Station| c.y.hypot(c.x) > m.y.hypot(m.x))
        {
            max_deflection = Some(c);
        }
        up -= we;
        up_z -= we * 0.5 * (z[e] + z[e + 1]);
        let (y, x) = curve(e, z[e + 1]);
        stations.push(Station {
            element: e,
            position: z[e + 1],
            shear: -up,
            bending_moment: -(up * z[e + 1] - up_z),
            y,
            x,
        });
    }
    let max_shear = stations
        .iter()
        .max_by(|a, b| a.shear.abs().total_cmp(&b.shear.abs()))
        .cloned()
        .expect("a shaft has elements");
    Ok(StaticResult {
        reactions,
        nodes,
        stations,
        diagram,
        max_moment: max_moment.expect("a shaft has elements"),
        max_shear,
        max_deflection: max_deflection.expect("a shaft has elements"),
        weight,
    })
}

/// Node positions along the shaft, from 0.
fn positions(rotor: &BeamRotor) -> Vec<f64> {
    let mut z = vec![0.0];
    for e in rotor.elements() {
        z.push(z.last().unwrap() + e.length());
    }
    z
}

type Solution = (Vec<f64>, Vec<f64>, Vec<Reaction>);

/// Pinned at the support nodes: the y plane without their translations.
fn rigid(
    k: &Sparse,
    w: &[f64],
    supports: &[(usize, usize, Matrix2)],
) -> Result<Solution, AnalysisError> {
    let n = w.len();
    let mut pinned: Vec<usize> = supports.iter().map(|s| 2 * s.1).collect();
    pinned.sort_unstable();
    pinned.dedup();
    // A connected beam pinned at two distinct points has no rigid motion left.
    if pinned.len() < 2 {
        return Err(UNHELD);
    }
    let free: Vec<usize> = (0..n)
        .filter(|i| pinned.binary_search(i).is_err())
        .collect();
    let mut index = vec![None; n];
    for (i, &d) in free.iter().enumerate() {
        index[d] = Some(i);
    }
    let kff: Vec<(usize, usize, f64)> = k
        .entries()
        .filter_map(|(i, j, v)| Some((index[i]?, index[j]?, v)))
        .collect();
    let wf: Vec<f64> = free.iter().map(|&d| w[d]).collect();
    let uf = solve(free.len(), &kff, &wf)?;
    let mut uy = vec![0.0; n];
    for (i, &d) in free.iter().enumerate() {
        uy[d] = uf[i];
    }
    let ku = k.mul_vec(&uy);
    let reactions = supports
        .iter()
        .map(|&(support, node, _)| {
            let d = 2 * node;
            let r = ku[d] - w[d];
            // Supports on one node are equal penalties in ROSS: they share its reaction.
            let sharing = supports.iter().filter(|s| s.1 == node).count() as f64;
            Reaction {
                support,
                node,
                y: r / sharing,
                x: 0.0,
            }
        })
        .collect();
    Ok((vec![0.0; n], uy, reactions))
}

/// Held by the supports' stiffness: both planes, coupled by `kxy`, `kyx`.
fn elastic(
    rotor: &BeamRotor,
    k: &Sparse,
    w: &[f64],
    supports: &[(usize, usize, Matrix2)],
) -> Result<Solution, AnalysisError> {
    if !holds(rotor, supports) {
        return Err(UNHELD);
    }
    let n = w.len();
    let coupled = supports.iter().any(|s| s.2.xy != 0.0 || s.2.yx != 0.0);
    let (ux, uy): (Vec<f64>, Vec<f64>) = if coupled {
        let mut a: Vec<(usize, usize, f64)> = k.entries().collect();
        a.extend(k.entries().map(|(i, j, v)| (n + i, n + j, v)));
        for &(_, node, s) in supports {
            let (x, y) = (2 * node, n + 2 * node);
            a.extend([(x, x, s.xx), (x, y, s.xy), (y, x, s.yx), (y, y, s.yy)]);
        }
        let b: Vec<f64> = (0..2 * n)
            .map(|i| if i < n { 0.0 } else { w[i - n] })
            .collect();
        let u = solve(2 * n, &a, &b)?;
        (u[..n].to_vec(), u[n..].to_vec())
    } else {
        // The planes separate and the x plane has no load.
        let mut a: Vec<(usize, usize, f64)> = k.entries().collect();
        for &(_, node, s) in supports {
            a.push((2 * node, 2 * node, s.yy));
        }
        (vec![0.0; n], solve(n, &a, w)?)
    };
    let reactions = supports
        .iter()
        .map(|&(support, node, s)| {
            let (x, y) = (ux[2 * node], uy[2 * node]);
            Reaction {
                support,
                node,
                y: -(s.yx * x + s.yy * y),
                x: -(s.xx * x + s.xy * y),
            }
        })
        .collect();
    Ok((ux, uy, reactions))
}

/// `A u = b`, `A` of order `n` from `entries` (repeated positions summed): dense up to
/// [`DENSE_UP_TO`], else by sparse Cholesky where `A` is symmetric and positive definite (a
/// shaft held by pins or by springs that are), else by sparse LU. A beam couples neighbouring
/// nodes only, so the work and memory are linear in the mesh (a 10,000-element shaft's
/// statics was a dense 40,000-unknown solve).
fn solve(n: usize, entries: &[(usize, usize, f64)], b: &[f64]) -> Result<Vec<f64>, AnalysisError> {
    let a = Sparse::from_triplets(n, n, entries);
    let column = |b: &[f64]| RMat::from_fn(n, 1, |i, _| b[i]);
    if n <= DENSE_UP_TO {
        let u = linalg::solve_real_matrix(&a.to_dense(), &column(b))?;
        return Ok((0..n).map(|i| u[(i, 0)]).collect());
    }
    let symmetric = a.entries().all(|(i, j, v)| a.get(j, i) == v);
    if symmetric && let Ok(llt) = Cholesky::new(&a) {
        return finite(llt.solve_vec(b));
    }
    let complex: Vec<(usize, usize, c64)> = a
        .entries()
        .map(|(i, j, v)| (i, j, c64::new(v, 0.0)))
        .collect();
    let lu = Lu::new(n, &complex)?;
    let mut u: Vec<c64> = b.iter().map(|&v| c64::new(v, 0.0)).collect();
    lu.solve_in_place(&mut u);
    finite(u.iter().map(|z| z.re).collect())
}

/// `u`, or the error of a shaft its supports cannot hold where a singular factor left it
/// non-finite.
fn finite(u: Vec<f64>) -> Result<Vec<f64>, AnalysisError> {
    match u.iter().all(|v| v.is_finite()) {
        true => Ok(u),
        false => Err(UNHELD),
    }
}

/// Whether the supports hold every rigid motion of the shaft: `S = R^T K_sup R` regular, with
/// `R` = translation and tilt `(z - z_mid) / L` of each plane (see the module docs).
fn holds(rotor: &BeamRotor, supports: &[(usize, usize, Matrix2)]) -> bool {
    let z = positions(rotor);
    let length = *z.last().unwrap();
    let mid = 0.5 * length;
    let mut s = [[0.0f64; 4]; 4];
    for &(_, node, k) in supports {
        let t = (z[node] - mid) / length;
        // Mode a = (plane, shape): 0, 1 the x plane, 2, 3 the y plane; shapes 1 and t.
        let shape = [1.0, t, 1.0, t];
        let plane = |a: usize| a / 2;
        let kk = [[k.xx, k.xy], [k.yx, k.yy]];
        for a in 0..4 {
            for b in 0..4 {
                s[a][b] += shape[a] * kk[plane(a)][plane(b)] * shape[b];
            }
        }
    }
    regular(s)
}

/// Gaussian elimination with full pivoting: every pivot above 1e-12 of the largest entry.
fn regular(mut s: [[f64; 4]; 4]) -> bool {
    let scale = s.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    if !(scale > 0.0 && scale.is_finite()) {
        return false;
    }
    let mut rows: Vec<usize> = (0..4).collect();
    let mut cols: Vec<usize> = (0..4).collect();
    for step in 0..4 {
        let (mut pi, mut pj, mut best) = (step, step, 0.0);
        for i in step..4 {
            for j in step..4 {
                let v = s[rows[i]][cols[j]].abs();
                if v > best {
                    (pi, pj, best) = (i, j, v);
                }
            }
        }
        if best <= 1e-12 * scale {
            return false;
        }
        rows.swap(step, pi);
        cols.swap(step, pj);
        let p = s[rows[step]][cols[step]];
        for i in step + 1..4 {
            let f = s[rows[i]][cols[step]] / p;
            for j in step..4 {
                s[rows[i]][cols[j]] -= f * s[rows[step]][cols[j]];
            }
        }
    }
    true
}
