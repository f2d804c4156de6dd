//! The thin layer over faer: the only module that imports it.
//!
//! Everything the numerics need from dense linear algebra:
//! - the complex eigendecomposition `A V = V diag(s)` of a general (non-Hermitian) matrix;
//! - the symmetric-definite pencil `K phi = w^2 M phi` by Cholesky: with `M = L L^T`,
//!   `L^-1 K L^-T u = w^2 u` and `phi = L^-T u`, so that `phi^T M phi = I` (mass-normalised);
//! - solves with a symmetric positive definite matrix (the mass matrix).
//!
//! faer runs sequentially here (`Par::Seq`, set once at startup): the service parallelises over
//! spin speeds instead, which is faster on few cores than parallelising one small problem.

pub mod arnoldi;
mod general;
mod gram;
pub mod lanczos;
mod lstsq;
mod phi;
pub mod sparse;

pub use general::{Eigen, balance, eigen, eigen_real, eigenvalues};
pub use gram::m_orthonormal_extend;
pub use lstsq::{bounded_least_squares, least_squares};
pub use phi::{phi1, phi2};
pub use sparse::Sparse;

use faer::linalg::solvers::Solve;
use faer::{Par, Side};

pub use faer::c64;

/// Dense real matrix.
pub type RMat = faer::Mat<f64>;
/// Dense complex matrix.
pub type CMat = faer::Mat<c64>;

/// A failure of a decomposition: reported to the caller as an unsolvable model, never a panic.
#[derive(Debug, Clone, PartialEq)]
pub enum LinalgError {
    /// The QR algorithm did not converge.
    NoConvergence,
    /// The matrix that must be positive definite is not.
    NotPositiveDefinite,
    /// A result contains NaN or infinity.
    NonFinite,
}

impl std::fmt::Display for LinalgError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::NoConvergence => write!(f, "the eigenvalue iteration did not converge"),
            Self::NotPositiveDefinite => write!(f, "the mass matrix is not positive definite"),
            Self::NonFinite => write!(f, "the computation produced a non-finite number"),
        }
    }
}

impl std::error::Error for LinalgError {}

/// Makes faer sequential for the whole process (see the module docs).
pub fn set_sequential() {
    faer::set_global_parallelism(Par::Seq);
}

/// Undamped modes of the symmetric pencil `(K, M)`, `M` positive definite.
pub struct SymmetricModes {
    /// Eigenvalues `w^2`, ascending.
    pub omega_squared: Vec<f64>,
    /// Mass-normalised modes as columns: `phi^T M phi = I`, `phi^T K phi = diag(w^2)`.
    pub phi: RMat,
}

/// Eigenvalues (ascending) and orthonormal eigenvectors of a self-adjoint matrix, by the
/// tridiagonal QR algorithm at every size.
///
/// faer switches to divide and conquer from n = 128, which loses the small eigenvalues of a
/// graded matrix: on a 162-element shaft (`L^-1 K L^-T` from 7e4 to 4e12) its lowest `w`
/// was 267.64 rad/s against 266.667 from its own eigenvalues-only path and from LAPACK's
/// `dsygv`. QR (LAPACK's `dsteqr`) keeps them to round-off of the largest.
fn self_adjoint_qr<T: faer::traits::ComplexField>(
    a: &faer::Mat<T>,
) -> Result<(Vec<T>, faer::Mat<T>), LinalgError> {
    let (s, u) = self_adjoint(a, true)?;
    Ok((s, u.expect("asked for")))
}

