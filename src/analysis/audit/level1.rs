//! API 617's Level I stability screen: the first forward mode's log decrement as destabilising
//! cross-coupled stiffness is added.
//!
//! At each node `j` a share `w_j q` of the total cross-coupling `q` acts as a support with
//! `kxy = w_j q`, `kyx = -w_j q`: on `r = x + i y` the force `i w_j q r`, so a Jeffcott rotor
//! obeys `m s^2 + c s + k - i q = 0`, whose forward pole crosses `Re s = 0` at
//! `q0 = c sqrt(k/m)`. The term is isotropic (skew), so it keeps the rotor's coordinates, and it
//! stores no energy, so the damping models' modal bases (built on the symmetric parts at rest)
//! do not change with `q`. The first forward mode is the forward rotor pole of lowest frequency
//! that oscillates.
//! `q0`, where its decay rate changes sign, is bracketed on the requested grid (extended by
//! doubling up to 1000 times its end when the grid stays stable) and refined by the Illinois
//! method to 1e-9 relative.

use crate::analysis::AnalysisError;
use crate::analysis::control::Control;
use crate::analysis::poles::{Whirl, poles_at};
use crate::damping::DampedModel;
use crate::model::damping::DampingModel;
use crate::model::supports::{Coefficients, GeneralSupport, Law, Matrix2};
use crate::system::{PlacedSupport, Placement, RotorSystem};

/// The first forward mode at one cross-coupling: `(decay rate, frequency)`; `None` where the
/// model defines no forward pole (hysteretic model).
pub type ForwardPole = Option<(f64, f64)>;

#[derive(Debug, Clone, PartialEq)]
pub struct Level1 {
    /// The first forward mode at each requested q.
    pub curve: Vec<ForwardPole>,
    /// Without cross-coupling.
    pub base: ForwardPole,
    pub q0: Option<f64>,
}

/// Where the cross-coupling acts: `(degree of freedom of the translation, share)`.
pub type Placing = [(usize, f64)];

/// Relative tolerance of `q0`.
const Q_TOL: f64 = 1e-9;

/// The first forward mode of `system` at `speed` with total cross-coupling `q` at `at`.
pub fn first_forward(
    system: &RotorSystem,
    damping: &DampingModel,
    speed: f64,
    at: &Placing,
    q: f64,
) -> Result<ForwardPole, AnalysisError> {
    let mut s = system.clone();
    if q != 0.0 {
        for &(dof, w) in at {
            let k = Matrix2 {
                xx: 0.0,
                xy: w * q,
                yx: -w * q,
                yy: 0.0,
            };
            s.supports.push(PlacedSupport {
                at: Placement::Dof(dof),
                support: GeneralSupport {
                    index: usize::MAX,
                    node: s.dofs[dof].node,
                    law: Law::Constant(Coefficients {
                        k,
                        ..Coefficients::default()
                    }),
                    loss_factor: 0.0,
                },
            });
        }
    }
    let model = DampedModel::build(&s, damping)?;
    let set = poles_at(&model, speed)?;
    Ok(set
        .rotor
        .iter()
        // Overdamped poles (heavily damped bearings) do not whirl: not a mode to screen.
        .filter(|p| p.whirl == Whirl::Forward && p.frequency() > 1e-6 * p.s.norm())
        .min_by(|a, b| a.frequency().total_cmp(&b.frequency()))
        .map(|p| (p.decay_rate(), p.frequency())))
}

