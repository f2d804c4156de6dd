use super::*;

#[test]
fn skew_cross_coupling_is_isotropic_and_imaginary() {
    let k = Matrix2 {
        xx: 2.0,
        xy: 3.0,
        yx: -3.0,
        yy: 2.0,
    };
    assert!(k.isotropic());
    let (iso, an) = k.complex();
    assert_eq!((iso, an), (c64::new(2.0, -3.0), c64::new(0.0, 0.0)));
    // f_r = -(iso r + an conj r) equals -(K [x, y]) as a complex number.
    let general = Matrix2 {
        xx: 1.2,
        xy: 0.3,
        yx: -0.7,
        yy: 0.5,
    };
    let (iso, an) = general.complex();
    let (x, y) = (0.4, -1.3);
    let r = c64::new(x, y);
    let f = -(iso * r + an * r.conj());
    let fx = -(general.xx * x + general.xy * y);
    let fy = -(general.yx * x + general.yy * y);
    assert!((f - c64::new(fx, fy)).norm() < 1e-15);
}

#[test]
fn tables_are_linear_inside_and_held_outside() {
    let at = |k: f64| Coefficients {
        k: Matrix2 {
            xx: k,
            xy: 0.0,
            yx: 0.0,
            yy: k,
        },
        ..Coefficients::default()
    };
    let s = GeneralSupport {
        index: 0,
        seal: false,
        node: 0,
        link: None,
        law: Law::Table {
            speeds: vec![100.0, 200.0, 400.0],
            values: vec![at(1.0), at(3.0), at(4.0)],
            ross: None,
        },
        loss_factor: 0.0,
        branches: None,
    };
    assert_eq!(s.at(0.0).k.xx, 1.0);
    assert_eq!(s.at(150.0).k.xx, 2.0);
    assert_eq!(s.at(300.0).k.xx, 3.5);
    assert_eq!(s.at(1e4).k.xx, 4.0);
    assert!(held_warning("s", &s, 0.0, 300.0).unwrap().contains("first"));
    assert!(held_warning("s", &s, 150.0, 300.0).is_none());
}
