//! Supports (bearings, seals, pedestals) in their general form: stiffness, damping and mass
//! coefficients `[[xx, xy], [yx, yy]]`, possibly tabulated against spin speed.
//!
//! The force on the shaft is `f = -K [x, y] - C [x', y'] - M [x'', y'']` (the convention of
//! ROSS and API 684). In complex coordinates `r = x + i y` a coefficient matrix `A` acts as
//! `f_r = -(a_iso r + a_an conj(r))` with `a_iso = (xx + yy)/2 + i (yx - xy)/2` and
//! `a_an = (xx - yy)/2 + i (xy + yx)/2` (MODEL.md section 8): skew cross-coupling is the
//! imaginary part of `a_iso`, and only `a_an` couples `r` to its conjugate.
//!
//! A table gives every coefficient at increasing spin speeds; between them a coefficient is
//! linear in the speed, outside them it is held at the end value. With `interpolation: "ross"`
//! each coefficient is instead ROSS 2.3.0's curve through its column ([`Curve::ross`]: scipy's
//! `interp1d` for 2-3 points, else its smoothing spline), extrapolated beyond the table as ROSS
//! does; only stiffness and damping may then change with the speed.
//!
//! A table over whirl frequency (and speed) is a [`grid::Grid`]: read at `|w|` wherever the
//! motion's frequency is known (a pole's own, a harmonic response's, 0 for a static load), and
//! at `w` = the speed where one value per speed is asked for ([`GeneralSupport::at`]).

pub mod fitted;
mod general;
pub mod grid;

pub use general::{is_general, parse_general};

use super::api::SupportInput;
use super::error::{Invalid, loss_factor, non_negative};
use super::spline::Curve;
use crate::linalg::c64;

/// Most speeds in one support's table.
pub const MAX_TABLE: usize = 512;

/// A 2x2 real coefficient matrix `[[xx, xy], [yx, yy]]`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Matrix2 {
    pub xx: f64,
    pub xy: f64,
    pub yx: f64,
    pub yy: f64,
}

impl Matrix2 {
    /// `(a_iso, a_an)` of the module docs.
    pub fn complex(&self) -> (c64, c64) {
        (
            c64::new(0.5 * (self.xx + self.yy), 0.5 * (self.yx - self.xy)),
            c64::new(0.5 * (self.xx - self.yy), 0.5 * (self.xy + self.yx)),
        )
    }

    /// The symmetric part: what stores energy (the skew part is circulatory).
    pub fn symmetric(&self) -> Self {
        let c = 0.5 * (self.xy + self.yx);
        Matrix2 {
            xx: self.xx,
            xy: c,
            yx: c,
            yy: self.yy,
        }
    }

    pub fn scaled(&self, f: f64) -> Self {
        Matrix2 {
            xx: f * self.xx,
            xy: f * self.xy,
            yx: f * self.yx,
            yy: f * self.yy,
        }
    }

    fn lerp(&self, other: &Self, t: f64) -> Self {
        let l = |a: f64, b: f64| a + (b - a) * t;
        Matrix2 {
            xx: l(self.xx, other.xx),
            xy: l(self.xy, other.xy),
            yx: l(self.yx, other.yx),
            yy: l(self.yy, other.yy),
        }
    }

    /// Whether it acts on `r` alone (`a_an = 0`).
    pub fn isotropic(&self) -> bool {
        self.xx == self.yy && self.xy == -self.yx
    }

    pub fn is_zero(&self) -> bool {
        *self == Matrix2::default()
    }
}

/// Stiffness, damping and mass coefficients at one speed.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Coefficients {
    pub k: Matrix2,
    pub c: Matrix2,
    pub m: Matrix2,
}

impl Coefficients {
    fn lerp(&self, other: &Self, t: f64) -> Self {
        Coefficients {
            k: self.k.lerp(&other.k, t),
            c: self.c.lerp(&other.c, t),
            m: self.m.lerp(&other.m, t),
        }
    }

    pub fn isotropic(&self) -> bool {
        self.k.isotropic() && self.c.isotropic() && self.m.isotropic()
    }
}

/// How a support's coefficients depend on the spin speed.
#[derive(Debug, Clone, PartialEq)]
pub enum Law {
    Constant(Coefficients),
    /// Linear between increasing `speeds`, held outside them; or, with `ross`, each
    /// coefficient on its ROSS curve (12 of them, in the order k, c, m and xx, xy, yx, yy).
    Table {
        speeds: Vec<f64>,
        values: Vec<Coefficients>,
        ross: Option<Vec<Curve>>,
    },
    /// Over whirl frequency (and spin speed), `grid.rs`.
    Grid(Box<grid::Grid>),
    /// A grid read at one speed and frequency, keeping the grid's isotropy (so the rotor is
    /// solved in the same coordinates at every reading).
    Read {
        values: Coefficients,
        isotropic: bool,
    },
}

