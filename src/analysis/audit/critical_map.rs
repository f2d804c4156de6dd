//! The undamped critical speed map (ROSS's `run_ucs`).
//!
//! The full beam (two complex degrees of freedom per node, never Guyan-reduced) at zero speed,
//! with every support replaced by the same isotropic undamped spring `k` on its node's
//! translation (no damping, no support mass, no cross-coupling; seals left out, as API 684 and
//! ROSS's `run_ucs` do):
//!
//! ```text
//! (K_shaft + k E) phi = w^2 M phi,    E = sum over supports of e_t e_t^T
//! ```
//!
//! In complex coordinates an eigenpair of this real symmetric pencil is one degenerate x/y
//! pair of the real 4 dof/node model, so the lowest `modes` eigenvalues are the `modes` lowest
//! distinct natural frequencies `w = sqrt(w^2)` (ROSS's `wn[::2]`).
//!
//! Intersections, for every support and its `kxx` (and `kyy`, when different) coefficient:
//! - constant `k_s > 0`: the mode's frequency at `k = k_s`, from the eigenproblem at `k_s`
//!   (not read off the sampled curve);
//! - tabulated against speed (`k(w)` linear between table speeds, held outside): every speed
//!   `w` with `w_m(k(w)) = w`, a critical speed on the support's own stiffness. Outside the
//!   table `k` is held, so the root there is `w_m(k_end)` when it lies outside; inside, each
//!   table segment is scanned at a few points for sign changes of `g(w) = w_m(k(w)) - w` and
//!   each bracket is closed by Brent's method to 1e-10 relative. Since `g(0) >= 0` and `g`
//!   falls as `-w` beyond the table, every mode has at least one such speed.
//! - tabulated over whirl frequency: read synchronously (speed = frequency = `w`: a critical
//!   speed whirls at the speed), the same search from rest over every speed and frequency of
//!   the table, continued past its last along its end slopes.

use crate::analysis::AnalysisError;
use crate::analysis::control::Control;
use crate::analysis::roots::brent;
use crate::fem::assembly;
use crate::linalg::{self, LinalgError, RMat, Sparse, lanczos};
use crate::model::limits::map_is_sparse;
use crate::model::rotor::BeamRotor;
use crate::model::supports::grid::Grid;
use crate::model::supports::{GeneralSupport, Law, Matrix2};

/// Where a mode meets a support's actual stiffness.
#[derive(Debug, Clone, PartialEq)]
pub struct Intersection {
    /// Index of the support in the request's `rotor.supports`.
    pub support: usize,
    pub node: usize,
    /// `"kxx"` or `"kyy"`.
    pub coefficient: &'static str,
    /// Mode, from 1.
    pub mode: usize,
    pub stiffness: f64,
    pub frequency: f64,
}

#[derive(Debug, Clone, PartialEq)]
pub struct CriticalMap {
    /// `frequencies[mode][i]` at `stiffness[i]`, rad/s.
    pub frequencies: Vec<Vec<f64>>,
    pub intersections: Vec<Intersection>,
}

/// Sub-intervals per table segment scanned for sign changes: within a segment `k` is linear
/// in `w`, and `g` is concave for the first mode (at most two roots), nearly so for the others.
const SCAN: usize = 4;
/// Relative tolerance of a critical speed found on a tabulated coefficient.
const TOL: f64 = 1e-10;

/// The lowest `modes` undamped natural frequencies at zero speed (one per degenerate pair)
/// with every support replaced by an isotropic undamped spring of each `stiffness`.
/// `modes` is capped at the number of complex degrees of freedom (two per node).
pub fn critical_speed_map(
    rotor: &BeamRotor,
    stiffness: &[f64],
    modes: usize,
    control: &Control,
) -> Result<CriticalMap, AnalysisError> {
    let map = Springs::new(rotor, modes);
    let curves = curves(rotor);
    control.expect((stiffness.len() + curves.len()) as u64);
    let mut frequencies = vec![Vec::with_capacity(stiffness.len()); map.modes];
    for &k in stiffness {
        control.check()?;
        for (f, w) in frequencies.iter_mut().zip(map.at(k)?) {
            f.push(w);
        }
        control.advance(1);
    }
    let mut intersections = vec![];
    for c in &curves {
        control.check()?;
        let found = match c.law {
            Coefficient::Constant(k) if k > 0.0 => {
                map.at(k)?.into_iter().map(|w| vec![(k, w)]).collect()
            }
            // No spring, no point on the map's (positive) stiffness axis.
            Coefficient::Constant(_) => vec![],
            Coefficient::Table(s, pick) => on_table(&map, s, pick, control)?,
        };
        for (m, roots) in found.into_iter().enumerate() {
            intersections.extend(roots.into_iter().map(|(k, w)| Intersection {
                support: c.support,
                node: c.node,
                coefficient: c.name,
                mode: m + 1,
                stiffness: k,
                frequency: w,
            }));
        }
        control.advance(1);
    }
    // ROSS's order for one support: mode, then coefficient.
    intersections.sort_by_key(|i| (i.support, i.mode, i.coefficient != "kxx"));
    Ok(CriticalMap {
        frequencies,
        intersections,
    })
}

