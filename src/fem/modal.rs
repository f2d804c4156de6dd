//! Undamped, nonrotating modes: the basis of the equivalent and nonviscous models.
//!
//! `K phi_i = w_i^2 M phi_i` with `phi^T M phi = I`. For a retained subset `Phi*` the projection
//! back is `Mbar^-1 Phi*^T M = Phi*^T M` (mass-normalised), which is `Phi^-1` when all modes are
//! kept; so one formula serves the full and the reduced mode sets (paper eq. 7 and after).

use crate::linalg::{self, CMat, LinalgError, RMat, Sparse, c64};
use crate::system::{Dof, DofKind, Layout, PlacedSupport, Placement, Realized, RotorSystem};

/// Mass-normalised undamped modes of the nonrotating rotor, lowest first.
#[derive(Debug, Clone)]
pub struct ModalBasis {
    /// Natural frequencies `w_i`, rad/s, ascending.
    pub omega: Vec<f64>,
    /// Modes as columns.
    pub phi: RMat,
}

/// Why a modal basis cannot be built.
#[derive(Debug, Clone, PartialEq)]
pub enum ModalError {
    Linalg(LinalgError),
    /// A mode with (numerically) zero frequency: the rotor is not supported.
    RigidBody {
        mode: usize,
        omega_squared: f64,
    },
}

impl std::fmt::Display for ModalError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Linalg(e) => write!(f, "{e}"),
            Self::RigidBody { mode, .. } => write!(
                f,
                "mode {mode} of the nonrotating system has zero natural frequency: the rotor \
                 needs supports (stiffness) that hold it in place"
            ),
        }
    }
}

impl ModalBasis {
    /// All modes of `(K, M)`, `K` the total stiffness. Supports in the general form count
    /// with the symmetric parts of their coefficients at rest, averaged over the directions:
    /// these are the rotor's own axisymmetric modes, the basis of its rotating damping.
    pub fn of(system: &RotorSystem) -> Result<Self, ModalError> {
        let (k, m) = pencil(system);
        let modes =
            linalg::symmetric_modes(&k.to_dense(), &m.to_dense()).map_err(ModalError::Linalg)?;
        if system.axial_or_torsional() {
            // A free train turns (or slides) as a rigid body: a mode at 0, with no stiffness
            // and so no loss for the damping models to carry.
            let largest = modes.omega_squared.iter().cloned().fold(0.0, f64::max);
            let rigid = |w2: f64| w2 <= 1e-11 * largest;
            return Ok(ModalBasis {
                omega: modes
                    .omega_squared
                    .iter()
                    .map(|&w2| if rigid(w2) { 0.0 } else { w2.sqrt() })
                    .collect(),
                phi: modes.phi,
            });
        }
        supported(&modes.omega_squared)?;
        Ok(ModalBasis {
            omega: modes.omega_squared.iter().map(|w2| w2.sqrt()).collect(),
            phi: modes.phi,
        })
    }

    /// The lowest modes of [`ModalBasis::of`]'s pencil, by shift-invert Lanczos on its sparse
    /// matrices (`linalg::lanczos`), until `enough(w^2 ascending)` holds: a large rotor's basis
    /// at a cost linear in its size. Refused as [`ModalBasis::of`] refuses a rotor not held in
    /// place (`K` not positive definite, or a mode with `w^2` below `1e-11` of the largest
    /// `K_ii / M_ii`, a lower bound of the highest mode's).
    pub fn lowest(
        system: &RotorSystem,
        enough: impl Fn(&[f64]) -> bool,
    ) -> Result<Self, ModalError> {
        let (k, m) = pencil(system);
        let modes = lowest_of(&k, &m, enough)?;
        Ok(ModalBasis {
            omega: modes.omega_squared.iter().map(|w2| w2.sqrt()).collect(),
            phi: modes.phi,
        })
    }

    /// The lowest `count` modes.
    pub fn truncated(&self, count: usize) -> Self {
        let count = count.min(self.omega.len());
        ModalBasis {
            omega: self.omega[..count].to_vec(),
            phi: self.phi.subcols(0, count).to_owned(),
        }
    }

    pub fn len(&self) -> usize {
        self.omega.len()
    }

    pub fn is_empty(&self) -> bool {
        self.omega.is_empty()
    }

    /// Modal projection of a symmetric matrix: `Phi^T A Phi`.
    pub fn project(&self, a: &Sparse) -> RMat {
        a.project(&self.phi)
    }

