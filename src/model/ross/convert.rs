//! ROSS's elements as a Whirl beam rotor (the JSON every analysis takes as `rotor`).
//!
//! - Shaft: ROSS's nodes are kept. Shaft elements are grouped by their node `n` (0, 1, 2, ...
//!   without gaps); at each node the first element in the file is the shaft's, the others
//!   (`compressor_example`'s sleeves, shrink fits) become `sleeves` over it, one element long,
//!   their matrices added as ROSS adds them. Consecutive uniform elements that are the same in
//!   every respect are one segment of `elements: n` when Whirl's split `length / n` gives
//!   back exactly their length; a conical element (ROSS's `odl != odr` or `idl != idr`) is a
//!   segment of its own with `outer_diameter_right` / `inner_diameter_right`.
//! - Materials: deduplicated by (E, Poisson ratio, density) under ROSS's names. ROSS keeps E and
//!   G_s and recomputes Cowper's shear coefficient from `Poisson = E / (2 G_s) - 1` for the
//!   ratio of the element's mean diameters, `((idl + idr)/2) / ((odl + odr)/2)`
//!   (shaft_element.py, `shear_method_calc = "cowper"`); Whirl's default shear factor is the
//!   same formula for the same ratio, so `shear_factor` is left out. `"hutchinson"` is given as
//!   `shear_factor = 1/kappa` with ROSS's Hutchinson formula.
//! - `axial_force` (ROSS's sign: tension > 0) and `torque` are carried over; `alpha`, `beta`
//!   become `rayleigh_damping` in the nonrotating frame, as ROSS adds `alpha M + beta K` to the
//!   damping matrix with no circulatory term.
//! - Bearings and seals: each coefficient one number when constant, else an array over
//!   `speeds` (ROSS's `frequency`) with `interpolation: "ross"` (interp1d / smoothing spline,
//!   extrapolating, as ROSS reads it), unless some table's mass coefficients change with the
//!   speed: then every table is linear and held at its ends (a warning says so).
//!   `SealElement` and its subclasses go to `seals`.
//! - Point masses: the shaft's nodes or nodes off it, numbered as ROSS numbers them. Whirl's
//!   point mass is isotropic: `mx != my` is `min(mx, my)` plus a support of mass coefficients
//!   only (`mxx`, `myy`) on the node, exactly ROSS's mass matrix.
//! - Couplings (`CouplingElement`): a segment `{"length", "outer_diameter", "coupling"}` on
//!   their node, isotropic (`ross::coupling`); their dampers turn with the shafts in Whirl
//!   (a warning says so).
//! - Axial and torsional data are kept for the torsional and axial analyses (`motion`):
//!   couplings' `kt_z`, `kr_z`, `ct_z`, `cr_z`, bearings' `kzz`, `czz`; the elements' options
//!   `shear_effects`, `rotary_inertia` and `gyroscopic` are carried. Bearings' `mzz` and point
//!   masses' `mz` have no place (a warning says so).

use std::collections::BTreeMap;

use serde_json::{Map, Value, json};

use super::coupling::by_node_of;
use super::{Bearing, COEFFICIENTS, Coupling, Material, RossFile, ShaftElement, ShearMethod};
use crate::model::{Invalid, Limits};

/// A converted rotor and what the conversion says about it.
#[derive(Debug, Clone)]
pub struct Converted {
    pub rotor: Value,
    pub warnings: Vec<String>,
}

/// Sleeve lengths may differ from their shaft element's by rounding only.
const SAME_LENGTH: f64 = 1e-9;