/// A validated support in the general form.
#[derive(Debug, Clone, PartialEq)]
pub struct GeneralSupport {
    /// Its position in the request's `supports` (or `seals`).
    pub index: usize,
    /// A seal (`rotor.seals`): left out of the critical speed map and the static analysis.
    pub seal: bool,
    pub node: usize,
    /// The node it links `node` to (`None`: ground); it acts on `node - link`.
    pub link: Option<usize>,
    pub law: Law,
    /// Its hysteretic stiffness is `loss_factor` times the symmetric part of `K`.
    pub loss_factor: f64,
    /// Maxwell branches beside its law: a table over whirl frequency fitted for the time
    /// domain (`fitted.rs`), none as parsed.
    pub branches: Option<Box<fitted::Fitted>>,
}

impl GeneralSupport {
    /// Its path in the request: `rotor.supports[i]` or `rotor.seals[i]`.
    pub fn path(&self) -> String {
        support_path(self.seal, self.index)
    }

    /// The coefficients at `speed`: for a table over whirl frequency, the synchronous ones
    /// (frequency = speed, what an unbalance reads and a critical speed crosses at).
    pub fn at(&self, speed: f64) -> Coefficients {
        match &self.law {
            Law::Constant(c) | Law::Read { values: c, .. } => *c,
            Law::Grid(g) => g.at(speed, speed),
            Law::Table {
                ross: Some(curves), ..
            } => {
                let m = |b: usize| Matrix2 {
                    xx: curves[b].at(speed),
                    xy: curves[b + 1].at(speed),
                    yx: curves[b + 2].at(speed),
                    yy: curves[b + 3].at(speed),
                };
                Coefficients {
                    k: m(0),
                    c: m(4),
                    m: m(8),
                }
            }
            Law::Table { speeds, values, .. } => {
                let last = speeds.len() - 1;
                if speed <= speeds[0] {
                    return values[0];
                }
                if speed >= speeds[last] {
                    return values[last];
                }
                let k = speeds.partition_point(|&w| w <= speed) - 1;
                let t = (speed - speeds[k]) / (speeds[k + 1] - speeds[k]);
                values[k].lerp(&values[k + 1], t)
            }
        }
    }

    /// The coefficients at `speed` under whirl at `frequency` (rad/s, either sign).
    pub fn at_whirl(&self, speed: f64, frequency: f64) -> Coefficients {
        match &self.law {
            Law::Grid(g) => g.at(speed, frequency),
            _ => self.at(speed),
        }
    }

    /// Whether its coefficients depend on the whirl frequency.
    pub fn frequency_dependent(&self) -> bool {
        matches!(&self.law, Law::Grid(_))
    }

    /// Its table over whirl frequency, if it has one.
    pub fn grid(&self) -> Option<&grid::Grid> {
        match &self.law {
            Law::Grid(g) => Some(g),
            _ => None,
        }
    }

    /// This support with its coefficients read at `speed` and `frequency`, constant (the same
    /// support where they do not depend on the frequency).
    pub fn read(&self, speed: f64, frequency: f64) -> Self {
        match &self.law {
            Law::Grid(g) => GeneralSupport {
                law: Law::Read {
                    values: g.at(speed, frequency),
                    isotropic: g.isotropic(),
                },
                ..self.clone()
            },
            _ => self.clone(),
        }
    }

    /// The coefficients the rotor's modes at rest are taken with: at speed 0, or, for a ROSS
    /// curve, at the table's first speed (as a linear table holds them below it), so that a
    /// curve extrapolated to rest does not decide the modal basis.
    pub fn at_rest(&self) -> Coefficients {
        match &self.law {
            Law::Table {
                speeds,
                ross: Some(_),
                ..
            } => self.at(speeds[0]),
            _ => self.at(0.0),
        }
    }

    /// Whether its coefficients follow ROSS's curves.
    pub fn ross(&self) -> bool {
        matches!(&self.law, Law::Table { ross: Some(_), .. })
    }

    /// The speeds of a table over speed alone (none for constant coefficients, and none for a
    /// table over whirl frequency, which is only ever read at one speed and frequency).
    pub fn speeds(&self) -> &[f64] {
        match &self.law {
            Law::Table { speeds, .. } => speeds,
            _ => &[],
        }
    }

    /// The speeds its table is given at: a table over speed's, or one over whirl frequency's
    /// (none where the coefficients do not depend on the speed).
    pub fn tabulated_speeds(&self) -> &[f64] {
        match &self.law {
            Law::Grid(g) => &g.speeds,
            _ => self.speeds(),
        }
    }

    /// Whether it acts on `r` alone at every speed.
    pub fn isotropic(&self) -> bool {
        match &self.law {
            Law::Constant(c) => c.isotropic(),
            Law::Table { values, .. } => values.iter().all(Coefficients::isotropic),
            Law::Grid(g) => g.isotropic(),
            Law::Read { isotropic, .. } => *isotropic,
        }
    }

    /// Whether its mass coefficients change with speed.
    pub fn mass_varies(&self) -> bool {
        match &self.law {
            Law::Table { values, .. } => values.iter().any(|v| v.m != values[0].m),
            _ => false,
        }
    }
}

