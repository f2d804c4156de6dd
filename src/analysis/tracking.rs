//! Branch tracking: following each physical mode from speed to speed.
//!
//! Sorting poles by frequency mixes branches up wherever two of them cross or veer. Here each
//! branch carries its last mode shape and a linear prediction of its pole; the poles at the
//! next speed are assigned to branches by an optimal (Hungarian) assignment minimising
//! `(1 - MAC) + |s_predicted - s| / max(|s_predicted|, |s|)`. An assignment costing more than
//! [`GATE`] is refused: the branch gets no value at that speed (the hysteretic model leaves
//! modes undefined near critical speeds) and the pole may start a branch of its own.
//!
//! A branch is a mode, not a sign of frequency. In doubled coordinates each mode is the mirror
//! pair `(s, conj s)`, and the member a pole set reports (the one whose `r` part is the larger)
//! changes from `s` to `conj s` where the whirl ratio of a nearly planar mode passes through
//! zero: the reported frequency changes sign and the shape swaps its halves. Branches are
//! therefore matched on the member with `omega >= 0` (continuous through that point), and keep
//! at each speed the member the pole set reported, with its whirl ratio.
//!
//! Where the assignment chosen and the swap of two of its branches cost nearly the same (two
//! branches veering or crossing with similar shapes), the hand-over is ambiguous: it is
//! recorded, not guessed silently.

use super::poles::{Pole, PoleSet};
use crate::linalg::{self, c64};

/// Largest cost of an accepted assignment. A forward and a backward pole of the same shape at
/// `+-omega` cost 2; the same pole predicted within 50% with the same shape costs < 0.5.
pub const GATE: f64 = 1.5;

/// A swap of two assigned branches costing at most this much more than the assignment chosen
/// makes the hand-over ambiguous (costs of a clear continuation are below 0.05).
pub const AMBIGUOUS: f64 = 0.1;

/// One branch: its pole at each speed, `None` where it has none.
#[derive(Debug, Clone)]
pub struct Track {
    /// The pole as its pole set reported it (see the module docs).
    pub values: Vec<Option<c64>>,
    /// Its whirl ratio at each speed.
    pub ratios: Vec<Option<f64>>,
    /// Its shape at its first speed, as reported.
    pub shape: Vec<c64>,
}

/// Two branches (indices into [`Tracker::finish`]'s list) whose hand-over at a speed (index)
/// was ambiguous.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Ambiguity {
    pub speed: usize,
    pub branches: (usize, usize),
}

struct State {
    /// Shape of the matched (`omega >= 0` when mirrored) member at the last speed.
    shape: Vec<c64>,
    last: (f64, c64),
    before: Option<(f64, c64)>,
    values: Vec<Option<c64>>,
    ratios: Vec<Option<f64>>,
    first_shape: Vec<c64>,
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
    ambiguities: Vec<Ambiguity>,
}

/// The member of a pole's mirror pair that branches are matched on: itself, or in doubled
/// coordinates the one with `omega >= 0`.
fn matched(p: &Pole, doubled: bool) -> (c64, std::borrow::Cow<'_, [c64]>) {
    if doubled && p.s.im < 0.0 {
        let m = p.mirror();
        (m.s, std::borrow::Cow::Owned(m.shape))
    } else {
        (p.s, std::borrow::Cow::Borrowed(&p.shape[..]))
    }
}

impl Tracker {
    /// A tracker of at most `max_branches` branches alive at one speed.
    pub fn new(max_branches: usize) -> Self {
        Tracker {
            branches: vec![],
            speeds: 0,
            max_branches,
            ambiguities: vec![],
        }
    }

