//! Point masses (bearing housings, pedestals) and the nodes off the shaft they make.
//!
//! A point mass sits on the translation of a shaft node or of a node off the shaft. Nodes off
//! the shaft are numbered on from the shaft's last node, consecutively, as ROSS numbers them
//! (`rotor_assembly.py`: a point mass beyond the shaft has x, y and z only); each has a
//! translation and no rotation, and is held only by its point mass's own stiffness and by the
//! supports that name it (`node` or `n_link`).

use super::api::PointMassInput;
use super::error::{Invalid, non_negative};

/// A validated point mass.
#[derive(Debug, Clone, PartialEq)]
pub struct PointMass {
    /// Its position in the request's `point_masses`.
    pub index: usize,
    pub node: usize,
    /// kg.
    pub mass: f64,
    /// Isotropic stiffness to ground, N/m.
    pub stiffness: f64,
    /// Isotropic viscous damping to ground, N s/m.
    pub damping: f64,
}

/// The number of nodes off the shaft the point masses name (shaft nodes `0..shaft_nodes`), or
/// `None` with the error recorded when they are not numbered on from the shaft without gaps.
pub fn nodes_off_shaft(
    inputs: &[PointMassInput],
    shaft_nodes: usize,
    bad: &mut Invalid,
) -> Option<usize> {
    let mut off: Vec<i64> = inputs
        .iter()
        .map(|p| p.node)
        .filter(|&n| n >= shaft_nodes as i64)
        .collect();
    off.sort_unstable();
    off.dedup();
    for (k, &n) in off.iter().enumerate() {
        let want = shaft_nodes as i64 + k as i64;
        if n != want {
            let i = inputs.iter().position(|p| p.node == n).unwrap_or(0);
            bad.push(
                format!("rotor.point_masses[{i}].node"),
                format!(
                    "node {n} is off the shaft (nodes 0 to {}) and leaves a gap: nodes off the \
                     shaft are numbered on from {shaft_nodes} without gaps (next: {want})",
                    shaft_nodes - 1
                ),
            );
            return None;
        }
    }
    Some(off.len())
}

/// Validates the point masses; `node_ok` checks a node (shaft or off it) and records its error.
pub fn parse_point_masses(
    inputs: &[PointMassInput],
    shaft_nodes: usize,
    bad: &mut Invalid,
    mut node_ok: impl FnMut(&mut Invalid, String, i64) -> Option<usize>,
) -> Vec<PointMass> {
    let mut out = vec![];
    for (i, p) in inputs.iter().enumerate() {
        let at = format!("rotor.point_masses[{i}]");
        let node = node_ok(bad, format!("{at}.node"), p.node);
        let mass = bad.check(&format!("{at}.mass"), non_negative(p.mass));
        let k = bad.check(
            &format!("{at}.stiffness"),
            non_negative(p.stiffness.unwrap_or(0.0)),
        );
        let c = bad.check(
            &format!("{at}.damping"),
            non_negative(p.damping.unwrap_or(0.0)),
        );
        if let (Some(node), Some(mass), Some(stiffness), Some(damping)) = (node, mass, k, c) {
            out.push(PointMass {
                index: i,
                node,
                mass,
                stiffness,
                damping,
            });
        }
    }
    // A node off the shaft has no mass but its point masses': without one it has none.
    let mut off: Vec<usize> = out
        .iter()
        .filter(|p| p.node >= shaft_nodes)
        .map(|p| p.node)
        .collect();
    off.sort_unstable();
    off.dedup();
    for n in off {
        if out.iter().filter(|p| p.node == n).all(|p| p.mass == 0.0) {
            let i = out.iter().find(|p| p.node == n).map_or(0, |p| p.index);
            bad.push(
                format!("rotor.point_masses[{i}].mass"),
                format!(
                    "must be > 0 on node {n}, off the shaft: nothing else gives that node mass"
                ),
            );
        }
    }
    out
}
