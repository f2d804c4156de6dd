//! Critical speeds: where a branch's whirl frequency equals the spin speed, `|omega(Omega)| =
//! Omega`, forward and backward.
//!
//! The grid brackets each crossing (a sign change of `g(Omega) = |omega(Omega)| - Omega` between
//! two speeds where the branch is defined, across gaps too); Brent's method then closes it to
//! [`TOLERANCE`] relative on the model itself, each evaluation one eigensolve at the trial speed
//! and the pole continuing the branch (the one nearest the branch interpolated between the
//! evaluated speeds nearest the trial, on the member with `omega >= 0` in doubled coordinates).
//!
//! The hysteretic model has no pole (or two) in a narrow band around a crossing, because the
//! sign of the loss that sees the whirl relative to the rotor (`omega - Omega` forward, in
//! doubled coordinates `omega + Omega` backward) flips exactly there. At the crossing that
//! frequency is zero, and so is the loss term (`sgn 0 = 0`): the crossing is solved on the
//! linear problem with that sign set to 0, the mean of the two problems with it at +1 and -1.
//! Its pole there is the damping the mode has at its critical speed.
//!
//! A crossing whose pole has a damping ratio above [`CRITICALLY_DAMPED`] is critically damped in
//! API 684's sense (amplification factor `1 / (2 zeta)` below 2.5): flagged, not a critical
//! speed that needs a separation margin.

use std::borrow::Cow;

use super::AnalysisError;
use super::control::Control;
use super::poles::{self, Pole, Whirl, poles_at};
use super::roots::brent;
use crate::damping::{DampedModel, ModelKind};
use crate::linalg::{arnoldi, c64};
use crate::system::Layout;

/// Relative width to which a crossing is refined.
pub const TOLERANCE: f64 = 1e-12;

/// Damping ratio above which a mode is critically damped: API 684's amplification factor
/// `AF < 2.5`, with the single-mode `AF = 1 / (2 zeta)`.
pub const CRITICALLY_DAMPED: f64 = 0.2;

/// A crossing of a branch with the 1x line.
#[derive(Debug, Clone, PartialEq)]
pub struct Critical {
    /// Spin speed, rad/s.
    pub speed: f64,
    /// Index of the branch in the Campbell result.
    pub branch: usize,
    pub mode: usize,
    /// The whirl of the pole at the crossing.
    pub whirl: Whirl,
    /// The pole there (as `/v1/modal` reports it).
    pub pole: c64,
    pub whirl_ratio: f64,
}

impl Critical {
    pub fn log_decrement(&self) -> Option<f64> {
        poles::log_decrement(self.pole)
    }

    pub fn damping_ratio(&self) -> f64 {
        poles::damping_ratio(self.pole)
    }

    /// `AF = 1 / (2 zeta) < 2.5` (see [`CRITICALLY_DAMPED`]).
    pub fn critically_damped(&self) -> bool {
        self.damping_ratio() > CRITICALLY_DAMPED
    }
}

/// The member of a mirror pair that is continuous along a branch.
fn matched(s: c64, doubled: bool) -> c64 {
    if doubled && s.im < 0.0 { s.conj() } else { s }
}

/// A branch as the crossings need it: its mode number, and its pole (as `/v1/modal` reports
/// it) and whirl ratio at each speed.
pub struct Curve<'a> {
    pub mode: usize,
    pub poles: &'a [Option<c64>],
    pub whirl_ratio: &'a [Option<f64>],
}

/// Every crossing of every branch over the grid `speeds`, refined on `model`, by speed.
pub fn criticals(
    model: &DampedModel,
    speeds: &[f64],
    branches: &[Curve],
    control: &Control,
) -> Result<Vec<Critical>, AnalysisError> {
    crossings(model, speeds, branches, 1.0, control)
}

