//! Guyan (static) reduction.
//!
//! Partition the degrees of freedom into kept `m` and condensed `s`; from the total stiffness,
//! `q = T q_m` with `T = [I; -K_ss^-1 K_sm]`, and every matrix `X` (mass, each stiffness,
//! each damping, gyroscopic, each imaginary stiffness) becomes `T^T X T` with the same `T`.
//! Exact for the statics, and for massless condensed coordinates.

use crate::linalg::{self, LinalgError, RMat, Sparse};
use crate::system::RotorSystem;

/// Reduces `system` to the degrees of freedom where `keep` is true.
pub fn reduce(system: &RotorSystem, keep: &[bool]) -> Result<RotorSystem, LinalgError> {
    let n = system.n();
    let kept: Vec<usize> = (0..n).filter(|&i| keep[i]).collect();
    let cond: Vec<usize> = (0..n).filter(|&i| !keep[i]).collect();
    let k = system.stiffness().to_dense();
    let kss = RMat::from_fn(cond.len(), cond.len(), |i, j| k[(cond[i], cond[j])]);
    let ksm = RMat::from_fn(cond.len(), kept.len(), |i, j| k[(cond[i], kept[j])]);
    let x = linalg::solve_real_matrix(&kss, &ksm)?;
    let mut t = RMat::zeros(n, kept.len());
    for (j, &i) in kept.iter().enumerate() {
        t[(i, j)] = 1.0;
    }
    for (r, &i) in cond.iter().enumerate() {
        for j in 0..kept.len() {
            t[(i, j)] = -x[(r, j)];
        }
    }
    let red = |a: &Sparse| Sparse::from_dense(&symmetrise(&(t.transpose() * a.to_dense() * &t)));
    Ok(RotorSystem {
        mass: red(&system.mass),
        gyroscopic: red(&system.gyroscopic),
        stiffness_rotating: red(&system.stiffness_rotating),
        stiffness_nonrotating: red(&system.stiffness_nonrotating),
        damping_rotating: red(&system.damping_rotating),
        damping_nonrotating: red(&system.damping_nonrotating),
        hysteretic_rotating: red(&system.hysteretic_rotating),
        hysteretic_nonrotating: red(&system.hysteretic_nonrotating),
        // Not symmetric: projected as it is.
        circulatory: Sparse::from_dense(&(t.transpose() * system.circulatory.to_dense() * &t)),
        dofs: kept.iter().map(|&i| system.dofs[i]).collect(),
        supports: system
            .supports
            .iter()
            .filter_map(|p| {
                // Supports are placed after the Guyan reduction (see `fem::assembly`).
                use crate::system::Placement;
                let new = |d: usize| kept.iter().position(|&i| i == d);
                let at = match p.at {
                    Placement::Dof(d) => Placement::Dof(new(d)?),
                    Placement::Between(a, b) => Placement::Between(new(a)?, new(b)?),
                    Placement::Shape(_) => return None,
                };
                Some(crate::system::PlacedSupport {
                    at,
                    support: p.support.clone(),
                })
            })
            .collect(),
    })
}

fn symmetrise(a: &RMat) -> RMat {
    RMat::from_fn(a.nrows(), a.ncols(), |i, j| 0.5 * (a[(i, j)] + a[(j, i)]))
}
