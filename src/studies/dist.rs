//! The distributions of random designs, sampled by inversion: a value is `F⁻¹(u)` for `u` in
//! the truncated probability range, so Monte Carlo and Latin hypercube share one path and a
//! stratum of `u` is a stratum of the value.

use std::f64::consts::SQRT_2;

/// A distribution with its truncation as probabilities `[p_lo, p_hi]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dist {
    pub shape: Shape,
    p_lo: f64,
    p_hi: f64,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    Uniform {
        low: f64,
        high: f64,
    },
    Normal {
        mean: f64,
        std: f64,
    },
    /// `ln x` is normal with mean `mu` and standard deviation `sigma`.
    Lognormal {
        mu: f64,
        sigma: f64,
    },
}

impl Shape {
    fn cdf(&self, x: f64) -> f64 {
        match *self {
            Shape::Uniform { low, high } => ((x - low) / (high - low)).clamp(0.0, 1.0),
            Shape::Normal { mean, std } => normal_cdf((x - mean) / std),
            Shape::Lognormal { mu, sigma } if x > 0.0 => normal_cdf((x.ln() - mu) / sigma),
            Shape::Lognormal { .. } => 0.0,
        }
    }

    fn quantile(&self, p: f64) -> f64 {
        match *self {
            Shape::Uniform { low, high } => low + p * (high - low),
            Shape::Normal { mean, std } => mean + std * normal_quantile(p),
            Shape::Lognormal { mu, sigma } => (mu + sigma * normal_quantile(p)).exp(),
        }
    }
}

impl Dist {
    /// `shape` truncated to `[min, max]`; an error when that range has no probability.
    pub fn new(shape: Shape, min: Option<f64>, max: Option<f64>) -> Result<Self, String> {
        let p_lo = min.map_or(0.0, |m| shape.cdf(m));
        let p_hi = max.map_or(1.0, |m| shape.cdf(m));
        // (NaN-safe: a NaN probability range is refused too.)
        if (p_hi - p_lo).partial_cmp(&1e-12) != Some(std::cmp::Ordering::Greater) {
            return Err(format!(
                "the truncation [{}, {}] leaves no probability (below 1e-12) of this distribution",
                min.map_or("-inf".into(), |m| m.to_string()),
                max.map_or("inf".into(), |m| m.to_string())
            ));
        }
        Ok(Dist { shape, p_lo, p_hi })
    }

    /// The value at probability `u` in (0, 1) of the truncated distribution, finite.
    pub fn at(&self, u: f64) -> f64 {
        let p = self.p_lo + u * (self.p_hi - self.p_lo);
        // Keep away from 0 and 1, where the normal quantile is infinite.
        let p = p.clamp(1e-300, 1.0 - f64::EPSILON / 2.0);
        self.shape.quantile(p)
    }
}

/// Standard normal CDF through erfc (Numerical Recipes' Chebyshev fit, relative error below
/// 1.2e-7: enough to place a truncation).
pub fn normal_cdf(z: f64) -> f64 {
    0.5 * erfc(-z / SQRT_2)
}

fn erfc(x: f64) -> f64 {
    let z = x.abs();
    let t = 1.0 / (1.0 + 0.5 * z);
    let poly = -z * z - 1.265_512_23
        + t * (1.000_023_68
            + t * (0.374_091_96
                + t * (0.096_784_18
                    + t * (-0.186_288_06
                        + t * (0.278_868_07
                            + t * (-1.135_203_98
                                + t * (1.488_515_87 + t * (-0.822_152_23 + t * 0.170_872_77))))))));
    let r = t * poly.exp();
    if x >= 0.0 { r } else { 2.0 - r }
}

