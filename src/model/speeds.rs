//! Validated spin-speed grids and operating ranges.

use super::api::{OperatingRange, SpeedsInput};
use super::error::{Invalid, finite, positive};

/// rad/s to rpm: `60 / (2 pi)`.
pub const RPM: f64 = 60.0 / (2.0 * std::f64::consts::PI);

/// Largest integer a double holds exactly, and then every smaller one.
const EXACT: f64 = 9_007_199_254_740_992.0;

/// `x` as `m / 10^p` with integers `m` and `p <= 15` (the fewest decimals), when the double
/// nearest that decimal is `x`, as it is for a decimal literal like `0.05`.
fn decimal(x: f64) -> Option<(f64, i32)> {
    (0..=15).find_map(|p| {
        let scale = 10f64.powi(p);
        let m = (x * scale).round();
        (m.abs() < EXACT && m / scale == x).then_some((m, p))
    })
}

/// `n >= 2` points from `a` to `b`, both included: `a + (b - a) i / (n - 1)`. When `a` and `b`
/// are decimals (as typed) every point is the double nearest its exact value, computed as one
/// division of exact integers, so a decimal grid prints as decimals (`0.15`, not
/// `0.15000000000000002`); otherwise within round-off of it. The ends are `a` and `b` exactly.
pub fn linear(a: f64, b: f64, n: usize) -> Vec<f64> {
    let last = (n - 1) as f64;
    let exact = match (decimal(a), decimal(b)) {
        (Some((ma, pa)), Some((mb, pb))) => {
            let p = pa.max(pb);
            let (ma, mb) = (ma * 10f64.powi(p - pa), mb * 10f64.powi(p - pb));
            let den = last * 10f64.powi(p);
            // Every product and sum below is an integer below 2^53: exact.
            (ma.abs() < EXACT
                && mb.abs() < EXACT
                && (ma.abs() + mb.abs()) * last < EXACT
                && den < EXACT)
                .then_some((ma, mb, den))
        }
        _ => None,
    };
    (0..n)
        .map(|i| {
            let k = i as f64;
            if i == 0 {
                a
            } else if i + 1 == n {
                b
            } else if let Some((ma, mb, den)) = exact {
                (ma * (last - k) + mb * k) / den
            } else {
                a + (b - a) * k / last
            }
        })
        .collect()
}

/// `k dt` for `k = 0..n`: the double nearest `k dt` when `dt` is a decimal (`3 x 0.1` is `0.3`,
/// not `0.30000000000000004`), `k * dt` otherwise.
pub fn multiples(dt: f64, n: usize) -> Vec<f64> {
    let exact = decimal(dt).filter(|&(m, _)| m.abs() * n as f64 <= EXACT);
    (0..n)
        .map(|k| match exact {
            Some((m, p)) => k as f64 * m / 10f64.powi(p),
            None => k as f64 * dt,
        })
        .collect()
}

/// `n >= 2` points from `a > 0` to `b`, both included, evenly spaced in log: `a (b/a)^(i/(n-1))`,
/// each rounded to 12 significant digits when that moves it by round-off only (a few units in
/// the last place), so that decades print as `1e7`, not `10000000.000000002`. The ends are `a`
/// and `b` exactly.
pub fn logarithmic(a: f64, b: f64, n: usize) -> Vec<f64> {
    let last = (n - 1) as f64;
    (0..n)
        .map(|i| {
            if i == 0 {
                return a;
            }
            if i + 1 == n {
                return b;
            }
            let x = a * (b / a).powf(i as f64 / last);
            let tidy: f64 = format!("{x:.11e}").parse().unwrap_or(x);
            if (tidy - x).abs() <= 8.0 * f64::EPSILON * x.abs() {
                tidy
            } else {
                x
            }
        })
        .collect()
}

/// Spin speeds, rad/s: finite, non-negative, strictly increasing, at least two.
#[derive(Debug, Clone, PartialEq)]
pub struct SpeedGrid(Vec<f64>);

impl SpeedGrid {
    /// Validates `speeds` (in their unit; the grid is in rad/s); `max` is the configured limit
    /// on the number of speeds.
    pub fn parse(input: &SpeedsInput, max: usize) -> Result<Self, Invalid> {
        let unit = input.unit();
        Self::parse_typed(input, max)
            .map(|g| SpeedGrid(g.0.into_iter().map(|x| unit.to_rad_s(x)).collect()))
    }

