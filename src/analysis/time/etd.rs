//! ETD-RK4's weights (Cox & Matthews 2002) for `w' = lambda w + N(t)`, per pole: the step's,
//! which integrate exactly the quadratic through `N` at a step's start, middle and end, and
//! the dense output's, the same integral stopped at a fraction `theta` of the step. With
//! `z = lambda h`, `int_0^{theta h} e^{lambda (theta h - s)} (s / h)^(k-1) ds
//! = theta^k h (k-1)! phi_k(theta z)`.

use crate::linalg::c64;

/// `phi_k(z) = sum_j z^j / (j + k)!` for k = 1, 2, 3 (`phi_0 = e^z`).
fn phis(z: c64) -> [c64; 3] {
    if z.norm() < 1.0 {
        let mut out = [c64::new(0.0, 0.0); 3];
        for (k, o) in out.iter_mut().enumerate() {
            // 1/(k+1)! + z/(k+2)! + ...: 24 terms reach 1/25! < 1e-25.
            let mut term = c64::new(1.0 / [1.0, 2.0, 6.0][k], 0.0);
            let mut sum = term;
            for j in 1..24 {
                term = term * z / (j + k + 1) as f64;
                sum += term;
            }
            *o = sum;
        }
        out
    } else {
        let p1 = (z.exp() - 1.0) / z;
        let p2 = (p1 - 1.0) / z;
        let p3 = (p2 - 0.5) / z;
        [p1, p2, p3]
    }
}

/// The step's coefficients, per pole.
pub(super) struct Coefficients {
    pub(super) e: Vec<c64>,
    pub(super) e_half: Vec<c64>,
    pub(super) p_half: Vec<c64>,
    pub(super) b1: Vec<c64>,
    pub(super) b2: Vec<c64>,
    pub(super) b4: Vec<c64>,
}

impl Coefficients {
    pub(super) fn new(lambda: &[c64], h: f64) -> Self {
        let mut c = Coefficients {
            e: vec![],
            e_half: vec![],
            p_half: vec![],
            b1: vec![],
            b2: vec![],
            b4: vec![],
        };
        for &l in lambda {
            let z = l * h;
            let [p1, p2, p3] = phis(z);
            let [q1, _, _] = phis(z * 0.5);
            c.e.push(z.exp());
            c.e_half.push((z * 0.5).exp());
            c.p_half.push(q1 * (0.5 * h));
            c.b1.push((p1 - p2 * 3.0 + p3 * 4.0) * h);
            c.b2.push((p2 * 2.0 - p3 * 4.0) * h);
            c.b4.push((p3 * 4.0 - p2) * h);
        }
        c
    }
}

/// The dense output at `theta` of a step of length `h`: with `N` on the step the quadratic
/// through `N0`, `Nm`, `N1` at its start, middle and end,
/// `w(theta h) = e^{theta z} w + c0 N0 + cm Nm + c1 N1`, where (`P_k` = `theta^k h (k-1)!
/// phi_k(theta z)`, the integrals of `e^{lambda (theta h - s)} (s / h)^(k-1)`)
/// `c0 = P1 - 3 P2 + 2 P3`, `cm = 4 P2 - 4 P3`, `c1 = 2 P3 - P2`; at `theta = 1` the step itself.
pub(super) struct Dense {
    pub(super) e: Vec<c64>,
    pub(super) c0: Vec<c64>,
    pub(super) cm: Vec<c64>,
    pub(super) c1: Vec<c64>,
}

/// The dense output's coefficients at `theta` (cached per stage: steps and outputs repeat).
pub(super) fn dense_at<'a>(
    cache: &'a mut Vec<(f64, f64, Dense)>,
    lambda: &[c64],
    h: f64,
    theta: f64,
) -> &'a Dense {
    let found = cache
        .iter()
        .position(|(hh, th, _)| (hh - h).abs() <= 1e-10 * h && (th - theta).abs() <= 1e-10);
    let at = found.unwrap_or_else(|| {
        let mut d = Dense {
            e: vec![],
            c0: vec![],
            cm: vec![],
            c1: vec![],
        };
        for &l in lambda {
            let z = l * (theta * h);
            let [p1, p2, p3] = phis(z);
            let (p1, p2, p3) = (
                p1 * (theta * h),
                p2 * (theta * theta * h),
                p3 * (2.0 * theta.powi(3) * h),
            );
            d.e.push(z.exp());
            d.c0.push(p1 - p2 * 3.0 + p3 * 2.0);
            d.cm.push((p2 - p3) * 4.0);
            d.c1.push(p3 * 2.0 - p2);
        }
        cache.push((h, theta, d));
        cache.len() - 1
    });
    &cache[at].2
}
