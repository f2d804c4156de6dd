//! Shape-preserving interpolation of a coefficient table (ROSS 3's tables over speed and whirl
//! frequency: PCHIP, or linear on request; extrapolated linearly beyond the ends).
//!
//! PCHIP (Fritsch and Carlson; Fritsch and Butland's weights, as scipy's
//! `PchipInterpolator`): on `[x_k, x_{k+1}]` the cubic Hermite interpolant of the values `y_k`
//! and slopes `d_k`, where with `h_k = x_{k+1} - x_k` and `m_k = (y_{k+1} - y_k) / h_k`
//!
//! - inside, `d_k = 0` where `m_{k-1}` and `m_k` differ in sign or either is zero, else the
//!   weighted harmonic mean `(w1 + w2) / d_k = w1 / m_{k-1} + w2 / m_k`,
//!   `w1 = 2 h_k + h_{k-1}`, `w2 = h_k + 2 h_{k-1}`;
//! - at an end, the three-point estimate `((2 h_0 + h_1) m_0 - h_0 m_1) / (h_0 + h_1)`, set to
//!   zero where its sign is not `m_0`'s and to `3 m_0` where `m_0`, `m_1` differ in sign and it
//!   passes `3 |m_0|`;
//! - with two points, the line through them.
//!
//! The curve passes through every value, keeps each interval's monotonicity (no overshoot)
//! and is C1. Past the ends it continues as the line of the end value and slope.

/// How a table is read between its points.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Interpolation {
    #[default]
    Pchip,
    Linear,
}

/// One coefficient tabulated over a strictly increasing axis.
#[derive(Debug, Clone, PartialEq)]
pub struct Table1 {
    x: Vec<f64>,
    y: Vec<f64>,
    how: Interpolation,
    /// PCHIP: the slope at each point. Linear: each interval's slope, then the last again.
    d: Vec<f64>,
}

fn sign(v: f64) -> i8 {
    (v > 0.0) as i8 - (v < 0.0) as i8
}

impl Table1 {
    /// The table `(x, y)`: at least one point, `x` strictly increasing (the caller's check).
    pub fn new(x: &[f64], y: &[f64], how: Interpolation) -> Self {
        assert!(!x.is_empty() && x.len() == y.len());
        let n = x.len();
        let h: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
        let m: Vec<f64> = (0..n - 1).map(|k| (y[k + 1] - y[k]) / h[k]).collect();
        let d = match (n, how) {
            (1, _) => vec![0.0],
            (2, _) => vec![m[0]; 2],
            (_, Interpolation::Linear) => {
                let mut d = m.clone();
                d.push(m[n - 2]);
                d
            }
            (_, Interpolation::Pchip) => {
                let mut d = vec![0.0; n];
                for k in 1..n - 1 {
                    let (m0, m1) = (m[k - 1], m[k]);
                    if m0 == 0.0 || m1 == 0.0 || sign(m0) != sign(m1) {
                        continue;
                    }
                    let w1 = 2.0 * h[k] + h[k - 1];
                    let w2 = h[k] + 2.0 * h[k - 1];
                    d[k] = (w1 + w2) / (w1 / m0 + w2 / m1);
                }
                d[0] = edge(h[0], h[1], m[0], m[1]);
                d[n - 1] = edge(h[n - 2], h[n - 3], m[n - 2], m[n - 3]);
                d
            }
        };
        Self {
            x: x.to_vec(),
            y: y.to_vec(),
            how,
            d,
        }
    }

    /// Whether `v` lies outside the tabulated range (read by extrapolation).
    pub fn outside(&self, v: f64) -> bool {
        v < self.x[0] || v > self.x[self.x.len() - 1]
    }

    /// The number of points.
    pub fn len(&self) -> usize {
        self.x.len()
    }

    pub fn is_empty(&self) -> bool {
        self.x.is_empty()
    }

    /// The value at `v`.
    pub fn at(&self, v: f64) -> f64 {
        let n = self.x.len();
        if n == 1 {
            return self.y[0];
        }
        if v <= self.x[0] {
            return self.y[0] + self.d[0] * (v - self.x[0]);
        }
        if v >= self.x[n - 1] {
            return self.y[n - 1] + self.d[n - 1] * (v - self.x[n - 1]);
        }
        // The interval holding `v`: x[k] <= v < x[k + 1].
        let k = self.x.partition_point(|&t| t <= v) - 1;
        if self.how == Interpolation::Linear {
            return self.y[k] + self.d[k] * (v - self.x[k]);
        }
        let h = self.x[k + 1] - self.x[k];
        let t = (v - self.x[k]) / h;
        // The cubic Hermite basis on t in [0, 1].
        let h00 = (1.0 + 2.0 * t) * (1.0 - t) * (1.0 - t);
        let h10 = t * (1.0 - t) * (1.0 - t);
        let h01 = t * t * (3.0 - 2.0 * t);
        let h11 = t * t * (t - 1.0);
        h00 * self.y[k] + h10 * h * self.d[k] + h01 * self.y[k + 1] + h11 * h * self.d[k + 1]
    }
}

/// scipy's end slope from the two end intervals, kept shape-preserving.
fn edge(h0: f64, h1: f64, m0: f64, m1: f64) -> f64 {
    let d = ((2.0 * h0 + h1) * m0 - h0 * m1) / (h0 + h1);
    if sign(d) != sign(m0) {
        0.0
    } else if sign(m0) != sign(m1) && d.abs() > 3.0 * m0.abs() {
        3.0 * m0
    } else {
        d
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Values of scipy 1.x's `PchipInterpolator` on the same tables (printed to 17 digits by
    /// `tests/data/pchip_scipy.py`), and its end slopes continued as lines.
    #[test]
    fn pchip_is_scipys() {
        for (x, y, probes) in SCIPY {
            let t = Table1::new(x, y, Interpolation::Pchip);
            for &(v, want) in *probes {
                let got = t.at(v);
                assert!(
                    (got - want).abs() <= 1e-14 * want.abs().max(1.0),
                    "{x:?} {y:?} at {v}: {got} against scipy's {want}"
                );
            }
        }
    }

    /// Linear reading: each interval's line, the end intervals' lines beyond.
    #[test]
    fn linear_reads_each_intervals_line() {
        let t = Table1::new(&[0.0, 1.0, 3.0], &[1.0, 3.0, 2.0], Interpolation::Linear);
        for (v, want) in [(0.5, 2.0), (2.0, 2.5), (-1.0, -1.0), (5.0, 1.0), (1.0, 3.0)] {
            assert_eq!(t.at(v), want, "at {v}");
        }
        assert!(t.outside(-0.1) && t.outside(3.1) && !t.outside(3.0));
    }

    include!(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/pchip_scipy.rs"
    ));
}
