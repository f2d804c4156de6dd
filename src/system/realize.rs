//! The rotor at one speed as complex second-order matrices, in the coordinates it is solved in.
//!
//! With every support isotropic, `q = r` (`N = n`, the **single** layout) and a support adds
//! its `a_iso` to the diagonal entry of its translation. Otherwise `q = (r, conj r)` (`N = 2n`,
//! the **doubled** layout, MODEL.md section 8): the `conj r` rows are the conjugates of the `r`
//! rows, so the rotor's real matrices stand on both diagonal blocks, the terms proportional to
//! the spin speed change sign there (`spin = -1`: `-i Omega G` becomes `+i Omega G`, and
//! rotating damping's circulatory term `-i Omega C_r` becomes `+i Omega C_r`), and a support on
//! translation `d` writes `[[a_iso, a_an], [conj a_an, conj a_iso]]` on rows and columns
//! `(d, n + d)`. Hysteretic loss: the rotor's on both blocks (the rotating part sees
//! `omega - Omega` on the `r` rows and `omega + Omega` on the others, which `spin` tells), the
//! supports' `loss_factor` times the symmetric part of their stiffness.

use super::RotorSystem;
use crate::linalg::{CMat, Sparse, c64};
use crate::model::supports::{Coefficients, Matrix2};

/// The coordinates a rotor is solved in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Layout {
    /// `q = r`.
    Single,
    /// `q = (r, conj r)`.
    Doubled,
}

impl Layout {
    /// Coordinates of a rotor of `n` complex degrees of freedom: `n`, or `2 n` doubled.
    pub fn size(self, n: usize) -> usize {
        match self {
            Layout::Single => n,
            Layout::Doubled => 2 * n,
        }
    }
}

/// The rotor's matrices at one speed, complex, `N x N` (see the module docs).
#[derive(Debug, Clone)]
pub struct Realized {
    pub layout: Layout,
    /// Complex degrees of freedom of the rotor, before doubling.
    pub n: usize,
    pub mass: CMat,
    pub gyroscopic: CMat,
    /// Rotor and supports (all of each support's stiffness, circulatory part included).
    pub stiffness: CMat,
    pub damping_nonrotating: CMat,
    pub damping_rotating: CMat,
    pub loss_nonrotating: CMat,
    pub loss_rotating: CMat,
    /// Per row: `+1` for `r`, `-1` for `conj r`: the sign of the terms in the spin speed.
    pub spin: Vec<f64>,
    /// The supports' Maxwell branches (a table over whirl frequency fitted for the time
    /// domain); none for the undamped rotor.
    pub branches: SupportBranches,
}

/// The supports' Maxwell branches in the layout (`model::supports::fitted`): internal
/// coordinate `j` follows `y_j' = d_j (u_j^H q - y_j)` and pushes on the rotor with
/// `-w_j (u_j^H q - y_j)`. In the single layout one per branch, `u_j` the support's weights and
/// `w_j` those times `g_iso`; doubled, two (on `r` and on `conj r`), `w_j` a column of the
/// branch's action on both.
#[derive(Debug, Clone)]
pub struct SupportBranches {
    pub u: CMat,
    pub w: CMat,
    pub rate: Vec<f64>,
    /// Per internal coordinate: the support (its position in `supports`), the branch index,
    /// and whether it is the `conj r` copy.
    pub of: Vec<(usize, usize, bool)>,
}

impl SupportBranches {
    pub fn none(size: usize) -> Self {
        SupportBranches {
            u: CMat::zeros(size, 0),
            w: CMat::zeros(size, 0),
            rate: vec![],
            of: vec![],
        }
    }

    pub fn len(&self) -> usize {
        self.rate.len()
    }

    pub fn is_empty(&self) -> bool {
        self.rate.is_empty()
    }

    /// The branches of `system`'s supports at `speed`, in `layout`.
    fn of(system: &RotorSystem, layout: Layout, speed: f64) -> Self {
        let n = system.n();
        let size = layout.size(n);
        let (mut u_cols, mut w_cols) = (vec![], vec![]);
        let (mut rate, mut of) = (vec![], vec![]);
        for (s, p) in system.supports.iter().enumerate() {
            let Some(f) = &p.support.branches else {
                continue;
            };
            let weights = p.at.weights();
            for (j, g) in f.at(speed).iter().enumerate() {
                let a = point_action(g, layout);
                for b in 0..a.ncols() {
                    let mut u = vec![c64::new(0.0, 0.0); size];
                    let mut w = vec![c64::new(0.0, 0.0); size];
                    for &(i, wi) in &weights {
                        u[i + b * n] = c64::new(wi, 0.0);
                        for r in 0..a.nrows() {
                            w[i + r * n] = a[(r, b)] * wi;
                        }
                    }
                    u_cols.push(u);
                    w_cols.push(w);
                    rate.push(f.rates[j]);
                    of.push((s, j, b == 1));
                }
            }
        }
        let cols = |c: &[Vec<c64>]| CMat::from_fn(size, c.len(), |i, j| c[j][i]);
        SupportBranches {
            u: cols(&u_cols),
            w: cols(&w_cols),
            rate,
            of,
        }
    }
}

