//! The elements of a ROSS file read from their tables: shaft elements and their materials,
//! disks, point masses, bearings and seals.

use super::*;

pub(super) fn shaft_element(r: &mut Reader, tab: &Tab) -> Option<ShaftElement> {
    r.only(tab, SHAFT_KEYS, "ShaftElement");
    let n = r.node(tab, "n", true).flatten();
    let length = r.number(tab, "L", None);
    let idl = r.number(tab, "idl", None);
    let odl = r.number(tab, "odl", None);
    let idr = r.number(tab, "idr", idl);
    let odr = r.number(tab, "odr", odl);
    let axial_force = r.number(tab, "axial_force", Some(0.0));
    let torque = r.number(tab, "torque", Some(0.0));
    let alpha = r.number(tab, "alpha", Some(0.0));
    let beta = r.number(tab, "beta", Some(0.0));
    let material = shaft_material(r, tab);
    let flags = ["shear_effects", "rotary_inertia", "gyroscopic"].map(|k| r.flag(tab, k, true));
    let shear = match r.string(tab, "shear_method_calc")? {
        None => Some(ShearMethod::Cowper),
        Some(s) if s == "cowper" => Some(ShearMethod::Cowper),
        Some(s) if s == "hutchinson" => Some(ShearMethod::Hutchinson),
        Some(s) => {
            let line = tab
                .get("shear_method_calc")
                .map_or(tab.line, |v| r.line(v.span()));
            r.push(
                tab,
                Some("shear_method_calc"),
                line,
                format!("must be \"cowper\" or \"hutchinson\", as in ROSS (got \"{s}\")"),
            );
            None
        }
    };
    let mut ok = true;
    for (key, v, positive) in [
        ("L", length, true),
        ("odl", odl, true),
        ("odr", odr, true),
        ("idl", idl, false),
        ("idr", idr, false),
    ] {
        if let Some(x) = v
            && (x < 0.0 || (positive && x == 0.0))
        {
            let line = tab.get(key).map_or(tab.line, |v| r.line(v.span()));
            let want = if positive { "> 0" } else { ">= 0" };
            r.push(tab, Some(key), line, format!("must be {want} (got {x})"));
            ok = false;
        }
    }
    for (inner, outer, ki) in [(idl, odl, "idl"), (idr, odr, "idr")] {
        if let (Some(i), Some(o)) = (inner, outer)
            && i >= o
        {
            let line = tab.get(ki).map_or(tab.line, |v| r.line(v.span()));
            r.push(
                tab,
                Some(ki),
                line,
                format!("must be smaller than the outer diameter {o} (got {i})"),
            );
            ok = false;
        }
    }
    for (key, v) in [("alpha", alpha), ("beta", beta)] {
        if let Some(x) = v
            && x < 0.0
        {
            let line = tab.get(key).map_or(tab.line, |v| r.line(v.span()));
            r.push(
                tab,
                Some(key),
                line,
                format!("must be >= 0 (got {x}): Whirl's Rayleigh damping is dissipative"),
            );
            ok = false;
        }
    }
    Some(ShaftElement {
        table: tab.name.to_string(),
        line: tab.line,
        n: n?,
        length: length?,
        idl: idl?,
        odl: odl?,
        idr: idr?,
        odr: odr?,
        material: material?,
        axial_force: axial_force?,
        torque: torque?,
        alpha: alpha?,
        beta: beta?,
        shear: shear?,
        shear_effects: flags[0]?,
        rotary_inertia: flags[1]?,
        gyroscopic: flags[2]?,
    })
    .filter(|_| ok)
}

