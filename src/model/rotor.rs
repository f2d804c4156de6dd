//! Validated rotors. A value of these types exists only if it is physically valid.

use super::api::{MatricesInput, Motion, RotorInput};
pub use super::beam::{BeamRotor, Disk};
pub use super::coupling::Coupling;
use super::error::Invalid;
pub use super::gear::Gear;
pub use super::point_masses::PointMass;
pub use super::shaft::{Element, Rayleigh, ShaftElement, Sleeve};
use super::supports::GeneralSupport;
pub use super::supports::{Support, parse_supports, support_path};
pub use super::train::TrainRotor;
use crate::linalg::{self, RMat};

pub use super::jeffcott::Jeffcott;
pub use super::limits::Limits;

/// A valid rotor.
#[derive(Debug, Clone)]
pub enum Rotor {
    Jeffcott(Jeffcott),
    Beam(BeamRotor),
    Matrices(Box<MatrixRotor>),
    /// A beam rotor in torsion or axially.
    Train(Box<TrainRotor>),
}

impl Rotor {
    /// Validates the `rotor` field of a request; paths are prefixed with `rotor.`.
    pub fn parse(input: &RotorInput, limits: &Limits) -> Result<Self, Invalid> {
        Self::parse_motion(input, Motion::Lateral, limits)
    }

    /// [`Rotor::parse`] for the motion an analysis solves: a torsional or axial one needs a
    /// beam rotor; a lateral one refuses gear meshes (they have no lateral model).
    pub fn parse_motion(
        input: &RotorInput,
        motion: Motion,
        limits: &Limits,
    ) -> Result<Self, Invalid> {
        if !motion.is_lateral() {
            return match input {
                RotorInput::Beam(b) => {
                    TrainRotor::parse(b, motion, limits).map(|t| Rotor::Train(Box::new(t)))
                }
                _ => Err(Invalid::one(
                    "motion",
                    "torsional and axial motion need a beam rotor (`type: beam`): a Jeffcott \
                     rotor or a rotor given as matrices has lateral coordinates only",
                )),
            };
        }
        match input {
            RotorInput::Jeffcott(j) => Jeffcott::parse(j, "rotor").map(Rotor::Jeffcott),
            RotorInput::Beam(b) => {
                let rotor = BeamRotor::parse(b, limits)?;
                let gears: Vec<usize> = b
                    .shaft
                    .iter()
                    .enumerate()
                    .filter(|(_, s)| s.gear.is_some())
                    .map(|(i, _)| i)
                    .collect();
                if let Some(i) = gears.first() {
                    return Err(Invalid::one(
                        format!("rotor.shaft[{i}].gear"),
                        "a gear mesh joins shafts turning at different speeds, which the \
                         lateral analyses do not model: ask for `motion: torsional` or `axial`, \
                         or analyse each shaft laterally on its own",
                    ));
                }
                Ok(Rotor::Beam(rotor))
            }
            RotorInput::Matrices(m) => {
                MatrixRotor::parse(m, limits).map(|m| Rotor::Matrices(Box::new(m)))
            }
        }
    }

    /// The motion its coordinates describe.
    pub fn motion(&self) -> Motion {
        match self {
            Rotor::Train(t) => t.motion,
            _ => Motion::Lateral,
        }
    }

    /// Whether this is the paper's nondimensional Jeffcott rotor (mass = stiffness = 1).
    pub fn nondimensional(&self) -> bool {
        matches!(self, Rotor::Jeffcott(j) if j.is_nondimensional())
    }

    /// Number of nodes (each with a translation).
    pub fn node_count(&self) -> usize {
        match self {
            Rotor::Jeffcott(_) => 1,
            Rotor::Beam(b) => b.nodes(),
            Rotor::Matrices(m) => m.mass.nrows(),
            Rotor::Train(t) => t.nodes(),
        }
    }

    /// Supports in the general form.
    pub fn general_supports(&self) -> &[GeneralSupport] {
        match self {
            Rotor::Jeffcott(_) => &[],
            Rotor::Beam(b) => b.general_supports(),
            Rotor::Matrices(m) => &m.general_supports,
            Rotor::Train(t) => &t.axial_supports,
        }
    }

    /// Whether the equations couple `r` to its conjugate (a support not isotropic): the
    /// doubled coordinates `(r, conj r)` are then solved.
    pub fn doubled(&self) -> bool {
        self.general_supports().iter().any(|s| !s.isotropic())
    }

    /// Complex degrees of freedom as assembled, before any reduction.
    pub fn assembled_dofs(&self) -> usize {
        match self {
            Rotor::Jeffcott(_) => 1,
            Rotor::Beam(b) => b.assembled_dofs(),
            Rotor::Matrices(m) => m.mass.nrows(),
            Rotor::Train(t) => t.nodes(),
        }
    }

    /// Whether the rotor has rotating and nonrotating hysteretic loss: which sides get
    /// nonviscous branches.
    pub fn loss_sides(&self) -> (bool, bool) {
        match self {
            Rotor::Jeffcott(j) => (
                j.loss_factor_rotating() > 0.0,
                j.loss_factor_nonrotating() > 0.0,
            ),
            Rotor::Beam(b) => (
                b.elements().iter().any(|e| e.loss_factor() > 0.0)
                    || b.sleeves().iter().any(|s| s.element.loss_factor > 0.0),
                b.supports()
                    .iter()
                    .any(|s| s.loss_factor > 0.0 && s.stiffness > 0.0),
            ),
            Rotor::Matrices(m) => {
                let nonzero =
                    |a: &RMat| (0..a.ncols()).any(|j| (0..a.nrows()).any(|i| a[(i, j)] != 0.0));
                (
                    nonzero(&m.hysteretic_rotating),
                    nonzero(&m.hysteretic_nonrotating),
                )
            }
            Rotor::Train(t) => (false, t.has_loss()),
        }
    }

