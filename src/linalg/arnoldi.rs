//! The eigenvalues of `A` near a shift, by Arnoldi on `T = (A - sigma I)^-1`.
//!
//! An eigenpair `A x = s x` is `T x = theta x` with `theta = 1 / (s - sigma)`: the eigenvalues
//! nearest `sigma` are the largest of `T`, which a Krylov space `span{v, T v, T^2 v, ...}`
//! finds first. With an orthonormal basis `V_m` (Gram-Schmidt twice, so orthogonality holds
//! to round-off), `T V_m = V_m H_m + h e_m^T` and the Ritz pairs `(theta, V_m y)` of the small
//! Hessenberg `H_m` have residuals `|h| |y_m|`; a Ritz value is accepted when that residual,
//! carried to `s` (`|ds| = |dtheta| / |theta|^2`), is below `tolerance |s|`.
//!
//! The space grows by half until every Ritz value within `radius` of the shift has converged,
//! and so have a few beyond it (a guard: Ritz values emerge by modulus, so converged ones
//! outside the disc mean none inside is still hidden). The caller applies `T` (one solve with
//! a factor kept for all steps); a space as large as the dense problem is not attempted.
//! Multiple eigenvalues appear once: a single start vector spans one vector of each
//! eigenspace, which is what a distance between sets of poles needs.

use super::{CMat, LinalgError, c64, eigen};

/// Eigenvalues near a shift and their (unit) eigenvectors.
pub struct Nearest {
    pub values: Vec<c64>,
    pub vectors: Vec<Vec<c64>>,
    /// Dimension of the Krylov space used.
    pub dimension: usize,
}

/// Every eigenvalue `s` of the `size x size` matrix `A` with `|s - sigma| <= radius`, given
/// `solve(b) = (A - sigma I)^-1 b`. `None` when the Krylov space would need more than
/// `max_dimension` vectors (then solve densely) or the solve is not finite.
pub fn nearest(
    size: usize,
    solve: impl Fn(&[c64]) -> Vec<c64>,
    sigma: c64,
    radius: f64,
    tolerance: f64,
    max_dimension: usize,
) -> Result<Option<Nearest>, LinalgError> {
    nearest_from(
        size,
        solve,
        sigma,
        radius,
        tolerance,
        (40, 3),
        max_dimension,
    )
}

/// [`nearest`] starting from a space of `first.0` vectors and asking at least `first.1`
/// converged Ritz values beyond the disc (fewer of both where only the eigenvalue nearest the
/// shift is wanted: the refinement of one pole, where no guard is needed beyond that one's own
/// convergence, which a nearer eigenvalue's would precede).
pub fn nearest_from(
    size: usize,
    solve: impl Fn(&[c64]) -> Vec<c64>,
    sigma: c64,
    radius: f64,
    tolerance: f64,
    first: (usize, usize),
    max_dimension: usize,
) -> Result<Option<Nearest>, LinalgError> {
    let zero = c64::new(0.0, 0.0);
    let max_dimension = max_dimension.min(size);
    // A fixed start vector with every component present (reproducible answers).
    let mut seed = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    let mut v0: Vec<c64> = (0..size).map(|_| c64::new(next(), next())).collect();
    normalise(&mut v0);
    // The basis, column-major: Gram-Schmidt is two products with it (classical, twice).
    let mut basis: Vec<c64> = v0;
    // Columns of H (each of length j + 2).
    let mut h: Vec<Vec<c64>> = vec![];
    let mut target = first.0.max(1).min(max_dimension);
    loop {
        // Extend the space to `target` vectors.
        let mut exhausted = false;
        // The whole extension at once (growing by doubling copied it and faulted its pages
        // in again: 14% of a small rotor's check).
        basis.reserve((target + 1) * size - basis.len());
        while h.len() < target {
            let j = h.len();
            let mut w = solve(&basis[j * size..(j + 1) * size]);
            if w.iter().any(|z| !z.re.is_finite() || !z.im.is_finite()) {
                return Ok(None);
            }
            let mut col = vec![zero; j + 2];
            let mut c = vec![zero; j + 1];
            for _pass in 0..2 {
                super::adjoint_matvec_slice(&mut c, &basis, &w);
                super::add_matvec_slice(&mut w, &basis, &c, c64::new(-1.0, 0.0));
                for (a, b) in col.iter_mut().zip(&c) {
                    *a += b;
                }
            }
            let norm = norm2(&w);
            col[j + 1] = c64::new(norm, 0.0);
            h.push(col);
            let scale = h[j].iter().map(|z| z.norm()).fold(0.0, f64::max);
            if norm <= 1e-14 * scale {
                // An invariant subspace: its Ritz pairs are exact.
                exhausted = true;
                break;
            }
            basis.extend(w.iter().map(|wk| wk / norm));
        }
        let m = h.len();
        let hm = CMat::from_fn(m, m, |i, j| if i <= j + 1 { h[j][i] } else { zero });
        let e = eigen(&hm)?;
        let beta = if exhausted { 0.0 } else { h[m - 1][m].re };
        // (s, residual in s relative to |s|, |theta|, index) of each Ritz pair.
        let mut ritz: Vec<(c64, bool, f64, usize)> = (0..m)
            .map(|k| {
                let theta = e.values[k];
                let s = sigma + c64::new(1.0, 0.0) / theta;
                let r = beta * e.vectors[(m - 1, k)].norm();
                let ds = r / theta.norm_sqr();
                (s, ds <= tolerance * s.norm(), theta.norm(), k)
            })
            .collect();
        ritz.sort_by(|a, b| b.2.total_cmp(&a.2));
        let inside = ritz.iter().filter(|r| r.2 * radius >= 1.0).count();
        let guard = (inside / 4).max(first.1);
        // At least the Ritz value nearest the shift: with no guard, the answer is then
        // whatever of the disc holds the converged nearest eigenvalue.
        let wanted = (inside + guard).max(1).min(m);
        let converged = ritz[..wanted].iter().all(|r| r.1);
        if exhausted || (converged && (inside + guard <= m)) {
            let mut out = Nearest {
                values: vec![],
                vectors: vec![],
                dimension: m,
            };
            for &(s, _, _, k) in &ritz[..inside] {
                let mut x = vec![zero; size];
                let y: Vec<c64> = (0..m).map(|i| e.vectors[(i, k)]).collect();
                super::add_matvec_slice(&mut x, &basis[..m * size], &y, c64::new(1.0, 0.0));
                normalise(&mut x);
                out.values.push(s);
                out.vectors.push(x);
            }
            return Ok(Some(out));
        }
        if m >= max_dimension {
            return Ok(None);
        }
        target = (3 * m).div_ceil(2).min(max_dimension);
    }
}

