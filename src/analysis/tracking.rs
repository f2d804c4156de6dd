//! Branch tracking: following each physical mode from speed to speed.
//!
//! Sorting poles by frequency mixes branches up wherever two of them cross or veer. Here each
//! branch carries its last mode shape and a linear prediction of its pole; the poles at the
//! next speed are assigned to branches by an optimal (Hungarian) assignment minimising
//! `(1 - MAC) + |s_predicted - s| / max(|s_predicted|, |s|)`. An assignment costing more than
//! [`GATE`] is refused: the branch gets no value at that speed (the hysteretic model leaves
//! modes undefined near critical speeds) and the pole may start a branch of its own.

use super::poles::PoleSet;
use crate::linalg::{self, c64};

/// Largest cost of an accepted assignment. A forward and a backward pole of the same shape at
/// `+-omega` cost 2; the same pole predicted within 50% with the same shape costs < 0.5.
pub const GATE: f64 = 1.5;

/// One branch: its pole at each speed, `None` where it has none.
#[derive(Debug, Clone)]
pub struct Track {
    pub values: Vec<Option<c64>>,
}

struct State {
    shape: Vec<c64>,
    last: (f64, c64),
    before: Option<(f64, c64)>,
    values: Vec<Option<c64>>,
}

impl State {
    fn predict(&self, speed: f64) -> c64 {
        match self.before {
            Some((w0, s0)) if self.last.0 != w0 => {
                let t = (speed - self.last.0) / (self.last.0 - w0);
                self.last.1 + (self.last.1 - s0) * t
            }
            _ => self.last.1,
        }
    }
}

/// Follows branches through pole sets given one speed at a time, in order, keeping only each
/// branch's values and its last shape (a sweep never holds all its pole sets).
pub struct Tracker {
    branches: Vec<State>,
    speeds: usize,
    max_branches: usize,
}

impl Tracker {
    /// A tracker of at most `max_branches` branches.
    pub fn new(max_branches: usize) -> Self {
        Tracker {
            branches: vec![],
            speeds: 0,
            max_branches,
        }
    }

    /// Assigns the rotor poles of the next speed to branches.
    pub fn push(&mut self, set: &PoleSet) {
        let k = self.speeds;
        self.speeds += 1;
        let speed = set.speed;
        let poles = &set.rotor;
        let branches = &mut self.branches;
        let mut taken = vec![false; poles.len()];
        let mut assigned: Vec<Option<usize>> = vec![None; branches.len()];
        if !branches.is_empty() && !poles.is_empty() {
            let shapes: Vec<&[c64]> = branches.iter().map(|b| &b.shape[..]).collect();
            let pole_shapes: Vec<&[c64]> = poles.iter().map(|p| &p.shape[..]).collect();
            let macs = linalg::mac_matrix(&shapes, &pole_shapes);
            let cost: Vec<Vec<f64>> = branches
                .iter()
                .zip(&macs)
                .map(|(b, macs)| {
                    let pred = b.predict(speed);
                    poles
                        .iter()
                        .zip(macs)
                        .map(|(p, mac)| {
                            let scale = pred.norm().max(p.s.norm()).max(f64::MIN_POSITIVE);
                            (1.0 - mac) + (pred - p.s).norm() / scale
                        })
                        .collect()
                })
                .collect();
            for (bi, pi) in assignment(&cost).into_iter().enumerate() {
                if let Some(pi) = pi
                    && cost[bi][pi] <= GATE
                {
                    assigned[bi] = Some(pi);
                    taken[pi] = true;
                }
            }
        }
        for (b, a) in branches.iter_mut().zip(&assigned) {
            match a {
                Some(pi) => {
                    let p = &poles[*pi];
                    b.before = Some(b.last);
                    b.last = (speed, p.s);
                    b.shape.clone_from(&p.shape);
                    b.values.push(Some(p.s));
                }
                None => b.values.push(None),
            }
        }
        for (pi, p) in poles.iter().enumerate() {
            if !taken[pi] && branches.len() < self.max_branches {
                let mut values = vec![None; k];
                values.push(Some(p.s));
                branches.push(State {
                    shape: p.shape.clone(),
                    last: (speed, p.s),
                    before: None,
                    values,
                });
            }
        }
    }

    /// The branches.
    pub fn finish(self) -> Vec<Track> {
        self.branches
            .into_iter()
            .map(|b| Track { values: b.values })
            .collect()
    }
}

