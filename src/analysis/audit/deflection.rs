//! The exact static deflection inside a Timoshenko element under its own uniform weight.
//!
//! In one plane, with `w` the displacement, `psi` the section's rotation (the element's `phi`
//! degree of freedom), `E I psi' = M`, `w' = psi + V chi / (G A)` and a uniform load `q` per
//! length, the deflection between the element's ends is the homogeneous solution that meets
//! the end values `(w1, psi1, w2, psi2)` plus the particular solution of an element clamped at
//! both ends (`xi = x / l`, `P = 12 E I chi / (G A l^2)`):
//!
//! ```text
//! w(x) = N1 w1 + N2 psi1 + N3 w2 + N4 psi2 + q x^2 (l - x)^2 / (24 E I) + q chi x (l - x) / (2 G A)
//! N1 = (1 - 3 xi^2 + 2 xi^3 + P (1 - xi)) / (1 + P)
//! N2 = l (xi - 2 xi^2 + xi^3 + P (xi - xi^2) / 2) / (1 + P)
//! N3 = (3 xi^2 - 2 xi^3 + P xi) / (1 + P)
//! N4 = l (-xi^2 + xi^3 - P (xi - xi^2) / 2) / (1 + P)
//! ```
//!
//! The `N` are the element's own (interdependent) shape functions, and the end values of an
//! element with its consistent load are exact for a uniform load, so the curve is exact too:
//! a simply supported shaft gives `q x (L^3 - 2 L x^2 + x^3) / (24 E I) + q chi x (L - x) / (2 G A)`
//! at every point, nodes or not, to 1e-9 (tests/it/audit_ross.rs). Joining the nodes straight is
//! not: Example 1 on pins deflects 63.6 um at mid-span, inside its middle element, where its
//! nodes reach 55.2 um (13% less).

use crate::fem::element::Section;

/// One element's bending and shear properties, with the load it carries per length.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Span {
    pub length: f64,
    /// `E I`, N m^2.
    pub bending: f64,
    /// `chi / (G A)`, 1/N: the shear compliance per length.
    pub shear: f64,
    /// Load per length in the plane, N/m (negative: down).
    pub load: f64,
}

impl Span {
    pub fn new(s: &Section, load: f64) -> Self {
        let g = s.young_modulus / (2.0 * (1.0 + s.poisson_ratio));
        Span {
            length: s.length,
            bending: s.young_modulus * s.inertia(),
            shear: s.shear_factor / (g * s.area()),
            load,
        }
    }

    /// `P = 12 E I chi / (G A l^2)`.
    fn shear_parameter(&self) -> f64 {
        12.0 * self.bending * self.shear / (self.length * self.length)
    }

    /// The displacement at `x` from the left end (0 to `length`), the ends' displacements and
    /// rotations `[w1, psi1, w2, psi2]` given.
    pub fn deflection(&self, ends: [f64; 4], x: f64) -> f64 {
        let (l, p) = (self.length, self.shear_parameter());
        if l <= 0.0 {
            return ends[0];
        }
        let xi = x / l;
        let (xi2, xi3) = (xi * xi, xi * xi * xi);
        let d = 1.0 + p;
        let n = [
            (1.0 - 3.0 * xi2 + 2.0 * xi3 + p * (1.0 - xi)) / d,
            l * (xi - 2.0 * xi2 + xi3 + 0.5 * p * (xi - xi2)) / d,
            (3.0 * xi2 - 2.0 * xi3 + p * xi) / d,
            l * (-xi2 + xi3 - 0.5 * p * (xi - xi2)) / d,
        ];
        let homogeneous: f64 = n.iter().zip(ends).map(|(n, u)| n * u).sum();
        let r = l - x;
        homogeneous
            + self.load * x * x * r * r / (24.0 * self.bending)
            + 0.5 * self.load * self.shear * x * r
    }
}

/// The point of largest `f` on `[a, b]` near a sampled maximum: golden-section search to
/// `1e-12` of the interval (the curves are smooth and unimodal between neighbouring samples).
pub fn refine_max(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    let r = 0.5 * (5f64.sqrt() - 1.0);
    // Not below a few ulps of the positions: on a fine mesh far from z = 0 (elements of 1 mm
    // at z = 2 m) 1e-12 of the bracket is below one ulp of z, and the loop never ended.
    let ulps = 4.0 * f64::EPSILON * a.abs().max(b.abs());
    let tol = (1e-12 * (b - a).abs()).max(ulps).max(f64::MIN_POSITIVE);
    let (mut c, mut d) = (b - r * (b - a), a + r * (b - a));
    let (mut fc, mut fd) = (f(c), f(d));
    // Golden section shrinks by 0.618 a step: 1e-12 takes 58; the cap only guards round-off.
    let mut steps = 0;
    while (b - a).abs() > tol && steps < 200 {
        steps += 1;
        if fc >= fd {
            b = d;
            (d, fd) = (c, fc);
            c = b - r * (b - a);
            fc = f(c);
        } else {
            a = c;
            (c, fc) = (d, fd);
            d = a + r * (b - a);
            fd = f(d);
        }
    }
    0.5 * (a + b)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn steel(length: f64, d: f64) -> Section {
        Section {
            length,
            outer_diameter: d,
            inner_diameter: 0.0,
            young_modulus: 2.1e11,
            density: 7800.0,
            poisson_ratio: 0.3,
            shear_factor: 1.2,
        }
    }

    #[test]
    fn a_cantilever_under_its_weight_is_beam_theory_everywhere() {
        // Clamped at x = 0 (w = psi = 0), free end: w(x) = q x^2 (6 L^2 - 4 L x + x^2) / (24 E I)
        // + q chi (L x - x^2 / 2) / (G A). A stubby 0.3 m x 0.1 m bar: the shear term is 2% of
        // the tip deflection, so a curve without it would fail.
        let s = Span::new(&steel(0.3, 0.1), -600.0);
        let (l, q, ei, c) = (s.length, s.load, s.bending, s.shear);
        let exact = |x: f64| {
            q * x * x * (6.0 * l * l - 4.0 * l * x + x * x) / (24.0 * ei)
                + q * c * (l * x - 0.5 * x * x)
        };
        // psi at the tip: q L^3 / (6 E I).
        let ends = [0.0, 0.0, exact(l), q * l.powi(3) / (6.0 * ei)];
        assert!(q * c * l * l / 2.0 / exact(l) > 0.01);
        for k in 0..=10 {
            let x = l * k as f64 / 10.0;
            let w = s.deflection(ends, x);
            assert!(
                (w - exact(x)).abs() < 1e-12 * exact(l).abs(),
                "{x}: {w} vs {}",
                exact(x)
            );
        }
    }

    #[test]
    fn golden_section_finds_a_parabolas_top() {
        let x = refine_max(|x| -(x - 0.3141).powi(2), 0.0, 1.0);
        assert!((x - 0.3141).abs() < 1e-9);
    }

    #[test]
    fn golden_section_ends_on_a_bracket_narrower_than_its_tolerance_allows() {
        // A 0.25 mm bracket at z = 2 m (a 2000-element shaft's samples): 1e-12 of it is below
        // one ulp of z (4.4e-16 m); the search used to spin forever there.
        let top = 2.000_1;
        let x = refine_max(|x| -(x - top).powi(2), 2.0, 2.000_25);
        assert!((x - top).abs() < 1e-12, "{x}");
    }
}