/// Every crossing of every branch with the line `|omega| = slope Omega` (an excitation of
/// order `slope` of the speed), refined on `model`, by speed.
pub fn crossings(
    model: &DampedModel,
    speeds: &[f64],
    branches: &[Curve],
    slope: f64,
    control: &Control,
) -> Result<Vec<Critical>, AnalysisError> {
    let doubled = model.layout == Layout::Doubled;
    let mut out = vec![];
    for (bi, b) in branches.iter().enumerate() {
        let pts: Vec<Point> = speeds
            .iter()
            .zip(b.poles.iter().zip(b.whirl_ratio))
            .filter_map(|(&w, (p, r))| p.map(|s| (w, s, r.unwrap_or(0.0))))
            .collect();
        let g = |(w, s, _): Point| s.im.abs() - slope * w;
        for pair in pts.windows(2) {
            let (p, q) = (pair[0], pair[1]);
            let (gp, gq) = (g(p), g(q));
            // An overdamped pole (at rest: on the 1x line by round-off) crosses nothing.
            if !(gp * gq < 0.0 || (gp == 0.0 && p.0 > 0.0))
                || poles::overdamped(p.1)
                || poles::overdamped(q.1)
            {
                continue;
            }
            control.check()?;
            let c = refine(model, doubled, slope, p, q, control)?;
            if c.0 <= 0.0 {
                continue;
            }
            out.push(critical(c, bi, b.mode));
        }
        if let Some(&last) = pts.last()
            && g(last) == 0.0
            && last.0 > 0.0
        {
            let c = refine(model, doubled, slope, last, last, control)?;
            out.push(critical(c, bi, b.mode));
        }
    }
    out.sort_by(|a, b| a.speed.total_cmp(&b.speed));
    Ok(out)
}

/// A refined crossing `(speed, pole, whirl ratio)` of branch `branch` (mode `mode`).
fn critical(c: (f64, c64, f64), branch: usize, mode: usize) -> Critical {
    Critical {
        speed: c.0,
        branch,
        mode,
        whirl: if c.1.im >= 0.0 {
            Whirl::Forward
        } else {
            Whirl::Backward
        },
        pole: c.1,
        whirl_ratio: c.2,
    }
}

/// The model a crossing is solved on: the model itself, or for the hysteretic model the linear
/// problem with the vanishing sign at 0 (module docs). `s` is the branch's matched member
/// (`omega >= 0` when doubled): a forward crossing when `omega > 0`.
fn crossing_model<'a>(model: &'a DampedModel, s: c64) -> Cow<'a, DampedModel> {
    let ModelKind::Hysteretic(signed) = &model.kind else {
        return Cow::Borrowed(model);
    };
    if s.im < 0.0 {
        // Backward in the coordinates `r` alone: `omega - Omega < 0` throughout, no gap.
        return Cow::Borrowed(model);
    }
    // Forward: the rotating sign `b` vanishes; `a = +1` (and `c = +1` when doubled).
    let side = |b: f64| {
        signed
            .iter()
            .find(|m| m.nonrotating > 0.0 && m.rotating == b && m.counter >= 0.0)
    };
    match (side(1.0), side(-1.0)) {
        (Some(up), Some(down)) => Cow::Owned(DampedModel {
            kind: ModelKind::Linear(Box::new(up.model.mean(&down.model))),
            basis: model.basis.clone(),
            layout: model.layout,
            natural_frequencies: model.natural_frequencies.clone(),
        }),
        _ => Cow::Borrowed(model),
    }
}

/// A branch point: speed, pole as reported, whirl ratio.
type Point = (f64, c64, f64);

/// Evaluates `g` on the crossing model, following the branch.
struct Follower<'a> {
    model: Cow<'a, DampedModel>,
    doubled: bool,
    /// Evaluated points (speed, matched pole).
    known: Vec<(f64, c64)>,
    /// The bracket's extent in `s`: how far the branch moves over it.
    span: f64,
    last: Option<Point>,
    /// Of the line crossed, `|omega| = slope Omega`.
    slope: f64,
}

impl Follower<'_> {
    /// `|omega| - Omega` of the branch's pole at `w`, or `None` where the model has no pole
    /// continuing it.
    fn eval(&mut self, w: f64, control: &Control) -> Result<Option<f64>, AnalysisError> {
        control.check()?;
        let pred = predict(&self.known, w);
        let doubled = self.doubled;
        let dist = |s: c64| (matched(s, doubled) - pred).norm();
        // A pole farther from the prediction than the branch moves over the bracket is not
        // the branch's.
        let radius = 4.0 * self.span.max(1e-3 * pred.norm());
        let Some(best) = nearest(&self.model, w, pred, radius)? else {
            return Ok(None);
        };
        if dist(best.s) > radius {
            return Ok(None);
        }
        self.known.push((w, matched(best.s, doubled)));
        // Reported as `/v1/modal` does: in doubled coordinates the member whose `r` part is the
        // larger (the crossing model of the hysteretic model has no mirror pairs to choose from).
        let reported = if doubled {
            let m = matched(best.s, doubled);
            if best.whirl_ratio < 0.0 { m.conj() } else { m }
        } else {
            best.s
        };
        self.last = Some((w, reported, best.whirl_ratio));
        Ok(Some(best.s.im.abs() - self.slope * w))
    }
}

