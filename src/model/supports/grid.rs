//! Supports whose coefficients depend on the whirl frequency (and the spin speed): seals,
//! squeeze films, fluid-film bearings and elastomers tabulated over `frequencies` (and
//! `speeds`), read as ROSS 3 reads its 2-D tables.
//!
//! The coefficients are those of the support in its own fixed `x, y` frame: under a motion at
//! frequency `w >= 0` its force is `-(K(w) + i w C(w) - w^2 M(w)) [X, Y]`. A real motion has
//! `H(-w) = conj H(w)`, so `K`, `C` and `M` are even in `w`: a table given at `w >= 0` is read
//! at `|w|`, for forward and backward whirl alike (a pole `s` at `|Im s|`, a harmonic response
//! at its excitation frequency, a static deflection at 0).
//!
//! Each coefficient is read along the frequencies at each tabulated speed, then along the speeds
//! at the speed wanted; each axis by PCHIP ([`Table1`], scipy's `PchipInterpolator`) or
//! linearly, continued past its ends along the end slope. Fewer than [`FEW_POINTS`] points on
//! an axis, or a reading past its ends, is stated in the answer's `warnings`.

use super::{Coefficients, MAX_TABLE, Matrix2};
use crate::model::api::{Coefficient, Interpolation as Asked, SupportInput};
use crate::model::error::Invalid;
use crate::model::pchip::{Interpolation, Table1};

/// Fewer points than this on an axis are warned of (PCHIP's end slopes come from three points;
/// ROSS 3 warns likewise).
pub const FEW_POINTS: usize = 5;

/// A support's coefficients tabulated over whirl frequency (and spin speed).
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    /// The spin speeds, rad/s (empty: the coefficients do not depend on the speed).
    pub speeds: Vec<f64>,
    /// The whirl frequencies, rad/s.
    pub frequencies: Vec<f64>,
    pub how: Interpolation,
    /// Per coefficient (`k`, `c`, `m` by `xx`, `xy`, `yx`, `yy`), per speed (one without
    /// `speeds`), its table over the frequencies.
    rows: Vec<Vec<Table1>>,
    isotropic: bool,
}

impl Grid {
    /// The coefficients at spin speed `speed` under whirl at `frequency` (read at its modulus).
    pub fn at(&self, speed: f64, frequency: f64) -> Coefficients {
        let w = frequency.abs();
        let value = |c: usize| -> f64 {
            let rows = &self.rows[c];
            if rows.len() == 1 {
                return rows[0].at(w);
            }
            let column: Vec<f64> = rows.iter().map(|t| t.at(w)).collect();
            Table1::new(&self.speeds, &column, self.how).at(speed)
        };
        let matrix = |b: usize| Matrix2 {
            xx: value(b),
            xy: value(b + 1),
            yx: value(b + 2),
            yy: value(b + 3),
        };
        Coefficients {
            k: matrix(0),
            c: matrix(4),
            m: matrix(8),
        }
    }

    /// Whether it acts on `r` alone at every point (`xx = yy`, `xy = -yx` throughout; its
    /// readings then are too).
    pub fn isotropic(&self) -> bool {
        self.isotropic
    }

    /// Warnings of its axes with fewer than [`FEW_POINTS`] points.
    pub fn few_points(&self, path: &str) -> Vec<String> {
        let how = match self.how {
            Interpolation::Pchip => "PCHIP",
            Interpolation::Linear => "linear interpolation",
        };
        [("frequencies", &self.frequencies), ("speeds", &self.speeds)]
            .into_iter()
            .filter(|(_, p)| !p.is_empty() && p.len() < FEW_POINTS)
            .map(|(axis, p)| {
                format!(
                    "{path}.{axis}: {} points only; {how} between so few is little more than \
                     a line (at least {FEW_POINTS} recommended)",
                    p.len()
                )
            })
            .collect()
    }

