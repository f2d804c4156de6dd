//! Validated spin-speed grids.

use super::api::SpeedsInput;
use super::error::{Invalid, finite};

/// Spin speeds, rad/s: finite, non-negative, strictly increasing, at least two.
#[derive(Debug, Clone, PartialEq)]
pub struct SpeedGrid(Vec<f64>);

impl SpeedGrid {
    /// Validates `speeds`; `max` is the configured limit on the number of speeds.
    pub fn parse(input: &SpeedsInput, max: usize) -> Result<Self, Invalid> {
        match input {
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
                    let (a, b, n) = (start.unwrap(), stop.unwrap(), r.count as usize);
                    let h = (b - a) / (n - 1) as f64;
                    // The last point is `stop` exactly, not a + (n-1) h with round-off.
                    SpeedGrid(
                        (0..n)
                            .map(|i| if i + 1 == n { b } else { a + i as f64 * h })
                            .collect(),
                    )
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
        }
    }

    pub fn as_slice(&self) -> &[f64] {
        &self.0
    }

    /// First and last speed.
    pub fn range(&self) -> (f64, f64) {
        (self.0[0], self.0[self.0.len() - 1])
    }
}
