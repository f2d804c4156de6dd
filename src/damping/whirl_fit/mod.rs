//! Supports over whirl frequency in the time domain: each table's dynamic stiffness fitted by
//! Maxwell branches, the nonviscous model's idea carried from a constant loss factor to a
//! tabulated complex stiffness.
//!
//! At spin speed `W` each coefficient `ab` (`xx`, `xy`, `yx`, `yy`) of a support has the
//! dynamic stiffness `H(w) = K(w) + i w C(w) - w^2 M(w)` at whirl frequency `w >= 0` (the table
//! read as `grid.rs` reads it). It is replaced by
//!
//! ```text
//! H~(w) = K0 + i w C0 - w^2 M0 + sum_j G_j i w / (i w + d_j)
//! ```
//!
//! `M0 = M(0)` (a branch has no mass), the rates `d_j` geometric over the table's band widened
//! by 2 each way (`[w_1 / 2, 2 w_F]`, `w_1` its first nonzero frequency), and `K0`, `C0`, `G_j`
//! by least squares over the samples of `design.rs` (the table's frequencies, three readings
//! between each two, and 40 per decade of the band), each weighted by the support's direct
//! `|H|` there, so that the fit is as good relative to the table at the rotor's frequencies as
//! at the top of the band; real and imaginary parts alike. Anchors (the spin speed of a time
//! response, whose unbalance whirls there) are held to the table. The branches are added one
//! at a time until the largest deviation, measured at the samples and between them relative to
//! the direct `|H|` at each, is at most the target, or [`MAX_BRANCHES`] are used.
//!
//! Passivity: on the direct coefficients `C0 >= 0` and `G_j >= 0` (each branch a spring and a
//! damper in series; Lawson-Hanson), and the symmetric part of `C0` and of every `G_j` kept
//! positive semidefinite (a symmetric cross term larger than the direct terms allow is
//! shrunk to their geometric mean). The fitted support's damping, the symmetric part of
//! `Im H~`, is then nonnegative at every frequency; its skew part (cross-coupling that feeds
//! forward whirl) is the table's, fitted like the rest. A table that is not what passive,
//! causal branches give (stiffness rising while the damping falls) keeps the deviation it is
//! left with; the time response compares the fitted model's poles with the rotor's own
//! (`analysis::time::fit_poles`).
//!
//! Between the table's speeds the fitted coefficients are linear in the speed, as every table
//! over speed is in the state model. Past the band the fitted support follows its branches
//! (`K0 + sum G_j` and `C0` as `w` grows), not the table's straight continuation.

mod design;

use super::DampingError;
use crate::linalg;
use crate::model::supports::fitted::Fitted;
use crate::model::supports::{Coefficients, GeneralSupport, Law, Matrix2};
use crate::system::RotorSystem;
use design::Design;

pub use crate::model::supports::fitted::MAX_BRANCHES;

/// Default target: the largest deviation over the band, relative to the support's direct
/// dynamic stiffness at each frequency.
pub const TARGET: f64 = 1e-3;

/// How to fit.
#[derive(Debug, Clone)]
pub struct FitOptions {
    /// The rates `d_j` (1/s), instead of choosing them.
    pub rates: Option<Vec<f64>>,
    pub target: f64,
    pub max_branches: usize,
    /// Whirl frequencies (rad/s) the fit is held to (`design::ANCHOR`).
    pub anchors: Vec<f64>,
}

impl Default for FitOptions {
    fn default() -> Self {
        FitOptions {
            rates: None,
            target: TARGET,
            max_branches: MAX_BRANCHES,
            anchors: vec![],
        }
    }
}

/// How well one support's table is fitted.
#[derive(Debug, Clone, PartialEq)]
pub struct SupportFit {
    /// Its path in the request (`rotor.supports[i]`, `rotor.seals[i]`).
    pub path: String,
    /// The rates `d_j`, 1/s.
    pub rates: Vec<f64>,
    /// The table's frequencies, first and last, rad/s.
    pub band: [f64; 2],
    /// Per coefficient `xx`, `xy`, `yx`, `yy`: the largest `|H~ - H|` over the band and the
    /// table's speeds, relative to the support's direct `|H|` (`max(|H_xx|, |H_yy|)`) at that
    /// frequency and speed.
    pub deviation: [f64; 4],
    /// The speeds the fit was made at (none: the table does not depend on the speed).
    pub speeds: Vec<f64>,
    /// Whether a symmetric cross term had to be shrunk to keep the fit passive.
    pub shrunk: bool,
}

