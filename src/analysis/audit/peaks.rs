//! Resonance peaks of a response curve, their amplification factors, and API 684's separation
//! margins.
//!
//! A peak is an interior local maximum of the amplitude over the grid, refined between the
//! grid's neighbours by Brent's minimisation on the response itself (`eval`, one steady solve
//! per call), so that it does not depend on how fine the grid is. Its half-power points
//! `N_1 < N_c < N_2`, where the amplitude is `A_peak / sqrt 2`, are bracketed on the grid and
//! refined by Brent's root finding; the amplification factor is `AF = N_c / (N_2 - N_1)`
//! (API 684), `1 / (2 zeta)` for a lightly damped single mode; the ratio is the same on the
//! zero-to-peak and the peak-to-peak amplitude. A half-power point that the curve does not
//! reach before it rises above the peak again, or before the grid ends, is missing: with the
//! other one the peak is taken as symmetric (`AF = N_c / (2 |N_c - N_i|)`, flagged
//! `one_sided`); with neither the AF is undefined, as it is for an undamped peak (never
//! infinite).
//!
//! Separation margin of a peak from the operating range `[N_min, N_max]`: below it
//! `100 (N_min - N_c) / N_min`, above it `100 (N_c - N_max) / N_max` (percent). Required for
//! `AF >= 2.5` (below 2.5 the mode is critically damped and needs none):
//! `min(16, 17 (1 - 1 / (AF - 1.5)))` below the range, `min(26, 10 + 17 (1 - 1 / (AF - 1.5)))`
//! above it; a peak inside the range with `AF >= 2.5` fails.

use crate::analysis::AnalysisError;

/// A refined peak.
#[derive(Debug, Clone, PartialEq)]
pub struct Peak {
    pub speed: f64,
    pub amplitude: f64,
    pub half_power: Option<[f64; 2]>,
    pub amplification_factor: Option<f64>,
    /// Whether the AF came from one half-power point (the other beyond the sweep or hidden by
    /// a neighbouring peak), the peak taken as symmetric.
    pub one_sided: bool,
    /// Whether it was refined on the response (else interpolated linearly on the grid).
    pub refined: bool,
}

impl Peak {
    /// API 684: a mode with `AF < 2.5` is critically damped (it needs no separation margin);
    /// unknown without an AF.
    pub fn critically_damped(&self) -> Option<bool> {
        self.amplification_factor
            .map(|af| af < CRITICALLY_DAMPED_AF)
    }
}

/// API 684's amplification factor below which a mode is critically damped.
pub const CRITICALLY_DAMPED_AF: f64 = 2.5;

/// Most steady solves one peak's refinement takes (Brent's maximisation and two roots, each
/// well under 40 steps at 1e-10).
pub const SOLVES_PER_PEAK: usize = 120;

/// The margin of a peak from an operating range.
#[derive(Debug, Clone, PartialEq)]
pub struct Margin {
    /// Percent; 0 inside the range.
    pub separation: f64,
    /// Percent; `None` where API 684 requires none (AF < 2.5) or the AF is unknown.
    pub required: Option<f64>,
    /// `None` when the AF is unknown.
    pub passes: Option<bool>,
}

/// Relative tolerance of the refined speeds.
const SPEED_TOL: f64 = 1e-10;

