//! The audit report as one self-contained HTML5 page: inline CSS, inline SVG plots, no scripts
//! and no external resources. It gathers the verdict of the API 684 / API 617 checks, the
//! model, the critical speed map, static loads, Campbell diagram, unbalance peaks, the Level I
//! screen, and the margins under each damping model side by side.

use std::fmt::Write;

use super::plot::{RPM, campbell_with};
use super::plot_audit::{
    critical_speed_map_with, level1, rotor_sketch, stiffness_unit, unbalance_with,
};
use crate::model::api::{ReportResponse, ResponsePeak, RotorInput};

type Err = Box<dyn std::error::Error>;

const STYLE: &str = "
body { font-family: 'DejaVu Sans', 'Helvetica Neue', Arial, sans-serif; color: #1e1e1e;
  margin: 0; background: #f4f5f7; line-height: 1.4; }
main { max-width: 1000px; margin: 0 auto; padding: 24px 28px 48px; background: #fff; }
h1 { font-size: 26px; margin: 0 0 4px; }
h2 { font-size: 20px; margin: 32px 0 10px; padding-bottom: 4px; border-bottom: 2px solid #d0d4da; }
p.lead { color: #555; margin: 0 0 16px; }
table { border-collapse: collapse; margin: 8px 0 14px; font-size: 14px; }
th, td { border: 1px solid #cfd3d8; padding: 4px 9px; text-align: left; vertical-align: top; }
th { background: #eef0f3; font-weight: 600; }
td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
tr.pass td.verdict, td.pass { background: #dff3e0; color: #155b1b; font-weight: 600; }
tr.fail td.verdict, td.fail { background: #fbe0e0; color: #9b1111; font-weight: 600; }
.banner { padding: 10px 14px; border-radius: 4px; font-weight: 600; margin: 10px 0; }
.banner.pass { background: #dff3e0; color: #155b1b; }
.banner.fail { background: #fbe0e0; color: #9b1111; }
figure { margin: 10px 0 18px; }
figure svg { max-width: 100%; height: auto; display: block; border: 1px solid #e2e5e9; }
.warn { background: #fff6e0; border-left: 4px solid #e6a100; padding: 6px 12px; }
.grid { display: flex; gap: 18px; flex-wrap: wrap; align-items: flex-start; }
footer { margin-top: 32px; color: #777; font-size: 12px; }
@media print { body { background: #fff; } main { padding: 0; } h2 { break-after: avoid; }
  figure { break-inside: avoid; } }
";

/// `s` with `& < > " '` escaped for HTML text and attributes.
pub fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

/// `f(v)` of a finite value (a rounded `-0` without its sign), else a dash.
fn num(v: Option<f64>, f: impl Fn(f64) -> String) -> String {
    let s = v.filter(|x| x.is_finite()).map_or_else(|| "—".into(), f);
    match s.strip_prefix('-') {
        Some(t)
            if t.chars()
                .take_while(|c| c.is_ascii_digit() || *c == '.')
                .all(|c| c == '0' || c == '.') =>
        {
            t.into()
        }
        _ => s,
    }
}

fn speed(w: f64) -> String {
    num(Some(w), |w| format!("{w:.1} rad/s ({:.0} rpm)", w * RPM))
}

/// API 684 separation of a speed from `[lo, hi]`, percent of the nearer end (0 inside).
fn separation(w: f64, lo: f64, hi: f64) -> f64 {
    if w < lo {
        100.0 * (lo - w) / lo
    } else if w > hi {
        100.0 * (w - hi) / hi
    } else {
        0.0
    }
}

fn verdict(p: Option<bool>) -> (&'static str, &'static str) {
    match p {
        Some(true) => ("pass", "pass"),
        Some(false) => ("fail", "fail"),
        None => ("", "—"),
    }
}

/// A table: header cells, then rows of already escaped cells (`<td>`s included).
fn table(out: &mut String, head: &[&str], rows: &[String]) {
    out.push_str("<table><thead><tr>");
    for h in head {
        let _ = write!(out, "<th>{}</th>", escape(h));
    }
    out.push_str("</tr></thead><tbody>\n");
    for r in rows {
        let _ = writeln!(out, "{r}");
    }
    out.push_str("</tbody></table>\n");
}

fn figure(out: &mut String, svg: &str, caption: &str) {
    let svg = svg.trim_start();
    let svg = svg
        .strip_prefix("<?xml")
        .map_or(svg, |s| s.split_once("?>").map_or(s, |x| x.1));
    let _ = writeln!(
        out,
        "<figure>{}<figcaption class=\"lead\">{}</figcaption></figure>",
        svg.trim(),
        escape(caption)
    );
}

fn supports_name(s: crate::model::api::StaticSupports) -> &'static str {
    match s {
        crate::model::api::StaticSupports::Elastic => "elastic",
        crate::model::api::StaticSupports::Rigid => "rigid",
    }
}

fn td(s: &str) -> String {
    format!("<td>{}</td>", escape(s))
}

fn td_num(s: &str) -> String {
    format!("<td class=\"num\">{}</td>", escape(s))
}

fn peak_cells(p: &ResponsePeak) -> String {
    let (class, word) = verdict(p.passes);
    let half = p.half_power.map_or("—".into(), |[a, b]| {
        if a.is_finite() && b.is_finite() {
            format!("{:.0}–{:.0} rpm", a * RPM, b * RPM)
        } else {
            "—".into()
        }
    });
    format!(
        "{}{}{}{}{}{}{}<td class=\"{class}\">{word}</td>",
        td_num(&num(Some(p.speed), |w| format!("{w:.1}"))),
        td_num(&num(Some(p.speed), |w| format!("{:.0}", w * RPM))),
        td_num(&num(Some(p.amplitude), |a| format!("{:.2}", a * 1e6))),
        td_num(&num(p.amplification_factor, |a| format!("{a:.2}"))),
        td_num(&half),
        td_num(&num(p.separation_margin, |s| format!("{s:.1}%"))),
        td_num(&num(p.required_margin, |s| format!("{s:.1}%"))),
    )
}

/// The audit page of `report` on `rotor`.
pub fn html(report: &ReportResponse, rotor: &RotorInput) -> Result<String, Err> {
    let range = [report.operating_range.min, report.operating_range.max];
    let (lo, hi) = (range[0], range[1]);
    let mut o = String::with_capacity(1 << 20);
    o.push_str("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n");
    o.push_str("<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n");
    let _ = writeln!(
        o,
        "<title>Rotordynamic audit</title>\n<style>{STYLE}</style>\n</head>\n<body><main>"
    );
    o.push_str("<h1>Rotordynamic audit</h1>\n");
    let _ = writeln!(
        o,
        "<p class=\"lead\">API 684 / API 617 checks of the rotor over its operating range {} to {}.</p>",
        escape(&speed(lo)),
        escape(&speed(hi))
    );

    if let Some(p) = &report.provenance {
        let _ = writeln!(
            o,
            "<p class=\"lead\">{} {} · computed {} · input SHA-256 <code>{}</code></p>",
            escape(&p.software),
            escape(&p.version),
            escape(&p.generated),
            escape(&p.input_sha256)
        );
    }
    o.push_str("<h2 id=\"verdict\">Verdict</h2>\n");
    let failed = report.checks.iter().filter(|c| !c.passes).count();
    let (class, msg) = match failed {
        0 => ("pass", format!("All {} checks pass.", report.checks.len())),
        n => (
            "fail",
            format!("{n} of {} checks fail.", report.checks.len()),
        ),
    };
    let _ = writeln!(o, "<div class=\"banner {class}\">{}</div>", escape(&msg));
    let rows: Vec<String> = report
        .checks
        .iter()
        .map(|c| {
            let (class, word) = verdict(Some(c.passes));
            format!(
                "<tr class=\"check {class}\">{}{}{}{}<td class=\"verdict\">{word}</td></tr>",
                td(&c.check),
                td(&c.model),
                td_num(&c.value),
                td(&c.requirement)
            )
        })
        .collect();
    table(
        &mut o,
        &["check", "damping model", "value", "requirement", "verdict"],
        &rows,
    );

    o.push_str("<h2 id=\"model\">Model</h2>\n");
    o.push_str("<table><tbody>\n");
    for r in model_rows(report, rotor) {
        let _ = writeln!(o, "{r}");
    }
    o.push_str("</tbody></table>\n");
    figure(
        &mut o,
        &rotor_sketch(rotor)?,
        "Rotor sketch: lengths to scale, diameters exaggerated.",
    );

    o.push_str("<h2 id=\"map\">Undamped critical speed map</h2>\n");
    let map = &report.critical_speed_map;
    figure(
        &mut o,
        &critical_speed_map_with(map, Some(range))?,
        "Natural frequencies at zero speed against the support stiffness; dots: the actual supports.",
    );
    // Supports with the same coefficient meeting a mode at the same point share a row.
    let mut merged: Vec<(
        &crate::model::api::MapIntersection,
        Vec<String>,
        Vec<String>,
    )> = vec![];
    for i in &map.intersections {
        let same = |m: &&mut (
            &crate::model::api::MapIntersection,
            Vec<String>,
            Vec<String>,
        )| {
            m.0.mode == i.mode
                && m.0.coefficient == i.coefficient
                && (m.0.stiffness - i.stiffness).abs() <= 1e-9 * i.stiffness.abs()
                && (m.0.frequency - i.frequency).abs() <= 1e-9 * i.frequency.abs()
        };
        match merged.iter_mut().find(same) {
            Some(m) => {
                m.1.push(i.support.to_string());
                m.2.push(i.node.to_string());
            }
            None => merged.push((i, vec![i.support.to_string()], vec![i.node.to_string()])),
        }
    }
    let rows: Vec<String> = merged
        .iter()
        .map(|(i, supports, nodes)| {
            format!(
                "<tr>{}{}{}{}{}{}{}</tr>",
                td_num(&i.mode.to_string()),
                td_num(&supports.join(", ")),
                td_num(&nodes.join(", ")),
                td(&i.coefficient),
                td_num(&num(Some(i.stiffness), |k| format!("{k:.3e}"))),
                td_num(&num(Some(i.frequency), |f| format!("{f:.1}"))),
                td_num(&num(Some(i.frequency), |f| format!("{:.0}", f * RPM))),
            )
        })
        .collect();
    table(
        &mut o,
        &[
            "mode",
            "support",
            "node",
            "coefficient",
            "stiffness [N/m]",
            "frequency [rad/s]",
            "[rpm]",
        ],
        &rows,
    );

    o.push_str("<h2 id=\"static\">Static deflection and bearing loads</h2>\n");
    let s = &report.static_deflection;
    figure(
        &mut o,
        &super::plot_audit::static_deflection(s)?,
        &format!(
            "Under gravity {:.4} m/s², {} supports. Largest deflection {:.2} µm at {:.3} m, \
             largest bending moment {:.2} N m at {:.3} m, largest shear {:.1} N at {:.3} m.",
            s.gravity,
            supports_name(s.supports_model),
            s.max_deflection * 1e6,
            s.max_deflection_position,
            s.max_moment.abs(),
            s.max_moment_position,
            s.max_shear.abs(),
            s.max_shear_position,
        ),
    );
    let rows: Vec<String> = s
        .supports
        .iter()
        .map(|r| {
            let share = if s.weight > 0.0 {
                Some(100.0 * r.reaction / s.weight)
            } else {
                None
            };
            format!(
                "<tr>{}{}{}{}{}</tr>",
                td_num(&r.support.to_string()),
                td_num(&r.node.to_string()),
                td_num(&num(Some(r.reaction), |v| format!("{v:.1}"))),
                td_num(&num(Some(r.reaction_x), |v| format!("{v:.1}"))),
                td_num(&num(share, |v| format!("{v:.1}%"))),
            )
        })
        .collect();
    table(
        &mut o,
        &[
            "support",
            "node",
            "load y [N]",
            "load x [N]",
            "share of weight",
        ],
        &rows,
    );

    o.push_str("<h2 id=\"campbell\">Campbell diagram and critical speeds</h2>\n");
    let c = &report.campbell;
    figure(
        &mut o,
        &campbell_with(c, Some(range))?,
        "Whirl frequencies and decay rates against speed; shaded: the operating range.",
    );
    let rows: Vec<String> = c
        .criticals
        .iter()
        .map(|k| {
            // AF = 1 / (2 zeta) of the pole at the crossing; API 684: critically damped below 2.5.
            let af = (k.damping_ratio > 0.0).then(|| 0.5 / k.damping_ratio);
            format!(
                "<tr>{}{}{}{}{}{}{}{}</tr>",
                td_num(&k.mode.to_string()),
                td(&format!("{:?}", k.whirl).to_lowercase()),
                td_num(&num(Some(k.speed), |w| format!("{w:.1}"))),
                td_num(&num(Some(k.speed), |w| format!("{:.0}", w * RPM))),
                td_num(&num(k.log_decrement, |d| format!("{d:.3}"))),
                td_num(&num(af, |a| format!("{a:.2}"))),
                td(if k.critically_damped {
                    "critically damped"
                } else {
                    ""
                }),
                td_num(&num(Some(separation(k.speed, lo, hi)), |m| format!(
                    "{m:.1}%"
                ))),
            )
        })
        .collect();
    table(
        &mut o,
        &[
            "mode",
            "whirl",
            "critical speed [rad/s]",
            "[rpm]",
            "δ",
            "AF = 1/(2ζ)",
            "",
            "separation from the range",
        ],
        &rows,
    );
    let _ = writeln!(
        o,
        "<p>Onset of instability: {}.</p>",
        escape(&c.threshold.map_or("none in the speeds swept".into(), speed))
    );

    o.push_str("<h2 id=\"unbalance\">Unbalance response</h2>\n");
    let u = &report.unbalance;
    let rows: Vec<String> = u
        .nodes
        .iter()
        .flat_map(|n| {
            n.peaks
                .iter()
                .map(move |p| format!("<tr>{}{}</tr>", td_num(&n.node.to_string()), peak_cells(p)))
        })
        .collect();
    let head = [
        "node",
        "N_c [rad/s]",
        "[rpm]",
        "peak [µm]",
        "AF",
        "half-power",
        "SM",
        "required SM",
        "verdict",
    ];
    table(&mut o, &head, &rows);
    figure(&mut o, &unbalance_with(u, Some(range))?, &u.note);

    cases_section(&mut o, report, range)?;

    o.push_str("<h2 id=\"level1\">Level I stability screen (API 617)</h2>\n");
    let l = &report.level1;
    let (div, unit) = stiffness_unit(l.q0.into_iter().chain(l.qa).fold(0.0, f64::max));
    let q = |v: Option<f64>| num(v, |q| format!("{:.3} {unit}", q / div));
    let (class, word) = verdict(l.passes);
    let rows = vec![format!(
        "<tr>{}{}{}{}{}<td class=\"{class}\">{word}</td></tr>",
        td_num(&q(l.q0)),
        td_num(&q(l.qa)),
        td_num(&num(l.ratio, |r| format!("{r:.2}"))),
        td_num(&num(l.log_decrement_0, |d| format!("{d:.3}"))),
        td_num(&num(l.log_decrement_at_qa, |d| format!("{d:.3}"))),
    )];
    table(
        &mut o,
        &[
            "q0 (δ = 0)",
            "q_A",
            "q0 / q_A",
            "δ at q = 0",
            "δ at q_A",
            "Level I",
        ],
        &rows,
    );
    if let Some(l2) = &l.level2 {
        o.push_str("<p>Level II (API 617): the first forward mode at the maximum continuous speed with each destabilising source alone, then all together.</p>\n");
        let rows: Vec<String> = l2
            .sources
            .iter()
            .map(|s| {
                let (class, word) = verdict(Some(s.passes));
                format!(
                    "<tr>{}{}{}<td class=\"{class}\">{word}</td></tr>",
                    td(&s.source),
                    td_num(&num(s.log_decrement, |d| format!("{d:.3}"))),
                    td_num(&num(s.frequency, |f| format!("{:.0}", f * RPM))),
                )
            })
            .collect();
        table(
            &mut o,
            &["configuration", "δ", "frequency [rpm]", "δ ≥ 0.1"],
            &rows,
        );
    }
    figure(
        &mut o,
        &level1(l)?,
        &format!(
            "Log decrement of the first forward mode at {} against the cross-coupling at nodes {:?}.",
            speed(l.speed),
            l.nodes
        ),
    );

    o.push_str("<h2 id=\"models\">Damping models compared</h2>\n");
    o.push_str("<p>The same margins under each damping model: hysteretic, equivalent viscous and nonviscous damping need not agree.</p>\n");
    models_table(&mut o, report, lo, hi);
    sets_section(&mut o, report, lo, hi);
    torsion_section(&mut o, report)?;

    let mut warnings: Vec<&String> = vec![];
    let all = [
        &report.warnings,
        &report.critical_speed_map.warnings,
        &report.static_deflection.warnings,
        &report.campbell.warnings,
        &report.unbalance.warnings,
        &report.level1.warnings,
    ];
    for w in all.into_iter().flatten() {
        if !warnings.contains(&w) {
            warnings.push(w);
        }
    }
    if !warnings.is_empty() {
        o.push_str("<h2 id=\"warnings\">Warnings</h2>\n<div class=\"warn\"><ul>\n");
        for w in warnings {
            let _ = writeln!(o, "<li>{}</li>", escape(w));
        }
        o.push_str("</ul></div>\n");
    }
    let made = report.provenance.as_ref().map_or(String::new(), |p| {
        format!(
            " {} {}, {}; input SHA-256 {}.",
            p.software, p.version, p.generated, p.input_sha256
        )
    });
    let _ = writeln!(
        o,
        "<footer>Generated by Whirl.{} Speeds in rad/s and rpm; amplitudes zero to peak unless marked pk-pk.</footer>",
        escape(&made)
    );
    o.push_str("</main></body>\n</html>\n");
    Ok(o)
}

mod cases;
mod models;
mod sets;
mod summary;
mod torsion;
use cases::cases_section;
use models::models_table;
use sets::sets_section;
use summary::model_rows;
use torsion::torsion_section;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_print_without_nan_or_minus_zero() {
        assert_eq!(num(Some(-0.01), |v| format!("{v:.1} N")), "0.0 N");
        assert_eq!(num(Some(-0.5), |v| format!("{v:.1}")), "-0.5");
        assert_eq!(num(Some(f64::NAN), |v| format!("{v}")), "—");
        assert_eq!(num(None, |v| format!("{v}")), "—");
        assert_eq!(speed(f64::INFINITY), "—");
        assert_eq!(separation(120.0, 180.0, 300.0).round(), 33.0);
        assert_eq!(separation(200.0, 180.0, 300.0), 0.0);
        assert_eq!(
            escape("<a href='x'>&</a>"),
            "&lt;a href=&#39;x&#39;&gt;&amp;&lt;/a&gt;"
        );
    }
}
