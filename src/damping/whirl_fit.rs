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
//! by least squares over the table's frequencies and three readings between each two, so the
//! fit follows the table's own interpolation; real and imaginary parts alike, in N/m. The
//! branches are added one at a time until the largest deviation over the band, relative to the
//! support's largest direct `|H|` there, is at most the target, or [`MAX_BRANCHES`] are used.
//!
//! Passivity: on the direct coefficients `C0 >= 0` and `G_j >= 0` (each branch a spring and a
//! damper in series; Lawson-Hanson), and the symmetric part of `C0` and of every `G_j` kept
//! positive semidefinite (a symmetric cross term larger than the direct terms allow is
//! shrunk to their geometric mean). The fitted support's damping, the symmetric part of
//! `Im H~`, is then nonnegative at every frequency; its skew part (cross-coupling that feeds
//! forward whirl) is the table's, fitted like the rest.
//!
//! Between the table's speeds the fitted coefficients are linear in the speed, as every table
//! over speed is in the state model. Past the band the fitted support follows its branches
//! (`K0 + sum G_j` and `C0` as `w` grows), not the table's straight continuation.

use super::DampingError;
use crate::linalg::{self, RMat};
use crate::model::supports::fitted::Fitted;
use crate::model::supports::{Coefficients, GeneralSupport, Law, Matrix2};
use crate::system::RotorSystem;

pub use crate::model::supports::fitted::MAX_BRANCHES;

/// Default target: the largest deviation over the band, relative to the support's largest
/// direct dynamic stiffness there.
pub const TARGET: f64 = 1e-3;

/// How to fit.
#[derive(Debug, Clone)]
pub struct FitOptions {
    /// The rates `d_j` (1/s), instead of choosing them.
    pub rates: Option<Vec<f64>>,
    pub target: f64,
    pub max_branches: usize,
}

