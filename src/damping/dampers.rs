//! The equivalent and nonviscous models of a rotor held sparse: their dampers on its lowest
//! modes, as a low-rank term of its second-order system.
//!
//! Both models put, on each retained undamped mode `i` (natural frequency `w_i`, mass-normalised
//! shape `phi_i`, coordinate `u_i^H x` with `u_i = M phi_i`), a damper with the mode's loss
//! stiffness `l_i = phi_i^H K'' phi_i` (MODEL.md sections 3 and 4, `equivalent.rs`,
//! `nonviscous.rs`): viscous `c_i = l_i / w_i` (E), or Maxwell branches tuned at `w_i` (NVD). On
//! the rotor's sparse second-order system `Z0(s) = s^2 M + s D + K` they add
//!
//! ```text
//! Z(s) = Z0(s) + sum_t  l_t w_t(s) r_t^H,
//!        w_t(s) = a_t s + b_t + sum_j (nu_j k_j - k_j d_j / (s + d_j - i Omega rho_j))
//! ```
//!
//! one term per damper (per pair of columns: the rotating equivalent damper of doubled
//! coordinates acts on `q' - i Omega S q`, so its stiffness part has left column `S u`), and an
//! internal coordinate per branch. The shapes are those the dense models use, found by
//! shift-invert Lanczos (`ModalBasis::lowest`, `HermitianBasis::lowest`): the axisymmetric
//! modes, and the real x/y modes of doubled coordinates.
//!
//! The dense models keep every mode of the rotor (or the request's `modes`); a large rotor keeps
//! the request's `modes` or every mode up to [`DAMPER_BAND`] times the analysis' bound (the
//! dampers of higher modes shift the poles below the bound by less than the reduction's check,
//! `tests/it/damping_large.rs` measures how much). A reduction of such a rotor carries the same
//! dampers projected on its basis ([`ModalDampers::projected`]), so its check against the full
//! model measures the reduction alone.

use super::large::{Term, Terms, nonrotating_loss_entries, rotor_loss_entries};
use super::state::Branches;
use crate::fem::modal::{HermitianBasis, ModalBasis, ModalError, pencil, undamped_doubled};
use crate::linalg::{CMat, RMat, c64};
use crate::model::damping::{BranchSet, DampingModel};
use crate::model::limits::MAX_DAMPED_MODES;
use crate::system::{Layout, RotorSystem};

/// Dampers of a large rotor on the modes up to this many times an analysis' bound.
pub const DAMPER_BAND: f64 = 16.0;

/// One damper's mode: its natural frequency and its column `u = M phi` (layout coordinates).
#[derive(Debug, Clone)]
struct Mode {
    w: f64,
    phi: Vec<c64>,
    column: Vec<c64>,
}

/// A rotating damper: its mode, its loss stiffness (constant: the rotor's own), and for the
/// nonviscous model of doubled coordinates the copy it acts on (`rho = +1` on `r`, `-1` on
/// `conj r`; the columns are zero on the other block).
#[derive(Debug, Clone)]
struct Rotating {
    mode: Mode,
    loss: f64,
    rho: f64,
}

/// The dampers of the equivalent or nonviscous model of a rotor held sparse.
#[derive(Debug, Clone)]
pub struct ModalDampers {
    model: DampingModel,
    /// The rotor's coordinates `n`.
    n: usize,
    doubled: bool,
    /// Nonrotating dampers: the axisymmetric modes, or the x/y modes when doubled.
    nonrotating: Vec<Mode>,
    /// Whether each nonrotating damper exists (nonviscous: loss at some table speed).
    present: Vec<bool>,
    rotating: Vec<Rotating>,
}

/// `Re(phi^H A phi)` for complex entries `A`.
fn quadratic(a: &[(usize, usize, c64)], phi: &[c64]) -> f64 {
    a.iter()
        .map(|&(i, j, v)| (phi[i].conj() * v * phi[j]).re)
        .sum()
}

/// `A x` for complex entries.
fn times(a: &[(usize, usize, c64)], size: usize, x: &[c64]) -> Vec<c64> {
    let mut y = vec![c64::new(0.0, 0.0); size];
    for &(i, j, v) in a {
        y[i] += v * x[j];
    }
    y
}

