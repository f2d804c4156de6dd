//! API 617's Level I stability screen: the first forward mode's log decrement as destabilising
//! cross-coupled stiffness is added.
//!
//! At each node `j` a share `w_j q` of the total cross-coupling `q` acts as a support with
//! `kxy = w_j q`, `kyx = -w_j q`: on `r = x + i y` the force `i w_j q r`, so a Jeffcott rotor
//! obeys `m s^2 + c s + k - i q = 0`, whose forward pole crosses `Re s = 0` at
//! `q0 = c sqrt(k/m)`. The term is isotropic (skew), so it keeps the rotor's coordinates, and it
//! stores no energy, so the damping models' modal bases (built on the symmetric parts at rest)
//! do not change with `q`. The first forward mode is the forward rotor pole of lowest frequency
//! that oscillates and is not overdamped, followed by its shape and pole as q grows
//! ([`FirstForward`]).
//! `q0`, where its decay rate changes sign, is bracketed on the requested grid (extended by
//! doubling up to 1000 times its end when the grid stays stable) and refined by the Illinois
//! method to 1e-9 relative.
//!
//! On supports over whirl frequency every candidate is a pole consistent with the frequency it
//! reads them at ([`modal_consistent`]: continued from the rotor read synchronously), in a box
//! of [`WHIRL_BOX`] times the synchronous reading's first forward mode (the box of a rotor
//! held sparse where it is): q0 is then where the consistent pole crosses `Re s = 0`, for a
//! Jeffcott rotor `q0 = c(w*) w*` with `k(w*) = m w*^2`.

use std::cell::Cell;

use crate::analysis::AnalysisError;
use crate::analysis::control::Control;
use crate::analysis::modal::{large_poles, modal_consistent};
use crate::analysis::poles::{Pole, Whirl, overdamped, poles_at};
use crate::damping::dampers::{ModalDampers, Projected};
use crate::damping::{DampedModel, DampingError};
use crate::linalg::{self, c64};
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
    /// On supports over whirl frequency: the largest residual of a first forward pole found
    /// ([`crate::analysis::consistent`]).
    pub residual: Option<f64>,
}

/// Where the cross-coupling acts: `(degree of freedom of the translation, share)`.
pub type Placing = [(usize, f64)];

/// API 617 Level I: the log decrement at q_A at least 0.1 ...
pub const MIN_LOG_DEC: f64 = 0.1;
/// ... and q0 / q_A at least 2 ...
pub const MIN_Q_RATIO: f64 = 2.0;
/// ... and, for 2 <= q0 / q_A below this, the machine in Region A.
pub const REGION_Q_RATIO: f64 = 10.0;

/// API 617's Region A/B boundary of the critical speed ratio against the mean gas density
/// `rho` (kg/m^3), as ross-report draws it: 2.5 up to 16.53 kg/m^3, then `2.69 - 0.0115 rho`
/// down to 2.0 at 60 kg/m^3; above 60 kg/m^3 no critical speed ratio is in Region A (0).
pub fn region_boundary(rho: f64) -> f64 {
    if rho <= 16.53 {
        2.5
    } else if rho <= 60.0 {
        2.69 - 0.0115 * rho
    } else {
        0.0
    }
}

/// The Level I verdict of a machine.
#[derive(Debug, Clone, PartialEq)]
pub struct Screen {
    pub ratio: Option<f64>,
    /// `'A'` or `'B'` (with a mean gas density and a critical speed ratio).
    pub region: Option<char>,
    /// Why Level II is required; empty when Level I passes.
    pub reasons: Vec<String>,
}

