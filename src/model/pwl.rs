//! A piecewise-linear history `[[t, v], ...]`: times nondecreasing, a repeated time is a jump
//! (the value after it holds from that time on), constant before the first and after the last
//! point.

use super::error::Invalid;

/// A piecewise-linear function of time.
#[derive(Debug, Clone, PartialEq)]
pub struct Pwl {
    points: Vec<(f64, f64)>,
}

impl Pwl {
    pub fn parse(points: &[[f64; 2]], at: &str, jumps: bool, bad: &mut Invalid) -> Option<Self> {
        if points.is_empty() {
            bad.push(at, "needs at least one [t, value] point");
            return None;
        }
        let mut ok = true;
        for (i, p) in points.iter().enumerate() {
            if !p[0].is_finite() || !p[1].is_finite() {
                bad.push(format!("{at}[{i}]"), "must be finite numbers");
                ok = false;
            } else if i > 0 && p[0] < points[i - 1][0] {
                bad.push(format!("{at}[{i}]"), "times must not decrease");
                ok = false;
            } else if i > 0 && p[0] == points[i - 1][0] {
                if !jumps {
                    bad.push(
                        format!("{at}[{i}]"),
                        "a repeated time (a jump) is not allowed here",
                    );
                    ok = false;
                } else if i > 1 && points[i - 2][0] == p[0] {
                    bad.push(
                        format!("{at}[{i}]"),
                        "at most two points per time (one jump)",
                    );
                    ok = false;
                }
            }
        }
        ok.then(|| Pwl {
            points: points.iter().map(|p| (p[0], p[1])).collect(),
        })
    }

    pub fn constant(v: f64) -> Self {
        Pwl {
            points: vec![(0.0, v)],
        }
    }

    /// Index of the segment `[t_k, t_{k+1})` containing `t` (right-continuous), or None before
    /// the first / after the last point.
    fn segment(&self, t: f64) -> Option<usize> {
        let p = &self.points;
        if p.len() < 2 || t < p[0].0 || t >= p[p.len() - 1].0 {
            return None;
        }
        // Last k with t_k <= t (after a jump, the later of two equal times).
        let k = p.partition_point(|q| q.0 <= t) - 1;
        (k + 1 < p.len()).then_some(k)
    }

    /// Value at `t`; at a jump, the value after it.
    pub fn value(&self, t: f64) -> f64 {
        let p = &self.points;
        match self.segment(t) {
            Some(k) => {
                let ((t0, v0), (t1, v1)) = (p[k], p[k + 1]);
                v0 + (v1 - v0) * (t - t0) / (t1 - t0)
            }
            None if t < p[0].0 => p[0].1,
            None => p[p.len() - 1].1,
        }
    }

    /// Slope at `t` (right derivative).
    pub fn slope(&self, t: f64) -> f64 {
        match self.segment(t) {
            Some(k) => {
                let ((t0, v0), (t1, v1)) = (self.points[k], self.points[k + 1]);
                (v1 - v0) / (t1 - t0)
            }
            None => 0.0,
        }
    }