/// A real `n x n` matrix on the diagonal block(s) of an `N x N` complex one.
fn blocks(a: &Sparse, layout: Layout) -> CMat {
    let n = a.nrows();
    let size = layout.size(n);
    let mut out = CMat::zeros(size, size);
    for (i, j, v) in a.entries() {
        out[(i, j)] = c64::new(v, 0.0);
        if layout == Layout::Doubled {
            out[(n + i, n + j)] = c64::new(v, 0.0);
        }
    }
    out
}

/// Adds `i S` on the `r` block and its conjugate `-i S` on the `conj r` block.
fn add_circulatory(target: &mut CMat, s: &Sparse, layout: Layout) {
    let n = s.nrows();
    for (i, j, a) in s.entries() {
        {
            if a != 0.0 {
                target[(i, j)] += c64::new(0.0, a);
                if layout == Layout::Doubled {
                    target[(n + i, n + j)] += c64::new(0.0, -a);
                }
            }
        }
    }
}

/// The action of a support coefficient matrix on one point's coordinates: `[a_iso]`, or on
/// `(r, conj r)` `[[a_iso, a_an], [conj a_an, conj a_iso]]` (`supports.rs`).
pub fn point_action(a: &Matrix2, layout: Layout) -> CMat {
    let (iso, an) = a.complex();
    match layout {
        Layout::Single => CMat::from_fn(1, 1, |_, _| iso),
        Layout::Doubled => CMat::from_fn(2, 2, |i, j| match (i, j) {
            (0, 0) => iso,
            (0, 1) => an,
            (1, 0) => an.conj(),
            _ => iso.conj(),
        }),
    }
}

/// Adds a support coefficient matrix on the translation `sum w_i q_i` (`weights`).
fn add_support(target: &mut CMat, weights: &[(usize, f64)], n: usize, a: &Matrix2, layout: Layout) {
    let k = point_action(a, layout);
    for &(i, wi) in weights {
        for &(j, wj) in weights {
            let w = wi * wj;
            for b in 0..k.nrows() {
                for c in 0..k.ncols() {
                    target[(i + b * n, j + c * n)] += k[(b, c)] * w;
                }
            }
        }
    }
}

impl Realized {
    /// Size `N` of the matrices.
    pub fn size(&self) -> usize {
        self.mass.nrows()
    }

    /// The rotor with its supports' coefficients at `speed`.
    pub fn at(system: &RotorSystem, speed: f64) -> Self {
        let layout = system.layout();
        let mut r = Self::with(system, layout, |s| s.at(speed));
        r.branches = SupportBranches::of(system, layout, speed);
        r
    }

    /// The rotor with each support's coefficients as `coefficients` gives them.
    fn with(
        system: &RotorSystem,
        layout: Layout,
        coefficients: impl Fn(&crate::model::supports::GeneralSupport) -> Coefficients,
    ) -> Self {
        let n = system.n();
        let mut r = Realized {
            layout,
            n,
            mass: blocks(&system.mass, layout),
            gyroscopic: blocks(&system.gyroscopic, layout),
            stiffness: blocks(&system.stiffness(), layout),
            damping_nonrotating: blocks(&system.damping_nonrotating, layout),
            damping_rotating: blocks(&system.damping_rotating, layout),
            loss_nonrotating: blocks(&system.hysteretic_nonrotating, layout),
            loss_rotating: blocks(&system.hysteretic_rotating, layout),
            spin: match layout {
                Layout::Single => vec![1.0; n],
                Layout::Doubled => (0..2 * n).map(|i| if i < n { 1.0 } else { -1.0 }).collect(),
            },
            branches: SupportBranches::none(layout.size(n)),
        };
        add_circulatory(&mut r.stiffness, &system.circulatory, layout);
        for p in &system.supports {
            let c = coefficients(&p.support);
            let d = p.at.weights();
            add_support(&mut r.stiffness, &d, n, &c.k, layout);
            add_support(&mut r.damping_nonrotating, &d, n, &c.c, layout);
            add_support(&mut r.mass, &d, n, &c.m, layout);
            let loss = c.k.symmetric().scaled(p.support.loss_factor);
            add_support(&mut r.loss_nonrotating, &d, n, &loss, layout);
        }
        r
    }

