//! Least squares, plain and with some unknowns kept nonnegative.
//!
//! `min |A x - b|` by Householder QR (faer). With bounds `x_i >= 0` on the unknowns marked
//! constrained, Lawson and Hanson's active-set method (Solving Least Squares Problems, 1974,
//! ch. 23), the free unknowns always in its passive set: from the least-squares fit of the free
//! unknowns alone, the constrained unknown whose gradient most wants to grow enters; an inner
//! loop steps back to the feasible set where an entered one would go negative. Each least
//! squares is on the passive columns only.

use super::{LinalgError, RMat};
use faer::linalg::solvers::SolveLstsq;

/// `argmin |A x - b|` (`A` with at least as many rows as columns, full column rank).
pub fn least_squares(a: &RMat, b: &[f64]) -> Result<Vec<f64>, LinalgError> {
    if a.ncols() == 0 {
        return Ok(vec![]);
    }
    let rhs = RMat::from_fn(b.len(), 1, |i, _| b[i]);
    let x = a.qr().solve_lstsq(&rhs);
    let x: Vec<f64> = (0..a.ncols()).map(|i| x[(i, 0)]).collect();
    if x.iter().all(|v| v.is_finite()) {
        Ok(x)
    } else {
        Err(LinalgError::NonFinite)
    }
}

/// `argmin |A x - b|` subject to `x_i >= 0` where `constrained[i]`.
pub fn bounded_least_squares(
    a: &RMat,
    b: &[f64],
    constrained: &[bool],
) -> Result<Vec<f64>, LinalgError> {
    let n = a.ncols();
    // Least squares on the passive columns, zero elsewhere.
    let solve = |passive: &[bool]| -> Result<Vec<f64>, LinalgError> {
        let cols: Vec<usize> = (0..n).filter(|&j| passive[j]).collect();
        let sub = RMat::from_fn(a.nrows(), cols.len(), |i, k| a[(i, cols[k])]);
        let z = least_squares(&sub, b)?;
        let mut out = vec![0.0; n];
        for (k, &j) in cols.iter().enumerate() {
            out[j] = z[k];
        }
        Ok(out)
    };
    let norm_b = b.iter().map(|v| v * v).sum::<f64>().sqrt();
    let norm_a = (0..n)
        .map(|j| {
            (0..a.nrows())
                .map(|i| a[(i, j)].powi(2))
                .sum::<f64>()
                .sqrt()
        })
        .fold(0.0, f64::max);
    let tol = 1e-12 * norm_a * norm_b.max(f64::MIN_POSITIVE);
    let mut passive: Vec<bool> = constrained.iter().map(|c| !c).collect();
    let mut x = solve(&passive)?;
    for _ in 0..3 * n + 3 {
        // The gradient -A^T (A x - b) on the constrained unknowns held at zero.
        let r: Vec<f64> = (0..a.nrows())
            .map(|i| b[i] - (0..n).map(|j| a[(i, j)] * x[j]).sum::<f64>())
            .collect();
        let entering = (0..n)
            .filter(|&j| !passive[j])
            .map(|j| (j, (0..a.nrows()).map(|i| a[(i, j)] * r[i]).sum::<f64>()))
            .filter(|&(_, g)| g > tol)
            .max_by(|p, q| p.1.total_cmp(&q.1));
        let Some((j, _)) = entering else {
            return Ok(x);
        };
        passive[j] = true;
        loop {
            let z = solve(&passive)?;
            let bad: Vec<usize> = (0..n)
                .filter(|&i| passive[i] && constrained[i] && z[i] <= 0.0)
                .collect();
            if bad.is_empty() {
                x = z;
                break;
            }
            let alpha = bad
                .iter()
                .map(|&i| x[i] / (x[i] - z[i]))
                .fold(f64::INFINITY, f64::min);
            for i in 0..n {
                x[i] += alpha * (z[i] - x[i]);
                if passive[i] && constrained[i] && x[i] <= 1e-15 * norm_b.max(1.0) {
                    passive[i] = false;
                    x[i] = 0.0;
                }
            }
            if !passive.iter().zip(constrained).any(|(p, c)| *p && *c) {
                break;
            }
        }
    }
    Ok(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_through_three_points_by_hand() {
        // y = 1 + 2 t at t = 0, 1, 2 with y = (1.1, 2.9, 5.1): the normal equations give
        // slope 2.0, intercept 1.0333...
        let a = RMat::from_fn(3, 2, |i, j| if j == 0 { 1.0 } else { i as f64 });
        let x = least_squares(&a, &[1.1, 2.9, 5.1]).unwrap();
        assert!((x[0] - 31.0 / 30.0).abs() < 1e-14, "{x:?}");
        assert!((x[1] - 2.0).abs() < 1e-14, "{x:?}");
    }

    #[test]
    fn a_negative_slope_is_held_at_zero_and_the_mean_fits_the_rest() {
        // y = (3, 2, 1) at t = 0, 1, 2: free intercept, slope >= 0 -> slope 0, intercept 2.
        let a = RMat::from_fn(3, 2, |i, j| if j == 0 { 1.0 } else { i as f64 });
        let x = bounded_least_squares(&a, &[3.0, 2.0, 1.0], &[false, true]).unwrap();
        assert_eq!(x[1], 0.0);
        assert!((x[0] - 2.0).abs() < 1e-14, "{x:?}");
        // Unconstrained it is the line itself.
        let x = bounded_least_squares(&a, &[3.0, 2.0, 1.0], &[false, false]).unwrap();
        assert!(
            (x[0] - 3.0).abs() < 1e-14 && (x[1] + 1.0).abs() < 1e-14,
            "{x:?}"
        );
    }

    #[test]
    fn nonnegative_least_squares_by_hand() {
        // [[1, 0], [1, 0], [0, 1]] x = (2, 1, 1): x = (1.5, 1), both positive. And
        // [[1, 2], [3, 4], [5, 6]] x = (-1, 0, 1) is solved exactly by (2, -1.5); with x >= 0
        // the best is the first column alone, x1 = a1.b / a1.a1 = 4/35 (residual 1.543 < the
        // second column's 1.714).
        let a = RMat::from_fn(3, 2, |i, j| [[1.0, 0.0], [1.0, 0.0], [0.0, 1.0]][i][j]);
        let x = bounded_least_squares(&a, &[2.0, 1.0, 1.0], &[true, true]).unwrap();
        assert!(
            (x[0] - 1.5).abs() < 1e-14 && (x[1] - 1.0).abs() < 1e-14,
            "{x:?}"
        );
        let a = RMat::from_fn(3, 2, |i, j| [[1.0, 2.0], [3.0, 4.0], [5.0, 6.0]][i][j]);
        let x = bounded_least_squares(&a, &[-1.0, 0.0, 1.0], &[true, true]).unwrap();
        assert!((x[0] - 4.0 / 35.0).abs() < 1e-14 && x[1] == 0.0, "{x:?}");
    }
}
