//! ROSS's `CouplingElement`, read from its table: a coupling in the shaft line from node `n` to
//! `n + 1` (`model::coupling`), its lateral part. Whirl's coupling is isotropic (a rotating
//! element stiffer in one direction turns that direction with it, which no time-invariant model
//! holds), so `kt_x = kt_y`, `kr_x = kr_y`, `ct_x = ct_y` and `cr_x = cr_y` are required; the
//! axial and torsional terms (`kt_z`, `kr_z`, `ct_z`, `cr_z`) are its axial and torsional
//! stiffness and damping.

use super::*;
use crate::model::api::CouplingInput;
use serde_json::{Value, json};
use std::collections::BTreeMap;

const COUPLING_KEYS: &[&str] = &[
    "m_l",
    "m_r",
    "Ip_l",
    "Ip_r",
    "Id_l",
    "Id_r",
    "kt_x",
    "kt_y",
    "kt_z",
    "kr_x",
    "kr_y",
    "kr_z",
    "ct_x",
    "ct_y",
    "ct_z",
    "cr_x",
    "cr_y",
    "cr_z",
    "o_d",
    "L",
    "n",
    "tag",
    "scale_factor",
    "color",
];

/// ROSS's `CouplingElement`, lateral and isotropic.
#[derive(Debug, Clone)]
pub struct Coupling {
    pub table: String,
    pub line: usize,
    pub n: usize,
    /// `L`, `o_d` (ROSS draws with them; they place the nodes after it).
    pub length: f64,
    pub outer_diameter: f64,
    /// The coupling as Whirl takes it (`Id` absent or 0 is ROSS's half of `Ip`).
    pub coupling: CouplingInput,
}

impl Coupling {
    /// The Whirl shaft segment: `{"length", "outer_diameter", "coupling": {...}}`.
    pub fn segment(&self) -> Value {
        json!({
            "length": self.length,
            "outer_diameter": self.outer_diameter,
            "coupling": self.coupling,
        })
    }
}

pub(super) fn coupling(r: &mut Reader, tab: &Tab) -> Option<Coupling> {
    r.only(tab, COUPLING_KEYS, "CouplingElement");
    let n = r.node(tab, "n", true).flatten();
    let length = r.number(tab, "L", Some(0.2));
    let od = r.number(tab, "o_d", Some(0.2));
    let m = [r.number(tab, "m_l", None), r.number(tab, "m_r", None)];
    let ip = [r.number(tab, "Ip_l", None), r.number(tab, "Ip_r", None)];
    let id = [
        r.number(tab, "Id_l", Some(0.0)),
        r.number(tab, "Id_r", Some(0.0)),
    ];
    let mut ok = true;
    let mut same = |r: &mut Reader, x: &str, y: &str| -> Option<f64> {
        let (a, b) = (r.number(tab, x, Some(0.0))?, r.number(tab, y, Some(0.0))?);
        if a != b {
            let line = tab.get(y).map_or(tab.line, |v| r.line(v.span()));
            r.push(
                tab,
                Some(y),
                line,
                format!(
                    "is {b}, but {x} is {a}: a Whirl coupling is isotropic (a coupling stiffer \
                     in one direction turns that direction with the shaft, which no \
                     time-invariant model holds)"
                ),
            );
            ok = false;
        }
        Some(a)
    };
    let kt = same(r, "kt_x", "kt_y");
    let kr = same(r, "kr_x", "kr_y");
    let ct = same(r, "ct_x", "ct_y");
    let cr = same(r, "cr_x", "cr_y");
    let mut z = |key: &str| r.number(tab, key, Some(0.0));
    let (kz, kaz, cz, caz) = (z("kr_z"), z("kt_z"), z("cr_z"), z("ct_z"));
    let pair = |v: [Option<f64>; 2]| Some([v[0]?, v[1]?]);
    let (ip, id) = (pair(ip)?, pair(id)?);
    Some(Coupling {
        table: tab.name.to_string(),
        line: tab.line,
        n: n?,
        length: length?,
        outer_diameter: od?,
        coupling: CouplingInput {
            translational_stiffness: kt?,
            angular_stiffness: kr?,
            translational_damping: ct?,
            angular_damping: cr?,
            loss_factor: 0.0,
            mass: pair(m)?,
            polar_inertia: ip,
            transverse_inertia: Some(
                [0, 1].map(|k| if id[k] != 0.0 { id[k] } else { ip[k] / 2.0 }),
            ),
            torsional_stiffness: kz?,
            torsional_damping: cz?,
            axial_stiffness: kaz?,
            axial_damping: caz?,
        },
    })
    .filter(|_| ok)
}

/// The file's couplings by node, each alone on its node (no shaft element, no other coupling
/// there), and the warning that their dampers now turn.
pub(super) fn by_node_of<'f>(
    file: &'f RossFile,
    by_node: &BTreeMap<usize, Vec<&ShaftElement>>,
    warnings: &mut Vec<String>,
) -> Result<BTreeMap<usize, &'f Coupling>, Invalid> {
    let mut bad = Invalid::default();
    let mut couplings: BTreeMap<usize, &Coupling> = BTreeMap::new();
    for c in &file.couplings {
        let taken = by_node
            .get(&c.n)
            .map(|g| g[0].table.clone())
            .or_else(|| couplings.get(&c.n).map(|o| o.table.clone()));
        if let Some(other) = taken {
            bad.push(
                c.table.as_str(),
                format!(
                    "starts at node {} (line {}), as {other} does: a coupling is an element of \
                     the shaft line, alone on its node",
                    c.n, c.line
                ),
            );
            return Err(bad);
        }
        couplings.insert(c.n, c);
    }
    if !couplings.is_empty() {
        warnings.push(
            "ROSS adds a CouplingElement's dampers (ct, cr) to the nonrotating damping matrix; \
             Whirl's coupling turns with the shafts, so its dampers are rotating damping, with \
             their circulatory term (the same at rest, apart when spun)"
                .into(),
        );
    }
    Ok(couplings)
}
