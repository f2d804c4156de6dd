//! Validated damping models.

use super::api::{BranchesInput, DampingInput};
use super::error::Invalid;
use crate::damping::nonviscous::BranchSet;

/// Default number of Maxwell branches per damper.
pub const DEFAULT_BRANCHES: usize = 3;
/// Default ratio between consecutive relaxation rates (one decade).
pub const DEFAULT_SPACING: f64 = 10.0;

/// A valid damping model for a rotor with `dofs` complex degrees of freedom.
#[derive(Debug, Clone, PartialEq)]
pub enum DampingModel {
    Viscous,
    Hysteretic,
    Equivalent { modes: Option<usize> },
    Nonviscous(NonviscousSpec),
}

/// The nonviscous model: branches for the rotating and the nonrotating dampers of each mode.
#[derive(Debug, Clone, PartialEq)]
pub struct NonviscousSpec {
    pub rotating: BranchSet,
    pub nonrotating: BranchSet,
    /// Lowest modes that get dampers (`None`: all).
    pub modes: Option<usize>,
}

impl DampingModel {
    /// Validates the `damping` field; `dofs` (when the rotor is valid) bounds `modes`.
    pub fn parse(input: &DampingInput, dofs: Option<usize>) -> Result<Self, Invalid> {
        match input {
            DampingInput::Viscous(_) => Ok(DampingModel::Viscous),
            DampingInput::Hysteretic(_) => Ok(DampingModel::Hysteretic),
            DampingInput::Equivalent(e) => {
                let mut bad = Invalid::default();
                let modes = bad.check("damping.modes", parse_modes(e.modes, dofs));
                bad.into_result(|| DampingModel::Equivalent {
                    modes: modes.unwrap(),
                })
            }
            DampingInput::Nonviscous(nv) => {
                let mut bad = Invalid::default();
                let modes = bad.check("damping.modes", parse_modes(nv.modes, dofs));
                let rotating = parse_branches(nv.rotating.as_ref(), "damping.rotating", &mut bad);
                let nonrotating =
                    parse_branches(nv.nonrotating.as_ref(), "damping.nonrotating", &mut bad);
                bad.into_result(|| {
                    DampingModel::Nonviscous(NonviscousSpec {
                        rotating: rotating.unwrap(),
                        nonrotating: nonrotating.unwrap(),
                        modes: modes.unwrap(),
                    })
                })
            }
        }
    }

    /// The model's name as in the API.
    pub fn name(&self) -> &'static str {
        match self {
            DampingModel::Viscous => "viscous",
            DampingModel::Hysteretic => "hysteretic",
            DampingModel::Equivalent { .. } => "equivalent",
            DampingModel::Nonviscous(_) => "nonviscous",
        }
    }
}

fn parse_modes(modes: Option<i64>, dofs: Option<usize>) -> Result<Option<usize>, String> {
    match (modes, dofs) {
        (None, _) => Ok(None),
        (Some(k), Some(n)) if k >= 1 && k as u64 <= n as u64 => Ok(Some(k as usize)),
        (Some(k), None) if k >= 1 => Ok(Some(k as usize)),
        (Some(k), Some(n)) => Err(format!(
            "must be between 1 and the number of degrees of freedom, {n} (got {k})"
        )),
        (Some(k), None) => Err(format!("must be >= 1 (got {k})")),
    }
}

fn parse_branches(b: Option<&BranchesInput>, at: &str, bad: &mut Invalid) -> Option<BranchSet> {
    let default = BranchesInput::default();
    let b = b.unwrap_or(&default);
    let count = match b.branches {
        None => Some(DEFAULT_BRANCHES),
        Some(m) if (1..=BranchSet::MAX_BRANCHES as i64).contains(&m) => Some(m as usize),
        Some(m) => {
            bad.push(
                format!("{at}.branches"),
                format!(
                    "must be between 1 and {} (got {m})",
                    BranchSet::MAX_BRANCHES
                ),
            );
            None
        }
    };
    let spacing = b.spacing.unwrap_or(DEFAULT_SPACING);
    let count = count?;
    let nu = match &b.nu {
        None => vec![1.0; count],
        Some(nu) => {
            if nu.len() != count {
                bad.push(
                    format!("{at}.nu"),
                    format!("needs one value per branch: {count} (got {})", nu.len()),
                );
                return None;
            }
            let mut ok = true;
            for (i, &v) in nu.iter().enumerate() {
                if !v.is_finite() || v < 0.0 {
                    bad.push(format!("{at}.nu[{i}]"), "must be a finite number >= 0");
                    ok = false;
                }
            }
            if !ok {
                return None;
            }
            nu.clone()
        }
    };
    match BranchSet::new(count, spacing, nu) {
        Ok(set) => Some(set),
        Err(e) => {
            bad.push(format!("{at}.{}", e.field), e.message);
            None
        }
    }
}
