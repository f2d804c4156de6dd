//! ROSS 2.3.0's matrices of one conical element (printed by its own code: `ShaftElement(L=0.5,
//! idl=0.05, idr=0.03, odl=0.1, odr=0.15, material=steel, axial_force=2e5, torque=3e3)`, steel
//! E = 211e9 Pa, G_s = 81.2e9 Pa, rho = 7810 kg/m^3), the planar block `x0, beta0, x1, beta1`.

use super::*;
use crate::fem::element::{self, Section, cowper_shear_factor};
use crate::linalg::c64;

const E: f64 = 211e9;
const G_S: f64 = 81.2e9;

fn ross_cone() -> Cone {
    let nu = E / (2.0 * G_S) - 1.0;
    let c = Cone {
        length: 0.5,
        outer_left: 0.1,
        inner_left: 0.05,
        outer_right: 0.15,
        inner_right: 0.03,
        young_modulus: E,
        density: 7810.0,
        poisson_ratio: nu,
        shear_factor: 1.0,
    };
    let (o, i) = mean_diameters(&c);
    Cone {
        shear_factor: cowper_shear_factor(o, i, nu),
        ..c
    }
}

const M: Mat4 = [
    [
        11.880884296048238,
        0.9119719898911375,
        5.683132829815292,
        -0.683126394489357,
    ],
    [
        0.9119719898911375,
        0.09190907189029554,
        0.7417527950249145,
        -0.08302928553044711,
    ],
    [
        5.683132829815292,
        0.7417527950249145,
        20.30396360287309,
        -1.2745175681435261,
    ],
    [
        -0.683126394489357,
        -0.08302928553044711,
        -1.2745175681435261,
        0.12005832297191196,
    ],
];
const K0: Mat4 = [
    [
        227545746.91856962,
        42724875.752662964,
        -227545746.91856962,
        71047997.70662184,
    ],
    [
        42724875.752662964,
        12544677.11227262,
        -42724875.752662964,
        8817760.76405886,
    ],
    [
        -227545746.91856962,
        -42724875.752662964,
        227545746.91856962,
        -71047997.70662184,
    ],
    [
        71047997.70662184,
        8817760.76405886,
        -71047997.70662184,
        26706238.08925207,
    ],
];
/// ROSS's `G` on rows `x, beta` and columns `y, -alpha`: the complex gyroscopic matrix.
const G: Mat4 = [
    [
        0.3269859721639411,
        0.012917806011474856,
        -0.3269859721639411,
        -0.013114395774692771,
    ],
    [
        0.012917806011474856,
        0.006903811904885532,
        -0.012917806011474856,
        -0.0043112858327822605,
    ],
    [
        -0.3269859721639411,
        -0.012917806011474856,
        0.3269859721639411,
        0.013114395774692771,
    ],
    [
        -0.013114395774692771,
        -0.0043112858327822605,
        0.013114395774692771,
        0.019785288679999773,
    ],
];
/// `K(axial_force, torque) - K(0, 0)` on the lateral dofs `x0 y0 alpha0 beta0 x1 y1 alpha1 beta1`.
const FORCES: [[f64; 8]; 8] = [
    [
        456899.5230036378,
        0.0,
        6000.0,
        14224.880750909448,
        -456899.5230036378,
        0.0,
        -6000.0,
        14224.880750909448,
    ],
    [
        0.0,
        456899.5230036378,
        -14224.880750909448,
        6000.0,
        0.0,
        -456899.5230036378,
        -14224.880750909448,
        -6000.0,
    ],
    [
        6000.0,
        -14224.880750909448,
        11889.553521061316,
        -1500.0,
        -6000.0,
        14224.880750909448,
        -4777.113145606592,
        1500.0,
    ],
    [
        14224.880750909448,
        6000.0,
        1500.0,
        11889.553521061316,
        -14224.880750909448,
        -6000.0,
        -1500.0,
        -4777.113145606592,
    ],
    [
        -456899.5230036378,
        0.0,
        -6000.0,
        -14224.880750909448,
        456899.5230036378,
        0.0,
        6000.0,
        -14224.880750909448,
    ],
    [
        0.0,
        -456899.5230036378,
        14224.880750909448,
        -6000.0,
        0.0,
        456899.5230036378,
        14224.880750909448,
        6000.0,
    ],
    [
        -6000.0,
        -14224.880750909448,
        -4777.113145606592,
        -1500.0,
        6000.0,
        14224.880750909448,
        11889.553521059453,
        1500.0,
    ],
    [
        14224.880750909448,
        -6000.0,
        1500.0,
        -4777.113145606592,
        -14224.880750909448,
        6000.0,
        -1500.0,
        11889.553521059453,
    ],
];

