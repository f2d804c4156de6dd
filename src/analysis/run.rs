//! Runs a validated task: assemble the rotor, build its damping model, analyse. The one entry
//! point of the numerics for the service (which converts the outcome to wire types).

mod audit_report;
mod models;
mod threshold;
mod time_fit;

pub use models::build;
use models::{assemble, damping_error, harmonic_model, rigid_body};
pub use time_fit::FittedTime;

use super::AnalysisError;
use super::audit::cases::{self, Assessment, Case};
use super::audit::critical_map::{self, CriticalMap};
use super::audit::frequency::Excitation;
use super::audit::level1::{ForwardPole, Level1};
use super::audit::level1_reduced;
use super::audit::level2;
use super::audit::peaks::{self, Peak};
use super::audit::placement;
use super::audit::statics::{self, Held, StaticResult};
use super::campbell::{self, CampbellResult};
use super::campbell_whirl;
use super::control::Control;
use super::criticals::Critical;
use super::modal::{self, ModalResult};
use super::poles::Whirl;
use super::refine;
use super::response::{self, ResponseReduction};
use super::stability::Threshold;
use super::stability_large;
use super::time::{self, TimeError, TimeResult};
use super::unbalance::{Orbit, SteadyUnbalance};
use crate::damping::DampedModel;
use crate::damping::report::{self, ModelMatrices, ReportError};
use crate::damping::whirl_fit::SupportFit;
use crate::model::task::{MAX_CASES, ReportPlan, Task, TaskKind};
use crate::model::{Invalid, rotor::Rotor};

/// What an analysis found, in domain types.
#[derive(Debug, Clone)]
pub enum Outcome {
    Modal(ModalResult),
    Campbell(CampbellResult),
    Stability {
        threshold: Option<Threshold>,
        speeds: Vec<f64>,
        max_decay_rate: Vec<f64>,
        /// Held sparse: the bound of the poles considered and how the threshold was found (on
        /// a reduction; none on supports over whirl frequency, whose consistent poles are the
        /// full model's).
        held: Option<(f64, Option<Box<stability_large::Bounded>>)>,
    },
    Damping {
        matrices: Box<ModelMatrices>,
        model: &'static str,
        /// The fits of the supports over whirl frequency.
        fits: Vec<SupportFit>,
    },
    Time(
        TimeResult,
        Option<crate::analysis::reduction::Reduction>,
        time_fit::FittedTime,
    ),
    Unbalance {
        speeds: Vec<f64>,
        nodes: Vec<usize>,
        /// The orbit of each node at each speed.
        response: Vec<Vec<Orbit>>,
        /// The peaks of each node's amplitude (semi-major axis).
        peaks: Vec<Vec<Peak>>,
        range: Option<(f64, f64)>,
        model: &'static str,
        /// The checked modal reduction solved; `None` for the full model.
        reduction: Option<ResponseReduction>,
        /// Whether the full model was held sparse.
        sparse: bool,
    },
    CriticalMap {
        stiffness: Vec<f64>,
        map: CriticalMap,
    },
    Static {
        result: StaticResult,
        gravity: f64,
        rigid: bool,
    },
    Level1 {
        speed: f64,
        at: Vec<(usize, f64)>,
        qs: Vec<f64>,
        result: Level1,
        /// q_A and the first forward mode there.
        qa: Option<(f64, ForwardPole)>,
        /// The first critical speed on rigid supports (beam rotors), rad/s.
        rigid: Option<f64>,
        /// The machine's mean gas density, kg/m^3.
        density: Option<f64>,
        /// API 617's Level II, with the machine's data.
        level2: Option<Vec<(level2::Source, ForwardPole)>>,
        /// The checked reduction Level I ran on, if it did.
        reduction: Option<level1_reduced::Level1Reduction>,
        model: &'static str,
    },
    Frequency {
        speed: f64,
        input: (usize, Excitation),
        output: usize,
        frequencies: Vec<f64>,
        response: Vec<Orbit>,
        model: &'static str,
        reduction: Option<ResponseReduction>,
        /// Whether the full model was held sparse.
        sparse: bool,
    },
    /// The report's parts, in the order of its plan: map, static, Campbell, unbalance, then
    /// per compared model its Campbell, Level I and unbalance; and its unbalance cases.
    Report {
        parts: Vec<Outcome>,
        cases: Vec<CaseOutcome>,
        /// The same on each bearing set, in the plan's order.
        sets: Vec<Outcome>,
    },
}

