//! Damping models: each turns a [`RotorSystem`] with hysteretic (imaginary) stiffness into
//! first-order systems `z' = A(Omega) z` that the analyses solve.
//!
//! - `viscous`: the loss factors are dropped.
//! - `hysteretic` (H, MODEL.md section 2): four linear problems, one per sign pair `(a, b)` of
//!   `K + i a K''_n + i b K''_r`; a root is a pole only where `sgn(omega) = a` and
//!   `sgn(omega - Omega) = b`. Frequency domain only.
//! - `equivalent` (E, section 3): each mode's loss stiffness over its natural frequency, as a
//!   viscous damping matrix, rotating (with its circulatory term) and nonrotating apart.
//! - `nonviscous` (NVD, section 4): Maxwell branches on massless internal coordinates.
//!
//! Every `A(Omega) = A0 + Omega A1` is affine in the spin speed, so a sweep assembles once.
//! With supports tabulated against speed, the models are built at the table's speeds and the
//! state matrix is linear between them (`StateModel`). The modal bases are those of the
//! nonrotating rotor, at rest.

pub mod branches;
pub mod dampers;
pub mod equivalent;
pub mod harmonic;
pub mod hysteretic;
pub mod large;
pub mod nonviscous;
pub mod report;
pub mod schedule;
pub mod state;
pub mod whirl_fit;

use crate::fem::modal::{HermitianBasis, ModalBasis, ModalError};
use crate::linalg::{CMat, LinalgError, RMat, Sparse};
use crate::model::damping::DampingModel;
use crate::system::{Layout, Realized, RotorSystem};
pub use schedule::Schedule;
pub use state::{Branches, SecondOrder, StateModel};
use std::sync::Arc;

/// A rotor under one damping model, ready for eigenvalue analyses.
#[derive(Debug, Clone)]
pub struct DampedModel {
    pub kind: ModelKind,
    /// Undamped nonrotating modes of the rotor (all of them, axisymmetric: supports averaged
    /// over directions): the basis a modal reduction starts from.
    pub basis: ModalBasis,
    /// The coordinates: `r`, or `(r, conj r)`.
    pub layout: Layout,
    /// Natural frequencies of the undamped nonrotating rotor, rad/s, ascending: one per
    /// degenerate pair in the coordinates `r`; each x/y mode when doubled.
    pub natural_frequencies: Vec<f64>,
}

/// The linear problem(s) a damping model poses.
#[derive(Debug, Clone)]
pub enum ModelKind {
    /// Viscous, equivalent and nonviscous models: one linear system.
    Linear(Box<StateModel>),
    /// The hysteretic model: one linear system per sign pattern, roots filtered by consistency.
    Hysteretic(Vec<hysteretic::SignedModel>),
}

/// The modal bases the equivalent and nonviscous models are built on (truncated to the modes
/// they retain).
#[derive(Debug, Clone)]
pub struct Bases {
    /// The rotor's axisymmetric modes (its rotating dampers; every damper in the coordinates
    /// `r`), real, and the mass they are normalised with.
    pub axis: ModalBasis,
    pub axis_mass: Sparse,
    /// Doubled coordinates: the real x/y modes (the nonrotating dampers) and their mass.
    pub xy: Option<(HermitianBasis, CMat)>,
}

/// Why a damping model cannot be built for a rotor.
#[derive(Debug, Clone, PartialEq)]
pub enum DampingError {
    Modal(ModalError),
    Linalg(LinalgError),
    /// A model that cannot be solved the way it was asked for (the message says why).
    Unsolvable(String),
}

impl std::fmt::Display for DampingError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Modal(e) => write!(f, "{e}"),
            Self::Linalg(e) => write!(f, "{e}"),
            Self::Unsolvable(m) => write!(f, "{m}"),
        }
    }
}

impl From<ModalError> for DampingError {
    fn from(e: ModalError) -> Self {
        Self::Modal(e)
    }
}

