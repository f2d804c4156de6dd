//! The report's API 684 unbalance cases: where each mode is excited and how hard, its peaks,
//! and its response against API 617's vibration limit and the clearances.

use super::*;
use crate::model::api::UnbalanceCase;

pub(super) fn cases_section(
    o: &mut String,
    report: &ReportResponse,
    range: [f64; 2],
) -> Result<(), Err> {
    o.push_str("<h2 id=\"cases\">Unbalance cases (API 684)</h2>\n");
    let cases = &report.unbalance_cases;
    let _ = writeln!(
        o,
        "<p>One case per forward critical speed of the Campbell diagram in the sweep, under the \
         {} model: <code>Ua = 2 × 6350 W / N</code> g mm (N = {:.0} rpm) at the mode's antinodes \
         (one: W the sum of the journal static loads; two, 180° apart: W the nearest journal's \
         load; overhung: W the overhung mass). Vibration limit <code>Avl = 25.4 µm √(12000 / N)</code> \
         = {} µm peak to peak; scale factor <code>Scc = Avl / A1</code> (at most 6), A1 the \
         largest peak-to-peak amplitude at a bearing in the operating range.</p>",
        escape(&report.level1.model),
        range[1] * RPM,
        num(Some(report.vibration_limit * 1e6), |v| format!("{v:.2}")),
    );
    if cases.is_empty() {
        o.push_str("<p>No forward critical speed in the sweep: no case to run.</p>\n");
        return Ok(());
    }
    let bearings: Vec<f64> = report
        .static_deflection
        .supports
        .iter()
        .filter_map(|r| {
            report
                .static_deflection
                .nodes
                .iter()
                .find(|n| n.node == r.node)
                .map(|n| n.position)
        })
        .collect();
    figure(
        o,
        &crate::render::plot_audit::mode_shapes(cases, &bearings)?,
        "Each mode's orbit major semi-axis at its critical speed, signed by phase, scaled to 1 \
         at the node that moves most, interpolated along each element with its shape functions; \
         triangles: bearings; dots: the unbalances.",
    );
    let rows: Vec<String> = cases.iter().map(case_row).collect();
    table(
        o,
        &[
            "mode",
            "critical speed [rpm]",
            "δ",
            "unbalances",
            "A1 [µm pk-pk]",
            "Avl [µm pk-pk]",
            "Scc",
            "vibration",
        ],
        &rows,
    );
    let mut peaks = vec![];
    let mut clear = vec![];
    for c in cases {
        let loaded: Vec<usize> = c.unbalances.iter().map(|u| u.node).collect();
        for n in c.response.nodes.iter().filter(|n| loaded.contains(&n.node)) {
            for p in &n.peaks {
                peaks.push(format!(
                    "<tr>{}{}{}{}</tr>",
                    td_num(&c.mode.to_string()),
                    td_num(&n.node.to_string()),
                    td_num(&num(Some(p.amplitude_peak_to_peak), |a| format!(
                        "{:.2}",
                        a * 1e6
                    ))),
                    peak_cells(p)
                ));
            }
        }
        for k in &c.clearances {
            let (class, word) = verdict(Some(k.passes));
            clear.push(format!(
                "<tr>{}{}{}{}{}{}<td class=\"{class}\">{word}</td></tr>",
                td_num(&c.mode.to_string()),
                td_num(&k.node.to_string()),
                td_num(&num(Some(k.diametral), |d| format!("{:.1}", d * 1e6))),
                td_num(&num(Some(k.scaled_amplitude), |a| format!(
                    "{:.2}",
                    a * 1e6
                ))),
                td_num(&num(Some(k.speed), |w| format!("{:.0}", w * RPM))),
                td_num(&num(Some(k.limit), |l| format!("{:.1}", l * 1e6))),
            ));
        }
    }
    o.push_str("<p>Peaks at the loaded nodes (amplitudes zero to peak unless marked pk-pk):</p>\n");
    table(
        o,
        &[
            "mode",
            "node",
            "peak [µm pk-pk]",
            "N_c [rad/s]",
            "[rpm]",
            "peak [µm 0-pk]",
            "AF",
            "half-power",
            "SM",
            "required SM",
            "verdict",
        ],
        &peaks,
    );
    if !clear.is_empty() {
        o.push_str("<p>Clearances: the largest peak-to-peak amplitude over the sweep times Scc, under 75% of the minimum diametral clearance.</p>\n");
        table(
            o,
            &[
                "mode",
                "node",
                "clearance [µm]",
                "scaled [µm pk-pk]",
                "at [rpm]",
                "limit [µm]",
                "verdict",
            ],
            &clear,
        );
    }
    for c in cases {
        figure(
            o,
            &crate::render::plot_audit::unbalance_bode(&c.response, Some(range))?,
            &format!(
                "Mode {}: response to its unbalances, amplitude zero to peak (pk-pk is twice) \
                 and phase of the forward whirl relative to the first unbalance.",
                c.mode
            ),
        );
    }
    Ok(())
}

fn case_row(c: &UnbalanceCase) -> String {
    let u: Vec<String> = c
        .unbalances
        .iter()
        .map(|u| {
            format!(
                "{} g mm at node {} ({:.0}°; W {} kg, {})",
                num(Some(u.amount * 1e6), |a| format!("{a:.1}")),
                u.node,
                u.phase.to_degrees(),
                num(Some(u.weight), |w| format!("{w:.2}")),
                u.rule
            )
        })
        .collect();
    let (class, word) = verdict(c.within_vibration_limit);
    format!(
        "<tr>{}{}{}{}{}{}{}<td class=\"{class}\">{word}</td></tr>",
        td_num(&c.mode.to_string()),
        td_num(&num(Some(c.critical_speed), |w| format!("{:.0}", w * RPM))),
        td_num(&num(c.log_decrement, |d| format!("{d:.3}"))),
        td(&u.join("; ")),
        td_num(&num(c.max_bearing_amplitude, |a| format!("{:.2}", a * 1e6))),
        td_num(&num(Some(c.vibration_limit), |a| format!("{:.2}", a * 1e6))),
        td_num(&num(c.scale_factor, |s| format!("{s:.2}"))),
    )
}
