//! The report's summary of the model: shaft, disks, supports, weight, range, unbalance.

use super::*;

/// The model's summary rows (beam rotors in detail).
pub(super) fn model_rows(report: &ReportResponse, rotor: &RotorInput) -> Vec<String> {
    let mut rows = vec![];
    let mut row =
        |k: &str, v: String| rows.push(format!("<tr><th>{}</th>{}</tr>", escape(k), td(&v)));
    match rotor {
        RotorInput::Beam(b) => {
            let elements: i64 = b.shaft.iter().map(|s| s.elements.unwrap_or(1).max(1)).sum();
            let length: f64 = b.shaft.iter().map(|s| s.length).sum();
            let dmax = b
                .shaft
                .iter()
                .flat_map(|s| [Some(s.outer_diameter), s.outer_diameter_right])
                .flatten()
                .fold(0.0, f64::max);
            row(
                "shaft",
                format!(
                    "{} segment{}, {length:.3} m long, up to {:.1} mm in diameter",
                    b.shaft.len(),
                    if b.shaft.len() == 1 { "" } else { "s" },
                    dmax * 1e3
                ),
            );
            row("elements / nodes", format!("{elements} / {}", elements + 1));
            let couplings = b.shaft.iter().filter(|s| s.coupling.is_some()).count();
            if couplings > 0 {
                // Shafts: the runs of segments between couplings.
                let shafts = b
                    .shaft
                    .iter()
                    .enumerate()
                    .filter(|(i, s)| {
                        s.coupling.is_none() && (*i == 0 || b.shaft[i - 1].coupling.is_some())
                    })
                    .count();
                row(
                    "couplings",
                    format!("{couplings}, joining {shafts} shafts (rotating springs and dampers)"),
                );
            }
            if !b.sleeves.is_empty() {
                row(
                    "sleeves",
                    format!("{} (matrices added to the shaft's)", b.sleeves.len()),
                );
            }
            let names: Vec<&str> = b.materials.keys().map(String::as_str).collect();
            row("materials", names.join(", "));
            let mass: f64 = b.disks.iter().map(|d| d.mass).sum();
            let at: Vec<String> = b
                .disks
                .iter()
                .map(|d| format!("{:.1} kg at node {}", d.mass, d.node))
                .collect();
            row(
                "disks",
                if b.disks.is_empty() {
                    "none".into()
                } else {
                    format!(
                        "{} ({}): {}",
                        b.disks.len(),
                        num(Some(mass), |m| format!("{m:.1} kg")),
                        at.join(", ")
                    )
                },
            );
            // `count: node n: stiffness; ...` of the supports, and of the seals when there are any.
            let listed = |list: &[crate::model::api::SupportInput]| {
                let each: Vec<String> = list
                    .iter()
                    .map(|s| {
                        format!(
                            "node {}: {}",
                            s.node,
                            crate::render::plot_audit::support_stiffness(s)
                        )
                    })
                    .collect();
                format!("{}: {}", list.len(), each.join("; "))
            };
            row("supports", listed(&b.supports));
            if !b.seals.is_empty() {
                row("seals", listed(&b.seals));
            }
        }
        RotorInput::Jeffcott(_) => row("rotor", "Jeffcott rotor".into()),
        RotorInput::Matrices(_) => row("rotor", "given as matrices".into()),
    }
    let s = &report.static_deflection;
    let kg = if s.gravity > 0.0 {
        s.weight / s.gravity
    } else {
        f64::NAN
    };
    row(
        "total weight",
        format!(
            "{} ({})",
            num(Some(s.weight), |w| format!("{w:.1} N")),
            num(Some(kg), |m| format!("{m:.2} kg"))
        ),
    );
    let r = report.operating_range;
    row(
        "operating range",
        format!("{} to {}", speed(r.min), speed(r.max)),
    );
    let u: Vec<String> = report
        .unbalances
        .iter()
        .map(|u| {
            format!(
                "{} g mm at node {} ({:.0}°)",
                num(Some(u.amount * 1e6), |a| format!("{a:.0}")),
                u.node,
                u.phase.to_degrees()
            )
        })
        .collect();
    row(
        "unbalance",
        if u.is_empty() {
            "—".into()
        } else {
            u.join("; ")
        },
    );
    row("damping model of the plots", report.level1.model.clone());
    rows
}
