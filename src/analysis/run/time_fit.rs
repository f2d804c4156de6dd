//! A time response on supports over whirl frequency: the supports fitted by Maxwell branches
//! (held to their tables at a constant spin speed, where the unbalance whirls), the fitted
//! model's poles compared with the rotor's own before integrating, and a refit, or a refusal
//! that names the support, where the fitted model grows where the rotor does not.

use super::RunError;
use super::models::{assemble, fit};
use crate::analysis::control::Control;
use crate::analysis::time::TimeSpec;
use crate::analysis::time::fit_poles::{self, FitPoles};
use crate::damping::whirl_fit::{self, SupportFit};
use crate::linalg::c64;
use crate::model::task::Model;
use crate::system::RotorSystem;

/// The fits of a time response's supports over whirl frequency and their poles.
#[derive(Debug, Clone, Default)]
pub struct FittedTime {
    pub fits: Vec<SupportFit>,
    /// At each speed compared ([`speeds`]).
    pub poles: Vec<FitPoles>,
}

/// The speeds the poles are compared at: the constant speed, or the profile's at its knots
/// within the duration (and at its ends), increasing.
fn speeds(spec: &TimeSpec) -> Vec<f64> {
    if let Some(w) = spec.speed.constant() {
        return vec![w];
    }
    let mut at: Vec<f64> = match &spec.speed {
        crate::model::loads::SpeedLaw::Profile(p) => p
            .breakpoints()
            .filter(|&t| t > 0.0 && t < spec.duration)
            .chain([0.0, spec.duration])
            .map(|t| p.value(t))
            .collect(),
        crate::model::loads::SpeedLaw::Constant(w) => vec![*w],
    };
    at.sort_by(f64::total_cmp);
    at.dedup();
    at
}

/// The rotor of `model` with its supports over whirl frequency fitted for the time response
/// `spec`, and the fits and their poles (not compared where `compare` is false: a rotor held
/// sparse, which is not integrated with fitted supports).
pub(super) fn fitted(
    model: &Model,
    spec: &TimeSpec,
    compare: bool,
    control: &Control,
) -> Result<(RotorSystem, FittedTime), RunError> {
    let system = assemble(model)?;
    if !system.frequency_dependent() {
        return Ok((system, FittedTime::default()));
    }
    let mut anchors: Vec<f64> = spec.speed.constant().into_iter().collect();
    let (mut fitted, mut fits) = fit(&system, model, &anchors, control)?;
    if fits.is_empty() || !compare {
        return Ok((
            fitted,
            FittedTime {
                fits,
                poles: vec![],
            },
        ));
    }
    let at = speeds(spec);
    for refit in [true, false] {
        let mut poles = vec![];
        for &w in &at {
            if control.is_cancelled() {
                return Err(RunError::Cancelled);
            }
            poles.push(fit_poles::compare(&system, &fitted, &model.damping, w)?);
        }
        let growing: Vec<(f64, c64)> = poles
            .iter()
            .flat_map(|p| p.unstable.iter().map(move |&s| (p.speed, s)))
            .collect();
        if growing.is_empty() {
            return Ok((fitted, FittedTime { fits, poles }));
        }
        if refit {
            // Held also where the growing poles whirl: the fit there is the table's.
            anchors.extend(growing.iter().map(|(_, s)| s.im.abs()));
            anchors.sort_by(f64::total_cmp);
            anchors.dedup();
            (fitted, fits) = fit(&system, model, &anchors, control)?;
            continue;
        }
        let (speed, s) = growing
            .iter()
            .copied()
            .max_by(|a, b| a.1.re.total_cmp(&b.1.re))
            .unwrap_or_else(|| unreachable!("not empty"));
        let own = poles
            .iter()
            .find(|p| p.speed == speed)
            .map_or(f64::NAN, |p| p.max_decay_rate.0);
        let culprit = match whirl_fit::worst_at(&system, &fitted, speed, s.im.abs()) {
            Some((path, coefficient, d)) => format!(
                ": there {path}'s fitted {coefficient} is {:.3}% of its direct |H| off its table",
                100.0 * d
            ),
            None => String::new(),
        };
        return Err(RunError::Unsolvable(format!(
            "the supports over whirl frequency, fitted by Maxwell branches, give the model a \
             pole at {:.6e} {:+.6e}i 1/s at {speed} rad/s that grows, where the rotor's own \
             poles (each reading its supports at its frequency) decay (the least damped at \
             {own:.6e} 1/s), even held to the tables at the frequencies such poles whirl at \
             (|{:.6e}| rad/s{culprit}); not integrated: a table that passive branches can \
             follow (a stiffness rising with the frequency brings loss with it) or more \
             frequencies where the rotor whirls",
            s.re, s.im, s.im
        )));
    }
    unreachable!("the second pass returns")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::loads::{Pwl, SpeedLaw};

    #[test]
    fn a_profile_is_compared_at_its_knots_within_the_duration() {
        let mut bad = crate::model::Invalid::default();
        let p = Pwl::parse(
            &[[0.0, 0.0], [1.0, 500.0], [4.0, 800.0]],
            "p",
            false,
            &mut bad,
        )
        .unwrap();
        let spec = |duration: f64| TimeSpec {
            speed: SpeedLaw::Profile(p.clone()),
            forces: vec![],
            unbalances: vec![],
            duration,
            output_interval: 0.1,
            nodes: vec![],
            tolerance: 1e-6,
            max_steps: 1,
            reduce: false,
            generated: Default::default(),
        };
        assert_eq!(speeds(&spec(5.0)), vec![0.0, 500.0, 800.0]);
        assert_eq!(speeds(&spec(2.5)), vec![0.0, 500.0, 650.0]);
    }
}
