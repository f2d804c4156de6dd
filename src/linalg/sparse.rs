//! Sparse matrices: the assembled rotor's storage, and the factorisations that keep large models
//! linear in their size.
//!
//! A beam element couples a node with its neighbours only, so each of the rotor's matrices holds
//! `O(n)` entries (a band of half-width 3 in complex coordinates); supports, seals and couplings
//! add a few. [`Sparse`] stores them by compressed columns, rows ascending in each column.
//! Dense paths read them as dense ([`Sparse::to_dense`]) where a model is small; large models
//! factor them sparse, with a fill-reducing ordering: [`Cholesky`] (`L L^T`) for the stiffness,
//! [`Lu`] (partial pivoting) for a complex dynamic stiffness `Z(sigma)`. Either factor of a
//! banded matrix costs `O(n b^2)` and each solve `O(n b)`.

use super::{LinalgError, RMat, c64};
use faer::linalg::solvers::Solve;
use faer::sparse::{SparseColMat, Triplet};
use faer::{Mat, Side};

/// Order up to which products with a [`Sparse`] matrix go through its dense form
/// ([`Sparse::times`]): below it dense kernels are as fast, and small models keep the round-off
/// they had when every matrix was dense.
pub const DENSE_UP_TO: usize = 600;

/// A real sparse matrix by compressed columns.
#[derive(Debug, Clone, PartialEq)]
pub struct Sparse {
    nrows: usize,
    ncols: usize,
    /// Column `j`'s entries are `rows[col_ptr[j]..col_ptr[j + 1]]`, ascending.
    col_ptr: Vec<usize>,
    rows: Vec<usize>,
    values: Vec<f64>,
}

impl Sparse {
    /// The `nrows x ncols` zero matrix.
    pub fn zeros(nrows: usize, ncols: usize) -> Self {
        Sparse {
            nrows,
            ncols,
            col_ptr: vec![0; ncols + 1],
            rows: vec![],
            values: vec![],
        }
    }

    /// From `(row, column, value)` triplets; repeated positions are summed in the order given
    /// (so that assembly gives the same round-off as adding into a dense matrix element by
    /// element).
    pub fn from_triplets(nrows: usize, ncols: usize, entries: &[(usize, usize, f64)]) -> Self {
        let mut order: Vec<usize> = (0..entries.len()).collect();
        // A stable sort keeps each position's contributions in their given order.
        order.sort_by_key(|&k| (entries[k].1, entries[k].0));
        let mut col_ptr = vec![0; ncols + 1];
        let mut rows = Vec::with_capacity(entries.len());
        let mut values: Vec<f64> = Vec::with_capacity(entries.len());
        let mut last: Option<(usize, usize)> = None;
        for k in order {
            let (i, j, v) = entries[k];
            assert!(
                i < nrows && j < ncols,
                "entry ({i}, {j}) outside {nrows} x {ncols}"
            );
            if last == Some((i, j)) {
                *values.last_mut().expect("an entry was pushed") += v;
            } else {
                rows.push(i);
                values.push(0.0 + v);
                col_ptr[j + 1] += 1;
                last = Some((i, j));
            }
        }
        for j in 0..ncols {
            col_ptr[j + 1] += col_ptr[j];
        }
        Sparse {
            nrows,
            ncols,
            col_ptr,
            rows,
            values,
        }
    }

    /// The nonzero entries of a dense matrix.
    pub fn from_dense(a: &RMat) -> Self {
        let mut entries = vec![];
        for j in 0..a.ncols() {
            for i in 0..a.nrows() {
                if a[(i, j)] != 0.0 {
                    entries.push((i, j, a[(i, j)]));
                }
            }
        }
        Self::from_triplets(a.nrows(), a.ncols(), &entries)
    }

    pub fn nrows(&self) -> usize {
        self.nrows
    }

    pub fn ncols(&self) -> usize {
        self.ncols
    }

    /// Stored entries.
    pub fn nnz(&self) -> usize {
        self.values.len()
    }

