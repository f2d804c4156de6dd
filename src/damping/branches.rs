//! Maxwell branches on massless internal coordinates: a damping model's (the nonviscous
//! model's dampers, `nonviscous.rs`, `dampers.rs`) and a support's (its table over whirl
//! frequency fitted, `whirl_fit.rs`), in the form `state.rs` assembles.

use crate::linalg::CMat;
use crate::system::SupportBranches;

/// Maxwell branches on massless internal coordinates (see the module docs).
#[derive(Debug, Clone)]
pub struct Branches {
    /// `U`: column j maps physical coordinates to the coordinate branch j acts on,
    /// `u_j^H x` (real in the single layout).
    pub coupling: CMat,
    /// Branch spring stiffness `k_j`.
    pub stiffness: Vec<f64>,
    /// Stiffness `nu_j k_j` the branch adds on its main coordinate.
    pub main_stiffness: Vec<f64>,
    /// Relaxation rate `d_j = k_j / c_j`, 1/s.
    pub rate: Vec<f64>,
    /// `rho_j`: 0 for a nonrotating branch; for a rotating one, whose damper is in the rotor,
    /// +1 on `r` and -1 on `conj r` (the internal equation's `+i Omega rho_j y_j`).
    pub spin: Vec<f64>,
    /// Mode (0-based) whose damper the branch belongs to.
    pub mode: Vec<usize>,
    /// Index j (0-based) of the branch within its damper.
    pub index: Vec<usize>,
    /// `(W, W_nu)` where they are not `(U diag(k), U diag(nu k))`: with a support's branches,
    /// whose force is along its own column (then `k_j` is that column's largest entry, a
    /// scale for the branch's energy).
    pub loads: Option<(CMat, CMat)>,
    /// How many of the branches, the last ones, are a support's (its table over whirl
    /// frequency fitted): physical poles of the support, not of a damping model.
    pub from_supports: usize,
}

impl Branches {
    /// No internal coordinates.
    pub fn none(n: usize) -> Self {
        Branches {
            coupling: CMat::zeros(n, 0),
            stiffness: vec![],
            main_stiffness: vec![],
            rate: vec![],
            spin: vec![],
            mode: vec![],
            index: vec![],
            loads: None,
            from_supports: 0,
        }
    }

    /// `W`: column `j` is the direction branch `j` pushes the rotor along, times its stiffness.
    pub fn load(&self) -> CMat {
        match &self.loads {
            Some((w, _)) => w.clone(),
            None => self.scaled(&self.stiffness),
        }
    }

    /// `W_nu`: the stiffness each branch adds on its own coordinate, `W_nu U^H`.
    pub fn main_load(&self) -> CMat {
        match &self.loads {
            Some((_, w)) => w.clone(),
            None => self.scaled(&self.main_stiffness),
        }
    }

    /// `U diag(k)`.
    fn scaled(&self, k: &[f64]) -> CMat {
        let u = &self.coupling;
        CMat::from_fn(u.nrows(), u.ncols(), |i, j| u[(i, j)] * k[j])
    }

    /// These branches and the supports' ([`SupportBranches`]) after them. A support's branch is
    /// nonrotating, its own damper (`mode` is its support, `index` its branch).
    pub fn with_supports(&self, s: &SupportBranches) -> Branches {
        if s.is_empty() {
            return self.clone();
        }
        let (n, p, q) = (self.coupling.nrows(), self.len(), s.len());
        let join = |a: &CMat, b: &CMat| {
            CMat::from_fn(
                n,
                p + q,
                |i, j| if j < p { a[(i, j)] } else { b[(i, j - p)] },
            )
        };
        let scale: Vec<f64> = (0..q)
            .map(|j| (0..n).map(|i| s.w[(i, j)].norm()).fold(0.0, f64::max))
            .collect();
        let mut out = self.clone();
        out.coupling = join(&self.coupling, &s.u);
        out.loads = Some((join(&self.load(), &s.w), join(&self.main_load(), &s.w)));
        out.stiffness.extend(&scale);
        out.main_stiffness.extend(&scale);
        out.rate.extend(&s.rate);
        out.spin.extend(std::iter::repeat_n(0.0, q));
        out.mode.extend(s.of.iter().map(|o| o.0));
        out.index.extend(s.of.iter().map(|o| o.1));
        out.from_supports += q;
        out
    }

    pub fn len(&self) -> usize {
        self.stiffness.len()
    }

    pub fn is_empty(&self) -> bool {
        self.stiffness.is_empty()
    }

    /// Whether any branch is a damping model's (not a support's).
    pub fn modelled(&self) -> bool {
        self.len() > self.from_supports
    }

    /// Whether branch `j` is rotating.
    pub fn rotating(&self, j: usize) -> bool {
        self.spin[j] != 0.0
    }
}