/// The lowest `modes` frequencies of [`critical_speed_map`]'s pencil with springs `k`, the
/// shaft held dense or sparse as asked (the map chooses by size; this lets the two be compared
/// on one rotor).
pub fn frequencies_at(
    rotor: &BeamRotor,
    k: f64,
    modes: usize,
    sparse: bool,
) -> Result<Vec<f64>, AnalysisError> {
    Springs::with(rotor, modes, sparse).at(k)
}

/// The first undamped natural frequency at rest on rigid supports, rad/s: the shaft and disks
/// with the translations of every bearing's node held (rotations free; seals left out), the
/// critical speed API 617's critical speed ratio `MCS / N_c1` is taken on.
pub fn rigid_first(rotor: &BeamRotor) -> Result<f64, AnalysisError> {
    let s = assembly::beam_shaft(rotor);
    let mut held = vec![false; s.n()];
    for node in rotor
        .supports()
        .iter()
        .filter(|s| !s.seal && s.node < rotor.shaft_nodes())
        .map(|s| s.node)
        .chain(
            rotor
                .general_supports()
                .iter()
                .filter(|g| !g.seal && g.node < rotor.shaft_nodes())
                .map(|g| g.node),
        )
    {
        held[2 * node] = true;
    }
    let free: Vec<usize> = (0..s.n()).filter(|&i| !held[i]).collect();
    // Past 600 coordinates by Lanczos on the sparse pencil (as the map), linear in the mesh.
    let w2 = if map_is_sparse(s.n(), 1) {
        let mut index = vec![usize::MAX; s.n()];
        for (k, &i) in free.iter().enumerate() {
            index[i] = k;
        }
        let pick = |a: &Sparse| {
            let kept: Vec<(usize, usize, f64)> = a
                .entries()
                .filter(|&(i, j, _)| !held[i] && !held[j])
                .map(|(i, j, v)| (index[i], index[j], v))
                .collect();
            Sparse::from_triplets(free.len(), free.len(), &kept)
        };
        lowest_sparse(&pick(&s.stiffness_rotating), &pick(&s.mass), 1)?
    } else {
        let pick = |a: &RMat| RMat::from_fn(free.len(), free.len(), |i, j| a[(free[i], free[j])]);
        linalg::symmetric_modes(
            &pick(&s.stiffness_rotating.to_dense()),
            &pick(&s.mass.to_dense()),
        )?
        .omega_squared
    };
    Ok(w2.first().map_or(0.0, |w2| w2.max(0.0).sqrt()))
}

/// The lowest `count` (at least) `w^2` of the sparse pencil `(kk, m)`. Where `kk` is not
/// positive definite (springs too soft or too few to hold the shaft, or negative), the pencil
/// is shifted by `s M` (`s` = 1e-8 of the largest `K_ii / M_ii`, below the shaft's lowest
/// bending mode on any practical mesh) and `s` taken off again.
fn lowest_sparse(kk: &Sparse, m: &Sparse, count: usize) -> Result<Vec<f64>, AnalysisError> {
    let n = kk.nrows();
    let enough = |w2: &[f64]| w2.len() >= count;
    match lanczos::lowest_modes(kk, m, enough) {
        Ok(modes) => Ok(modes.omega_squared),
        Err(LinalgError::NotPositiveDefinite) => {
            let s = 1e-8
                * (0..n)
                    .map(|i| kk.get(i, i) / m.get(i, i))
                    .filter(|r| r.is_finite())
                    .fold(0.0, f64::max);
            let shifted = kk.plus(m, s);
            let modes = lanczos::lowest_modes(&shifted, m, enough)?;
            Ok(modes.omega_squared.iter().map(|w2| w2 - s).collect())
        }
        Err(e) => Err(e.into()),
    }
}

