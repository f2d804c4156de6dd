//! The report's unbalance cases: one per forward critical speed in the sweep, its unbalances
//! placed by API 684's rules ([`placement`](super::placement)) on the mode's shape at that
//! speed, and its response read against API 617's vibration limit and the clearances.

use super::frequency::Orbit;
use super::placement::{self, CLEARANCE_FRACTION, Journal, Placed, Profile};
use super::statics::StaticResult;
use crate::analysis::AnalysisError;
use crate::analysis::criticals::Critical;
use crate::analysis::poles::{PoleSet, Whirl};
use crate::linalg::c64;
use crate::model::rotor::BeamRotor;
use crate::system::{DofKind, RotorSystem};

/// One case: the mode it excites and its unbalances.
#[derive(Debug, Clone, PartialEq)]
pub struct Case {
    /// 1-based, by increasing critical speed among the forward ones.
    pub mode: usize,
    pub critical: Critical,
    pub unbalances: Vec<Placed>,
}

/// The journals: each bearing's node, position and static load (seals carry none).
pub fn journals(statics: &StaticResult) -> Vec<Journal> {
    statics
        .reactions
        .iter()
        .map(|r| Journal {
            node: r.node,
            position: position(statics, r.node),
            load: r.y.hypot(r.x),
        })
        .collect()
}

fn position(statics: &StaticResult, node: usize) -> f64 {
    statics
        .nodes
        .iter()
        .find(|n| n.node == node)
        .map_or(f64::NAN, |n| n.position)
}

/// Mass of shaft and disks outboard of the first (`left`) or last bearing, kg; `None` when no
/// disk is there (a bare shaft end is no overhung rotor).
pub fn overhung_mass(rotor: &BeamRotor, statics: &StaticResult, left: bool) -> Option<f64> {
    let bearings: Vec<usize> = statics.reactions.iter().map(|r| r.node).collect();
    let (Some(&lo), Some(&hi)) = (bearings.iter().min(), bearings.iter().max()) else {
        return None;
    };
    let outboard = |node: usize| if left { node < lo } else { node > hi };
    let shaft: f64 = rotor
        .element_masses()
        .iter()
        .enumerate()
        // Element k joins nodes k and k + 1: outboard when both ends are (or one is the
        // bearing's own node).
        .filter(|(k, _)| if left { *k < lo } else { *k >= hi })
        .map(|(_, m)| m)
        .sum();
    let disks: Vec<f64> = rotor
        .disks()
        .iter()
        .filter(|d| outboard(d.node))
        .map(|d| d.mass)
        .collect();
    (!disks.is_empty()).then(|| shaft + disks.iter().sum::<f64>())
}

/// A mode's shape along the shaft: the signed major semi-axis at every node ([`Profile`]),
/// and between nodes `curve`, `(position, value)` at [`CURVE_POINTS`] points per element.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Shape {
    pub nodes: Vec<Profile>,
    pub curve: Vec<(f64, f64)>,
}

/// Points per element of [`Shape::curve`], ends included.
pub const CURVE_POINTS: usize = 9;

/// The shape of the forward pole of `set` (the poles at the critical speed, dense or held
/// sparse) nearest `pole`: at each node `|a| +
/// |b|` of the forward and backward circular parts, signed by the real part of its inner
/// product with the node that moves most (in phase or in opposition). Between two nodes that
/// keep their rotations the translations are the element's cubic Hermite interpolation of
/// both ends' translations and rotations (the complex rotation `phi_y - i phi_x` is
/// `d(x + i y)/dz`), then reduced the same way; across a coupling (`couplings`: their left
/// nodes), a spring and no beam, the nodes are joined straight.
pub fn profile(
    system: &RotorSystem,
    set: &PoleSet,
    pole: c64,
    statics: &StaticResult,
    couplings: &[usize],
) -> Result<Shape, AnalysisError> {
    let Some(p) = set
        .rotor
        .iter()
        .filter(|p| p.whirl == Whirl::Forward)
        .min_by(|a, b| (a.s - pole).norm().total_cmp(&(b.s - pole).norm()))
    else {
        return Ok(Shape::default());
    };
    let n = system.dofs.len();
    let doubled = set.doubled;
    let part = |j: usize| {
        let a = p.shape.get(j).copied().unwrap_or_default();
        let b = if doubled {
            p.shape.get(n + j).copied().unwrap_or_default()
        } else {
            c64::new(0.0, 0.0)
        };
        (a, b)
    };
    // Nodes a reduction left out have no translation of their own: not loaded.
    type Node = (usize, f64, (c64, c64), Option<(c64, c64)>);
    let nodes: Vec<Node> = statics
        .nodes
        .iter()
        .filter_map(|d| {
            let t = part(translation_of(system, d.node)?);
            let r = dof_of(system, d.node, DofKind::Rotation).map(part);
            Some((d.node, d.position, t, r))
        })
        .collect();
    let size = |(a, b): (c64, c64)| a.norm() + b.norm();
    let Some(&(_, _, reference, _)) = nodes.iter().max_by(|x, y| size(x.2).total_cmp(&size(y.2)))
    else {
        return Ok(Shape::default());
    };
    let signed = |(a, b): (c64, c64)| {
        let dot = (a * reference.0.conj() + b * reference.1.conj()).re;
        size((a, b)) * if dot < 0.0 { -1.0 } else { 1.0 }
    };
    let mut curve = vec![];
    for w in nodes.windows(2) {
        let ((n0, z0, t0, r0), (n1, z1, t1, r1)) = (w[0], w[1]);
        let beam = n1 == n0 + 1 && !couplings.contains(&n0);
        let (Some(r0), Some(r1), true) = (r0, r1, beam) else {
            curve.extend([(z0, signed(t0)), (z1, signed(t1))]);
            continue;
        };
        let l = z1 - z0;
        for k in 0..CURVE_POINTS {
            let x = k as f64 / (CURVE_POINTS - 1) as f64;
            let h = [
                1.0 - 3.0 * x * x + 2.0 * x * x * x,
                l * (x - 2.0 * x * x + x * x * x),
                3.0 * x * x - 2.0 * x * x * x,
                l * (x * x * x - x * x),
            ];
            let at = |f: fn((c64, c64)) -> c64| {
                f(t0) * h[0] + f(r0) * h[1] + f(t1) * h[2] + f(r1) * h[3]
            };
            curve.push((z0 + x * l, signed((at(|v| v.0), at(|v| v.1)))));
        }
    }
    Ok(Shape {
        nodes: nodes
            .iter()
            .map(|&(node, position, t, _)| Profile {
                node,
                position,
                value: signed(t),
            })
            .collect(),
        curve,
    })
}

