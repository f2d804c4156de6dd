//! The answer to a task, before any transport: the outcome of its analysis in the wire types
//! its endpoint returns ([`Output`]), or why there is none ([`ApiError`], with its problem).
//!
//! [`execute`] runs a task (`analysis::run`) and writes the outcome with the conversions of
//! analysis results into `model::api` types: [`convert`] (poles, Campbell, stability, damping
//! matrices, time and unbalance responses) and [`convert_audit`] (the audit's analyses and the
//! report that gathers them). Synchronous requests and jobs both answer through it: `render`
//! writes an output as a document, `jobs` keeps it, `service` sends it.

pub mod convert;
pub mod convert_audit;
mod convert_time;
mod convert_torsion;
mod convert_train;
pub mod error;
mod output;
mod units;

pub use error::ApiError;
pub use output::Output;

use crate::analysis::control::Control;
use crate::analysis::run::{CaseOutcome, Outcome, run};
use crate::model::Task;
use crate::model::api::{self, BearingSetReport, ReportCheck, ReportResponse};
use crate::model::limits::BYTES_PER_VALUE;
use crate::model::task::ModalTask;
use crate::model::task::ReportPlan;
use crate::model::task::TaskKind;

impl Output {
    /// The wire form of an outcome of `task`.
    fn of(o: Outcome, task: &Task) -> Result<Self, ApiError> {
        Ok(match o {
            Outcome::Modal(r) => Output::Modal({
                let mut m = convert::modal(&r);
                if let TaskKind::Modal(ModalTask {
                    model,
                    max_frequency,
                    sparse,
                    ..
                }) = &task.kind
                {
                    m.shaft = convert::shaft_layout(&model.rotor);
                    m.max_frequency = max_frequency.is_finite().then_some(*max_frequency);
                    if *sparse {
                        m.full_model = crate::model::api::Storage::Sparse;
                    }
                    if let Some(c) = &m.consistency {
                        m.warnings = model.whirl_warnings(c.read_at[0], c.read_at[1]);
                    }
                    m.motion = model.rotor.motion();
                    if !m.motion.is_lateral() {
                        // One pole per mode: the conjugates of a real motion are the same.
                        m.poles.retain(|p| {
                            let size = p.decay_rate.abs() + p.frequency.abs();
                            p.frequency >= -1e-9 * size || p.whirl == api::Whirl::Internal
                        });
                        let scale = crate::system::RotorSystem::assemble(&model.rotor)
                            .map_or(0.0, |s| crate::fem::modal::frequency_scale(&s));
                        rigid_motion(&mut m.poles, scale);
                        m.shaft = None;
                    }
                }
                m
            }),
            Outcome::Campbell(r) => Output::Campbell({
                let mut c = convert::campbell(&r);
                if let TaskKind::Campbell(t) = &task.kind {
                    c.motion = t.model.rotor.motion();
                }
                c
            }),
            Outcome::Stability {
                threshold,
                speeds,
                max_decay_rate,
                held,
            } => Output::Stability({
                let mut s = convert::stability(threshold.as_ref(), &speeds, max_decay_rate);
                if let Some((bound, r)) = held {
                    s.max_frequency = Some(bound);
                    s.reduction = r.as_ref().map(|r| convert::reduction(&r.reduction));
                    // Without a reduction the threshold is the full model's.
                    let closed = r.as_ref().is_none_or(|r| r.closed);
                    s.threshold_closed = threshold.is_some().then_some(closed);
                }
                s
            }),
            Outcome::Damping {
                matrices,
                model,
                fits,
            } => Output::Damping(Box::new({
                let mut d = convert::damping_matrices(&matrices, model);
                d.support_fits = fits.iter().map(convert::support_fit).collect();
                d
            })),
            Outcome::Time(r, reduction, fitted) => {
                let mut t = convert_time::time_response(&r);
                t.motion = task
                    .model()
                    .map_or(Default::default(), |m| m.rotor.motion());
                t.reduction = reduction.as_ref().map(convert::reduction);
                t.support_fits = fitted.fits.iter().map(convert::support_fit).collect();
                t.fit_poles = fitted.poles.iter().map(convert::fit_poles).collect();
                Output::Time(t)
            }
            Outcome::Unbalance {
                speeds,
                nodes,
                response,
                peaks,
                range,
                model,
                reduction,
                sparse,
            } => {
                let mut u = convert::unbalance_response(&speeds, &nodes, &response, model);
                u.reduction = reduction.as_ref().map(convert::response_reduction);
                u.full_model = convert::storage(sparse);
                for (n, p) in u.nodes.iter_mut().zip(&peaks) {
                    n.peaks = convert_audit::peaks(p, range);
                }
                Output::Unbalance(u)
            }
            Outcome::CriticalMap { stiffness, map } => {
                Output::CriticalMap(convert_audit::critical_map(&stiffness, &map))
            }
            Outcome::Static {
                result,
                gravity,
                rigid,
            } => Output::Static(convert_audit::statics(&result, gravity, rigid)),
            Outcome::Level1 {
                speed,
                at,
                qs,
                result,
                qa,
                rigid,
                density,
                level2,
                model,
                reduction,
            } => Output::Level1({
                let mut l =
                    convert_audit::level1(speed, &at, &qs, &result, qa, (rigid, density), model);
                l.level2 = level2.as_deref().map(convert_audit::level2);
                l.reduction = reduction.as_ref().map(convert_audit::level1_reduction);
                l
            }),
            Outcome::Frequency {
                speed,
                input,
                output,
                frequencies,
                response,
                model,
                reduction,
                sparse,
                elements,
            } => Output::Frequency({
                let mut f =
                    convert_audit::frequency(speed, input, output, &frequencies, &response, model);
                f.reduction = reduction.as_ref().map(convert::response_reduction);
                f.full_model = convert::storage(sparse);
                f.elements = elements
                    .iter()
                    .map(convert_time::element_response)
                    .collect();
                f
            }),
            Outcome::Report { parts, cases, sets } => {
                let TaskKind::Report(plan) = &task.kind else {
                    return Err(ApiError::Internal(
                        "a report outcome of another task".into(),
                    ));
                };
                Output::Report(Box::new(report_of(parts, cases, sets, plan)?))
            }
        })
    }
}