/// The eigenvalues of a self-adjoint matrix, ascending, and its eigenvectors if `vectors`.
fn self_adjoint<T: faer::traits::ComplexField>(
    a: &faer::Mat<T>,
    vectors: bool,
) -> Result<(Vec<T>, Option<faer::Mat<T>>), LinalgError> {
    use faer::dyn_stack::{MemBuffer, MemStack};
    use faer::linalg::evd::{self, ComputeEigenvectors, SelfAdjointEvdParams};
    let n = a.nrows();
    let par = Par::Seq;
    let params: faer::Spec<SelfAdjointEvdParams, T> = faer::Spec::new(SelfAdjointEvdParams {
        recursion_threshold: usize::MAX,
        ..faer::Auto::<T>::auto()
    });
    let compute = match vectors {
        true => ComputeEigenvectors::Yes,
        false => ComputeEigenvectors::No,
    };
    let mut u = faer::Mat::<T>::zeros(if vectors { n } else { 0 }, if vectors { n } else { 0 });
    let mut s = faer::diag::Diag::<T>::zeros(n);
    let mut buf = MemBuffer::new(evd::self_adjoint_evd_scratch::<T>(n, compute, par, params));
    evd::self_adjoint_evd(
        a.as_ref(),
        s.as_mut(),
        vectors.then(|| u.as_mut()),
        par,
        MemStack::new(&mut buf),
        params,
    )
    .map_err(|_| LinalgError::NoConvergence)?;
    let s = s.column_vector();
    Ok(((0..n).map(|i| s[i].clone()).collect(), vectors.then_some(u)))
}

/// `L` and `A = L^-1 K L^-T` for `M = L L^T`: the pencil `(K, M)` as a symmetric matrix.
fn standard_form(k: &RMat, m: &RMat) -> Result<(RMat, RMat), LinalgError> {
    if !all_finite_r(k) || !all_finite_r(m) {
        return Err(LinalgError::NonFinite);
    }
    let n = k.nrows();
    let llt = m
        .llt(Side::Lower)
        .map_err(|_| LinalgError::NotPositiveDefinite)?;
    let l = llt.L().to_owned();
    // Two triangular solves.
    let mut x = k.clone();
    l.as_ref().solve_lower_triangular_in_place(x.as_mut()); // L^-1 K
    let mut a = x.transpose().to_owned();
    l.as_ref().solve_lower_triangular_in_place(a.as_mut()); // L^-1 (L^-1 K)^T = L^-1 K L^-T
    // Symmetrise against round-off before the symmetric solver.
    let a = RMat::from_fn(n, n, |i, j| 0.5 * (a[(i, j)] + a[(j, i)]));
    Ok((l, a))
}

/// Solves `K phi = w^2 M phi` (see the module docs).
pub fn symmetric_modes(k: &RMat, m: &RMat) -> Result<SymmetricModes, LinalgError> {
    let (l, a) = standard_form(k, m)?;
    let (s, u) = self_adjoint_qr(&a)?;
    let omega_squared: Vec<f64> = s;
    // phi = L^-T u
    let mut phi = u;
    l.as_ref()
        .transpose()
        .solve_upper_triangular_in_place(phi.as_mut());
    if omega_squared.iter().any(|v| !v.is_finite()) || !all_finite_r(&phi) {
        return Err(LinalgError::NonFinite);
    }
    Ok(SymmetricModes { omega_squared, phi })
}

/// The eigenvalues `w^2` of `K phi = w^2 M phi` (real symmetric, `M` positive definite),
/// ascending, without the modes: a quarter of [`symmetric_modes`]'s work.
pub fn symmetric_eigenvalues(k: &RMat, m: &RMat) -> Result<Vec<f64>, LinalgError> {
    let (_, a) = standard_form(k, m)?;
    let (s, _) = self_adjoint(&a, false)?;
    if s.iter().any(|v| !v.is_finite()) {
        return Err(LinalgError::NonFinite);
    }
    Ok(s)
}

/// Modes of the Hermitian pencil `K phi = w^2 M phi`, `M` Hermitian positive definite:
/// `phi^H M phi = I`, `phi^H K phi = diag(w^2)` (by Cholesky, as [`symmetric_modes`]).
pub struct HermitianModes {
    /// Eigenvalues `w^2`, ascending.
    pub omega_squared: Vec<f64>,
    pub phi: CMat,
}