/// The rotor pole of `model` at `w` nearest `pred` (matched members): by shift-invert Arnoldi
/// about `pred` within `radius` where the model is one linear problem (a few solves with one
/// `n x n` factor instead of a dense eigensolve: the refinement of a crossing is about ten such
/// evaluations), else, or where Arnoldi declines, from the dense pole set.
fn nearest(
    model: &DampedModel,
    w: f64,
    pred: c64,
    radius: f64,
) -> Result<Option<Pole>, AnalysisError> {
    let doubled = model.layout == Layout::Doubled;
    let dist = |s: c64| (matched(s, doubled) - pred).norm();
    if let ModelKind::Linear(m) = &model.kind {
        // Off the prediction itself, which may be an eigenvalue to round-off.
        let sigma = pred + c64::new(0.0113, 0.0137) * (0.01 * radius);
        let op = m.shift_invert(w, sigma);
        let size = m.size();
        let found = arnoldi::nearest(
            size,
            |b| op.solve(b),
            sigma,
            radius,
            ARNOLDI_TOLERANCE,
            size / 2,
        )?;
        if let Some(found) = found {
            let n = m.n();
            return Ok(found
                .values
                .iter()
                .zip(&found.vectors)
                .filter(|(_, z)| {
                    m.p() == 0 || m.rotor_energy_fraction(&z[n..2 * n], &z[2 * n..]) >= 0.5
                })
                .min_by(|a, b| dist(*a.0).total_cmp(&dist(*b.0)))
                .map(|(s, z)| poles::pole_of_state(*s, z, m, doubled)));
        }
    }
    let set = poles_at(model, w)?;
    Ok(set
        .rotor
        .into_iter()
        .min_by(|a, b| dist(a.s).total_cmp(&dist(b.s))))
}

/// Residual of an accepted Ritz value, relative to `|s|`: far below the 1e-12 of the roots.
const ARNOLDI_TOLERANCE: f64 = 1e-13;

/// The branch's matched pole at `w`, linear between the two evaluated speeds nearest it.
fn predict(known: &[(f64, c64)], w: f64) -> c64 {
    let mut near: Vec<&(f64, c64)> = known.iter().collect();
    near.sort_by(|a, b| (a.0 - w).abs().total_cmp(&(b.0 - w).abs()));
    match near[..] {
        [a, b, ..] if a.0 != b.0 => a.1 + (b.1 - a.1) * ((w - a.0) / (b.0 - a.0)),
        [a, ..] => a.1,
        [] => c64::new(0.0, 0.0),
    }
}

/// The crossing between the branch points `p` and `q` (`p == q`: a grid point on the line),
/// refined on the model; the linear interpolation of the grid where the model gives no pole
/// continuing the branch.
fn refine(
    model: &DampedModel,
    doubled: bool,
    slope: f64,
    p: Point,
    q: Point,
    control: &Control,
) -> Result<Point, AnalysisError> {
    let g = |x: &Point| x.1.im.abs() - slope * x.0;
    let interpolated = || -> Point {
        let (gp, gq) = (g(&p), g(&q));
        let t = if gp == gq { 0.0 } else { gp / (gp - gq) };
        (
            p.0 + (q.0 - p.0) * t,
            p.1 + (q.1 - p.1) * t,
            p.2 + (q.2 - p.2) * t,
        )
    };
    let mut f = Follower {
        model: crossing_model(model, matched(p.1, doubled)),
        doubled,
        known: vec![(p.0, matched(p.1, doubled)), (q.0, matched(q.1, doubled))],
        span: (matched(p.1, doubled) - matched(q.1, doubled)).norm(),
        last: None,
        slope,
    };
    // The ends on the crossing model (for the hysteretic model they differ from the branch's).
    let fp = f.eval(p.0, control)?;
    if p.0 == q.0 || fp == Some(0.0) {
        return Ok(f.last.unwrap_or(p));
    }
    let fq = f.eval(q.0, control)?;
    let (Some(fp), Some(fq)) = (fp, fq) else {
        return Ok(interpolated());
    };
    if fp * fq > 0.0 {
        return Ok(interpolated());
    }
    let mut lost = false;
    let root = brent(
        |w| match f.eval(w, control)? {
            Some(v) => Ok::<_, AnalysisError>(v),
            None => {
                lost = true;
                Ok(0.0)
            }
        },
        (p.0, q.0),
        (fp, fq),
        TOLERANCE,
    )?;
    if lost {
        return Ok(interpolated());
    }
    if f.last.is_none_or(|l| l.0 != root) {
        f.eval(root, control)?;
    }
    Ok(f.last.filter(|l| l.0 == root).unwrap_or_else(interpolated))
}
