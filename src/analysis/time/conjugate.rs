//! The conjugate symmetry of doubled coordinates, for the exponential integrator.
//!
//! In doubled coordinates the state `z = [v; q]` holds `(r, conj r)` in each block, so a
//! physical (real) motion satisfies `z = P conj z`, with `P` the involution that swaps `r` and
//! `conj r`; the state matrix does too: `A = P conj(A) P`. In the real coordinates
//! `x = T z` (`x_i = (z_i + z_Pi) / 2`, `x_Pi = (z_i - z_Pi) / 2i` for each pair `i < Pi`)
//! `A_r = T A T^-1` is real, and its eigenvalues come as conjugate pairs with conjugate vectors
//! (from the real Schur form, which costs less than the complex solve). The modal
//! coordinates `w = V^-1 z` of a real motion then pair as well, `w_{j+1} = conj w_j`, so only
//! one of each pair needs integrating: half the state and half of each product with the
//! coupling matrices (the run-ups of cross-coupled rotors).

use crate::linalg::{self, CMat, Eigen, LinalgError, RMat, c64};

/// Largest imaginary part of `T A T^-1`, relative to its largest entry, taken for round-off.
const REAL: f64 = 1e-12;

/// The involution `P` of a state of doubled coordinates.
pub struct Pairing {
    partner: Vec<usize>,
}

impl Pairing {
    /// For a state `[v; q]` of `2 N` entries, `N = 2 n` (`(r, conj r)` in each block), and no
    /// internal coordinates.
    pub fn doubled(big_n: usize, size: usize) -> Option<Self> {
        if size != 2 * big_n || !big_n.is_multiple_of(2) || big_n == 0 {
            return None;
        }
        let n = big_n / 2;
        let partner = (0..size)
            .map(|i| match i % big_n < n {
                true => i + n,
                false => i - n,
            })
            .collect();
        Some(Self { partner })
    }

    fn pairs(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        self.partner
            .iter()
            .enumerate()
            .filter(|&(i, &p)| i < p)
            .map(|(i, &p)| (i, p))
    }

    /// `T A T^-1`, if real to round-off (else `a` lacks the symmetry).
    pub fn real_form(&self, a: &CMat) -> Option<RMat> {
        let m = a.nrows();
        let i1 = c64::new(0.0, 1.0);
        // A T^-1: column i of T^-1 is e_i + e_Pi, column Pi is i (e_i - e_Pi).
        let mut right = CMat::zeros(m, m);
        for (i, p) in self.pairs() {
            for k in 0..m {
                right[(k, i)] = a[(k, i)] + a[(k, p)];
                right[(k, p)] = (a[(k, i)] - a[(k, p)]) * i1;
            }
        }
        // T (A T^-1): row i of T is (e_i + e_Pi) / 2, row Pi is (e_i - e_Pi) / 2i.
        let mut out = RMat::zeros(m, m);
        let (mut imag, mut scale) = (0.0f64, 0.0f64);
        for (i, p) in self.pairs() {
            for k in 0..m {
                let x = (right[(i, k)] + right[(p, k)]) * 0.5;
                let y = (right[(i, k)] - right[(p, k)]) * c64::new(0.0, -0.5);
                out[(i, k)] = x.re;
                out[(p, k)] = y.re;
                imag = imag.max(x.im.abs()).max(y.im.abs());
                scale = scale.max(x.re.abs()).max(y.re.abs());
            }
        }
        (imag <= REAL * scale).then_some(out)
    }

    /// `T^-1 U`: vectors of the real form back in doubled coordinates.
    pub fn to_doubled(&self, u: &CMat) -> CMat {
        let mut v = CMat::zeros(u.nrows(), u.ncols());
        let i1 = c64::new(0.0, 1.0);
        for (i, p) in self.pairs() {
            for j in 0..u.ncols() {
                v[(i, j)] = u[(i, j)] + u[(p, j)] * i1;
                v[(p, j)] = u[(i, j)] - u[(p, j)] * i1;
            }
        }
        v
    }