impl ModalDampers {
    /// The dampers of `model` (equivalent or nonviscous) on the modes up to `DAMPER_BAND *
    /// bound` (or the model's `modes`), found by Lanczos; `None` for the other models.
    pub fn new(
        system: &RotorSystem,
        model: &DampingModel,
        bound: f64,
    ) -> Result<Option<Self>, ModalError> {
        let modes = match model {
            DampingModel::Equivalent { modes } => *modes,
            DampingModel::Nonviscous(spec) => spec.modes,
            _ => return Ok(None),
        };
        let top = DAMPER_BAND * bound;
        // Every mode up to `top` and one past it, or `modes` of them (x/y modes: twice).
        let enough = |copies: usize| {
            move |w2: &[f64]| match modes {
                Some(k) => w2.len() >= copies * k,
                None => w2.last().is_some_and(|&l| l.sqrt() > top) || w2.len() > MAX_DAMPED_MODES,
            }
        };
        let keep = |omega: &[f64], copies: usize| match modes {
            Some(k) => (copies * k).min(omega.len()),
            // At most the modes the memory estimate counts (`MAX_DAMPED_MODES`).
            None => omega
                .iter()
                .filter(|&&w| w <= top)
                .count()
                .clamp(1, MAX_DAMPED_MODES),
        };
        let n = system.n();
        let doubled = system.layout() == Layout::Doubled;
        let size = if doubled { 2 * n } else { n };
        let axis = ModalBasis::lowest(system, enough(1))?;
        let kept = keep(&axis.omega, 1);
        let axis = axis.truncated(kept);
        let (_, axis_mass) = pencil(system);
        let axis_modes: Vec<Mode> = (0..axis.len())
            .map(|i| {
                let phi: Vec<f64> = (0..n).map(|r| axis.phi[(r, i)]).collect();
                Mode {
                    w: axis.omega[i],
                    column: axis_mass.mul_vec(&phi).into_iter().map(real).collect(),
                    phi: phi.into_iter().map(real).collect(),
                }
            })
            .collect();
        let xy_modes = if doubled {
            let xy = HermitianBasis::lowest(system, enough(2))?;
            let xy = xy.truncated(keep(&xy.omega, 2));
            let (_, mass) = undamped_doubled(system);
            Some(
                (0..xy.omega.len())
                    .map(|i| {
                        let phi: Vec<c64> = (0..2 * n).map(|r| xy.phi[(r, i)]).collect();
                        Mode {
                            w: xy.omega[i],
                            column: times(&mass, 2 * n, &phi),
                            phi,
                        }
                    })
                    .collect::<Vec<_>>(),
            )
        } else {
            None
        };
        let loss_r = &system.hysteretic_rotating;
        let axis_loss = |m: &Mode| {
            let phi: Vec<f64> = m.phi.iter().map(|v| v.re).collect();
            phi.iter()
                .zip(loss_r.mul_vec(&phi))
                .map(|(a, b)| a * b)
                .sum::<f64>()
        };
        let nonviscous = matches!(model, DampingModel::Nonviscous(_));
        let nonrotating = xy_modes.clone().unwrap_or_else(|| axis_modes.clone());
        let rotating: Vec<Rotating> = match (&xy_modes, nonviscous) {
            // The equivalent rotating damper of doubled coordinates is on the x/y modes.
            (Some(xy), false) => {
                let loss = rotor_loss_entries(system, true);
                xy.iter()
                    .map(|m| Rotating {
                        loss: quadratic(&loss, &m.phi),
                        mode: m.clone(),
                        rho: 0.0,
                    })
                    .collect()
            }
            // The nonviscous one on the axisymmetric modes, on each copy.
            (Some(_), true) => axis_modes
                .iter()
                .flat_map(|m| {
                    let loss = axis_loss(m);
                    [1.0, -1.0].map(|rho| {
                        let offset = if rho > 0.0 { 0 } else { n };
                        let mut column = vec![c64::new(0.0, 0.0); size];
                        column[offset..offset + n].copy_from_slice(&m.column);
                        let mut phi = vec![c64::new(0.0, 0.0); size];
                        phi[offset..offset + n].copy_from_slice(&m.phi);
                        Rotating {
                            mode: Mode {
                                w: m.w,
                                phi,
                                column,
                            },
                            loss,
                            rho,
                        }
                    })
                })
                .collect(),
            (None, _) => axis_modes
                .iter()
                .map(|m| Rotating {
                    loss: axis_loss(m),
                    mode: m.clone(),
                    rho: 1.0,
                })
                .collect(),
        };
        let mut out = ModalDampers {
            model: model.clone(),
            n,
            doubled,
            present: vec![true; nonrotating.len()],
            nonrotating,
            rotating,
        };
        if nonviscous {
            // A nonviscous damper exists where its mode has loss at some table speed.
            let mut points = system.table_speeds();
            if points.is_empty() {
                points.push(0.0);
            }
            let losses: Vec<Vec<f64>> = points.iter().map(|&w| out.losses(system, w)).collect();
            out.present = (0..out.nonrotating.len())
                .map(|i| losses.iter().any(|l| l[i] > 0.0))
                .collect();
        }
        Ok(Some(out))
    }