fn close(a: &Mat4, b: &Mat4, tol: f64) {
    let scale = b.iter().flatten().fold(0.0f64, |s, x| s.max(x.abs()));
    for i in 0..4 {
        for j in 0..4 {
            assert!(
                (a[i][j] - b[i][j]).abs() <= tol * scale,
                "[{i}][{j}]: {} vs {}",
                a[i][j],
                b[i][j]
            );
        }
    }
}

#[test]
fn the_conical_element_is_ross_s() {
    let c = ross_cone();
    // ROSS: kappa 0.7229258360285415, phi 0.18574330354908594, m 43.551113558551904 kg.
    assert!((1.0 / c.shear_factor - 0.7229258360285415).abs() < 1e-15);
    assert!((shear_parameter(&c) - 0.18574330354908594).abs() < 1e-15);
    assert!((c.mass() - 43.551113558551904).abs() < 1e-12);
    close(&mass(&c), &M, 1e-14);
    close(&stiffness(&c), &K0, 1e-14);
    close(&gyroscopic(&c), &G, 1e-14);
}

#[test]
fn a_rigid_translation_carries_the_frustum_s_mass_and_strains_nothing() {
    let c = ross_cone();
    let mt = translational_mass(&c);
    let u = [1.0, 0.0, 1.0, 0.0];
    let total: f64 = (0..4)
        .map(|i| (0..4).map(|j| u[i] * mt[i][j] * u[j]).sum::<f64>())
        .sum();
    // rho pi l / 12 ((D_l^2 + D_l D_r + D_r^2) - (d_l^2 + d_l d_r + d_r^2)), by hand:
    // 7810 pi 0.5 / 12 (0.0475 - 0.0049) = 43.5511 kg.
    let frustum = 7810.0 * std::f64::consts::PI * 0.5 / 12.0 * (0.0475 - 0.0049);
    assert!(
        (total - frustum).abs() < 1e-12 * frustum,
        "{total} vs {frustum}"
    );
    let k = stiffness(&c);
    let l = c.length;
    for v in [[1.0, 0.0, 1.0, 0.0], [-l / 2.0, 1.0, l / 2.0, 1.0]] {
        for row in k {
            let f: f64 = row.iter().zip(v).map(|(a, b)| a * b).sum();
            assert!(f.abs() < 1e-9 * k[0][0], "{f}");
        }
    }
}

#[test]
fn a_uniform_cone_is_the_uniform_element() {
    let s = Section {
        length: 0.3,
        outer_diameter: 0.08,
        inner_diameter: 0.02,
        young_modulus: 2.1e11,
        density: 7800.0,
        poisson_ratio: 0.3,
        shear_factor: cowper_shear_factor(0.08, 0.02, 0.3),
    };
    let c = Cone {
        length: s.length,
        outer_left: s.outer_diameter,
        inner_left: s.inner_diameter,
        outer_right: s.outer_diameter,
        inner_right: s.inner_diameter,
        young_modulus: s.young_modulus,
        density: s.density,
        poisson_ratio: s.poisson_ratio,
        shear_factor: s.shear_factor,
    };
    close(&stiffness(&c), &element::stiffness(&s), 1e-14);
    close(&mass(&c), &element::mass(&s), 1e-14);
    close(&gyroscopic(&c), &element::gyroscopic(&s), 1e-14);
}

#[test]
fn axial_force_and_torque_in_complex_coordinates_are_ross_s_real_matrices() {
    let c = ross_cone();
    let p = shear_parameter(&c);
    let af = axial_force(2e5, c.length, p);
    let s = torque(3e3, c.length);
    // A real lateral motion (x0 y0 alpha0 beta0 x1 y1 alpha1 beta1) and ROSS's real force.
    let v = [0.3, -0.7, 0.011, -0.023, 1.1, 0.4, -0.017, 0.005];
    let f: Vec<f64> = FORCES
        .iter()
        .map(|row| row.iter().zip(v).map(|(a, b)| a * b).sum())
        .collect();
    // r = x + i y, phi = beta - i alpha; forces f_r = f_x + i f_y, moments m = m_beta - i m_alpha.
    let q = [
        c64::new(v[0], v[1]),
        c64::new(v[3], -v[2]),
        c64::new(v[4], v[5]),
        c64::new(v[7], -v[6]),
    ];
    let want = [
        c64::new(f[0], f[1]),
        c64::new(f[3], -f[2]),
        c64::new(f[4], f[5]),
        c64::new(f[7], -f[6]),
    ];
    let scale = f.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    for i in 0..4 {
        let got: c64 = (0..4)
            .map(|j| (c64::new(af[i][j], 0.0) + c64::new(0.0, s[i][j])) * q[j])
            .sum();
        assert!(
            (got - want[i]).norm() < 1e-13 * scale,
            "{i}: {got} vs {}",
            want[i]
        );
    }
}
