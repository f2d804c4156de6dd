//! Poles a reduced sweep reports outside the box its reduction was checked in, refined on the
//! full model.
//!
//! A sweep reduced below a bound `w_b` ([`super::reduction`]) is checked for every pole in the
//! box `|Re s|, |Im s| <= w_b`, but keeps every branch whose `|Im s| <= w_b` at some speed: a
//! heavily damped bearing mode (`|Re s| > w_b`) or a branch rising past the bound reports
//! poles the check never saw, and a reduction on the modes below `2 w_b` places a pole of
//! modulus past that band only to `(|s| / w_k)^2` of the neglected modes (5e-3 measured on a
//! bench rotor's bearing mode at `-8525 + 1673i` 1/s below a 3187 rad/s bound).
//!
//! Each such pole `s_r` at spin speed `Omega` is replaced by the full model's eigenvalue nearest
//! it: shift-invert Arnoldi with the shift at `s_r` (one factor of `Z(s_r)`, sparse where the
//! model is the rotor's own second-order system, `damping::large`) finds every eigenvalue
//! within `5 %` of `|s_r|` (then `25 %`) in a few solves, since they are the largest of
//! `(A - s_r I)^-1`. For the hysteretic model only a root with the signs its problem assumed
//! counts; for a model with internal coordinates only a rotor pole. A reduced pole with no
//! full-model eigenvalue within `25 %` has no counterpart in the model and is removed (so is a
//! branch left with none). What was done is counted in [`Outside`].

use rayon::prelude::*;

use super::AnalysisError;
use super::campbell::{Branch, CampbellResult, forward_criticals};
use super::reduction::Outside;
use crate::damping::dampers::ModalDampers;
use crate::damping::{DampedModel, DampingError, ModelKind, large};
use crate::linalg::{LinalgError, arnoldi, c64};
use crate::model::damping::DampingModel;
use crate::system::RotorSystem;

/// Radii searched about a reduced pole, relative to its modulus.
const SEARCH: [f64; 2] = [0.05, 0.25];

/// Krylov vectors of the first space, and no guard beyond the search radius: the eigenvalue
/// nearest the shift is the largest of `(A - s_r I)^-1`, the first a Krylov space finds, so its
/// converged Ritz value leaves none nearer hidden.
const FIRST: (usize, usize) = (8, 0);

/// Residual, relative to the pole, at which a refined pole is accepted: far below the 1e-6 the
/// reduction is checked to.
pub(super) const TOLERANCE: f64 = 1e-10;

/// Largest Krylov space per refinement.
const MAX_SPACE: usize = 120;

/// Rotor energy fraction above which an eigenvalue of a model with internal coordinates is a
/// rotor pole (as [`super::nearest`] tells them).
const ROTOR_FRACTION: f64 = 0.5;

/// The full model a reduced sweep is refined on.
#[derive(Clone, Copy)]
pub enum Full<'a> {
    /// The viscous and hysteretic models: the rotor's second-order system, factored sparse.
    Sparse {
        system: &'a RotorSystem,
        damping: &'a DampingModel,
        /// The equivalent and nonviscous models' dampers (`damping::dampers`).
        dampers: Option<&'a ModalDampers>,
    },
    /// The others: the dense full model's structured shift-invert.
    Dense(&'a DampedModel),
}

impl<'a> Full<'a> {
    /// Sparse where the damping model has a sparse form, else `full`.
    pub fn of(system: &'a RotorSystem, damping: &'a DampingModel, full: &'a DampedModel) -> Self {
        match damping {
            DampingModel::Viscous | DampingModel::Hysteretic => Full::Sparse {
                system,
                damping,
                dampers: None,
            },
            _ => Full::Dense(full),
        }
    }
}

