//! Timoshenko shaft element in complex coordinates (MODEL.md section 5).
//!
//! Degrees of freedom `(r1, phi1, r2, phi2)`, `r = x + i y`, `phi = phi_y - i phi_x = dr/dz`.
//! In these coordinates an axisymmetric shaft's matrices are exactly the planar (x-z) beam
//! matrices. Shear enters through `P = 12 E I chi / (G A l^2)`, `G = E / (2 (1 + nu))`:
//!
//! - stiffness `E I / (l^3 (1+P)) [[12, 6l, -12, 6l], [6l, (4+P) l^2, -6l, (2-P) l^2], ...]`;
//! - consistent translational mass `rho A l / (1+P)^2 [[a, b, c, -d], ...]` and rotary-inertia
//!   mass `rho I / ((1+P)^2 l) [[g, h, -g, h], ...]`, both with their shear terms;
//! - gyroscopic matrix `2 x` the rotary-inertia mass (polar = twice diametral inertia).

/// A 4x4 element matrix.
pub type Mat4 = [[f64; 4]; 4];

/// Geometry and material of one element.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Section {
    pub length: f64,
    pub outer_diameter: f64,
    pub inner_diameter: f64,
    pub young_modulus: f64,
    pub density: f64,
    pub poisson_ratio: f64,
    /// chi = 1/kappa.
    pub shear_factor: f64,
}

impl Section {
    pub fn area(&self) -> f64 {
        std::f64::consts::PI / 4.0 * (self.outer_diameter.powi(2) - self.inner_diameter.powi(2))
    }

    /// Diametral second moment of area.
    pub fn inertia(&self) -> f64 {
        std::f64::consts::PI / 64.0 * (self.outer_diameter.powi(4) - self.inner_diameter.powi(4))
    }

    /// Shear parameter `P = 12 E I chi / (G A l^2)`.
    pub fn shear_parameter(&self) -> f64 {
        let g = self.young_modulus / (2.0 * (1.0 + self.poisson_ratio));
        12.0 * self.young_modulus * self.inertia() * self.shear_factor
            / (g * self.area() * self.length.powi(2))
    }
}

/// Cowper's shear factor `chi = 1/kappa` for a hollow circular section:
/// `kappa = 6 (1+nu) (1+m^2)^2 / ((7+6 nu)(1+m^2)^2 + (20+12 nu) m^2)`, `m = d_i/d_o`.
pub fn cowper_shear_factor(outer: f64, inner: f64, poisson: f64) -> f64 {
    let m2 = (inner / outer).powi(2);
    let a = (1.0 + m2).powi(2);
    let kappa =
        6.0 * (1.0 + poisson) * a / ((7.0 + 6.0 * poisson) * a + (20.0 + 12.0 * poisson) * m2);
    1.0 / kappa
}

pub fn stiffness(s: &Section) -> Mat4 {
    let (l, p) = (s.length, s.shear_parameter());
    let f = s.young_modulus * s.inertia() / (l.powi(3) * (1.0 + p));
    let l2 = l * l;
    scale(
        f,
        [
            [12.0, 6.0 * l, -12.0, 6.0 * l],
            [6.0 * l, (4.0 + p) * l2, -6.0 * l, (2.0 - p) * l2],
            [-12.0, -6.0 * l, 12.0, -6.0 * l],
            [6.0 * l, (2.0 - p) * l2, -6.0 * l, (4.0 + p) * l2],
        ],
    )
}

pub fn translational_mass(s: &Section) -> Mat4 {
    let (l, p) = (s.length, s.shear_parameter());
    let p2 = p * p;
    let a = 13.0 / 35.0 + 7.0 * p / 10.0 + p2 / 3.0;
    let b = (11.0 / 210.0 + 11.0 * p / 120.0 + p2 / 24.0) * l;
    let c = 9.0 / 70.0 + 3.0 * p / 10.0 + p2 / 6.0;
    let d = (13.0 / 420.0 + 3.0 * p / 40.0 + p2 / 24.0) * l;
    let e = (1.0 / 105.0 + p / 60.0 + p2 / 120.0) * l * l;
    let f = (1.0 / 140.0 + p / 60.0 + p2 / 120.0) * l * l;
    scale(
        s.density * s.area() * l / (1.0 + p).powi(2),
        [[a, b, c, -d], [b, e, d, -f], [c, d, a, -b], [-d, -f, -b, e]],
    )
}