    /// The warning for a reading at speeds (`frequencies` false) or whirl frequencies in
    /// `[lo, hi]` (rad/s) past the ends of that axis, if any.
    pub fn past(&self, path: &str, frequencies: bool, (lo, hi): (f64, f64)) -> Option<String> {
        let (axis, points, what) = match frequencies {
            true => ("frequencies", &self.frequencies, "whirl frequencies"),
            false => ("speeds", &self.speeds, "speeds"),
        };
        let (first, last) = (*points.first()?, *points.last()?);
        (lo < first || hi > last).then(|| {
            format!(
                "{path}.{axis}: read at {what} {lo:.6} to {hi:.6} rad/s, outside its table \
                 ({first} to {last} rad/s): extrapolated along the end slopes"
            )
        })
    }
}

impl Grid {
    /// Warnings for each direct stiffness or damping (`kxx`, `kyy`, `cxx`, `cyy`) that,
    /// continued past an end of the frequencies along its end slope, changes sign at whirl
    /// frequencies in `[lo, hi]` (rad/s): a negative direct damping or stiffness is no longer a
    /// support, and is a reading only the extrapolation made (at each speed of the table).
    pub fn sign_changes(&self, path: &str, (lo, hi): (f64, f64)) -> Vec<String> {
        let f = &self.frequencies;
        let (first, last) = (f[0], f[f.len() - 1]);
        let mut out = vec![];
        for (c, name, unit) in [
            (0, "kxx", "N/m"),
            (3, "kyy", "N/m"),
            (4, "cxx", "N s/m"),
            (7, "cyy", "N s/m"),
        ] {
            for (i, row) in self.rows[c].iter().enumerate() {
                // Along the end slope from the end to the furthest reading: linear.
                let ends = [(first, lo, "first"), (last, hi, "last")];
                for (end, far, which) in ends {
                    let beyond = if which == "first" {
                        far < end
                    } else {
                        far > end
                    };
                    let (v0, v1) = (row.at(end), row.at(far));
                    if !beyond || v0 == 0.0 || v0.signum() == v1.signum() || v1 == 0.0 {
                        continue;
                    }
                    let zero = end + (far - end) * v0 / (v0 - v1);
                    let speed = match self.speeds.get(i) {
                        Some(w) if self.speeds.len() > 1 => format!(" at speed {w} rad/s"),
                        _ => String::new(),
                    };
                    out.push(format!(
                        "{path}.{name}{speed}: continued past its {which} frequency ({end} rad/s) \
                         along its end slope, it changes sign at {zero:.1} rad/s (from {v0} to \
                         {v1:.6e} {unit} at {far:.1} rad/s, where it is read): a direct \
                         coefficient of the wrong sign is no support, and the poles that read it \
                         there may be unstable for that alone; extend the table"
                    ));
                }
            }
        }
        out
    }
}

/// Checks an axis of a table: 2 to [`MAX_TABLE`] finite values >= 0, strictly increasing.
pub fn check_axis(w: &[f64], path: &str, what: &str, bad: &mut Invalid) {
    if w.len() < 2 || w.len() > MAX_TABLE {
        bad.push(
            path,
            format!("needs 2 to {MAX_TABLE} {what} (got {})", w.len()),
        );
    }
    for (i, x) in w.iter().enumerate() {
        if !x.is_finite() || *x < 0.0 {
            bad.push(
                format!("{path}[{i}]"),
                format!("must be a finite {what} >= 0"),
            );
        } else if i > 0 && w[i - 1].is_finite() && *x <= w[i - 1] {
            bad.push(
                format!("{path}[{i}]"),
                format!("{what} must be strictly increasing"),
            );
        }
    }
}