/// Refines every pole of `result`'s branches outside the box `|Re s|, |Im s| <= bound` on
/// `full` (see the module docs), if it was solved on a reduction; counted in its
/// `reduction.outside`.
pub fn outside_box(
    result: &mut CampbellResult,
    full: Full,
    bound: f64,
) -> Result<(), AnalysisError> {
    if result.reduction.is_none() {
        return Ok(());
    }
    let outside = |s: &c64| s.re.abs() > bound || s.im.abs() > bound;
    let lists = [&result.branches, &result.overdamped];
    let work: Vec<(usize, Vec<Reported>)> = (0..result.speeds.len())
        .filter_map(|i| {
            let here: Vec<Reported> = lists
                .iter()
                .enumerate()
                .flat_map(|(l, list)| {
                    list.iter()
                        .enumerate()
                        .filter_map(move |(b, br)| br.poles[i].map(|s| (l, b, s)))
                })
                .filter(|(_, _, s)| outside(s))
                .collect();
            (!here.is_empty()).then_some((i, here))
        })
        .collect();
    let speeds = &result.speeds;
    let found: Vec<Vec<Found>> = work
        .par_iter()
        .map(|(i, here)| {
            let poles: Vec<c64> = here.iter().map(|p| p.2).collect();
            refine_at(full, speeds[*i], &poles)
        })
        .collect::<Result<_, _>>()?;
    let mut out = Outside::default();
    for ((i, here), found) in work.iter().zip(found) {
        for (&(l, b, s), f) in here.iter().zip(found) {
            out.poles += 1;
            let branch = match l {
                0 => &mut result.branches[b],
                _ => &mut result.overdamped[b],
            };
            match f {
                Found::At(t) => {
                    out.refined += 1;
                    out.largest_change = out.largest_change.max((t - s).norm() / t.norm());
                    branch.poles[*i] = Some(t);
                }
                Found::Nothing => {
                    out.removed += 1;
                    branch.poles[*i] = None;
                    branch.whirl_ratio[*i] = None;
                }
                Found::Unsettled => {}
            }
        }
    }
    if out.removed > 0 {
        drop_empty(result);
    }
    // The crossings with the 1x line whose pole is outside the box, closed on the full model.
    let hysteretic = matches!(
        full,
        Full::Sparse {
            damping: DampingModel::Hysteretic,
            ..
        }
    );
    let moved: Vec<Option<(f64, c64)>> = result
        .criticals
        .par_iter()
        .map(|c| match outside(&c.pole) && !hysteretic {
            true => crossing(full, c.speed, c.pole),
            false => Ok(None),
        })
        .collect::<Result<_, _>>()?;
    for (c, m) in result.criticals.iter_mut().zip(moved) {
        if outside(&c.pole) {
            out.poles += 1;
        }
        if let Some((w, t)) = m {
            out.refined += 1;
            out.largest_change = out.largest_change.max((t - c.pole).norm() / t.norm());
            (c.speed, c.pole) = (w, t);
        }
    }
    result.criticals.sort_by(|a, b| a.speed.total_cmp(&b.speed));
    result.critical_speeds = forward_criticals(&result.criticals);
    if let Some(r) = result.reduction.as_mut() {
        r.outside = Some(out);
    }
    Ok(())
}

/// Secant steps allowed to close a crossing on the full model.
const CROSSING_STEPS: usize = 12;

/// The crossing `|Im s(Omega)| = Omega` of the full model's pole that continues `pole` at
/// `speed` (a reduced model's crossing): secant steps on `g(Omega) = |Im s(Omega)| - Omega`,
/// each pole refined from the last, to [`super::criticals::TOLERANCE`] relative. `None` where a
/// step finds no pole or the steps do not settle (the reduced crossing is kept). Not for the
/// hysteretic model, whose crossing is solved on the mean of two sign patterns.
fn crossing(full: Full, speed: f64, pole: c64) -> Result<Option<(f64, c64)>, AnalysisError> {
    let at = |w: f64, guess: c64| -> Result<Option<c64>, AnalysisError> {
        Ok(match refine_at(full, w, &[guess])?.pop() {
            Some(Found::At(t)) => Some(t),
            _ => None,
        })
    };
    let Some(s0) = at(speed, pole)? else {
        return Ok(None);
    };
    let (mut a, mut b) = ((speed, s0), (speed * (1.0 + 1e-6) + 1e-9, s0));
    let Some(s1) = at(b.0, s0)? else {
        return Ok(None);
    };
    b.1 = s1;
    let g = |(w, s): (f64, c64)| s.im.abs() - w;
    for _ in 0..CROSSING_STEPS {
        let (ga, gb) = (g(a), g(b));
        if gb == 0.0 || (b.0 - a.0).abs() <= super::criticals::TOLERANCE * b.0.abs() {
            return Ok(Some(b));
        }
        if ga == gb {
            return Ok(None);
        }
        let w = b.0 - gb * (b.0 - a.0) / (gb - ga);
        if !(w.is_finite() && w > 0.0) {
            return Ok(None);
        }
        let Some(s) = at(w, b.1)? else {
            return Ok(None);
        };
        (a, b) = (b, (w, s));
    }
    Ok(None)
}

/// A pole reported at one speed: its list (0 the oscillating branches, 1 the overdamped ones),
/// branch and value.
type Reported = (usize, usize, c64);

/// What the full model has near a reduced pole.
enum Found {
    /// Its eigenvalue nearest the pole.
    At(c64),
    /// No eigenvalue within the largest search radius.
    Nothing,
    /// The Krylov space would grow past [`MAX_SPACE`]: the pole is kept as reduced.
    Unsettled,
}

