//! The Campbell diagram and stability threshold of a rotor on supports whose coefficients
//! depend on the whirl frequency: every pole consistent with the frequency it reads them at.
//!
//! At each speed of the sweep the poles are those of [`modal::modal_consistent`] (each
//! continued from the rotor read synchronously to `|Im s(w)| = w`), tracked into branches as
//! any sweep's are. A crossing with the 1x line is a root of `g(W) = |Im s(W)| - W` over the
//! spin speed, closed by Brent's method, each evaluation the branch's consistent pole at the
//! trial speed continued from the pole interpolated there. At the crossing the pole whirls at
//! the speed, so it reads its tables at the speed: the synchronous reading's crossing, which a
//! table of one value per speed gives too. The threshold is found on the consistent poles as a
//! stability sweep finds it ([`stability::threshold_of`]).

use rayon::prelude::*;

use super::AnalysisError;
use super::campbell::{Branch, CampbellResult, Keep, branches_of, forward_criticals};
use super::consistent::consistent_on;
use super::control::Control;
use super::criticals::{Critical, TOLERANCE};
use super::modal::modal_consistent;
use super::poles::{self, PoleSet, Whirl};
use super::roots::brent;
use super::stability::{self, Summary, Threshold};
use super::tracking::Tracker;
use crate::linalg::c64;
use crate::model::damping::DampingModel;
use crate::system::{Layout, RotorSystem};

/// The consistent poles in the box of `bound` at a speed.
pub fn consistent_poles(
    system: &RotorSystem,
    damping: &DampingModel,
    bound: f64,
    sparse: bool,
) -> impl Fn(f64) -> Result<PoleSet, AnalysisError> + Sync {
    move |w| Ok(modal_consistent(system, damping, w, bound, sparse)?.poles)
}

/// The Campbell diagram of the branches `keep` asks for (poles in the box of `keep.below`;
/// the rotor's synchronous reading solved dense, or held sparse where `sparse`).
pub fn campbell_consistent(
    system: &RotorSystem,
    damping: &DampingModel,
    speeds: &[f64],
    keep: Keep,
    sparse: bool,
    control: &Control,
) -> Result<CampbellResult, AnalysisError> {
    control.expect(stability::work(speeds.len()) + speeds.len() as u64);
    let at = consistent_poles(system, damping, keep.below, sparse);
    let doubled = system.layout() == Layout::Doubled;
    let mut tracker = Tracker::new(2 * system.n());
    let summaries: Vec<Summary> = stability::sweep_of(&at, speeds, control, |set| {
        tracker.push(set);
    })?;
    let (branches, overdamped, ambiguities) = branches_of(tracker, doubled, keep);
    let criticals = crossings(system, damping, speeds, &branches, control)?;
    control.advance(speeds.len() as u64);
    let threshold: Option<Threshold> = stability::threshold_of(&at, &summaries, control)?;
    control.advance(stability::work(0));
    Ok(CampbellResult {
        speeds: speeds.to_vec(),
        critical_speeds: forward_criticals(&criticals),
        branches,
        overdamped,
        criticals,
        threshold,
        reduction: None,
        ambiguities,
        interference: None,
    })
}

/// Every crossing of a branch with the 1x line (module docs), by speed.
fn crossings(
    system: &RotorSystem,
    damping: &DampingModel,
    speeds: &[f64],
    branches: &[Branch],
    control: &Control,
) -> Result<Vec<Critical>, AnalysisError> {
    // Per branch, the brackets: consecutive defined points where g changes sign.
    let mut work = vec![];
    for (bi, b) in branches.iter().enumerate() {
        let pts: Vec<(f64, c64, f64)> = speeds
            .iter()
            .zip(b.poles.iter().zip(&b.whirl_ratio))
            .filter_map(|(&w, (p, r))| p.map(|s| (w, s, r.unwrap_or(0.0))))
            .collect();
        let g = |(w, s, _): (f64, c64, f64)| s.im.abs() - w;
        for pair in pts.windows(2) {
            let (p, q) = (pair[0], pair[1]);
            if g(p) * g(q) < 0.0 && !poles::overdamped(p.1) && !poles::overdamped(q.1) {
                work.push((bi, b.mode, p, q));
            }
        }
    }
    let found: Vec<Option<Critical>> = work
        .par_iter()
        .map(|&(bi, mode, p, q)| {
            control.check()?;
            crossing(system, damping, p, q).map(|c| {
                c.map(|(speed, pole)| Critical {
                    speed,
                    branch: bi,
                    mode,
                    whirl: if pole.im >= 0.0 {
                        Whirl::Forward
                    } else {
                        Whirl::Backward
                    },
                    pole,
                    // The ratio of the nearer grid point (the crossing does not move it much).
                    whirl_ratio: if speed - p.0 <= q.0 - speed { p.2 } else { q.2 },
                })
            })
        })
        .collect::<Result<_, _>>()?;
    let mut out: Vec<Critical> = found.into_iter().flatten().collect();
    out.sort_by(|a, b| a.speed.total_cmp(&b.speed));
    Ok(out)
}

/// The crossing between the branch points `p` and `q` (speed, pole, whirl ratio): the speed and
/// the consistent pole there, or `None` where the branch's pole cannot be followed.
fn crossing(
    system: &RotorSystem,
    damping: &DampingModel,
    p: (f64, c64, f64),
    q: (f64, c64, f64),
) -> Result<Option<(f64, c64)>, AnalysisError> {
    let guess = |w: f64| {
        let t = (w - p.0) / (q.0 - p.0);
        p.1 + (q.1 - p.1) * t
    };
    // A forward crossing of the hysteretic model on its crossing problem (the rotating loss's
    // sign flips there: `analysis::criticals`).
    let forward = p.1.im >= 0.0;
    let consistent = |w: f64, s: c64| consistent_on(system, damping, w, s, forward);
    let mut last: Option<(f64, c64)> = None;
    let mut lost = false;
    let mut g = |w: f64| -> Result<f64, AnalysisError> {
        let Some(c) = consistent(w, guess(w))? else {
            lost = true;
            return Ok(0.0);
        };
        last = Some((w, c.s));
        Ok(c.s.im.abs() - w)
    };
    let gp = p.1.im.abs() - p.0;
    let gq = q.1.im.abs() - q.0;
    let w = brent(&mut g, (p.0, q.0), (gp, gq), TOLERANCE)?;
    if lost {
        return Ok(None);
    }
    // The pole at the root itself (Brent's last evaluation need not be there).
    Ok(match last {
        Some((at, s)) if at == w => Some((w, s)),
        _ => consistent(w, guess(w))?.map(|c| (w, c.s)),
    })
}