pub fn rotary_mass(s: &Section) -> Mat4 {
    let (l, p) = (s.length, s.shear_parameter());
    let p2 = p * p;
    let g = 6.0 / 5.0;
    let h = (1.0 / 10.0 - p / 2.0) * l;
    let i = (2.0 / 15.0 + p / 6.0 + p2 / 3.0) * l * l;
    let j = (1.0 / 30.0 + p / 6.0 - p2 / 6.0) * l * l;
    scale(
        s.density * s.inertia() / ((1.0 + p).powi(2) * l),
        [
            [g, h, -g, h],
            [h, i, -h, -j],
            [-g, -h, g, -h],
            [h, -j, -h, i],
        ],
    )
}

/// Consistent mass: translational plus rotary inertia.
pub fn mass(s: &Section) -> Mat4 {
    add(translational_mass(s), rotary_mass(s))
}

/// Gyroscopic matrix: twice the rotary-inertia mass.
pub fn gyroscopic(s: &Section) -> Mat4 {
    scale(2.0, rotary_mass(s))
}

fn scale(f: f64, m: Mat4) -> Mat4 {
    m.map(|row| row.map(|x| f * x))
}

fn add(a: Mat4, b: Mat4) -> Mat4 {
    let mut c = a;
    for i in 0..4 {
        for j in 0..4 {
            c[i][j] += b[i][j];
        }
    }
    c
}

#[cfg(test)]
mod tests {
    use super::*;

    fn section(p_zero: bool) -> Section {
        Section {
            length: 0.5,
            outer_diameter: 0.06,
            inner_diameter: 0.05,
            young_modulus: 210e9,
            density: 7810.0,
            poisson_ratio: 0.3,
            shear_factor: if p_zero { 0.0 } else { 1.85 },
        }
    }

    #[test]
    fn rigid_translation_carries_the_element_mass_and_no_stiffness() {
        for p_zero in [true, false] {
            let s = section(p_zero);
            let (k, m) = (stiffness(&s), mass(&s));
            // Rigid translation u = (1, 0, 1, 0): K u = 0, u^T M_t u = rho A l.
            let u = [1.0, 0.0, 1.0, 0.0];
            for row in k {
                let f: f64 = row.iter().zip(u).map(|(a, b)| a * b).sum();
                assert!(f.abs() < 1e-6 * k[0][0]);
            }
            let mt = translational_mass(&s);
            let total: f64 = (0..4)
                .map(|i| (0..4).map(|j| u[i] * mt[i][j] * u[j]).sum::<f64>())
                .sum();
            let rho_a_l = s.density * s.area() * s.length;
            assert!((total - rho_a_l).abs() < 1e-12 * rho_a_l);
            // Rigid rotation about the midpoint: no strain energy either.
            let l = s.length;
            let r = [-l / 2.0, 1.0, l / 2.0, 1.0];
            let e: f64 = (0..4)
                .map(|i| (0..4).map(|j| r[i] * k[i][j] * r[j]).sum::<f64>())
                .sum();
            assert!(e.abs() < 1e-9 * k[1][1]);
            // Symmetric.
            for i in 0..4 {
                for j in 0..4 {
                    assert_eq!(k[i][j], k[j][i]);
                    assert!((m[i][j] - m[j][i]).abs() <= 1e-15 * m[0][0]);
                }
            }
        }
    }

    #[test]
    fn cowper_factor_of_the_paper_tube_and_of_a_solid_shaft() {
        // Solid: kappa = 6 (1 + nu) / (7 + 6 nu).
        let solid = cowper_shear_factor(0.1, 0.0, 0.3);
        assert!((solid - (7.0 + 1.8) / (6.0 * 1.3)).abs() < 1e-14);
        // The paper's 60/50 mm tube: chi = 1.86 by Cowper (the paper used 1.85).
        let tube = cowper_shear_factor(0.06, 0.05, 0.3);
        assert!((tube - 1.86).abs() < 0.005, "{tube}");
    }
}