/// Standard normal quantile for `p` in (0, 1) (Acklam's rational approximation, relative
/// error below 1.2e-9).
pub fn normal_quantile(p: f64) -> f64 {
    const A: [f64; 6] = [
        -3.969_683_028_665_376e1,
        2.209_460_984_245_205e2,
        -2.759_285_104_469_687e2,
        1.383_577_518_672_69e2,
        -3.066_479_806_614_716e1,
        2.506_628_277_459_239,
    ];
    const B: [f64; 5] = [
        -5.447_609_879_822_406e1,
        1.615_858_368_580_409e2,
        -1.556_989_798_598_866e2,
        6.680_131_188_771_972e1,
        -1.328_068_155_288_572e1,
    ];
    const C: [f64; 6] = [
        -7.784_894_002_430_293e-3,
        -3.223_964_580_411_365e-1,
        -2.400_758_277_161_838,
        -2.549_732_539_343_734,
        4.374_664_141_464_968,
        2.938_163_982_698_783,
    ];
    const D: [f64; 4] = [
        7.784_695_709_041_462e-3,
        3.224_671_290_700_398e-1,
        2.445_134_137_142_996,
        3.754_408_661_907_416,
    ];
    let tail = |q: f64| {
        (((((C[0] * q + C[1]) * q + C[2]) * q + C[3]) * q + C[4]) * q + C[5])
            / ((((D[0] * q + D[1]) * q + D[2]) * q + D[3]) * q + 1.0)
    };
    const P_LOW: f64 = 0.02425;
    if p < P_LOW {
        tail((-2.0 * p.ln()).sqrt())
    } else if p <= 1.0 - P_LOW {
        let q = p - 0.5;
        let r = q * q;
        (((((A[0] * r + A[1]) * r + A[2]) * r + A[3]) * r + A[4]) * r + A[5]) * q
            / (((((B[0] * r + B[1]) * r + B[2]) * r + B[3]) * r + B[4]) * r + 1.0)
    } else {
        -tail((-2.0 * (1.0 - p).ln()).sqrt())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normal_quantile_matches_tabulated_values() {
        // Tables: z(0.975) = 1.959963985, z(0.95) = 1.644853627, z(0.001) = -3.090232306.
        assert!((normal_quantile(0.975) - 1.959_963_985).abs() < 1e-8);
        assert!((normal_quantile(0.95) - 1.644_853_627).abs() < 1e-8);
        assert!((normal_quantile(0.001) + 3.090_232_306).abs() < 1e-8);
        assert_eq!(normal_quantile(0.5), 0.0);
        for p in [1e-9, 0.01, 0.3, 0.7, 0.99] {
            assert!(
                (normal_cdf(normal_quantile(p)) - p).abs() < 2e-7 * p.max(1e-3),
                "{p}"
            );
        }
    }

    #[test]
    fn truncation_keeps_values_inside_and_refuses_an_empty_range() {
        let d = Dist::new(
            Shape::Normal {
                mean: 1.0,
                std: 2.0,
            },
            Some(0.5),
            Some(1.5),
        )
        .unwrap();
        for u in [0.0, 1e-6, 0.5, 1.0 - 1e-9, 1.0] {
            let x = d.at(u);
            assert!((0.5 - 1e-6..=1.5 + 1e-6).contains(&x), "{u} -> {x}");
        }
        // The median of a symmetric truncation is the mean.
        assert!((d.at(0.5) - 1.0).abs() < 1e-6);
        let ln = Dist::new(
            Shape::Lognormal {
                mu: 0.0,
                sigma: 0.5,
            },
            None,
            None,
        )
        .unwrap();
        assert!((ln.at(0.5) - 1.0).abs() < 1e-12);
        assert!(
            Dist::new(
                Shape::Normal {
                    mean: 0.0,
                    std: 1.0
                },
                Some(50.0),
                Some(60.0)
            )
            .is_err()
        );
        let u = Dist::new(
            Shape::Uniform {
                low: 2.0,
                high: 4.0,
            },
            None,
            Some(3.0),
        )
        .unwrap();
        assert_eq!(u.at(0.5), 2.5);
    }
}