/// Peaks of `amplitude` over `speeds` (increasing), refined with `eval(speed) = amplitude`
/// while `budget` (solves, shared between calls) lasts; the rest are interpolated on the grid
/// (a response with many peaks costs at most its budget).
pub fn peaks(
    speeds: &[f64],
    amplitude: &[f64],
    eval: &mut dyn FnMut(f64) -> Result<f64, AnalysisError>,
    budget: &mut usize,
) -> Result<Vec<Peak>, AnalysisError> {
    let mut grid = |x: f64| -> Result<f64, AnalysisError> { Ok(interpolate(speeds, amplitude, x)) };
    let n = speeds.len();
    let top = amplitude.iter().copied().fold(0.0_f64, f64::max);
    let mut out = vec![];
    if n < 3 || top <= 0.0 {
        return Ok(out);
    }
    for i in 1..n - 1 {
        let a = amplitude[i];
        // Plateaus count once, at their first point; round-off bumps do not count.
        if !(a > amplitude[i - 1] && a >= amplitude[i + 1]) || a < 1e-9 * top {
            continue;
        }
        let refined = *budget >= SOLVES_PER_PEAK;
        let mut calls = 0;
        let mut counted = |x: f64| {
            calls += 1;
            eval(x)
        };
        let eval: &mut dyn FnMut(f64) -> Result<f64, AnalysisError> =
            if refined { &mut counted } else { &mut grid };
        let (speed, peak) = maximise(speeds[i - 1], speeds[i], speeds[i + 1], a, eval)?;
        let target = peak / std::f64::consts::SQRT_2;
        // Walk out from the peak to the first grid point at or below the target.
        let left = (0..i)
            .rev()
            .take_while(|&j| amplitude[j] <= peak)
            .find(|&j| amplitude[j] <= target);
        let right = (i + 1..n)
            .take_while(|&j| amplitude[j] <= peak)
            .find(|&j| amplitude[j] <= target);
        let n1 = match left {
            Some(l) => {
                let l_hi = if l + 1 == i { speed } else { speeds[l + 1] };
                Some(crossing(speeds[l], l_hi, target, eval)?)
            }
            None => None,
        };
        let n2 = match right {
            Some(r) => {
                let r_lo = if r - 1 == i { speed } else { speeds[r - 1] };
                Some(crossing(r_lo, speeds[r], target, eval)?)
            }
            None => None,
        };
        let half = n1.zip(n2).map(|(a, b)| [a, b]);
        // One half-power point: the peak taken as symmetric, `AF = N_c / (2 |N_c - N_i|)`.
        let af = match (n1, n2) {
            (Some(a), Some(b)) => Some(speed / (b - a)),
            (Some(x), None) | (None, Some(x)) => Some(speed / (2.0 * (speed - x).abs())),
            (None, None) => None,
        }
        .filter(|af| af.is_finite() && *af > 0.0);
        if refined {
            *budget = budget.saturating_sub(calls.max(SOLVES_PER_PEAK / 4));
        }
        out.push(Peak {
            speed,
            amplitude: peak,
            amplification_factor: af,
            half_power: half,
            one_sided: af.is_some() && half.is_none(),
            refined,
        });
    }
    Ok(out)
}

/// `amplitude` linear between the grid's speeds.
fn interpolate(speeds: &[f64], amplitude: &[f64], x: f64) -> f64 {
    let k = speeds
        .partition_point(|&w| w <= x)
        .clamp(1, speeds.len() - 1);
    let t = (x - speeds[k - 1]) / (speeds[k] - speeds[k - 1]);
    amplitude[k - 1] + t * (amplitude[k] - amplitude[k - 1])
}

/// API 684's margin of a peak at `nc` with amplification factor `af` from `[min, max]`.
pub fn margin(nc: f64, af: Option<f64>, min: f64, max: f64) -> Margin {
    let (separation, below) = if nc < min {
        (100.0 * (min - nc) / min, true)
    } else if nc > max {
        (100.0 * (nc - max) / max, false)
    } else {
        // Inside: judged against the nearer end.
        (0.0, nc - min < max - nc)
    };
    let Some(af) = af else {
        return Margin {
            separation,
            required: None,
            passes: None,
        };
    };
    if af < CRITICALLY_DAMPED_AF {
        return Margin {
            separation,
            required: None,
            passes: Some(true),
        };
    }
    let base = 17.0 * (1.0 - 1.0 / (af - 1.5));
    let required = if below {
        base.min(16.0)
    } else {
        (10.0 + base).min(26.0)
    };
    let inside = nc >= min && nc <= max;
    Margin {
        separation,
        required: Some(required),
        passes: Some(!inside && separation >= required),
    }
}

/// The maximum of `eval` in `[a, c]` around `b` (with `eval(b) = fb`), by Brent's method on
/// `-eval`: golden sections with parabolic steps.
fn maximise(
    a: f64,
    b: f64,
    c: f64,
    fb: f64,
    eval: &mut dyn FnMut(f64) -> Result<f64, AnalysisError>,
) -> Result<(f64, f64), AnalysisError> {
    const GOLD: f64 = 0.381_966_011_250_105;
    let (mut lo, mut hi) = (a, c);
    let (mut x, mut w, mut v) = (b, b, b);
    let (mut fx, mut fw, mut fv) = (-fb, -fb, -fb);
    let (mut d, mut e) = (0.0_f64, 0.0_f64);
    for _ in 0..100 {
        let m = 0.5 * (lo + hi);
        let tol = SPEED_TOL * x.abs() + 1e-300;
        if (x - m).abs() <= 2.0 * tol - 0.5 * (hi - lo) {
            break;
        }
        let mut golden = true;
        if e.abs() > tol {
            let r = (x - w) * (fx - fv);
            let q0 = (x - v) * (fx - fw);
            let mut p = (x - v) * q0 - (x - w) * r;
            let mut q = 2.0 * (q0 - r);
            if q > 0.0 {
                p = -p;
            }
            q = q.abs();
            if p.abs() < (0.5 * q * e).abs() && p > q * (lo - x) && p < q * (hi - x) {
                e = d;
                d = p / q;
                let u = x + d;
                if u - lo < 2.0 * tol || hi - u < 2.0 * tol {
                    d = if x < m { tol } else { -tol };
                }
                golden = false;
            }
        }
        if golden {
            e = if x < m { hi - x } else { lo - x };
            d = GOLD * e;
        }
        let u = if d.abs() >= tol {
            x + d
        } else {
            x + tol.copysign(d)
        };
        let fu = -eval(u)?;
        if fu <= fx {
            if u < x {
                hi = x;
            } else {
                lo = x;
            }
            (v, fv, w, fw, x, fx) = (w, fw, x, fx, u, fu);
        } else {
            if u < x {
                lo = u;
            } else {
                hi = u;
            }
            if fu <= fw || w == x {
                (v, fv, w, fw) = (w, fw, u, fu);
            } else if fu <= fv || v == x || v == w {
                (v, fv) = (u, fu);
            }
        }
    }
    Ok((x, -fx))
}

