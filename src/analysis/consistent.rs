//! Poles of a rotor on supports whose coefficients depend on the whirl frequency, each
//! consistent with the frequency it reads them at.
//!
//! With the supports read at whirl frequency `w` (`model::supports::grid`), the rotor is a
//! constant-coefficient model with poles `s(w)`. A pole of the rotor reads them at its own
//! frequency: `|Im s(w)| = w`. This is how the paper makes the hysteretic model's poles
//! consistent with the sign of their frequency (MODEL.md section 2), carried from a sign to a
//! frequency. Each pole is found from one of the model read synchronously (`w` = the speed,
//! what a table of one value per speed means) as a root of the scalar
//! `g(w) = |Im s(w)| - w`: a fixed-point step, then secant steps, where `s(w)` is the
//! eigenvalue of the model read at `w` nearest the last one found (shift-invert Arnoldi through
//! a sparse factor at it, `damping::large`). The fixed point alone converges at the rate
//! `|d Im s / d w|` (a seal's pole moves far less than its reading); the secant steps make it
//! superlinear.
//!
//! Each pole's residual is that of the rotor's own equation at it,
//! `||Z(s) x|| / ((|s|^2 ||M|| + |s| ||D|| + ||K||) ||x||)` with `Z` read at `|Im s|`
//! (`Problem::residual`): the error of consistency and of the eigensolve together.

use super::AnalysisError;
use crate::damping::{DampingError, large};
use crate::linalg::{arnoldi, c64};
use crate::model::damping::DampingModel;
use crate::system::RotorSystem;

/// `|g(w)|` relative to `|s|` at which a pole is consistent.
pub const TOLERANCE: f64 = 1e-10;

/// `|g(w)|` relative to `|s|` at which a pole whose steps stop short of [`TOLERANCE`] (each
/// eigenvalue is found to about 1e-10 of itself, `refine::TOLERANCE`) is still reported.
const SETTLED: f64 = 1e-8;

/// Steps allowed per pole.
const STEPS: usize = 40;

/// Radius searched about the last pole for the next, relative to its modulus.
const SEARCH: f64 = 0.25;

/// A pole consistent with the frequency its supports are read at.
#[derive(Debug, Clone)]
pub struct Consistent {
    pub s: c64,
    /// Its shape on the coordinates (unscaled).
    pub shape: Vec<c64>,
    /// The rotor's equation's residual at it (module docs).
    pub residual: f64,
    /// Eigensolves it took.
    pub solves: usize,
}

/// The eigenvalue of `system` read at `w` nearest `guess` (within [`SEARCH`] of it), with its
/// shape and residual; on the hysteretic model's crossing problem where `crossing`
/// ([`large::crossing_problem`]).
fn nearest_read(
    system: &RotorSystem,
    damping: &DampingModel,
    speed: f64,
    (w, crossing): (f64, bool),
    guess: c64,
) -> Result<Option<(c64, Vec<c64>, f64)>, AnalysisError> {
    let read = system.read(speed, w);
    let problems = match crossing {
        true => large::crossing_problem(&read, speed).map(|p| vec![p]),
        false => large::problems(&read, damping, None, speed),
    };
    let problems = problems.ok_or_else(|| {
        AnalysisError::Damping(DampingError::Unsolvable(
            "supports over whirl frequency are read by the viscous and hysteretic models".into(),
        ))
    })?;
    // Off the pole itself (the last step's, an eigenvalue of a nearby reading).
    let scale = guess.norm().max(1e-3);
    let shift = guess + c64::new(1e-9, 1.3e-9) * scale;
    let mut best: Option<(c64, Vec<c64>, f64)> = None;
    // The hysteretic model's problems whose signs the guess has first; the others where none
    // of those holds a pole near it with its own signs (a guess on the wrong side of the 1x
    // line, as near a crossing, where the rotating loss changes sign).
    let (first, rest): (Vec<_>, Vec<_>) = problems.iter().partition(|p| p.consistent(guess, speed));
    for p in first.into_iter().chain(rest) {
        if best.is_some() && !p.consistent(guess, speed) {
            break;
        }
        let op = p.shift_invert(shift)?;
        let size = op.states();
        let n = op.coordinates();
        let Some(found) = arnoldi::nearest_from(
            size,
            |b| op.solve(b),
            shift,
            SEARCH * scale,
            super::refine::TOLERANCE,
            (8, 0),
            size.min(120),
        )?
        else {
            continue;
        };
        for (t, z) in found.values.into_iter().zip(found.vectors) {
            if !p.consistent(t, speed) {
                continue;
            }
            let x = z[n..2 * n].to_vec();
            if best
                .as_ref()
                .is_none_or(|b| (t - guess).norm() < (b.0 - guess).norm())
            {
                let r = p.residual(t, &x);
                best = Some((t, x, r));
            }
        }
    }
    Ok(best)
}

