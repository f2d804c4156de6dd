//! The audit analyses' results to wire types, and the report's verdict.

use super::output::Output;
use crate::analysis::audit::critical_map::CriticalMap;
use crate::analysis::audit::frequency::Excitation;
use crate::analysis::audit::level1::{ForwardPole, Level1};
use crate::analysis::audit::peaks::{self, Peak};
use crate::analysis::audit::statics::StaticResult;
use crate::analysis::unbalance::Orbit;
use crate::model::api;
use crate::model::task::ReportPlan;
use crate::model::task::TaskKind;

use crate::model::speeds::RPM;

pub fn critical_map(stiffness: &[f64], map: &CriticalMap) -> api::CriticalSpeedMapResponse {
    api::CriticalSpeedMapResponse {
        stiffness: stiffness.to_vec(),
        frequencies: map.frequencies.clone(),
        intersections: map
            .intersections
            .iter()
            .map(|i| api::MapIntersection {
                support: i.support,
                node: i.node,
                coefficient: i.coefficient.into(),
                mode: i.mode,
                stiffness: i.stiffness,
                frequency: i.frequency,
            })
            .collect(),
        warnings: vec![],
    }
}

pub fn statics(r: &StaticResult, gravity: f64, rigid: bool) -> api::StaticResponse {
    api::StaticResponse {
        gravity,
        supports_model: if rigid {
            api::StaticSupports::Rigid
        } else {
            api::StaticSupports::Elastic
        },
        supports: r
            .reactions
            .iter()
            .map(|s| api::SupportReaction {
                support: s.support,
                node: s.node,
                reaction: s.y,
                reaction_x: s.x,
            })
            .collect(),
        nodes: r
            .nodes
            .iter()
            .map(|n| api::NodeDeflection {
                node: n.node,
                position: n.position,
                deflection: n.y,
                deflection_x: n.x,
            })
            .collect(),
        stations: r
            .stations
            .iter()
            .map(|s| api::ShaftStation {
                element: s.element,
                position: s.position,
                shear: s.shear,
                bending_moment: s.bending_moment,
            })
            .collect(),
        weight: r.weight,
        warnings: vec![],
    }
}

/// `-2 pi sigma / omega` of a forward pole.
fn log_dec(p: &ForwardPole) -> Option<f64> {
    p.map(|(sigma, w)| -2.0 * std::f64::consts::PI * sigma / w)
}

/// API 617 Level I: the log decrement at q_A at least 0.1 and q0 / q_A at least 2.
pub const MIN_LOG_DEC: f64 = 0.1;
pub const MIN_Q_RATIO: f64 = 2.0;

pub fn level1(
    speed: f64,
    at: &[(usize, f64)],
    qs: &[f64],
    r: &Level1,
    qa: Option<(f64, ForwardPole)>,
    model: &str,
) -> api::Level1Response {
    let at_qa = qa.and_then(|(_, p)| log_dec(&p));
    let ratio = match (r.q0, qa) {
        (Some(q0), Some((qa, _))) if qa > 0.0 => Some(q0 / qa),
        _ => None,
    };
    let passes = qa
        .map(|_| at_qa.is_some_and(|d| d >= MIN_LOG_DEC) && ratio.is_none_or(|x| x >= MIN_Q_RATIO));
    api::Level1Response {
        speed,
        nodes: at.iter().map(|a| a.0).collect(),
        weights: at.iter().map(|a| a.1).collect(),
        cross_coupling: qs.to_vec(),
        log_decrement: r.curve.iter().map(log_dec).collect(),
        frequency: r.curve.iter().map(|p| p.map(|x| x.1)).collect(),
        log_decrement_0: log_dec(&r.base),
        frequency_0: r.base.map(|x| x.1),
        q0: r.q0,
        qa: qa.map(|q| q.0),
        log_decrement_at_qa: at_qa,
        ratio,
        passes,
        model: model.into(),
        warnings: vec![],
    }
}

pub fn frequency(
    speed: f64,
    input: (usize, Excitation),
    output: usize,
    frequencies: &[f64],
    response: &[Orbit],
    model: &str,
) -> api::FrequencyResponseResponse {
    let theta = match input.1 {
        Excitation::Direction(t) => t,
        _ => 0.0,
    };
    let along = |o: &Orbit| {
        let [x, y] = o.xy();
        x * theta.cos() + y * theta.sin()
    };
    let col = |f: &dyn Fn(&Orbit) -> f64| response.iter().map(f).collect::<Vec<f64>>();
    api::FrequencyResponseResponse {
        speed,
        input_node: input.0,
        output_node: output,
        frequencies: frequencies.to_vec(),
        amplitude: col(&|o| along(o).norm()),
        phase: col(&|o| along(o).arg()),
        x_amplitude: col(&|o| o.xy()[0].norm()),
        x_phase: col(&|o| o.xy()[0].arg()),
        y_amplitude: col(&|o| o.xy()[1].norm()),
        y_phase: col(&|o| o.xy()[1].arg()),
        forward: col(&|o| o.a.norm()),
        backward: col(&|o| o.b.norm()),
        model: model.into(),
        warnings: vec![],
    }
}

