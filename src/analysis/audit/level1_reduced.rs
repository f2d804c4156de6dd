//! API 617 Level I on a checked modal reduction.
//!
//! Every point of the Level I curve, and every step of the root finder for `q0`, is an
//! eigenproblem of the rotor with the cross-coupling added. On the full model each is a damping
//! model rebuilt and a dense eigensolve of the full state. The cross-coupling acts at a few
//! translations, so a basis that holds the static responses to unit loads there (with the
//! lowest modes, their static corrections and those at the supports, as for the Campbell
//! diagram: [`reduction::reduce`]) carries it exactly: in modal coordinates it is a support on
//! the rows of the basis at those translations, a rank-two update of the reduced stiffness.
//! Each `q` then costs a reduced eigensolve.
//!
//! The reduction keeps every pole within twice the first forward mode's modulus to 1e-6
//! relative at the screen's speed; the result is checked against the full model at the
//! largest `q` solved (`q0` when found, else the end of the curve), where the cross-coupling
//! moves the poles furthest: every pole in that band, reduced against full and the other way
//! round (eigenvalues only, so one full solve without shapes), and the full model is solved
//! instead if any differs there by more than [`CHECK`] relative.
//!
//! For the viscous and hysteretic models of 100 states or more no dense matrix of the rotor's
//! size is formed: the modes by Lanczos, the reduction and both checks through sparse factors
//! of `Z(s)` ([`large::reduce`], [`large::band_error`]). On the cross-coupled 113-element rotor
//! of `benches/forced_ross.py` the dense full model's two builds and checks took 185 of 245 ms.
//! Nor for the equivalent and nonviscous models of a rotor held sparse: their dampers on the
//! full rotor's lowest modes (`damping::dampers`), projected on the basis for the reduced
//! model at every `q` (the cross-coupling changes no damper) and in the full model's check.
//!
//! [`reduction::reduce`]: crate::analysis::reduction::reduce

use super::level1::{
    self, FirstForward, Level1, Placing, auto_range_of, built, coupled, level1_of,
};
use super::level2::held_box;
use crate::analysis::AnalysisError;
use crate::analysis::control::Control;
use crate::analysis::large;
use crate::analysis::reduction::{self, Criterion, TOLERANCE};
use crate::damping::dampers::ModalDampers;
use crate::damping::{DampedModel, DampingError};
use crate::fem::modal::ModalBasis;
use crate::model::damping::DampingModel;
use crate::system::{Placement, RotorSystem};

/// Largest relative difference of a pole in the band, reduced against full, accepted at the
/// check.
pub const CHECK: f64 = 1e-5;

/// The full model a screen's reduction starts from and is checked against: its lowest modes
/// (held sparse), or the dense model.
enum Full {
    Sparse(ModalBasis),
    Dense(DampedModel),
}

/// How a Level I screen was reduced.
#[derive(Debug, Clone, PartialEq)]
pub struct Level1Reduction {
    pub modes: usize,
    pub vectors: usize,
    /// State size of each reduced eigenproblem.
    pub states: usize,
    pub full_states: usize,
    /// The cross-coupling at which the first forward pole was compared with the full model's.
    pub checked_q: f64,
    /// Largest `|s_reduced - s_full| / |s_full|` over the poles in the band there.
    pub max_relative_error: f64,
    /// Whether the full model was held sparse.
    pub sparse: bool,
    /// The equivalent or nonviscous model held sparse: `(modes damped, the highest's
    /// frequency)`.
    pub dampers: Option<(usize, f64)>,
}

/// A Level I screen: the grid (given, or [`level1::auto_range`]'s of `count` points), its
/// result, the first forward pole at `qa` (if asked), and the reduction it ran on.
pub struct Screened {
    pub qs: Vec<f64>,
    pub result: Level1,
    pub qa: Option<(f64, level1::ForwardPole)>,
    pub reduction: Option<Level1Reduction>,
}