/// Solves `K phi = w^2 M phi` for Hermitian `K` and `M`.
pub fn hermitian_modes(k: &CMat, m: &CMat) -> Result<HermitianModes, LinalgError> {
    if !all_finite_c(k) || !all_finite_c(m) {
        return Err(LinalgError::NonFinite);
    }
    let n = k.nrows();
    let mh = CMat::from_fn(n, n, |i, j| (m[(i, j)] + m[(j, i)].conj()) * 0.5);
    let llt = mh
        .llt(Side::Lower)
        .map_err(|_| LinalgError::NotPositiveDefinite)?;
    let l = llt.L().to_owned();
    let mut x = k.clone();
    l.as_ref().solve_lower_triangular_in_place(x.as_mut()); // L^-1 K
    let mut a = x.adjoint().to_owned(); // K L^-H
    l.as_ref().solve_lower_triangular_in_place(a.as_mut()); // L^-1 K L^-H
    let a = CMat::from_fn(n, n, |i, j| (a[(i, j)] + a[(j, i)].conj()) * 0.5);
    let (s, u) = self_adjoint_qr(&a)?;
    let omega_squared: Vec<f64> = s.iter().map(|v| v.re).collect();
    let mut phi = u;
    l.as_ref()
        .adjoint()
        .solve_upper_triangular_in_place(phi.as_mut());
    if omega_squared.iter().any(|v| !v.is_finite()) || !all_finite_c(&phi) {
        return Err(LinalgError::NonFinite);
    }
    Ok(HermitianModes { omega_squared, phi })
}

/// Whether [`mass_solve`] will succeed with `m`, at a fraction of its cost (a real Cholesky
/// factor, or a complex LU's solve of one column).
pub fn mass_factors(m: &CMat) -> Result<(), LinalgError> {
    let n = m.nrows();
    let real = (0..n).all(|j| (0..n).all(|i| m[(i, j)].im == 0.0));
    if real {
        let mr = RMat::from_fn(n, n, |i, j| m[(i, j)].re);
        return match is_positive_definite(&mr) {
            true => Ok(()),
            false => Err(LinalgError::NotPositiveDefinite),
        };
    }
    solve_complex(m, &CMat::from_fn(n, 1, |_, _| c64::new(1.0, 0.0))).map(|_| ())
}

/// `M^-1 B` for a mass matrix: by Cholesky when it is real (symmetric positive definite), by
/// LU when supports made it complex.
pub fn mass_solve(m: &CMat, b: &CMat) -> Result<CMat, LinalgError> {
    let n = m.nrows();
    let real = (0..n).all(|j| (0..n).all(|i| m[(i, j)].im == 0.0));
    if real {
        return spd_solve(&RMat::from_fn(n, n, |i, j| m[(i, j)].re), b);
    }
    solve_complex(m, b)
}

/// `M^-1 B` for a symmetric positive definite `M` and a complex right-hand side.
pub fn spd_solve(m: &RMat, b: &CMat) -> Result<CMat, LinalgError> {
    let mc = to_complex(m);
    let llt = mc
        .llt(Side::Lower)
        .map_err(|_| LinalgError::NotPositiveDefinite)?;
    Ok(llt.solve(b))
}

/// Real to complex matrix.
pub fn to_complex(a: &RMat) -> CMat {
    CMat::from_fn(a.nrows(), a.ncols(), |i, j| c64::new(a[(i, j)], 0.0))
}

fn all_finite_r(a: &RMat) -> bool {
    (0..a.ncols()).all(|j| (0..a.nrows()).all(|i| a[(i, j)].is_finite()))
}

fn all_finite_c(a: &CMat) -> bool {
    (0..a.ncols())
        .all(|j| (0..a.nrows()).all(|i| a[(i, j)].re.is_finite() && a[(i, j)].im.is_finite()))
}

/// Solves the small dense real system `A x = b` (partial pivoting LU).
pub fn solve_real(a: &RMat, b: &[f64]) -> Result<Vec<f64>, LinalgError> {
    let rhs = RMat::from_fn(b.len(), 1, |i, _| b[i]);
    let x = a.partial_piv_lu().solve(&rhs);
    let x: Vec<f64> = (0..b.len()).map(|i| x[(i, 0)]).collect();
    if x.iter().all(|v| v.is_finite()) {
        Ok(x)
    } else {
        Err(LinalgError::NonFinite)
    }
}

/// Solves `A X = B` for a dense real square `A` (partial pivoting LU).
pub fn solve_real_matrix(a: &RMat, b: &RMat) -> Result<RMat, LinalgError> {
    if a.nrows() == 0 {
        return Ok(RMat::zeros(0, b.ncols()));
    }
    let x = a.partial_piv_lu().solve(b);
    if all_finite_r(&x) {
        Ok(x)
    } else {
        Err(LinalgError::NonFinite)
    }
}

