//! Where a support's table is fitted and where the fit is measured.
//!
//! A sum of Maxwell branches is smooth on a logarithmic scale of frequency, one rate per
//! `(hi / lo)^(1/(m-1))`: a fit seen only at the table's knots (and three readings between each
//! two) is free to swing between knots that are decades apart (a table flat from 3000 rad/s to
//! its last point at 1e6 rad/s left 16 branches seen at 4 frequencies over two decades, whose
//! cross-coupling swung to 4e2 times the table's there). So the fit also reads the table at
//! [`PER_DECADE`] frequencies per decade of its band, and is measured at every one of them and
//! between, each relative to the support's own direct `|H|` at that frequency: a 15% error at
//! the rotor's frequencies is not hidden by a large `w C` at the top of the band.

use crate::linalg::{RMat, c64};
use crate::model::supports::{Coefficients, Matrix2};

/// Geometric samples per decade of the band: about 10 per rate spacing at the most branches
/// over the widest bands, so no branch is seen at fewer than a few frequencies.
pub const PER_DECADE: f64 = 40.0;

/// Weight of an anchor (a frequency the fit is held to, such as the spin speed of a time
/// response, whose unbalance whirls there) relative to the other samples: the fit is within
/// about 1e-7 of the table there.
pub const ANCHOR: f64 = 1e4;

/// The table's frequencies, three readings between each two, and [`PER_DECADE`] geometric
/// per decade from its first nonzero frequency to its last; increasing.
pub fn samples(freqs: &[f64]) -> Vec<f64> {
    let mut out = vec![freqs[0]];
    for w in freqs.windows(2) {
        for k in 1..=4 {
            out.push(w[0] + (w[1] - w[0]) * k as f64 / 4.0);
        }
    }
    let hi = freqs[freqs.len() - 1];
    if let Some(lo) = freqs.iter().copied().find(|&w| w > 0.0) {
        let count = ((hi / lo).log10() * PER_DECADE).ceil() as usize;
        out.extend((1..count).map(|k| lo * (hi / lo).powf(k as f64 / count as f64)));
    }
    sorted(out)
}

/// `samples` and a point between each two (geometric between positive ones): where the
/// deviation is measured.
pub fn checks(samples: &[f64]) -> Vec<f64> {
    let mut out = samples.to_vec();
    for w in samples.windows(2) {
        out.push(match w[0] > 0.0 {
            true => (w[0] * w[1]).sqrt(),
            false => 0.5 * (w[0] + w[1]),
        });
    }
    sorted(out)
}

fn sorted(mut v: Vec<f64>) -> Vec<f64> {
    v.sort_by(f64::total_cmp);
    v.dedup();
    v
}

/// `(xx, xy, yx, yy)` entry `e` of `m`.
pub fn entry(m: &Matrix2, e: usize) -> f64 {
    [m.xx, m.xy, m.yx, m.yy][e]
}

/// The table's dynamic stiffness `K + i w C - w^2 M` of coefficient `e` at `w`.
pub fn dynamic(c: &Coefficients, e: usize, w: f64) -> c64 {
    c64::new(entry(&c.k, e) - w * w * entry(&c.m, e), w * entry(&c.c, e))
}

/// The support's direct dynamic stiffness at each reading, `max(|H_xx|, |H_yy|)`, kept above
/// 1e-9 of its largest (a coefficient through zero would weigh without bound).
pub fn scales(table: &[Coefficients], at: &[f64]) -> Vec<f64> {
    let r: Vec<f64> = table
        .iter()
        .zip(at)
        .map(|(c, &w)| dynamic(c, 0, w).norm().max(dynamic(c, 3, w).norm()))
        .collect();
    let floor = 1e-9 * r.iter().copied().fold(0.0, f64::max);
    r.into_iter()
        .map(|x| x.max(floor).max(f64::MIN_POSITIVE))
        .collect()
}

/// The least-squares matrix of a fit with `rates` over `samples` and then `anchors`, the same at
/// every speed and for every coefficient: rows Re and Im at each, columns `K0`, `C0`, `G_j`
/// (unweighted: each speed weighs the rows by its own table).
pub struct Design<'a> {
    pub samples: Vec<f64>,
    /// How many of `samples`, the last, are anchors.
    pub anchors: usize,
    pub rates: &'a [f64],
    a: RMat,
}

