//! Validated loads and speed laws of a time response.
//!
//! A piecewise-linear history `[[t, v], ...]`: times nondecreasing, a repeated time is a jump
//! (the value after it holds from that time on), constant before the first and after the last
//! point. The spin speed is such a history without jumps; the rotation angle is its integral
//! from `t = 0` (exact: piecewise quadratic).
//!
//! Also how the unit force of a frequency response is applied ([`Excitation`]; its force on
//! the coordinates, `Excitation::at`, is the analysis's, in `analysis::audit::frequency`).

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

/// A nonrotating force in a fixed direction on the translation of a node.
#[derive(Debug, Clone, PartialEq)]
pub struct Force {
    pub node: usize,
    pub direction: f64,
    pub history: Pwl,
}

/// An unbalance `m e` rotating with the shaft.
#[derive(Debug, Clone, PartialEq)]
pub struct Unbalance {
    pub node: usize,
    pub amount: f64,
    pub phase: f64,
    pub from: f64,
}

/// Spin speed against time.
#[derive(Debug, Clone, PartialEq)]
pub enum SpeedLaw {
    Constant(f64),
    Profile(Pwl),
}

impl SpeedLaw {
    pub fn omega(&self, t: f64) -> f64 {
        match self {
            SpeedLaw::Constant(w) => *w,
            SpeedLaw::Profile(p) => p.value(t),
        }
    }

    /// Angular acceleration; `left`: just before `t`.
    pub fn accel(&self, t: f64, left: bool) -> f64 {
        match self {
            SpeedLaw::Constant(_) => 0.0,
            SpeedLaw::Profile(p) if left => p.left_slope(t),
            SpeedLaw::Profile(p) => p.slope(t),
        }
    }

    /// Rotation angle `int_0^t Omega`.
    pub fn angle(&self, t: f64) -> f64 {
        match self {
            SpeedLaw::Constant(w) => w * t,
            SpeedLaw::Profile(p) => p.integral(t),
        }
    }

    /// The lowest and highest speed over `[0, duration]`.
    pub fn range(&self, duration: f64) -> (f64, f64) {
        match self {
            SpeedLaw::Constant(w) => (*w, *w),
            SpeedLaw::Profile(p) => {
                let mut ts: Vec<f64> = p
                    .breakpoints()
                    .filter(|&t| t > 0.0 && t < duration)
                    .collect();
                ts.extend([0.0, duration]);
                ts.iter()
                    .map(|&t| p.value(t))
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                        (a.min(v), b.max(v))
                    })
            }
        }
    }

    /// The speed, if it never changes.
    pub fn constant(&self) -> Option<f64> {
        match self {
            SpeedLaw::Constant(w) => Some(*w),
            SpeedLaw::Profile(p) if p.is_constant() => Some(p.value(0.0)),
            SpeedLaw::Profile(_) => None,
        }
    }
}

/// A validated time-response problem.
#[derive(Debug, Clone)]
pub struct TimeSpec {
    pub speed: SpeedLaw,
    pub forces: Vec<Force>,
    pub unbalances: Vec<Unbalance>,
    pub duration: f64,
    pub output_interval: f64,
    /// Nodes reported.
    pub nodes: Vec<usize>,
    /// Relative tolerance of the implicit integrator.
    pub tolerance: f64,
    /// Most implicit steps.
    pub max_steps: usize,
    /// Whether a varying speed may be integrated on a checked modal reduction.
    pub reduce: bool,
}

/// The angle the loads may turn in one step of the exponential integrator at tolerance `tol`:
/// ETD-RK4's error on a harmonic load goes as `theta^4`; `theta = 0.2` at `tol = 1e-6` keeps
/// the response within about `tol` of its peak (`tests/it/exponential.rs`).
pub fn step_angle(tol: f64) -> f64 {
    (0.2 * (tol / 1e-6).powf(0.25)).clamp(0.02, 0.5)
}

impl TimeSpec {
    /// The fewest steps any integrator takes for this problem, known before any work: with a
    /// varying speed, an unbalance turns through `int |Omega| dt` from its appearance to the
    /// end, and a step resolves at most [`step_angle`] of it (the exponential integrator takes
    /// exactly that step; TR-BDF2, second order, needs steps several times shorter for the
    /// same tolerance). 0 at a constant speed (the response is exact) or without unbalances.
    pub fn fewest_steps(&self) -> f64 {
        if self.speed.constant().is_some() {
            return 0.0;
        }
        let Some(from) = self.unbalances.iter().map(|u| u.from).reduce(f64::min) else {
            return 0.0;
        };
        let from = from.min(self.duration);
        // Speeds are >= 0: the angle grows with time.
        let turned = self.speed.angle(self.duration) - self.speed.angle(from);
        turned.max(0.0) / step_angle(self.tolerance)
    }

    /// Output times `0, dt, 2 dt, ...` up to and including `duration` (each the double nearest
    /// `k dt` when `dt` is a decimal: `0.0003`, not `0.00030000000000000003`).
    pub fn output_times(&self) -> Vec<f64> {
        super::speeds::multiples(
            self.output_interval,
            sample_count(self.duration, self.output_interval),
        )
    }
}

/// Samples at `0, dt, 2 dt, ...` up to and including `duration` (saturating: a count to check
/// against a limit before anything is allocated).
pub fn sample_count(duration: f64, dt: f64) -> usize {
    let n = (duration / dt * (1.0 + 1e-12)).floor();
    if n.is_finite() && n < 1e15 {
        n as usize + 1
    } else {
        usize::MAX
    }
}

/// How a unit force is applied at a node.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Excitation {
    /// `cos(omega t)` along the angle from x, rad.
    Direction(f64),
    /// `e^{i omega t}` on `r`: unit magnitude, whirling forward.
    Forward,
    /// `e^{-i omega t}`.
    Backward,
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
