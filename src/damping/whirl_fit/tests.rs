//! The fit of one table at one speed.

use super::*;

/// The fit of `table` (read at `w`, no mass) with `rates`, measured at `w`.
fn fit_table(w: &[f64], table: Vec<Coefficients>, rates: &[f64], isotropic: bool) -> AtSpeed {
    let read = Read {
        samples: table.clone(),
        checks: table,
        m0: Matrix2::default(),
    };
    fit_at(&Design::new(w, &[], rates), &read, w, isotropic).unwrap()
}

/// `H(w) = K0 + i w C0 + G i w / (i w + d)` per coefficient, as a table would read it.
fn maxwell(k0: Matrix2, c0: Matrix2, g: Matrix2, d: f64, w: f64) -> Coefficients {
    let e = |k: f64, c: f64, g: f64| {
        // Re: k + g w^2 / (w^2 + d^2); Im / w: c + g d / (w^2 + d^2).
        let den = w * w + d * d;
        (k + g * w * w / den, c + g * d / den)
    };
    let (kxx, cxx) = e(k0.xx, c0.xx, g.xx);
    let (kxy, cxy) = e(k0.xy, c0.xy, g.xy);
    let (kyx, cyx) = e(k0.yx, c0.yx, g.yx);
    let (kyy, cyy) = e(k0.yy, c0.yy, g.yy);
    Coefficients {
        k: Matrix2 {
            xx: kxx,
            xy: kxy,
            yx: kyx,
            yy: kyy,
        },
        c: Matrix2 {
            xx: cxx,
            xy: cxy,
            yx: cyx,
            yy: cyy,
        },
        m: Matrix2::default(),
    }
}

#[test]
fn a_table_of_one_maxwell_branch_is_recovered_at_its_rate() {
    // N/m, N s/m, N/m, 1/s: an anisotropic support with skew cross-coupling in K0 and a
    // branch with a symmetric cross term inside its direct terms' limit.
    let k0 = Matrix2 {
        xx: 2e5,
        xy: 4e4,
        yx: -4e4,
        yy: 3e5,
    };
    let c0 = Matrix2 {
        xx: 100.0,
        xy: 0.0,
        yx: 0.0,
        yy: 150.0,
    };
    let g = Matrix2 {
        xx: 3e5,
        xy: 5e4,
        yx: 5e4,
        yy: 2e5,
    };
    let d = 300.0;
    let w: Vec<f64> = (0..=40).map(|i| 25.0 * i as f64).collect();
    let table: Vec<Coefficients> = w.iter().map(|&w| maxwell(k0, c0, g, d, w)).collect();
    let f = fit_table(&w, table, &[d], false);
    let close = |a: &Matrix2, b: &Matrix2, scale: f64| {
        [(a.xx, b.xx), (a.xy, b.xy), (a.yx, b.yx), (a.yy, b.yy)]
            .iter()
            .all(|(x, y)| (x - y).abs() <= 1e-9 * scale)
    };
    assert!(close(&f.base.k, &k0, 3e5), "{:?}", f.base.k);
    assert!(close(&f.base.c, &c0, 150.0), "{:?}", f.base.c);
    assert!(close(&f.branches[0], &g, 3e5), "{:?}", f.branches);
    assert!(f.deviation.iter().all(|&e| e < 1e-12), "{:?}", f.deviation);
    assert!(!f.shrunk);
}

#[test]
fn stiffness_rising_without_loss_is_no_passive_support_and_its_fit_says_so() {
    // k(w) = 2e5 + 500 w N/m with c = 100 N s/m: a rising storage stiffness with no loss to
    // go with it (Kramers-Kronig), which no sum of passive branches follows; the fit stays
    // passive and reports the deviation it is left with.
    let w: Vec<f64> = (0..=20).map(|i| 25.0 * i as f64).collect();
    let table: Vec<Coefficients> = w
        .iter()
        .map(|&w| Coefficients {
            k: Matrix2 {
                xx: 2e5 + 500.0 * w,
                xy: 0.0,
                yx: 0.0,
                yy: 2e5 + 500.0 * w,
            },
            c: Matrix2 {
                xx: 100.0,
                xy: 0.0,
                yx: 0.0,
                yy: 100.0,
            },
            m: Matrix2::default(),
        })
        .collect();
    let rates = geometric(12.5, 1000.0, MAX_BRANCHES);
    let f = fit_table(&w, table, &rates, true);
    let c0 = [f.base.c.xx, f.base.c.xy, f.base.c.yx, f.base.c.yy];
    let g: Vec<[f64; 4]> = f
        .branches
        .iter()
        .map(|m| [m.xx, m.xy, m.yx, m.yy])
        .collect();
    assert!(passive(&c0, &g, &rates));
    assert!(f.deviation[0] > 0.05, "{:?}", f.deviation);
}