/// The speed in `[a, b]` where `eval` equals `target` (it crosses there), by Brent's method.
fn crossing(
    a: f64,
    b: f64,
    target: f64,
    eval: &mut dyn FnMut(f64) -> Result<f64, AnalysisError>,
) -> Result<f64, AnalysisError> {
    let mut f = |x: f64| -> Result<f64, AnalysisError> { Ok(eval(x)? - target) };
    let (fa, fb) = (f(a)?, f(b)?);
    if fa == 0.0 {
        return Ok(a);
    }
    if fb == 0.0 || fa.signum() == fb.signum() {
        return Ok(b);
    }
    // Brent's tolerance is half the bracket's relative width.
    crate::analysis::roots::brent(f, (a, b), (fa, fb), 2.0 * SPEED_TOL)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `|H|` of a single mode under unbalance forcing `Omega^2`: its peak and half-power points
    /// are known in closed form.
    fn single_mode(zeta: f64) -> impl Fn(f64) -> f64 {
        move |w: f64| w * w / ((1.0 - w * w).powi(2) + (2.0 * zeta * w).powi(2)).sqrt()
    }

    #[test]
    fn refined_peak_and_af_of_a_single_mode() {
        let zeta = 0.02;
        let h = single_mode(zeta);
        let speeds: Vec<f64> = (0..41).map(|i| 0.05 * i as f64).collect();
        let amp: Vec<f64> = speeds.iter().map(|&w| h(w)).collect();
        let mut eval = |w: f64| Ok(h(w));
        let p = peaks(&speeds, &amp, &mut eval, &mut 1000).unwrap();
        assert!(p[0].refined);
        assert_eq!(p.len(), 1);
        // Peak of w^2 / |1 - w^2 + 2 i zeta w| at w = 1 / sqrt(1 - 2 zeta^2).
        let exact = 1.0 / (1.0 - 2.0 * zeta * zeta).sqrt();
        assert!((p[0].speed - exact).abs() < 1e-7, "{}", p[0].speed);
        let [n1, n2] = p[0].half_power.unwrap();
        let t = p[0].amplitude / std::f64::consts::SQRT_2;
        assert!((h(n1) - t).abs() < 1e-9 * t && (h(n2) - t).abs() < 1e-9 * t);
        let af = p[0].amplification_factor.unwrap();
        assert!((af * 2.0 * zeta - 1.0).abs() < 2.0 * zeta, "AF {af}");
        // Without a budget: the grid's own peak and linear half-power points.
        let p = peaks(&speeds, &amp, &mut eval, &mut 0).unwrap();
        assert!(!p[0].refined);
        assert_eq!((p[0].speed, p[0].amplitude), (1.0, h(1.0)));
    }

    #[test]
    fn api_684_margins() {
        // AF 10 below the range: 17 (1 - 1/8.5) = 15.0 %.
        let m = margin(800.0, Some(10.0), 1000.0, 1500.0);
        assert!((m.separation - 20.0).abs() < 1e-12);
        assert!((m.required.unwrap() - 17.0 * (1.0 - 1.0 / 8.5)).abs() < 1e-12);
        assert_eq!(m.passes, Some(true));
        // Above, capped at 26 %.
        let m = margin(1800.0, Some(100.0), 1000.0, 1500.0);
        assert!((m.separation - 20.0).abs() < 1e-12);
        assert_eq!(
            m.required,
            Some(26.0_f64.min(10.0 + 17.0 * (1.0 - 1.0 / 98.5)))
        );
        assert_eq!(m.passes, Some(false));
        // Critically damped: no margin needed, even inside the range.
        assert_eq!(margin(1200.0, Some(2.0), 1000.0, 1500.0).passes, Some(true));
        assert_eq!(
            margin(1200.0, Some(3.0), 1000.0, 1500.0).passes,
            Some(false)
        );
    }
}
