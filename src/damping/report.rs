//! The equivalent and nonviscous models as matrices for use elsewhere, and how well each
//! nonviscous damper reproduces the hysteretic loss it replaces.
//!
//! With internal coordinates `y` appended to `q`, the nonviscous model is again a rotor
//! equation of the same form, `M q'' + (C_n + C_r - i Omega G) q' + (K - i Omega C_r) q = F`:
//! `M`, `G` padded with zeros, `K = [[K + U nu k U^T, -U k], [-k U^T, k]]`, the branch dampers
//! `c_j` on the diagonal of `C_r` (rotating) or `C_n` (nonrotating). All symmetric and real.
//!
//! A damper tuned at `w0` with loss `eta` (branches `k_j = eta k gamma_j`, `r = w / d_j`) has, at
//! the frequency `w` its material sees (`w - Omega` in the rotor), the loss factor
//! `eta sum_j gamma_j r / (1 + r^2)` and the added storage stiffness
//! `eta k sum_j gamma_j (nu_j - 1 + r^2 / (1 + r^2))`. Deviations are relative to `eta`.

use super::nonviscous::{self, BranchSet};
use super::state::{Branches, SecondOrder, StateModel};
use super::{Bases, DampingError, equivalent};
use crate::linalg::{self, CMat};
use crate::model::damping::{DampingModel, NonviscousSpec};
use crate::system::{Dof, Realized, RotorSystem};

/// What to report.
#[derive(Debug, Clone, Default)]
pub struct Options {
    /// Also the first-order state matrices.
    pub state_form: bool,
    /// Band of the fit (rad/s); default per damper, see [`default_band`].
    pub band: Option<[f64; 2]>,
    /// Choose the branches of each side to stay within this deviation over `band`.
    pub max_deviation: Option<f64>,
    /// Largest state size allowed.
    pub max_states: usize,
    /// Spin speed at which tabulated supports are evaluated.
    pub speed: f64,
}

/// An equivalent or nonviscous model as matrices, with its fit report.
#[derive(Debug, Clone)]
pub struct ModelMatrices {
    /// Second-order matrices (the equivalent model's include `C_eq`).
    pub augmented: Augmented,
    /// First-order form and `M^-1`, when asked.
    pub state: Option<(StateModel, CMat)>,
    /// Equivalent model: `C_eq,r` and `C_eq,n` alone.
    pub equivalent: Option<(CMat, CMat)>,
    /// Per retained axisymmetric mode: natural frequency, rotating and nonrotating loss factors.
    pub modes: Vec<(f64, f64, f64)>,
    pub dampers: Vec<DamperFit>,
    pub added_states: usize,
    /// Branches per damper used, rotating and nonrotating (nonviscous).
    pub branches: Option<(usize, usize)>,
}

/// Why the matrices cannot be given.
#[derive(Debug, Clone, PartialEq)]
pub enum ReportError {
    Damping(DampingError),
    /// The target deviation cannot be met with this spacing.
    Unreachable {
        side: &'static str,
        spacing: f64,
        best: f64,
    },
    TooLarge {
        states: usize,
        max: usize,
    },
    /// Numbers beyond floating point range (extreme inputs).
    NonFinite,
}

impl std::fmt::Display for ReportError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Damping(e) => write!(f, "{e}"),
            Self::Unreachable {
                side,
                spacing,
                best,
            } => write!(
                f,
                "not reachable for the {side} dampers with spacing {spacing}: the best is \
                 {best:.4} with {} branches (use a smaller spacing or a narrower band)",
                BranchSet::MAX_BRANCHES
            ),
            Self::NonFinite => write!(
                f,
                "the matrices overflow floating point range: the input's magnitudes are too \
                 extreme (mass, stiffness or damping)"
            ),
            Self::TooLarge { states, max } => write!(
                f,
                "the model has {states} states, more than the limit of {max} (WHIRL_MAX_STATES): \
                 use Guyan reduction, `modes`, or fewer branches"
            ),
        }
    }
}