    /// The lowest `count` modes augmented with their static correction, then made modes of the
    /// subspace again (Rayleigh-Ritz on `(K, M)`).
    ///
    /// Truncating modes neglects how the dropped modes respond to the forces that couple the
    /// kept ones: gyroscopic `G phi_k`, damping `C phi_k` and loss `K'' phi_k`. Well below the
    /// dropped band that response is quasi-static, `K^-1 F`; adding those vectors (their part
    /// outside the kept modes in the M inner product, linearly independent ones only) takes
    /// the compressor example's poles below 6000 rad/s from 1e-4 to 7e-8 relative error with
    /// the same 8 modes. The result is M-orthonormal and K-diagonal, and its lowest modes are
    /// the exact ones (a Ritz pair that is an eigenpair is reproduced).
    pub fn augmented(&self, system: &RotorSystem, count: usize) -> Result<Self, ModalError> {
        self.augmented_with(system, count, &[])
    }

    /// [`ModalBasis::augmented`] with the static responses to unit loads on the `loads` dofs
    /// added too: a force applied there (unbalance, a support's force) is then represented
    /// exactly at zero frequency, not only through the kept modes.
    pub fn augmented_with(
        &self,
        system: &RotorSystem,
        count: usize,
        loads: &[usize],
    ) -> Result<Self, ModalError> {
        self.augment(system, count, loads, false)
    }

    /// [`ModalBasis::augmented_with`] with `K V` formed as a product, for harmonic responses.
    ///
    /// A response on the basis is a Galerkin solve in the span of the vectors actually held,
    /// so its stiffness must be theirs. The tracked `K v` is that of the exact vectors the
    /// computed ones approximate; a static correction that nearly lies in the span of the kept
    /// modes (the soft supports' bounce and rock) keeps only its small remainder, computed to
    /// `eps / remainder`, and the two differ there. On the soft heavily damped cross-coupled
    /// held-out rotor (113 elements) the unbalance response then drifted from the full model's
    /// as the basis grew (1.7e-7 of the largest response at 4 modes, 1.2e-5 at 25, 1e-3 at 40);
    /// formed, 6.7e-9 at 4 modes. Eigenvalue reductions keep the tracked product: the formed
    /// one cancels for low modes (see [`ModalBasis::augmented_with`]'s body).
    pub fn augmented_formed(
        &self,
        system: &RotorSystem,
        count: usize,
        loads: &[usize],
    ) -> Result<Self, ModalError> {
        self.augment(system, count, loads, true)
    }

    fn augment(
        &self,
        system: &RotorSystem,
        count: usize,
        loads: &[usize],
        formed: bool,
    ) -> Result<Self, ModalError> {
        let kept = self.truncated(count);
        let n = system.n();
        let (k, m) = pencil(system);
        let dense = n <= linalg::sparse::DENSE_UP_TO;
        let m_dense = dense.then(|| m.to_dense());
        let m_times = |x: &RMat| match &m_dense {
            Some(d) => d * x,
            None => m.mul(x),
        };
        let couplings: Vec<&Sparse> = [
            &system.gyroscopic,
            &system.damping_rotating,
            &system.damping_nonrotating,
            &system.hysteretic_rotating,
            &system.hysteretic_nonrotating,
            &system.circulatory,
        ]
        .into_iter()
        .filter(|a| !a.is_zero())
        .collect();
        let coupled = couplings.len() * kept.len();
        let mut f = RMat::zeros(n, coupled + loads.len());
        for (b, a) in couplings.iter().enumerate() {
            let block = a.times(&kept.phi);
            for j in 0..kept.len() {
                for i in 0..n {
                    f[(i, b * kept.len() + j)] = block[(i, j)];
                }
            }
        }
        for (j, &d) in loads.iter().enumerate() {
            f[(d, coupled + j)] = 1.0;
        }
        let x = k.solve_symmetric(&f).map_err(ModalError::Linalg)?;
        // K v is tracked beside every basis vector v, never formed as K times v: for a low mode
        // of a stiff shaft that product cancels to eps * w_max^2 / w^2 relative (5e-6 on the
        // unreduced compressor), while K phi = w^2 M phi and K (K^-1 f) = f are exact.
        let kept_k = m_times(&kept.phi);
        let kept_kphi = RMat::from_fn(n, kept.len(), |i, j| {
            kept.omega[j] * kept.omega[j] * kept_k[(i, j)]
        });
        let (v, kv) = linalg::m_orthonormal_extend(m_times, &kept.phi, &kept_kphi, &x, &f);
        let kv = if formed { k.times(&v) } else { kv };
        let kr = v.transpose() * &kv;
        let kr = RMat::from_fn(kr.nrows(), kr.ncols(), |i, j| {
            0.5 * (kr[(i, j)] + kr[(j, i)])
        });
        let mr = match &m_dense {
            Some(d) => v.transpose() * d * &v,
            None => v.transpose() * m.mul(&v),
        };
        let ritz = linalg::symmetric_modes(&kr, &mr).map_err(ModalError::Linalg)?;
        Ok(ModalBasis {
            omega: ritz
                .omega_squared
                .iter()
                .map(|w2| w2.max(0.0).sqrt())
                .collect(),
            phi: &v * &ritz.phi,
        })
    }
}

