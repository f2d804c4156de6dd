//! Hysteretic damping (model H, MODEL.md sections 2 and 8): frequency domain only.
//!
//! The imaginary stiffness is `i sgn(omega) K''_n` in the supports and `i sgn(omega - Omega) K''_r`
//! in the rotor, whose material sees the whirl at `omega - Omega`; in doubled coordinates the
//! rotor's loss on the `conj r` rows sees `omega + Omega`. The model is piecewise linear in the
//! signs, so it is solved as linear problems, one per sign pattern; a root of a problem is a
//! pole only if it is consistent with the pattern. In the coordinates `r` alone the patterns
//! are `(sgn omega, sgn(omega - Omega))` in `{+1, -1}^2`; doubled, for `Omega >= 0`, the four
//! consistent ones of `(sgn omega, sgn(omega - Omega), sgn(omega + Omega))`: `(+,+,+)`,
//! `(+,-,+)`, `(-,-,+)`, `(-,-,-)`. Near a forward critical speed a mode can have no consistent
//! root (or two): the model itself is undefined there, and it is reported so.

use super::state::{Branches, SecondOrder, StateModel};
use crate::linalg::{LinalgError, c64};
use crate::system::{Layout, Realized};

/// One sign pattern and its linear problem.
#[derive(Debug, Clone)]
pub struct SignedModel {
    /// `a`: the sign of `omega` this problem assumes.
    pub nonrotating: f64,
    /// `b`: the sign of `omega - Omega` this problem assumes.
    pub rotating: f64,
    /// `c`: the sign of `omega + Omega` (doubled coordinates; 0 when it does not apply).
    pub counter: f64,
    pub model: StateModel,
}

impl SignedModel {
    /// Whether the root `s` at spin speed `speed` has the signs this problem assumed.
    pub fn consistent(&self, s: c64, speed: f64) -> bool {
        consistent((self.nonrotating, self.rotating, self.counter), s, speed)
    }
}

/// Whether the root `s` at spin speed `speed` has the signs `(a, b, c)` of its problem: of
/// `omega`, `omega - Omega` and (doubled; 0 when it does not apply) `omega + Omega`.
pub fn consistent((a, b, c): (f64, f64, f64), s: c64, speed: f64) -> bool {
    let w = s.im;
    a * w > 0.0 && b * (w - speed) > 0.0 && (c == 0.0 || c * (w + speed) > 0.0)
}

/// `-1`, `0` or `1`: the sign the hysteretic loss takes at a frequency (`sgn 0 = 0`, unlike
/// [`f64::signum`]).
pub fn sign(v: f64) -> f64 {
    if v > 0.0 {
        1.0
    } else if v < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// The sign patterns of a layout: `(a, b, c)`.
pub fn patterns(layout: Layout) -> Vec<(f64, f64, f64)> {
    match layout {
        Layout::Single => vec![
            (1.0, 1.0, 0.0),
            (1.0, -1.0, 0.0),
            (-1.0, 1.0, 0.0),
            (-1.0, -1.0, 0.0),
        ],
        Layout::Doubled => vec![
            (1.0, 1.0, 1.0),
            (1.0, -1.0, 1.0),
            (-1.0, -1.0, 1.0),
            (-1.0, -1.0, -1.0),
        ],
    }
}

/// The second-order problem of one pattern: `K + i a K''_n + i diag(b, c) K''_r`.
pub fn signed_second_order(r: &Realized, (a, b, c): (f64, f64, f64)) -> SecondOrder {
    let mut so = SecondOrder::viscous(r);
    let size = r.size();
    for i in 0..size {
        let rot = if r.spin[i] > 0.0 { b } else { c };
        for j in 0..size {
            so.k0[(i, j)] += c64::new(0.0, 1.0)
                * (r.loss_nonrotating[(i, j)] * a + r.loss_rotating[(i, j)] * rot);
        }
    }
    so
}

/// The signed models of one realization.
pub fn signed_models(r: &Realized) -> Result<Vec<SignedModel>, LinalgError> {
    patterns(r.layout)
        .into_iter()
        .map(|(a, b, c)| {
            Ok(SignedModel {
                nonrotating: a,
                rotating: b,
                counter: c,
                model: StateModel::new(
                    &signed_second_order(r, (a, b, c)),
                    &Branches::none(r.size()),
                )?,
            })
        })
        .collect()
}