pub fn to_whirl(file: &RossFile, limits: &Limits) -> Result<Converted, Invalid> {
    let mut bad = Invalid::default();
    let mut warnings = vec![];
    if let Some(v) = &file.version
        && v != super::ROSS_VERSION
    {
        warnings.push(format!(
            "the file was written by ROSS {v}; the converter reads ROSS {}'s format",
            super::ROSS_VERSION
        ));
    }
    if !file.parameters.is_empty() {
        warnings.push(format!(
            "the rotor's parameters ({}) have no place in a Whirl rotor: give speeds to each \
             analysis",
            file.parameters.join(", ")
        ));
    }

    // The shaft: elements by node, in the file's order at each node; a coupling on a node of
    // its own.
    let mut by_node: BTreeMap<usize, Vec<&ShaftElement>> = BTreeMap::new();
    for e in &file.shaft {
        by_node.entry(e.n).or_default().push(e);
    }
    let couplings = match by_node_of(file, &by_node, &mut warnings) {
        Ok(c) => c,
        Err(e) => {
            bad.extend(e);
            return Err(bad);
        }
    };
    // Every node's element, shaft or coupling, by node.
    let mut line: BTreeMap<usize, Result<&Vec<&ShaftElement>, &Coupling>> =
        by_node.iter().map(|(&n, g)| (n, Ok(g))).collect();
    line.extend(couplings.iter().map(|(&n, &c)| (n, Err(c))));
    let elements = line.len();
    let max_elements = (limits.max_dofs / 2).saturating_sub(1).max(1);
    if let Some((k, (&n, e))) = line.iter().enumerate().find(|(k, (n, _))| *k != **n) {
        let (table, at) = match e {
            Ok(group) => (group[0].table.as_str(), group[0].line),
            Err(c) => (c.table.as_str(), c.line),
        };
        bad.push(
            table,
            format!(
                "starts at node {n} (line {at}), but no shaft element starts at node {k}: ROSS's \
                 shaft elements run from node 0 without gaps"
            ),
        );
        return Err(bad);
    }
    if elements > max_elements {
        bad.push(
            "ShaftElement",
            format!(
                "{elements} shaft elements give {} degrees of freedom, more than the limit of \
                 {} (WHIRL_MAX_DOFS)",
                2 * (elements + 1),
                limits.max_dofs
            ),
        );
        return Err(bad);
    }
    let last_shaft_node = elements; // nodes 0..=elements

    let mut materials = Materials::default();
    // Each segment with the shaft element it repeats (none for a coupling).
    let mut segments: Vec<(Value, Option<&ShaftElement>, usize)> = vec![];
    let mut sleeves = vec![];
    for element in line.values() {
        let group = match element {
            Ok(group) => group,
            Err(c) => {
                segments.push((c.segment(), None, 1));
                continue;
            }
        };
        let e = group[0];
        let material = materials.name(&e.material);
        // Joined to the previous segment when that is exactly the same uniform element.
        if let Some((seg, Some(prev), count)) = segments.last_mut()
            && mergeable(prev, e)
        {
            let k = (*count + 1) as f64;
            let total = e.length * k;
            if total / k == e.length {
                *count += 1;
                seg["length"] = json!(total);
                seg["elements"] = json!(*count);
                continue;
            }
        }
        let mut seg = element_fields(e, &material);
        seg.insert("length".into(), json!(e.length));
        segments.push((Value::Object(seg), Some(e), 1));
        for s in &group[1..] {
            if (s.length - e.length).abs() > SAME_LENGTH * e.length {
                bad.push(
                    s.table.as_str(),
                    format!(
                        "shares node {} with {} (a sleeve over it) but its length L = {} is not \
                         that element's {} (line {}): ROSS places elements on the same node \
                         over the same span",
                        s.n, e.table, s.length, e.length, s.line
                    ),
                );
                continue;
            }
            let name = materials.name(&s.material);
            let mut sleeve = element_fields(s, &name);
            sleeve.insert("node".into(), json!(s.n));
            sleeve.insert("elements".into(), json!(1));
            sleeves.push(Value::Object(sleeve));
        }
    }
    let rayleigh = file.shaft.iter().any(|e| e.alpha != 0.0 || e.beta != 0.0);
    if rayleigh {
        warnings.push(
            "ROSS's proportional damping of shaft elements (alpha M + beta K) is added to the \
             damping matrix with no circulatory term: it is converted as `rayleigh_damping` in \
             the nonrotating frame (`frame: \"nonrotating\"`), as ROSS computes it, though \
             damping of the shaft's material turns with it (`frame: \"rotating\"`)"
                .into(),
        );
    }
    let both: Vec<String> = file
        .shaft
        .iter()
        .filter(|e| e.beta != 0.0 && e.torque != 0.0)
        .map(|e| e.table.clone())
        .collect();
    if !both.is_empty() {
        warnings.push(format!(
            "{}: ROSS's beta multiplies the element's whole stiffness, its torque's geometric \
             (circulatory) stiffness included; Whirl's `beta K` leaves the torque's out, so the \
             damping differs by beta T / L there",
            both.join(", ")
        ));
    }
    if file
        .shaft
        .iter()
        .any(|e| e.shear == ShearMethod::Hutchinson)
    {
        warnings.push(
            "shear_method_calc = \"hutchinson\" is given as each element's `shear_factor` (1 / \
             kappa of ROSS's Hutchinson formula)"
                .into(),
        );
    }

    // Point masses: on the shaft's nodes, or off it numbered on from its last node.
    let mut off: Vec<usize> = file
        .point_masses
        .iter()
        .map(|p| p.n)
        .filter(|&n| n > last_shaft_node)
        .collect();
    off.sort_unstable();
    off.dedup();
    if let Some((k, &n)) = off
        .iter()
        .enumerate()
        .find(|(k, n)| **n != last_shaft_node + 1 + k)
    {
        let p = file.point_masses.iter().find(|p| p.n == n).expect("listed");
        bad.push(
            format!("{}.n", p.table),
            format!(
                "node {n} is off the shaft (nodes 0 to {last_shaft_node}) and leaves a gap \
                 (line {}): ROSS numbers the nodes off the shaft on from the shaft's last \
                 node, without gaps (next: {})",
                p.line,
                last_shaft_node + 1 + k
            ),
        );
    }
    if 2 * (last_shaft_node + 1) + off.len() > limits.max_dofs {
        bad.push(
            "PointMass",
            format!(
                "{} nodes off the shaft give {} degrees of freedom, more than the limit of {} \
                 (WHIRL_MAX_DOFS)",
                off.len(),
                2 * (last_shaft_node + 1) + off.len(),
                limits.max_dofs
            ),
        );
    }
    let last_node = last_shaft_node + off.len();
    let mut point_masses = vec![];
    let mut mass_supports = vec![];
    let mut seen = std::collections::BTreeSet::new();
    for p in &file.point_masses {
        let m = p.mx.min(p.my);
        if p.n > last_shaft_node && m == 0.0 {
            bad.push(
                p.table.as_str(),
                format!(
                    "has no mass in x or y (mx = {}, my = {}) on node {}, off the shaft (line \
                     {}): that node's motion would have no mass (ROSS's mass matrix is \
                     singular too)",
                    p.mx, p.my, p.n, p.line
                ),
            );
            continue;
        }
        if p.n <= last_shaft_node || !seen.insert(p.n) {
            warnings.push(format!(
                "{}: its mass is added to node {}'s translations; ROSS 2.3.0 also gives every \
                 point mass 3 degrees of freedom of its own, which here stay empty (a singular \
                 mass matrix: ROSS's run_modal fails on this rotor)",
                p.table, p.n
            ));
        }
        point_masses.push(json!({"node": p.n, "mass": m}));
        if p.mx != p.my {
            warnings.push(format!(
                "{}: mx = {} and my = {} differ; Whirl's point mass is isotropic, so it is \
                 {m} kg with the rest as a support of mass coefficients only (mxx = {}, myy = \
                 {}) on node {}: the same mass matrix",
                p.table,
                p.mx,
                p.my,
                p.mx - m,
                p.my - m,
                p.n
            ));
            let mut s = json!({"node": p.n, "kxx": 0.0, "kyy": 0.0, "cxx": 0.0, "cyy": 0.0});
            for (key, extra) in [("mxx", p.mx - m), ("myy", p.my - m)] {
                if extra != 0.0 {
                    s[key] = json!(extra);
                }
            }
            mass_supports.push(s);
        }
    }

    let mut disks = vec![];
    for d in &file.disks {
        if d.n > last_shaft_node {
            bad.push(
                format!("{}.n", d.table),
                format!(
                    "node {} is not on the shaft (nodes 0 to {last_shaft_node}) (line {})",
                    d.n, d.line
                ),
            );
            continue;
        }
        disks.push(json!({
            "node": d.n, "mass": d.mass, "polar_inertia": d.polar_inertia,
            "transverse_inertia": d.transverse_inertia,
        }));
    }

    let mut supports = vec![];
    let mut seals = vec![];
    let mut tables = false;
    // ROSS's interpolation needs every table's mass constant (supports.rs: check_schedule).
    let varying_mass = file.bearings.iter().find(|b| {
        b.speeds.is_some() && b.values[8..12].iter().any(|v| v.iter().any(|x| *x != v[0]))
    });
    for b in &file.bearings {
        let mut ok = true;
        for (key, node) in [("n", Some(b.n)), ("n_link", b.n_link)] {
            if let Some(node) = node
                && node > last_node
            {
                bad.push(
                    format!("{}.{key}", b.table),
                    format!(
                        "node {node} is neither on the shaft (nodes 0 to {last_shaft_node}) \
                         nor a point mass's node off it{} (line {})",
                        if last_node > last_shaft_node {
                            format!(" ({} to {last_node})", last_shaft_node + 1)
                        } else {
                            String::new()
                        },
                        b.line
                    ),
                );
                ok = false;
            }
        }
        if b.n_link == Some(b.n) {
            bad.push(
                format!("{}.n_link", b.table),
                format!("links node {} to itself (line {})", b.n, b.line),
            );
            ok = false;
        }
        if !ok {
            continue;
        }
        let (s, tabulated) = support(b, varying_mass.is_none(), &mut warnings);
        tables |= tabulated;
        if b.seal {
            seals.push(s);
        } else {
            supports.push(s);
        }
    }
    supports.extend(mass_supports);
    if let (true, Some(b)) = (tables, varying_mass) {
        warnings.push(format!(
            "tables are read linearly between their speeds and held at the end values outside \
             (interpolation \"linear\"), not with ROSS's interp1d / smoothing spline, because \
             {}'s mass coefficients change with the speed (ROSS's interpolation is available \
             for stiffness and damping only): between and beyond the table speeds the \
             coefficients, and the poles, differ from ROSS's",
            b.table
        ));
    }
    if !bad.is_empty() {
        return Err(bad);
    }

    let mut rotor = Map::new();
    rotor.insert("type".into(), json!("beam"));
    rotor.insert("materials".into(), materials.into_json());
    rotor.insert(
        "shaft".into(),
        Value::Array(segments.into_iter().map(|(s, _, _)| s).collect()),
    );
    rotor.insert("disks".into(), Value::Array(disks));
    rotor.insert("supports".into(), Value::Array(supports));
    for (key, list) in [
        ("seals", seals),
        ("point_masses", point_masses),
        ("sleeves", sleeves),
    ] {
        if !list.is_empty() {
            rotor.insert(key.into(), Value::Array(list));
        }
    }
    Ok(Converted {
        rotor: Value::Object(rotor),
        warnings,
    })
}

