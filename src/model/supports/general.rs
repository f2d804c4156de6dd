//! Validation of a support given in the general form: its coefficients as numbers, as tables
//! over the spin speed, or (`grid.rs`) over the whirl frequency.

use super::{Coefficients, GeneralSupport, Law, Matrix2, grid};
use crate::model::api::{Coefficient, Interpolation, SupportInput};
use crate::model::error::{Invalid, loss_factor};
use crate::model::spline::Curve;

/// One coefficient as given: a number, or one value per table speed.
fn values(
    c: &Option<Coefficient>,
    at: &str,
    table: Option<usize>,
    bad: &mut Invalid,
) -> Option<Vec<f64>> {
    let v = match c {
        None => return Some(vec![]),
        Some(Coefficient::Number(x)) => vec![*x],
        Some(Coefficient::Grid(_)) => {
            bad.push(
                at,
                "a list of lists is a table over `speeds` and `frequencies`: give both",
            );
            return None;
        }
        Some(Coefficient::Table(v)) => {
            match table {
                None => {
                    bad.push(
                        at,
                        "an array of values needs `speeds`: the spin speeds they are given at",
                    );
                    return None;
                }
                Some(n) if v.len() != n => {
                    bad.push(
                        at,
                        format!(
                            "needs one value per speed in `speeds`: {n} (got {})",
                            v.len()
                        ),
                    );
                    return None;
                }
                Some(_) => {}
            }
            v.clone()
        }
    };
    for (i, x) in v.iter().enumerate() {
        if !x.is_finite() {
            let path = if matches!(c, Some(Coefficient::Table(_))) {
                format!("{at}[{i}]")
            } else {
                at.to_string()
            };
            bad.push(path, "must be a finite number");
            return None;
        }
    }
    Some(v)
}

/// The general-form fields of a support, with their names.
fn general_fields(s: &SupportInput) -> [(&'static str, &Option<Coefficient>); 12] {
    [
        ("kxx", &s.kxx),
        ("kxy", &s.kxy),
        ("kyx", &s.kyx),
        ("kyy", &s.kyy),
        ("cxx", &s.cxx),
        ("cxy", &s.cxy),
        ("cyx", &s.cyx),
        ("cyy", &s.cyy),
        ("mxx", &s.mxx),
        ("mxy", &s.mxy),
        ("myx", &s.myx),
        ("myy", &s.myy),
    ]
}

/// Whether a support is given in the general form.
pub fn is_general(s: &SupportInput) -> bool {
    general_fields(s).iter().any(|(_, v)| v.is_some())
        || s.speeds.is_some()
        || s.frequencies.is_some()
}

/// Validates the general form of `s` (at path `at`), its node already checked.
pub fn parse_general(
    s: &SupportInput,
    (index, seal): (usize, bool),
    (node, link): (usize, Option<usize>),
    at: &str,
    bad: &mut Invalid,
) -> Option<GeneralSupport> {
    let before = bad.count();
    for (field, given) in [
        ("stiffness", s.stiffness.is_some()),
        ("damping", s.damping.is_some()),
    ] {
        if given {
            bad.push(
                format!("{at}.{field}"),
                "give the isotropic form (`stiffness`, `damping`) or the general form (`kxx`, \
                 `kxy`, ..., `speeds`), not both",
            );
        }
    }
    let table = s.speeds.as_ref().map(|w| {
        grid::check_axis(w, &format!("{at}.speeds"), "speeds", bad);
        w.len()
    });
    let eta = bad.check(
        &format!("{at}.loss_factor"),
        loss_factor(s.loss_factor.unwrap_or(0.0)),
    );
    if let Some(w) = &s.frequencies {
        grid::check_axis(w, &format!("{at}.frequencies"), "frequencies", bad);
        if bad.count() > before {
            return None;
        }
        let g = grid::parse(s, general_fields(s), at, bad)?;
        return Some(GeneralSupport {
            index,
            seal,
            node,
            link,
            law: Law::Grid(Box::new(g)),
            loss_factor: eta?,
            branches: None,
        });
    }
    let mut columns: Vec<Vec<f64>> = vec![];
    for (name, c) in general_fields(s) {
        columns.push(values(c, &format!("{at}.{name}"), table, bad).unwrap_or_default());
    }
    if bad.count() > before {
        return None;
    }
    if s.interpolation == Some(Interpolation::Pchip) {
        bad.push(
            format!("{at}.interpolation"),
            "\"pchip\" reads a table over `frequencies` (and `speeds`); a table over `speeds` \
             alone is read \"linear\" or \"ross\"",
        );
        return None;
    }
    if s.interpolation.is_some() && s.speeds.is_none() {
        bad.push(
            format!("{at}.interpolation"),
            "applies to a table: give `speeds` and the coefficients at them",
        );
        return None;
    }
    let points = table.unwrap_or(1);
    // Column order: k(xx, xy, yx, yy), c(...), m(...); kyy and cyy default to kxx and cxx.
    let value = |col: usize, i: usize| -> f64 {
        let v = &columns[col];
        match v.len() {
            0 => match col {
                3 => value_of(&columns[0], i),
                7 => value_of(&columns[4], i),
                _ => 0.0,
            },
            _ => value_of(v, i),
        }
    };
    fn value_of(v: &[f64], i: usize) -> f64 {
        match v.len() {
            0 => 0.0,
            1 => v[0],
            _ => v[i],
        }
    }
    let matrix = |base: usize, i: usize| Matrix2 {
        xx: value(base, i),
        xy: value(base + 1, i),
        yx: value(base + 2, i),
        yy: value(base + 3, i),
    };
    let at_point = |i: usize| Coefficients {
        k: matrix(0, i),
        c: matrix(4, i),
        m: matrix(8, i),
    };
    let law = match &s.speeds {
        None => Law::Constant(at_point(0)),
        Some(w) => {
            let values: Vec<Coefficients> = (0..points).map(at_point).collect();
            let ross = match s.interpolation {
                Some(Interpolation::Ross) => {
                    if values.iter().any(|v| v.m != values[0].m) {
                        bad.push(
                            format!("{at}.interpolation"),
                            "ROSS's interpolation is for stiffness and damping: mass \
                             coefficients must not change with the speed (use \"linear\")",
                        );
                        return None;
                    }
                    if eta.is_some_and(|e| e > 0.0) {
                        bad.push(
                            format!("{at}.loss_factor"),
                            "a table with ROSS's interpolation has no loss factor (ROSS has \
                             none; use \"linear\" for a tabulated lossy support)",
                        );
                        return None;
                    }
                    Some(
                        (0..12)
                            .map(|col| {
                                Curve::ross(
                                    w,
                                    &(0..points).map(|i| value(col, i)).collect::<Vec<_>>(),
                                )
                            })
                            .collect(),
                    )
                }
                _ => None,
            };
            Law::Table {
                speeds: w.clone(),
                values,
                ross,
            }
        }
    };
    Some(GeneralSupport {
        index,
        seal,
        node,
        link,
        law,
        loss_factor: eta?,
        branches: None,
    })
}
