//! Supports whose coefficients follow curves of the spin speed (ROSS's splines, and linear
//! tables beside them), scheduled on one state model instead of one per table speed.
//!
//! A support acts on the coordinates through its real weights `w` (its translation is
//! `P^T q`, `P = w` in the single layout, `[w 0; 0 w]` on `r` and `conj r` when doubled), so
//! its stiffness and damping enter the second-order form as `P kappa(K_s) P^T` and
//! `P kappa(C_s) P^T`, `kappa` the `q x q` complex form of a 2x2 coefficient matrix
//! (`[a_iso]`, or `[[a_iso, a_an], [conj a_an, conj a_iso]]`; `supports.rs`). The state
//! matrix is therefore affine in them: with a model built once at a reference speed `w0`,
//!
//! ```text
//! A(w) z = A_ref(w) z + sum_s G_s (dK_s(w) P_s^T x + dC_s(w) P_s^T v),   G_s = -M^-1 P_s,
//! ```
//!
//! `dK_s(w) = kappa(K_s(w)) - kappa(K_s(w0))` (likewise `dC_s`), exact at every speed whatever
//! the curves are, as long as the mass coefficients are constant and a tabulated support has
//! no loss factor (its loss would enter the hysteretic and modal models otherwise):
//! `supports.rs` refuses both on every table of a rotor with a support on ROSS's curves
//! (`check_schedule`). `kappa` is [`point_action`], the one `Realized` assembles with.

use crate::linalg::{self, CMat, LinalgError, c64};
use crate::model::supports::GeneralSupport;
use crate::system::{Layout, Realized, RotorSystem, point_action};

/// One tabulated support: where it acts, its reference coefficients and `G = -M^-1 P`.
#[derive(Debug, Clone)]
struct Term {
    support: GeneralSupport,
    /// `kappa` of its stiffness and damping at the reference speed.
    k0: CMat,
    c0: CMat,
    /// `(coordinate, weight)` over the rotor's coordinates (the `r` block).
    weights: Vec<(usize, f64)>,
    /// `n x q`, `n` the layout's coordinates.
    g: CMat,
}

/// The tabulated supports of a rotor, scheduled on a state model built at `reference`.
#[derive(Debug, Clone)]
pub struct Schedule {
    /// Coordinates of the layout (`n`, or `2n` doubled) and of the rotor (`n`).
    n: usize,
    rotor: usize,
    layout: Layout,
    terms: Vec<Term>,
}

impl Schedule {
    /// Whether `system` needs a schedule: a support on ROSS's curves. Its other tables then go
    /// on the schedule too (see the module docs for what they may not have).
    pub fn applies(system: &RotorSystem) -> bool {
        system.supports.iter().any(|p| p.support.ross())
    }

    /// The speed the model is built at: the first speed of the tables.
    pub fn reference_speed(system: &RotorSystem) -> f64 {
        system
            .supports
            .iter()
            .filter_map(|p| p.support.speeds().first().copied())
            .reduce(f64::min)
            .unwrap_or(0.0)
    }

    /// The schedule of `system`'s tabulated supports on the model realized at `reference`
    /// (`r`: its mass gives `G`).
    pub fn new(system: &RotorSystem, r: &Realized, reference: f64) -> Result<Self, LinalgError> {
        let n = r.size();
        let rotor = system.n();
        let layout = r.layout;
        let q = if layout == Layout::Doubled { 2 } else { 1 };
        let tabulated: Vec<_> = system
            .supports
            .iter()
            .filter(|p| !p.support.speeds().is_empty())
            .collect();
        // All the P_s side by side: one solve with M for every G_s.
        let mut p = CMat::zeros(n, q * tabulated.len());
        let weights: Vec<Vec<(usize, f64)>> = tabulated.iter().map(|s| s.at.weights()).collect();
        for (s, w) in weights.iter().enumerate() {
            for &(i, wi) in w {
                for b in 0..q {
                    p[(i + b * rotor, q * s + b)] = c64::new(wi, 0.0);
                }
            }
        }
        let m_inv_p = linalg::mass_solve(&r.mass, &p)?;
        let terms = tabulated
            .iter()
            .zip(weights)
            .enumerate()
            .map(|(s, (placed, weights))| {
                let c = placed.support.at(reference);
                Term {
                    support: placed.support.clone(),
                    k0: point_action(&c.k, layout),
                    c0: point_action(&c.c, layout),
                    weights,
                    g: CMat::from_fn(n, q, |i, b| -m_inv_p[(i, q * s + b)]),
                }
            })
            .collect();
        Ok(Schedule {
            n,
            rotor,
            layout,
            terms,
        })
    }

    /// Speeds where a linear table on the schedule changes segment (ROSS's curves are
    /// smooth).
    pub fn breaks(&self) -> Vec<f64> {
        let mut w: Vec<f64> = self
            .terms
            .iter()
            .filter(|t| !t.support.ross())
            .flat_map(|t| t.support.speeds().iter().copied())
            .collect();
        w.sort_by(f64::total_cmp);
        w.dedup();
        w
    }