impl SupportFit {
    /// The largest deviation over the four coefficients.
    pub fn max_deviation(&self) -> f64 {
        self.deviation.iter().copied().fold(0.0, f64::max)
    }
}

/// `K0`, `C0` and each `G_j` by coefficient (xx, xy, yx, yy).
type Parts = ([f64; 4], [f64; 4], Vec<[f64; 4]>);

/// One support's fit at one speed.
struct AtSpeed {
    base: Coefficients,
    branches: Vec<Matrix2>,
    deviation: [f64; 4],
    shrunk: bool,
}

/// `system` with every support over whirl frequency replaced by its fit (the support's law a
/// table over the speeds of the fit, or constant, with its branches beside it), and how well
/// each was fitted. `stop` is asked before each speed's fit: a table of 512 speeds by 512
/// frequencies takes minutes, and a cancelled task stops there (`None`).
pub fn fit(
    system: &RotorSystem,
    options: &FitOptions,
    stop: &dyn Fn() -> bool,
) -> Result<Option<(RotorSystem, Vec<SupportFit>)>, DampingError> {
    if let Some(p) = system.supports.iter().find(|p| p.support.ross()) {
        return Err(DampingError::Unsolvable(format!(
            "{}: a table on ROSS's curves is scheduled on one model, which a support over whirl \
             frequency cannot join in the time domain (use \"linear\")",
            p.support.path()
        )));
    }
    // Every speed of every table: the state model is realized there.
    let mut speeds: Vec<f64> = system
        .supports
        .iter()
        .flat_map(|p| p.support.tabulated_speeds().iter().copied())
        .collect();
    speeds.sort_by(f64::total_cmp);
    speeds.dedup();
    let mut out = system.clone();
    let mut fits = vec![];
    for p in &mut out.supports {
        let Some(grid) = p.support.grid() else {
            continue;
        };
        let at: Vec<f64> = if speeds.is_empty() {
            vec![0.0]
        } else {
            speeds.clone()
        };
        let freqs = &grid.frequencies;
        let hi = freqs[freqs.len() - 1];
        let lo = freqs.iter().copied().find(|&w| w > 0.0).unwrap_or(hi);
        let samples = design::samples(freqs);
        let checks = design::checks(&samples);
        let isotropic = grid.isotropic();
        // The table read at every speed once (at the samples and anchors, and where the fit is
        // measured; its mass at rest), whatever the rates.
        let mut tables: Vec<Read> = vec![];
        for &w in &at {
            if stop() {
                return Ok(None);
            }
            let read = |f: &[f64]| f.iter().map(|&f| grid.at(w, f)).collect::<Vec<_>>();
            let fitted: Vec<f64> = samples.iter().chain(&options.anchors).copied().collect();
            tables.push(Read {
                samples: read(&fitted),
                checks: read(&checks),
                m0: grid.at(w, 0.0).m,
            });
        }
        // The fit at every speed with `rates`; `None` once stopped.
        let all = |rates: &[f64]| -> Result<Option<Vec<AtSpeed>>, DampingError> {
            let design = Design::new(&samples, &options.anchors, rates);
            let mut out = vec![];
            for read in &tables {
                if stop() {
                    return Ok(None);
                }
                out.push(fit_at(&design, read, &checks, isotropic)?);
            }
            Ok(Some(out))
        };
        let fitted: Vec<AtSpeed> = match &options.rates {
            Some(rates) => match all(rates)? {
                Some(f) => f,
                None => return Ok(None),
            },
            None => {
                // Branches added until every speed meets the target.
                let mut m = 1;
                loop {
                    let rates = geometric(lo / 2.0, 2.0 * hi.max(lo), m);
                    let Some(f) = all(&rates)? else {
                        return Ok(None);
                    };
                    let worst = f.iter().flat_map(|a| a.deviation).fold(0.0, f64::max);
                    if worst <= options.target || m >= options.max_branches {
                        break f;
                    }
                    m += 1;
                }
            }
        };
        let rates = match &options.rates {
            Some(r) => r.clone(),
            None => geometric(lo / 2.0, 2.0 * hi.max(lo), fitted[0].branches.len()),
        };
        // A branch held at zero at every speed adds only a decoupled state: dropped.
        let kept: Vec<usize> = (0..rates.len())
            .filter(|&j| fitted.iter().any(|a| !a.branches[j].is_zero()))
            .collect();
        let rates: Vec<f64> = kept.iter().map(|&j| rates[j]).collect();
        let mut deviation = [0.0; 4];
        for a in &fitted {
            for (d, e) in deviation.iter_mut().zip(a.deviation) {
                *d = f64::max(*d, e);
            }
        }
        fits.push(SupportFit {
            path: p.support.path(),
            rates: rates.clone(),
            band: [freqs[0], hi],
            deviation,
            speeds: speeds.clone(),
            shrunk: fitted.iter().any(|a| a.shrunk),
        });
        let law = match speeds.is_empty() {
            true => Law::Constant(fitted[0].base),
            false => Law::Table {
                speeds: speeds.clone(),
                values: fitted.iter().map(|a| a.base).collect(),
                ross: None,
            },
        };
        p.support = GeneralSupport {
            law,
            branches: Some(Box::new(Fitted {
                rates,
                speeds: speeds.clone(),
                stiffness: fitted
                    .into_iter()
                    .map(|a| kept.iter().map(|&j| a.branches[j]).collect())
                    .collect(),
            })),
            ..p.support.clone()
        };
    }
    Ok(Some((out, fits)))
}