    /// Every stored entry as `(row, column, value)`, column by column.
    pub fn entries(&self) -> impl Iterator<Item = (usize, usize, f64)> + '_ {
        (0..self.ncols).flat_map(move |j| {
            (self.col_ptr[j]..self.col_ptr[j + 1]).map(move |k| (self.rows[k], j, self.values[k]))
        })
    }

    /// The entry at `(i, j)` (zero if not stored).
    pub fn get(&self, i: usize, j: usize) -> f64 {
        let range = self.col_ptr[j]..self.col_ptr[j + 1];
        match self.rows[range.clone()].binary_search(&i) {
            Ok(k) => self.values[range.start + k],
            Err(_) => 0.0,
        }
    }

    /// Whether every entry is zero.
    pub fn is_zero(&self) -> bool {
        self.values.iter().all(|&v| v == 0.0)
    }

    pub fn to_dense(&self) -> RMat {
        let mut a = RMat::zeros(self.nrows, self.ncols);
        for (i, j, v) in self.entries() {
            a[(i, j)] = v;
        }
        a
    }

    /// `self + alpha other`.
    pub fn plus(&self, other: &Sparse, alpha: f64) -> Sparse {
        let entries: Vec<_> = self
            .entries()
            .chain(other.entries().map(|(i, j, v)| (i, j, alpha * v)))
            .collect();
        Self::from_triplets(self.nrows, self.ncols, &entries)
    }

    /// `A X`, through the dense form up to [`DENSE_UP_TO`].
    pub fn times(&self, x: &RMat) -> RMat {
        match self.nrows.max(self.ncols) <= DENSE_UP_TO {
            true => self.to_dense() * x,
            false => self.mul(x),
        }
    }

    /// `A X`.
    pub fn mul(&self, x: &RMat) -> RMat {
        let mut y = RMat::zeros(self.nrows, x.ncols());
        for c in 0..x.ncols() {
            for j in 0..self.ncols {
                let xj = x[(j, c)];
                if xj != 0.0 {
                    for k in self.col_ptr[j]..self.col_ptr[j + 1] {
                        y[(self.rows[k], c)] += self.values[k] * xj;
                    }
                }
            }
        }
        y
    }

    /// `A x`.
    pub fn mul_vec(&self, x: &[f64]) -> Vec<f64> {
        let mut y = vec![0.0; self.nrows];
        for (j, &xj) in x.iter().enumerate().take(self.ncols) {
            if xj != 0.0 {
                for k in self.col_ptr[j]..self.col_ptr[j + 1] {
                    y[self.rows[k]] += self.values[k] * xj;
                }
            }
        }
        y
    }

    /// `y += alpha A x` for a complex `x` (the real matrix acting on each part).
    pub fn add_mul_complex(&self, y: &mut [c64], x: &[c64], alpha: c64) {
        for (j, &xj) in x.iter().enumerate().take(self.ncols) {
            if xj == c64::new(0.0, 0.0) {
                continue;
            }
            let ax = alpha * xj;
            for k in self.col_ptr[j]..self.col_ptr[j + 1] {
                y[self.rows[k]] += ax * self.values[k];
            }
        }
    }

    /// `V^T A V`, by the sparse product `A V` (through the dense form, forming `A` costs more
    /// than the product: a reduction projects nine matrices).
    pub fn project(&self, v: &RMat) -> RMat {
        v.transpose() * self.mul(v)
    }

    /// `A^-1 B` for a symmetric `A`: dense LU up to [`DENSE_UP_TO`], else a sparse Cholesky
    /// factor (`A` positive definite).
    pub fn solve_symmetric(&self, b: &RMat) -> Result<RMat, LinalgError> {
        match self.nrows <= DENSE_UP_TO {
            true => super::solve_real_matrix(&self.to_dense(), b),
            false => Ok(Cholesky::new(self)?.solve(b)),
        }
    }
}

/// `A = L L^T` of a sparse symmetric positive definite matrix (its lower triangle is read).
pub struct Cholesky {
    llt: faer::sparse::linalg::solvers::Llt<usize, f64>,
}