/// `sqrt(max K_ii / M_ii)` of [`pencil`], rad/s: a lower bound of the highest natural
/// frequency, the scale of the round-off an eigensolver leaves on a pole at 0 (about
/// `sqrt(eps)` times the highest frequency).
pub fn frequency_scale(system: &RotorSystem) -> f64 {
    let (k, m) = pencil(system);
    (0..system.n())
        .filter(|&i| m.get(i, i) > 0.0)
        .map(|i| k.get(i, i) / m.get(i, i))
        .fold(0.0, f64::max)
        .sqrt()
}

/// A rigid-body mode has `w^2 ~ 0` relative to the largest; equivalent and nonviscous damping
/// divide by `w`, so it is refused here rather than turned into infinities.
fn supported(omega_squared: &[f64]) -> Result<(), ModalError> {
    supported_below(
        omega_squared,
        omega_squared.iter().cloned().fold(0.0, f64::max),
    )
}

/// [`supported`] against `largest`, the highest `w^2` or a lower bound of it.
fn supported_below(omega_squared: &[f64], largest: f64) -> Result<(), ModalError> {
    for (i, &w2) in omega_squared.iter().enumerate() {
        if w2 <= 1e-11 * largest || w2 <= 0.0 {
            return Err(ModalError::RigidBody {
                mode: i + 1,
                omega_squared: w2,
            });
        }
    }
    Ok(())
}

/// `T^H A T` for a Hermitian `A` on the doubled coordinates `(r, conj r)` of real coordinates
/// `(x, y)`, `r = x + i y` (`T = [[I, i I], [I, -i I]]`): real symmetric, since `A` is the form
/// of a real operator (the imaginary parts left are round-off).
fn real_form(a: &CMat) -> RMat {
    let n = a.nrows() / 2;
    let i = c64::new(0.0, 1.0);
    // Column c of T holds two entries, at rows c % n and n + c % n: 1 and 1 (x), i and -i (y).
    let t = |upper: bool, c: usize| -> c64 {
        match (c >= n, upper) {
            (false, _) => c64::new(1.0, 0.0),
            (true, true) => i,
            (true, false) => -i,
        }
    };
    // (A T)(r, c).
    let at = |r: usize, c: usize| -> c64 {
        let j = c % n;
        a[(r, j)] * t(true, c) + a[(r, n + j)] * t(false, c)
    };
    RMat::from_fn(2 * n, 2 * n, |r, c| {
        let j = r % n;
        (t(true, r).conj() * at(j, c) + t(false, r).conj() * at(n + j, c)).re
    })
}

/// Mass-normalised undamped modes in doubled coordinates: the real x/y modes of a rotor on
/// supports that are not isotropic, as vectors `(a, conj a)` of `(r, conj r)`
/// (`phi^H M phi = I`), lowest first. The basis of the nonrotating damping there.
#[derive(Debug, Clone)]
pub struct HermitianBasis {
    pub omega: Vec<f64>,
    pub phi: CMat,
}

impl HermitianBasis {
    pub fn of(system: &RotorSystem) -> Result<Self, ModalError> {
        let (k, m) = Realized::undamped(system, Layout::Doubled);
        let modes = linalg::hermitian_modes(&k, &m).map_err(ModalError::Linalg)?;
        supported(&modes.omega_squared)?;
        Ok(HermitianBasis {
            omega: modes.omega_squared.iter().map(|w2| w2.sqrt()).collect(),
            phi: modes.phi,
        })
    }

    /// The natural frequencies alone, ascending, refused as [`HermitianBasis::of`] refuses
    /// them: from the same pencil in the real coordinates `(x, y)`, `r = x + i y`, where it
    /// is real symmetric, without the modes (on a 456-coordinate rotor 8 ms instead of 92).
    pub fn frequencies(system: &RotorSystem) -> Result<Vec<f64>, ModalError> {
        let (k, m) = Realized::undamped(system, Layout::Doubled);
        let (k, m) = (real_form(&k), real_form(&m));
        let w2 = linalg::symmetric_eigenvalues(&k, &m).map_err(ModalError::Linalg)?;
        supported(&w2)?;
        Ok(w2.iter().map(|w2| w2.sqrt()).collect())
    }