/// The grid of a support given with `frequencies` (at path `at`; its axes already checked).
pub fn parse(
    s: &SupportInput,
    fields: [(&'static str, &Option<Coefficient>); 12],
    at: &str,
    bad: &mut Invalid,
) -> Option<Grid> {
    let frequencies = s.frequencies.clone().unwrap_or_default();
    let speeds = s.speeds.clone().unwrap_or_default();
    let (nf, ns) = (frequencies.len(), speeds.len().max(1));
    let how = match s.interpolation {
        None | Some(Asked::Pchip) => Interpolation::Pchip,
        Some(Asked::Linear) => Interpolation::Linear,
        Some(Asked::Ross) => {
            bad.push(
                format!("{at}.interpolation"),
                "ROSS 2.3.0's curves are for tables over `speeds` alone: a table over \
                 `frequencies` reads \"pchip\" (the default) or \"linear\"",
            );
            return None;
        }
    };
    let before = bad.count();
    // Each coefficient as rows (per speed) over the frequencies; `None` where not given.
    let mut grids: Vec<Option<Vec<Vec<f64>>>> = vec![];
    for (name, c) in fields {
        let path = format!("{at}.{name}");
        let rows = match c {
            None => None,
            Some(Coefficient::Number(x)) => Some(vec![vec![*x; nf]; ns]),
            Some(Coefficient::Table(v)) if speeds.is_empty() => {
                if v.len() != nf {
                    bad.push(
                        &path,
                        format!(
                            "needs one value per frequency in `frequencies`: {nf} (got {})",
                            v.len()
                        ),
                    );
                    continue;
                }
                Some(vec![v.clone()])
            }
            Some(Coefficient::Table(_)) => {
                bad.push(
                    &path,
                    format!(
                        "with `speeds` and `frequencies` a coefficient is a number or a list \
                         per speed ({ns}) of values over the frequencies ({nf})"
                    ),
                );
                continue;
            }
            Some(Coefficient::Grid(rows)) => {
                if speeds.is_empty() {
                    bad.push(
                        &path,
                        "a list of lists needs `speeds`: one list over `frequencies` per speed",
                    );
                    continue;
                }
                if rows.len() != ns {
                    bad.push(
                        &path,
                        format!(
                            "needs one list per speed in `speeds`: {ns} (got {})",
                            rows.len()
                        ),
                    );
                    continue;
                }
                if let Some(i) = rows.iter().position(|r| r.len() != nf) {
                    bad.push(
                        format!("{path}[{i}]"),
                        format!(
                            "needs one value per frequency in `frequencies`: {nf} (got {})",
                            rows[i].len()
                        ),
                    );
                    continue;
                }
                Some(rows.clone())
            }
        };
        if let Some(rows) = &rows {
            let nested = matches!(c, Some(Coefficient::Grid(_)));
            let scalar = matches!(c, Some(Coefficient::Number(_)));
            'check: for (i, row) in rows.iter().enumerate() {
                for (j, x) in row.iter().enumerate() {
                    if !x.is_finite() {
                        let p = match (scalar, nested) {
                            (true, _) => path.clone(),
                            (_, true) => format!("{path}[{i}][{j}]"),
                            _ => format!("{path}[{j}]"),
                        };
                        bad.push(p, "must be a finite number");
                        break 'check;
                    }
                }
            }
        }
        grids.push(rows);
    }
    if bad.count() > before {
        return None;
    }
    // Omitted coefficients are 0, except kyy and cyy: kxx and cxx.
    let zero = vec![vec![0.0; nf]; ns];
    let column = |c: usize| -> Vec<Vec<f64>> {
        match (&grids[c], c) {
            (Some(g), _) => g.clone(),
            (None, 3) => grids[0].clone().unwrap_or_else(|| zero.clone()),
            (None, 7) => grids[4].clone().unwrap_or_else(|| zero.clone()),
            _ => zero.clone(),
        }
    };
    let columns: Vec<Vec<Vec<f64>>> = (0..12).map(column).collect();
    let negated = |a: &Vec<Vec<f64>>, b: &Vec<Vec<f64>>| {
        a.iter()
            .flatten()
            .zip(b.iter().flatten())
            .all(|(x, y)| *x == -*y)
    };
    let isotropic = (0..3).all(|b| {
        let base = 4 * b;
        columns[base] == columns[base + 3] && negated(&columns[base + 1], &columns[base + 2])
    });
    let rows = columns
        .iter()
        .map(|g| {
            g.iter()
                .map(|row| Table1::new(&frequencies, row, how))
                .collect()
        })
        .collect();
    Some(Grid {
        speeds,
        frequencies,
        how,
        rows,
        isotropic,
    })
}