/// The matrices of an equivalent or nonviscous model (`None` for the others: they add none).
pub fn matrices(
    system: &RotorSystem,
    model: &DampingModel,
    options: &Options,
) -> Result<ModelMatrices, ReportError> {
    let (modes, nv) = match model {
        DampingModel::Equivalent { modes } => (*modes, None),
        DampingModel::Nonviscous(spec) => (spec.modes, Some(spec.clone())),
        _ => (None, None),
    };
    let bases = Bases::of(system, modes).map_err(ReportError::Damping)?;
    let r = Realized::at(system, options.speed);
    let rotor_loss = &system.hysteretic_rotating;
    let dampers = bases.dampers(&r, rotor_loss);
    let mut c_n = r.damping_nonrotating.clone();
    let mut c_r = r.damping_rotating.clone();
    let mut equivalent = None;
    let mut branches = Branches::none(r.size());
    let mut spec = None;
    if let Some(mut s) = nv {
        if let (Some(max_dev), Some(band)) = (options.max_deviation, options.band) {
            for (side, set, rotating) in [
                ("rotating", &mut s.rotating, true),
                ("nonrotating", &mut s.nonrotating, false),
            ] {
                let tunings: Vec<f64> = dampers
                    .iter()
                    .filter(|d| d.3 == rotating)
                    .map(|d| d.1)
                    .collect();
                if !tunings.is_empty() {
                    *set = choose_branches(set.spacing(), band, max_dev, &tunings).map_err(
                        |best| ReportError::Unreachable {
                            side,
                            spacing: set.spacing(),
                            best,
                        },
                    )?;
                }
            }
        }
        branches = nonviscous::branches(&[&r], rotor_loss, &bases, &s)
            .into_iter()
            .next()
            .expect("one realization");
        spec = Some(s);
    } else {
        let (eq_r, eq_n) = equivalent::matrices(&r, rotor_loss, &bases);
        c_n = &c_n + &eq_n;
        c_r = &c_r + &eq_r;
        equivalent = Some((eq_r, eq_n));
    }
    // A support's table over whirl frequency, fitted: its branches after the model's.
    let branches = branches.with_supports(&r.branches);
    let states = 2 * r.size() + branches.len();
    if states > options.max_states {
        return Err(ReportError::TooLarge {
            states,
            max: options.max_states,
        });
    }
    let state = if options.state_form {
        let lin = |e: linalg::LinalgError| ReportError::Damping(DampingError::Linalg(e));
        let sm =
            StateModel::new(&SecondOrder::with_damping(&r, &c_n, &c_r), &branches).map_err(lin)?;
        let n = r.size();
        let identity = CMat::from_fn(n, n, |i, j| {
            linalg::c64::new(if i == j { 1.0 } else { 0.0 }, 0.0)
        });
        Some((sm, linalg::mass_solve(&r.mass, &identity).map_err(lin)?))
    } else {
        None
    };
    let aug = augmented(&r, system, &c_n, &c_r, &branches);
    let finite = |a: &CMat| {
        (0..a.nrows())
            .all(|i| (0..a.ncols()).all(|j| a[(i, j)].re.is_finite() && a[(i, j)].im.is_finite()))
    };
    let ok = [
        &aug.mass,
        &aug.gyroscopic,
        &aug.stiffness,
        &aug.damping_rotating,
        &aug.damping_nonrotating,
    ]
    .iter()
    .all(|a| finite(a))
        && state
            .as_ref()
            .is_none_or(|(sm, m_inv)| finite(sm.a0()) && finite(sm.a1()) && finite(m_inv));
    if !ok {
        return Err(ReportError::NonFinite);
    }
    let axis = &bases.axis;
    let loss_r = axis.project(rotor_loss);
    let phi = linalg::to_complex(&axis.phi);
    let r_single = Realized::at(system, options.speed);
    let loss_n: Vec<f64> = if r_single.layout == crate::system::Layout::Single {
        let kp = &r_single.loss_nonrotating * &phi;
        (0..axis.len())
            .map(|i| {
                (0..phi.nrows())
                    .map(|k| (phi[(k, i)].conj() * kp[(k, i)]).re)
                    .sum()
            })
            .collect()
    } else {
        // Doubled: the nonrotating loss of the x/y pair of each axisymmetric mode, averaged.
        let xy = dampers.iter().filter(|d| !d.3);
        let mut v = vec![0.0; axis.len()];
        for d in xy {
            if d.0 / 2 < v.len() {
                v[d.0 / 2] += 0.5 * d.2;
            }
        }
        v
    };
    Ok(ModelMatrices {
        augmented: aug,
        state,
        equivalent,
        modes: (0..axis.len())
            .map(|i| {
                let k = axis.omega[i].powi(2);
                (axis.omega[i], loss_r[(i, i)] / k, loss_n[i] / k)
            })
            .collect(),
        dampers: spec
            .as_ref()
            .map(|s| fits(&dampers, s, options.band))
            .unwrap_or_default(),
        added_states: branches.len(),
        branches: spec
            .as_ref()
            .map(|s| (s.rotating.count(), s.nonrotating.count())),
    })
}