fn norm2(x: &[c64]) -> f64 {
    x.iter().map(|z| z.norm_sqr()).sum::<f64>().sqrt()
}

fn normalise(x: &mut [c64]) {
    let n = norm2(x);
    if n > 0.0 {
        for z in x.iter_mut() {
            *z /= n;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::solve_complex;

    /// A non-normal matrix with known eigenvalues: `A = S diag(s) S^-1`.
    #[test]
    fn finds_every_eigenvalue_in_the_disc_of_a_non_normal_matrix() {
        let n = 120;
        let values: Vec<c64> = (0..n)
            .map(|k| {
                let w = 1.0 + k as f64 * 0.37;
                c64::new(
                    -0.02 * w - 0.1 * (k % 3) as f64,
                    if k % 2 == 0 { w } else { -w },
                )
            })
            .collect();
        let s = CMat::from_fn(n, n, |i, j| {
            let d = if i == j { 1.0 } else { 0.0 };
            c64::new(
                d + 0.3 / (1.0 + (i as f64 - j as f64).abs()),
                0.05 * ((i + 2 * j) % 5) as f64,
            )
        });
        let diag = CMat::from_fn(n, n, |i, j| {
            if i == j {
                values[i]
            } else {
                c64::new(0.0, 0.0)
            }
        });
        let eye = CMat::from_fn(n, n, |i, j| c64::new(if i == j { 1.0 } else { 0.0 }, 0.0));
        let s_inv = solve_complex(&s, &eye).unwrap();
        let a = &s * &diag * &s_inv;
        let sigma = c64::new(0.05, 0.07);
        let shifted = CMat::from_fn(n, n, |i, j| {
            a[(i, j)] - if i == j { sigma } else { c64::new(0.0, 0.0) }
        });
        let lu = crate::linalg::ComplexLu::new(&shifted);
        let solve = |b: &[c64]| {
            let mut x = b.to_vec();
            lu.solve_in_place(&mut x);
            x
        };
        let radius = 8.0;
        let found = nearest(n, solve, sigma, radius, 1e-11, n).unwrap().unwrap();
        let expected: Vec<c64> = values
            .iter()
            .cloned()
            .filter(|v| (v - sigma).norm() <= radius)
            .collect();
        assert_eq!(found.values.len(), expected.len(), "{}", found.dimension);
        assert!(found.dimension < n);
        for v in &expected {
            let d = found
                .values
                .iter()
                .map(|f| (f - v).norm())
                .fold(f64::INFINITY, f64::min);
            assert!(d <= 1e-9 * v.norm(), "{v}: {d}");
        }
        // Each vector is an eigenvector.
        for (s, x) in found.values.iter().zip(&found.vectors) {
            let ax: Vec<c64> = (0..n)
                .map(|i| (0..n).map(|j| a[(i, j)] * x[j]).sum())
                .collect();
            let r: f64 = ax
                .iter()
                .zip(x)
                .map(|(p, q)| (p - s * q).norm_sqr())
                .sum::<f64>()
                .sqrt();
            assert!(r <= 1e-8 * s.norm(), "{s}: {r}");
        }
    }
}