/// The support of `examples/whirl-anisotropic.*` at `w`: linear between its frequencies, its
/// stiffness rising and damping falling to 3000 rad/s, flat from there to 1e6 rad/s.
fn flat_tail(w: f64) -> Coefficients {
    const F: [f64; 8] = [0.0, 500.0, 1000.0, 1500.0, 2000.0, 2500.0, 3000.0, 1e6];
    let line = |v: [f64; 7]| {
        let k = F.partition_point(|&f| f <= w).clamp(1, F.len() - 1) - 1;
        let (a, b) = (v[k.min(6)], v[(k + 1).min(6)]);
        a + (b - a) * ((w - F[k]) / (F[k + 1] - F[k])).clamp(0.0, 1.0)
    };
    let kxy = line([0.0, 0.7e5, 1.4e5, 2.0e5, 2.7e5, 3.4e5, 4.0e5]);
    Coefficients {
        k: Matrix2 {
            xx: line([2.0e6, 2.5e6, 3.0e6, 3.5e6, 4.0e6, 4.5e6, 5.0e6]),
            xy: kxy,
            yx: -kxy,
            yy: line([1.6e6, 2.0e6, 2.4e6, 2.8e6, 3.2e6, 3.6e6, 4.0e6]),
        },
        c: Matrix2 {
            xx: line([900.0, 750.0, 620.0, 510.0, 420.0, 375.0, 330.0]),
            xy: 0.0,
            yx: 0.0,
            yy: line([720.0, 600.0, 500.0, 410.0, 340.0, 300.0, 265.0]),
        },
        m: Matrix2::default(),
    }
}

#[test]
fn a_table_flat_over_decades_is_fitted_between_its_knots_and_held_at_its_anchor() {
    // Fitted at its knots and three readings between each two alone, the 16 branches over
    // [250, 2e6] 1/s saw the two decades from 3000 to 1e6 rad/s at 4 frequencies; between them
    // the cross-coupling swung to 1.5e8 N/m at 3.2e4 rad/s (the table's: 4e5) and the fitted
    // rotor had poles growing at +1000 1/s, while the deviation (relative to w C at 1e6 rad/s)
    // read 0.3%.
    let freqs = [0.0, 500.0, 1000.0, 1500.0, 2000.0, 2500.0, 3000.0, 1e6];
    let samples = design::samples(&freqs);
    let checks = design::checks(&samples);
    let anchors = [900.0];
    let fitted: Vec<f64> = samples.iter().chain(&anchors).copied().collect();
    let read = Read {
        samples: fitted.iter().map(|&w| flat_tail(w)).collect(),
        checks: checks.iter().map(|&w| flat_tail(w)).collect(),
        m0: Matrix2::default(),
    };
    let rates = geometric(250.0, 2e6, MAX_BRANCHES);
    let f = fit_at(
        &Design::new(&samples, &anchors, &rates),
        &read,
        &checks,
        false,
    )
    .unwrap();
    // Measured apart, at 20001 frequencies geometric from 1 to 1e6 rad/s: within what the fit
    // says (the table is not what passive branches give: its stiffness rises as its damping
    // falls, and the fit is left 38% off it at the worst).
    let fine: Vec<f64> = (0..=20000)
        .map(|k| 10f64.powf(6.0 * k as f64 / 20000.0))
        .collect();
    let table: Vec<Coefficients> = fine.iter().map(|&w| flat_tail(w)).collect();
    let apart = design::deviation(&fine, &table, &f.base, &f.branches, &rates);
    for e in 0..4 {
        assert!(
            apart[e] <= 1.01 * f.deviation[e],
            "{apart:?} {:?}",
            f.deviation
        );
    }
    assert!(f.deviation[0] < 0.4 && apart[1] < 0.07, "{apart:?}");
    // Held to the table at the anchor (a time response's speed).
    let at = design::deviation(&anchors, &[flat_tail(900.0)], &f.base, &f.branches, &rates);
    assert!(at.iter().all(|&d| d < 1e-6), "{at:?}");
    let c0 = [f.base.c.xx, f.base.c.xy, f.base.c.yx, f.base.c.yy];
    let g: Vec<[f64; 4]> = f
        .branches
        .iter()
        .map(|m| [m.xx, m.xy, m.yx, m.yy])
        .collect();
    assert!(passive(&c0, &g, &rates));
}