/// A coordinate of the augmented system.
#[derive(Debug, Clone, PartialEq)]
pub enum Coordinate {
    /// A physical coordinate; `conjugate`: the `conj r` copy of doubled coordinates.
    Physical { dof: Dof, conjugate: bool },
    Internal {
        /// Mode (0-based) whose damper the branch belongs to.
        mode: usize,
        /// Branch index within the damper (0-based).
        branch: usize,
        rotating: bool,
        /// Relaxation rate `d_j`, 1/s.
        rate: f64,
    },
    /// A branch fitted to a support's table over whirl frequency.
    Support {
        /// Its path in the request.
        support: String,
        /// Branch index (0-based).
        branch: usize,
        /// The `conj r` copy (doubled coordinates).
        conjugate: bool,
        /// Relaxation rate `d_j`, 1/s.
        rate: f64,
    },
}

/// The rotor with its nonviscous branches, in second-order form:
/// `M q'' + (C_n + C_r - i Omega S G) q' + (K - i Omega S C_r) q = F`, `S = diag(spin)`.
#[derive(Debug, Clone)]
pub struct Augmented {
    pub mass: CMat,
    pub gyroscopic: CMat,
    pub stiffness: CMat,
    pub damping_rotating: CMat,
    pub damping_nonrotating: CMat,
    /// +1, or -1 on the `conj r` coordinates (and their rotating branches).
    pub spin: Vec<f64>,
    pub coordinates: Vec<Coordinate>,
}

/// Appends the branches' internal coordinates to the viscous rotor `(r, c_n, c_r)`, the
/// supports' own (`r.branches`, of `system`'s supports) last.
pub fn augmented(
    r: &Realized,
    system: &RotorSystem,
    c_n: &CMat,
    c_r: &CMat,
    br: &Branches,
) -> Augmented {
    let dofs = &system.dofs;
    let (n, p) = (r.size(), br.len());
    let zero = linalg::c64::new(0.0, 0.0);
    let pad = |a: &CMat| {
        CMat::from_fn(
            n + p,
            n + p,
            |i, j| if i < n && j < n { a[(i, j)] } else { zero },
        )
    };
    let mut stiffness = pad(&r.stiffness);
    let mut c_r = pad(c_r);
    let mut c_n = pad(c_n);
    let mut spin = r.spin.clone();
    // `W` and `W_nu` (`U diag(k)`, `U diag(nu k)` but for a support's branches).
    let (load, main) = (br.load(), br.main_load());
    for j in 0..p {
        let (k, y) = (br.stiffness[j], n + j);
        for row in 0..n {
            for c in 0..n {
                stiffness[(row, c)] += main[(row, j)] * br.coupling[(c, j)].conj();
            }
            stiffness[(row, y)] = -load[(row, j)];
            stiffness[(y, row)] = -br.coupling[(row, j)].conj() * k;
        }
        stiffness[(y, y)] = linalg::c64::new(k, 0.0);
        let c = linalg::c64::new(k / br.rate[j], 0.0);
        if br.rotating(j) {
            c_r[(y, y)] = c;
        } else {
            c_n[(y, y)] = c;
        }
        spin.push(if br.spin[j] < 0.0 { -1.0 } else { 1.0 });
    }
    let mut coordinates: Vec<Coordinate> = (0..n)
        .map(|i| Coordinate::Physical {
            dof: dofs[i % dofs.len()],
            conjugate: i >= dofs.len(),
        })
        .collect();
    let own = p - r.branches.len();
    coordinates.extend((0..p).map(|j| match j < own {
        true => Coordinate::Internal {
            mode: br.mode[j],
            branch: br.index[j],
            rotating: br.rotating(j),
            rate: br.rate[j],
        },
        false => {
            let (s, branch, conjugate) = r.branches.of[j - own];
            Coordinate::Support {
                support: system.supports[s].support.path(),
                branch,
                conjugate,
                rate: br.rate[j],
            }
        }
    }));
    Augmented {
        mass: pad(&r.mass),
        gyroscopic: pad(&r.gyroscopic),
        stiffness,
        damping_rotating: c_r,
        damping_nonrotating: c_n,
        spin,
        coordinates,
    }
}

