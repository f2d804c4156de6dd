//! The audit analyses' results to wire types, and the report's verdict.

use super::output::Output;
use crate::analysis::audit::critical_map::CriticalMap;
use crate::analysis::audit::frequency::Excitation;
use crate::analysis::audit::level1::{self, ForwardPole, Level1, MIN_LOG_DEC, MIN_Q_RATIO};
use crate::analysis::audit::level2::Source;
use crate::analysis::audit::peaks::{self, Peak};
use crate::analysis::audit::placement::{self, CLEARANCE_FRACTION};
use crate::analysis::audit::statics::StaticResult;
use crate::analysis::run::CaseOutcome;
use crate::analysis::unbalance::Orbit;
use crate::model::api;
use crate::model::task::CampbellTask;
use crate::model::task::ReportPlan;
use crate::model::task::TaskKind;

use crate::model::speeds::RPM;

pub fn critical_map(stiffness: &[f64], map: &CriticalMap) -> api::CriticalSpeedMapResponse {
    api::CriticalSpeedMapResponse {
        output_unit: Default::default(),
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
                slope: n.slope_y,
                slope_x: n.slope_x,
            })
            .collect(),
        stations: r.stations.iter().map(station).collect(),
        diagram: r.diagram.iter().map(station).collect(),
        max_moment: r.max_moment.bending_moment,
        max_moment_position: r.max_moment.position,
        max_shear: r.max_shear.shear,
        max_shear_position: r.max_shear.position,
        max_shear_element: r.max_shear.element,
        max_deflection: r.max_deflection.y.hypot(r.max_deflection.x),
        max_deflection_position: r.max_deflection.position,
        max_deflection_y: r.max_deflection.y,
        weight: r.weight,
        warnings: vec![],
    }
}

fn station(s: &crate::analysis::audit::statics::Station) -> api::ShaftStation {
    api::ShaftStation {
        element: s.element,
        position: s.position,
        shear: s.shear,
        bending_moment: s.bending_moment,
        deflection: s.y,
        deflection_x: s.x,
    }
}

/// `-2 pi sigma / omega` of a forward pole.
fn log_dec(p: &ForwardPole) -> Option<f64> {
    p.map(|(sigma, w)| -2.0 * std::f64::consts::PI * sigma / w)
}

pub fn level1(
    speed: f64,
    at: &[(usize, f64)],
    qs: &[f64],
    r: &Level1,
    qa: Option<(f64, ForwardPole)>,
    (rigid, density): (Option<f64>, Option<f64>),
    model: &str,
) -> api::Level1Response {
    let at_qa = qa.and_then(|(_, p)| log_dec(&p));
    let csr = rigid.filter(|w| *w > 0.0).map(|w| speed / w);
    let screen = qa.map(|(q, _)| level1::screen(r.q0, q, at_qa, csr, density));
    api::Level1Response {
        output_unit: Default::default(),
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
        ratio: screen.as_ref().and_then(|s| s.ratio),
        passes: screen.as_ref().map(|s| s.reasons.is_empty()),
        level2_required: screen.as_ref().map(|s| !s.reasons.is_empty()),
        level2_reasons: screen.as_ref().map_or(vec![], |s| s.reasons.clone()),
        rigid_critical_speed: rigid,
        critical_speed_ratio: csr,
        region: screen.as_ref().and_then(|s| s.region.map(String::from)),
        level2: None,
        reduction: None,
        max_residual: r.residual,
        model: model.into(),
        warnings: vec![],
    }
}

pub fn level1_reduction(
    d: &crate::analysis::audit::level1_reduced::Level1Reduction,
) -> api::Level1ReductionInfo {
    api::Level1ReductionInfo {
        modes: d.modes,
        vectors: d.vectors,
        states: d.states,
        full_states: d.full_states,
        checked_cross_coupling: d.checked_q,
        max_relative_error: d.max_relative_error,
        full_model: super::convert::storage(d.sparse),
        damped_modes: d.dampers.map(|(m, _)| m),
        damped_band: d.dampers.map(|(_, b)| b),
    }
}