/// The shaft with one spring `k` per support on its translation.
struct Springs {
    pencil: Pencil,
    /// Translation dof of each support (repeated if two share a node: they add).
    dofs: Vec<usize>,
    modes: usize,
}

/// The shaft's `K` and `M`: dense, or sparse past 600 coordinates ([`map_is_sparse`]: the
/// lowest modes by shift-invert Lanczos, work linear in the mesh).
enum Pencil {
    Dense { k: RMat, m: RMat },
    Sparse { k: Sparse, m: Sparse },
}

impl Springs {
    fn new(rotor: &BeamRotor, modes: usize) -> Self {
        let n = 2 * rotor.shaft_nodes();
        Self::with(rotor, modes, map_is_sparse(n, modes))
    }

    /// [`Springs::new`] held dense or sparse as asked.
    fn with(rotor: &BeamRotor, modes: usize, sparse: bool) -> Self {
        let s = assembly::beam_shaft(rotor);
        let dofs = rotor
            .supports()
            .iter()
            .filter(|s| !s.seal && s.node < rotor.shaft_nodes())
            .map(|s| 2 * s.node)
            .chain(
                rotor
                    .general_supports()
                    .iter()
                    .filter(|g| !g.seal && g.node < rotor.shaft_nodes())
                    .map(|g| 2 * g.node),
            )
            .collect();
        let pencil = match sparse {
            true => Pencil::Sparse {
                k: s.stiffness_rotating.clone(),
                m: s.mass.clone(),
            },
            false => Pencil::Dense {
                k: s.stiffness_rotating.to_dense(),
                m: s.mass.to_dense(),
            },
        };
        Springs {
            modes: modes.min(s.n()),
            pencil,
            dofs,
        }
    }

    /// The lowest natural frequencies with springs `k`. A negative eigenvalue (a tabulated
    /// `k < 0`) or round-off below a free rigid mode is reported as 0, never NaN.
    fn at(&self, k: f64) -> Result<Vec<f64>, AnalysisError> {
        let w2 = match &self.pencil {
            Pencil::Dense { k: k0, m } => {
                let mut kk = k0.clone();
                for &d in &self.dofs {
                    kk[(d, d)] += k;
                }
                linalg::symmetric_modes(&kk, m)?.omega_squared
            }
            Pencil::Sparse { k: k0, m } => self.lowest(k0, m, k)?,
        };
        Ok(w2
            .iter()
            .take(self.modes)
            .map(|v| v.max(0.0).sqrt())
            .collect())
    }

    /// The lowest `w^2` of the sparse pencil with springs `k` ([`lowest_sparse`]).
    fn lowest(&self, k0: &Sparse, m: &Sparse, k: f64) -> Result<Vec<f64>, AnalysisError> {
        let n = k0.nrows();
        let springs: Vec<(usize, usize, f64)> = self.dofs.iter().map(|&d| (d, d, k)).collect();
        let kk = k0.plus(&Sparse::from_triplets(n, n, &springs), 1.0);
        lowest_sparse(&kk, m, self.modes)
    }
}

enum Coefficient<'a> {
    Constant(f64),
    /// A tabulated support and which coefficient of its stiffness.
    Table(&'a GeneralSupport, fn(&Matrix2) -> f64),
}

struct Curve<'a> {
    support: usize,
    node: usize,
    name: &'static str,
    law: Coefficient<'a>,
}

/// `kxx` of every support, and `kyy` where it differs.
fn curves(rotor: &BeamRotor) -> Vec<Curve<'_>> {
    let mut out: Vec<Curve> = rotor
        .supports()
        .iter()
        .filter(|s| !s.seal && s.node < rotor.shaft_nodes())
        .map(|s| Curve {
            support: s.index,
            node: s.node,
            name: "kxx",
            law: Coefficient::Constant(s.stiffness),
        })
        .collect();
    for g in rotor
        .general_supports()
        .iter()
        .filter(|g| !g.seal && g.node < rotor.shaft_nodes())
    {
        let curve = |name, law| Curve {
            support: g.index,
            node: g.node,
            name,
            law,
        };
        match &g.law {
            Law::Constant(c) => {
                out.push(curve("kxx", Coefficient::Constant(c.k.xx)));
                if c.k.yy != c.k.xx {
                    out.push(curve("kyy", Coefficient::Constant(c.k.yy)));
                }
            }
            Law::Table { values, .. } => {
                out.push(curve("kxx", Coefficient::Table(g, |k| k.xx)));
                if values.iter().any(|v| v.k.yy != v.k.xx) {
                    out.push(curve("kyy", Coefficient::Table(g, |k| k.yy)));
                }
            }
            // Over whirl frequency: read synchronously (a critical speed whirls at the speed).
            Law::Grid(grid) => {
                out.push(curve("kxx", Coefficient::Table(g, |k| k.xx)));
                let differs = knots(grid).iter().any(|&w| {
                    let k = g.at(w).k;
                    k.yy != k.xx
                });
                if differs {
                    out.push(curve("kyy", Coefficient::Table(g, |k| k.yy)));
                }
            }
            Law::Read { .. } => {}
        }
    }
    out.sort_by_key(|c| c.support);
    out
}