/// Tracks the rotor poles of consecutive pole sets into at most `max_branches` branches.
pub fn track(sets: &[PoleSet], max_branches: usize) -> Vec<Track> {
    let mut t = Tracker::new(max_branches);
    for set in sets {
        t.push(set);
    }
    t.finish()
}

/// Minimum-cost assignment of rows to columns (Hungarian algorithm with potentials,
/// O(n^2 m)); rectangular matrices allowed. Returns the column of each row, if any.
pub fn assignment(cost: &[Vec<f64>]) -> Vec<Option<usize>> {
    let rows = cost.len();
    let cols = cost.first().map_or(0, |r| r.len());
    if rows == 0 || cols == 0 {
        return vec![None; rows];
    }
    if rows > cols {
        let t: Vec<Vec<f64>> = (0..cols)
            .map(|j| (0..rows).map(|i| cost[i][j]).collect())
            .collect();
        let col_to_row = assignment(&t);
        let mut out = vec![None; rows];
        for (j, i) in col_to_row.into_iter().enumerate() {
            if let Some(i) = i {
                out[i] = Some(j);
            }
        }
        return out;
    }
    let (n, m) = (rows, cols);
    let inf = f64::INFINITY;
    let mut u = vec![0.0; n + 1];
    let mut v = vec![0.0; m + 1];
    let mut p = vec![0usize; m + 1];
    let mut way = vec![0usize; m + 1];
    for i in 1..=n {
        p[0] = i;
        let mut j0 = 0;
        let mut minv = vec![inf; m + 1];
        let mut used = vec![false; m + 1];
        loop {
            used[j0] = true;
            let i0 = p[j0];
            let mut delta = inf;
            let mut j1 = 0;
            for j in 1..=m {
                if !used[j] {
                    let cur = cost[i0 - 1][j - 1] - u[i0] - v[j];
                    if cur < minv[j] {
                        minv[j] = cur;
                        way[j] = j0;
                    }
                    if minv[j] < delta {
                        delta = minv[j];
                        j1 = j;
                    }
                }
            }
            for j in 0..=m {
                if used[j] {
                    u[p[j]] += delta;
                    v[j] -= delta;
                } else {
                    minv[j] -= delta;
                }
            }
            j0 = j1;
            if p[j0] == 0 {
                break;
            }
        }
        loop {
            let j1 = way[j0];
            p[j0] = p[j1];
            j0 = j1;
            if j0 == 0 {
                break;
            }
        }
    }
    let mut out = vec![None; n];
    for j in 1..=m {
        if p[j] != 0 {
            out[p[j] - 1] = Some(j - 1);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn total(cost: &[Vec<f64>], a: &[Option<usize>]) -> f64 {
        a.iter()
            .enumerate()
            .filter_map(|(i, j)| j.map(|j| cost[i][j]))
            .sum()
    }

    #[test]
    fn assignment_is_optimal_where_greedy_is_not() {
        // Greedy takes (0,0)=1 then (1,1)=10: 11. Optimal: (0,1)+(1,0) = 2 + 2 = 4.
        let cost = vec![vec![1.0, 2.0], vec![2.0, 10.0]];
        let a = assignment(&cost);
        assert_eq!(a, vec![Some(1), Some(0)]);
        assert_eq!(total(&cost, &a), 4.0);
    }

    #[test]
    fn assignment_matches_brute_force_on_rectangular_matrices() {
        // Deterministic pseudo-random 3x5 and 5x3 costs against all permutations.
        let mut seed = 12345u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..20 {
            let cost: Vec<Vec<f64>> = (0..3).map(|_| (0..5).map(|_| rnd()).collect()).collect();
            let a = assignment(&cost);
            let mut best = f64::INFINITY;
            for x in 0..5 {
                for y in 0..5 {
                    for z in 0..5 {
                        if x != y && y != z && x != z {
                            best = best.min(cost[0][x] + cost[1][y] + cost[2][z]);
                        }
                    }
                }
            }
            assert!((total(&cost, &a) - best).abs() < 1e-12);
            let t: Vec<Vec<f64>> = (0..5)
                .map(|j| (0..3).map(|i| cost[i][j]).collect())
                .collect();
            assert!((total(&t, &assignment(&t)) - best).abs() < 1e-12);
        }
    }
}