/// Whether `e` continues the uniform segment of `prev` exactly.
fn mergeable(prev: &ShaftElement, e: &ShaftElement) -> bool {
    let uniform = |x: &ShaftElement| x.idl == x.idr && x.odl == x.odr;
    uniform(prev)
        && uniform(e)
        && prev.length == e.length
        && prev.odl == e.odl
        && prev.idl == e.idl
        && prev.material == e.material
        && prev.axial_force == e.axial_force
        && prev.torque == e.torque
        && prev.alpha == e.alpha
        && prev.beta == e.beta
        && prev.shear == e.shear
        && (prev.shear_effects, prev.rotary_inertia, prev.gyroscopic)
            == (e.shear_effects, e.rotary_inertia, e.gyroscopic)
}

/// The fields a shaft segment and a sleeve share.
fn element_fields(e: &ShaftElement, material: &str) -> Map<String, Value> {
    let mut m = Map::new();
    m.insert("outer_diameter".into(), json!(e.odl));
    m.insert("inner_diameter".into(), json!(e.idl));
    if e.odr != e.odl {
        m.insert("outer_diameter_right".into(), json!(e.odr));
    }
    if e.idr != e.idl {
        m.insert("inner_diameter_right".into(), json!(e.idr));
    }
    m.insert("material".into(), json!(material));
    if !e.shear_effects {
        m.insert("shear_effects".into(), json!(false));
    } else if e.shear == ShearMethod::Hutchinson {
        m.insert("shear_factor".into(), json!(1.0 / hutchinson_kappa(e)));
    }
    for (key, on) in [
        ("rotary_inertia", e.rotary_inertia),
        ("gyroscopic", e.gyroscopic),
    ] {
        if !on {
            m.insert(key.into(), json!(false));
        }
    }
    if e.axial_force != 0.0 {
        m.insert("axial_force".into(), json!(e.axial_force));
    }
    if e.torque != 0.0 {
        m.insert("torque".into(), json!(e.torque));
    }
    if e.alpha != 0.0 || e.beta != 0.0 {
        m.insert(
            "rayleigh_damping".into(),
            json!({"alpha": e.alpha, "beta": e.beta, "frame": "nonrotating"}),
        );
    }
    m
}

