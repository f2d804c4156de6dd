//! The samples of a design: the grid's combinations, or draws of the distributions from a
//! seeded ChaCha stream (Monte Carlo: independent; Latin hypercube: one draw per stratum of
//! each parameter, the strata paired by random permutations).

use rand_chacha::ChaCha8Rng;
use rand_chacha::rand_core::{RngCore, SeedableRng};
use serde_json::{Number, Value};

use super::dist::Dist;

/// A uniform draw in (0, 1): 53 random bits, centred in their interval (never 0 or 1).
fn uniform(rng: &mut ChaCha8Rng) -> f64 {
    ((rng.next_u64() >> 11) as f64 + 0.5) / (1u64 << 53) as f64
}

/// A uniform index below `n` (rejection sampling: no modulo bias).
fn below(rng: &mut ChaCha8Rng, n: usize) -> usize {
    let n = n as u64;
    let zone = u64::MAX - u64::MAX % n;
    loop {
        let x = rng.next_u64();
        if x < zone {
            return (x % n) as usize;
        }
    }
}

/// Every combination of the lists, the first list varying slowest.
pub fn grid(lists: &[Vec<Value>]) -> Vec<Vec<Value>> {
    let total: usize = lists.iter().map(Vec::len).product();
    (0..total)
        .map(|mut k| {
            let mut row = vec![Value::Null; lists.len()];
            for (j, list) in lists.iter().enumerate().rev() {
                row[j] = list[k % list.len()].clone();
                k /= list.len();
            }
            row
        })
        .collect()
}

/// The probabilities `u` of `n` samples of `dims` parameters: Monte Carlo, or a Latin
/// hypercube (`(stratum + draw) / n`, each stratum once per parameter).
pub fn probabilities(dims: usize, n: usize, seed: u64, latin: bool) -> Vec<Vec<f64>> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut u = vec![vec![0.0; dims]; n];
    if !latin {
        for row in &mut u {
            for x in row.iter_mut() {
                *x = uniform(&mut rng);
            }
        }
        return u;
    }
    for j in 0..dims {
        // Fisher-Yates: a uniformly random permutation of the strata.
        let mut strata: Vec<usize> = (0..n).collect();
        for i in (1..n).rev() {
            strata.swap(i, below(&mut rng, i + 1));
        }
        for (row, s) in u.iter_mut().zip(strata) {
            row[j] = (s as f64 + uniform(&mut rng)) / n as f64;
        }
    }
    u
}

/// The values of random samples: each parameter's distribution at its probability.
pub fn draws(dists: &[Dist], n: usize, seed: u64, latin: bool) -> Vec<Vec<Value>> {
    probabilities(dists.len(), n, seed, latin)
        .into_iter()
        .map(|row| {
            row.iter()
                .zip(dists)
                .map(|(&p, d)| Number::from_f64(d.at(p)).map_or(Value::Null, Value::Number))
                .collect()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn the_grid_is_the_product_first_slowest() {
        let g = grid(&[
            vec![json!(1), json!(2)],
            vec![json!("a"), json!("b"), json!("c")],
        ]);
        assert_eq!(g.len(), 6);
        assert_eq!(g[0], vec![json!(1), json!("a")]);
        assert_eq!(g[2], vec![json!(1), json!("c")]);
        assert_eq!(g[3], vec![json!(2), json!("a")]);
    }

    #[test]
    fn latin_hypercube_has_one_sample_per_stratum_and_repeats_with_its_seed() {
        let n = 97;
        let u = probabilities(3, n, 42, true);
        for j in 0..3 {
            let mut seen = vec![0; n];
            for row in &u {
                seen[(row[j] * n as f64).floor() as usize] += 1;
            }
            assert!(seen.iter().all(|&c| c == 1), "parameter {j}: {seen:?}");
        }
        assert_eq!(u, probabilities(3, n, 42, true));
        assert_ne!(u, probabilities(3, n, 43, true));
        let mc = probabilities(2, 1000, 7, false);
        assert_eq!(mc, probabilities(2, 1000, 7, false));
        let mean = mc.iter().map(|r| r[0]).sum::<f64>() / 1000.0;
        assert!((mean - 0.5).abs() < 0.03, "{mean}");
    }
}