fn dof_of(system: &RotorSystem, node: usize, kind: DofKind) -> Option<usize> {
    system
        .dofs
        .iter()
        .position(|d| d.node == node && d.kind == kind)
}

/// The translation of `node` in `system`, if it kept one.
pub fn translation_of(system: &RotorSystem, node: usize) -> Option<usize> {
    dof_of(system, node, DofKind::Translation)
}

/// How a case's response reads against the limits.
#[derive(Debug, Clone, PartialEq)]
pub struct Assessment {
    /// API 617's `Avl`, m peak to peak.
    pub vibration_limit: f64,
    /// The largest peak-to-peak amplitude at a bearing over the operating range, m, its node
    /// and speed.
    pub a1: Option<(f64, usize, f64)>,
    pub scale_factor: Option<f64>,
    pub clearances: Vec<ClearanceCheck>,
}

/// A close-clearance location's check.
#[derive(Debug, Clone, PartialEq)]
pub struct ClearanceCheck {
    pub node: usize,
    /// Minimum diametral clearance, m.
    pub diametral: f64,
    /// The largest peak-to-peak amplitude over the sweep times the scale factor, m, and the
    /// speed where it is.
    pub scaled: f64,
    pub speed: f64,
    pub passes: bool,
}

/// Reads a response (`response[speed][k]` the orbit of `nodes[k]`) against API 617's limits.
pub fn assess(
    speeds: &[f64],
    nodes: &[usize],
    response: &[Vec<Orbit>],
    bearings: &[usize],
    clearances: &[(usize, f64)],
    range: (f64, f64),
    rpm: f64,
) -> Assessment {
    let limit = placement::vibration_limit(rpm);
    let pk_pk = |i: usize, k: usize| 2.0 * response[i][k].major();
    let column = |node: usize| nodes.iter().position(|&n| n == node);
    let mut a1: Option<(f64, usize, f64)> = None;
    for &b in bearings {
        let Some(k) = column(b) else { continue };
        for (i, &w) in speeds.iter().enumerate() {
            if w < range.0 || w > range.1 {
                continue;
            }
            let a = pk_pk(i, k);
            if a.is_finite() && a1.is_none_or(|(m, _, _)| a > m) {
                a1 = Some((a, b, w));
            }
        }
    }
    let scale = a1.and_then(|(a, _, _)| placement::scale_factor(limit, a));
    let clearances = clearances
        .iter()
        .filter_map(|&(node, diametral)| {
            let k = column(node)?;
            let (i, a) = (0..speeds.len())
                .map(|i| (i, pk_pk(i, k)))
                .max_by(|x, y| x.1.total_cmp(&y.1))?;
            let scaled = a * scale.unwrap_or(1.0);
            Some(ClearanceCheck {
                node,
                diametral,
                scaled,
                speed: speeds[i],
                passes: scaled < CLEARANCE_FRACTION * diametral,
            })
        })
        .collect();
    Assessment {
        vibration_limit: limit,
        a1,
        scale_factor: scale,
        clearances,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_limits_read_the_bearings_in_the_range_and_scale_the_clearances() {
        // Two nodes: a bearing (0) and a seal location (1), in circular orbits of the radii
        // below at 100, 200 and 300 rad/s.
        let circle = |r: f64| Orbit {
            a: c64::new(r, 0.0),
            b: c64::new(0.0, 0.0),
        };
        let speeds = [100.0, 200.0, 300.0];
        let response = vec![
            vec![circle(2e-6), circle(5e-6)],
            vec![circle(3e-6), circle(8e-6)],
            vec![circle(10e-6), circle(20e-6)],
        ];
        // Operating range 150-250 rad/s, MCS 15,000 rpm: Avl 22.72 um; A1 = 6 um pk-pk at the
        // bearing at 200 rad/s (the 20 um at 300 rad/s is outside the range).
        let a = assess(
            &speeds,
            &[0, 1],
            &response,
            &[0],
            &[(1, 100e-6)],
            (150.0, 250.0),
            15_000.0,
        );
        let (a1, node, at) = a.a1.unwrap();
        assert!((a1 - 6e-6).abs() < 1e-18 && node == 0 && at == 200.0);
        let scc = a.scale_factor.unwrap();
        assert!((scc - 22.718e-6 / 6e-6).abs() < 1e-3);
        // The seal: 40 um pk-pk at 300 rad/s, times 3.79 = 151 um > 75 um: it fails.
        let c = &a.clearances[0];
        assert!((c.scaled - 40e-6 * scc).abs() < 1e-15 && c.speed == 300.0);
        assert!(!c.passes);
    }
}