/// The material subtable: `rho` and two of `E`, `G_s`, `Poisson` (as ROSS's `Material`).
pub(super) fn shaft_material(r: &mut Reader, tab: &Tab) -> Option<Material> {
    let Some(v) = tab.get("material") else {
        r.push(tab, Some("material"), tab.line, "is missing");
        return None;
    };
    let line = r.line(v.span());
    let DeValue::Table(entries) = v.get_ref() else {
        r.push(
            tab,
            Some("material"),
            line,
            "must be the material's table (`name`, `rho`, `E`, `G_s`): a material named only \
             refers to ROSS's own library, which the file does not hold",
        );
        return None;
    };
    let name = format!("{}.material", tab.name);
    let m = Tab {
        name: &name,
        line,
        entries,
    };
    let label = r.string(&m, "name")?.unwrap_or_else(|| "material".into());
    let rho = r.number(&m, "rho", None);
    let given: Vec<&str> = ["E", "G_s", "Poisson"]
        .into_iter()
        .filter(|k| m.get(k).is_some())
        .collect();
    if given.len() != 2 {
        r.push(
            &m,
            None,
            line,
            format!(
                "needs exactly two of E, G_s and Poisson, as ROSS's Material (got {})",
                if given.is_empty() {
                    "none".into()
                } else {
                    given.join(", ")
                }
            ),
        );
        return None;
    }
    let e = r.number(&m, "E", Some(f64::NAN));
    let g = r.number(&m, "G_s", Some(f64::NAN));
    let nu = r.number(&m, "Poisson", Some(f64::NAN));
    let (rho, e, g, nu) = (rho?, e?, g?, nu?);
    // ROSS: E = 2 G_s (1 + nu), G_s = E / (2 (1 + nu)), nu = E / (2 G_s) - 1.
    let (e, nu) = if e.is_nan() {
        (g * (2.0 * (1.0 + nu)), nu)
    } else if nu.is_nan() {
        (e, e / (2.0 * g) - 1.0)
    } else {
        (e, nu)
    };
    let mut ok = true;
    for (key, x) in [("rho", rho), ("E", e)] {
        if !(x > 0.0 && x.is_finite()) {
            r.push(&m, Some(key), line, format!("must be > 0 (got {x})"));
            ok = false;
        }
    }
    if ok && !(nu > -1.0 && nu < 0.5) {
        r.push(
            &m,
            None,
            line,
            format!(
                "its Poisson ratio (E / (2 G_s) - 1 = {nu}) is outside (-1, 0.5), where a \
                 Whirl material is defined"
            ),
        );
        ok = false;
    }
    ok.then_some(Material {
        name: label,
        density: rho,
        young_modulus: e,
        poisson_ratio: nu,
    })
}

pub(super) fn disk(r: &mut Reader, tab: &Tab) -> Option<Disk> {
    r.only(tab, DISK_KEYS, "DiskElement");
    let n = r.node(tab, "n", true).flatten();
    let mass = r.number(tab, "m", None);
    let id = r.number(tab, "Id", None);
    let ip = r.number(tab, "Ip", None);
    let mut ok = true;
    for (key, v) in [("m", mass), ("Id", id), ("Ip", ip)] {
        if let Some(x) = v
            && x < 0.0
        {
            let line = tab.get(key).map_or(tab.line, |v| r.line(v.span()));
            r.push(tab, Some(key), line, format!("must be >= 0 (got {x})"));
            ok = false;
        }
    }
    Some(Disk {
        table: tab.name.to_string(),
        line: tab.line,
        n: n?,
        mass: mass?,
        transverse_inertia: id?,
        polar_inertia: ip?,
    })
    .filter(|_| ok)
}

pub(super) fn point_mass(r: &mut Reader, tab: &Tab) -> Option<PointMass> {
    r.only(tab, POINT_MASS_KEYS, "PointMass");
    let n = r.node(tab, "n", true).flatten();
    // ROSS: with none of mx, my, mz, each is m; otherwise mx and my are required, mz is 0 when
    // absent.
    let directional = ["mx", "my", "mz"].iter().any(|k| tab.get(k).is_some());
    let (mx, my, mz) = if directional {
        (
            r.number(tab, "mx", None),
            r.number(tab, "my", None),
            r.number(tab, "mz", Some(0.0)),
        )
    } else {
        let m = r.number(tab, "m", None);
        (m, m, m)
    };
    let mut ok = true;
    for (key, v) in [("mx", mx), ("my", my), ("mz", mz)] {
        if let Some(x) = v
            && x < 0.0
        {
            let key = if directional { key } else { "m" };
            let line = tab.get(key).map_or(tab.line, |v| r.line(v.span()));
            r.push(tab, Some(key), line, format!("must be >= 0 (got {x})"));
            ok = false;
        }
    }
    Some(PointMass {
        table: tab.name.to_string(),
        line: tab.line,
        n: n?,
        mx: mx?,
        my: my?,
        mz: mz?,
    })
    .filter(|_| ok)
}