/// One point of a damper's fit.
#[derive(Debug, Clone, PartialEq)]
pub struct FitSample {
    pub frequency: f64,
    pub loss_factor: f64,
    /// Added storage stiffness relative to the modal stiffness.
    pub storage_change: f64,
}

/// How one nonviscous damper reproduces its hysteretic loss over a band.
#[derive(Debug, Clone, PartialEq)]
pub struct DamperFit {
    pub mode: usize,
    pub rotating: bool,
    /// `w0`, rad/s.
    pub tuning_frequency: f64,
    /// Target loss factor `eta` (modal loss stiffness over modal stiffness).
    pub loss_factor: f64,
    pub branches: usize,
    pub spacing: f64,
    pub relaxation_rates: Vec<f64>,
    /// Branch springs `k_j` and dampers `c_j` in modal units (mass-normalised modes).
    pub spring: Vec<f64>,
    pub damper: Vec<f64>,
    pub band: [f64; 2],
    /// Largest and RMS of `|eta_branches / eta - 1|` over the band (log-spaced samples).
    pub max_deviation: f64,
    pub rms_deviation: f64,
    pub storage_change_at_tuning: f64,
    pub max_storage_change: f64,
    pub added_states: usize,
    pub samples: Vec<FitSample>,
}

/// Samples per band for the deviations; the reported curve is every tenth.
const SAMPLES: usize = 401;

/// The default band of a damper: `m` spacings wide, centred on its tuning (one decade per
/// branch for the default spacing of 10).
pub fn default_band(set: &BranchSet, w0: f64) -> [f64; 2] {
    let half = set.spacing().powf(set.count() as f64 / 2.0);
    [w0 / half, w0 * half]
}

/// Largest and RMS relative deviation of the loss factor over `band`.
pub fn deviation(set: &BranchSet, w0: f64, band: [f64; 2]) -> (f64, f64) {
    let (mut max, mut sum) = (0.0f64, 0.0);
    for w in log_space(band, SAMPLES) {
        let d = (set.relative_loss(w, w0) - 1.0).abs();
        max = max.max(d);
        sum += d * d;
    }
    (max, (sum / SAMPLES as f64).sqrt())
}