/// The pole of `system` at `speed` consistent with its own frequency, continued from `s0` (a
/// pole of the model read synchronously); `None` where a step finds no pole near the last or
/// the steps do not settle.
pub fn consistent(
    system: &RotorSystem,
    damping: &DampingModel,
    speed: f64,
    s0: c64,
) -> Result<Option<Consistent>, AnalysisError> {
    consistent_on(system, damping, speed, s0, false)
}

/// The eigenvalues of `system` read at `|Im around|` within [`SEARCH`] of `around` (the
/// hysteretic model's with their own signs), nearest first: where a
/// continuation ended on a pole already found, the pole it missed is among them (two modes of
/// an anisotropic rotor a few rad/s apart, the one followed veering onto the other's mirror).
pub fn neighbours(
    system: &RotorSystem,
    damping: &DampingModel,
    speed: f64,
    around: c64,
) -> Result<Vec<c64>, AnalysisError> {
    let read = system.read(speed, around.im.abs());
    let Some(problems) = large::problems(&read, damping, None, speed) else {
        return Ok(vec![]);
    };
    let scale = around.norm().max(1e-3);
    let shift = around + c64::new(1e-9, 1.3e-9) * scale;
    let mut out = vec![];
    for p in &problems {
        let op = p.shift_invert(shift)?;
        let size = op.states();
        let found = arnoldi::nearest_from(
            size,
            |b| op.solve(b),
            shift,
            SEARCH * scale,
            super::refine::TOLERANCE,
            (8, 0),
            size.min(120),
        )?;
        out.extend(
            found
                .into_iter()
                .flat_map(|f| f.values)
                .filter(|&t| p.consistent(t, speed)),
        );
    }
    out.sort_by(|a, b| (a - around).norm().total_cmp(&(b - around).norm()));
    Ok(out)
}

/// [`consistent`] on the hysteretic model's crossing problem where `crossing` (a forward
/// crossing of the 1x line, where its rotating loss changes sign: `analysis::criticals`).
pub fn consistent_on(
    system: &RotorSystem,
    damping: &DampingModel,
    speed: f64,
    s0: c64,
    crossing: bool,
) -> Result<Option<Consistent>, AnalysisError> {
    let crossing = crossing && matches!(damping, DampingModel::Hysteretic);
    let mut solves = 0;
    let mut at = |w: f64, guess: c64| {
        solves += 1;
        nearest_read(system, damping, speed, (w, crossing), guess)
    };
    let w0 = s0.im.abs();
    let Some(first) = at(w0, s0)? else {
        return Ok(None);
    };
    let (mut a, mut fa) = (w0, first.0.im.abs() - w0);
    // The most nearly consistent pole found, and its |g|.
    let mut best = (fa.abs(), first.clone());
    let mut last = first;
    let mut w = last.0.im.abs();
    for _ in 0..STEPS {
        if (last.0.im.abs() - a).abs() <= TOLERANCE * last.0.norm() || w == a {
            break;
        }
        let Some(next) = at(w, last.0)? else {
            break;
        };
        let fw = next.0.im.abs() - w;
        if fw.abs() < best.0 {
            best = (fw.abs(), next.clone());
        }
        // Secant on g; the fixed point |Im s| where it has no slope to use.
        let secant = w - fw * (w - a) / (fw - fa);
        let following = if secant.is_finite() && fw != fa {
            secant.max(0.0)
        } else {
            next.0.im.abs()
        };
        (a, fa) = (w, fw);
        last = next;
        w = following;
    }
    // Within TOLERANCE, or where the eigensolves' own error keeps g from getting there, within
    // SETTLED (the residual reported says how close).
    let (g, (s, shape, residual)) = best;
    if g <= SETTLED * s.norm() {
        return Ok(Some(Consistent {
            s,
            shape,
            residual,
            solves,
        }));
    }
    Ok(None)
}