/// The full model's eigenvalue nearest `s` at spin speed `speed` (within 25 % of `|s|`), or
/// `None` where it has none there or it does not settle.
pub fn nearest_pole(full: Full, speed: f64, s: c64) -> Result<Option<c64>, AnalysisError> {
    Ok(match refine_at(full, speed, &[s])?.pop() {
        Some(Found::At(t)) => Some(t),
        _ => None,
    })
}

/// The full model's eigenvalue nearest each of `poles` at spin speed `speed`.
fn refine_at(full: Full, speed: f64, poles: &[c64]) -> Result<Vec<Found>, AnalysisError> {
    match full {
        Full::Sparse {
            system,
            damping,
            dampers,
        } => {
            let problems =
                large::problems(system, damping, dampers.map(|d| d.at(system, speed)), speed)
                    .ok_or_else(|| {
                        AnalysisError::Damping(DampingError::Unsolvable(
                            "this damping model has no sparse form".into(),
                        ))
                    })?;
            poles
                .iter()
                .map(|&s| {
                    let mut searches = vec![];
                    for p in problems.iter().filter(|p| p.consistent(s, speed)) {
                        let op = p.shift_invert(s)?;
                        searches.push(search(
                            op.states(),
                            |b| op.solve(b),
                            s,
                            |t, z| {
                                p.consistent(t, speed)
                                    && (p.internal() == 0 || p.rotor_fraction(z) >= ROTOR_FRACTION)
                            },
                        )?);
                    }
                    Ok(settle(s, searches))
                })
                .collect()
        }
        Full::Dense(model) => {
            // The hysteretic model is refined sparse ([`Full::of`]).
            let ModelKind::Linear(m) = &model.kind else {
                return Ok(poles.iter().map(|_| Found::Unsettled).collect());
            };
            let n = m.n();
            poles
                .iter()
                .map(|&s| {
                    let op = m.shift_invert(speed, s);
                    let found = search(
                        m.size(),
                        |b| op.solve(b),
                        s,
                        |_, z| {
                            m.p() == 0
                                || m.rotor_energy_fraction(&z[n..2 * n], &z[2 * n..])
                                    >= ROTOR_FRACTION
                        },
                    )?;
                    Ok(settle(s, vec![found]))
                })
                .collect()
        }
    }
}

/// The eigenvalues `accept`ed (given their eigenvectors) within each of [`SEARCH`]'s radii of
/// `sigma`, the first radius that holds any; `Some(vec![])` if none does, `None` if the space
/// would grow past [`MAX_SPACE`].
fn search(
    size: usize,
    solve: impl Fn(&[c64]) -> Vec<c64>,
    sigma: c64,
    accept: impl Fn(c64, &[c64]) -> bool,
) -> Result<Option<Vec<c64>>, LinalgError> {
    for r in SEARCH {
        let Some(found) = arnoldi::nearest_from(
            size,
            &solve,
            sigma,
            r * sigma.norm(),
            TOLERANCE,
            FIRST,
            (size / 2).min(MAX_SPACE),
        )?
        else {
            return Ok(None);
        };
        let kept: Vec<c64> = found
            .values
            .iter()
            .zip(&found.vectors)
            .filter(|(t, z)| accept(**t, z))
            .map(|(t, _)| *t)
            .collect();
        if !kept.is_empty() {
            return Ok(Some(kept));
        }
    }
    Ok(Some(vec![]))
}

/// The nearest to `s` of what the searches found.
fn settle(s: c64, searches: Vec<Option<Vec<c64>>>) -> Found {
    if searches.iter().any(Option::is_none) {
        return Found::Unsettled;
    }
    searches
        .into_iter()
        .flatten()
        .flatten()
        .min_by(|a, b| (a - s).norm().total_cmp(&(b - s).norm()))
        .map_or(Found::Nothing, Found::At)
}

/// Removes the branches left with no pole, and what refers to them.
fn drop_empty(result: &mut CampbellResult) {
    let empty = |b: &Branch| b.poles.iter().all(Option::is_none);
    let gone: Vec<bool> = result.branches.iter().map(empty).collect();
    // New index of each kept branch.
    let mut index = vec![None; gone.len()];
    let mut k = 0;
    for (i, g) in gone.iter().enumerate() {
        if !g {
            index[i] = Some(k);
            k += 1;
        }
    }
    let mut g = gone.iter();
    result
        .branches
        .retain(|_| !g.next().copied().unwrap_or(false));
    result.overdamped.retain(|b| !empty(b));
    result
        .ambiguities
        .retain_mut(|a| match (index[a.branches.0], index[a.branches.1]) {
            (Some(x), Some(y)) => {
                a.branches = (x, y);
                true
            }
            _ => false,
        });
    result.criticals.retain_mut(|c| match index[c.branch] {
        Some(b) => {
            c.branch = b;
            true
        }
        None => false,
    });
}
