//! The report's bearing sets: the audit repeated with each set's supports, side by side.

use super::*;

pub(super) fn sets_section(o: &mut String, report: &ReportResponse, lo: f64, hi: f64) {
    if report.bearing_sets.is_empty() {
        return;
    }
    o.push_str("<h2 id=\"sets\">Bearing sets</h2>\n");
    o.push_str("<p>The audit repeated with each set's supports (API 684: minimum, nominal and maximum clearance); every set's checks are in the verdict, prefixed by its name.</p>\n");
    let rows: Vec<String> = report
        .bearing_sets
        .iter()
        .map(|s| {
            let crit: Vec<String> = s
                .campbell
                .criticals
                .iter()
                .filter(|k| k.whirl == crate::model::api::Whirl::Forward)
                .map(|k| {
                    let af = (k.damping_ratio > 0.0).then(|| 0.5 / k.damping_ratio);
                    format!(
                        "{:.0} rpm (AF {}, {})",
                        k.speed * RPM,
                        num(af, |a| format!("{a:.1}")),
                        num(Some(separation(k.speed, lo, hi)), |m| format!("{m:.1}%"))
                    )
                })
                .collect();
            let loads: Vec<String> = s
                .static_deflection
                .supports
                .iter()
                .map(|r| format!("{:.0} N at node {}", r.reaction, r.node))
                .collect();
            let a1 = s
                .unbalance_cases
                .iter()
                .filter_map(|c| c.max_bearing_amplitude)
                .fold(f64::NAN, f64::max);
            let failed = s.checks.iter().filter(|c| !c.passes).count();
            let (class, word) = verdict(Some(failed == 0));
            format!(
                "<tr>{}{}{}{}{}{}<td class=\"{class}\">{word}: {failed} of {} fail</td></tr>",
                td(&s.name),
                td(&if crit.is_empty() {
                    "none".into()
                } else {
                    crit.join("; ")
                }),
                td(&loads.join("; ")),
                td_num(&num(s.level1.log_decrement_0, |d| format!("{d:.3}"))),
                td_num(&num(s.level1.ratio, |r| format!("{r:.2}"))),
                td_num(&num(Some(a1), |a| format!("{:.2}", a * 1e6))),
                s.checks.len()
            )
        })
        .collect();
    table(
        o,
        &[
            "set",
            "forward critical speeds (AF, separation)",
            "journal loads",
            "δ at MCS",
            "q0 / q_A",
            "A1 [µm pk-pk]",
            "checks",
        ],
        &rows,
    );
}
