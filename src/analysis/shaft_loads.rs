//! The loads a train's elements carry: each element's torque (torsion, N m) or axial force (N),
//! `t_e . x` with `t_e` its stiffness on the twist or stretch of its right end over its left
//! (`fem::train::element_loads`; a mesh on `theta_1 - theta_2 / ratio`), from a response's
//! motion of every node; and the stress it puts on the element's section.

use crate::fem::train::{element_loads, stress_per_load};
use crate::linalg::c64;
use crate::model::train::TrainRotor;

/// One element's load over time.
#[derive(Debug, Clone)]
pub struct ElementHistory {
    pub element: usize,
    pub nodes: [usize; 2],
    /// At each output time.
    pub load: Vec<f64>,
    /// Stress per unit load at its more stressed end, concentration included (Pa per N m or
    /// per N); `None` for a coupling or mesh.
    pub stress: Option<f64>,
}

/// One element's load per unit input at each frequency of a harmonic response.
#[derive(Debug, Clone)]
pub struct ElementResponse {
    pub element: usize,
    pub nodes: [usize; 2],
    /// Complex amplitude at each frequency.
    pub load: Vec<c64>,
    pub stress: Option<f64>,
}

/// Each element's `(nodes, row weights, stress per load)`.
fn rows(t: &TrainRotor) -> impl Iterator<Item = (usize, [(usize, f64); 2], Option<f64>)> {
    let stress = stress_per_load(t);
    element_loads(t)
        .into_iter()
        .zip(stress)
        .enumerate()
        .map(|(e, (row, s))| (e, row, s))
}

/// The element loads of a time response whose `nodes` hold every node's history (the real
/// part is the motion).
pub fn histories(t: &TrainRotor, nodes: &[(usize, Vec<c64>)]) -> Vec<ElementHistory> {
    let x = |node: usize| -> &[c64] {
        &nodes
            .iter()
            .find(|(n, _)| *n == node)
            .expect("every node solved")
            .1
    };
    rows(t)
        .map(|(element, [(a, wa), (b, wb)], stress)| ElementHistory {
            element,
            nodes: [a, b],
            load: x(a)
                .iter()
                .zip(x(b))
                .map(|(p, q)| wa * p.re + wb * q.re)
                .collect(),
            stress,
        })
        .collect()
}

/// The element loads of a harmonic response: `x[f][node]` the complex amplitude of every node
/// at frequency `f`.
pub fn responses(t: &TrainRotor, x: &[Vec<c64>]) -> Vec<ElementResponse> {
    rows(t)
        .map(|(element, [(a, wa), (b, wb)], stress)| ElementResponse {
            element,
            nodes: [a, b],
            load: x.iter().map(|q| q[a] * wa + q[b] * wb).collect(),
            stress,
        })
        .collect()
}
