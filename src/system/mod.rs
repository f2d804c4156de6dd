//! The assembled rotor in complex coordinates: the one currency between `fem`, `damping` and
//! `analysis`.
//!
//! For an axisymmetric rotor on isotropic supports, with `q = x + i y` per node (translations,
//! and rotations `phi_y - i phi_x`), the equation of motion is (MODEL.md section 1)
//!
//! ```text
//! M q'' + (C_n + C_r - i Omega G) q' + (K - i Omega C_r) q  [+ i K''_n q + i K''_r q] = F(t)
//! ```
//!
//! All matrices are real and symmetric. Rotating (shaft) and nonrotating (support) parts are
//! kept apart all the way through: rotating damping brings the circulatory term
//! `-i Omega C_r`, and hysteretic damping sees the frequency `omega - Omega` in the rotor and
//! `omega` in the supports. The bracketed imaginary stiffness is how the damping models start;
//! each model in `damping` turns it into something an analysis can solve.
//!
//! Supports in the general form (cross-coupled, anisotropic, speed-dependent) are kept beside
//! the real matrices, on the translations they act on, and [`realize`] writes the whole rotor
//! at a given speed as complex matrices: in the coordinates `r` when every support is
//! isotropic, else in the doubled coordinates `(r, conj r)` (MODEL.md section 8).

pub mod realize;

use crate::linalg::Sparse;
use crate::model::rotor::Jeffcott;
use crate::model::supports::GeneralSupport;

pub use realize::{Layout, Realized, SupportBranches, point_action};

/// What a degree of freedom of the assembled system is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DofKind {
    /// Complex translation `x + i y`, m.
    Translation,
    /// Complex rotation `phi_y - i phi_x`, rad.
    Rotation,
    /// Modal coordinate `eta_k` of a reduced system (`node` is the mode index `k`, from 0).
    Mode,
    /// A shaft node's twist about the axis, rad, in its own shaft's angles (a torsional system:
    /// real motion in a complex coordinate).
    Twist,
    /// A shaft node's displacement along the axis, m (an axial system).
    Axial,
}

/// One complex degree of freedom: its node and kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Dof {
    pub node: usize,
    pub kind: DofKind,
}

/// Rotor matrices in complex coordinates (see the module docs), sparse: a beam's couple a node
/// with its neighbours only.
#[derive(Debug, Clone)]
pub struct RotorSystem {
    pub mass: Sparse,
    pub gyroscopic: Sparse,
    /// Real stiffness of the rotating parts (shaft).
    pub stiffness_rotating: Sparse,
    /// Real stiffness of the nonrotating parts (supports).
    pub stiffness_nonrotating: Sparse,
    pub damping_rotating: Sparse,
    pub damping_nonrotating: Sparse,
    /// Imaginary (hysteretic) stiffness `K''_r` of the rotating parts.
    pub hysteretic_rotating: Sparse,
    /// Imaginary (hysteretic) stiffness `K''_n` of the nonrotating parts.
    pub hysteretic_nonrotating: Sparse,
    /// Circulatory stiffness `S` (not symmetric): the stiffness is `K + i S` whatever the
    /// frequency's sign (a shaft's torque, `fem::conical`).
    pub circulatory: Sparse,
    pub dofs: Vec<Dof>,
    /// Supports in the general form, each on the degree of freedom of its translation.
    pub supports: Vec<PlacedSupport>,
}

/// A general support and the coordinates it acts on.
#[derive(Debug, Clone, PartialEq)]
pub struct PlacedSupport {
    pub at: Placement,
    pub support: GeneralSupport,
}

/// Where a support's translation `u` is in the coordinates `q` of a system.
#[derive(Debug, Clone, PartialEq)]
pub enum Placement {
    /// `u = q[d]`: a degree of freedom of an assembled rotor.
    Dof(usize),
    /// `u = q[a] - q[b]`: a support between two translations (a bearing on a pedestal).
    Between(usize, usize),
    /// `u = w^T q`: in modal coordinates `q = Phi eta` the row of `Phi` at the translation
    /// (real, so `conj u` is `w^T conj q` in doubled coordinates).
    Shape(Vec<f64>),
}

impl PlacedSupport {
    /// A general support on the coordinates numbered as its nodes (a matrix rotor's, a train's).
    pub fn on_nodes(g: &GeneralSupport) -> Self {
        PlacedSupport {
            at: match g.link {
                None => Placement::Dof(g.node),
                Some(l) => Placement::Between(g.node, l),
            },
            support: g.clone(),
        }
    }
}

