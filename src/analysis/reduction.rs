//! Modal reduction of a sweep below a frequency bound, checked against the full model.
//!
//! A Campbell diagram up to a bound `w_b` needs only the poles below it. Projected on its
//! lowest undamped nonrotating modes, `q = Phi_m eta` (a Rayleigh-Ritz reduction, see
//! [`ModalBasis::reduce`]), the rotor keeps every matrix, rotating and nonrotating apart, and
//! every damping model builds on it unchanged; the state shrinks from `2n + p` to `2m + p`
//! and each eigenproblem by `((2n + p) / (2m + p))^3`.
//!
//! The basis is the modes with `w_k <= 2 w_b` (at least 4) and their static corrections
//! ([`ModalBasis::augmented`]); the band widens by half until the check passes: at the
//! fastest speed of the sweep (where the gyroscopic coupling of the neglected modes is
//! largest) every full-model eigenvalue in the box `|Re s|, |Im s| <= w_b` has a reduced one
//! within [`TOLERANCE`] relative, and the other way round. The measured error is reported.
//! Reduction is used only where it at least halves the state.
//!
//! [`ModalBasis::reduce`]: crate::fem::modal::ModalBasis::reduce
//! [`ModalBasis::augmented`]: crate::fem::modal::ModalBasis::augmented

use super::AnalysisError;
use crate::damping::{DampedModel, ModelKind};
use crate::linalg::{self, LinalgError, c64};
use crate::model::damping::DampingModel;
use crate::system::RotorSystem;

/// Largest relative eigenvalue change allowed by the reduction, at the check speed.
pub const TOLERANCE: f64 = 1e-6;

/// How a sweep was reduced.
#[derive(Debug, Clone, PartialEq)]
pub struct Reduction {
    /// Undamped modes retained.
    pub modes: usize,
    /// Size of the basis: the modes and their independent static corrections.
    pub vectors: usize,
    /// State size of each reduced eigenproblem.
    pub states: usize,
    /// State size of the full model.
    pub full_states: usize,
    /// Natural frequency of the highest retained mode, rad/s.
    pub band: f64,
    /// The speed at which the reduced poles were checked against the full ones.
    pub checked_speed: f64,
    /// Largest relative distance between a checked pole and its counterpart.
    pub max_relative_error: f64,
}

/// The reduced model for a sweep over `speeds` with poles wanted below `bound`, or `None` when
/// no reduction at least halves the state and passes the check (then solve `full`).
pub fn reduce_for_sweep(
    system: &RotorSystem,
    damping: &DampingModel,
    full: &DampedModel,
    speeds: &[f64],
    bound: f64,
) -> Result<Option<(DampedModel, Reduction)>, AnalysisError> {
    let n = system.n();
    // Supports in the general form are not carried into modal coordinates (yet): such rotors
    // are solved in full.
    if !bound.is_finite() || speeds.is_empty() || !system.supports.is_empty() {
        return Ok(None);
    }
    let basis = &full.basis;
    let mut m = basis
        .omega
        .iter()
        .filter(|&&w| w <= 2.0 * bound)
        .count()
        .max(4);
    let checked_speed = speeds
        .iter()
        .cloned()
        .fold(0.0, |a: f64, b| if b.abs() > a.abs() { b } else { a });
    let inside = |v: &[c64]| -> Vec<c64> {
        v.iter()
            .cloned()
            .filter(|s| s.re.abs() <= bound && s.im.abs() <= bound)
            .collect()
    };
    let mut exact: Option<Vec<c64>> = None;
    while m < n {
        // A basis or model that cannot be built only means no reduction: solve the full one.
        let Ok(sub) = basis.augmented(system, m) else {
            break;
        };
        let Ok(model) = DampedModel::build(&sub.reduce(system), damping) else {
            break;
        };
        if 2 * model.states() > full.states() {
            break;
        }
        let exact = match &exact {
            Some(e) => e,
            None => exact.insert(eigenvalues_at(full, checked_speed)?),
        };
        let Ok(approx) = eigenvalues_at(&model, checked_speed) else {
            break;
        };
        let error = distance(&inside(exact), &approx).max(distance(&inside(&approx), exact));
        if error <= TOLERANCE {
            let states = model.states();
            return Ok(Some((
                model,
                Reduction {
                    modes: m,
                    vectors: sub.len(),
                    states,
                    full_states: full.states(),
                    band: basis.omega[m - 1],
                    checked_speed,
                    max_relative_error: error,
                },
            )));
        }
        m = (3 * m).div_ceil(2);
    }
    Ok(None)
}

/// Largest relative distance from a value in `from` to the nearest in `to`.
fn distance(from: &[c64], to: &[c64]) -> f64 {
    from.iter()
        .map(|s| {
            let nearest = to
                .iter()
                .map(|t| (s - t).norm())
                .fold(f64::INFINITY, f64::min);
            nearest / s.norm().max(f64::MIN_POSITIVE)
        })
        .fold(0.0, f64::max)
}

/// Every eigenvalue of the model at `speed` (for the hysteretic model, the consistent roots).
fn eigenvalues_at(model: &DampedModel, speed: f64) -> Result<Vec<c64>, LinalgError> {
    match &model.kind {
        ModelKind::Linear(m) => linalg::eigenvalues(&m.at(speed)),
        ModelKind::Hysteretic(signed) => {
            let mut out = vec![];
            for sm in signed {
                out.extend(
                    linalg::eigenvalues(&sm.model.at(speed))?
                        .into_iter()
                        .filter(|&s| sm.consistent(s, speed)),
                );
            }
            Ok(out)
        }
    }
}
