//! Before a rotor on supports fitted by Maxwell branches is integrated: the fitted model's
//! poles against the rotor's own, each consistent with the whirl frequency it reads its
//! supports at (`analysis::consistent`, the frequency domain's poles).
//!
//! The fit is exact nowhere but at its anchors, so the two sets differ by what the fit's
//! deviation moves a pole; a pole of the fitted model that grows where every pole of the rotor
//! decays is no deviation but a realisation the time domain must not integrate (a fit swinging
//! between its samples once gave a cross-coupling 4e2 times the table's at 3.2e4 rad/s and a
//! pole growing at 1e3 1/s). The comparison is made at each speed the integration runs at
//! (the constant speed, or the knots of a speed profile) under the frequency domain's model:
//! viscous for viscous damping, hysteretic otherwise (the nonviscous and equivalent models
//! stand in for it in the time domain).

use crate::analysis::AnalysisError;
use crate::analysis::modal::modal_consistent;
use crate::analysis::poles::{INSTABILITY_MARGIN, poles_at};
use crate::damping::DampedModel;
use crate::linalg::c64;
use crate::model::damping::DampingModel;
use crate::system::{Layout, RotorSystem};

/// A pole of the rotor and the fitted model's nearest.
#[derive(Debug, Clone, PartialEq)]
pub struct PolePair {
    /// Consistent with its frequency (the frequency domain's).
    pub consistent: c64,
    /// The fitted model's (or its mirror, in doubled coordinates).
    pub fitted: c64,
    /// `|fitted - consistent| / |consistent|`.
    pub distance: f64,
}

/// The fitted model's poles against the rotor's at one speed.
#[derive(Debug, Clone, PartialEq)]
pub struct FitPoles {
    pub speed: f64,
    /// Each consistent pole with its partner, by increasing |frequency|.
    pub pairs: Vec<PolePair>,
    /// The largest `distance`.
    pub max_distance: f64,
    /// The largest decay rate of the rotor's poles, and of every pole of the fitted model
    /// (its branches' and internal ones included), 1/s.
    pub max_decay_rate: (f64, f64),
    /// The fitted model's poles that grow with no growing pole of the rotor to pair with.
    pub unstable: Vec<c64>,
    /// Poles of the consistency search not found, and merged into others.
    pub lost: usize,
    pub merged: usize,
}

/// The model the frequency domain reads the rotor with, for `damping` in the time domain.
fn reference(damping: &DampingModel) -> DampingModel {
    match damping {
        DampingModel::Viscous => DampingModel::Viscous,
        _ => DampingModel::Hysteretic,
    }
}

/// The poles of `fitted` (the rotor `system` with its supports over whirl frequency fitted) at
/// `speed` under `damping`, against the consistent poles of `system`.
pub fn compare(
    system: &RotorSystem,
    fitted: &RotorSystem,
    damping: &DampingModel,
    speed: f64,
) -> Result<FitPoles, AnalysisError> {
    let own = modal_consistent(system, &reference(damping), speed, f64::INFINITY, false)?;
    let consistency = own
        .consistency
        .unwrap_or_else(|| unreachable!("supports over frequency"));
    let model = DampedModel::build(fitted, damping)?;
    let set = poles_at(&model, speed)?;
    let candidates: Vec<c64> = set.all().map(|p| p.s).collect();
    let doubled = fitted.layout() == Layout::Doubled;
    let consistent: Vec<c64> = own.poles.rotor.iter().map(|p| p.s).collect();
    let pairs = pair(&consistent, &candidates, doubled);
    let grows = |s: c64| s.re > INSTABILITY_MARGIN * s.norm();
    let unstable = candidates
        .iter()
        .copied()
        .filter(|&s| grows(s))
        .filter(|&s| {
            // Paired with a growing pole of the rotor: the rotor is unstable there too.
            !pairs
                .iter()
                .any(|p| grows(p.consistent) && (p.fitted == s || p.fitted == s.conj()))
        })
        .collect();
    let max = |v: &mut dyn Iterator<Item = c64>| v.map(|s| s.re).fold(f64::NEG_INFINITY, f64::max);
    Ok(FitPoles {
        speed,
        max_distance: pairs.iter().map(|p| p.distance).fold(0.0, f64::max),
        max_decay_rate: (
            max(&mut consistent.iter().copied()),
            max(&mut candidates.iter().copied()),
        ),
        pairs,
        unstable,
        lost: consistency.lost,
        merged: consistency.merged,
    })
}

/// Each of `consistent` with the nearest of `candidates` not taken by a nearer pair (a
/// candidate's mirror counts as it in doubled coordinates, where a pole set holds each pair
/// once), by increasing |frequency|.
fn pair(consistent: &[c64], candidates: &[c64], doubled: bool) -> Vec<PolePair> {
    let distance = |c: c64, f: c64| {
        let d = (f - c).norm();
        let d = if doubled {
            d.min((f.conj() - c).norm())
        } else {
            d
        };
        d / c.norm().max(f64::MIN_POSITIVE)
    };
    let mut all: Vec<(f64, usize, usize)> = consistent
        .iter()
        .enumerate()
        .flat_map(|(i, &c)| {
            candidates
                .iter()
                .enumerate()
                .map(move |(j, &f)| (distance(c, f), i, j))
        })
        .collect();
    all.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (mut used_c, mut used_f) = (vec![false; consistent.len()], vec![false; candidates.len()]);
    let mut out = vec![];
    for (d, i, j) in all {
        if used_c[i] || used_f[j] {
            continue;
        }
        used_c[i] = true;
        used_f[j] = true;
        let (c, f) = (consistent[i], candidates[j]);
        // The member of a mirror pair on the consistent pole's side.
        let fitted = if doubled && (f.conj() - c).norm() < (f - c).norm() {
            f.conj()
        } else {
            f
        };
        out.push(PolePair {
            consistent: c,
            fitted,
            distance: d,
        });
    }
    out.sort_by(|a, b| {
        (a.consistent.im.abs())
            .total_cmp(&b.consistent.im.abs())
            .then(a.consistent.im.total_cmp(&b.consistent.im))
    });
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_pole_pairs_with_the_nearest_free_one_or_its_mirror() {
        let c = [c64::new(-1.0, 100.0), c64::new(-2.0, 101.0)];
        // The second candidate is nearest both; the nearer pair takes it.
        let f = [
            c64::new(-1.5, 103.0),
            c64::new(-2.0, -101.1),
            c64::new(-7.0, 0.0),
        ];
        let p = pair(&c, &f, true);
        assert_eq!(p.len(), 2);
        assert_eq!(p[1].consistent, c[1]);
        assert_eq!(p[1].fitted, c64::new(-2.0, 101.1));
        assert!((p[1].distance - 0.1 / c[1].norm()).abs() < 1e-15);
        assert_eq!(p[0].fitted, f[0]);
        // Not doubled: the mirror is another pole.
        let p = pair(&c, &f, false);
        assert_eq!(p[1].fitted, f[0]);
    }
}