    /// The eigendecomposition of `a` through its real form, with the modal coordinates to
    /// integrate (one of each conjugate pair, every real one): `None` where `a` lacks the
    /// symmetry.
    pub fn eigen(&self, a: &CMat) -> Option<Result<(Eigen, Halves), LinalgError>> {
        let real = self.real_form(a)?;
        Some(linalg::eigen_real(&real).map(|e| {
            let halves = Halves::of(&e.values);
            let vectors = self.to_doubled(&e.vectors);
            (
                Eigen {
                    values: e.values,
                    vectors,
                },
                halves,
            )
        }))
    }
}

/// Which modal coordinates are integrated: `kept[k]` is a full index; `full[j] = (k, conj)`
/// gives coordinate `j` from the kept `k` (conjugated for the second of a pair).
pub struct Halves {
    pub kept: Vec<usize>,
    pub full: Vec<(usize, bool)>,
}

impl Halves {
    /// Every coordinate kept.
    pub fn all(size: usize) -> Self {
        Self {
            kept: (0..size).collect(),
            full: (0..size).map(|j| (j, false)).collect(),
        }
    }

    /// From eigenvalues ordered as [`linalg::eigen_real`] gives them.
    fn of(values: &[c64]) -> Self {
        let (mut kept, mut full) = (vec![], vec![(0, false); values.len()]);
        let mut j = 0;
        while j < values.len() {
            let k = kept.len();
            kept.push(j);
            full[j] = (k, false);
            if values[j].im != 0.0 && values.get(j + 1) == Some(&values[j].conj()) {
                full[j + 1] = (k, true);
                j += 2;
            } else {
                j += 1;
            }
        }
        Self { kept, full }
    }

    /// The full modal coordinates from the kept ones, into `out`.
    pub fn expand(&self, w: &[c64], out: &mut [c64]) {
        for (o, &(k, conj)) in out.iter_mut().zip(&self.full) {
            *o = if conj { w[k].conj() } else { w[k] };
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A doubled 2-coordinate state matrix (n = 1, N = 2): the real form of a damped
    /// oscillator with gyroscopic coupling, written in `(r, conj r)`; its eigenvalues through
    /// the real form equal the complex solve's, and the kept half holds one of each pair.
    #[test]
    fn real_form_of_a_doubled_oscillator() {
        // M r'' + (C - i G) r' + K r = 0 with m = 2 kg, c = 3 N s/m, g = 5, k = 800 N/m, and
        // a cross stiffness coupling r to conj r (anisotropy) of 100 N/m.
        let (m, c, g, k, d) = (2.0, 3.0, 5.0, 800.0, 100.0);
        let z = c64::new(0.0, 0.0);
        let re = |x: f64| c64::new(x, 0.0);
        // State [v_r, v_c, r, c]: v' = -M^-1 (C' v + K' q), q' = v.
        let cv = [[c64::new(c, -g), z], [z, c64::new(c, g)]];
        let kq = [[re(k), re(d)], [re(d), re(k)]];
        let a = CMat::from_fn(4, 4, |i, j| match (i < 2, j < 2) {
            (true, true) => -cv[i][j] / m,
            (true, false) => -kq[i][j - 2] / m,
            (false, true) => re(if i - 2 == j { 1.0 } else { 0.0 }),
            (false, false) => z,
        });
        let p = Pairing::doubled(2, 4).unwrap();
        let (e, halves) = p.eigen(&a).unwrap().unwrap();
        let mut exact = linalg::eigenvalues(&a).unwrap();
        for s in &e.values {
            let i = (0..exact.len())
                .min_by(|&x, &y| (exact[x] - s).norm().total_cmp(&(exact[y] - s).norm()))
                .unwrap();
            assert!(
                (exact[i] - s).norm() <= 1e-12 * s.norm(),
                "{s} vs {exact:?}"
            );
            exact.remove(i);
        }
        // A V = V diag(s) in doubled coordinates.
        let av = &a * &e.vectors;
        for j in 0..4 {
            for i in 0..4 {
                let r = av[(i, j)] - e.vectors[(i, j)] * e.values[j];
                assert!(r.norm() <= 1e-12 * e.values[j].norm(), "{r}");
            }
        }
        assert_eq!(halves.kept.len(), 2);
        assert_eq!(halves.full.iter().filter(|f| f.1).count(), 2);
        // Not doubled: no pairing (a state matrix without the symmetry).
        let mut b = a.clone();
        b[(0, 2)] += c64::new(0.0, 1.0);
        assert!(p.real_form(&b).is_none());
    }
}