/// API 617 Level I on q0, q_A, the log decrement at q_A, the critical speed ratio and the mean
/// gas density (kg/m^3): Level II is required when q0 / q_A < 2, when the log decrement at
/// q_A is below 0.1, or when 2 <= q0 / q_A < 10 and the machine is in Region B (or its
/// region is unknown).
pub fn screen(
    q0: Option<f64>,
    qa: f64,
    log_dec_at_qa: Option<f64>,
    csr: Option<f64>,
    density: Option<f64>,
) -> Screen {
    // No q0 (stable up to the search's end): the ratio is beyond every limit.
    let ratio = q0.map(|q| q / qa);
    let region = match (csr, density) {
        (Some(c), Some(rho)) => Some(if c > region_boundary(rho) { 'B' } else { 'A' }),
        _ => None,
    };
    let mut reasons = vec![];
    if let Some(r) = ratio.filter(|r| *r < MIN_Q_RATIO) {
        reasons.push(format!("q0 / q_A = {r:.3} is below {MIN_Q_RATIO}"));
    }
    match log_dec_at_qa {
        Some(d) if d < MIN_LOG_DEC => reasons.push(format!(
            "the log decrement at q_A, {d:.4}, is below {MIN_LOG_DEC}"
        )),
        None => reasons.push("the model has no first forward mode at q_A".into()),
        _ => {}
    }
    if let Some(r) = ratio.filter(|r| (MIN_Q_RATIO..REGION_Q_RATIO).contains(r)) {
        match region {
            Some('B') => reasons.push(format!(
                "q0 / q_A = {r:.3} is below {REGION_Q_RATIO} and the critical speed ratio {:.3} \
                 is in Region B at {:.2} kg/m^3",
                csr.unwrap_or(0.0),
                density.unwrap_or(0.0)
            )),
            Some(_) => {}
            None => reasons.push(format!(
                "q0 / q_A = {r:.3} is below {REGION_Q_RATIO}: the Region A/B screen needs \
                 machine.mean_gas_density (and a beam rotor for the critical speed ratio)"
            )),
        }
    }
    Screen {
        ratio,
        region,
        reasons,
    }
}

/// The box the poles are made consistent in on supports over whirl frequency, times the
/// modulus of the synchronous reading's first forward mode: cross-coupling up to twice q0 and
/// the consistency move it by far less.
pub const WHIRL_BOX: f64 = 3.0;

/// Relative tolerance of `q0`.
const Q_TOL: f64 = 1e-9;

/// The first forward mode of a rotor at one speed, followed as cross-coupling is added.
///
/// Without cross-coupling it is the forward rotor pole of lowest frequency that oscillates and
/// is not overdamped ([`overdamped`]: heavily damped bearings do not whirl, as on the Campbell
/// diagram). With it, the same mode is the forward pole nearest that reference by the
/// tracking cost `(1 - MAC) + |s_ref - s| / max(|s_ref|, |s|)`: the lowest forward pole is not
/// it once q turns the overdamped bearing poles slowly (a log decrement of 600 at 1 rad/s on a
/// 150 rad/s first mode).
pub struct FirstForward<'a> {
    system: &'a RotorSystem,
    damping: &'a DampingModel,
    speed: f64,
    /// Where each share acts in the system's coordinates, its node, the share.
    at: Vec<(Placement, usize, f64)>,
    reference: Option<Pole>,
    /// Held sparse: the candidates are the full model's poles in the box `|Re s|, |Im s| <=`
    /// this ([`large_poles`]); `None`: every pole of the dense model.
    bound: Option<f64>,
    /// A reduction of a rotor held sparse: its equivalent or nonviscous dampers, those of the
    /// full rotor projected on the basis (the same at every q: the cross-coupling has no loss
    /// and no symmetric stiffness), not rebuilt on the reduced rotor's modes.
    given: Option<&'a Projected>,
    /// Held sparse: the equivalent or nonviscous model's dampers, found once for every q.
    dampers: Option<&'a ModalDampers>,
    /// On supports over whirl frequency: the box its consistent poles are found in.
    whirl: Option<f64>,
    /// The largest residual of a consistent first forward pole chosen so far.
    residual: Cell<f64>,
}

impl<'a> FirstForward<'a> {
    pub fn new(
        system: &'a RotorSystem,
        damping: &'a DampingModel,
        speed: f64,
        at: &Placing,
    ) -> Result<Self, AnalysisError> {
        let at = at
            .iter()
            .map(|&(dof, w)| (Placement::Dof(dof), system.dofs[dof].node, w))
            .collect();
        Self::placed(system, damping, speed, at)
    }

    /// The first forward mode of a system whose cross-coupling acts at `at`: `(placement,
    /// node, share)` (a reduced system's translations are rows of its basis).
    pub fn placed(
        system: &'a RotorSystem,
        damping: &'a DampingModel,
        speed: f64,
        at: Vec<(Placement, usize, f64)>,
    ) -> Result<Self, AnalysisError> {
        Self::bounded(system, damping, speed, at, (None, None), None)
    }