/// Runs a task to its output, refusing an answer beyond `max_bytes`.
pub fn execute(task: &Task, control: &Control, max_bytes: u64) -> Result<Output, ApiError> {
    let mut out = Output::of(run(task, control)?, task)?;
    out.set_warnings(task.warnings.clone());
    out.in_unit(task.output_unit);
    out.set_nondimensional(task.model().is_some_and(|m| m.rotor.nondimensional()));
    let bytes = out.values() * BYTES_PER_VALUE;
    if bytes > max_bytes {
        return Err(ApiError::Unsolvable(format!(
            "the answer would be about {} MB, more than the limit of {} MB \
             (WHIRL_MAX_RESPONSE_BYTES): use a lower max_frequency or fewer speeds",
            bytes.div_ceil(1 << 20),
            max_bytes >> 20
        )));
    }
    Ok(out)
}

/// A report's answer from its outcomes (and each bearing set's, recursively).
fn report_of(
    parts: Vec<Outcome>,
    cases: Vec<CaseOutcome>,
    sets: Vec<Outcome>,
    plan: &ReportPlan,
) -> Result<ReportResponse, ApiError> {
    let parts = parts
        .into_iter()
        .zip(plan.tasks())
        .map(|(o, t)| {
            let mut out = Output::of(o, t)?;
            out.set_warnings(t.warnings.clone());
            Ok(out)
        })
        .collect::<Result<Vec<_>, ApiError>>()?;
    let cases = cases
        .into_iter()
        .map(
            |c| match Output::of((*c.response).clone(), &plan.unbalance)? {
                Output::Unbalance(u) => Ok(convert_audit::unbalance_case(&c, u)),
                _ => Err(ApiError::Internal("a case's response".into())),
            },
        )
        .collect::<Result<Vec<_>, ApiError>>()?;
    let mut report = convert_audit::report(parts, plan, cases).map_err(ApiError::Internal)?;
    for (o, (name, sub)) in sets.into_iter().zip(&plan.sets) {
        let Outcome::Report { parts, cases, sets } = o else {
            return Err(ApiError::Internal("a bearing set's outcome".into()));
        };
        let r = report_of(parts, cases, sets, sub)?;
        report.checks.extend(r.checks.iter().map(|c| ReportCheck {
            check: format!("[{name}] {}", c.check),
            ..c.clone()
        }));
        report.bearing_sets.push(BearingSetReport {
            name: name.clone(),
            critical_speed_map: r.critical_speed_map,
            static_deflection: r.static_deflection,
            campbell: r.campbell,
            level1: r.level1,
            unbalance_cases: r.unbalance_cases,
            models: r.models,
            checks: r.checks,
        });
    }
    Ok(report)
}

/// A free train's rigid turning (or sliding) is a double pole at 0, which the eigensolver
/// returns as `sqrt(eps)`-sized round-off: reported once, exactly 0.
fn rigid_motion(poles: &mut Vec<api::Pole>, scale: f64) {
    use crate::analysis::interference::RIGID;
    let size = |p: &api::Pole| p.decay_rate.hypot(p.frequency);
    let largest = poles.iter().map(size).fold(scale, f64::max);
    let rigid = |p: &api::Pole| p.whirl != api::Whirl::Internal && size(p) <= RIGID * largest;
    let Some(first) = poles.iter().position(rigid) else {
        return;
    };
    let mut zero = poles[first].clone();
    zero.decay_rate = 0.0;
    zero.frequency = 0.0;
    zero.damping_ratio = 0.0;
    zero.log_decrement = None;
    poles.retain(|p| !rigid(p));
    poles.insert(0, zero);
}