impl Default for FitOptions {
    fn default() -> Self {
        FitOptions {
            rates: None,
            target: TARGET,
            max_branches: MAX_BRANCHES,
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
    /// table's speeds, relative to the support's largest direct `|H|` over the band at that
    /// speed.
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
        let samples = samples(freqs);
        let isotropic = grid.isotropic();
        // The table read at every speed once (and its mass at rest), whatever the rates.
        let mut tables: Vec<(Vec<Coefficients>, Matrix2)> = vec![];
        for &w in &at {
            if stop() {
                return Ok(None);
            }
            let table = samples.iter().map(|&f| grid.at(w, f)).collect();
            tables.push((table, grid.at(w, 0.0).m));
        }
        // The fit at every speed with `rates`; `None` once stopped.
        let all = |rates: &[f64]| -> Result<Option<Vec<AtSpeed>>, DampingError> {
            let design = Design::new(&samples, rates);
            let mut out = vec![];
            for (table, m0) in &tables {
                if stop() {
                    return Ok(None);
                }
                out.push(fit_at(&design, table, *m0, isotropic)?);
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

/// `m` rates geometric from `lo` to `hi` (one: their geometric mean).
fn geometric(lo: f64, hi: f64, m: usize) -> Vec<f64> {
    if m == 1 {
        return vec![(lo * hi).sqrt()];
    }
    let r = (hi / lo).ln() / (m - 1) as f64;
    (0..m).map(|j| lo * (r * j as f64).exp()).collect()
}

/// The table's frequencies and three points between each two.
fn samples(freqs: &[f64]) -> Vec<f64> {
    let mut out = vec![freqs[0]];
    for w in freqs.windows(2) {
        for k in 1..=4 {
            out.push(w[0] + (w[1] - w[0]) * k as f64 / 4.0);
        }
    }
    out
}

/// The least-squares matrix of a fit over `samples` with `rates`, the same at every speed and
/// for every coefficient: rows Re and Im at each sample, columns `K0`, `C0`, `G_j`, each
/// scaled to unit length (`K0` in N/m beside `C0` in N s/m).
struct Design<'a> {
    samples: &'a [f64],
    rates: &'a [f64],
    scaled: RMat,
    scale: Vec<f64>,
}

impl<'a> Design<'a> {
    fn new(samples: &'a [f64], rates: &'a [f64]) -> Self {
        let p = rates.len();
        let rows = 2 * samples.len();
        let mut a = RMat::zeros(rows, p + 2);
        for (i, &w) in samples.iter().enumerate() {
            a[(2 * i, 0)] = 1.0;
            a[(2 * i + 1, 1)] = w;
            for (j, &d) in rates.iter().enumerate() {
                let den = w * w + d * d;
                a[(2 * i, 2 + j)] = w * w / den;
                a[(2 * i + 1, 2 + j)] = w * d / den;
            }
        }
        let scale: Vec<f64> = (0..p + 2)
            .map(|j| {
                let s = (0..rows).map(|i| a[(i, j)].powi(2)).sum::<f64>().sqrt();
                if s > 0.0 { s } else { 1.0 }
            })
            .collect();
        let scaled = RMat::from_fn(rows, p + 2, |i, j| a[(i, j)] / scale[j]);
        Design {
            samples,
            rates,
            scaled,
            scale,
        }
    }
}

/// The fit at one speed of `table` read at the design's samples, its mass `m0` at rest.
fn fit_at(
    design: &Design,
    table: &[Coefficients],
    m0: Matrix2,
    isotropic: bool,
) -> Result<AtSpeed, DampingError> {
    let Design {
        samples,
        rates,
        scaled,
        scale,
    } = design;
    let p = rates.len();
    let get = |m: &Matrix2, e: usize| [m.xx, m.xy, m.yx, m.yy][e];
    let target = |e: usize| -> Vec<f64> {
        samples
            .iter()
            .zip(table)
            .flat_map(|(&w, c)| {
                let k = get(&c.k, e) - w * w * (get(&c.m, e) - get(&m0, e));
                [k, w * get(&c.c, e)]
            })
            .collect()
    };
    // Every coefficient free first; kept if the fitted support is passive, else the direct
    // ones again with C0, G_j >= 0 and the symmetric parts made semidefinite.
    let solve = |bounded: bool| -> Result<Parts, DampingError> {
        let (mut k0, mut c0) = ([0.0; 4], [0.0; 4]);
        let mut g = vec![[0.0; 4]; p];
        let solved: &[usize] = if isotropic { &[0, 1] } else { &[0, 1, 2, 3] };
        for &e in solved {
            let direct = e == 0 || e == 3;
            let constrained: Vec<bool> = (0..p + 2).map(|j| bounded && direct && j > 0).collect();
            let x = linalg::bounded_least_squares(scaled, &target(e), &constrained)?;
            k0[e] = x[0] / scale[0];
            c0[e] = x[1] / scale[1];
            for j in 0..p {
                g[j][e] = x[2 + j] / scale[2 + j];
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
    // Deviations over the samples, relative to the largest direct |H|.
    let mut worst = [0.0; 4];
    let mut direct = 0.0_f64;
    for (&w, c) in samples.iter().zip(table) {
        for e in 0..4 {
            let h = linalg::c64::new(get(&c.k, e) - w * w * get(&c.m, e), w * get(&c.c, e));
            let mut f = linalg::c64::new(k0[e] - w * w * get(&m0, e), w * c0[e]);
            for (j, &d) in rates.iter().enumerate() {
                let iw = linalg::c64::new(0.0, w);
                f += iw / (iw + d) * g[j][e];
            }
            worst[e] = f64::max(worst[e], (f - h).norm());
            if e == 0 || e == 3 {
                direct = direct.max(h.norm());
            }
        }
    }
    if direct == 0.0 {
        direct = 1.0;
    }
    Ok(AtSpeed {
        base: Coefficients {
            k: matrix(k0),
            c: matrix(c0),
            m: m0,
        },
        branches: g.into_iter().map(matrix).collect(),
        deviation: worst.map(|d| d / direct),
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
mod tests {
    use super::*;

    /// `H(w) = K0 + i w C0 + G i w / (i w + d)` per coefficient, as a table would read it.
    fn maxwell(k0: Matrix2, c0: Matrix2, g: Matrix2, d: f64, w: f64) -> Coefficients {
        let e = |k: f64, c: f64, g: f64| {
            // Re: k + g w^2 / (w^2 + d^2); Im / w: c + g d / (w^2 + d^2).
            let den = w * w + d * d;
            (k + g * w * w / den, c + g * d / den)
        };
        let (kxx, cxx) = e(k0.xx, c0.xx, g.xx);
        let (kxy, cxy) = e(k0.xy, c0.xy, g.xy);
        let (kyx, cyx) = e(k0.yx, c0.yx, g.yx);
        let (kyy, cyy) = e(k0.yy, c0.yy, g.yy);
        Coefficients {
            k: Matrix2 {
                xx: kxx,
                xy: kxy,
                yx: kyx,
                yy: kyy,
            },
            c: Matrix2 {
                xx: cxx,
                xy: cxy,
                yx: cyx,
                yy: cyy,
            },
            m: Matrix2::default(),
        }
    }

    #[test]
    fn a_table_of_one_maxwell_branch_is_recovered_at_its_rate() {
        // N/m, N s/m, N/m, 1/s: an anisotropic support with skew cross-coupling in K0 and a
        // branch with a symmetric cross term inside its direct terms' limit.
        let k0 = Matrix2 {
            xx: 2e5,
            xy: 4e4,
            yx: -4e4,
            yy: 3e5,
        };
        let c0 = Matrix2 {
            xx: 100.0,
            xy: 0.0,
            yx: 0.0,
            yy: 150.0,
        };
        let g = Matrix2 {
            xx: 3e5,
            xy: 5e4,
            yx: 5e4,
            yy: 2e5,
        };
        let d = 300.0;
        let w: Vec<f64> = (0..=40).map(|i| 25.0 * i as f64).collect();
        let table: Vec<Coefficients> = w.iter().map(|&w| maxwell(k0, c0, g, d, w)).collect();
        let f = fit_at(&Design::new(&w, &[d]), &table, Matrix2::default(), false).unwrap();
        let close = |a: &Matrix2, b: &Matrix2, scale: f64| {
            [(a.xx, b.xx), (a.xy, b.xy), (a.yx, b.yx), (a.yy, b.yy)]
                .iter()
                .all(|(x, y)| (x - y).abs() <= 1e-9 * scale)
        };
        assert!(close(&f.base.k, &k0, 3e5), "{:?}", f.base.k);
        assert!(close(&f.base.c, &c0, 150.0), "{:?}", f.base.c);
        assert!(close(&f.branches[0], &g, 3e5), "{:?}", f.branches);
        assert!(f.deviation.iter().all(|&e| e < 1e-12), "{:?}", f.deviation);
        assert!(!f.shrunk);
    }

    #[test]
    fn stiffness_rising_without_loss_is_no_passive_support_and_its_fit_says_so() {
        // k(w) = 2e5 + 500 w N/m with c = 100 N s/m: a rising storage stiffness with no loss to
        // go with it (Kramers-Kronig), which no sum of passive branches follows; the fit stays
        // passive and reports the deviation it is left with.
        let w: Vec<f64> = (0..=20).map(|i| 25.0 * i as f64).collect();
        let table: Vec<Coefficients> = w
            .iter()
            .map(|&w| Coefficients {
                k: Matrix2 {
                    xx: 2e5 + 500.0 * w,
                    xy: 0.0,
                    yx: 0.0,
                    yy: 2e5 + 500.0 * w,
                },
                c: Matrix2 {
                    xx: 100.0,
                    xy: 0.0,
                    yx: 0.0,
                    yy: 100.0,
                },
                m: Matrix2::default(),
            })
            .collect();
        let rates = geometric(12.5, 1000.0, MAX_BRANCHES);
        let f = fit_at(&Design::new(&w, &rates), &table, Matrix2::default(), true).unwrap();
        let c0 = [f.base.c.xx, f.base.c.xy, f.base.c.yx, f.base.c.yy];
        let g: Vec<[f64; 4]> = f
            .branches
            .iter()
            .map(|m| [m.xx, m.xy, m.yx, m.yy])
            .collect();
        assert!(passive(&c0, &g, &rates));
        assert!(f.deviation[0] > 0.05, "{:?}", f.deviation);
    }
}
