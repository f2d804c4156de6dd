//! M-orthonormal extension of a basis by Gram-Schmidt.
//!
//! Given columns `V` with `V^T M V = I` and `K V` tracked beside them, each new column `x`
//! (with `K x`) is made M-orthogonal to every column kept so far by classical Gram-Schmidt,
//! `x <- x - V (V^T M x)`, run twice (Kahan: twice is enough), and kept, normalised to
//! `x^T M x = 1`, unless it has vanished below `1e-8` of its starting M-norm (it lay in the
//! span already). `K x` follows the same combinations, so it is never formed as a product with
//! `K` (which cancels badly for low modes of stiff shafts). Each pass is two matrix-vector
//! products and two thin products with the basis.

use super::RMat;

/// Drop threshold: a column whose M-norm falls below this fraction of its start is dependent.
const DEPENDENT: f64 = 1e-8;

/// `V` extended by the columns of `x` (see the module docs), with `K V` extended by `kx`
/// alike.
/// `m` multiplies by the mass matrix.
pub fn m_orthonormal_extend(
    m: impl Fn(&RMat) -> RMat,
    v: &RMat,
    kv: &RMat,
    x: &RMat,
    kx: &RMat,
) -> (RMat, RMat) {
    let n = x.nrows();
    let cap = v.ncols() + x.ncols();
    let mut basis = RMat::zeros(n, cap);
    let mut k_basis = RMat::zeros(n, cap);
    basis.as_mut().subcols_mut(0, v.ncols()).copy_from(v);
    k_basis.as_mut().subcols_mut(0, v.ncols()).copy_from(kv);
    let mut r = v.ncols();
    let m_norm = |c: &RMat| -> f64 {
        let mc = m(c);
        (0..n)
            .map(|i| c[(i, 0)] * mc[(i, 0)])
            .sum::<f64>()
            .max(0.0)
            .sqrt()
    };
    for j in 0..x.ncols() {
        let mut c = x.as_ref().subcols(j, 1).to_owned();
        let mut kc = kx.as_ref().subcols(j, 1).to_owned();
        let start = m_norm(&c);
        if start == 0.0 || !start.is_finite() {
            continue;
        }
        for _twice in 0..2 {
            let b = basis.as_ref().subcols(0, r);
            let coef = b.transpose() * m(&c);
            c -= b * &coef;
            kc -= k_basis.as_ref().subcols(0, r) * &coef;
        }
        let norm = m_norm(&c);
        if norm > DEPENDENT * start {
            for i in 0..n {
                basis[(i, r)] = c[(i, 0)] / norm;
                k_basis[(i, r)] = kc[(i, 0)] / norm;
            }
            r += 1;
        }
    }
    (
        basis.as_ref().subcols(0, r).to_owned(),
        k_basis.as_ref().subcols(0, r).to_owned(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extends_m_orthonormally_and_drops_dependent_columns() {
        // M = diag(1, 2, 3, 4), K = diag(10, 20, 30, 40); V: the first unit mode.
        let n = 4;
        let m = RMat::from_fn(n, n, |i, j| if i == j { (i + 1) as f64 } else { 0.0 });
        let k = RMat::from_fn(
            n,
            n,
            |i, j| if i == j { 10.0 * (i + 1) as f64 } else { 0.0 },
        );
        let v = RMat::from_fn(n, 1, |i, _| if i == 0 { 1.0 } else { 0.0 });
        let kv = &k * &v;
        // x: a mix of all four, then a copy of the first (dependent), then e_2.
        let x = RMat::from_fn(n, 3, |i, j| match j {
            0 => 1.0 + i as f64,
            1 => 1.0 + i as f64,
            _ => (i == 1) as u8 as f64,
        });
        let kx = &k * &x;
        let (b, kb) = m_orthonormal_extend(|c: &RMat| &m * c, &v, &kv, &x, &kx);
        assert_eq!(b.ncols(), 3);
        let g = b.transpose() * &m * &b;
        for i in 0..3 {
            for j in 0..3 {
                let want = if i == j { 1.0 } else { 0.0 };
                assert!((g[(i, j)] - want).abs() < 1e-14, "{i} {j}: {}", g[(i, j)]);
            }
        }
        // K is tracked, not formed: K b equals the tracked columns.
        let kb_exact = &k * &b;
        for i in 0..n {
            for j in 0..3 {
                assert!((kb[(i, j)] - kb_exact[(i, j)]).abs() < 1e-12);
            }
        }
        // The second column: (0, 2, 3, 4) / sqrt(2*4 + 3*9 + 4*16) = / sqrt(99).
        assert!((b[(1, 1)] - 2.0 / 99f64.sqrt()).abs() < 1e-15);
    }
}