impl Cholesky {
    pub fn new(a: &Sparse) -> Result<Self, LinalgError> {
        if a.values.iter().any(|v| !v.is_finite()) {
            return Err(LinalgError::NonFinite);
        }
        let lower: Vec<_> = a
            .entries()
            .filter(|&(i, j, _)| i >= j)
            .map(|(i, j, v)| Triplet::new(i, j, v))
            .collect();
        let m = SparseColMat::<usize, f64>::try_new_from_triplets(a.nrows, a.ncols, &lower)
            .map_err(|_| LinalgError::NotPositiveDefinite)?;
        let llt = m
            .sp_cholesky(Side::Lower)
            .map_err(|_| LinalgError::NotPositiveDefinite)?;
        Ok(Cholesky { llt })
    }

    /// `A^-1 b`.
    pub fn solve_vec(&self, b: &[f64]) -> Vec<f64> {
        let mut x = Mat::<f64>::from_fn(b.len(), 1, |i, _| b[i]);
        self.llt.solve_in_place(x.as_mut());
        (0..b.len()).map(|i| x[(i, 0)]).collect()
    }

    /// `A^-1 B`.
    pub fn solve(&self, b: &RMat) -> RMat {
        let mut x: Mat<f64> = b.clone();
        self.llt.solve_in_place(x.as_mut());
        x
    }
}

/// `A = P L U Q` of a sparse complex square matrix.
pub struct Lu {
    lu: faer::sparse::linalg::solvers::Lu<usize, c64>,
    n: usize,
}

impl Lu {
    /// From `(row, column, value)` triplets (repeated positions summed).
    pub fn new(n: usize, entries: &[(usize, usize, c64)]) -> Result<Self, LinalgError> {
        if entries
            .iter()
            .any(|e| !(e.2.re.is_finite() && e.2.im.is_finite()))
        {
            return Err(LinalgError::NonFinite);
        }
        let t: Vec<_> = entries
            .iter()
            .map(|&(i, j, v)| Triplet::new(i, j, v))
            .collect();
        let m = SparseColMat::<usize, c64>::try_new_from_triplets(n, n, &t)
            .map_err(|_| LinalgError::NonFinite)?;
        let lu = m.sp_lu().map_err(|_| LinalgError::NonFinite)?;
        Ok(Lu { lu, n })
    }

    /// `B <- A^-1 B`, every column at once.
    pub fn solve_columns(&self, b: &mut Mat<c64>) {
        self.lu.solve_in_place(b.as_mut());
    }

    /// `b <- A^-1 b`.
    pub fn solve_in_place(&self, b: &mut [c64]) {
        let mut x = Mat::<c64>::from_fn(self.n, 1, |i, _| b[i]);
        self.lu.solve_in_place(x.as_mut());
        for (i, bi) in b.iter_mut().enumerate() {
            *bi = x[(i, 0)];
        }
    }
}

/// The positions of a sparse complex square matrix's entries, ordered and analysed once, for
/// many factors of matrices with entries at the same positions (a dynamic stiffness over
/// frequency): each factor then skips the sort, the compression and the fill-reducing
/// ordering, which cost as much as the numeric factor of a banded matrix.
pub struct LuPattern {
    n: usize,
    /// Entries given, repeated positions included.
    len: usize,
    csc: faer::sparse::SymbolicSparseColMat<usize>,
    order: faer::sparse::Argsort<usize>,
    symbolic: faer::sparse::linalg::solvers::SymbolicLu<usize>,
}

impl LuPattern {
    /// From the `(row, column)` of each entry, repeated positions summed when factored.
    pub fn new(n: usize, positions: &[(usize, usize)]) -> Result<Self, LinalgError> {
        let pairs: Vec<_> = positions
            .iter()
            .map(|&(i, j)| faer::sparse::Pair::new(i, j))
            .collect();
        let (csc, order) = faer::sparse::SymbolicSparseColMat::try_new_from_indices(n, n, &pairs)
            .map_err(|_| LinalgError::NonFinite)?;
        let symbolic = faer::sparse::linalg::solvers::SymbolicLu::try_new(csc.as_ref())
            .map_err(|_| LinalgError::NonFinite)?;
        Ok(LuPattern {
            n,
            len: positions.len(),
            csc,
            order,
            symbolic,
        })
    }