/// ROSS's Hutchinson (2001) shear coefficient for the ratio of the mean diameters
/// (shaft_element.py).
fn hutchinson_kappa(e: &ShaftElement) -> f64 {
    let r = ((e.idl + e.idr) / 2.0) / ((e.odl + e.odr) / 2.0);
    let r2 = r * r;
    let r12 = (1.0 + r2) * (1.0 + r2);
    let nu = e.material.poisson_ratio;
    6.0 * r12 * (1.0 + nu)
        / (r12 * (7.0 + 12.0 * nu + 4.0 * nu * nu) + 4.0 * r2 * (5.0 + 6.0 * nu + 2.0 * nu * nu))
}

/// A bearing or seal as a Whirl support; whether it is tabulated.
fn support(b: &Bearing, ross: bool, warnings: &mut Vec<String>) -> (Value, bool) {
    let mut s = Map::new();
    s.insert("node".into(), json!(b.n));
    if let Some(l) = b.n_link {
        s.insert("n_link".into(), json!(l));
    }
    let constant = |v: &[f64]| v.iter().all(|x| *x == v[0]);
    let tabulated = b.speeds.is_some() && b.values[..14].iter().any(|v| !constant(v));
    for (name, v) in COEFFICIENTS[..14].iter().zip(&b.values) {
        // kxx, kyy, cxx, cyy always (Whirl's kyy and cyy default to kxx and cxx, not ROSS's
        // values); the others when not 0.
        let always = matches!(*name, "kxx" | "kyy" | "cxx" | "cyy");
        let value = if tabulated && !constant(v) {
            json!(v)
        } else if always || v[0] != 0.0 {
            json!(v[0])
        } else {
            continue;
        };
        s.insert((*name).into(), value);
    }
    if tabulated {
        s.insert("speeds".into(), json!(b.speeds));
        if ross {
            s.insert("interpolation".into(), json!("ross"));
        }
    }
    let axial: Vec<&str> = COEFFICIENTS[14..]
        .iter()
        .zip(&b.values[14..])
        .filter(|(_, v)| v.iter().any(|x| *x != 0.0))
        .map(|(n, _)| *n)
        .collect();
    if !axial.is_empty() {
        warnings.push(format!(
            "{}: {} (an axial mass coefficient) has no place in a Whirl support: dropped",
            b.table,
            axial.join(", ")
        ));
    }
    (Value::Object(s), tabulated)
}