    /// The lowest modes of [`HermitianBasis::of`]'s pencil until `enough(w^2 ascending)`
    /// holds, by shift-invert Lanczos on its real form in `(x, y)` (sparse, built from the
    /// rotor's bands and the supports' symmetric coefficients at rest as
    /// [`Realized::undamped`] adds them): a large rotor's x/y modes at a cost linear in its
    /// size. Each real mode `psi = (x, y)` is `phi = T psi = (x + i y, x - i y)`, so that
    /// `phi^H M phi = psi^T (T^H M T) psi = 1`.
    pub fn lowest(
        system: &RotorSystem,
        enough: impl Fn(&[f64]) -> bool,
    ) -> Result<Self, ModalError> {
        let (k, m) = real_pencil(system);
        let modes = lowest_of(&k, &m, enough)?;
        let n = system.n();
        let psi = &modes.phi;
        Ok(HermitianBasis {
            omega: modes.omega_squared.iter().map(|w2| w2.sqrt()).collect(),
            phi: CMat::from_fn(2 * n, psi.ncols(), |r, c| {
                let (x, y) = (psi[(r % n, c)], psi[(n + r % n, c)]);
                c64::new(x, if r < n { y } else { -y })
            }),
        })
    }

    /// The lowest `count` modes.
    pub fn truncated(&self, count: usize) -> Self {
        let count = count.min(self.omega.len());
        HermitianBasis {
            omega: self.omega[..count].to_vec(),
            phi: self.phi.subcols(0, count).to_owned(),
        }
    }
}

/// The lowest modes of the sparse pencil `(k, m)` by Lanczos, refused as a rotor not held in
/// place (`K` not positive definite, or a mode with `w^2` below `1e-11` of the largest
/// `K_ii / M_ii`, a lower bound of the highest mode's).
fn lowest_of(
    k: &Sparse,
    m: &Sparse,
    enough: impl Fn(&[f64]) -> bool,
) -> Result<linalg::SymmetricModes, ModalError> {
    let modes = linalg::lanczos::lowest_modes(k, m, enough).map_err(|e| match e {
        LinalgError::NotPositiveDefinite => ModalError::RigidBody {
            mode: 1,
            omega_squared: 0.0,
        },
        e => ModalError::Linalg(e),
    })?;
    let largest = (0..k.nrows())
        .map(|i| k.get(i, i) / m.get(i, i))
        .filter(|r| r.is_finite())
        .fold(0.0, f64::max);
    supported_below(&modes.omega_squared, largest)?;
    Ok(modes)
}

/// `(T^H K T, T^H M T)` of the undamped nonrotating rotor in doubled coordinates (what
/// [`real_form`] makes of [`Realized::undamped`]), sparse: each entry `a` at `(i, j)` of the
/// doubled matrix adds `conj(T_ip) a T_jq` at the four `(p, q)` of its real coordinates.
fn real_pencil(system: &RotorSystem) -> (Sparse, Sparse) {
    let n = system.n();
    let i1 = c64::new(0.0, 1.0);
    // T's entry at row `i` (block `i / n`) of column `c` (x below n, y from n).
    let t = |i: usize, c: usize| match (c >= n, i >= n) {
        (false, _) => c64::new(1.0, 0.0),
        (true, false) => i1,
        (true, true) => -i1,
    };
    let real = |entries: &[(usize, usize, c64)]| {
        let mut out = Vec::with_capacity(4 * entries.len());
        for &(i, j, a) in entries {
            for p in [i % n, n + i % n] {
                for q in [j % n, n + j % n] {
                    out.push((p, q, (t(i, p).conj() * a * t(j, q)).re));
                }
            }
        }
        Sparse::from_triplets(2 * n, 2 * n, &out)
    };
    let (k, m) = undamped_doubled(system);
    (real(&k), real(&m))
}