/// One of the report's unbalance cases, run.
#[derive(Debug, Clone)]
pub struct CaseOutcome {
    pub case: Case,
    pub shape: cases::Shape,
    /// An [`Outcome::Unbalance`].
    pub response: Box<Outcome>,
    pub assessment: Assessment,
}

/// Why a valid request could not be analysed.
#[derive(Debug, Clone, PartialEq)]
pub enum RunError {
    /// The model is invalid in a way only assembly shows (a rotor its supports do not hold).
    Invalid(Invalid),
    /// The analysis cannot be carried out on this model; the reason.
    Unsolvable(String),
    Cancelled,
}

impl From<AnalysisError> for RunError {
    fn from(e: AnalysisError) -> Self {
        match e {
            AnalysisError::Cancelled => RunError::Cancelled,
            e => RunError::Unsolvable(e.to_string()),
        }
    }
}

impl From<TimeError> for RunError {
    fn from(e: TimeError) -> Self {
        match e {
            TimeError::Cancelled => RunError::Cancelled,
            e => RunError::Unsolvable(e.to_string()),
        }
    }
}

/// Why a large rotor's time response failed: it is integrated on a checked reduction only.
const NOT_REDUCED: &str = "no modal reduction of this rotor passed the check against its full \
    model (every pole in the band within 1e-3 of its decay rate), and a rotor this large is not \
    integrated on its full model: use fewer elements";

