//! The conical (tapered) Timoshenko element of Genta and Gugliotta (1988) as ROSS 2.3.0
//! implements it (`shaft_element.py`), and the geometric stiffness of an axial force and of a
//! torque, in the complex coordinates of [`super::element`] (`(r1, phi1, r2, phi2)`).
//!
//! With radii linear along the element, `A(xi) = A_l (1 + a1 xi + b1 xi^2)` and
//! `I(xi) = I_l (1 + a2 xi + b2 xi^2 + gamma xi^3 + delta xi^4)`, `xi = z / l`; the shape
//! functions are the uniform element's, with the shear parameter `P = 12 E I_m chi / (G A_m l^2)`
//! of the mid section (`A_m`, `I_m`) and Cowper's factor of the mean diameters. The planar
//! (x-z) block of ROSS's 12x12 matrices (dofs `x, beta` at both ends) is the complex matrix.
//! For a uniform element every coefficient vanishes and the matrices are the uniform element's.
//!
//! - axial force `F` (tension > 0): `F / (30 l (1+P)^2) [[36+60P+30P^2, 3l, ...]]`, symmetric;
//! - torque `T`: ROSS's `K_tq` couples `x` with `alpha` and `y` with `beta`; with
//!   `phi = beta - i alpha` it is `i (T / l) S`, `S` real and not symmetric (a follower torque
//!   is circulatory):
//!   `S = [[0, 1, 0, -1], [-1, l/2, 1, -l/2], [0, -1, 0, 1], [1, l/2, -1, -l/2]]`.

use super::element::Mat4;

/// A conical element: diameters at both ends, material, shear factor (`chi = 1/kappa`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cone {
    pub length: f64,
    pub outer_left: f64,
    pub inner_left: f64,
    pub outer_right: f64,
    pub inner_right: f64,
    pub young_modulus: f64,
    pub density: f64,
    pub poisson_ratio: f64,
    pub shear_factor: f64,
}

/// The taper's coefficients and the sections ROSS's formulas use.
struct Taper {
    a1: f64,
    a2: f64,
    b1: f64,
    b2: f64,
    gamma: f64,
    delta: f64,
    area_left: f64,
    inertia_left: f64,
    area_mid: f64,
    inertia_mid: f64,
    /// Shear parameter `P`.
    p: f64,
}

impl Cone {
    fn taper(&self) -> Taper {
        use std::f64::consts::PI;
        let (ro_l, ri_l) = (self.outer_left / 2.0, self.inner_left / 2.0);
        let (ro_r, ri_r) = (self.outer_right / 2.0, self.inner_right / 2.0);
        let area_left = PI * (self.outer_left.powi(2) - self.inner_left.powi(2)) / 4.0;
        let inertia_left = PI * (self.outer_left.powi(4) - self.inner_left.powi(4)) / 64.0;
        let (dro, dri) = (ro_r - ro_l, ri_r - ri_l);
        let a1 = 2.0 * PI * (ro_l * dro - ri_l * dri) / area_left;
        let a2 = PI * (ro_l.powi(3) * dro - ri_l.powi(3) * dri) / inertia_left;
        let b1 = PI * (dro.powi(2) - dri.powi(2)) / area_left;
        let b2 = 3.0 * PI * (ro_l.powi(2) * dro.powi(2) - ri_l.powi(2) * dri.powi(2))
            / (2.0 * inertia_left);
        let gamma = PI * (ro_l * dro.powi(3) - ri_l * dri.powi(3)) / inertia_left;
        let delta = PI * (dro.powi(4) - dri.powi(4)) / (4.0 * inertia_left);
        let area_mid = area_left * (1.0 + a1 * 0.5 + b1 * 0.25);
        let inertia_mid =
            inertia_left * (1.0 + a2 * 0.5 + b2 * 0.25 + gamma * 0.125 + delta * 0.0625);
        let g = self.young_modulus / (2.0 * (1.0 + self.poisson_ratio));
        let p = 12.0 * self.young_modulus * inertia_mid * self.shear_factor
            / (g * area_mid * self.length.powi(2));
        Taper {
            a1,
            a2,
            b1,
            b2,
            gamma,
            delta,
            area_left,
            inertia_left,
            area_mid,
            inertia_mid,
            p,
        }
    }

    /// Mass of the frustum, kg.
    pub fn mass(&self) -> f64 {
        let (ol, or, il, ir) = (
            self.outer_left,
            self.outer_right,
            self.inner_left,
            self.inner_right,
        );
        let volume = std::f64::consts::PI * self.length / 12.0
            * ((ol * ol + ol * or + or * or) - (il * il + il * ir + ir * ir));
        self.density * volume
    }
}

/// Mean diameters: what ROSS's Cowper factor of a conical element is computed from.
pub fn mean_diameters(c: &Cone) -> (f64, f64) {
    (
        0.5 * (c.outer_left + c.outer_right),
        0.5 * (c.inner_left + c.inner_right),
    )
}