    /// Assigns the rotor poles of the next speed to branches.
    pub fn push(&mut self, set: &PoleSet) {
        let k = self.speeds;
        self.speeds += 1;
        let speed = set.speed;
        let poles = &set.rotor;
        let m: Vec<(c64, std::borrow::Cow<'_, [c64]>)> =
            poles.iter().map(|p| matched(p, set.doubled)).collect();
        let branches = &mut self.branches;
        let mut taken = vec![false; poles.len()];
        let mut assigned: Vec<Option<usize>> = vec![None; branches.len()];
        if !branches.is_empty() && !poles.is_empty() {
            let shapes: Vec<&[c64]> = branches.iter().map(|b| &b.shape[..]).collect();
            let pole_shapes: Vec<&[c64]> = m.iter().map(|p| &p.1[..]).collect();
            let macs = linalg::mac_matrix(&shapes, &pole_shapes);
            let cost: Vec<Vec<f64>> = branches
                .iter()
                .zip(&macs)
                .map(|(b, macs)| {
                    let pred = b.predict(speed);
                    m.iter()
                        .zip(macs)
                        .map(|((s, _), mac)| {
                            let scale = pred.norm().max(s.norm()).max(f64::MIN_POSITIVE);
                            (1.0 - mac) + (pred - s).norm() / scale
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
            self.ambiguities
                .extend(ambiguous(&cost, &assigned).into_iter().map(|b| Ambiguity {
                    speed: k,
                    branches: b,
                }));
        }
        for (b, a) in branches.iter_mut().zip(&assigned) {
            match a {
                Some(pi) => {
                    let p = &poles[*pi];
                    b.before = Some(b.last);
                    b.last = (speed, m[*pi].0);
                    b.shape.clear();
                    b.shape.extend_from_slice(&m[*pi].1);
                    b.values.push(Some(p.s));
                    b.ratios.push(Some(p.whirl_ratio));
                }
                None => {
                    b.values.push(None);
                    b.ratios.push(None);
                }
            }
        }
        // A pole no branch takes starts one, as long as the branches alive at this speed are
        // fewer than the model's poles: a branch that ended (two real poles that met and left
        // as a complex pair) must not keep the pole it became from being followed.
        let mut live = assigned.iter().flatten().count();
        for (pi, p) in poles.iter().enumerate() {
            if !taken[pi] && live < self.max_branches {
                live += 1;
                let mut values = vec![None; k];
                values.push(Some(p.s));
                let mut ratios = vec![None; k];
                ratios.push(Some(p.whirl_ratio));
                branches.push(State {
                    shape: m[pi].1.to_vec(),
                    last: (speed, m[pi].0),
                    before: None,
                    values,
                    ratios,
                    first_shape: p.shape.clone(),
                });
            }
        }
    }

    /// The branches, and the ambiguous hand-overs between them.
    pub fn finish(self) -> (Vec<Track>, Vec<Ambiguity>) {
        let tracks = self
            .branches
            .into_iter()
            .map(|b| Track {
                values: b.values,
                ratios: b.ratios,
                shape: b.first_shape,
            })
            .collect();
        (tracks, self.ambiguities)
    }
}

/// Pairs of assigned branches whose swap costs at most [`AMBIGUOUS`] more than the choice made
/// (both swapped assignments within the gate).
fn ambiguous(cost: &[Vec<f64>], assigned: &[Option<usize>]) -> Vec<(usize, usize)> {
    let mut out = vec![];
    for (a, pa) in assigned.iter().enumerate() {
        let Some(pa) = *pa else { continue };
        for (b, pb) in assigned.iter().enumerate().skip(a + 1) {
            let Some(pb) = *pb else { continue };
            let (swap_a, swap_b) = (cost[a][pb], cost[b][pa]);
            if swap_a <= GATE
                && swap_b <= GATE
                && swap_a + swap_b <= cost[a][pa] + cost[b][pb] + AMBIGUOUS
            {
                out.push((a, b));
            }
        }
    }
    out
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

    fn set(speed: f64, poles: &[(c64, usize)]) -> PoleSet {
        let pole = |&(s, at): &(c64, usize)| Pole {
            s,
            whirl: super::super::poles::Whirl::Forward,
            shape: (0..4)
                .map(|i| c64::new(if i == at { 1.0 } else { 0.0 }, 0.0))
                .collect(),
            whirl_ratio: 1.0,
        };
        PoleSet {
            speed,
            rotor: poles.iter().map(pole).collect(),
            internal: vec![],
            expected_rotor: 2,
            doubled: false,
        }
    }

    #[test]
    fn poles_that_no_ended_branch_takes_start_branches_of_their_own() {
        // Two branches of a two-pole model end (their poles leave, as two real poles that meet
        // and leave as a complex pair do) and two poles no branch can take appear: they start
        // two branches, though four were made in all.
        let mut t = Tracker::new(2);
        t.push(&set(
            0.0,
            &[(c64::new(-100.0, 0.0), 0), (c64::new(-300.0, 0.0), 1)],
        ));
        let pair = [(c64::new(-50.0, 500.0), 2), (c64::new(-50.0, -500.0), 3)];
        t.push(&set(1.0, &pair));
        let (tracks, _) = t.finish();
        assert_eq!(tracks.len(), 4);
        for (track, (s, _)) in tracks[2..].iter().zip(pair) {
            assert_eq!(track.values, vec![None, Some(s)]);
        }
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