    /// [`FirstForward::placed`] on a reduction carrying the full rotor's dampers projected
    /// (`given`, [`DampedModel::projection`]).
    pub fn projected(
        system: &'a RotorSystem,
        damping: &'a DampingModel,
        speed: f64,
        at: Vec<(Placement, usize, f64)>,
        given: Option<&'a Projected>,
    ) -> Result<Self, AnalysisError> {
        Self::bounded(system, damping, speed, at, (None, None), given)
    }

    /// [`FirstForward::new`] of a rotor held sparse: its candidates the full model's poles in
    /// the box `|Re s|, |Im s| <= bound`, by sparse factors, under the equivalent or nonviscous
    /// model's `dampers` (those of `system` without the cross-coupling).
    pub fn held(
        system: &'a RotorSystem,
        damping: &'a DampingModel,
        speed: f64,
        at: &Placing,
        bound: f64,
        dampers: Option<&'a ModalDampers>,
    ) -> Result<Self, AnalysisError> {
        let at = at
            .iter()
            .map(|&(dof, w)| (Placement::Dof(dof), system.dofs[dof].node, w))
            .collect();
        Self::bounded(system, damping, speed, at, (Some(bound), dampers), None)
    }

    fn bounded(
        system: &'a RotorSystem,
        damping: &'a DampingModel,
        speed: f64,
        at: Vec<(Placement, usize, f64)>,
        (bound, dampers): (Option<f64>, Option<&'a ModalDampers>),
        given: Option<&'a Projected>,
    ) -> Result<Self, AnalysisError> {
        let whirl = match (system.frequency_dependent(), bound) {
            (false, _) => None,
            (true, Some(b)) => Some(b),
            (true, None) => {
                let synchronous = system.read(speed, speed);
                let first = poles_at(&built(&synchronous, damping, given)?, speed)?
                    .rotor
                    .into_iter()
                    .filter(first_forward_candidate)
                    .min_by(|a, b| a.frequency().total_cmp(&b.frequency()));
                Some(first.map_or(f64::INFINITY, |p| WHIRL_BOX * p.s.norm()))
            }
        };
        let mut first = Self {
            system,
            damping,
            speed,
            at,
            reference: None,
            bound,
            given,
            dampers,
            whirl,
            residual: Cell::new(0.0),
        };
        let reference = first
            .candidates(0.0)?
            .into_iter()
            .min_by(|a, b| a.0.frequency().total_cmp(&b.0.frequency()));
        if let Some((_, r)) = &reference {
            first.residual.set(*r);
        }
        first.reference = reference.map(|(p, _)| p);
        Ok(first)
    }

    /// On supports over whirl frequency, the largest residual of a consistent first forward
    /// pole found so far.
    pub fn residual(&self) -> Option<f64> {
        self.whirl.map(|_| self.residual.get())
    }

    /// `|s|` of the first forward pole without cross-coupling.
    pub fn reference_modulus(&self) -> Option<f64> {
        self.reference.as_ref().map(|p| p.s.norm())
    }

    /// Without cross-coupling.
    pub fn base(&self) -> ForwardPole {
        self.reference
            .as_ref()
            .map(|p| (p.decay_rate(), p.frequency()))
    }

    /// With total cross-coupling `q`.
    pub fn at(&self, q: f64) -> Result<ForwardPole, AnalysisError> {
        let Some(reference) = &self.reference else {
            return Ok(None);
        };
        if q == 0.0 {
            return Ok(self.base());
        }
        let candidates = self.candidates(q)?;
        let shapes: Vec<&[c64]> = candidates.iter().map(|p| p.0.shape.as_slice()).collect();
        let macs = linalg::mac_matrix(&[reference.shape.as_slice()], &shapes);
        let cost = |((p, _), mac): (&(Pole, f64), &f64)| {
            (1.0 - mac) + (reference.s - p.s).norm() / reference.s.norm().max(p.s.norm())
        };
        let chosen = candidates
            .iter()
            .zip(&macs[0])
            .min_by(|a, b| cost(*a).total_cmp(&cost(*b)));
        Ok(chosen.map(|((p, r), _)| {
            self.residual.set(self.residual.get().max(*r));
            (p.decay_rate(), p.frequency())
        }))
    }

    /// The forward rotor poles that oscillate and are not overdamped, at `q`, each with its
    /// residual on supports over whirl frequency (0 on others).
    fn candidates(&self, q: f64) -> Result<Vec<(Pole, f64)>, AnalysisError> {
        let s = coupled(self.system, &self.at, q);
        let (set, residuals) = match (self.whirl, self.bound) {
            (Some(b), held) => {
                let r = modal_consistent(&s, self.damping, self.speed, b, held.is_some())?;
                (
                    r.poles,
                    r.consistency.map(|c| c.residuals).unwrap_or_default(),
                )
            }
            (None, Some(bound)) => (
                large_poles(&s, self.damping, self.dampers, self.speed, bound)?,
                vec![],
            ),
            (None, None) => (
                poles_at(&built(&s, self.damping, self.given)?, self.speed)?,
                vec![],
            ),
        };
        Ok(set
            .rotor
            .into_iter()
            .enumerate()
            .map(|(i, p)| (p, residuals.get(i).copied().unwrap_or(0.0)))
            .filter(|(p, _)| first_forward_candidate(p))
            .collect())
    }
}

/// Whether a pole may be the first forward mode: a forward rotor pole that oscillates and is
/// not overdamped.
fn first_forward_candidate(p: &Pole) -> bool {
    p.whirl == Whirl::Forward && p.oscillates() && !overdamped(p.s)
}

/// The damping model of `system`: built on its own modes, or with the `given` projection.
pub fn built(
    system: &RotorSystem,
    damping: &DampingModel,
    given: Option<&Projected>,
) -> Result<DampedModel, DampingError> {
    match given {
        Some(g) => DampedModel::with_projection(system, damping, g),
        None => DampedModel::build(system, damping),
    }
}

/// `system` with the total cross-coupling `q` shared as `at` says: `(placement, node,
/// share)`, each share a support `kxy = w q`, `kyx = -w q`.
pub fn coupled(system: &RotorSystem, at: &[(Placement, usize, f64)], q: f64) -> RotorSystem {
    let mut s = system.clone();
    if q != 0.0 {
        for (at, node, w) in at {
            let k = Matrix2 {
                xx: 0.0,
                xy: w * q,
                yx: -w * q,
                yy: 0.0,
            };
            s.supports.push(PlacedSupport {
                at: at.clone(),
                support: GeneralSupport {
                    index: usize::MAX,
                    seal: false,
                    node: *node,
                    link: None,
                    law: Law::Constant(Coefficients {
                        k,
                        ..Coefficients::default()
                    }),
                    loss_factor: 0.0,
                    branches: None,
                },
            });
        }
    }
    s
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
    let first = FirstForward::new(system, damping, speed, at)?;
    auto_range_of(&first, stiffness_scale(system), count, control)
}

/// The largest stiffness on the diagonal of `system`, N/m.
pub fn stiffness_scale(system: &RotorSystem) -> f64 {
    let k = system.stiffness();
    (0..k.nrows())
        .map(|i| k.get(i, i).abs())
        .fold(0.0, f64::max)
        .max(1e-300)
}

/// [`auto_range`] of `first`, growing from a millionth of `scale` up to it.
pub fn auto_range_of(
    first: &FirstForward,
    scale: f64,
    count: usize,
    control: &Control,
) -> Result<Vec<f64>, AnalysisError> {
    let mut q = 1e-6 * scale;
    let mut stop = scale;
    while q < scale {
        control.check()?;
        match first.at(q)? {
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
    let first = FirstForward::new(system, damping, speed, at)?;
    level1_of(&first, qs, control)
}

/// The Level I curve of `first` over `qs` (increasing, >= 0) and `q0`.
pub fn level1_of(
    first: &FirstForward,
    qs: &[f64],
    control: &Control,
) -> Result<Level1, AnalysisError> {
    control.expect(qs.len() as u64 + 40);
    let mut eval = |q: f64| -> Result<ForwardPole, AnalysisError> {
        control.check()?;
        let p = first.at(q);
        control.advance(1);
        p
    };
    let base = first.base();
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
    Ok(Level1 {
        curve,
        base,
        q0,
        residual: first.residual(),
    })
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
