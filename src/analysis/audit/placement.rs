//! API 684's unbalance cases: where each mode is excited, and how hard, and the limits its
//! response is read against.
//!
//! The amount is `Ua = 2 Ur` with API 617's residual unbalance `Ur = 6350 W / N` (g mm; W in
//! kg, N the maximum continuous speed in rpm): 2 x 6350 x 100 kg / 10,000 rpm = 127 g mm =
//! 1.27e-4 kg m. Per mode, from its shape at its critical speed (the signed major semi-axis of
//! each node's orbit, [`Profile`]):
//! - one antinode between the bearings: there, W the sum of the journal static loads;
//! - two antinodes (a conical or second bending mode): at both, 180 degrees apart where the
//!   lobes move in opposition, each W the static load of its nearest journal;
//! - an antinode outboard of the bearings on an overhang that carries a disk (an overhung
//!   impeller or coupling hub): there, W the mass outboard of the nearest bearing (shaft and
//!   disks); when the mode's largest motion is there, only its overhangs are loaded. A bare
//!   shaft end past a bearing is no overhang: its antinodes count as the span's.
//!
//! A lobe is a run of nodes moving in phase; a lobe whose largest motion is under
//! [`MINOR_LOBE`] of the mode's is not an antinode (a coupling end swinging against a first
//! bending mode). At most the two largest lobes are loaded, as API 684 defines no more.
//!
//! The response is then read against API 617's mechanical test limit `Avl = 25.4 um x
//! sqrt(12000 / N)` peak to peak (at most 25.4 um): 25.4 um x sqrt(12000 / 15,000) = 22.7 um.
//! The scale factor `Scc = Avl / A1` (at most 6), `A1` the largest peak-to-peak amplitude at
//! a bearing over the operating range, scales the response at every close-clearance location,
//! which must stay under 75% of the minimum diametral clearance.

/// API 617's residual unbalance constant: `Ur = 6350 W / N` g mm with W in kg, N in rpm.
pub const UR: f64 = 6350.0;
/// API 684's unbalance for the response analysis, as a multiple of `Ur`.
pub const UA_OVER_UR: f64 = 2.0;
/// A lobe under this fraction of the mode's largest motion is not an antinode.
pub const MINOR_LOBE: f64 = 0.2;
/// API 617's cap on the scale factor.
pub const MAX_SCALE: f64 = 6.0;
/// The scaled amplitude may use this fraction of the diametral clearance.
pub const CLEARANCE_FRACTION: f64 = 0.75;

/// One node of a mode shape: where it is and its signed major semi-axis (any scale).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Profile {
    pub node: usize,
    pub position: f64,
    pub value: f64,
}

/// A bearing's journal: its node, axial position, m, and static load, N.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Journal {
    pub node: usize,
    pub position: f64,
    pub load: f64,
}

/// Which of API 684's rules placed an unbalance.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rule {
    /// One antinode between the bearings: W the sum of the journal loads.
    OneAntinode,
    /// One of two antinodes: W its nearest journal's load; `opposed` where the lobes move in
    /// opposition (the unbalances 180 degrees apart), else in phase.
    TwoAntinodes { opposed: bool },
    /// Outboard of the bearings: W the overhung mass.
    Overhung,
}

impl Rule {
    pub fn name(self) -> &'static str {
        match self {
            Rule::OneAntinode => "one antinode: W the sum of the journal static loads",
            Rule::TwoAntinodes { opposed: true } => {
                "two antinodes, 180 degrees apart (the lobes move in opposition): W the nearest \
                 journal's load"
            }
            Rule::TwoAntinodes { opposed: false } => {
                "two antinodes, in phase (the lobes move together): W the nearest journal's load"
            }
            Rule::Overhung => "overhung: W the mass outboard of the nearest bearing",
        }
    }
}

/// One unbalance: `amount` kg m at `node`, `phase` rad, sized by `weight` kg under `rule`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placed {
    pub node: usize,
    pub amount: f64,
    pub phase: f64,
    pub weight: f64,
    pub rule: Rule,
}