    /// Complex degrees of freedom of the assembled (and reduced) system.
    pub fn dof_count(&self) -> usize {
        match self {
            Rotor::Jeffcott(_) => 1,
            Rotor::Beam(b) => {
                if b.guyan().is_some() {
                    b.nodes()
                } else {
                    b.assembled_dofs()
                }
            }
            Rotor::Matrices(m) => m.mass.nrows(),
            Rotor::Train(t) => t.nodes(),
        }
    }
}

/// A rotor given as matrices: square, one size, symmetric, mass positive definite.
#[derive(Debug, Clone)]
pub struct MatrixRotor {
    pub mass: RMat,
    pub stiffness: RMat,
    pub gyroscopic: RMat,
    pub damping_rotating: RMat,
    pub damping_nonrotating: RMat,
    pub hysteretic_rotating: RMat,
    pub hysteretic_nonrotating: RMat,
    /// Supports in the general form, `node` being a degree of freedom.
    pub general_supports: Vec<GeneralSupport>,
}

impl MatrixRotor {
    pub fn parse(m: &MatricesInput, limits: &Limits) -> Result<Self, Invalid> {
        let mut bad = Invalid::default();
        let n = m.mass.len();
        if n == 0 {
            bad.push("rotor.mass", "must be a non-empty square matrix");
            return Err(bad);
        }
        if n > limits.max_dofs {
            bad.push(
                "rotor.mass",
                format!(
                    "{n} degrees of freedom, more than the limit of {} ({})",
                    limits.max_dofs, limits.dofs_setting
                ),
            );
            return Err(bad);
        }
        let mut matrix = |name: &str, rows: Option<&Vec<Vec<f64>>>| -> Option<RMat> {
            let at = format!("rotor.{name}");
            let Some(rows) = rows else {
                return Some(RMat::zeros(n, n));
            };
            if rows.len() != n || rows.iter().any(|r| r.len() != n) {
                bad.push(at, format!("must be {n} x {n} like `mass`"));
                return None;
            }
            for (i, r) in rows.iter().enumerate() {
                for (j, x) in r.iter().enumerate() {
                    if !x.is_finite() {
                        bad.push(format!("{at}[{i}][{j}]"), "must be a finite number");
                        return None;
                    }
                }
            }
            let a = RMat::from_fn(n, n, |i, j| rows[i][j]);
            let scale = rows.iter().flatten().fold(0.0f64, |s, x| s.max(x.abs()));
            for i in 0..n {
                for j in 0..i {
                    if (a[(i, j)] - a[(j, i)]).abs() > 1e-9 * scale {
                        bad.push(
                            format!("{at}[{i}][{j}]"),
                            format!(
                                "must be symmetric: {} != {} at [{j}][{i}]",
                                a[(i, j)],
                                a[(j, i)]
                            ),
                        );
                        return None;
                    }
                }
            }
            Some(a)
        };
        let mass = matrix("mass", Some(&m.mass));
        let stiffness = matrix("stiffness", Some(&m.stiffness));
        let gyroscopic = matrix("gyroscopic", m.gyroscopic.as_ref());
        let c_r = matrix("damping_rotating", m.damping_rotating.as_ref());
        let c_n = matrix("damping_nonrotating", m.damping_nonrotating.as_ref());
        let h_r = matrix("hysteretic_rotating", m.hysteretic_rotating.as_ref());
        let h_n = matrix("hysteretic_nonrotating", m.hysteretic_nonrotating.as_ref());
        if let Some(mm) = &mass
            && !linalg::is_positive_definite(mm)
        {
            bad.push("rotor.mass", "must be positive definite");
        }
        let dof_ok = |bad: &mut Invalid, at: String, k: i64| -> Option<usize> {
            if k >= 0 && (k as u64) < n as u64 {
                Some(k as usize)
            } else {
                bad.push(
                    at,
                    format!("degree of freedom {k} does not exist (0 to {})", n - 1),
                );
                None
            }
        };
        let (isotropic, general_supports) = parse_supports(&m.supports, false, &mut bad, dof_ok);
        super::supports::check_schedule(&general_supports, &mut bad);
        let mut stiffness = stiffness;
        let mut c_n = c_n;
        let mut h_n = h_n;
        for s in &isotropic {
            if let (Some(k), Some(c), Some(h)) = (&mut stiffness, &mut c_n, &mut h_n) {
                for (m, a) in [
                    (k, s.stiffness),
                    (c, s.damping),
                    (h, s.loss_factor * s.stiffness),
                ] {
                    m[(s.node, s.node)] += a;
                    if let Some(l) = s.link {
                        m[(l, l)] += a;
                        m[(s.node, l)] -= a;
                        m[(l, s.node)] -= a;
                    }
                }
            }
        }
        bad.into_result(|| MatrixRotor {
            mass: mass.unwrap(),
            stiffness: stiffness.unwrap(),
            gyroscopic: gyroscopic.unwrap(),
            damping_rotating: c_r.unwrap(),
            damping_nonrotating: c_n.unwrap(),
            hysteretic_rotating: h_r.unwrap(),
            hysteretic_nonrotating: h_n.unwrap(),
            general_supports,
        })
    }
}
