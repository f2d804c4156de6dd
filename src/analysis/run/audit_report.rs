//! The report: its analyses two at a time, its unbalance cases, and its bearing sets.

use super::*;
use crate::analysis::modal;
use crate::analysis::poles::{PoleSet, poles_at};
use crate::linalg::c64;
use crate::model::task::UnbalanceTask;

/// A report's parts, its unbalance cases and, for each bearing set, the same.
///
/// Its analyses do not depend on each other: they run in two lanes at once (see [`lanes`]),
/// which matters where one model's checks are long single-threaded eigensolves (the
/// nonviscous model's full check on a 100-element rotor) while the other lane runs the rest.
/// Each analysis fills a share of the progress in proportion to its estimated work (the
/// cases take [`MAX_CASES`] unbalance responses' share), so progress never goes back when
/// the next analysis announces its own work.
impl Analysis for ReportPlan {
    fn run(&self, control: &Control) -> Result<Outcome, RunError> {
        run_report(self, control)
    }
}

fn run_report(plan: &ReportPlan, control: &Control) -> Result<Outcome, RunError> {
    let total = report_work(plan);
    let mut at = 0.0;
    let mut share = |work: f64| {
        let from = at / total;
        at += work;
        (from, at / total)
    };
    let tasks = plan.run_tasks();
    let (from, to) = share(tasks.iter().map(|t| work(t)).sum());
    let mut done = control
        .part(from, to, || lanes(&tasks, control))?
        .into_iter();
    let mut next = || done.next().expect("one outcome per analysis");
    let mut parts = vec![next(), next(), next(), next()];
    for m in &plan.models {
        if m.primary {
            parts.extend([parts[2].clone(), next(), parts[3].clone()]);
        } else {
            parts.extend([next(), next(), next()]);
        }
    }
    if let Some(t) = &plan.torsion {
        parts.extend(t.tasks().iter().map(|_| next()));
    }
    let (from, to) = share(cases_work(plan));
    let cases = control.part(from, to, || {
        report_cases(plan, &parts[1], &parts[2], control)
    })?;
    let mut sets = vec![];
    for (_, sub) in &plan.sets {
        let (from, to) = share(report_work(sub));
        sets.push(control.part(from, to, || run_report(sub, control))?);
    }
    Ok(Outcome::Report { parts, cases, sets })
}

/// Runs `tasks` in two lanes, each one task at a time, the largest estimated work first onto
/// the lane with less: two analyses hold memory at once at most (the report's estimate counts
/// the two largest), and each still spreads its own speeds over the pool. Progress counts of
/// both fill the one share. The outcomes in the order of `tasks`.
fn lanes(tasks: &[&Task], control: &Control) -> Result<Vec<Outcome>, RunError> {
    if rayon::current_num_threads() < 2 {
        return tasks.iter().map(|t| run(t, control)).collect();
    }
    let mut order: Vec<usize> = (0..tasks.len()).collect();
    order.sort_by(|&a, &b| work(tasks[b]).total_cmp(&work(tasks[a])));
    let (mut lane, mut load) = ([vec![], vec![]], [0.0, 0.0]);
    for i in order {
        let l = usize::from(load[1] < load[0]);
        load[l] += work(tasks[i]);
        lane[l].push(i);
    }
    let failed = std::sync::atomic::AtomicBool::new(false);
    let run_lane = |ids: &[usize]| -> Vec<(usize, Result<Outcome, RunError>)> {
        let mut out = vec![];
        for &i in ids {
            // The other lane failed: the report fails with its error, nothing more to run.
            if failed.load(std::sync::atomic::Ordering::Relaxed) {
                break;
            }
            let r = run(tasks[i], control);
            if r.is_err() {
                failed.store(true, std::sync::atomic::Ordering::Relaxed);
            }
            out.push((i, r));
        }
        out
    };
    let (a, b) = rayon::join(|| run_lane(&lane[0]), || run_lane(&lane[1]));
    let mut all: Vec<(usize, Result<Outcome, RunError>)> = a.into_iter().chain(b).collect();
    // The first error in the tasks' order, as the sequential report would have met it.
    all.sort_by_key(|(i, _)| *i);
    let mut outs = Vec::with_capacity(tasks.len());
    for (_, r) in all {
        outs.push(r?);
    }
    if outs.len() < tasks.len() {
        return Err(RunError::Unsolvable(
            "report: an analysis did not run".into(),
        ));
    }
    Ok(outs)
}

/// A task's estimated work for the report's progress (at least one unit: every analysis
/// takes some time).
fn work(task: &Task) -> f64 {
    task.cost.work.max(1.0)
}