/// API 617's Level II in wire form.
pub fn level2(sources: &[(Source, ForwardPole)]) -> api::Level2Response {
    let sources: Vec<api::Level2Source> = sources
        .iter()
        .map(|(s, p)| {
            let d = log_dec(p);
            api::Level2Source {
                source: s.name().into(),
                log_decrement: d,
                frequency: p.map(|x| x.1),
                passes: d.is_some_and(|d| d >= MIN_LOG_DEC),
            }
        })
        .collect();
    api::Level2Response {
        passes: sources.iter().all(|s| s.passes),
        sources,
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
        output_unit: Default::default(),
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
        elements: vec![],
        model: model.into(),
        reduction: None,
        full_model: Default::default(),
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
                amplitude_peak_to_peak: 2.0 * p.amplitude,
                amplification_factor: p.amplification_factor,
                critically_damped: p.critically_damped(),
                one_sided: p.one_sided,
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

/// One unbalance case, its response already converted.
pub fn unbalance_case(
    c: &CaseOutcome,
    response: api::UnbalanceResponseResponse,
) -> api::UnbalanceCase {
    let a = &c.assessment;
    let top = c
        .shape
        .nodes
        .iter()
        .map(|p| p.value.abs())
        .fold(0.0, f64::max);
    let scale = |v: f64| if top > 0.0 { v / top } else { 0.0 };
    api::UnbalanceCase {
        mode: c.case.mode,
        critical_speed: c.case.critical.speed,
        log_decrement: c.case.critical.log_decrement(),
        shape: c
            .shape
            .nodes
            .iter()
            .map(|p| api::ShapePoint {
                node: p.node,
                position: p.position,
                value: scale(p.value),
            })
            .collect(),
        shape_curve: c.shape.curve.iter().map(|&(z, v)| [z, scale(v)]).collect(),
        unbalances: c
            .case
            .unbalances
            .iter()
            .map(|u| api::PlacedUnbalance {
                node: u.node,
                amount: u.amount,
                phase: u.phase,
                weight: u.weight,
                rule: u.rule.name().into(),
            })
            .collect(),
        response,
        vibration_limit: a.vibration_limit,
        max_bearing_amplitude: a.a1.map(|x| x.0),
        max_bearing_amplitude_node: a.a1.map(|x| x.1),
        max_bearing_amplitude_speed: a.a1.map(|x| x.2),
        within_vibration_limit: a.a1.map(|x| x.0 <= a.vibration_limit),
        scale_factor: a.scale_factor,
        clearances: a
            .clearances
            .iter()
            .map(|k| api::ClearanceResult {
                node: k.node,
                diametral: k.diametral,
                scaled_amplitude: k.scaled,
                speed: k.speed,
                limit: CLEARANCE_FRACTION * k.diametral,
                passes: k.passes,
            })
            .collect(),
    }
}

/// The checks of the unbalance cases: separation margins of their peaks at the nodes they
/// load, the vibration limit at the bearings, the clearances.
fn case_checks(cases: &[api::UnbalanceCase], model: &str, checks: &mut Vec<api::ReportCheck>) {
    for c in cases {
        let loaded: Vec<usize> = c.unbalances.iter().map(|u| u.node).collect();
        let mode = format!("mode {} ({})", c.mode, rpm(c.critical_speed));
        for node in c.response.nodes.iter().filter(|n| loaded.contains(&n.node)) {
            for p in &node.peaks {
                let Some(passes) = p.passes else { continue };
                checks.push(api::ReportCheck {
                    check: format!(
                        "{mode}: separation margin of the peak at {} (node {})",
                        rpm(p.speed),
                        node.node
                    ),
                    model: model.into(),
                    value: match p.amplification_factor {
                        Some(af) => {
                            format!("AF {af:.2}, SM {:.1} %", p.separation_margin.unwrap_or(0.0))
                        }
                        None => "AF undefined".into(),
                    },
                    requirement: match p.required_margin {
                        Some(r) => format!("SM >= {r:.1} % (API 684)"),
                        None => "none: AF < 2.5 (API 684)".into(),
                    },
                    passes,
                });
            }
        }
        if let (Some(a1), Some(node)) = (c.max_bearing_amplitude, c.max_bearing_amplitude_node) {
            checks.push(api::ReportCheck {
                check: format!("{mode}: vibration at the bearings in the operating range"),
                model: model.into(),
                value: format!("{:.2} um pk-pk at node {node}", a1 * 1e6),
                requirement: format!("<= Avl = {:.2} um pk-pk (API 617)", c.vibration_limit * 1e6),
                passes: a1 <= c.vibration_limit,
            });
        }
        for k in &c.clearances {
            checks.push(api::ReportCheck {
                check: format!("{mode}: clearance at node {}", k.node),
                model: model.into(),
                value: format!(
                    "{:.1} um pk-pk scaled by Scc {:.2}",
                    k.scaled_amplitude * 1e6,
                    c.scale_factor.unwrap_or(1.0)
                ),
                requirement: format!(
                    "< 75% of {:.1} um = {:.1} um (API 617)",
                    k.diametral * 1e6,
                    k.limit * 1e6
                ),
                passes: k.passes,
            });
        }
    }
}

/// The report from its parts (in the plan's order), its plan and its unbalance cases.
pub fn report(
    parts: Vec<Output>,
    plan: &ReportPlan,
    unbalance_cases: Vec<api::UnbalanceCase>,
) -> Result<api::ReportResponse, String> {
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
        TaskKind::Campbell(CampbellTask { speeds, .. }) => speeds.range().1,
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
        if let Some(l2) = &l.level2 {
            for src in &l2.sources {
                checks.push(api::ReportCheck {
                    check: format!("Level II: {} (API 617)", src.source),
                    model: name.clone(),
                    value: src
                        .log_decrement
                        .map_or("undefined".into(), |d| format!("{d:.3}")),
                    requirement: format!(">= {MIN_LOG_DEC}"),
                    passes: src.passes,
                });
            }
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
    let torsion = match &plan.torsion {
        Some(t) => Some(super::convert_torsion::section(&mut next, t, &mut checks)?),
        None => None,
    };
    let _ = lo;
    case_checks(
        &unbalance_cases,
        campbell_model(&plan.campbell),
        &mut checks,
    );
    Ok(api::ReportResponse {
        bearing_sets: vec![],
        torsion,
        unbalance_cases,
        vibration_limit: placement::vibration_limit(hi * RPM),
        provenance: Some(api::Provenance {
            software: env!("CARGO_PKG_NAME").into(),
            version: env!("CARGO_PKG_VERSION").into(),
            input_sha256: plan.input_sha256.clone(),
            generated: humantime::format_rfc3339_seconds(std::time::SystemTime::now()).to_string(),
        }),
        rotor: plan.rotor.clone(),
        operating_range: api::OperatingRange {
            min: lo,
            max: hi,
            unit: None,
        },
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
