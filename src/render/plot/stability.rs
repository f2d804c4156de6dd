//! The stability plot: the largest decay rate against spin speed, the threshold marked (and,
//! for a rotor held sparse, the box of poles it considered named in the caption).

use super::campbell::{LEFT, RED, RIGHT, W, band, clipped_note, decay_range};
use super::svg::{Axis, INK, Stroke, Svg, extent};
use super::{COLOURS, Err, RPM, SHADE_HEX, clip};
use crate::model::api::{StabilityResponse, Whirl};
/// Largest decay rate against speed, the threshold marked.
pub fn stability(s: &StabilityResponse) -> Result<String, Err> {
    stability_with(s, None)
}

/// [`stability`] with the operating speeds `shade = [min, max]` (rad/s) shaded.
pub fn stability_with(s: &StabilityResponse, shade: Option<[f64; 2]>) -> Result<String, Err> {
    let mut svg = Svg::new(W as u32, 540).nondimensional(s.nondimensional);
    let (x0, x1) = extent(s.speeds.iter().copied()).unwrap_or((0.0, 1.0));
    let x = Axis::lin(x0, x1);
    let (y0, y1, clipped) = decay_range(s.max_decay_rate.iter().copied());
    // A rotor held sparse considers the poles in a box only: the caption says which.
    let caption = match s.max_frequency {
        Some(b) => {
            format!("Stability: largest decay rate of the poles with |σ|, |ω| ≤ {b:.0} rad/s")
        }
        None => "Stability: largest decay rate".to_string(),
    };
    svg.caption((W / 2.0, 24.0), &caption);
    let p = svg.panel([LEFT, 84.0, RIGHT, 476.0], x, Axis::lin(y0, y1));
    let shade = clip(shade, x.lo, x.hi);
    if let Some(b) = shade {
        band(&mut svg, &p, b);
    }
    svg.axes(
        &p,
        "spin speed [rad/s]",
        "largest decay rate σ [1/s]  (> 0 unstable)",
    );
    svg.top_axis(&p, RPM, "spin speed [rpm]");
    svg.path(
        &p,
        &[(x.lo, 0.0), (x.hi, 0.0)],
        Stroke::solid(INK, 1.0),
        "zero",
    );
    let pts: Vec<(f64, f64)> = s
        .speeds
        .iter()
        .copied()
        .zip(s.max_decay_rate.iter().copied())
        .collect();
    svg.path(&p, &pts, Stroke::solid(COLOURS[0], 2.0), "decay");
    let mut key: Vec<(String, &str, Option<&str>)> = vec![];
    if let Some(t) = s.threshold {
        svg.path(
            &p,
            &[(t, y0), (t, y1)],
            Stroke::solid(RED, 2.0),
            "threshold",
        );
        let mut name = format!("threshold {}", svg.speed_label(t));
        if let (Some(m), Some(w)) = (s.mode, s.whirl) {
            let w = if w == Whirl::Backward { "B" } else { "F" };
            name += &format!(": mode {m}{w}");
            if let Some(f) = s.frequency {
                name += &format!(" at {}", svg.frequency_label(f));
            }
        }
        key.push((name, RED, None));
    }
    if shade.is_some() {
        key.push(("operating range".into(), SHADE_HEX, Some("shade")));
    }
    svg.key_in(&p, &key);
    if let Some(m) = clipped {
        clipped_note(&mut svg, &p, m, 44.0);
    }
    Ok(svg.finish())
}
