//! A torsional or axial sweep's interference diagram in the wire types.

use crate::model::api;

/// The interference diagram, in rad/s.
pub fn interference(i: &crate::analysis::interference::Interference) -> api::Interference {
    use crate::analysis::interference::Line;
    api::Interference {
        excitations: i
            .spec
            .lines
            .iter()
            .map(|l| match *l {
                Line::Order { order, ratio } => api::Excitation {
                    kind: "order".into(),
                    order,
                    ratio,
                    slope: order * ratio,
                    frequency: None,
                },
                Line::Fixed {
                    multiple,
                    frequency,
                } => api::Excitation {
                    kind: "line".into(),
                    order: multiple,
                    ratio: 0.0,
                    slope: 0.0,
                    frequency: Some(frequency),
                },
            })
            .collect(),
        operating_range: i.spec.range,
        criticals: i
            .crossings
            .iter()
            .map(|c| api::InterferenceCritical {
                excitation: c.line,
                mode: c.mode,
                speed: c.speed,
                frequency: c.frequency,
                damping_ratio: c.damping_ratio,
                margin: c.margin,
                passes: c.passes(),
                beyond_sweep: c.beyond_sweep,
            })
            .collect(),
        unit: Default::default(),
    }
}