/// The support over whirl frequency of `system` and the coefficient (`xx`, `xy`, `yx`, `yy`)
/// whose fit in `fitted` (the same system fitted) is furthest from its table at spin speed
/// `speed` and whirl frequency `w`, and how far, relative to the support's direct `|H|` there:
/// what a pole of the fitted model at `w` reads that the rotor's does not.
pub fn worst_at(
    system: &RotorSystem,
    fitted: &RotorSystem,
    speed: f64,
    w: f64,
) -> Option<(String, &'static str, f64)> {
    let mut worst: Option<(String, &'static str, f64)> = None;
    for (p, f) in system.supports.iter().zip(&fitted.supports) {
        let (Some(grid), Some(branches)) = (p.support.grid(), &f.support.branches) else {
            continue;
        };
        let table = [grid.at(speed, w)];
        let base = f.support.at(speed);
        let d = design::deviation(&[w], &table, &base, &branches.at(speed), &branches.rates);
        for (e, name) in ["xx", "xy", "yx", "yy"].into_iter().enumerate() {
            if worst.as_ref().is_none_or(|x| d[e] > x.2) {
                worst = Some((p.support.path(), name, d[e]));
            }
        }
    }
    worst
}

/// `m` rates geometric from `lo` to `hi` (one: their geometric mean).
fn geometric(lo: f64, hi: f64, m: usize) -> Vec<f64> {
    if m == 1 {
        return vec![(lo * hi).sqrt()];
    }
    let r = (hi / lo).ln() / (m - 1) as f64;
    (0..m).map(|j| lo * (r * j as f64).exp()).collect()
}

/// One support's table read at one speed.
struct Read {
    /// At the design's samples and anchors.
    samples: Vec<Coefficients>,
    /// Where the fit is measured (`design::checks`).
    checks: Vec<Coefficients>,
    /// Its mass at rest.
    m0: Matrix2,
}

/// The fit at one speed of the table `read`, measured at `checks`.
fn fit_at(
    design: &Design,
    read: &Read,
    checks: &[f64],
    isotropic: bool,
) -> Result<AtSpeed, DampingError> {
    let rates = design.rates;
    let p = rates.len();
    // Each sample weighed by the support's direct |H| there: a relative fit.
    let scale = design::scales(&read.samples, &design.samples);
    let (a, norms) = design.weighted(&scale);
    // Every coefficient free first; kept if the fitted support is passive, else the direct
    // ones again with C0, G_j >= 0 and the symmetric parts made semidefinite.
    let solve = |bounded: bool| -> Result<Parts, DampingError> {
        let (mut k0, mut c0) = ([0.0; 4], [0.0; 4]);
        let mut g = vec![[0.0; 4]; p];
        let solved: &[usize] = if isotropic { &[0, 1] } else { &[0, 1, 2, 3] };
        for &e in solved {
            let direct = e == 0 || e == 3;
            let constrained: Vec<bool> = (0..p + 2).map(|j| bounded && direct && j > 0).collect();
            let b = design.target(&read.samples, &read.m0, e, &scale);
            let x = linalg::bounded_least_squares(&a, &b, &constrained)?;
            k0[e] = x[0] / norms[0];
            c0[e] = x[1] / norms[1];
            for j in 0..p {
                g[j][e] = x[2 + j] / norms[2 + j];
            }
        }
        if isotropic {
            (k0[3], k0[2], c0[3], c0[2]) = (k0[0], -k0[1], c0[0], -c0[1]);
            for gj in &mut g {
                (gj[3], gj[2]) = (gj[0], -gj[1]);
            }
        }
        Ok((k0, c0, g))
    };
    let (mut k0, mut c0, mut g) = solve(false)?;
    let mut shrunk = false;
    if !passive(&c0, &g, rates) {
        (k0, c0, g) = solve(true)?;
        let mut psd = |v: &mut [f64; 4]| {
            let s = 0.5 * (v[1] + v[2]);
            let limit = (v[0].max(0.0) * v[3].max(0.0)).sqrt();
            if s.abs() > limit {
                let change = s.signum() * limit - s;
                v[1] += change;
                v[2] += change;
                shrunk = true;
            }
        };
        psd(&mut c0);
        for gj in &mut g {
            psd(gj);
        }
    }
    let matrix = |v: [f64; 4]| Matrix2 {
        xx: v[0],
        xy: v[1],
        yx: v[2],
        yy: v[3],
    };
    let base = Coefficients {
        k: matrix(k0),
        c: matrix(c0),
        m: read.m0,
    };
    let branches: Vec<Matrix2> = g.into_iter().map(matrix).collect();
    let deviation = design::deviation(checks, &read.checks, &base, &branches, rates);
    Ok(AtSpeed {
        base,
        branches,
        deviation,
        shrunk,
    })
}

/// Whether the fitted damping `C0 + sum_j G_j d_j / (w^2 + d_j^2)` (the symmetric part of
/// `Im H~ / w`) is positive semidefinite at every `w >= 0`: at 0, at infinity (`C0`), and on
/// a grid 100 times finer than the rates and two decades past them each way, where a sum of
/// Lorentzians changes.
fn passive(c0: &[f64; 4], g: &[[f64; 4]], rates: &[f64]) -> bool {
    let damping = |w: f64| -> [f64; 4] {
        let mut c = *c0;
        for (gj, &d) in g.iter().zip(rates) {
            let f = d / (w * w + d * d);
            for e in 0..4 {
                c[e] += gj[e] * f;
            }
        }
        c
    };
    let ok = |c: [f64; 4]| {
        let s = 0.5 * (c[1] + c[2]);
        let size = c[0].abs() + c[3].abs() + s.abs();
        let tol = 1e-12 * size;
        c[0] >= -tol && c[3] >= -tol && c[0] * c[3] - s * s >= -tol * size
    };
    if !ok(*c0) || !ok(damping(0.0)) {
        return false;
    }
    let (Some(lo), Some(hi)) = (rates.first(), rates.last()) else {
        return true;
    };
    let (lo, hi) = (lo / 100.0, hi * 100.0);
    let count = 100 * rates.len().max(4);
    (0..=count).all(|k| ok(damping(lo * (hi / lo).powf(k as f64 / count as f64))))
}

#[cfg(test)]
mod tests;
