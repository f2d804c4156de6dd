//! A beam rotor seen in torsion or axially: the train's shafts, couplings, gear meshes and
//! thrust bearings, validated for the motion a request asks for.
//!
//! A straight shaft's twist and axial displacement are each one real coordinate per node and do
//! not couple to its bending in the linear model, so a torsional or axial analysis is its own
//! system (`fem::train`). Gear meshes join shafts turning at different speeds; they have no
//! lateral model here, so a rotor with gears is refused by the lateral analyses.

use super::api::{BeamInput, Motion, SupportInput};
use super::beam::BeamRotor;
use super::error::Invalid;
use super::limits::Limits;
use super::shaft::Element;
use super::supports::{GeneralSupport, parse_supports, support_path};

/// A beam rotor for a torsional or axial analysis.
#[derive(Debug, Clone, PartialEq)]
pub struct TrainRotor {
    /// `Torsional` or `Axial`.
    pub motion: Motion,
    pub beam: BeamRotor,
    /// The supports' axial coefficients (`kzz`, `czz`) as isotropic general supports on the
    /// axial coordinates (axial motion only; a support without them is not one axially).
    pub axial_supports: Vec<GeneralSupport>,
    /// Each element's stress concentration factor (its segment's; 1 by default).
    pub stress_concentration: Vec<f64>,
}

impl TrainRotor {
    /// Validates `input` for `motion` (torsional or axial).
    pub fn parse(input: &BeamInput, motion: Motion, limits: &Limits) -> Result<Self, Invalid> {
        debug_assert!(!motion.is_lateral());
        let beam = BeamRotor::parse(input, limits)?;
        let mut bad = Invalid::default();
        let nodes = beam.shaft_nodes();
        let axial_supports = match motion {
            Motion::Axial => axial_supports(&input.supports, nodes, &mut bad),
            _ => vec![],
        };
        let stress_concentration = stress_concentration(input, &mut bad);
        bad.into_result(|| TrainRotor {
            motion,
            beam,
            axial_supports,
            stress_concentration,
        })
    }

    /// Coordinates: one per shaft node.
    pub fn nodes(&self) -> usize {
        self.beam.shaft_nodes()
    }

    /// Each shaft node's speed over the first shaft's: the product of the gear ratios before it.
    pub fn speed_ratios(&self) -> Vec<f64> {
        let mut r = vec![1.0];
        for e in self.beam.elements() {
            let last = *r.last().expect("starts with one");
            r.push(match e {
                Element::Gear(g) => last * g.ratio,
                _ => last,
            });
        }
        r
    }

    /// The distinct shaft speeds of the train over the first shaft's, in order.
    pub fn shaft_ratios(&self) -> Vec<f64> {
        let mut out: Vec<f64> = vec![];
        for r in self.speed_ratios() {
            if !out.contains(&r) {
                out.push(r);
            }
        }
        out
    }

    /// Whether any part has hysteretic loss in this motion (all of it nonrotating in effect:
    /// in torsion and axially the rotating and fixed frames see one frequency).
    pub fn has_loss(&self) -> bool {
        let b = &self.beam;
        b.elements().iter().any(|e| match e {
            Element::Beam(s) => s.loss_factor > 0.0,
            Element::Coupling(c) => {
                c.loss_factor > 0.0
                    && match self.motion {
                        Motion::Axial => c.axial_stiffness > 0.0,
                        _ => c.torsional_stiffness > 0.0,
                    }
            }
            Element::Gear(_) => false,
        }) || b.sleeves().iter().any(|s| s.element.loss_factor > 0.0)
            || self
                .axial_supports
                .iter()
                .any(|s| s.loss_factor > 0.0 && s.at(0.0).k.xx > 0.0)
    }
}

/// Each element's segment's `stress_concentration` (>= 1, default 1).
fn stress_concentration(input: &BeamInput, bad: &mut Invalid) -> Vec<f64> {
    let mut out = vec![];
    for (i, seg) in input.shaft.iter().enumerate() {
        let scf = seg.stress_concentration.unwrap_or(1.0);
        if !(scf.is_finite() && scf >= 1.0) {
            bad.push(
                format!("rotor.shaft[{i}].stress_concentration"),
                format!("must be a factor >= 1 (got {scf})"),
            );
        }
        let single = seg.coupling.is_some() || seg.gear.is_some();
        let count = if single { 1 } else { seg.elements.unwrap_or(1) };
        out.extend(std::iter::repeat_n(scf, count.max(0) as usize));
    }
    out
}

/// The supports' `kzz`, `czz` as isotropic general supports (`kxx = kyy = kzz`), their errors
/// named by the fields given.
fn axial_supports(inputs: &[SupportInput], nodes: usize, bad: &mut Invalid) -> Vec<GeneralSupport> {
    let derived: Vec<(usize, SupportInput)> = inputs
        .iter()
        .enumerate()
        .filter(|(_, s)| s.kzz.is_some() || s.czz.is_some())
        .map(|(i, s)| {
            (
                i,
                SupportInput {
                    node: s.node,
                    n_link: s.n_link,
                    loss_factor: s.loss_factor,
                    kxx: s.kzz.clone(),
                    kyy: s.kzz.clone(),
                    cxx: s.czz.clone(),
                    cyy: s.czz.clone(),
                    speeds: s.speeds.clone(),
                    frequencies: s.frequencies.clone(),
                    interpolation: s.interpolation,
                    ..SupportInput::default()
                },
            )
        })
        .collect();
    let mut out = vec![];
    for (i, s) in derived {
        let mut mine = Invalid::default();
        let node_ok = |bad: &mut Invalid, at: String, node: i64| -> Option<usize> {
            if node >= 0 && (node as u64) < nodes as u64 {
                Some(node as usize)
            } else {
                bad.push(
                    at,
                    format!(
                        "an axial support acts between shaft nodes (0 to {}) or to ground \
                         (got {node})",
                        nodes - 1
                    ),
                );
                None
            }
        };
        let (_, mut general) = parse_supports(std::slice::from_ref(&s), false, &mut mine, node_ok);
        for g in &mut general {
            g.index = i;
        }
        let from = support_path(false, 0);
        let to = support_path(false, i);
        mine.prefix_paths(|p| {
            p.replacen(&from, &to, 1)
                .replace(".kxx", ".kzz")
                .replace(".kyy", ".kzz")
                .replace(".cxx", ".czz")
                .replace(".cyy", ".czz")
        });
        bad.extend(mine);
        out.extend(general);
    }
    out
}

/// One excitation.
#[derive(Debug, Clone, PartialEq)]
pub enum Line {
    /// `order x ratio x Omega`.
    Order { order: f64, ratio: f64 },
    /// A fixed frequency, rad/s (`multiple` of the line frequency).
    Fixed { multiple: f64, frequency: f64 },
}

impl Line {
    /// Its frequency per unit reference speed (0 for a fixed one).
    pub fn slope(&self) -> f64 {
        match self {
            Line::Order { order, ratio } => order * ratio,
            Line::Fixed { .. } => 0.0,
        }
    }
}

/// What a torsional interference diagram is asked for (`analysis::interference`).
#[derive(Debug, Clone, PartialEq)]
pub struct Spec {
    pub lines: Vec<Line>,
    /// Operating range of the reference shaft, rad/s.
    pub range: [f64; 2],
}