pub fn peaks(p: &[Peak], range: Option<(f64, f64)>) -> Vec<api::ResponsePeak> {
    p.iter()
        .map(|p| {
            let m = range.map(|(lo, hi)| peaks::margin(p.speed, p.amplification_factor, lo, hi));
            api::ResponsePeak {
                speed: p.speed,
                amplitude: p.amplitude,
                amplification_factor: p.amplification_factor,
                half_power: p.half_power,
                separation_margin: m.as_ref().map(|m| m.separation),
                required_margin: m.as_ref().and_then(|m| m.required),
                passes: m.and_then(|m| m.passes),
                refined: p.refined,
            }
        })
        .collect()
}

fn rpm(w: f64) -> String {
    format!("{:.1} rad/s ({:.0} rpm)", w, w * RPM)
}

/// The report from its parts (in the plan's order) and its plan.
pub fn report(parts: Vec<Output>, plan: &ReportPlan) -> Result<api::ReportResponse, String> {
    let mut it = parts.into_iter();
    let mut next = || it.next().ok_or("report: missing part");
    let Output::CriticalMap(map) = next()? else {
        return Err("report: part 1".into());
    };
    let Output::Static(statics) = next()? else {
        return Err("report: part 2".into());
    };
    let Output::Campbell(campbell) = next()? else {
        return Err("report: part 3".into());
    };
    let Output::Unbalance(unbalance) = next()? else {
        return Err("report: part 4".into());
    };
    let (lo, hi) = plan.range;
    let stop = match &plan.campbell.kind {
        TaskKind::Campbell { speeds, .. } => speeds.range().1,
        _ => hi,
    };
    let mut models = vec![];
    let mut checks = vec![];
    let mut first_level1 = None;
    for m in &plan.models {
        let Output::Campbell(c) = next()? else {
            return Err("report: model Campbell".into());
        };
        let Output::Level1(l) = next()? else {
            return Err("report: model Level I".into());
        };
        let Output::Unbalance(u) = next()? else {
            return Err("report: model unbalance".into());
        };
        let name = m.name.to_string();
        for node in &u.nodes {
            for p in &node.peaks {
                let Some(passes) = p.passes else { continue };
                let af = p.amplification_factor.unwrap_or(f64::NAN);
                checks.push(api::ReportCheck {
                    check: format!(
                        "separation margin of the peak at {} (node {})",
                        rpm(p.speed),
                        node.node
                    ),
                    model: name.clone(),
                    value: format!("AF {af:.2}, SM {:.1} %", p.separation_margin.unwrap_or(0.0)),
                    requirement: match p.required_margin {
                        Some(r) => format!("SM >= {r:.1} % (API 684)"),
                        None => "none: AF < 2.5 (API 684)".into(),
                    },
                    passes,
                });
            }
        }
        checks.push(api::ReportCheck {
            check: format!("stable up to {}", rpm(stop)),
            model: name.clone(),
            value: match c.threshold {
                Some(t) => format!("unstable from {}", rpm(t)),
                None => "stable".into(),
            },
            requirement: "no pole with decay rate > 0".into(),
            passes: c.threshold.is_none(),
        });
        match (l.log_decrement_at_qa, l.qa) {
            (_, Some(qa)) => {
                checks.push(api::ReportCheck {
                    check: "Level I: log decrement at q_A (API 617)".into(),
                    model: name.clone(),
                    value: match l.log_decrement_at_qa {
                        Some(d) => format!("{d:.3} at q_A = {qa:.4e} N/m"),
                        None => "undefined".into(),
                    },
                    requirement: format!(">= {MIN_LOG_DEC}"),
                    passes: l.log_decrement_at_qa.is_some_and(|d| d >= MIN_LOG_DEC),
                });
                checks.push(api::ReportCheck {
                    check: "Level I: q0 / q_A (API 617)".into(),
                    model: name.clone(),
                    value: l
                        .ratio
                        .map_or("q0 beyond the range searched".into(), |r| format!("{r:.2}")),
                    requirement: format!(">= {MIN_Q_RATIO}"),
                    passes: l.ratio.is_none_or(|r| r >= MIN_Q_RATIO) && l.log_decrement_0.is_some(),
                });
            }
            (_, None) => checks.push(api::ReportCheck {
                check: format!("log decrement of the first forward mode at {}", rpm(hi)),
                model: name.clone(),
                value: l
                    .log_decrement_0
                    .map_or("undefined".into(), |d| format!("{d:.3}")),
                requirement: format!(">= {MIN_LOG_DEC}"),
                passes: l.log_decrement_0.is_some_and(|d| d >= MIN_LOG_DEC),
            }),
        }
        models.push(api::ModelMargins {
            model: name,
            critical_speeds: c.critical_speeds.clone(),
            threshold: c.threshold,
            log_decrement: l.log_decrement_0,
            q0: l.q0,
            peaks: u.nodes.first().map(|n| n.peaks.clone()).unwrap_or_default(),
        });
        if first_level1.is_none() || m.name == campbell_model(&plan.campbell) {
            first_level1 = Some(l);
        }
    }
    let _ = lo;
    Ok(api::ReportResponse {
        rotor: plan.rotor.clone(),
        operating_range: api::OperatingRange { min: lo, max: hi },
        critical_speed_map: map,
        static_deflection: statics,
        warnings: campbell.warnings.clone(),
        campbell,
        unbalance,
        level1: first_level1.ok_or("report: no model")?,
        models,
        checks,
        unbalances: plan
            .unbalances
            .iter()
            .map(|u| api::SteadyUnbalanceInput {
                node: u.node,
                amount: u.amount,
                phase: u.phase,
            })
            .collect(),
    })
}

fn campbell_model(t: &crate::model::Task) -> &'static str {
    t.model().map_or("", |m| m.damping.name())
}
