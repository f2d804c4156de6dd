//! Validated damping models, and the branches of a nonviscous damper ([`BranchSet`]) that
//! validation builds (`damping::nonviscous` puts them on the rotor).

use super::api::{BranchesInput, DampingInput};
use super::error::Invalid;
use crate::linalg::{self, LinalgError, RMat};

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

    /// Whether the model is built on the rotor's undamped modes (the equivalent and nonviscous
    /// models: a damper per mode).
    pub fn on_modes(&self) -> bool {
        matches!(
            self,
            DampingModel::Equivalent { .. } | DampingModel::Nonviscous(_)
        )
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

/// The branches of one nonviscous damper, independent of the damper's size and tuning.
#[derive(Debug, Clone, PartialEq)]
pub struct BranchSet {
    count: usize,
    spacing: f64,
    nu: Vec<f64>,
    gamma: Vec<f64>,
}

/// Why branch parameters are invalid: the field (relative to the damper) and the reason.
#[derive(Debug, Clone, PartialEq)]
pub struct BranchSetError {
    pub field: &'static str,
    pub message: String,
}

impl BranchSet {
    /// Largest number of branches per damper.
    pub const MAX_BRANCHES: usize = 12;
    /// Largest ratio between consecutive relaxation rates.
    pub const MAX_SPACING: f64 = 1e6;

    /// Validates `count` (1..=12), `spacing` (> 1) and `nu` (one per branch), and solves the
    /// collocation for the `gamma_j`, which must all be positive (a negative branch stiffness
    /// would be an active element: spacings below about 3 give one with 3 or more branches).
    pub fn new(count: usize, spacing: f64, nu: Vec<f64>) -> Result<Self, BranchSetError> {
        if !(1..=Self::MAX_BRANCHES).contains(&count) {
            return Err(BranchSetError {
                field: "branches",
                message: format!("must be between 1 and {} (got {count})", Self::MAX_BRANCHES),
            });
        }
        if !spacing.is_finite() || spacing <= 1.0 || spacing > Self::MAX_SPACING {
            return Err(BranchSetError {
                field: "spacing",
                message: format!(
                    "must be a number in (1, {:e}] (got {spacing})",
                    Self::MAX_SPACING
                ),
            });
        }
        if nu.len() != count {
            return Err(BranchSetError {
                field: "nu",
                message: format!("needs one value per branch: {count} (got {})", nu.len()),
            });
        }
        let gamma = collocation_gammas(count, spacing).map_err(|_| BranchSetError {
            field: "spacing",
            message: "the collocation system for the branch weights is singular".into(),
        })?;
        if let Some(g) = gamma.iter().find(|g| **g <= 0.0) {
            return Err(BranchSetError {
                field: "spacing",
                message: format!(
                    "too small for {count} branches: the collocation gives a branch weight \
                     {g:.4} <= 0 (use a larger spacing or fewer branches)"
                ),
            });
        }
        Ok(BranchSet {
            count,
            spacing,
            nu,
            gamma,
        })
    }

    pub fn count(&self) -> usize {
        self.count
    }
    pub fn spacing(&self) -> f64 {
        self.spacing
    }
    pub fn nu(&self) -> &[f64] {
        &self.nu
    }
    pub fn gamma(&self) -> &[f64] {
        &self.gamma
    }

    /// Relaxation rates `d_j` centred on `omega0`.
    pub fn rates(&self, omega0: f64) -> Vec<f64> {
        let m = self.count as f64;
        (1..=self.count)
            .map(|j| omega0 * self.spacing.powf((2.0 * j as f64 - m - 1.0) / 2.0))
            .collect()
    }

    /// Loss factor the branches give at frequency `omega` (relative to `eta`, so 1 is exact)
    /// for a damper tuned at `omega0`.
    pub fn relative_loss(&self, omega: f64, omega0: f64) -> f64 {
        self.rates(omega0)
            .iter()
            .zip(&self.gamma)
            .map(|(d, g)| {
                let r = omega / d;
                g * r / (1.0 + r * r)
            })
            .sum()
    }
}

/// Collocation weights `gamma_j` for `m` branches `a` apart (`damping::nonviscous`'s module
/// docs).
pub fn collocation_gammas(m: usize, a: f64) -> Result<Vec<f64>, LinalgError> {
    let t = RMat::from_fn(m, m, |i, j| {
        let r = a.powf(i as f64 - j as f64);
        r / (1.0 + r * r)
    });
    linalg::solve_real(&t, &vec![1.0; m])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: &[f64], b: &[f64], tol: f64) -> bool {
        a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol)
    }

    #[test]
    fn collocation_gammas_are_model_md_values() {
        // MODEL.md section 4, to the printed digits.
        assert!(close(&collocation_gammas(1, 10.0).unwrap(), &[2.0], 1e-12));
        assert!(close(
            &collocation_gammas(2, 10.0).unwrap(),
            &[1.66942, 1.66942],
            5e-6
        ));
        assert!(close(
            &collocation_gammas(3, 10.0).unwrap(),
            &[1.703488, 1.325351, 1.703488],
            5e-7
        ));
        assert!(close(
            &collocation_gammas(4, 10.0).unwrap(),
            &[1.700088, 1.360036, 1.360036, 1.700088],
            5e-7
        ));
    }

    #[test]
    fn branches_restore_the_loss_factor_at_every_relaxation_rate() {
        let set = BranchSet::new(5, 10.0, vec![1.0; 5]).unwrap();
        for d in set.rates(370.0) {
            assert!((set.relative_loss(d, 370.0) - 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn rates_are_decades_centred_on_the_tuning_frequency() {
        let set = BranchSet::new(3, 10.0, vec![1.0; 3]).unwrap();
        assert!(close(&set.rates(2.0), &[0.2, 2.0, 20.0], 1e-14));
    }

    #[test]
    fn small_spacings_that_need_active_branches_are_refused() {
        let e = BranchSet::new(3, 2.0, vec![1.0; 3]).unwrap_err();
        assert_eq!(e.field, "spacing");
        assert!(BranchSet::new(0, 10.0, vec![]).is_err());
        assert!(BranchSet::new(13, 10.0, vec![1.0; 13]).is_err());
        assert!(BranchSet::new(3, 1.0, vec![1.0; 3]).is_err());
        assert!(BranchSet::new(3, f64::NAN, vec![1.0; 3]).is_err());
    }
}