    /// [`SpeedGrid::parse`] in the unit typed.
    fn parse_typed(input: &SpeedsInput, max: usize) -> Result<Self, Invalid> {
        let (input, path) = match input {
            SpeedsInput::Values(v) => (&SpeedsInput::List(v.values.clone()), "speeds.values"),
            other => (other, "speeds"),
        };
        let r = match input {
            SpeedsInput::Range(r) => {
                let mut bad = Invalid::default();
                let start = bad.check("speeds.start", finite(r.start));
                let stop = bad.check("speeds.stop", finite(r.stop));
                if let Some(s) = start
                    && s < 0.0
                {
                    bad.push("speeds.start", format!("must be >= 0 (got {s})"));
                }
                if let (Some(a), Some(b)) = (start, stop)
                    && b <= a
                {
                    bad.push("speeds.stop", format!("must be > start ({a}) (got {b})"));
                }
                if r.count < 2 {
                    bad.push("speeds.count", format!("must be >= 2 (got {})", r.count));
                } else if r.count as u64 > max as u64 {
                    bad.push(
                        "speeds.count",
                        format!("at most {max} speeds per request (got {})", r.count),
                    );
                }
                bad.into_result(|| {
                    SpeedGrid(linear(start.unwrap(), stop.unwrap(), r.count as usize))
                })
            }
            SpeedsInput::List(v) => {
                let mut bad = Invalid::default();
                if v.len() < 2 {
                    bad.push(
                        "speeds",
                        format!("needs at least 2 speeds (got {})", v.len()),
                    );
                } else if v.len() > max {
                    bad.push(
                        "speeds",
                        format!("at most {max} speeds per request (got {})", v.len()),
                    );
                }
                for (i, &x) in v.iter().enumerate() {
                    let path = format!("speeds[{i}]");
                    if !x.is_finite() {
                        bad.push(path, "must be a finite number");
                    } else if x < 0.0 {
                        bad.push(path, format!("must be >= 0 (got {x})"));
                    } else if i > 0 && v[i - 1].is_finite() && x <= v[i - 1] {
                        bad.push(path, "speeds must be strictly increasing");
                    }
                }
                bad.into_result(|| SpeedGrid(v.clone()))
            }
            SpeedsInput::Values(_) => unreachable!("a list above"),
        };
        r.map_err(|mut e| {
            if path != "speeds" {
                e.prefix_paths(|p| p.replacen("speeds", path, 1));
            }
            e
        })
    }

    pub fn as_slice(&self) -> &[f64] {
        &self.0
    }

    /// First and last speed.
    pub fn range(&self) -> (f64, f64) {
        (self.0[0], self.0[self.0.len() - 1])
    }
}

/// Validates an operating range (in its unit), in rad/s.
pub(crate) fn operating_range(
    r: &OperatingRange,
    at: &str,
    bad: &mut Invalid,
) -> Option<(f64, f64)> {
    let unit = r.unit.unwrap_or_default();
    operating_range_typed(r, at, bad).map(|(lo, hi)| (unit.to_rad_s(lo), unit.to_rad_s(hi)))
}

fn operating_range_typed(r: &OperatingRange, at: &str, bad: &mut Invalid) -> Option<(f64, f64)> {
    let lo = bad.check(&format!("{at}.min"), positive(r.min));
    let hi = bad.check(&format!("{at}.max"), positive(r.max));
    match (lo, hi) {
        (Some(lo), Some(hi)) if hi >= lo => Some((lo, hi)),
        (Some(lo), Some(hi)) => {
            bad.push(
                format!("{at}.max"),
                format!("must be >= min ({lo}) (got {hi})"),
            );
            None
        }
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decimal_grids_are_decimals_and_end_at_stop() {
        let g = linear(0.0, 1.0, 21);
        assert_eq!(g[3], 0.15);
        assert_eq!(g[3].to_string(), "0.15");
        assert_eq!(g[20], 1.0);
        let g = linear(0.1, 0.3, 5);
        assert_eq!(g, [0.1, 0.15, 0.2, 0.25, 0.3]);
        let g = linear(0.0, 0.3, 4);
        assert_eq!(g, [0.0, 0.1, 0.2, 0.3]);
        let g = linear(-1.0, 1.0, 21);
        assert_eq!(g[11], 0.1);
        for (i, x) in linear(0.0, 2000.0, 201).iter().enumerate() {
            assert_eq!(*x, 10.0 * i as f64);
        }
        // Not decimals: within round-off, increasing, the ends exact.
        let third = 1.0 / 3.0;
        let g = linear(third, 1e300, 7);
        assert_eq!((g[0], g[6]), (third, 1e300));
        assert!(g.windows(2).all(|w| w[0] < w[1]));
        let t = multiples(1e-4, 40);
        assert_eq!(t[3], 0.0003);
        assert_eq!(t[39].to_string(), "0.0039");
        let k = logarithmic(1e6, 1e11, 6);
        assert_eq!(k, [1e6, 1e7, 1e8, 1e9, 1e10, 1e11]);
        let k = logarithmic(1.0, 2.0, 5);
        assert!((k[2] - 2f64.sqrt()).abs() < 1e-15);
    }
}
