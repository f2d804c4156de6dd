//! The lowest modes of a large sparse symmetric pencil by shift-invert Lanczos.
//!
//! For `K phi = lambda M phi` with `K` and `M` symmetric positive definite (a supported rotor),
//! the operator `K^-1 M` is self-adjoint in the M inner product and its largest eigenvalues
//! `theta = 1 / lambda` are the lowest modes'. Lanczos builds an M-orthonormal Krylov basis
//! `Q_j` with `K^-1 M Q_j = Q_j T_j + beta_j q_{j+1} e_j^T` (`T_j` tridiagonal), each new vector
//! reorthogonalised against all before it (twice, as `gram.rs`), so no copies of converged modes
//! appear. A Ritz pair `(1 / theta, Q_j s)` of `T_j s = theta s` has the residual
//! `|beta_j s_j|` in the M norm; it is kept when that is below [`TOLERANCE`] `theta`. The lowest
//! modes converge first. Cost: per step one sparse solve with the factor of `K`, one product with
//! `M` and the reorthogonalisation, `O(n j)`: `O(n j^2)` in all, linear in the mesh.

use super::sparse::{Cholesky, Sparse};
use super::{LinalgError, RMat, SymmetricModes};

/// Largest Lanczos residual of a kept pair, relative to `theta`: the mode's `K phi - w^2 M phi`
/// is then about this fraction of `K phi`.
pub const TOLERANCE: f64 = 1e-11;

/// Steps between two Ritz extractions.
const STRIDE: usize = 8;

/// The lowest modes of `(K, M)`, M-normalised, until `enough(w^2 ascending)` holds of the
/// converged ones (or all `n` are found). `K` must be positive definite: a rigid-body mode fails
/// its factorisation with [`LinalgError::NotPositiveDefinite`].
pub fn lowest_modes(
    k: &Sparse,
    m: &Sparse,
    enough: impl Fn(&[f64]) -> bool,
) -> Result<SymmetricModes, LinalgError> {
    let n = k.nrows();
    let chol = Cholesky::new(k)?;
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    // A start with every mode in it, deterministic.
    let mut q: Vec<f64> = (0..n).map(|i| 1.0 + 0.5 * (0.7 * i as f64).sin()).collect();
    let mq = m.mul_vec(&q);
    let norm = dot(&q, &mq).sqrt();
    q.iter_mut().for_each(|v| *v /= norm);
    let mut basis: Vec<Vec<f64>> = vec![q];
    let mut m_basis: Vec<Vec<f64>> = vec![m.mul_vec(&basis[0])];
    let (mut alpha, mut beta): (Vec<f64>, Vec<f64>) = (vec![], vec![]);
    loop {
        let j = basis.len() - 1;
        let mut w = chol.solve_vec(&m_basis[j]);
        alpha.push(dot(&w, &m_basis[j]));
        // Full reorthogonalisation, twice: the three-term recurrence alone loses orthogonality
        // as modes converge.
        for _twice in 0..2 {
            for (qi, mqi) in basis.iter().zip(&m_basis) {
                let c = dot(&w, mqi);
                w.iter_mut().zip(qi).for_each(|(a, b)| *a -= c * b);
            }
        }
        let mw = m.mul_vec(&w);
        let b = dot(&w, &mw).max(0.0).sqrt();
        let size = j + 1;
        let scale = alpha.iter().cloned().fold(0.0, f64::max);
        let breakdown = b.is_nan() || b <= 1e-14 * scale || size == n;
        if breakdown || size.is_multiple_of(STRIDE) {
            let ritz = ritz(&alpha, &beta)?;
            // theta descending is w^2 ascending; converged from the lowest up.
            let mut kept = vec![];
            for (i, &theta) in ritz.0.iter().enumerate().rev() {
                let last = ritz.1[(size - 1, i)];
                if theta.is_nan()
                    || theta <= 0.0
                    || (b * last).abs() > TOLERANCE * theta && !breakdown
                {
                    break;
                }
                kept.push(i);
            }
            let omega_squared: Vec<f64> = kept.iter().map(|&i| 1.0 / ritz.0[i]).collect();
            if breakdown || (!kept.is_empty() && enough(&omega_squared)) {
                let mut phi = RMat::zeros(n, kept.len());
                for (c, &i) in kept.iter().enumerate() {
                    for (r, qr) in basis.iter().enumerate() {
                        let s = ritz.1[(r, i)];
                        for row in 0..n {
                            phi[(row, c)] += s * qr[row];
                        }
                    }
                }
                if omega_squared.iter().any(|v| !v.is_finite()) {
                    return Err(LinalgError::NonFinite);
                }
                return Ok(SymmetricModes { omega_squared, phi });
            }
        }
        beta.push(b);
        w.iter_mut().for_each(|v| *v /= b);
        m_basis.push(mw.iter().map(|v| v / b).collect());
        basis.push(w);
    }
}

/// Eigenvalues (ascending) and eigenvectors of the symmetric tridiagonal `T` with diagonal
/// `alpha` and off-diagonal `beta`.
fn ritz(alpha: &[f64], beta: &[f64]) -> Result<(Vec<f64>, RMat), LinalgError> {
    let size = alpha.len();
    let t = RMat::from_fn(size, size, |i, j| {
        if i == j {
            alpha[i]
        } else if i == j + 1 {
            beta[j]
        } else if j == i + 1 {
            beta[i]
        } else {
            0.0
        }
    });
    let (s, u) = super::self_adjoint(&t, true)?;
    Ok((s, u.expect("asked for")))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A string of `n` unit masses between unit springs, fixed at both ends:
    /// `w_k^2 = 2 - 2 cos(k pi / (n + 1))`.
    #[test]
    fn lowest_modes_of_a_fixed_string() {
        let n = 400;
        let k = crate::linalg::sparse::tests::laplacian(n);
        let m = Sparse::from_triplets(n, n, &(0..n).map(|i| (i, i, 1.0)).collect::<Vec<_>>());
        let modes = lowest_modes(&k, &m, |w2| w2.len() >= 6).unwrap();
        assert!(modes.omega_squared.len() >= 6);
        for (i, &w2) in modes.omega_squared.iter().enumerate().take(6) {
            let exact = 2.0 - 2.0 * ((i + 1) as f64 * std::f64::consts::PI / (n + 1) as f64).cos();
            assert!(
                (w2 - exact).abs() < 1e-9 * exact,
                "mode {i}: {w2} vs {exact}"
            );
            // K phi = w^2 M phi, phi^T M phi = 1.
            let phi: Vec<f64> = (0..n).map(|r| modes.phi[(r, i)]).collect();
            let kphi = k.mul_vec(&phi);
            let res = (0..n)
                .map(|r| (kphi[r] - w2 * phi[r]).powi(2))
                .sum::<f64>()
                .sqrt();
            assert!(res < 1e-9 * w2, "residual {res}");
            let norm: f64 = phi.iter().map(|v| v * v).sum();
            assert!((norm - 1.0).abs() < 1e-12);
        }
    }
}
