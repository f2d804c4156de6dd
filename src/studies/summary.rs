//! A study's outputs reduced: statistics per output, Spearman's rank correlation per parameter
//! and output. Only numbers count; everything else (null, a failed sample, a string) is a
//! "null" output. Nothing here returns NaN: too few numbers give `None`.

use serde_json::Value;

use crate::model::api::{OutputSummary, Sensitivity, StudySample};

/// Percentile `p` (0 to 1) of sorted values, linear between order statistics.
pub fn percentile(sorted: &[f64], p: f64) -> Option<f64> {
    let n = sorted.len();
    if n == 0 {
        return None;
    }
    let h = (n - 1) as f64 * p;
    let (lo, hi) = (h.floor() as usize, h.ceil() as usize);
    Some(sorted[lo] + (h - lo as f64) * (sorted[hi] - sorted[lo]))
}

/// The statistics of one output.
pub fn output_summary(output: &str, values: &[Option<f64>]) -> OutputSummary {
    let mut x: Vec<f64> = values.iter().flatten().copied().collect();
    x.sort_by(f64::total_cmp);
    let n = x.len();
    let mean = (n > 0).then(|| x.iter().sum::<f64>() / n as f64);
    let std = mean
        .filter(|_| n >= 2)
        .map(|m| (x.iter().map(|v| (v - m).powi(2)).sum::<f64>() / (n - 1) as f64).sqrt());
    OutputSummary {
        output: output.to_string(),
        count: n as u64,
        null_fraction: if values.is_empty() {
            0.0
        } else {
            (values.len() - n) as f64 / values.len() as f64
        },
        mean,
        std,
        min: x.first().copied(),
        max: x.last().copied(),
        p5: percentile(&x, 0.05),
        p50: percentile(&x, 0.5),
        p95: percentile(&x, 0.95),
    }
}

/// Ranks from 1, ties given their mean rank.
fn ranks(x: &[f64]) -> Vec<f64> {
    let mut order: Vec<usize> = (0..x.len()).collect();
    order.sort_by(|&a, &b| x[a].total_cmp(&x[b]));
    let mut r = vec![0.0; x.len()];
    let mut i = 0;
    while i < order.len() {
        let mut j = i;
        while j + 1 < order.len() && x[order[j + 1]] == x[order[i]] {
            j += 1;
        }
        let mean = (i + j) as f64 / 2.0 + 1.0;
        for &k in &order[i..=j] {
            r[k] = mean;
        }
        i = j + 1;
    }
    r
}

/// Spearman's rank correlation of paired values; `None` with fewer than 3 pairs or a constant.
pub fn spearman(pairs: &[(f64, f64)]) -> Option<f64> {
    if pairs.len() < 3 {
        return None;
    }
    let a = ranks(&pairs.iter().map(|p| p.0).collect::<Vec<_>>());
    let b = ranks(&pairs.iter().map(|p| p.1).collect::<Vec<_>>());
    let n = a.len() as f64;
    let (ma, mb) = (a.iter().sum::<f64>() / n, b.iter().sum::<f64>() / n);
    let (mut sab, mut saa, mut sbb) = (0.0, 0.0, 0.0);
    for (x, y) in a.iter().zip(&b) {
        sab += (x - ma) * (y - mb);
        saa += (x - ma).powi(2);
        sbb += (y - mb).powi(2);
    }
    (saa > 0.0 && sbb > 0.0).then(|| (sab / (saa * sbb).sqrt()).clamp(-1.0, 1.0))
}

fn number(v: Option<&Value>) -> Option<f64> {
    v.and_then(Value::as_f64).filter(|x| x.is_finite())
}

/// Output `k` of every sample (a number or `None`).
pub fn column(samples: &[StudySample], k: usize) -> Vec<Option<f64>> {
    samples.iter().map(|s| number(s.outputs.get(k))).collect()
}

/// Parameter `j` of every sample (a number or `None`).
pub fn parameter_column(samples: &[StudySample], j: usize) -> Vec<Option<f64>> {
    samples
        .iter()
        .map(|s| number(s.parameters.get(j)))
        .collect()
}

/// The summary of every output and the sensitivity of every output to every parameter.
pub fn summarize(
    samples: &[StudySample],
    parameters: &[String],
    outputs: &[String],
) -> (Vec<OutputSummary>, Vec<Sensitivity>) {
    let columns: Vec<Vec<Option<f64>>> = (0..outputs.len()).map(|k| column(samples, k)).collect();
    let summary = outputs
        .iter()
        .zip(&columns)
        .map(|(o, c)| output_summary(o, c))
        .collect();
    let mut sensitivity = vec![];
    for (j, p) in parameters.iter().enumerate() {
        let x = parameter_column(samples, j);
        for (o, y) in outputs.iter().zip(&columns) {
            let pairs: Vec<(f64, f64)> = x
                .iter()
                .zip(y)
                .filter_map(|(a, b)| Some(((*a)?, (*b)?)))
                .collect();
            sensitivity.push(Sensitivity {
                parameter: p.clone(),
                output: o.clone(),
                spearman: spearman(&pairs),
                count: pairs.len() as u64,
            });
        }
    }
    (summary, sensitivity)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn statistics_of_known_values() {
        let v: Vec<Option<f64>> = (1..=10)
            .map(|i| Some(i as f64))
            .chain([None, None])
            .collect();
        let s = output_summary("/x", &v);
        assert_eq!(s.count, 10);
        assert!((s.null_fraction - 2.0 / 12.0).abs() < 1e-15);
        assert_eq!(s.mean, Some(5.5));
        // Sample std of 1..10: sqrt(82.5 / 9).
        assert!((s.std.unwrap() - (82.5f64 / 9.0).sqrt()).abs() < 1e-12);
        assert_eq!((s.min, s.max), (Some(1.0), Some(10.0)));
        // numpy.percentile(range(1, 11), [5, 50, 95]) = 1.45, 5.5, 9.55.
        assert!((s.p5.unwrap() - 1.45).abs() < 1e-12);
        assert_eq!(s.p50, Some(5.5));
        assert!((s.p95.unwrap() - 9.55).abs() < 1e-12);
        let none = output_summary("/x", &[None, None]);
        assert_eq!(
            (none.mean, none.std, none.p50, none.null_fraction),
            (None, None, None, 1.0)
        );
    }

    #[test]
    fn spearman_of_monotone_tied_and_known_data() {
        let up: Vec<(f64, f64)> = (0..20).map(|i| (i as f64, (i as f64).exp())).collect();
        assert_eq!(spearman(&up), Some(1.0));
        let down: Vec<(f64, f64)> = (0..20).map(|i| (i as f64, -(i as f64).powi(3))).collect();
        assert_eq!(spearman(&down), Some(-1.0));
        assert_eq!(spearman(&[(1.0, 2.0), (2.0, 2.0), (3.0, 2.0)]), None);
        // scipy.stats.spearmanr([1,2,3,4,5], [5,6,7,8,7]) = 0.8207826816681233 (ties).
        let t = [(1.0, 5.0), (2.0, 6.0), (3.0, 7.0), (4.0, 8.0), (5.0, 7.0)];
        assert!((spearman(&t).unwrap() - 0.820_782_681_668_123_3).abs() < 1e-12);
    }
}