fn cases_work(plan: &ReportPlan) -> f64 {
    MAX_CASES as f64 * work(&plan.unbalance)
}

/// The work of everything [`run_report`] runs.
fn report_work(plan: &ReportPlan) -> f64 {
    let analyses: f64 = plan.run_tasks().iter().map(|t| work(t)).sum();
    analyses + cases_work(plan) + plan.sets.iter().map(|(_, s)| report_work(s)).sum::<f64>()
}

/// The report's unbalance cases (see [`cases`]): one per forward critical speed of its
/// Campbell diagram, the lowest [`MAX_CASES`], under the report's damping model.
fn report_cases(
    plan: &ReportPlan,
    statics: &Outcome,
    campbell: &Outcome,
    control: &Control,
) -> Result<Vec<CaseOutcome>, RunError> {
    let (
        Outcome::Static {
            result, gravity, ..
        },
        Outcome::Campbell(c),
        TaskKind::Unbalance(UnbalanceTask {
            model,
            speeds,
            range,
            ..
        }),
    ) = (statics, campbell, &plan.unbalance.kind)
    else {
        return Err(RunError::Unsolvable("report: parts out of order".into()));
    };
    let Rotor::Beam(rotor) = &model.rotor else {
        return Ok(vec![]);
    };
    // The mode shapes at the critical speeds: every pole of the dense model, or those of a
    // rotor held sparse in a box just holding the critical's pole.
    let sparse = matches!(
        plan.unbalance.kind,
        TaskKind::Unbalance(UnbalanceTask { sparse: true, .. })
    );
    let (system, damped) = match sparse {
        true => (assemble(model)?, None),
        false => build(model).map(|(s, d)| (s, Some(d)))?,
    };
    let poles = |speed: f64, pole: c64| -> Result<PoleSet, RunError> {
        Ok(match &damped {
            Some(d) => poles_at(d, speed).map_err(AnalysisError::from)?,
            None => {
                let bound = 1.01 * pole.re.abs().max(pole.im.abs());
                modal::modal_large(&system, &model.damping, speed, bound)?.poles
            }
        })
    };
    let rpm = plan.range.1 * 30.0 / std::f64::consts::PI;
    let journals = cases::journals(result);
    let bearings: Vec<usize> = journals.iter().map(|j| j.node).collect();
    let mut forward: Vec<&Critical> = c
        .criticals
        .iter()
        .filter(|k| k.whirl == Whirl::Forward)
        .collect();
    forward.sort_by(|a, b| a.speed.total_cmp(&b.speed));
    let couplings = rotor.couplings();
    let mut out = vec![];
    for (i, critical) in forward.into_iter().take(MAX_CASES).enumerate() {
        control.check().map_err(|_| RunError::Cancelled)?;
        let set = poles(critical.speed, critical.pole)?;
        let shape = cases::profile(&system, &set, critical.pole, result, &couplings)?;
        let overhung = |left: bool| cases::overhung_mass(rotor, result, left);
        let placed = placement::place(&shape.nodes, &journals, &overhung, rpm, *gravity);
        if placed.is_empty() {
            continue;
        }
        let mut nodes: Vec<usize> = placed.iter().map(|p| p.node).collect();
        nodes.extend(&bearings);
        nodes.extend(plan.clearances.iter().map(|c| c.0));
        nodes.retain(|&n| cases::translation_of(&system, n).is_some());
        nodes.sort_unstable();
        nodes.dedup();
        let task = Task {
            output_unit: Default::default(),
            kind: TaskKind::Unbalance(UnbalanceTask {
                model: model.clone(),
                speeds: speeds.clone(),
                unbalances: placed.iter().map(|p| (p.node, p.amount, p.phase)).collect(),
                nodes: nodes.clone(),
                range: *range,
                reduce: true,
                sparse,
            }),
            cost: plan.unbalance.cost,
            warnings: vec![],
        };
        let share = |k: usize| k as f64 / MAX_CASES as f64;
        let response = control.part(share(i), share(i + 1), || run(&task, control))?;
        let Outcome::Unbalance {
            response: orbits, ..
        } = &response
        else {
            return Err(RunError::Unsolvable(
                "report: a case without a response".into(),
            ));
        };
        let assessment = cases::assess(
            speeds.as_slice(),
            &nodes,
            orbits,
            &bearings,
            &plan.clearances,
            plan.range,
            rpm,
        );
        out.push(CaseOutcome {
            case: Case {
                mode: i + 1,
                critical: critical.clone(),
                unbalances: placed,
            },
            shape,
            response: Box::new(response),
            assessment,
        });
    }
    Ok(out)
}