/// Every damper of the model: one per retained mode and side with a nonzero loss, given as
/// `(mode, w0, loss stiffness, rotating)`.
pub fn fits(
    dampers: &[(usize, f64, f64, bool)],
    spec: &NonviscousSpec,
    band: Option<[f64; 2]>,
) -> Vec<DamperFit> {
    let mut out = vec![];
    for &(i, w0, loss, rotating) in dampers {
        let set = if rotating {
            &spec.rotating
        } else {
            &spec.nonrotating
        };
        let eta = loss / (w0 * w0);
        let band = band.unwrap_or_else(|| default_band(set, w0));
        let (max_deviation, rms_deviation) = deviation(set, w0, band);
        let storage = |w: f64| storage_change(set, eta, w, w0);
        let all: Vec<f64> = log_space(band, SAMPLES).collect();
        let rates = set.rates(w0);
        let spring: Vec<f64> = set.gamma().iter().map(|g| loss * g).collect();
        out.push(DamperFit {
            mode: i,
            rotating,
            tuning_frequency: w0,
            loss_factor: eta,
            branches: set.count(),
            spacing: set.spacing(),
            damper: spring.iter().zip(&rates).map(|(k, d)| k / d).collect(),
            spring,
            relaxation_rates: rates,
            band,
            max_deviation,
            rms_deviation,
            storage_change_at_tuning: storage(w0),
            max_storage_change: all.iter().map(|&w| storage(w).abs()).fold(0.0, f64::max),
            added_states: set.count(),
            samples: all
                .iter()
                .step_by(10)
                .map(|&w| FitSample {
                    frequency: w,
                    loss_factor: eta * set.relative_loss(w, w0),
                    storage_change: storage(w),
                })
                .collect(),
        });
    }
    // Single layout: one damper pair per mode, in the order of the modes.
    out.sort_by_key(|d| (d.mode, d.rotating));
    out
}

/// Added storage stiffness over the modal stiffness at `w`.
pub fn storage_change(set: &BranchSet, eta: f64, w: f64, w0: f64) -> f64 {
    set.rates(w0)
        .iter()
        .zip(set.gamma())
        .zip(set.nu())
        .map(|((d, g), nu)| {
            let r2 = (w / d).powi(2);
            g * (nu - 1.0 + r2 / (1.0 + r2))
        })
        .sum::<f64>()
        * eta
}

/// The fewest branches (with `spacing`, plain Maxwell branches) whose loss factor stays within
/// `max_deviation` of the target over `band` for dampers tuned at each of `tunings`; `Err`
/// with the best deviation reached at the largest count.
pub fn choose_branches(
    spacing: f64,
    band: [f64; 2],
    max_deviation: f64,
    tunings: &[f64],
) -> Result<BranchSet, f64> {
    let mut best = f64::INFINITY;
    for m in 1..=BranchSet::MAX_BRANCHES {
        let Ok(set) = BranchSet::new(m, spacing, vec![1.0; m]) else {
            continue;
        };
        let worst = tunings
            .iter()
            .map(|&w0| deviation(&set, w0, band).0)
            .fold(0.0, f64::max);
        if worst <= max_deviation {
            return Ok(set);
        }
        best = best.min(worst);
    }
    Err(best)
}

fn log_space(band: [f64; 2], n: usize) -> impl Iterator<Item = f64> {
    let (a, b) = (band[0].ln(), band[1].ln());
    (0..n).map(move |i| (a + (b - a) * i as f64 / (n - 1) as f64).exp())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn more_branches_flatten_the_loss_factor_until_they_span_the_band() {
        // Four decades around the tuning: the deviation falls until the branches span the
        // band (5 at spacing 10), then stays at the ripple between relaxation rates (~10.7%).
        let band = [1.0, 1e4];
        let dev =
            |m: usize| deviation(&BranchSet::new(m, 10.0, vec![1.0; m]).unwrap(), 100.0, band).0;
        for m in 1..5 {
            assert!(
                dev(m + 1) < dev(m),
                "{m} -> {}: {} -> {}",
                m + 1,
                dev(m),
                dev(m + 1)
            );
        }
        for m in 5..=8 {
            assert!((dev(m) - 0.107).abs() < 0.005, "{m}: {}", dev(m));
        }
        // The automatic choice stops at the first count that meets the bound.
        let set = choose_branches(10.0, band, 0.2, &[100.0]).unwrap();
        assert_eq!(set.count(), 5);
        assert!(choose_branches(10.0, band, 0.05, &[100.0]).is_err());
    }

    #[test]
    fn plain_maxwell_branches_add_no_static_stiffness_and_the_loss_at_high_frequency() {
        let set = BranchSet::new(3, 10.0, vec![1.0; 3]).unwrap();
        assert!(storage_change(&set, 0.02, 1e-9, 1.0).abs() < 1e-15);
        let total: f64 = set.gamma().iter().sum();
        assert!((storage_change(&set, 0.02, 1e6, 1.0) - 0.02 * total).abs() < 1e-9);
    }
}