impl Placement {
    /// `(coordinate, weight)` pairs whose sum is the support's translation.
    pub fn weights(&self) -> Vec<(usize, f64)> {
        match self {
            Placement::Dof(d) => vec![(*d, 1.0)],
            Placement::Between(a, b) => vec![(*a, 1.0), (*b, -1.0)],
            Placement::Shape(w) => w
                .iter()
                .enumerate()
                .filter(|(_, a)| **a != 0.0)
                .map(|(i, &a)| (i, a))
                .collect(),
        }
    }
}

impl RotorSystem {
    /// The Jeffcott rotor: one translation, the shaft's stiffness and loss are rotating.
    pub fn jeffcott(j: &Jeffcott) -> Self {
        let one = |v: f64| Sparse::from_triplets(1, 1, &[(0, 0, v)]);
        RotorSystem {
            mass: one(j.mass()),
            gyroscopic: one(0.0),
            stiffness_rotating: one(j.stiffness()),
            stiffness_nonrotating: one(0.0),
            damping_rotating: one(j.damping_rotating()),
            damping_nonrotating: one(j.damping_nonrotating()),
            hysteretic_rotating: one(j.loss_factor_rotating() * j.stiffness()),
            hysteretic_nonrotating: one(j.loss_factor_nonrotating() * j.stiffness()),
            circulatory: one(0.0),
            dofs: vec![Dof {
                node: 0,
                kind: DofKind::Translation,
            }],
            supports: vec![],
        }
    }

    /// Number of complex degrees of freedom.
    pub fn n(&self) -> usize {
        self.mass.nrows()
    }

    /// Total real stiffness `K` (without the general supports).
    pub fn stiffness(&self) -> Sparse {
        self.stiffness_rotating
            .plus(&self.stiffness_nonrotating, 1.0)
    }

    /// The coordinates the rotor is solved in.
    pub fn layout(&self) -> Layout {
        if self.supports.iter().all(|s| s.support.isotropic()) {
            Layout::Single
        } else {
            Layout::Doubled
        }
    }

    /// Whether any support's coefficients depend on the whirl frequency.
    pub fn frequency_dependent(&self) -> bool {
        self.supports
            .iter()
            .any(|s| s.support.frequency_dependent())
    }

    /// The rotor with each support over whirl frequency read at `speed` and `frequency`,
    /// constant, in the same coordinates (what a pole or a harmonic response at that
    /// frequency sees).
    pub fn read(&self, speed: f64, frequency: f64) -> Self {
        let mut s = self.clone();
        for p in &mut s.supports {
            p.support = p.support.read(speed, frequency);
        }
        s
    }

    /// Whether any support's coefficients change with the speed.
    pub fn speed_dependent(&self) -> bool {
        self.supports.iter().any(|s| !s.support.speeds().is_empty())
    }

    /// The supports' stiffness and mass at rest, symmetric parts averaged over the directions,
    /// as real `n x n` matrices: what the axisymmetric modes of the rotor see of them.
    pub fn supports_at_rest(&self) -> (Sparse, Sparse) {
        let n = self.n();
        let (mut k, mut m) = (vec![], vec![]);
        for p in &self.supports {
            let c = p.support.at_rest();
            let (kk, mm) = (0.5 * (c.k.xx + c.k.yy), 0.5 * (c.m.xx + c.m.yy));
            let w = p.at.weights();
            for &(i, a) in &w {
                for &(j, b) in &w {
                    k.push((i, j, kk * a * b));
                    m.push((i, j, mm * a * b));
                }
            }
        }
        (
            Sparse::from_triplets(n, n, &k),
            Sparse::from_triplets(n, n, &m),
        )
    }

    /// The speeds at which a support's table has a point (sorted, deduplicated).
    pub fn table_speeds(&self) -> Vec<f64> {
        let mut w: Vec<f64> = self
            .supports
            .iter()
            .flat_map(|s| s.support.speeds().iter().copied())
            .collect();
        w.sort_by(f64::total_cmp);
        w.dedup();
        w
    }

    /// The degree of freedom a load at a node acts on: its translation (its twist or axial
    /// displacement in a torsional or axial system).
    pub fn translation(&self, node: usize) -> Option<usize> {
        self.dofs.iter().position(|d| {
            d.node == node
                && matches!(
                    d.kind,
                    DofKind::Translation | DofKind::Twist | DofKind::Axial
                )
        })
    }

    /// Whether its coordinates are real motions along or about the axis (a torsional or axial
    /// system): its poles come in conjugate pairs, one mode each, and a mode with no stiffness
    /// (a free train's rigid turning) is a pole at 0, not a rotor that needs supports.
    pub fn axial_or_torsional(&self) -> bool {
        self.dofs
            .first()
            .is_some_and(|d| matches!(d.kind, DofKind::Twist | DofKind::Axial))
    }
}
