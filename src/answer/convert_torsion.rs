//! The report's torsional section: its interference diagram and transient, and the checks
//! they give (API 684's 10% separation of each torsional mode that an excitation can reach).

use super::output::Output;
use crate::model::api::{self, Interference, ReportCheck, TorsionReport};
use crate::model::task::TorsionPlan;

/// The section from its parts (the Campbell, then the transient if planned), and its checks.
pub fn section(
    next: &mut dyn FnMut() -> Result<Output, &'static str>,
    plan: &TorsionPlan,
    checks: &mut Vec<ReportCheck>,
) -> Result<TorsionReport, String> {
    let Output::Campbell(campbell) = next()? else {
        return Err("report: torsional Campbell".into());
    };
    let transient = match &plan.transient {
        Some(_) => match next()? {
            Output::Time(t) => Some(t),
            _ => return Err("report: torsional transient".into()),
        },
        None => None,
    };
    let model = plan.campbell.model().map_or("", |m| m.damping.name());
    if let Some(i) = &campbell.interference {
        checks.extend(separation_checks(&campbell, i, model));
    }
    Ok(TorsionReport {
        campbell,
        transient,
    })
}

/// One check per mode an excitation can reach ([`Interference::reach`]): its smallest margin.
fn separation_checks(c: &api::CampbellResponse, i: &Interference, model: &str) -> Vec<ReportCheck> {
    let hz = |f: f64| i.unit.to_rad_s(f) / std::f64::consts::TAU;
    let mut out = vec![];
    for b in &c.branches {
        let Some(k) = i.nearest(b.mode) else { continue };
        if k.frequency > i.reach() {
            continue;
        }
        out.push(ReportCheck {
            check: format!(
                "torsional mode {} ({:.2} Hz) from its nearest excitation, {}",
                b.mode,
                hz(k.frequency),
                i.label(k.excitation)
            ),
            model: model.into(),
            value: format!("SM {:.1} %", 100.0 * k.margin),
            requirement: "SM >= 10 % over the operating range (API 684)".into(),
            passes: k.passes,
        });
    }
    out
}
