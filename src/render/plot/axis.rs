//! Axes of the plots: linear and log ranges, nice tick steps (1, 2, 5 x 10^k) labelled with
//! as many decimals as the step needs, engineering length units.

/// An axis `[lo, hi]`, linear or logarithmic (then `lo > 0`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Axis {
    pub lo: f64,
    pub hi: f64,
    pub log: bool,
    /// A linear axis's tick step, when not chosen from the range.
    pub step: Option<f64>,
}

impl Axis {
    pub fn lin(lo: f64, hi: f64) -> Self {
        let (lo, hi) = if hi > lo {
            (lo, hi)
        } else {
            (lo - 0.5, lo + 0.5)
        };
        Axis {
            lo,
            hi,
            log: false,
            step: None,
        }
    }

    pub fn log(lo: f64, hi: f64) -> Self {
        let lo = if lo > 0.0 { lo } else { 1e-12 };
        let hi = if hi > lo { hi } else { lo * 10.0 };
        Axis {
            lo,
            hi,
            log: true,
            step: None,
        }
    }

    /// This axis ticked every `step`.
    pub fn with_step(self, step: f64) -> Self {
        Axis {
            step: (step.is_finite() && step > 0.0).then_some(step),
            ..self
        }
    }

    /// Position of `v` along the axis, 0 at `lo` and 1 at `hi`.
    pub fn frac(&self, v: f64) -> f64 {
        if self.log {
            (v.max(f64::MIN_POSITIVE).ln() - self.lo.ln()) / (self.hi.ln() - self.lo.ln())
        } else {
            (v - self.lo) / (self.hi - self.lo)
        }
    }

    /// The value at position `t` (the inverse of [`Axis::frac`]).
    pub fn value(&self, t: f64) -> f64 {
        if self.log {
            (self.lo.ln() + t * (self.hi.ln() - self.lo.ln())).exp()
        } else {
            self.lo + t * (self.hi - self.lo)
        }
    }

    /// Ticks and their labels, about `n` of them on a linear axis.
    pub fn ticks(&self, n: usize) -> Vec<(f64, String)> {
        if self.log {
            return log_ticks(self.lo, self.hi);
        }
        let step = self
            .step
            .unwrap_or_else(|| nice_step((self.hi - self.lo) / n.max(1) as f64));
        let first = (self.lo / step - 1e-9).ceil() as i64;
        let last = (self.hi / step + 1e-9).floor() as i64;
        (first..=last)
            .map(|k| {
                let v = k as f64 * step;
                (v, tick_label(v, step))
            })
            .collect()
    }
}

/// The nearest of 1, 2, 5 x 10^k to `raw` (geometrically, near enough).
pub fn nice_step(raw: f64) -> f64 {
    if !(raw.is_finite() && raw > 0.0) {
        return 1.0;
    }
    let p = 10f64.powf(raw.log10().floor());
    let m = raw / p;
    let m = if m < 1.5 {
        1.0
    } else if m < 3.5 {
        2.0
    } else if m < 7.5 {
        5.0
    } else {
        10.0
    };
    m * p
}

/// `v` with as many decimals as a tick step `step` needs; exponent form past 1e6 or below
/// 1e-4 steps.
pub fn tick_label(v: f64, step: f64) -> String {
    if v.abs() < step * 1e-6 {
        return "0".into();
    }
    if !(1e-4..1e6).contains(&step) {
        let e = step.log10().floor() as i32;
        let m = v / 10f64.powi(e);
        return format!("{}e{e}", trim(&format!("{m:.1}")));
    }
    let decimals = (-(step.log10() + 1e-9).floor()).max(0.0) as usize;
    format!("{v:.decimals$}")
}

fn trim(s: &str) -> String {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s.to_string()
    }
}

/// Powers of ten in `[lo, hi]`, with 2 and 5 times them when it spans at most three decades.
fn log_ticks(lo: f64, hi: f64) -> Vec<(f64, String)> {
    let mut out = vec![];
    let dense = (hi / lo).log10() <= 3.0;
    let mut e = lo.log10().floor() as i32;
    while 10f64.powi(e) <= hi * (1.0 + 1e-9) {
        for m in [1.0, 2.0, 5.0] {
            let v = m * 10f64.powi(e);
            if (m == 1.0 || dense) && v >= lo * (1.0 - 1e-9) && v <= hi * (1.0 + 1e-9) {
                let label = if (-4..6).contains(&e) {
                    tick_label(v, 10f64.powi(e))
                } else {
                    format!("{m}e{e}")
                };
                out.push((v, label));
            }
        }
        e += 1;
    }
    out
}

/// `[lo, hi]` of the finite values, or `None`.
pub fn extent(values: impl IntoIterator<Item = f64>) -> Option<(f64, f64)> {
    let (lo, hi) = values
        .into_iter()
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    lo.is_finite().then_some((lo, hi))
}

/// A length unit for values up to `max` m: `(factor, name)`.
pub fn length_unit(max: f64) -> (f64, &'static str) {
    let max = max.abs();
    if max >= 0.1 {
        (1.0, "m")
    } else if max >= 1e-3 {
        (1e3, "mm")
    } else if max >= 1e-7 || max == 0.0 || !max.is_finite() {
        (1e6, "µm")
    } else {
        (1e9, "nm")
    }
}

/// `v` to `n` significant digits, plainly written.
pub fn sig(v: f64, n: i32) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let d = (n - 1 - v.abs().log10().floor() as i32).clamp(0, 12) as usize;
    format!("{v:.d$}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_nice_and_distinct() {
        assert_eq!(nice_step(0.13), 0.1);
        assert_eq!(nice_step(0.22), 0.2);
        assert_eq!(nice_step(370.0), 500.0);
        let t = Axis::lin(0.0, 1.3).ticks(6);
        let labels: Vec<&str> = t.iter().map(|t| t.1.as_str()).collect();
        assert_eq!(labels, ["0", "0.2", "0.4", "0.6", "0.8", "1.0", "1.2"]);
        let t = Axis::lin(0.0, 3000.0).ticks(8);
        assert_eq!(t[1].1, "500");
        assert_eq!(tick_label(2.5e-5, 1e-5), "2.5e-5");
        let t = Axis::log(0.5, 300.0).ticks(0);
        let labels: Vec<&str> = t.iter().map(|t| t.1.as_str()).collect();
        assert_eq!(
            labels,
            ["0.5", "1", "2", "5", "10", "20", "50", "100", "200"]
        );
    }

    #[test]
    fn units_follow_the_data() {
        assert_eq!(length_unit(6e-4).1, "µm");
        assert_eq!(length_unit(2e-3).1, "mm");
        assert_eq!(length_unit(6e-5).1, "µm");
        assert_eq!(length_unit(2e-9).1, "nm");
    }
}