/// `count` values from 0 to twice `q0` (found by growing `q` by 4 from a millionth of the
/// largest stiffness on the diagonal), or to that largest stiffness if the mode stays stable.
pub fn auto_range(
    system: &RotorSystem,
    damping: &DampingModel,
    speed: f64,
    at: &Placing,
    count: usize,
    control: &Control,
) -> Result<Vec<f64>, AnalysisError> {
    let k = system.stiffness();
    let scale = (0..k.nrows())
        .map(|i| k[(i, i)].abs())
        .fold(0.0, f64::max)
        .max(1e-300);
    let mut q = 1e-6 * scale;
    let mut stop = scale;
    while q < scale {
        control.check()?;
        match first_forward(system, damping, speed, at, q)? {
            Some((sigma, _)) if sigma >= 0.0 => {
                stop = 2.0 * q;
                break;
            }
            Some(_) => q *= 4.0,
            None => break,
        }
    }
    let n = count.max(2);
    Ok((0..n).map(|i| stop * i as f64 / (n - 1) as f64).collect())
}

/// The Level I curve over `qs` (increasing, >= 0) and `q0`.
pub fn level1(
    system: &RotorSystem,
    damping: &DampingModel,
    speed: f64,
    at: &Placing,
    qs: &[f64],
    control: &Control,
) -> Result<Level1, AnalysisError> {
    control.expect(qs.len() as u64 + 40);
    let mut eval = |q: f64| -> Result<ForwardPole, AnalysisError> {
        control.check()?;
        let p = first_forward(system, damping, speed, at, q);
        control.advance(1);
        p
    };
    let base = eval(0.0)?;
    let mut curve = Vec::with_capacity(qs.len());
    for &q in qs {
        curve.push(if q == 0.0 { base } else { eval(q)? });
    }
    // Bracket the sign change of the decay rate from q = 0 up.
    let mut known: Vec<(f64, f64)> = std::iter::once((0.0, base))
        .chain(qs.iter().copied().zip(curve.iter().copied()))
        .filter_map(|(q, p)| p.map(|(sigma, _)| (q, sigma)))
        .collect();
    known.sort_by(|a, b| a.0.total_cmp(&b.0));
    let q0 = match known.first() {
        // Unstable without cross-coupling (or undefined): no positive margin.
        None => None,
        Some(&(_, s)) if s >= 0.0 => None,
        Some(_) => {
            let bracket = known.windows(2).find(|w| w[0].1 < 0.0 && w[1].1 >= 0.0);
            let mut extended = None;
            if bracket.is_none() {
                let &(mut q, mut s) = known.last().expect("non-empty");
                let limit = 1e3 * q;
                while q < limit {
                    let next = 2.0 * q;
                    match eval(next)? {
                        Some((sn, _)) if sn >= 0.0 => {
                            extended = Some([(q, s), (next, sn)]);
                            break;
                        }
                        Some((sn, _)) => (q, s) = (next, sn),
                        None => break,
                    }
                }
            }
            let pair = bracket.map(|w| [w[0], w[1]]).or(extended);
            match pair {
                None => None,
                Some([(a, fa), (b, fb)]) => illinois(a, fa, b, fb, &mut eval)?,
            }
        }
    };
    Ok(Level1 { curve, base, q0 })
}

/// The zero of the decay rate in `[a, b]` (`fa < 0 <= fb`), by the Illinois method.
fn illinois(
    mut a: f64,
    mut fa: f64,
    mut b: f64,
    mut fb: f64,
    eval: &mut dyn FnMut(f64) -> Result<ForwardPole, AnalysisError>,
) -> Result<Option<f64>, AnalysisError> {
    let mut side = 0;
    for _ in 0..200 {
        if (b - a).abs() <= Q_TOL * b.abs().max(a.abs()) {
            break;
        }
        let c = (a * fb - b * fa) / (fb - fa);
        let c = if c > a && c < b { c } else { 0.5 * (a + b) };
        let Some((fc, _)) = eval(c)? else {
            return Ok(None);
        };
        if fc < 0.0 {
            (a, fa) = (c, fc);
            if side == -1 {
                fb *= 0.5;
            }
            side = -1;
        } else {
            (b, fb) = (c, fc);
            if side == 1 {
                fa *= 0.5;
            }
            side = 1;
        }
    }
    Ok(Some(if fb.abs() < fa.abs() { b } else { a }))
}
