//! Eigenvalues and vectors of general (non-symmetric) dense matrices: a rotor's state matrix,
//! a reduced model's, a Krylov space's Hessenberg matrix. Balanced first (see [`eigen`]).

use super::{CMat, LinalgError, RMat, all_finite_c, c64, to_complex};

/// Eigenvalues and right eigenvectors (columns, unit 2-norm) of a general complex matrix.
pub struct Eigen {
    pub values: Vec<c64>,
    pub vectors: CMat,
}

/// Complex eigendecomposition `A V = V diag(s)`, on the balanced matrix.
///
/// A rotor's state matrix mixes velocities and displacements: its norm is about `w_max^2`,
/// and an unbalanced solve leaves round-off of `eps w_max^2` in the decay rates (on a
/// 100-element shaft, enough to fake an instability). Balancing `B = D^-1 A D` with a diagonal
/// `D` of powers of two (Parlett-Reinsch, as LAPACK's gebal) brings it to about `eps w_max`;
/// it changes no eigenvalue, and the vectors are `D` times those of `B`.
pub fn eigen(a: &CMat) -> Result<Eigen, LinalgError> {
    if !all_finite_c(a) {
        return Err(LinalgError::NonFinite);
    }
    let (b, d) = balance(a);
    unbalanced(&b.eigen().map_err(|_| LinalgError::NoConvergence)?, &d)
}

/// [`eigen`] of a real matrix (balanced the same way), by the real Schur form (fewer flops; in
/// faer at 44 states 0.70 ms against the complex solve's 0.84). A complex pair comes as
/// adjacent columns `j, j + 1` with `s[j + 1] = conj s[j]` (`s[j].im != 0`) and exactly
/// conjugate vectors; a real eigenvalue has `im == 0` and a real vector.
pub fn eigen_real(a: &RMat) -> Result<Eigen, LinalgError> {
    let n = a.nrows();
    if (0..n).any(|j| (0..n).any(|i| !a[(i, j)].is_finite())) {
        return Err(LinalgError::NonFinite);
    }
    let (_, d) = balance(&to_complex(a));
    let b = RMat::from_fn(n, n, |i, j| a[(i, j)] * d[j] / d[i]);
    unbalanced(&b.eigen().map_err(|_| LinalgError::NoConvergence)?, &d)
}

/// The decomposition of `A` from that of the balanced `D^-1 A D`: the vectors `D` times the
/// balanced ones, back to unit norm (as the unbalanced solver gives them); errs on anything
/// not finite.
fn unbalanced(e: &faer::linalg::solvers::Eigen<f64>, d: &[f64]) -> Result<Eigen, LinalgError> {
    let s = e.S().column_vector();
    let n = d.len();
    let values: Vec<c64> = (0..n).map(|j| s[j]).collect();
    if values
        .iter()
        .any(|v| !v.re.is_finite() || !v.im.is_finite())
    {
        return Err(LinalgError::NonFinite);
    }
    let u = e.U();
    let mut vectors = CMat::from_fn(n, n, |i, j| u[(i, j)] * d[i]);
    if !all_finite_c(&vectors) {
        return Err(LinalgError::NonFinite);
    }
    for j in 0..n {
        let norm = (0..n)
            .map(|i| vectors[(i, j)].norm_sqr())
            .sum::<f64>()
            .sqrt();
        if norm > 0.0 {
            for i in 0..n {
                vectors[(i, j)] /= norm;
            }
        }
    }
    Ok(Eigen { values, vectors })
}

/// Eigenvalues only of a general complex matrix (balanced as in [`eigen`]): about half the
/// work of values and vectors.
pub fn eigenvalues(a: &CMat) -> Result<Vec<c64>, LinalgError> {
    if !all_finite_c(a) {
        return Err(LinalgError::NonFinite);
    }
    let (b, _) = balance(a);
    let values = b.eigenvalues().map_err(|_| LinalgError::NoConvergence)?;
    if values
        .iter()
        .any(|v| !v.re.is_finite() || !v.im.is_finite())
    {
        return Err(LinalgError::NonFinite);
    }
    Ok(values)
}

/// Diagonal balancing `B = D^-1 A D` (see [`eigen`]); returns `B` and `diag(D)`.
pub fn balance(a: &CMat) -> (CMat, Vec<f64>) {
    let n = a.nrows();
    let mut b = a.clone();
    let mut d = vec![1.0; n];
    let abs1 = |z: c64| z.re.abs() + z.im.abs();
    for _sweep in 0..100 {
        let mut converged = true;
        for i in 0..n {
            let (mut c, mut r) = (0.0, 0.0);
            for k in 0..n {
                if k != i {
                    c += abs1(b[(k, i)]);
                    r += abs1(b[(i, k)]);
                }
            }
            if c == 0.0 || r == 0.0 {
                continue;
            }
            let s = c + r;
            let (mut f, mut cc, mut rr) = (1.0, c, r);
            while cc < rr / 2.0 {
                cc *= 2.0;
                rr /= 2.0;
                f *= 2.0;
            }
            while cc >= rr * 2.0 {
                cc /= 2.0;
                rr *= 2.0;
                f /= 2.0;
            }
            if cc + rr < 0.95 * s {
                converged = false;
                d[i] *= f;
                for k in 0..n {
                    b[(i, k)] /= f;
                    b[(k, i)] *= f;
                }
            }
        }
        if converged {
            break;
        }
    }
    (b, d)
}