impl<'a> Design<'a> {
    pub fn new(samples: &[f64], anchors: &[f64], rates: &'a [f64]) -> Self {
        let all: Vec<f64> = samples.iter().chain(anchors).copied().collect();
        let p = rates.len();
        let mut a = RMat::zeros(2 * all.len(), p + 2);
        for (i, &w) in all.iter().enumerate() {
            a[(2 * i, 0)] = 1.0;
            a[(2 * i + 1, 1)] = w;
            for (j, &d) in rates.iter().enumerate() {
                let den = w * w + d * d;
                a[(2 * i, 2 + j)] = w * w / den;
                a[(2 * i + 1, 2 + j)] = w * d / den;
            }
        }
        Design {
            samples: all,
            anchors: anchors.len(),
            rates,
            a,
        }
    }

    /// The rows weighted by `1 / scale` (times [`ANCHOR`] at the anchors) and the columns
    /// scaled to unit length (`K0` in N/m beside `C0` in N s/m): the matrix and the columns'
    /// scales.
    pub fn weighted(&self, scale: &[f64]) -> (RMat, Vec<f64>) {
        let first_anchor = self.samples.len() - self.anchors;
        let row = |i: usize| {
            let k = i / 2;
            let anchor = if k >= first_anchor { ANCHOR } else { 1.0 };
            anchor / scale[k]
        };
        let (rows, cols) = (self.a.nrows(), self.a.ncols());
        let a = RMat::from_fn(rows, cols, |i, j| self.a[(i, j)] * row(i));
        let norms: Vec<f64> = (0..cols)
            .map(|j| {
                let s = (0..rows).map(|i| a[(i, j)].powi(2)).sum::<f64>().sqrt();
                if s > 0.0 { s } else { 1.0 }
            })
            .collect();
        (
            RMat::from_fn(rows, cols, |i, j| a[(i, j)] / norms[j]),
            norms,
        )
    }

    /// The right-hand side of coefficient `e` weighted as [`Self::weighted`]'s rows: the
    /// table's `H - (-w^2 M0)` (Re, Im) at each sample.
    pub fn target(
        &self,
        table: &[Coefficients],
        m0: &Matrix2,
        e: usize,
        scale: &[f64],
    ) -> Vec<f64> {
        let first_anchor = self.samples.len() - self.anchors;
        self.samples
            .iter()
            .zip(table)
            .enumerate()
            .flat_map(|(k, (&w, c))| {
                let anchor = if k >= first_anchor { ANCHOR } else { 1.0 };
                let h = dynamic(c, e, w) + w * w * entry(m0, e);
                let f = anchor / scale[k];
                [h.re * f, h.im * f]
            })
            .collect()
    }
}

/// The fitted `H~(w) = K0 + i w C0 - w^2 M0 + sum_j G_j i w / (i w + d_j)` of coefficient `e`.
pub fn fitted(
    (k0, c0, m0): (f64, f64, f64),
    g: impl Iterator<Item = f64>,
    rates: &[f64],
    w: f64,
) -> c64 {
    let iw = c64::new(0.0, w);
    let mut f = c64::new(k0 - w * w * m0, w * c0);
    for (gj, &d) in g.zip(rates) {
        f += iw / (iw + d) * gj;
    }
    f
}

/// The largest `|H~ - H|` of each coefficient over `checks` (the table read there), each
/// relative to the support's direct `|H|` at that frequency.
pub fn deviation(
    checks: &[f64],
    table: &[Coefficients],
    base: &Coefficients,
    branches: &[Matrix2],
    rates: &[f64],
) -> [f64; 4] {
    let scale = scales(table, checks);
    let mut worst = [0.0_f64; 4];
    for ((&w, c), s) in checks.iter().zip(table).zip(scale) {
        for (e, d) in worst.iter_mut().enumerate() {
            let parts = (entry(&base.k, e), entry(&base.c, e), entry(&base.m, e));
            let f = fitted(parts, branches.iter().map(|g| entry(g, e)), rates, w);
            *d = d.max((f - dynamic(c, e, w)).norm() / s);
        }
    }
    worst
}