/// Runs `task`, checking `control` for cancellation and counting progress there.
pub fn run(task: &Task, control: &Control) -> Result<Outcome, RunError> {
    match &task.kind {
        TaskKind::Modal {
            model,
            speed,
            max_frequency,
            sparse,
        } => {
            let system = assemble(model)?;
            if system.frequency_dependent() {
                return modal::modal_consistent(
                    &system,
                    &model.damping,
                    *speed,
                    *max_frequency,
                    *sparse,
                )
                .map(Outcome::Modal)
                .map_err(|e| rigid_body(e, &model.rotor));
            }
            if *sparse {
                return modal::modal_large(&system, &model.damping, *speed, *max_frequency)
                    .map(Outcome::Modal)
                    .map_err(|e| match e {
                        AnalysisError::Damping(e) => damping_error(e, &model.rotor),
                        e => e.into(),
                    });
            }
            let damped = DampedModel::build(&system, &model.damping)
                .map_err(|e| damping_error(e, &model.rotor))?;
            let r = modal::modal_bounded(&system, &damped, *speed, *max_frequency)?;
            Ok(Outcome::Modal(r))
        }
        TaskKind::Campbell {
            model,
            speeds,
            max_frequency,
            modes,
            reduce,
            sparse,
            max_states,
        } => {
            let speeds = speeds.as_slice();
            let system = assemble(model)?;
            if system.frequency_dependent() {
                let keep = campbell::Keep {
                    below: *max_frequency,
                    lowest: *modes,
                };
                return campbell_whirl::campbell_consistent(
                    &system,
                    &model.damping,
                    speeds,
                    keep,
                    *sparse,
                    control,
                )
                .map(Outcome::Campbell)
                .map_err(|e| rigid_body(e, &model.rotor));
            }
            if *sparse {
                let keep = campbell::Keep {
                    below: *max_frequency,
                    lowest: None,
                };
                let dampers = super::large::dampers(&system, &model.damping, *max_frequency)?;
                let dampers = dampers.as_ref();
                let r = campbell::campbell_large(
                    &system,
                    &model.damping,
                    dampers,
                    speeds,
                    keep,
                    *max_states,
                    control,
                );
                return match r.and_then(|mut r| {
                    let full = refine::Full::Sparse {
                        system: &system,
                        damping: &model.damping,
                        dampers,
                    };
                    refine::outside_box(&mut r, full, *max_frequency)?;
                    Ok(r)
                }) {
                    Ok(r) => Ok(Outcome::Campbell(r)),
                    Err(AnalysisError::Damping(e)) => Err(damping_error(e, &model.rotor)),
                    Err(e) => Err(e.into()),
                };
            }
            let damped = DampedModel::build(&system, &model.damping)
                .map_err(|e| damping_error(e, &model.rotor))?;
            let bound = match modes {
                Some(n) => campbell::lowest_bound(&damped, speeds[0], *n)?.min(*max_frequency),
                None => *max_frequency,
            };
            let keep = campbell::Keep {
                below: bound,
                lowest: *modes,
            };
            let mut r = campbell::campbell_below(
                &system,
                &model.damping,
                &damped,
                speeds,
                keep,
                *reduce,
                control,
            )?;
            // The poles the reduction's check did not cover, on the full model.
            let full = refine::Full::of(&system, &model.damping, &damped);
            refine::outside_box(&mut r, full, bound)?;
            Ok(Outcome::Campbell(r))
        }
        TaskKind::Stability {
            model,
            speeds,
            held,
        } => threshold::run_stability(model, speeds.as_slice(), *held, control),
        TaskKind::Damping {
            model,
            state_form,
            band,
            max_deviation,
            max_states,
            speed,
        } => {
            let (system, fits) = models::fitted(model, &[*speed], control)?;
            let options = report::Options {
                state_form: *state_form,
                band: *band,
                max_deviation: *max_deviation,
                max_states: *max_states,
                speed: *speed,
            };
            let r = report::matrices(&system, &model.damping, &options).map_err(|e| match e {
                ReportError::Damping(e) => damping_error(e, &model.rotor),
                e @ ReportError::Unreachable { .. } => {
                    RunError::Invalid(Invalid::one("fit.max_deviation", e.to_string()))
                }
                e @ ReportError::NonFinite => RunError::Unsolvable(e.to_string()),
                e @ ReportError::TooLarge { .. } => {
                    RunError::Invalid(Invalid::one("damping", e.to_string()))
                }
            })?;
            Ok(Outcome::Damping {
                matrices: Box::new(r),
                model: model.damping.name(),
                fits,
            })
        }
        TaskKind::Time {
            model,
            spec,
            sparse,
        } => {
            let (system, fits) = time_fit::fitted(model, spec, !*sparse, control)?;
            let reduced = time::reduced::solve_sparse(
                &system,
                &model.damping,
                spec,
                spec.reduce,
                *sparse,
                control,
            )?;
            if let Some((r, reduction)) = reduced {
                return Ok(Outcome::Time(r, Some(reduction), fits));
            }
            if *sparse {
                if let Some(f) = fits.fits.first() {
                    return Err(RunError::Invalid(Invalid::one(
                        format!("{}.frequencies", f.path),
                        "a rotor held sparse has no internal coordinates for the branches a \
                         support over whirl frequency is fitted with, and is not integrated \
                         on its full model: use fewer elements",
                    )));
                }
                return Err(RunError::Unsolvable(NOT_REDUCED.into()));
            }
            let damped = DampedModel::build(&system, &model.damping)
                .map_err(|e| damping_error(e, &model.rotor))?;
            let (r, reduction) =
                time::reduced::solve(&system, &model.damping, &damped, spec, spec.reduce, control)?;
            Ok(Outcome::Time(r, reduction, fits))
        }
        TaskKind::Unbalance {
            model,
            speeds,
            unbalances,
            nodes,
            range,
            reduce,
            sparse,
        } => {
            let system = assemble(model)?;
            let top = speeds
                .as_slice()
                .iter()
                .fold(0.0, |a: f64, w| a.max(w.abs()));
            let owned = harmonic_model(*sparse, &system, model, top)?;
            let full = owned.full();
            let dof = |n: usize| time::translation(&system, n);
            let loads: Vec<SteadyUnbalance> = unbalances
                .iter()
                .map(|&(n, amount, phase)| SteadyUnbalance {
                    dof: dof(n),
                    amount,
                    phase,
                })
                .collect();
            let dofs: Vec<usize> = nodes.iter().map(|&n| dof(n)).collect();
            let grid = speeds.as_slice();
            let (response, solved) = response::unbalance_sweep(
                &system,
                &model.damping,
                full,
                grid,
                &loads,
                &dofs,
                *reduce,
                control,
            )?;
            // Refinement costs at most about two sweeps more; further peaks are interpolated.
            let mut budget = 2 * grid.len() + 2 * peaks::SOLVES_PER_PEAK;
            let n = system.n();
            let peaks = dofs
                .iter()
                .enumerate()
                .map(|(k, &d)| {
                    let amp: Vec<f64> = response.iter().map(|o| o[k].major()).collect();
                    let mut eval = |w: f64| -> Result<f64, AnalysisError> {
                        control.check()?;
                        let force = response::unbalance_force(&loads, n, w);
                        Ok(solved.orbits(w, w, &force, &[d])?[0].major())
                    };
                    peaks::peaks(grid, &amp, &mut eval, &mut budget)
                })
                .collect::<Result<Vec<_>, _>>()?;
            Ok(Outcome::Unbalance {
                speeds: grid.to_vec(),
                nodes: nodes.clone(),
                response,
                peaks,
                range: *range,
                model: model.damping.name(),
                reduction: solved.reduction().cloned(),
                sparse: *sparse || system.frequency_dependent(),
            })
        }
        TaskKind::CriticalMap {
            rotor,
            stiffness,
            modes,
        } => Ok(Outcome::CriticalMap {
            map: critical_map::critical_speed_map(rotor, stiffness, *modes, control)?,
            stiffness: stiffness.clone(),
        }),
        TaskKind::Static {
            rotor,
            gravity,
            rigid,
            speed,
        } => {
            let held = if *rigid {
                Held::Rigid
            } else {
                Held::Elastic { speed: *speed }
            };
            let result =
                statics::static_deflection(rotor, *gravity, held).map_err(|e| match e {
                    AnalysisError::Linalg(_) => RunError::Invalid(Invalid::one(
                        "rotor.supports",
                        "the supports do not hold the shaft (its stiffness matrix is singular)",
                    )),
                    e => e.into(),
                })?;
            Ok(Outcome::Static {
                result,
                gravity: *gravity,
                rigid: *rigid,
            })
        }
        TaskKind::Level1 {
            model,
            speed,
            at,
            qs,
            qa,
            density,
            extra,
            reduce,
            sparse,
        } => {
            let system = assemble(model)?;
            let placing: Vec<(usize, f64)> = at
                .iter()
                .map(|&(n, w)| (time::translation(&system, n), w))
                .collect();
            let screened = level1_reduced::level1_reduced(
                &system,
                &model.damping,
                *speed,
                &placing,
                qs,
                21,
                *qa,
                *reduce,
                *sparse,
                control,
            )
            .map_err(|e| rigid_body(e, &model.rotor))?;
            let (qs, result, qa) = (screened.qs, screened.result, screened.qa);
            let reduction = screened.reduction;
            let rigid = match &model.rotor {
                Rotor::Beam(b) => Some(critical_map::rigid_first(b)?),
                _ => None,
            };
            let level2 = match qa {
                Some((q, _)) => {
                    control.check().map_err(|_| RunError::Cancelled)?;
                    let more: Vec<(usize, f64)> = extra
                        .iter()
                        .map(|&(n, q)| (time::translation(&system, n), q))
                        .collect();
                    Some(level2::level2(
                        &system,
                        &model.damping,
                        *speed,
                        &placing,
                        q,
                        &more,
                        *sparse,
                    )?)
                }
                None => None,
            };
            Ok(Outcome::Level1 {
                speed: *speed,
                at: at.clone(),
                qs,
                result,
                qa,
                rigid,
                density: *density,
                level2,
                model: model.damping.name(),
                reduction,
            })
        }
        TaskKind::Frequency {
            model,
            speed,
            input,
            output,
            frequencies,
            reduce,
            sparse,
        } => {
            let system = assemble(model)?;
            let top = frequencies
                .iter()
                .fold(speed.abs(), |a: f64, w| a.max(w.abs()));
            let owned = harmonic_model(*sparse, &system, model, top)?;
            let full = owned.full();
            let dof = |n: usize| time::translation(&system, n);
            let force = input.1.at(dof(input.0), system.n());
            let (response, solved) = response::frequency_sweep(
                &system,
                &model.damping,
                full,
                *speed,
                &force,
                dof(*output),
                frequencies,
                *reduce,
                control,
            )?;
            Ok(Outcome::Frequency {
                speed: *speed,
                input: *input,
                output: *output,
                frequencies: frequencies.clone(),
                response,
                model: model.damping.name(),
                reduction: solved.reduction().cloned(),
                sparse: *sparse || system.frequency_dependent(),
            })
        }
        TaskKind::Report(plan) => audit_report::run_report(plan, control),
    }
}