    /// The modes the dampers are on (axisymmetric; x/y modes when doubled), for the answer.
    pub fn modes(&self) -> usize {
        self.nonrotating.len()
    }

    /// The highest natural frequency with a damper, rad/s.
    pub fn band(&self) -> f64 {
        self.nonrotating.iter().map(|m| m.w).fold(0.0, f64::max)
    }

    /// Internal coordinates of the nonviscous model (0 for the equivalent one).
    pub fn internal(&self) -> usize {
        let DampingModel::Nonviscous(spec) = &self.model else {
            return 0;
        };
        let n = self.present.iter().filter(|&&p| p).count() * spec.nonrotating.count();
        let r = self.rotating.iter().filter(|r| r.loss > 0.0).count() * spec.rotating.count();
        n + r
    }

    /// The nonrotating dampers' loss stiffness at `speed` (the supports' loss as the sparse
    /// full model holds it there).
    fn losses(&self, system: &RotorSystem, speed: f64) -> Vec<f64> {
        let loss = nonrotating_loss_entries(system, speed);
        self.nonrotating
            .iter()
            .map(|m| quadratic(&loss, &m.phi))
            .collect()
    }

    /// The dampers at `speed` as terms of `Z(s)` (module docs), shared by the problems built
    /// on them (`large::problems`).
    pub fn at(&self, system: &RotorSystem, speed: f64) -> std::sync::Arc<Terms> {
        std::sync::Arc::new(self.terms(system, speed))
    }

    /// The dampers at `speed` as terms of `Z(s)` (module docs).
    pub fn terms(&self, system: &RotorSystem, speed: f64) -> Terms {
        let losses = self.losses(system, speed);
        let mut columns = vec![];
        let mut terms = vec![];
        let zero = c64::new(0.0, 0.0);
        match &self.model {
            DampingModel::Nonviscous(spec) => {
                let mut branch = |set: &BranchSet, m: &Mode, loss: f64, rho: f64| {
                    let c = columns.len();
                    columns.push(m.column.clone());
                    let branches = set
                        .rates(m.w)
                        .into_iter()
                        .enumerate()
                        .map(|(j, d)| {
                            let k = loss * set.gamma()[j];
                            (k, set.nu()[j] * k, d, rho)
                        })
                        .collect();
                    terms.push(Term {
                        left: c,
                        right: c,
                        a: zero,
                        b: zero,
                        branches,
                    });
                };
                for (i, m) in self.nonrotating.iter().enumerate() {
                    if self.present[i] {
                        branch(&spec.nonrotating, m, losses[i].max(0.0), 0.0);
                    }
                }
                for r in self.rotating.iter().filter(|r| r.loss > 0.0) {
                    branch(&spec.rotating, &r.mode, r.loss, r.rho);
                }
            }
            _ => {
                let i1 = c64::new(0.0, 1.0);
                // Both dampers of a mode on its column (the rotating one on the x/y modes when
                // doubled, `equivalent.rs`): `c u u^H` in the damping, and the rotating one's
                // `-i Omega S c_r u u^H` in the stiffness (`S = I` in the single layout).
                for (i, m) in self.nonrotating.iter().enumerate() {
                    let c_n = losses[i] / m.w;
                    let c_r = self.rotating[i].loss / m.w;
                    if c_n == 0.0 && c_r == 0.0 {
                        continue;
                    }
                    let c = columns.len();
                    columns.push(m.column.clone());
                    let spun = match self.doubled {
                        false => c,
                        true => {
                            columns.push(
                                m.column
                                    .iter()
                                    .enumerate()
                                    .map(|(i, v)| if i < self.n { *v } else { -*v })
                                    .collect(),
                            );
                            c + 1
                        }
                    };
                    let stiffness = -i1 * (speed * c_r);
                    terms.push(Term {
                        left: c,
                        right: c,
                        a: real(c_n + c_r),
                        b: if spun == c { stiffness } else { zero },
                        branches: vec![],
                    });
                    if spun != c && c_r != 0.0 {
                        terms.push(Term {
                            left: spun,
                            right: c,
                            a: zero,
                            b: stiffness,
                            branches: vec![],
                        });
                    }
                }
            }
        }
        Terms {
            speed,
            columns,
            terms,
        }
    }