pub(super) fn bearing(
    r: &mut Reader,
    tab: &Tab,
    class: &str,
    speeds_key: Option<&str>,
) -> Option<Bearing> {
    let n = r.node(tab, "n", true).flatten();
    let n_link = r.node(tab, "n_link", false);
    let key = if tab.get("frequency").is_some() {
        "frequency"
    } else {
        speeds_key.unwrap_or("frequency")
    };
    let speeds = r.numbers(tab, key);
    let mut columns: Vec<Option<Option<Vec<f64>>>> = vec![];
    for name in COEFFICIENTS {
        columns.push(r.numbers(tab, name));
    }
    let (n, n_link, speeds) = (n?, n_link?, speeds?);
    let mut columns: Vec<Option<Vec<f64>>> = columns.into_iter().collect::<Option<_>>()?;
    for required in ["kxx", "cxx"] {
        if tab.get(required).is_none() {
            r.push(
                tab,
                Some(required),
                tab.line,
                "is missing (ROSS's BearingElement requires it)",
            );
            return None;
        }
    }
    // ROSS's defaults: kyy = kxx, cyy = cxx, myy = mxx; the others 0.
    for (col, from) in [(3, 0), (7, 4), (11, 8)] {
        if columns[col].is_none() {
            columns[col] = columns[from].clone();
        }
    }
    let values: Vec<Vec<f64>> = columns
        .into_iter()
        .map(|c| c.unwrap_or_else(|| vec![0.0]))
        .collect();
    // A table has its speeds and every coefficient one value per speed (ROSS expands a number
    // to the table's length and refuses arrays of another length); without one, every
    // coefficient is one value.
    let points = speeds.as_ref().map_or(1, Vec::len);
    let line_of = |r: &Reader, k: &str| tab.get(k).map_or(tab.line, |v| r.line(v.span()));
    let mut ok = true;
    for (name, v) in COEFFICIENTS.iter().zip(&values) {
        // A number (not an array) stands for every speed, as ROSS expands it; so does a
        // default (kyy from kxx is already of the table's length).
        let scalar = !matches!(tab.get(name).map(|v| v.get_ref()), Some(DeValue::Array(_)));
        if v.len() != points && !(v.len() == 1 && scalar) {
            let line = line_of(r, name);
            r.push(
                tab,
                Some(name),
                line,
                format!(
                    "has {} values for the {points} speed(s) of `{key}` (ROSS requires one per \
                     speed)",
                    v.len()
                ),
            );
            ok = false;
        }
    }
    if let Some(w) = &speeds {
        for (i, x) in w.iter().enumerate() {
            if *x < 0.0 || (i > 0 && *x <= w[i - 1]) {
                let line = line_of(r, key);
                r.push(
                    tab,
                    Some(&format!("{key}[{i}]")),
                    line,
                    "the speeds of a table must be >= 0 and strictly increasing (ROSS's \
                     spline needs them increasing)",
                );
                ok = false;
                break;
            }
        }
    }
    if !ok {
        return None;
    }
    // Expand the defaults of a table to its length.
    let values = values
        .into_iter()
        .map(|v| {
            if v.len() == 1 && points > 1 {
                vec![v[0]; points]
            } else {
                v
            }
        })
        .collect();
    Some(Bearing {
        table: tab.name.to_string(),
        line: tab.line,
        class: class.to_string(),
        seal: SEALS.contains(&class),
        n,
        n_link,
        speeds: speeds.filter(|w| w.len() > 1),
        values,
    })
}