/// With a support on ROSS's curves the rotor's tables are scheduled on one model
/// (`damping/schedule.rs`), which needs every tabulated support without loss and with constant
/// mass: each one that is not is an error naming it.
pub fn check_schedule(general: &[GeneralSupport], bad: &mut Invalid) {
    let Some(ross) = general.iter().find(|g| g.ross()) else {
        return;
    };
    for g in general
        .iter()
        .filter(|g| !g.speeds().is_empty() && !g.ross())
    {
        let why = if g.loss_factor > 0.0 {
            "loss_factor"
        } else if g.mass_varies() {
            "speeds"
        } else {
            continue;
        };
        bad.push(
            format!("{}.{why}", g.path()),
            format!(
                "{} reads its table with ROSS's interpolation, so every table of the rotor must \
                 have constant mass coefficients and no loss factor",
                ross.path()
            ),
        );
    }
}

/// The warning for analysis speeds outside a support's table (`None` if inside).
pub fn held_warning(path: &str, support: &GeneralSupport, lo: f64, hi: f64) -> Option<String> {
    let w = support.speeds();
    let (first, last) = (*w.first()?, *w.last()?);
    let below = lo < first;
    let above = hi > last;
    if support.ross() {
        return (below || above).then(|| {
            format!(
                "{path}: outside its table ({first} to {last} rad/s) its coefficients are \
                 extrapolated by ROSS's curves (analysis speeds {lo} to {hi} rad/s)"
            )
        });
    }
    match (below, above) {
        (false, false) => None,
        (true, false) => Some(format!(
            "{path}: below its table ({first} rad/s) its coefficients are held at their first \
             values"
        )),
        (false, true) => Some(format!(
            "{path}: above its table ({last} rad/s) its coefficients are held at their last \
             values"
        )),
        (true, true) => Some(format!(
            "{path}: outside its table ({first} to {last} rad/s) its coefficients are held at \
             their end values"
        )),
    }
}

/// An isotropic support on a translation.
#[derive(Debug, Clone, PartialEq)]
pub struct Support {
    /// Its position in the request's `supports` (or `seals`).
    pub index: usize,
    /// A seal (`rotor.seals`): left out of the critical speed map and the static analysis.
    pub seal: bool,
    pub node: usize,
    /// The node it links `node` to (`None`: ground).
    pub link: Option<usize>,
    pub stiffness: f64,
    pub damping: f64,
    pub loss_factor: f64,
}

/// The request path of support `index` (of `rotor.seals` for a seal).
pub fn support_path(seal: bool, index: usize) -> String {
    if seal {
        format!("rotor.seals[{index}]")
    } else {
        format!("rotor.supports[{index}]")
    }
}

/// Validates a rotor's supports (or seals): the isotropic ones and those in the general form.
/// `node_ok` checks a node (a degree of freedom for matrices) and records its error.
pub fn parse_supports(
    inputs: &[SupportInput],
    seal: bool,
    bad: &mut Invalid,
    mut node_ok: impl FnMut(&mut Invalid, String, i64) -> Option<usize>,
) -> (Vec<Support>, Vec<GeneralSupport>) {
    let mut isotropic = vec![];
    let mut general = vec![];
    for (i, s) in inputs.iter().enumerate() {
        let at = support_path(seal, i);
        let node = node_ok(bad, format!("{at}.node"), s.node);
        let link = match s.n_link {
            None => Some(None),
            Some(l) => {
                let l = node_ok(bad, format!("{at}.n_link"), l);
                if l.is_some() && l == node {
                    bad.push(
                        format!("{at}.n_link"),
                        format!("must differ from `node` ({})", s.node),
                    );
                    None
                } else {
                    l.map(Some)
                }
            }
        };
        if is_general(s) {
            if let (Some(g), Some(_), Some(_)) = (
                parse_general(s, (i, seal), (node.unwrap_or(0), link.flatten()), &at, bad),
                node,
                link,
            ) {
                general.push(g);
            }
            continue;
        }
        let Some(stiffness) = s.stiffness else {
            bad.push(
                format!("{at}.stiffness"),
                "needs `stiffness` (the isotropic form) or `kxx`, `kyy`, ... (the general form)",
            );
            continue;
        };
        let k = bad.check(&format!("{at}.stiffness"), non_negative(stiffness));
        let c = bad.check(
            &format!("{at}.damping"),
            non_negative(s.damping.unwrap_or(0.0)),
        );
        let eta = bad.check(
            &format!("{at}.loss_factor"),
            loss_factor(s.loss_factor.unwrap_or(0.0)),
        );
        if let (Some(node), Some(link), Some(k), Some(c), Some(eta)) = (node, link, k, c, eta) {
            isotropic.push(Support {
                index: i,
                seal,
                node,
                link,
                stiffness: k,
                damping: c,
                loss_factor: eta,
            });
        }
    }
    (isotropic, general)
}

#[cfg(test)]
mod tests;