    /// The undamped, nonrotating rotor in `layout`: its stiffness and mass with the symmetric
    /// parts of the supports' coefficients at rest (held at the start of a table). In the
    /// single layout of a rotor whose supports are not isotropic, those are averaged over
    /// the directions: the rotor's own axisymmetric modes.
    pub fn undamped(system: &RotorSystem, layout: Layout) -> (CMat, CMat) {
        let r = Self::with(system, layout, |s| {
            let c = s.at_rest();
            let sym = |m: &Matrix2| {
                let m = m.symmetric();
                match layout {
                    Layout::Doubled => m,
                    Layout::Single => {
                        let avg = 0.5 * (m.xx + m.yy);
                        Matrix2 {
                            xx: avg,
                            xy: 0.0,
                            yx: 0.0,
                            yy: avg,
                        }
                    }
                }
            };
            Coefficients {
                k: sym(&c.k),
                c: Matrix2::default(),
                m: sym(&c.m),
            }
        });
        (r.stiffness, r.mass)
    }

    /// A rotor matrix (`n x n`) on the diagonal block(s) of the layout.
    pub fn on_blocks(&self, a: &CMat) -> CMat {
        let n = self.n;
        match self.layout {
            Layout::Single => a.clone(),
            Layout::Doubled => CMat::from_fn(2 * n, 2 * n, |i, j| {
                if (i < n) == (j < n) {
                    a[(i % n, j % n)]
                } else {
                    c64::new(0.0, 0.0)
                }
            }),
        }
    }

    /// `diag(spin) A`: a matrix multiplied, row by row, by the sign of the spin terms.
    pub fn spun(&self, a: &CMat) -> CMat {
        CMat::from_fn(a.nrows(), a.ncols(), |i, j| a[(i, j)] * self.spin[i])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::supports::{GeneralSupport, Law};
    use crate::system::{Dof, DofKind, PlacedSupport, Placement};

    fn one_dof(k: Matrix2) -> RotorSystem {
        let one = |v: f64| Sparse::from_triplets(1, 1, &[(0, 0, v)]);
        RotorSystem {
            mass: one(2.0),
            gyroscopic: one(0.0),
            stiffness_rotating: one(10.0),
            stiffness_nonrotating: one(0.0),
            damping_rotating: one(0.0),
            damping_nonrotating: one(0.0),
            hysteretic_rotating: one(0.0),
            hysteretic_nonrotating: one(0.0),
            circulatory: one(0.0),
            dofs: vec![Dof {
                node: 0,
                kind: DofKind::Translation,
            }],
            supports: vec![PlacedSupport {
                at: Placement::Dof(0),
                support: GeneralSupport {
                    index: 0,
                    seal: false,
                    node: 0,
                    link: None,
                    law: Law::Constant(Coefficients {
                        k,
                        ..Coefficients::default()
                    }),
                    loss_factor: 0.1,
                    branches: None,
                },
            }],
        }
    }

    #[test]
    fn the_doubled_stiffness_is_the_real_xy_stiffness_in_r_and_conj_r() {
        let k = Matrix2 {
            xx: 3.0,
            xy: 1.0,
            yx: -2.0,
            yy: 5.0,
        };
        let s = one_dof(k);
        assert_eq!(s.layout(), Layout::Doubled);
        let r = Realized::at(&s, 100.0);
        // For a real motion (x, y), q = (x + i y, x - i y): the r row of K q is the complex
        // force -(f_x + i f_y) of the rotor's 10 and the support's [[3, 1], [-2, 5]].
        let (x, y) = (0.7, -0.2);
        let q = [c64::new(x, y), c64::new(x, -y)];
        let row = r.stiffness[(0, 0)] * q[0] + r.stiffness[(0, 1)] * q[1];
        let fx = 13.0 * x + 1.0 * y;
        let fy = -2.0 * x + 15.0 * y;
        assert!((row - c64::new(fx, fy)).norm() < 1e-14);
        let conj = r.stiffness[(1, 0)] * q[0] + r.stiffness[(1, 1)] * q[1];
        assert!((conj - c64::new(fx, -fy)).norm() < 1e-14);
        assert_eq!(r.spin, vec![1.0, -1.0]);
        // Loss: 0.1 of the symmetric part, [[3, -0.5], [-0.5, 5]].
        let lr = r.loss_nonrotating[(0, 0)] * q[0] + r.loss_nonrotating[(0, 1)] * q[1];
        assert!(
            (lr - c64::new(0.1 * (3.0 * x - 0.5 * y), 0.1 * (-0.5 * x + 5.0 * y))).norm() < 1e-14
        );
    }
}