impl From<LinalgError> for DampingError {
    fn from(e: LinalgError) -> Self {
        Self::Linalg(e)
    }
}

impl Bases {
    /// The bases of `system` from all its modes, truncated to `modes` (axisymmetric modes;
    /// each is a pair of x/y modes).
    pub fn new(
        system: &RotorSystem,
        all: &ModalBasis,
        xy_all: Option<&HermitianBasis>,
        modes: Option<usize>,
    ) -> Self {
        let axis_mass = if system.supports.is_empty() {
            system.mass.clone()
        } else {
            let (_, m) = Realized::undamped(system, Layout::Single);
            Sparse::from_dense(&RMat::from_fn(m.nrows(), m.ncols(), |i, j| m[(i, j)].re))
        };
        Bases {
            axis: modes.map_or_else(|| all.clone(), |k| all.truncated(k)),
            axis_mass,
            xy: xy_all.map(|b| {
                let b = modes.map_or_else(|| b.clone(), |k| b.truncated(2 * k));
                (b, Realized::undamped(system, Layout::Doubled).1)
            }),
        }
    }

    /// Every basis of `system`, truncated to `modes`.
    pub fn of(system: &RotorSystem, modes: Option<usize>) -> Result<Self, DampingError> {
        let all = ModalBasis::of(system)?;
        let xy = match system.layout() {
            Layout::Doubled => Some(HermitianBasis::of(system)?),
            Layout::Single => None,
        };
        Ok(Self::new(system, &all, xy.as_ref(), modes))
    }

    /// The dampers' tuning and loss stiffness, nonrotating on `omega_n` and rotating on the
    /// axisymmetric modes, for a realization's loss: `(mode, w0, loss, rotating)`.
    pub fn dampers(&self, r: &Realized, rotor_loss: &Sparse) -> Vec<(usize, f64, f64, bool)> {
        let mut out = vec![];
        let loss_r = self.axis.project(rotor_loss);
        let (omega_n, phi_n) = match &self.xy {
            None => (&self.axis.omega, crate::linalg::to_complex(&self.axis.phi)),
            Some((b, _)) => (&b.omega, b.phi.clone()),
        };
        let kp = &r.loss_nonrotating * &phi_n;
        for (i, &w) in omega_n.iter().enumerate() {
            let l: f64 = (0..phi_n.nrows())
                .map(|k| (phi_n[(k, i)].conj() * kp[(k, i)]).re)
                .sum();
            if l > 0.0 && w > 0.0 {
                out.push((i, w, l, false));
            }
        }
        for (i, &w) in self.axis.omega.iter().enumerate() {
            if loss_r[(i, i)] > 0.0 && w > 0.0 {
                out.push((i, w, loss_r[(i, i)], true));
            }
        }
        out
    }
}

impl DampedModel {
    /// Builds the model. The modal basis is computed once, here: it proves the rotor is held
    /// (no rigid-body mode) for every model, and it is the basis of the equivalent and
    /// nonviscous models.
    pub fn build(system: &RotorSystem, model: &DampingModel) -> Result<Self, DampingError> {
        Self::build_with(system, model, None)
    }

    /// The reduction `phi` (`system`, from [`ModalBasis::reduce`]) of a rotor held sparse
    /// (`full`) under its equivalent or nonviscous `dampers`, projected on `phi`
    /// ([`dampers::ModalDampers::projected`]) rather than rebuilt on the reduced rotor's modes.
    pub fn projected(
        system: &RotorSystem,
        full: &RotorSystem,
        model: &DampingModel,
        dampers: &dampers::ModalDampers,
        phi: &RMat,
    ) -> Result<Self, DampingError> {
        Self::with_projection(system, model, &Self::projection(system, full, dampers, phi))
    }