/// The doubled undamped pencil's entries: the rotor's matrices on both diagonal blocks (its
/// circulatory part `+i` on `r`, `-i` on `conj r`) and each support's symmetric coefficients at
/// rest as [`crate::system::point_action`] places them.
#[allow(clippy::type_complexity)]
pub fn undamped_doubled(
    system: &RotorSystem,
) -> (Vec<(usize, usize, c64)>, Vec<(usize, usize, c64)>) {
    let n = system.n();
    let (mut k, mut m) = (vec![], vec![]);
    let blocks = |out: &mut Vec<(usize, usize, c64)>, a: &Sparse, f: c64| {
        for (i, j, v) in a.entries() {
            out.push((i, j, f * v));
            out.push((n + i, n + j, f.conj() * v));
        }
    };
    blocks(&mut k, &system.stiffness(), c64::new(1.0, 0.0));
    blocks(&mut k, &system.circulatory, c64::new(0.0, 1.0));
    blocks(&mut m, &system.mass, c64::new(1.0, 0.0));
    for p in &system.supports {
        let c = p.support.at_rest();
        let w = p.at.weights();
        for (out, a) in [(&mut k, c.k.symmetric()), (&mut m, c.m.symmetric())] {
            let act = crate::system::point_action(&a, Layout::Doubled);
            for &(i, wi) in &w {
                for &(j, wj) in &w {
                    for b in 0..2 {
                        for d in 0..2 {
                            out.push((i + b * n, j + d * n, act[(b, d)] * (wi * wj)));
                        }
                    }
                }
            }
        }
    }
    (k, m)
}

/// `(K, M)` of the rotor's axisymmetric modes: supports in the general form count with the
/// symmetric parts of their coefficients at rest, averaged over the directions.
pub fn pencil(system: &RotorSystem) -> (Sparse, Sparse) {
    if system.supports.is_empty() {
        (system.stiffness(), system.mass.clone())
    } else {
        let (ks, ms) = system.supports_at_rest();
        (
            system.stiffness().plus(&ks, 1.0),
            system.mass.plus(&ms, 1.0),
        )
    }
}

impl ModalBasis {
    /// The rotor in the coordinates of these modes, `q = Phi eta`: every matrix becomes
    /// `Phi^T A Phi` (so the mass is the identity). A Rayleigh-Ritz reduction: exact with all
    /// modes, and for a truncated set the low poles converge as the retained band widens
    /// (`analysis::reduction` measures how well).
    ///
    /// The total stiffness is `diag(w^2)` by construction; it is set so rather than projected,
    /// which would cancel (see [`ModalBasis::augmented`]). The supports' part is projected
    /// (it is local and does not cancel) and the shaft's is the difference.
    ///
    /// Supports in the general form stay general, on the rows of `Phi` at their translations
    /// ([`Placement::Shape`]); the modes are those of the rotor with their averaged
    /// stiffness and mass at rest ([`ModalBasis::of`]), which the reduced matrices leave out
    /// so that the supports count once.
    pub fn reduce(&self, system: &RotorSystem) -> RotorSystem {
        let nonrotating = self.project(&system.stiffness_nonrotating);
        let m = self.len();
        let averaged = (!system.supports.is_empty()).then(|| {
            let (k, _) = system.supports_at_rest();
            self.project(&k)
        });
        let s = |a: &Sparse| Sparse::from_dense(&self.project(a));
        RotorSystem {
            mass: s(&system.mass),
            gyroscopic: s(&system.gyroscopic),
            stiffness_rotating: Sparse::from_dense(&RMat::from_fn(m, m, |i, j| {
                let total = if i == j {
                    self.omega[i] * self.omega[i]
                } else {
                    0.0
                };
                let supports = averaged.as_ref().map_or(0.0, |a| a[(i, j)]);
                total - supports - nonrotating[(i, j)]
            })),
            stiffness_nonrotating: Sparse::from_dense(&nonrotating),
            damping_rotating: s(&system.damping_rotating),
            damping_nonrotating: s(&system.damping_nonrotating),
            hysteretic_rotating: s(&system.hysteretic_rotating),
            hysteretic_nonrotating: s(&system.hysteretic_nonrotating),
            circulatory: s(&system.circulatory),
            dofs: (0..self.len())
                .map(|node| Dof {
                    node,
                    kind: DofKind::Mode,
                })
                .collect(),
            supports: system
                .supports
                .iter()
                .map(|p| PlacedSupport {
                    at: Placement::Shape(self.shape_of(&p.at)),
                    support: p.support.clone(),
                })
                .collect(),
        }
    }

    /// `Phi^T w`: a combination of the coordinates in modal ones.
    fn shape_of(&self, at: &Placement) -> Vec<f64> {
        let w = at.weights();
        (0..self.len())
            .map(|k| w.iter().map(|&(i, a)| a * self.phi[(i, k)]).sum())
            .collect()
    }

    /// `M Phi`: its columns map physical coordinates to modal ones (`eta = (M Phi)^T q`).
    pub fn participation(&self, mass: &Sparse) -> RMat {
        mass.times(&self.phi)
    }
}