/// `Ua = 2 x 6350 W / N` g mm, as kg m, for W in kg and N in rpm.
pub fn unbalance_amount(weight: f64, rpm: f64) -> f64 {
    UA_OVER_UR * UR * weight / rpm * 1e-6
}

/// API 617's vibration limit `Avl = 25.4 um sqrt(12000 / N)`, at most 25.4 um, peak to peak,
/// m, for N in rpm.
pub fn vibration_limit(rpm: f64) -> f64 {
    25.4e-6 * (12_000.0 / rpm).sqrt().min(1.0)
}

/// `Scc = Avl / A1`, at most 6 (`None` without motion).
pub fn scale_factor(limit: f64, a1: f64) -> Option<f64> {
    (a1 > 0.0 && a1.is_finite()).then(|| (limit / a1).min(MAX_SCALE))
}

/// The lobes of a profile (sorted by axial position): runs of one sign among the nodes that
/// move more than 1e-9 of the largest, each as `(node index of its largest |value|, sign)`.
fn lobes(profile: &[Profile]) -> Vec<(usize, f64)> {
    let top = profile.iter().map(|p| p.value.abs()).fold(0.0, f64::max);
    let mut out: Vec<(usize, f64)> = vec![];
    let mut sign = 0.0;
    for (i, p) in profile.iter().enumerate() {
        if p.value.abs() <= 1e-9 * top {
            continue;
        }
        let s = p.value.signum();
        match out.last_mut() {
            Some(last) if s == sign => {
                if p.value.abs() > profile[last.0].value.abs() {
                    last.0 = i;
                }
            }
            _ => out.push((i, s)),
        }
        sign = s;
    }
    out
}