    /// Times where the value or the slope may change.
    pub fn breakpoints(&self) -> impl Iterator<Item = f64> + '_ {
        self.points.iter().map(|p| p.0)
    }

    /// `(t, jump, slope change)` for `t >= 0`, so that for `t >= 0`
    /// `f(t) = sum jump H(t - t_k) + slope change (t - t_k) H(t - t_k)`. The first entry, at 0,
    /// carries `f(0)` and `f'(0)`.
    pub fn steps_and_ramps(&self) -> Vec<(f64, f64, f64)> {
        let mut out = vec![(0.0, self.value(0.0), self.slope(0.0))];
        let mut times: Vec<f64> = self.breakpoints().filter(|&t| t > 0.0).collect();
        times.dedup();
        for t in times {
            let before = self.left_value(t);
            let jump = self.value(t) - before;
            let dslope = self.slope(t) - self.left_slope(t);
            if jump != 0.0 || dslope != 0.0 {
                out.push((t, jump, dslope));
            }
        }
        out
    }

    /// Value just before `t` (left limit).
    pub fn left_value(&self, t: f64) -> f64 {
        let p = &self.points;
        let k = p.partition_point(|q| q.0 < t);
        if k == 0 {
            return p[0].1;
        }
        let (t0, v0) = p[k - 1];
        match p.get(k) {
            Some(&(t1, v1)) if t1 > t0 => v0 + (v1 - v0) * (t - t0) / (t1 - t0),
            _ => v0,
        }
    }

    /// Slope just before `t`.
    pub fn left_slope(&self, t: f64) -> f64 {
        let p = &self.points;
        let k = p.partition_point(|q| q.0 < t);
        if k == 0 || k >= p.len() {
            return 0.0;
        }
        let ((t0, v0), (t1, v1)) = (p[k - 1], p[k]);
        if t1 > t0 { (v1 - v0) / (t1 - t0) } else { 0.0 }
    }

    /// `int_0^t f`, exact (for a history without jumps before `t` it is piecewise quadratic;
    /// jumps are integrated as such too).
    pub fn integral(&self, t: f64) -> f64 {
        // Linear between breakpoints: the trapezoid on each piece of (0, t) is exact. No
        // allocation: a run-up evaluates the rotation angle four times a step.
        let mut sum = 0.0;
        let mut a = 0.0;
        for b in self
            .points
            .iter()
            .map(|q| q.0)
            .filter(|&b| b > 0.0 && b < t)
            .chain(std::iter::once(t))
        {
            if b > a {
                sum += 0.5 * (self.value(a) + self.left_value(b)) * (b - a);
                a = b;
            }
        }
        sum
    }

    /// Whether the function is constant.
    pub fn is_constant(&self) -> bool {
        self.points.iter().all(|p| p.1 == self.points[0].1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pwl(p: &[[f64; 2]]) -> Pwl {
        let mut bad = Invalid::default();
        Pwl::parse(p, "h", true, &mut bad).unwrap()
    }

    #[test]
    fn a_ramp_then_release_is_a_ramp_a_slope_stop_and_a_jump() {
        // The paper's shock: 0 to 10 kN in 11 ms, then released.
        let f = pwl(&[[0.0, 0.0], [0.011, 1e4], [0.011, 0.0]]);
        assert_eq!(f.value(0.0055), 5e3);
        assert_eq!(f.value(0.011), 0.0);
        assert_eq!(f.value(1.0), 0.0);
        let sr = f.steps_and_ramps();
        let eval = |t: f64| -> f64 {
            sr.iter()
                .filter(|(tk, _, _)| *tk <= t)
                .map(|(tk, j, s)| j + s * (t - tk))
                .sum()
        };
        for t in [0.0, 0.003, 0.0109, 0.011, 0.02, 0.5] {
            assert!((eval(t) - f.value(t)).abs() < 1e-9, "t = {t}");
        }
    }

    #[test]
    fn the_angle_of_a_linear_run_up_is_quadratic() {
        let speed = pwl(&[[0.0, 0.0], [2.0, 100.0]]);
        assert!((speed.integral(1.0) - 25.0).abs() < 1e-12);
        assert!((speed.integral(3.0) - (100.0 + 100.0)).abs() < 1e-12);
    }

    #[test]
    fn bad_histories_are_refused_with_their_index() {
        let mut bad = Invalid::default();
        assert!(Pwl::parse(&[[0.0, 1.0], [-1.0, 2.0]], "h", true, &mut bad).is_none());
        assert_eq!(bad.errors()[0].path, "h[1]");
        let mut bad = Invalid::default();
        assert!(Pwl::parse(&[[0.0, 1.0], [1.0, 2.0], [1.0, 3.0]], "s", false, &mut bad).is_none());
        assert_eq!(bad.errors()[0].path, "s[2]");
    }
}
