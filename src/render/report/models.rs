//! The report's table of the damping models side by side.

use super::*;

/// One column per damping model.
pub(super) fn models_table(o: &mut String, report: &ReportResponse, lo: f64, hi: f64) {
    let ms = &report.models;
    let mut head = vec![String::new()];
    head.extend(ms.iter().map(|m| m.model.clone()));
    let head: Vec<&str> = head.iter().map(String::as_str).collect();
    let q_max = ms.iter().filter_map(|m| m.q0).fold(0.0, f64::max);
    let (div, unit) = stiffness_unit(q_max);
    let first = |m: &crate::model::api::ModelMargins| m.peaks.first().cloned();
    type Cell = Box<dyn Fn(&crate::model::api::ModelMargins) -> String>;
    let rows: Vec<(&str, Cell)> = vec![
        (
            "critical speeds [rpm]",
            Box::new(|m| {
                let v: Vec<String> = m
                    .critical_speeds
                    .iter()
                    .filter(|w| w.is_finite())
                    .map(|w| format!("{:.0}", w * RPM))
                    .collect();
                if v.is_empty() {
                    "none".into()
                } else {
                    v.join(", ")
                }
            }),
        ),
        (
            "nearest separation",
            Box::new(move |m| {
                let sm = m
                    .critical_speeds
                    .iter()
                    .filter(|w| w.is_finite())
                    .map(|&w| separation(w, lo, hi))
                    .fold(f64::INFINITY, f64::min);
                num(Some(sm), |s| format!("{s:.1}%"))
            }),
        ),
        (
            "instability onset",
            Box::new(|m| m.threshold.map_or("none in range".into(), speed)),
        ),
        (
            "log decrement at MCS",
            Box::new(|m| num(m.log_decrement, |d| format!("{d:.3}"))),
        ),
        (
            "Level I q0",
            Box::new(move |m| num(m.q0, |q| format!("{:.3} {unit}", q / div))),
        ),
        (
            "first peak N_c",
            Box::new(move |m| num(first(m).map(|p| p.speed), |w| format!("{:.0} rpm", w * RPM))),
        ),
        (
            "first peak AF",
            Box::new(move |m| {
                num(first(m).and_then(|p| p.amplification_factor), |a| {
                    format!("{a:.2}")
                })
            }),
        ),
        (
            "first peak SM (required)",
            Box::new(move |m| match first(m) {
                Some(p) => format!(
                    "{} ({})",
                    num(p.separation_margin, |s| format!("{s:.1}%")),
                    num(p.required_margin, |s| format!("{s:.1}%"))
                ),
                None => "—".into(),
            }),
        ),
    ];
    let mut out = vec![];
    for (name, cell) in &rows {
        let mut r = format!("<tr><th>{}</th>", escape(name));
        for m in ms {
            // Coloured where API 684 / 617 set a limit.
            let verdict = match *name {
                "first peak SM (required)" => first(m).and_then(|p| p.passes),
                "log decrement at MCS" => {
                    m.log_decrement.filter(|d| d.is_finite()).map(|d| d >= 0.1)
                }
                "instability onset" => Some(m.threshold.is_none_or(|t| t > hi)),
                _ => None,
            };
            let class = match verdict {
                Some(true) => " pass",
                Some(false) => " fail",
                None => "",
            };
            let _ = write!(r, "<td class=\"num{class}\">{}</td>", escape(&cell(m)));
        }
        r.push_str("</tr>");
        out.push(r);
    }
    table(o, &head, &out);
}
