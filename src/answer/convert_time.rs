//! Time responses to wire types, with a train's rigid motion and element loads.

use crate::analysis::shaft_loads::{ElementHistory, ElementResponse};
use crate::analysis::time::{Method, TimeResult};
use crate::model::api;

pub fn time_response(r: &TimeResult) -> api::TimeResponseResponse {
    // A train's coordinates are real: `y` is 0, not the round-off of a complex solve.
    let real = r.train.is_some();
    let train = r.train.as_deref();
    api::TimeResponseResponse {
        nondimensional: false,
        warnings: train.map(|t| t.warnings.clone()).unwrap_or_default(),
        motion: Default::default(),
        time: r.time.clone(),
        nodes: r
            .nodes
            .iter()
            .map(|(node, h)| api::NodeHistory {
                node: *node,
                x: h.iter().map(|z| z.re).collect(),
                y: h.iter().map(|z| if real { 0.0 } else { z.im }).collect(),
            })
            .collect(),
        rigid_motion: train
            .and_then(|t| t.rigid.clone())
            .map(|(position, rate)| api::RigidMotion { position, rate }),
        elements: train
            .map(|t| {
                t.elements
                    .iter()
                    .map(|e| element_history(e, &r.time))
                    .collect()
            })
            .unwrap_or_default(),
        method: match r.method {
            Method::Exact => "exact",
            Method::Implicit => "implicit",
            Method::Exponential => "exponential",
        }
        .into(),
        steps: r.steps,
        states: r.states,
        reduction: None,
        support_fits: vec![],
        fit_poles: vec![],
    }
}

/// An element's load history with its peak and the stress there.
fn element_history(e: &ElementHistory, time: &[f64]) -> api::ElementLoadHistory {
    let (at, peak) = e
        .load
        .iter()
        .enumerate()
        .fold(
            (0, 0.0f64),
            |(k, p), (i, v)| if v.abs() > p { (i, v.abs()) } else { (k, p) },
        );
    api::ElementLoadHistory {
        element: e.element,
        nodes: e.nodes,
        load: e.load.clone(),
        peak,
        peak_time: time.get(at).copied().unwrap_or(0.0),
        peak_stress: e.stress.map(|s| s * peak),
    }
}

/// An element's load per unit input over frequency.
pub fn element_response(e: &ElementResponse) -> api::ElementLoadResponse {
    api::ElementLoadResponse {
        element: e.element,
        nodes: e.nodes,
        amplitude: e.load.iter().map(|z| z.norm()).collect(),
        phase: e.load.iter().map(|z| z.arg()).collect(),
        stress: e
            .stress
            .map(|s| e.load.iter().map(|z| s * z.norm()).collect()),
    }
}