/// Materials by their properties, named as ROSS names them (a name given to two different
/// materials gets a suffix).
#[derive(Default)]
struct Materials {
    list: Vec<(Material, String)>,
}

impl Materials {
    fn name(&mut self, m: &Material) -> String {
        let same = |a: &Material| {
            a.young_modulus == m.young_modulus
                && a.poisson_ratio == m.poisson_ratio
                && a.density == m.density
        };
        if let Some((_, name)) = self.list.iter().find(|(a, _)| same(a)) {
            return name.clone();
        }
        let base = if m.name.is_empty() {
            "material".to_string()
        } else {
            m.name.clone()
        };
        let mut name = base.clone();
        let mut k = 2;
        while self.list.iter().any(|(_, n)| *n == name) {
            name = format!("{base}_{k}");
            k += 1;
        }
        self.list.push((m.clone(), name.clone()));
        name
    }

    fn into_json(self) -> Value {
        Value::Object(
            self.list
                .into_iter()
                .map(|(m, name)| {
                    (
                        name,
                        json!({
                            "young_modulus": m.young_modulus,
                            "density": m.density,
                            "poisson_ratio": m.poisson_ratio,
                        }),
                    )
                })
                .collect(),
        )
    }
}

#[cfg(test)]
#[path = "convert_tests.rs"]
mod tests;
