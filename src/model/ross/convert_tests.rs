//! The converter's shear factors and element fields.
use super::*;

fn element(shear: ShearMethod) -> ShaftElement {
    let (e, g) = (211e9, 81.2e9);
    ShaftElement {
        table: "ShaftElement_0".into(),
        line: 1,
        n: 0,
        length: 0.1,
        idl: 0.02,
        odl: 0.07,
        idr: 0.03,
        odr: 0.05,
        material: Material {
            name: "Steel".into(),
            density: 7810.0,
            young_modulus: e,
            poisson_ratio: e / (2.0 * g) - 1.0,
        },
        axial_force: 0.0,
        torque: 0.0,
        alpha: 0.0,
        beta: 0.0,
        shear,
        shear_effects: true,
        rotary_inertia: true,
        gyroscopic: true,
    }
}

#[test]
fn hutchinsons_kappa_is_rosss() {
    // ROSS 2.3.0: ShaftElement(L=0.1, idl=0.02, odl=0.07, idr=0.03, odr=0.05,
    // material=Material(E=211e9, G_s=81.2e9), shear_method_calc="hutchinson").kappa
    let kappa = hutchinson_kappa(&element(ShearMethod::Hutchinson));
    assert!((kappa - 0.5388931804974394).abs() < 1e-15, "{kappa}");
    let seg = element_fields(&element(ShearMethod::Hutchinson), "Steel");
    assert_eq!(seg["shear_factor"], json!(1.0 / kappa));
    // Cowper's is Whirl's default for the mean diameters: no shear_factor.
    assert!(!element_fields(&element(ShearMethod::Cowper), "Steel").contains_key("shear_factor"));
}
