//! The functions of exponential integrators: `phi1(z) = (e^z - 1)/z` and
//! `phi2(z) = (e^z - 1 - z)/z^2`, so that `int_0^t e^{z s} ds = t phi1(z t)` and
//! `int_0^t (t - s) e^{z s} ds = t^2 phi2(z t)`, accurate near `z = 0` (series there).

use super::c64;

/// `(e^z - 1)/z`, accurate near 0.
pub fn phi1(z: c64) -> c64 {
    if z.norm() < 0.1 {
        let (mut term, mut sum) = (c64::new(1.0, 0.0), c64::new(1.0, 0.0));
        for k in 2..14 {
            term = term * z / k as f64;
            sum += term;
        }
        sum
    } else {
        (z.exp() - 1.0) / z
    }
}

/// `(e^z - 1 - z)/z^2`, accurate near 0.
pub fn phi2(z: c64) -> c64 {
    if z.norm() < 0.1 {
        let (mut term, mut sum) = (c64::new(0.5, 0.0), c64::new(0.5, 0.0));
        for k in 3..16 {
            term = term * z / k as f64;
            sum += term;
        }
        sum
    } else {
        (phi1(z) - 1.0) / z
    }
}