/// Solves `A X = B` for a dense complex square `A` (partial pivoting LU).
pub fn solve_complex(a: &CMat, b: &CMat) -> Result<CMat, LinalgError> {
    let x = a.partial_piv_lu().solve(b);
    if all_finite_c(&x) {
        Ok(x)
    } else {
        Err(LinalgError::NonFinite)
    }
}

/// `y += alpha A x` for `A` stored column-major in `a` (`y.len()` rows, `x.len()` columns).
///
/// The matrix-vector products of time stepping and of Arnoldi run here, on faer's kernels
/// (vectorised for the processor at run time): with the branch coupling formed as one
/// product, they took the nonviscous run-up of the unreduced compressor (120 reduced states,
/// four products a step) from 2.1 s to 1.0 s.
pub fn add_matvec_slice(y: &mut [c64], a: &[c64], x: &[c64], alpha: c64) {
    let (rows, cols) = (y.len(), x.len());
    debug_assert_eq!(a.len(), rows * cols);
    if rows == 0 || cols == 0 {
        return;
    }
    faer::linalg::matmul::matmul(
        faer::MatMut::from_column_major_slice_mut(y, rows, 1),
        faer::Accum::Add,
        faer::MatRef::from_column_major_slice(a, rows, cols),
        faer::MatRef::from_column_major_slice(x, cols, 1),
        alpha,
        Par::Seq,
    );
}

/// `y += alpha A x` (complex, or real: the drift's coupling of a paired integration).
pub fn add_matvec<T: faer::traits::ComplexField>(y: &mut [T], a: &faer::Mat<T>, x: &[T], alpha: T) {
    debug_assert_eq!((a.nrows(), a.ncols()), (y.len(), x.len()));
    if y.is_empty() || x.is_empty() {
        return;
    }
    faer::linalg::matmul::matmul(
        faer::MatMut::from_column_major_slice_mut(y, a.nrows(), 1),
        faer::Accum::Add,
        a.as_ref(),
        faer::MatRef::from_column_major_slice(x, a.ncols(), 1),
        alpha,
        Par::Seq,
    );
}

/// `y = A^H x` for `A` stored column-major in `a` (`x.len()` rows, `y.len()` columns).
pub fn adjoint_matvec_slice(y: &mut [c64], a: &[c64], x: &[c64]) {
    let (rows, cols) = (x.len(), y.len());
    debug_assert_eq!(a.len(), rows * cols);
    if rows == 0 || cols == 0 {
        y.iter_mut().for_each(|v| *v = c64::new(0.0, 0.0));
        return;
    }
    faer::linalg::matmul::matmul(
        faer::MatMut::from_column_major_slice_mut(y, cols, 1),
        faer::Accum::Replace,
        faer::MatRef::from_column_major_slice(a, rows, cols).adjoint(),
        faer::MatRef::from_column_major_slice(x, rows, 1),
        c64::new(1.0, 0.0),
        Par::Seq,
    );
}

/// `|a_i^H b_j|^2 / (|a_i|^2 |b_j|^2)` for every pair of vectors of equal length (0 where one
/// is zero): the modal assurance criterion of two sets of shapes, as one matrix product
/// (branch tracking compares every branch with every pole, 400 x 400 shapes at 404 states).
pub fn mac_matrix(a: &[&[c64]], b: &[&[c64]]) -> Vec<Vec<f64>> {
    let len = a.first().or(b.first()).map_or(0, |v| v.len());
    let stack = |v: &[&[c64]]| CMat::from_fn(len, v.len(), |i, j| v[j][i]);
    let (ma, mb) = (stack(a), stack(b));
    let dots = ma.adjoint() * &mb;
    let norms = |m: &CMat| -> Vec<f64> {
        (0..m.ncols())
            .map(|j| (0..len).map(|i| m[(i, j)].norm_sqr()).sum())
            .collect()
    };
    let (na, nb) = (norms(&ma), norms(&mb));
    (0..a.len())
        .map(|i| {
            (0..b.len())
                .map(|j| {
                    if na[i] > 0.0 && nb[j] > 0.0 {
                        dots[(i, j)].norm_sqr() / (na[i] * nb[j])
                    } else {
                        0.0
                    }
                })
                .collect()
        })
        .collect()
}