/// Where a table over whirl frequency's synchronous reading is scanned from: rest, and every
/// speed and frequency it is given at.
fn knots(g: &Grid) -> Vec<f64> {
    let mut v: Vec<f64> = std::iter::once(0.0)
        .chain(g.speeds.iter().copied())
        .chain(g.frequencies.iter().copied())
        .collect();
    v.sort_by(f64::total_cmp);
    v.dedup();
    v
}

/// Doublings of the last knot a table over whirl frequency is scanned past it to: read along
/// its end slopes there, its stiffness keeps changing, and the map's frequency `w_m(k)` (at
/// most the rigid-support one) falls behind `w` within a few.
const DOUBLINGS: usize = 10;

/// `SCAN` points in each interval of `knots` after the first, the first too.
fn subdivided(knots: &[f64]) -> Vec<f64> {
    let mut grid = vec![knots[0]];
    for p in knots.windows(2) {
        grid.extend((1..=SCAN).map(|j| p[0] + (p[1] - p[0]) * j as f64 / SCAN as f64));
    }
    grid
}

/// Per mode, the `(k(w), w)` with `w_m(k(w)) = w` on a tabulated coefficient, by speed. A
/// table over speed alone is held past its ends; one over whirl frequency is read
/// synchronously from rest, past its ends along its end slopes (scanned up to [`DOUBLINGS`]
/// doublings of its last knot while a mode is still above the line, and where its stiffness
/// stays positive: the map has no point elsewhere).
fn on_table(
    map: &Springs,
    s: &GeneralSupport,
    pick: fn(&Matrix2) -> f64,
    control: &Control,
) -> Result<Vec<Vec<(f64, f64)>>, AnalysisError> {
    let k = |w: f64| pick(&s.at(w).k);
    let held = s.grid().is_none();
    let mut grid = match s.grid() {
        Some(g) => subdivided(&knots(g)),
        None => subdivided(s.speeds()),
    };
    // The frequencies at every grid point, all modes from one eigen solve.
    let mut f: Vec<Vec<f64>> = Vec::with_capacity(grid.len());
    let mut i = 0;
    let mut doublings = 0;
    while i < grid.len() {
        control.check()?;
        let kw = k(grid[i]);
        if !held && kw <= 0.0 {
            grid.truncate(i);
            break;
        }
        f.push(map.at(kw)?);
        i += 1;
        let above = |f: &[f64], w: f64| f.iter().any(|&fm| fm > w);
        if !held && i == grid.len() && doublings < DOUBLINGS && above(&f[i - 1], grid[i - 1]) {
            let last = grid[i - 1];
            grid.extend(subdivided(&[last, 2.0 * last.max(1.0)]).into_iter().skip(1));
            doublings += 1;
        }
    }
    let mut out = vec![vec![]; map.modes];
    let Some(last) = grid.len().checked_sub(1) else {
        return Ok(out);
    };
    for (m, roots) in out.iter_mut().enumerate() {
        let g = |i: usize| f[i][m] - grid[i];
        // Below a table over speed k is held at its first value: the root is that frequency
        // itself.
        if held && f[0][m] < grid[0] {
            roots.push((k(grid[0]), f[0][m]));
        }
        for i in 0..=last {
            if g(i) == 0.0 {
                roots.push((k(grid[i]), grid[i]));
            } else if i < last && g(i) * g(i + 1) < 0.0 {
                let h = |w: f64| -> Result<f64, AnalysisError> {
                    control.check()?;
                    Ok(map.at(k(w))?[m] - w)
                };
                let w = brent(h, (grid[i], grid[i + 1]), (g(i), g(i + 1)), TOL)?;
                roots.push((k(w), w));
            }
        }
        if held && f[last][m] > grid[last] {
            roots.push((k(grid[last]), f[last][m]));
        }
    }
    Ok(out)
}