/// Level I of `system` on a checked reduction, or on the full model where none passes (or
/// where `reduce` is false); a rotor `held` sparse (past the dense limits) is never solved on
/// its full model: an error where no reduction passes.
#[allow(clippy::too_many_arguments)]
pub fn level1_reduced(
    system: &RotorSystem,
    damping: &DampingModel,
    speed: f64,
    at: &Placing,
    qs: &[f64],
    count: usize,
    qa: Option<f64>,
    reduce: bool,
    held: bool,
    control: &Control,
) -> Result<Screened, AnalysisError> {
    let dofs: Vec<usize> = at.iter().map(|&(d, _)| d).collect();
    let scale = level1::stiffness_scale(system);
    let run = |first: &FirstForward| -> Result<(Vec<f64>, Level1, _), AnalysisError> {
        let qs = if qs.is_empty() {
            auto_range_of(first, scale, count, control)?
        } else {
            qs.to_vec()
        };
        let result = level1_of(first, &qs, control)?;
        let qa = match qa {
            Some(q) => Some((q, first.at(q)?)),
            None => None,
        };
        Ok((qs, result, qa))
    };
    let whole = || -> Result<Screened, AnalysisError> {
        if held {
            return Err(AnalysisError::Damping(DampingError::Unsolvable(
                "no modal reduction of this rotor passed the Level I check against its full \
                 model, and a rotor this large is not solved on its full model: use fewer \
                 elements"
                    .into(),
            )));
        }
        let first = FirstForward::new(system, damping, speed, at)?;
        let (qs, result, qa) = run(&first)?;
        Ok(Screened {
            qs,
            result,
            qa,
            reduction: None,
        })
    };
    // On supports over whirl frequency each pole is continued to consistency through sparse
    // factors of the rotor read at its frequency, on the full model (a reduction's basis would
    // be one reading's): dense, or held sparse in level II's box.
    if system.frequency_dependent() {
        let first = match held {
            true => FirstForward::held(system, damping, speed, at, held_box(system)?, None)?,
            false => FirstForward::new(system, damping, speed, at)?,
        };
        let (qs, result, qa) = run(&first)?;
        return Ok(Screened {
            qs,
            result,
            qa,
            reduction: None,
        });
    }
    if !reduce {
        return whole();
    }
    let whole_at: Vec<(Placement, usize, f64)> = at
        .iter()
        .map(|&(d, w)| (Placement::Dof(d), system.dofs[d].node, w))
        .collect();
    // The viscous and hysteretic models reduce and check through sparse factors (no dense
    // matrix of the rotor's size), their lowest modes and the band's first bound in one Lanczos
    // run; so do the equivalent and nonviscous models of a rotor held sparse, their dampers on
    // the full rotor's lowest modes ([`large::dampers`], the reduction carrying them
    // projected); the other models, and a small rotor the Lanczos run refuses (the dense path
    // names what is wrong), on the dense full model.
    let band = |omega: &[f64]| omega.get(1).copied().unwrap_or(omega[0]).max(speed.abs());
    let damped = held && damping.on_modes();
    let full = if held {
        Full::Sparse(large::lowest(system, 2, band)?)
    } else {
        let sparse = large::sparse_applies(system, damping)
            .then(|| large::lowest(system, 2, band).ok())
            .flatten();
        match sparse {
            Some(basis) => Full::Sparse(basis),
            None => Full::Dense(DampedModel::build(system, damping)?),
        }
    };
    // The band: from the second mode at rest (the first forward mode is rarely above it),
    // widened to twice the first forward mode's modulus if it is not.
    let mut bound = band(match &full {
        Full::Sparse(basis) => &basis.omega,
        Full::Dense(f) => &f.basis.omega,
    });
    // The dampers up to 16 times the band, found again when it widens.
    let mut dampers: Option<(f64, ModalDampers)> = None;
    for _ in 0..4 {
        control.check()?;
        if damped && dampers.as_ref().is_none_or(|(b, _)| *b != bound) {
            dampers = large::dampers(system, damping, bound)?.map(|d| (bound, d));
        }
        let dampers = dampers.as_ref().map(|(_, d)| d);
        let criterion = Criterion::Relative(TOLERANCE);
        let red = match &full {
            Full::Dense(f) => {
                reduction::reduce(system, damping, f, speed, bound, &dofs, criterion)?
            }
            Full::Sparse(basis) => {
                let check = large::Check {
                    speeds: vec![speed],
                    bound,
                    criterion,
                };
                large::reduce(
                    system,
                    damping,
                    dampers,
                    basis.clone(),
                    &check,
                    &dofs,
                    usize::MAX,
                )?
            }
        };
        let Some(red) = red else {
            break;
        };
        let placed: Vec<(Placement, usize, f64)> = at
            .iter()
            .map(|&(d, w)| {
                let row = (0..red.basis.len())
                    .map(|k| red.basis.phi[(d, k)])
                    .collect();
                (Placement::Shape(row), system.dofs[d].node, w)
            })
            .collect();
        let given =
            dampers.map(|d| DampedModel::projection(&red.system, system, d, &red.basis.phi));
        let first =
            FirstForward::projected(&red.system, damping, speed, placed.clone(), given.as_ref())?;
        let modulus = first.reference_modulus();
        if let Some(m) = modulus
            && 1.5 * m > bound
        {
            bound = 2.0 * m;
            continue;
        }
        let (qs, result, qa) = run(&first)?;
        // The check: every pole in the band, reduced against full, at the largest
        // cross-coupling solved, where it has moved the poles furthest from where the
        // reduction was checked. Eigenvalues only: one full solve, no shapes.
        let q = result.q0.unwrap_or(qs.iter().copied().fold(0.0, f64::max));
        let approx = built(&coupled(&red.system, &placed, q), damping, given.as_ref())?;
        let exact = coupled(system, &whole_at, q);
        let error = match &full {
            Full::Dense(_) => {
                reduction::band_error(&DampedModel::build(&exact, damping)?, &approx, speed, bound)?
            }
            Full::Sparse(_) => large::band_error(&exact, damping, dampers, &approx, speed, bound)?,
        };
        if error > CHECK {
            break;
        }
        return Ok(Screened {
            qs,
            result,
            qa,
            reduction: Some(Level1Reduction {
                modes: red.info.modes,
                vectors: red.info.vectors,
                states: red.info.states,
                full_states: red.info.full_states,
                checked_q: q,
                max_relative_error: error,
                sparse: matches!(full, Full::Sparse(_)),
                dampers: red.info.dampers,
            }),
        });
    }
    whole()
}