    fn q(&self) -> usize {
        if self.layout == Layout::Doubled { 2 } else { 1 }
    }

    /// `(dK, dC)` of each support at `speed`.
    fn deltas(&self, speed: f64) -> Vec<(CMat, CMat)> {
        self.terms
            .iter()
            .map(|t| {
                let c = t.support.at(speed);
                (
                    &point_action(&c.k, self.layout) - &t.k0,
                    &point_action(&c.c, self.layout) - &t.c0,
                )
            })
            .collect()
    }

    /// `P^T u` for a vector `u` over the layout's coordinates.
    fn project(&self, t: &Term, u: &[c64]) -> Vec<c64> {
        (0..self.q())
            .map(|b| {
                t.weights
                    .iter()
                    .map(|&(i, w)| u[i + b * self.rotor] * w)
                    .sum()
            })
            .collect()
    }

    /// `A += sum_s G_s (dK_s P_s^T` on the `x` columns, `dC_s P_s^T` on the `v` columns).
    pub fn add_to(&self, a: &mut CMat, speed: f64) {
        let (n, q) = (self.n, self.q());
        for (t, (dk, dc)) in self.terms.iter().zip(self.deltas(speed)) {
            let hk = &t.g * &dk;
            let hc = &t.g * &dc;
            for &(i, w) in &t.weights {
                for b in 0..q {
                    let col = i + b * self.rotor;
                    for row in 0..n {
                        a[(row, n + col)] += hk[(row, b)] * w;
                        a[(row, col)] += hc[(row, b)] * w;
                    }
                }
            }
        }
    }

    /// `y += sum_s G_s (dK_s P_s^T x + dC_s P_s^T v)` for the state `z = [v, x, ...]`.
    pub fn apply_add(&self, speed: f64, z: &[c64], y: &mut [c64]) {
        let n = self.n;
        for (t, (dk, dc)) in self.terms.iter().zip(self.deltas(speed)) {
            let f = mix(
                &dk,
                &self.project(t, &z[n..2 * n]),
                &dc,
                &self.project(t, &z[..n]),
            );
            linalg::add_matvec(&mut y[..n], &t.g, &f, c64::new(1.0, 0.0));
        }
    }

    /// The schedule's terms in the eigenvector basis `V` of a stage frozen at `speed` (the
    /// exponential integrator's `V^-1 (A(w) - A(speed)) V`, as thin factors).
    pub fn modal(&self, vinv: &CMat, v: &CMat, speed: f64) -> ModalSchedule<'_> {
        let n = self.n;
        let q = self.q();
        let vinv_top = CMat::from_fn(vinv.nrows(), n, |i, j| vinv[(i, j)]);
        let terms = self
            .terms
            .iter()
            .map(|t| {
                let right = |offset: usize| {
                    CMat::from_fn(q, v.ncols(), |b, k| {
                        t.weights
                            .iter()
                            .map(|&(i, w)| v[(offset + i + b * self.rotor, k)] * w)
                            .sum()
                    })
                };
                (&vinv_top * &t.g, right(n), right(0))
            })
            .collect();
        ModalSchedule {
            schedule: self,
            at: self.deltas(speed),
            terms,
        }
    }
}

/// `dK px + dC pv`.
fn mix(dk: &CMat, px: &[c64], dc: &CMat, pv: &[c64]) -> Vec<c64> {
    (0..dk.nrows())
        .map(|a| {
            (0..dk.ncols())
                .map(|b| dk[(a, b)] * px[b] + dc[(a, b)] * pv[b])
                .sum()
        })
        .collect()
}

/// A schedule in a stage's eigenvector basis: per support `V^-1 G` (`size x q`) and `P^T` of
/// the `x` and `v` rows of `V` (`q x size`).
pub struct ModalSchedule<'a> {
    schedule: &'a Schedule,
    /// `(dK, dC)` at the stage's speed.
    at: Vec<(CMat, CMat)>,
    terms: Vec<(CMat, CMat, CMat)>,
}

impl ModalSchedule<'_> {
    /// `y += V^-1 (A(speed) - A(stage)) V w` of the supports' part.
    pub fn add_apply(&self, speed: f64, w: &[c64], y: &mut [c64]) {
        for (((left, rx, rv), (dk, dc)), (dk0, dc0)) in self
            .terms
            .iter()
            .zip(self.schedule.deltas(speed))
            .zip(&self.at)
        {
            let mut px = vec![c64::new(0.0, 0.0); rx.nrows()];
            let mut pv = px.clone();
            linalg::add_matvec(&mut px, rx, w, c64::new(1.0, 0.0));
            linalg::add_matvec(&mut pv, rv, w, c64::new(1.0, 0.0));
            let f = mix(&(dk - dk0), &px, &(dc - dc0), &pv);
            linalg::add_matvec(y, left, &f, c64::new(1.0, 0.0));
        }
    }
}