    /// The dampers projected on a reduction's real basis `phi` (`n x v`; on both blocks when
    /// doubled), at each of `points` (the reduced model's table speeds): the equivalent
    /// model's `(C_eq,r, C_eq,n)` or the nonviscous model's branches, as the dense models
    /// build them on a rotor's own modes.
    pub fn projected(&self, system: &RotorSystem, phi: &RMat, points: &[f64]) -> Projected {
        let v = phi.ncols();
        let vv = if self.doubled { 2 * v } else { v };
        // `P^T u`, P = phi or diag(phi, phi).
        let project = |u: &[c64]| -> Vec<c64> {
            (0..vv)
                .map(|c| {
                    let (offset, col) = if c < v { (0, c) } else { (self.n, c - v) };
                    (0..self.n)
                        .map(|r| u[offset + r] * phi[(r, col)])
                        .sum::<c64>()
                })
                .collect()
        };
        let nonrotating: Vec<Vec<c64>> = self
            .nonrotating
            .iter()
            .map(|m| project(&m.column))
            .collect();
        let rotating: Vec<Vec<c64>> = self
            .rotating
            .iter()
            .map(|r| project(&r.mode.column))
            .collect();
        let outer = |cols: &[(Vec<c64>, f64)]| {
            let mut c = CMat::zeros(vv, vv);
            for (u, w) in cols {
                for s in 0..vv {
                    let us = u[s].conj() * *w;
                    for r in 0..vv {
                        c[(r, s)] += u[r] * us;
                    }
                }
            }
            c
        };
        let per_point = points
            .iter()
            .map(|&speed| {
                let losses = self.losses(system, speed);
                match &self.model {
                    DampingModel::Nonviscous(spec) => {
                        let mut b = Branches::none(vv);
                        let mut cols = vec![];
                        let mut add =
                            |set: &BranchSet, w: f64, loss: f64, rho: f64, mode, u: &Vec<c64>| {
                                for (j, d) in set.rates(w).into_iter().enumerate() {
                                    let k = loss * set.gamma()[j];
                                    b.stiffness.push(k);
                                    b.main_stiffness.push(set.nu()[j] * k);
                                    b.rate.push(d);
                                    b.spin.push(rho);
                                    b.mode.push(mode);
                                    b.index.push(j);
                                    cols.push(u.clone());
                                }
                            };
                        // A damper whose mode the basis barely holds (`|P^T u|^2`, the M-norm
                        // fraction of its shape in the basis's span, below `HELD`) acts on the
                        // reduced rotor by no more than that fraction of its loss; its
                        // branches would only add states (the check still compares with the
                        // full model, which keeps them).
                        let held =
                            |u: &Vec<c64>| u.iter().map(|v| v.norm_sqr()).sum::<f64>() >= HELD;
                        for (i, m) in self.nonrotating.iter().enumerate() {
                            if self.present[i] && held(&nonrotating[i]) {
                                add(
                                    &spec.nonrotating,
                                    m.w,
                                    losses[i].max(0.0),
                                    0.0,
                                    i,
                                    &nonrotating[i],
                                );
                            }
                        }
                        for (i, r) in self.rotating.iter().enumerate() {
                            if r.loss > 0.0 && held(&rotating[i]) {
                                add(&spec.rotating, r.mode.w, r.loss, r.rho, i, &rotating[i]);
                            }
                        }
                        b.coupling = CMat::from_fn(vv, cols.len(), |r, c| cols[c][r]);
                        Damping::Branches(Box::new(b))
                    }
                    _ => {
                        let c_n: Vec<(Vec<c64>, f64)> = self
                            .nonrotating
                            .iter()
                            .zip(&nonrotating)
                            .zip(&losses)
                            .map(|((m, u), l)| (u.clone(), l / m.w))
                            .collect();
                        let c_r: Vec<(Vec<c64>, f64)> = self
                            .rotating
                            .iter()
                            .zip(&rotating)
                            .map(|(r, u)| (u.clone(), r.loss / r.mode.w))
                            .collect();
                        Damping::Equivalent {
                            rotating: outer(&c_r),
                            nonrotating: outer(&c_n),
                        }
                    }
                }
            })
            .collect();
        Projected { per_point }
    }
}

/// Fraction of a damper's mode a reduction's basis must hold for the reduced nonviscous model
/// to keep its branches ([`ModalDampers::projected`]).
const HELD: f64 = 1e-6;

/// A real number as complex.
fn real(v: f64) -> c64 {
    c64::new(v, 0.0)
}

/// The dampers on a reduced rotor, one per realization of its supports.
#[derive(Debug, Clone)]
pub struct Projected {
    pub per_point: Vec<Damping>,
}

/// The dampers at one realization.
#[derive(Debug, Clone)]
pub enum Damping {
    Equivalent { rotating: CMat, nonrotating: CMat },
    Branches(Box<Branches>),
}