/// API 684's unbalances for a mode of `profile` (module docs). `overhung(left)` is the mass
/// outboard of the first (`true`) or last bearing, kg, or `None` where no disk (impeller,
/// coupling hub) overhangs there: a bare shaft end past a bearing is part of a between-bearings
/// rotor, and an antinode on it is loaded as any other (as ross-report, which classifies the
/// rotor by its disks). `g` turns loads into kg.
pub fn place(
    profile: &[Profile],
    journals: &[Journal],
    overhung: &dyn Fn(bool) -> Option<f64>,
    rpm: f64,
    g: f64,
) -> Vec<Placed> {
    let mut profile = profile.to_vec();
    profile.sort_by(|a, b| a.position.total_cmp(&b.position));
    let lobes = lobes(&profile);
    let Some(top) = lobes
        .iter()
        .map(|&(i, _)| profile[i].value.abs())
        .reduce(f64::max)
    else {
        return vec![];
    };
    let mut major: Vec<(usize, f64)> = lobes
        .into_iter()
        .filter(|&(i, _)| profile[i].value.abs() >= MINOR_LOBE * top)
        .collect();
    major.sort_by(|a, b| {
        profile[b.0]
            .value
            .abs()
            .total_cmp(&profile[a.0].value.abs())
    });
    let span = journals
        .iter()
        .map(|j| j.position)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
            (lo.min(x), hi.max(x))
        });
    // The overhang an antinode is on, with its mass: `None` between the bearings or on a bare
    // shaft end.
    let overhang = |i: usize| {
        let x = profile[i].position;
        if x < span.0 {
            overhung(true)
        } else if x > span.1 {
            overhung(false)
        } else {
            None
        }
    };
    let outboard = |i: usize| overhang(i).is_some();
    // An overhung mode (its largest motion outboard) is loaded at its overhangs only: the
    // span swinging back against it is the overhang's reaction, not a mode of its own.
    if major.first().is_some_and(|&(i, _)| outboard(i)) {
        major.retain(|&(i, _)| outboard(i));
    }
    major.truncate(2);
    major.sort_by_key(|&(i, _)| i);
    let total: f64 = journals.iter().map(|j| j.load).sum::<f64>() / g;
    let first_sign = major.first().map_or(1.0, |m| m.1);
    let opposed = major.iter().any(|m| m.1 != first_sign);
    major
        .iter()
        .map(|&(i, sign)| {
            let p = profile[i];
            let (weight, rule) = if let Some(w) = overhang(i) {
                (w, Rule::Overhung)
            } else if major.len() == 1 {
                (total, Rule::OneAntinode)
            } else {
                let nearest = journals
                    .iter()
                    .min_by(|a, b| {
                        (a.position - p.position)
                            .abs()
                            .total_cmp(&(b.position - p.position).abs())
                    })
                    .map_or(total, |j| j.load / g);
                (nearest, Rule::TwoAntinodes { opposed })
            };
            Placed {
                node: p.node,
                amount: unbalance_amount(weight, rpm),
                phase: if sign == first_sign {
                    0.0
                } else {
                    std::f64::consts::PI
                },
                weight,
                rule,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn profile(values: &[f64]) -> Vec<Profile> {
        values
            .iter()
            .enumerate()
            .map(|(node, &value)| Profile {
                node,
                position: 0.1 * node as f64,
                value,
            })
            .collect()
    }

    const G: f64 = 9.80665;

    fn journals() -> [Journal; 2] {
        // Bearings at nodes 1 and 7 (0.1 m, 0.7 m), 300 N and 500 N.
        [
            Journal {
                node: 1,
                position: 0.1,
                load: 300.0,
            },
            Journal {
                node: 7,
                position: 0.7,
                load: 500.0,
            },
        ]
    }

    #[test]
    fn ua_is_twice_6350_w_over_n_in_g_mm() {
        // 100 kg at 10,000 rpm: 2 x 6350 x 100 / 10,000 = 127 g mm = 1.27e-4 kg m.
        assert!((unbalance_amount(100.0, 10_000.0) - 1.27e-4).abs() < 1e-15);
    }

    #[test]
    fn avl_is_25_4_um_sqrt_12000_over_n_capped() {
        // 15,000 rpm: 25.4 x sqrt(0.8) = 22.72 um; 3,000 rpm: sqrt(4) = 2, capped at 25.4 um.
        assert!((vibration_limit(15_000.0) - 22.718e-6).abs() < 1e-9);
        assert_eq!(vibration_limit(3_000.0), 25.4e-6);
        assert_eq!(vibration_limit(12_000.0), 25.4e-6);
        // Scc: 22.7 um over 5 um = 4.54; over 1 um, 22.7, capped at 6.
        assert!((scale_factor(22.718e-6, 5e-6).unwrap() - 4.5436).abs() < 1e-4);
        assert_eq!(scale_factor(22.718e-6, 1e-6), Some(6.0));
        assert_eq!(scale_factor(22.718e-6, 0.0), None);
    }

    #[test]
    fn a_first_bending_mode_is_loaded_at_its_antinode_with_the_journal_loads() {
        // The coupling end (node 0) swings against it at a tenth: not an antinode.
        let p = profile(&[-0.1, 0.0, 0.5, 0.9, 1.0, 0.8, 0.4, 0.0, 0.05]);
        let u = place(&p, &journals(), &|_| Some(7.0), 10_000.0, G);
        assert_eq!(u.len(), 1);
        assert_eq!(
            (u[0].node, u[0].rule, u[0].phase),
            (4, Rule::OneAntinode, 0.0)
        );
        // W = 800 N / 9.80665 m/s^2 = 81.58 kg: Ua = 2 x 6350 x 81.58 / 10,000 g mm.
        assert!((u[0].weight - 81.577).abs() < 1e-3);
        assert!((u[0].amount - 2.0 * 6350.0 * 81.577 / 10_000.0 * 1e-6).abs() < 1e-9);
    }

    #[test]
    fn a_conical_mode_is_loaded_at_both_antinodes_in_opposition() {
        let p = profile(&[1.0, 0.8, 0.5, 0.2, -0.1, -0.4, -0.7, -0.9, -1.1]);
        let u = place(&p, &journals(), &|_| Some(7.0), 10_000.0, G);
        assert_eq!(u.len(), 2);
        // Both ends are outboard of the bearings here: overhung masses.
        assert_eq!((u[0].node, u[1].node), (0, 8));
        assert!(
            u.iter()
                .all(|u| u.rule == Rule::Overhung && u.weight == 7.0)
        );
        assert_eq!((u[0].phase, u[1].phase), (0.0, std::f64::consts::PI));
        // The same ends without a disk on them are bare shaft: two antinodes of a
        // between-bearings rotor, each with its nearest journal's load.
        let u = place(&p, &journals(), &|_| None, 10_000.0, G);
        assert_eq!((u[0].node, u[1].node), (0, 8));
        assert!(
            u.iter()
                .all(|u| u.rule == Rule::TwoAntinodes { opposed: true })
        );
        assert!((u[0].weight - 300.0 / G).abs() < 1e-12);
        assert!((u[1].weight - 500.0 / G).abs() < 1e-12);
        // Between the bearings: the nearest journal's load each.
        let p = profile(&[0.0, 0.8, 1.0, 0.5, 0.0, -0.5, -1.2, -0.9, 0.0]);
        let u = place(&p, &journals(), &|_| Some(7.0), 10_000.0, G);
        assert_eq!((u[0].node, u[1].node), (2, 6));
        assert!((u[0].weight - 300.0 / G).abs() < 1e-12);
        assert!((u[1].weight - 500.0 / G).abs() < 1e-12);
        assert_eq!(u[0].rule, Rule::TwoAntinodes { opposed: true });
        assert!(u[0].rule.name().contains("180 degrees apart"));
    }

    #[test]
    fn a_third_mode_with_its_outer_lobes_in_phase_is_said_to_be_loaded_in_phase() {
        // A symmetric rotor's third mode between the bearings: the outer lobes move together,
        // the middle one against them at a half. The two largest lobes (nodes 2 and 6) are
        // loaded at phase 0 both, and the rule's text must say so, not "180 degrees apart".
        let p = profile(&[0.0, 0.9, 1.0, 0.3, -0.5, 0.3, 1.0, 0.9, 0.0]);
        let u = place(&p, &journals(), &|_| None, 10_000.0, G);
        assert_eq!((u[0].node, u[1].node), (2, 6));
        assert_eq!((u[0].phase, u[1].phase), (0.0, 0.0));
        assert!(
            u.iter()
                .all(|u| u.rule == Rule::TwoAntinodes { opposed: false })
        );
        let text = u[0].rule.name();
        assert!(text.contains("in phase") && !text.contains("180"), "{text}");
    }

    #[test]
    fn an_overhung_mode_is_loaded_at_the_overhang_with_its_mass() {
        let p = profile(&[0.05, 0.0, 0.02, 0.03, 0.02, 0.01, 0.1, 0.5, 1.0]);
        let u = place(
            &p,
            &journals(),
            &|left| Some(if left { 3.0 } else { 12.0 }),
            6_000.0,
            G,
        );
        assert_eq!(u.len(), 1);
        assert_eq!(
            (u[0].node, u[0].rule, u[0].weight),
            (8, Rule::Overhung, 12.0)
        );
        // 2 x 6350 x 12 kg / 6,000 rpm = 25.4 g mm.
        assert!((u[0].amount - 25.4e-6).abs() < 1e-15);
        // The span swinging back at a third of the overhang: still the overhang alone.
        let p = profile(&[0.0, 0.0, -0.2, -0.3, -0.33, -0.25, -0.1, 0.0, 1.0]);
        let u = place(&p, &journals(), &|_| Some(12.0), 6_000.0, G);
        assert_eq!(u.len(), 1);
        assert_eq!((u[0].node, u[0].rule), (8, Rule::Overhung));
    }
}