    /// The projection [`DampedModel::projected`] builds `system` with, computed once for the
    /// systems that differ from it only by supports without loss or symmetric stiffness (API
    /// 617's cross-coupling, Level I): their dampers are the same.
    pub fn projection(
        system: &RotorSystem,
        full: &RotorSystem,
        dampers: &dampers::ModalDampers,
        phi: &RMat,
    ) -> dampers::Projected {
        dampers.projected(full, phi, &realization_speeds(system))
    }

    /// [`DampedModel::projected`] from its [`DampedModel::projection`].
    pub fn with_projection(
        system: &RotorSystem,
        model: &DampingModel,
        given: &dampers::Projected,
    ) -> Result<Self, DampingError> {
        Self::build_with(system, model, Some(given))
    }

    fn build_with(
        system: &RotorSystem,
        model: &DampingModel,
        given: Option<&dampers::Projected>,
    ) -> Result<Self, DampingError> {
        let layout = system.layout();
        // The viscous and hysteretic models need no modal basis: built beside it, on two
        // cores (on the unreduced compressor the basis took 6.6 ms of a 28 ms build).
        let needs_basis = given.is_none() && model.on_modes();
        // The x/y modes only where a model is built on them; their frequencies otherwise.
        let modal = || -> Result<_, DampingError> {
            let all = ModalBasis::of(system)?;
            let xy_all = match layout {
                Layout::Doubled if needs_basis => Some(HermitianBasis::of(system)?),
                _ => None,
            };
            let natural_frequencies = match (&xy_all, layout) {
                (Some(b), _) => b.omega.clone(),
                (None, Layout::Doubled) => HermitianBasis::frequencies(system)?,
                (None, Layout::Single) => all.omega.clone(),
            };
            Ok((all, xy_all, natural_frequencies))
        };
        // One realization per speed of the supports' tables (one in all when constant), or,
        // with supports on ROSS's curves, one scheduled (`schedule.rs`).
        let scheduled = Schedule::applies(system);
        let points = realization_speeds(system);
        let tabulate = |models: Vec<StateModel>| -> StateModel {
            if models.len() == 1 {
                models.into_iter().next().expect("one")
            } else {
                StateModel::table(&points, models)
            }
        };
        // The state model; `bases` only for the models built on the modal basis.
        let kind = |bases: Option<&Bases>| -> Result<ModelKind, DampingError> {
            let realized: Vec<Realized> = points.iter().map(|&w| Realized::at(system, w)).collect();
            let size = realized[0].size();
            let schedule = match scheduled {
                true => Some(Arc::new(Schedule::new(system, &realized[0], points[0])?)),
                false => None,
            };
            let on_schedule = |m: StateModel| match &schedule {
                Some(s) => m.scheduled(s.clone()),
                None => m,
            };
            let bases = || bases.expect("the equivalent and nonviscous models have a basis");
            // Constant coefficients keep the second-order matrices for harmonic solves. The
            // supports' own branches (a table over whirl frequency, fitted) join the model's.
            let state = |r: &Realized, so: &SecondOrder, br: &Branches| {
                let br = br.with_supports(&r.branches);
                match scheduled || points.len() > 1 {
                    true => StateModel::new(so, &br),
                    false => StateModel::harmonic(so, &br),
                }
            };
            let linear = |models: Result<Vec<StateModel>, _>| -> Result<ModelKind, DampingError> {
                Ok(ModelKind::Linear(Box::new(on_schedule(tabulate(models?)))))
            };
            match model {
                DampingModel::Viscous => linear(
                    realized
                        .iter()
                        .map(|r| state(r, &SecondOrder::viscous(r), &Branches::none(size)))
                        .collect(),
                ),
                DampingModel::Hysteretic if !realized[0].branches.is_empty() => {
                    Err(DampingError::Unsolvable(
                        "the hysteretic model is defined for harmonic motion only: a support's \
                         table over whirl frequency is read as it stands there, not fitted"
                            .into(),
                    ))
                }
                DampingModel::Hysteretic => {
                    let per_point: Vec<Vec<hysteretic::SignedModel>> = realized
                        .iter()
                        .map(hysteretic::signed_models)
                        .collect::<Result<_, _>>()?;
                    let out = (0..per_point[0].len())
                        .map(|k| {
                            let first = &per_point[0][k];
                            hysteretic::SignedModel {
                                nonrotating: first.nonrotating,
                                rotating: first.rotating,
                                counter: first.counter,
                                model: on_schedule(tabulate(
                                    per_point.iter().map(|p| p[k].model.clone()).collect(),
                                )),
                            }
                        })
                        .collect();
                    Ok(ModelKind::Hysteretic(out))
                }
                DampingModel::Equivalent { .. } | DampingModel::Nonviscous(_)
                    if given.is_some() =>
                {
                    let given = given.expect("given");
                    linear(
                        realized
                            .iter()
                            .zip(&given.per_point)
                            .map(|(r, d)| match d {
                                dampers::Damping::Equivalent {
                                    rotating,
                                    nonrotating,
                                } => state(
                                    r,
                                    &SecondOrder::with_damping(
                                        r,
                                        &(&r.damping_nonrotating + nonrotating),
                                        &(&r.damping_rotating + rotating),
                                    ),
                                    &Branches::none(size),
                                ),
                                dampers::Damping::Branches(b) => {
                                    state(r, &SecondOrder::viscous(r), b)
                                }
                            })
                            .collect(),
                    )
                }
                DampingModel::Equivalent { .. } => linear(
                    realized
                        .iter()
                        .map(|r| {
                            let so =
                                equivalent::second_order(r, &system.hysteretic_rotating, bases());
                            state(r, &so, &Branches::none(size))
                        })
                        .collect(),
                ),
                DampingModel::Nonviscous(spec) => {
                    let refs: Vec<&Realized> = realized.iter().collect();
                    let branches =
                        nonviscous::branches(&refs, &system.hysteretic_rotating, bases(), spec);
                    linear(
                        realized
                            .iter()
                            .zip(&branches)
                            .map(|(r, br)| state(r, &SecondOrder::viscous(r), br))
                            .collect(),
                    )
                }
            }
        };
        let (bases_of, early) = rayon::join(modal, || (!needs_basis).then(|| kind(None)));
        let (all, xy_all, natural_frequencies) = bases_of?;
        let kind = match early {
            Some(k) => k?,
            None => {
                let modes = match model {
                    DampingModel::Equivalent { modes } => *modes,
                    DampingModel::Nonviscous(spec) => spec.modes,
                    _ => None,
                };
                kind(Some(&Bases::new(system, &all, xy_all.as_ref(), modes)))?
            }
        };
        Ok(DampedModel {
            kind,
            basis: all,
            layout,
            natural_frequencies,
        })
    }

    /// Complex degrees of freedom of the state's coordinates (`2n` when doubled), not
    /// counting internal coordinates.
    pub fn dofs(&self) -> usize {
        match &self.kind {
            ModelKind::Linear(m) => m.n(),
            ModelKind::Hysteretic(v) => v[0].model.n(),
        }
    }

    /// Complex degrees of freedom of the rotor (`n`, also when doubled).
    pub fn rotor_dofs(&self) -> usize {
        match self.layout {
            Layout::Single => self.dofs(),
            Layout::Doubled => self.dofs() / 2,
        }
    }

    /// Size of each first-order eigenproblem.
    pub fn states(&self) -> usize {
        match &self.kind {
            ModelKind::Linear(m) => m.size(),
            ModelKind::Hysteretic(v) => v[0].model.size(),
        }
    }
}

/// The speeds a model is realized at: the scheduled model's reference speed (supports on ROSS's
/// curves), else the supports' table speeds, else rest.
fn realization_speeds(system: &RotorSystem) -> Vec<f64> {
    let table = system.table_speeds();
    if Schedule::applies(system) {
        vec![Schedule::reference_speed(system)]
    } else if table.is_empty() {
        vec![0.0]
    } else {
        table
    }
}