/// `A diag(d) B`.
pub fn scaled_product(a: &CMat, d: &[c64], b: &CMat) -> CMat {
    let scaled = CMat::from_fn(b.nrows(), b.ncols(), |i, j| d[i] * b[(i, j)]);
    a * &scaled
}

/// A complex LU factorisation, kept to solve many right-hand sides.
pub struct ComplexLu(faer::linalg::solvers::PartialPivLu<c64>);

impl ComplexLu {
    pub fn new(a: &CMat) -> Self {
        ComplexLu(a.partial_piv_lu())
    }

    /// Solves `A x = b` in place.
    pub fn solve_in_place(&self, b: &mut [c64]) {
        // A column view of `b` itself: this runs once per implicit stage, so no copy.
        let n = b.len();
        self.0
            .solve_in_place(faer::MatMut::from_column_major_slice_mut(b, n, 1));
    }
}

/// Whether a symmetric matrix is positive definite (Cholesky succeeds).
pub fn is_positive_definite(a: &RMat) -> bool {
    all_finite_r(a) && a.llt(Side::Lower).is_ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn symmetric_modes_of_a_two_mass_chain() {
        // m = diag(1, 2), k = [[3, -1], [-1, 1]]: 2 w^4 - 7 w^2 + 2 = 0, w^2 = (7 +- sqrt(33)) / 4.
        let m = RMat::from_fn(2, 2, |i, j| if i == j { (i + 1) as f64 } else { 0.0 });
        let k = RMat::from_fn(2, 2, |i, j| [[3.0, -1.0], [-1.0, 1.0]][i][j]);
        let modes = symmetric_modes(&k, &m).unwrap();
        let r = 33f64.sqrt();
        assert!((modes.omega_squared[0] - (7.0 - r) / 4.0).abs() < 1e-14);
        assert!((modes.omega_squared[1] - (7.0 + r) / 4.0).abs() < 1e-14);
        let ptmp = modes.phi.transpose() * &m * &modes.phi;
        for i in 0..2 {
            for j in 0..2 {
                let expected = if i == j { 1.0 } else { 0.0 };
                assert!((ptmp[(i, j)] - expected).abs() < 1e-14);
            }
        }
    }

    #[test]
    fn eigen_of_a_rotation_generator() {
        let a = CMat::from_fn(2, 2, |i, j| c64::new([[0.0, -1.0], [1.0, 0.0]][i][j], 0.0));
        let mut s = eigen(&a).unwrap().values;
        s.sort_by(|x, y| x.im.total_cmp(&y.im));
        assert!((s[0] - c64::new(0.0, -1.0)).norm() < 1e-14);
        assert!((s[1] - c64::new(0.0, 1.0)).norm() < 1e-14);
    }

    #[test]
    fn balancing_keeps_eigenpairs_of_a_badly_scaled_matrix() {
        // [[0, -w^2], [1, 0]] with w = 1e6: eigenvalues +-i w, norm w^2 before balancing.
        let w: f64 = 1e6;
        let a = CMat::from_fn(2, 2, |i, j| {
            c64::new([[0.0, -w * w], [1.0, 0.0]][i][j], 0.0)
        });
        let (b, _) = balance(&a);
        let norm = |m: &CMat| {
            (0..2)
                .flat_map(|i| (0..2).map(move |j| (i, j)))
                .map(|(i, j)| m[(i, j)].norm())
                .fold(0.0, f64::max)
        };
        assert!(norm(&b) < 4.0 * w, "balanced norm {}", norm(&b));
        let e = eigen(&a).unwrap();
        for j in 0..2 {
            assert!(
                e.values[j].re.abs() < 1e-9,
                "decay rate noise {}",
                e.values[j].re
            );
            // A v = s v for the returned (unbalanced) vectors.
            for i in 0..2 {
                let av: c64 = (0..2).map(|k| a[(i, k)] * e.vectors[(k, j)]).sum();
                assert!((av - e.values[j] * e.vectors[(i, j)]).norm() < 1e-9 * w);
            }
        }
    }

    #[test]
    fn non_finite_input_is_an_error_not_a_panic() {
        let a = CMat::from_fn(2, 2, |_, _| c64::new(f64::NAN, 0.0));
        assert_eq!(eigen(&a).err(), Some(LinalgError::NonFinite));
    }
}