    /// The factor of the matrix with `values` at the pattern's positions, in their order.
    pub fn factor(&self, values: &[c64]) -> Result<Lu, LinalgError> {
        assert_eq!(values.len(), self.len, "values of another pattern");
        if values
            .iter()
            .any(|v| !(v.re.is_finite() && v.im.is_finite()))
        {
            return Err(LinalgError::NonFinite);
        }
        let m = SparseColMat::new_from_argsort(self.csc.clone(), &self.order, values)
            .map_err(|_| LinalgError::NonFinite)?;
        let lu = faer::sparse::linalg::solvers::Lu::try_new_with_symbolic(
            self.symbolic.clone(),
            m.as_ref(),
        )
        .map_err(|_| LinalgError::NonFinite)?;
        Ok(Lu { lu, n: self.n })
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// The 1-D Laplacian `tridiag(-1, 2, -1)` of order `n`: SPD, eigenvalues
    /// `2 - 2 cos(k pi / (n + 1))` (also a string of unit masses between unit springs).
    pub(crate) fn laplacian(n: usize) -> Sparse {
        let mut e = vec![];
        for i in 0..n {
            e.push((i, i, 2.0));
            if i + 1 < n {
                e.push((i, i + 1, -1.0));
                e.push((i + 1, i, -1.0));
            }
        }
        Sparse::from_triplets(n, n, &e)
    }

    #[test]
    fn triplets_sum_in_order_and_read_back() {
        let a = Sparse::from_triplets(3, 3, &[(2, 0, 1.0), (0, 0, 0.1), (2, 0, 2.0), (1, 2, -4.0)]);
        assert_eq!(a.nnz(), 3);
        assert_eq!(a.get(2, 0), 3.0);
        assert_eq!(a.get(0, 0), 0.1);
        assert_eq!(a.get(1, 2), -4.0);
        assert_eq!(a.get(1, 1), 0.0);
        assert_eq!(Sparse::from_dense(&a.to_dense()), a);
        assert!(!a.is_zero() && Sparse::zeros(3, 3).is_zero());
        let x = RMat::from_fn(3, 1, |i, _| (i + 1) as f64);
        let y = a.mul(&x);
        assert_eq!((y[(0, 0)], y[(1, 0)], y[(2, 0)]), (0.1, -12.0, 3.0));
    }

    #[test]
    fn cholesky_and_lu_solve_a_laplacian() {
        // A x = b with x_i = i: b = 0 inside, b_0 = -1, b_{n-1} = n - 2 + 2 = n (for x_n = n - 1).
        let n = 50;
        let a = laplacian(n);
        let x = RMat::from_fn(n, 1, |i, _| i as f64);
        let b = a.mul(&x);
        let got = Cholesky::new(&a).unwrap().solve(&b);
        for i in 0..n {
            assert!((got[(i, 0)] - i as f64).abs() < 1e-10);
        }
        // Complex: (A + i I) z = (A + i I) x.
        let mut e: Vec<_> = a
            .entries()
            .map(|(i, j, v)| (i, j, c64::new(v, 0.0)))
            .collect();
        e.extend((0..n).map(|i| (i, i, c64::new(0.0, 1.0))));
        let lu = Lu::new(n, &e).unwrap();
        let mut z: Vec<c64> = (0..n).map(|i| c64::new(b[(i, 0)], i as f64)).collect();
        lu.solve_in_place(&mut z);
        for (i, zi) in z.iter().enumerate() {
            assert!((zi - c64::new(i as f64, 0.0)).norm() < 1e-10);
        }
        assert!(
            Cholesky::new(&a.plus(&Sparse::from_triplets(n, n, &[(3, 3, -10.0)]), 1.0)).is_err()
        );
    }
}
