//! The report's torsional section: the train's natural frequencies against its excitations
//! (API 684's 10% separation), its interference diagram and its start-up or short-circuit
//! transient with every element's peak torque and stress.

use super::*;
use crate::render::plot::{interference, time};

pub(super) fn torsion_section(o: &mut String, report: &ReportResponse) -> Result<(), Err> {
    let Some(t) = &report.torsion else {
        return Ok(());
    };
    let c = &t.campbell;
    o.push_str("<h2 id=\"torsion\">Torsional analysis (API 684)</h2>\n");
    o.push_str("<p>The train's twist, its own system: each torsional natural frequency against the orders of its shafts' speeds and the line frequency, with API 684's separation margin (at least 10% from every excitation over the operating range).</p>\n");
    if let Some(i) = &c.interference {
        let hz = |f: f64| i.unit.to_rad_s(f) / std::f64::consts::TAU;
        let rows: Vec<String> = c
            .branches
            .iter()
            .filter_map(|b| {
                let f = b.frequency.iter().flatten().next()?;
                let logdec = b.log_decrement.iter().flatten().next().copied();
                let nearest = i.nearest(b.mode)?;
                if nearest.frequency > i.reach() {
                    return None;
                }
                let (class, word) = verdict(Some(nearest.passes));
                Some(format!(
                    "<tr class=\"check {class}\">{}{}{}{}{}<td class=\"verdict\">{word}</td></tr>",
                    td_num(&b.mode.to_string()),
                    td_num(&format!("{:.2} Hz ({:.0} cpm)", hz(*f), 60.0 * hz(*f))),
                    td_num(&num(logdec, |d| format!("{d:.3}"))),
                    td(&i.label(nearest.excitation)),
                    td_num(&format!("{:.1}%", 100.0 * nearest.margin)),
                ))
            })
            .collect();
        let _ = writeln!(
            o,
            "<p>The modes below {:.1} Hz, 1.5 times the highest excitation over the operating range (those above it are more than 50% from every excitation):</p>",
            hz(i.reach())
        );
        table(
            o,
            &[
                "mode",
                "natural frequency",
                "log decrement",
                "nearest excitation",
                "separation margin",
                "verdict",
            ],
            &rows,
        );
        figure(
            o,
            &interference(c)?,
            "Interference diagram: natural frequencies against the reference shaft's speed, the excitations, the operating range shaded; crossings marked red where the margin is under 10%.",
        );
    }
    if let Some(r) = &t.transient {
        o.push_str("<h3>Transient</h3>\n");
        figure(
            o,
            &time(r)?,
            "The most loaded element of each shaft over the transient, and the train's speed.",
        );
        let rows: Vec<String> = r
            .elements
            .iter()
            .map(|e| {
                format!(
                    "<tr>{}{}{}{}{}</tr>",
                    td_num(&e.element.to_string()),
                    td(&format!("{}-{}", e.nodes[0], e.nodes[1])),
                    td_num(&format!("{:.1}", e.peak)),
                    td_num(&format!("{:.4}", e.peak_time)),
                    td_num(&num(e.peak_stress, |s| format!("{:.2}", s / 1e6))),
                )
            })
            .collect();
        table(
            o,
            &[
                "element",
                "nodes",
                "peak torque [N m]",
                "at [s]",
                "peak shear stress [MPa]",
            ],
            &rows,
        );
    }
    Ok(())
}