pub fn stiffness(c: &Cone) -> Mat4 {
    let t = c.taper();
    let (l, p) = (c.length, t.p);
    let (a2, b2, g, d) = (t.a2, t.b2, t.gamma, t.delta);
    let k1 = 1260.0 + 630.0 * a2 + 504.0 * b2 + 441.0 * g + 396.0 * d;
    let q = p * (105.0 * a2 + 105.0 * b2 + 94.5 * g + 84.0 * d);
    let k2 = (630.0 + 210.0 * a2 + 147.0 * b2 + 126.0 * g + 114.0 * d - q) * l;
    let k3 = (630.0 + 420.0 * a2 + 357.0 * b2 + 315.0 * g + 282.0 * d + q) * l;
    let p2 = p * p;
    let k4 = (420.0
        + 210.0 * p
        + 105.0 * p2
        + a2 * (105.0 + 52.5 * p2)
        + b2 * (56.0 - 35.0 * p + 35.0 * p2)
        + g * (42.0 - 42.0 * p + 26.25 * p2)
        + d * (36.0 - 42.0 * p + 21.0 * p2))
        * l
        * l;
    let k5 = (210.0 - 210.0 * p - 105.0 * p2
        + a2 * (105.0 - 105.0 * p - 52.5 * p2)
        + b2 * (91.0 - 70.0 * p - 35.0 * p2)
        + g * (84.0 - 52.5 * p - 26.25 * p2)
        + d * (78.0 - 42.0 * p - 21.0 * p2))
        * l
        * l;
    let k6 = (420.0
        + 210.0 * p
        + 105.0 * p2
        + a2 * (315.0 + 210.0 * p + 52.5 * p2)
        + b2 * (266.0 + 175.0 * p + 35.0 * p2)
        + g * (231.0 + 147.0 * p + 26.25 * p2)
        + d * (204.0 + 126.0 * p + 21.0 * p2))
        * l
        * l;
    let (a1, b1) = (t.a1, t.b1);
    let k7 = 12.0 + 6.0 * a1 + 4.0 * b1;
    let k8 = (6.0 + 3.0 * a1 + 2.0 * b1) * l;
    let k9 = (3.0 + 1.5 * a1 + b1) * l * l;
    let bend = [
        [k1, k2, -k1, k3],
        [k2, k4, -k2, k5],
        [-k1, -k2, k1, -k3],
        [k3, k5, -k3, k6],
    ];
    let shear = [
        [k7, k8, -k7, k8],
        [k8, k9, -k8, k9],
        [-k7, -k8, k7, -k8],
        [k8, k9, -k8, k9],
    ];
    let (fb, fs) = (
        t.inertia_left / 105.0,
        t.inertia_mid * p * t.area_left / t.area_mid,
    );
    let f = c.young_modulus / (l.powi(3) * (1.0 + p).powi(2));
    let mut k = [[0.0; 4]; 4];
    for i in 0..4 {
        for j in 0..4 {
            k[i][j] = f * (fb * bend[i][j] + fs * shear[i][j]);
        }
    }
    k
}

pub fn translational_mass(c: &Cone) -> Mat4 {
    let t = c.taper();
    let (l, p, a1, b1) = (c.length, t.p, t.a1, t.b1);
    let p2 = p * p;
    let m1 = (468.0 + 882.0 * p + 420.0 * p2)
        + a1 * (108.0 + 210.0 * p + 105.0 * p2)
        + b1 * (38.0 + 78.0 * p + 42.0 * p2);
    let m2 = ((66.0 + 115.5 * p + 52.5 * p2)
        + a1 * (21.0 + 40.5 * p + 21.0 * p2)
        + b1 * (8.5 + 18.0 * p + 10.5 * p2))
        * l;
    let m3 = (162.0 + 378.0 * p + 210.0 * p2)
        + a1 * (81.0 + 189.0 * p + 105.0 * p2)
        + b1 * (46.0 + 111.0 * p + 63.0 * p2);
    let m4 = ((39.0 + 94.5 * p + 52.5 * p2)
        + a1 * (18.0 + 40.5 * p + 21.0 * p2)
        + b1 * (9.5 + 21.0 * p + 10.5 * p2))
        * l;
    let m5 = ((12.0 + 21.0 * p + 10.5 * p2)
        + a1 * (4.5 + 9.0 * p + 5.25 * p2)
        + b1 * (2.0 + 4.5 * p + 3.0 * p2))
        * l
        * l;
    let m6 = ((39.0 + 94.5 * p + 52.5 * p2)
        + a1 * (21.0 + 54.0 * p + 31.5 * p2)
        + b1 * (12.5 + 34.5 * p + 21.0 * p2))
        * l;
    let m7 = ((9.0 + 21.0 * p + 10.5 * p2)
        + a1 * (4.5 + 10.5 * p + 5.25 * p2)
        + b1 * (2.5 + 6.0 * p + 3.0 * p2))
        * l
        * l;
    let m8 = (468.0 + 882.0 * p + 420.0 * p2)
        + a1 * (360.0 + 672.0 * p + 315.0 * p2)
        + b1 * (290.0 + 540.0 * p + 252.0 * p2);
    let m9 = ((66.0 + 115.5 * p + 52.5 * p2)
        + a1 * (45.0 + 75.0 * p + 31.5 * p2)
        + b1 * (32.5 + 52.5 * p + 21.0 * p2))
        * l;
    let m10 = ((12.0 + 21.0 * p + 10.5 * p2)
        + a1 * (7.5 + 12.0 * p + 5.25 * p2)
        + b1 * (5.0 + 7.5 * p + 3.0 * p2))
        * l
        * l;
    let f = c.density * t.area_left * l / (1260.0 * (1.0 + p).powi(2));
    scale(
        f,
        [
            [m1, m2, m3, -m4],
            [m2, m5, m6, -m7],
            [m3, m6, m8, -m9],
            [-m4, -m7, -m9, m10],
        ],
    )
}

