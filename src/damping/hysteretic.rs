//! Hysteretic damping (model H, MODEL.md section 2): frequency domain only.
//!
//! The imaginary stiffness is `i sgn(omega) K''_n` in the supports and `i sgn(omega - Omega) K''_r`
//! in the rotor, whose material sees the whirl at `omega - Omega`. The model is piecewise linear
//! in the signs, so it is solved as four linear problems with `K + i a K''_n + i b K''_r`,
//! `(a, b) in {+1, -1}^2`; a root of problem `(a, b)` is a pole only if it is consistent:
//! `sgn(omega) = a` and `sgn(omega - Omega) = b`. Near a forward critical speed a mode can have no
//! consistent root (or two): the model itself is undefined there, and it is reported so.

use super::state::{Branches, SecondOrder, StateModel};
use crate::linalg::{LinalgError, c64};
use crate::system::RotorSystem;

/// One sign pair and its linear problem.
#[derive(Debug, Clone)]
pub struct SignedModel {
    /// `a`: the sign of `omega` this problem assumes.
    pub nonrotating: f64,
    /// `b`: the sign of `omega - Omega` this problem assumes.
    pub rotating: f64,
    pub model: StateModel,
}

impl SignedModel {
    /// Whether the root `s` at spin speed `speed` has the signs this problem assumed.
    pub fn consistent(&self, s: c64, speed: f64) -> bool {
        let w = s.im;
        self.nonrotating * w > 0.0 && self.rotating * (w - speed) > 0.0
    }
}

/// The four sign pairs.
pub fn signed_models(system: &RotorSystem) -> Result<Vec<SignedModel>, LinalgError> {
    let n = system.n();
    let mut out = Vec::with_capacity(4);
    for a in [1.0, -1.0] {
        for b in [1.0, -1.0] {
            let mut so = SecondOrder::viscous(system);
            for r in 0..n {
                for c in 0..n {
                    so.k0[(r, c)] += c64::new(
                        0.0,
                        a * system.hysteretic_nonrotating[(r, c)]
                            + b * system.hysteretic_rotating[(r, c)],
                    );
                }
            }
            out.push(SignedModel {
                nonrotating: a,
                rotating: b,
                model: StateModel::new(&so, &Branches::none(n))?,
            });
        }
    }
    Ok(out)
}