pub fn rotary_mass(c: &Cone) -> Mat4 {
    let t = c.taper();
    let (l, p, a2, b2, g, d) = (c.length, t.p, t.a2, t.b2, t.gamma, t.delta);
    let p2 = p * p;
    let m11 = 252.0 + 126.0 * a2 + 72.0 * b2 + 45.0 * g + 30.0 * d;
    let m12 = (21.0 - 105.0 * p
        + a2 * (21.0 - 42.0 * p)
        + b2 * (15.0 - 21.0 * p)
        + g * (10.5 - 12.0 * p)
        + d * (7.5 - 7.5 * p))
        * l;
    let m13 = (21.0
        - 105.0 * p
        - 63.0 * a2 * p
        - b2 * (6.0 + 42.0 * p)
        - g * (7.5 + 30.0 * p)
        - d * (7.5 + 22.5 * p))
        * l;
    let m14 = (28.0
        + 35.0 * p
        + 70.0 * p2
        + a2 * (7.0 - 7.0 * p + 17.5 * p2)
        + b2 * (4.0 - 7.0 * p + 7.0 * p2)
        + g * (2.75 - 5.0 * p + 3.5 * p2)
        + d * (2.0 - 3.5 * p + 2.0 * p2))
        * l
        * l;
    let m15 = (7.0 + 35.0 * p - 35.0 * p2
        + a2 * (3.5 + 17.5 * p - 17.5 * p2)
        + b2 * (3.0 + 10.5 * p - 10.5 * p2)
        + g * (2.75 + 7.0 * p - 7.0 * p2)
        + d * (2.5 + 5.0 * p - 5.0 * p2))
        * l
        * l;
    let m16 = (28.0
        + 35.0 * p
        + 70.0 * p2
        + a2 * (21.0 + 42.0 * p + 52.5 * p2)
        + b2 * (18.0 + 42.0 * p + 42.0 * p2)
        + g * (16.25 + 40.0 * p + 35.0 * p2)
        + d * (15.0 + 37.5 * p + 30.0 * p2))
        * l
        * l;
    let f = c.density * t.inertia_left / (210.0 * l * (1.0 + p).powi(2));
    scale(
        f,
        [
            [m11, m12, -m11, m13],
            [m12, m14, -m12, -m15],
            [-m11, -m12, m11, -m13],
            [m13, -m15, -m13, m16],
        ],
    )
}

/// Consistent mass: translational plus rotary inertia.
pub fn mass(c: &Cone) -> Mat4 {
    let (a, b) = (translational_mass(c), rotary_mass(c));
    let mut m = a;
    for i in 0..4 {
        for j in 0..4 {
            m[i][j] += b[i][j];
        }
    }
    m
}

/// Gyroscopic matrix: twice the rotary-inertia mass (ROSS's `G` has the same coefficients).
pub fn gyroscopic(c: &Cone) -> Mat4 {
    scale(2.0, rotary_mass(c))
}

/// Geometric stiffness of an axial force `force` (N, tension > 0) on an element of length `l`
/// and shear parameter `p` (ROSS's `K_af`).
pub fn axial_force(force: f64, l: f64, p: f64) -> Mat4 {
    let k10 = 36.0 + 60.0 * p + 30.0 * p * p;
    let k11 = 3.0 * l;
    let k12 = (4.0 + 5.0 * p + 2.5 * p * p) * l * l;
    let k13 = (1.0 + 5.0 * p + 2.5 * p * p) * l * l;
    scale(
        force / (30.0 * l * (1.0 + p).powi(2)),
        [
            [k10, k11, -k10, k11],
            [k11, k12, -k11, -k13],
            [-k10, -k11, k10, -k11],
            [k11, -k13, -k11, k12],
        ],
    )
}

/// `S` of the torque's geometric stiffness `i S` (module docs), N m / m.
pub fn torque(torque: f64, l: f64) -> Mat4 {
    let h = l / 2.0;
    scale(
        torque / l,
        [
            [0.0, 1.0, 0.0, -1.0],
            [-1.0, h, 1.0, -h],
            [0.0, -1.0, 0.0, 1.0],
            [1.0, h, -1.0, -h],
        ],
    )
}

/// The shear parameter `P` of the element (mid section).
pub fn shear_parameter(c: &Cone) -> f64 {
    c.taper().p
}

fn scale(f: f64, m: Mat4) -> Mat4 {
    m.map(|row| row.map(|x| f * x))
}

#[cfg(test)]
mod tests;
