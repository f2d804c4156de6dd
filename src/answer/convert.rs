//! Domain results to wire types.

use crate::analysis::campbell::CampbellResult;
use crate::analysis::modal::ModalResult;
use crate::analysis::poles;
use crate::analysis::stability::Threshold;
use crate::analysis::time::fit_poles::FitPoles;
use crate::analysis::unbalance::Orbit;
use crate::damping::StateModel;
use crate::damping::report::{Augmented, Coordinate, DamperFit, ModelMatrices};
use crate::damping::whirl_fit::SupportFit;
use crate::linalg::{CMat, RMat, c64};
use crate::model::api;
use crate::system::{Dof, DofKind};

pub fn whirl(w: poles::Whirl) -> api::Whirl {
    match w {
        poles::Whirl::Forward => api::Whirl::Forward,
        poles::Whirl::Backward => api::Whirl::Backward,
        poles::Whirl::Internal => api::Whirl::Internal,
    }
}

pub fn pole(p: &poles::Pole) -> api::Pole {
    api::Pole {
        decay_rate: p.decay_rate(),
        frequency: p.frequency(),
        whirl: whirl(p.whirl),
        damping_ratio: p.damping_ratio(),
        log_decrement: p.log_decrement(),
        whirl_ratio: (p.whirl != poles::Whirl::Internal).then_some(p.whirl_ratio),
        shape: None,
        residual: None,
    }
}

/// The translations of a mode shape, the largest scaled to 1 (real), each with its node's
/// slope (the rotation) where the node keeps one.
fn translations(p: &poles::Pole, dofs: &[Dof]) -> Vec<api::NodeDisplacement> {
    let of = |kind: DofKind| -> Vec<(usize, c64)> {
        dofs.iter()
            .zip(&p.shape)
            .filter(|(d, _)| d.kind == kind)
            .map(|(d, x)| (d.node, *x))
            .collect()
    };
    let (mut t, r) = (of(DofKind::Translation), of(DofKind::Rotation));
    if t.is_empty() {
        // A torsional or axial system: its twists or axial displacements.
        t = of(DofKind::Twist);
        t.extend(of(DofKind::Axial));
    }
    let big = t
        .iter()
        .map(|(_, x)| *x)
        .max_by(|a, b| a.norm().total_cmp(&b.norm()))
        .unwrap_or(c64::new(1.0, 0.0));
    let scale = if big.norm() > 0.0 {
        1.0 / big
    } else {
        c64::new(1.0, 0.0)
    };
    t.into_iter()
        .map(|(node, x)| {
            let v = x * scale;
            let slope = r.iter().find(|(n, _)| *n == node).map(|(_, phi)| {
                let s = *phi * scale;
                [s.re, s.im]
            });
            api::NodeDisplacement {
                node,
                re: v.re,
                im: v.im,
                slope,
            }
        })
        .collect()
}

/// Where a beam rotor's nodes, supports and disks are.
pub fn shaft_layout(rotor: &crate::model::rotor::Rotor) -> Option<api::ShaftLayout> {
    let crate::model::rotor::Rotor::Beam(b) = rotor else {
        return None;
    };
    let mut positions = vec![0.0];
    for e in b.elements() {
        positions.push(positions[positions.len() - 1] + e.length());
    }
    let supports = b
        .supports()
        .iter()
        .map(|s| (s.node, s.seal))
        .chain(b.general_supports().iter().map(|s| (s.node, s.seal)));
    let (mut bearings, mut seals) = (vec![], vec![]);
    for (node, seal) in supports {
        if seal { &mut seals } else { &mut bearings }.push(node);
    }
    for v in [&mut bearings, &mut seals] {
        v.sort_unstable();
        v.dedup();
    }
    let mut disks: Vec<usize> = b.disks().iter().map(|d| d.node).collect();
    disks.sort_unstable();
    disks.dedup();
    Some(api::ShaftLayout {
        positions,
        bearings,
        seals,
        disks,
        couplings: b.couplings(),
    })
}

pub fn modal(r: &ModalResult) -> api::ModalResponse {
    let residuals = r.consistency.as_ref().map(|c| &c.residuals);
    let mut poles: Vec<api::Pole> = r
        .poles
        .rotor
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let mut out = pole(p);
            out.shape = Some(translations(p, &r.dofs));
            out.residual = residuals.and_then(|v| v.get(i).copied());
            out
        })
        .collect();
    let read: Vec<f64> = r.poles.rotor.iter().map(|p| p.s.im.abs()).collect();
    let consistency = r.consistency.as_ref().map(|c| api::ConsistencyInfo {
        max_residual: c.residuals.iter().copied().fold(0.0, f64::max),
        lost: c.lost,
        merged: c.merged,
        solves: c.solves,
        read_at: match read.is_empty() {
            true => [0.0, 0.0],
            false => [
                read.iter().copied().fold(f64::INFINITY, f64::min),
                read.iter().copied().fold(0.0, f64::max),
            ],
        },
    });
    poles.extend(r.poles.internal.iter().map(pole));
    api::ModalResponse {
        output_unit: Default::default(),
        warnings: vec![],
        speed: r.poles.speed,
        poles,
        natural_frequencies: r.natural_frequencies.clone(),
        states: r.states,
        missing_poles: r.poles.missing(),
        max_frequency: None,
        full_model: api::Storage::Dense,
        shaft: None,
        consistency,
        motion: Default::default(),
    }
}

pub fn campbell(r: &CampbellResult) -> api::CampbellResponse {
    api::CampbellResponse {
        nondimensional: false,
        output_unit: Default::default(),
        warnings: vec![],
        speeds: r.speeds.clone(),
        branches: r
            .branches
            .iter()
            .map(|b| api::Branch {
                mode: b.mode,
                whirl: whirl(b.whirl),
                frequency: b.poles.iter().map(|p| p.map(|s| s.im)).collect(),
                decay_rate: b.poles.iter().map(|p| p.map(|s| s.re)).collect(),
                log_decrement: b.log_decrement(),
                damping_ratio: b.damping_ratio(),
                whirl_ratio: b.whirl_ratio.clone(),
            })
            .collect(),
        critical_speeds: r.critical_speeds.clone(),
        criticals: r
            .criticals
            .iter()
            .map(|c| api::CriticalSpeed {
                speed: c.speed,
                whirl: whirl(c.whirl),
                mode: c.mode,
                branch: c.branch,
                decay_rate: c.pole.re,
                log_decrement: c.log_decrement(),
                damping_ratio: c.damping_ratio(),
                whirl_ratio: c.whirl_ratio,
                critically_damped: c.critically_damped(),
            })
            .collect(),
        overdamped: r
            .overdamped
            .iter()
            .map(|b| api::OverdampedBranch {
                decay_rate: b.poles.iter().map(|p| p.map(|s| s.re)).collect(),
                frequency: b.poles.iter().map(|p| p.map(|s| s.im)).collect(),
            })
            .collect(),
        ambiguities: r
            .ambiguities
            .iter()
            .map(|a| api::Ambiguity {
                speed: r.speeds[a.speed],
                branches: [a.branches.0, a.branches.1],
            })
            .collect(),
        threshold: r.threshold.as_ref().map(|t| t.speed),
        reduction: r.reduction.as_ref().map(reduction),
        motion: Default::default(),
        interference: r
            .interference
            .as_ref()
            .map(super::convert_train::interference),
    }
}

pub fn reduction(d: &crate::analysis::reduction::Reduction) -> api::ReductionInfo {
    api::ReductionInfo {
        modes: d.modes,
        vectors: d.vectors,
        band: d.band,
        states: d.states,
        full_states: d.full_states,
        checked_speed: d.checked_speed,
        checked_speeds: d.checked_speeds.clone(),
        max_relative_error: d.max_relative_error,
        full_model: storage(d.sparse),
        outside_box: d.outside.map(|o| api::OutsideBox {
            poles: o.poles,
            refined: o.refined,
            removed: o.removed,
            largest_change: o.largest_change,
        }),
        damped_modes: d.dampers.map(|d| d.0),
        damped_band: d.dampers.map(|d| d.1),
    }
}

/// How a full model was held.
pub fn storage(sparse: bool) -> api::Storage {
    match sparse {
        true => api::Storage::Sparse,
        false => api::Storage::Dense,
    }
}

pub fn response_reduction(
    d: &crate::analysis::response::ResponseReduction,
) -> api::ResponseReductionInfo {
    api::ResponseReductionInfo {
        modes: d.modes,
        vectors: d.vectors,
        band: d.band,
        states: d.states,
        full_states: d.full_states,
        checked: d.checked.clone(),
        max_relative_error: d.max_relative_error,
    }
}

pub fn stability(
    t: Option<&Threshold>,
    speeds: &[f64],
    max_decay_rate: Vec<f64>,
) -> api::StabilityResponse {
    api::StabilityResponse {
        nondimensional: false,
        output_unit: Default::default(),
        warnings: vec![],
        speeds: speeds.to_vec(),
        max_decay_rate,
        threshold: t.map(|t| t.speed),
        mode: t.map(|t| t.mode),
        whirl: t.map(|t| whirl(t.pole.whirl)),
        frequency: t.map(|t| t.pole.frequency()),
        range: [speeds[0], speeds[speeds.len() - 1]],
        max_frequency: None,
        reduction: None,
        threshold_closed: None,
    }
}

/// Rows of a real matrix.
pub fn rows(a: &RMat) -> Vec<Vec<f64>> {
    (0..a.nrows())
        .map(|i| (0..a.ncols()).map(|j| a[(i, j)]).collect())
        .collect()
}

/// Rows of one part (`re` or `im`) of a complex matrix.
fn part(a: &CMat, f: fn(c64) -> f64) -> Vec<Vec<f64>> {
    (0..a.nrows())
        .map(|i| (0..a.ncols()).map(|j| f(a[(i, j)])).collect())
        .collect()
}

fn has_imaginary(a: &CMat) -> bool {
    (0..a.nrows()).any(|i| (0..a.ncols()).any(|j| a[(i, j)].im != 0.0))
}

fn complex(a: &CMat) -> api::ComplexMatrix {
    let part = |f: fn(c64) -> f64| -> Vec<Vec<f64>> {
        (0..a.nrows())
            .map(|i| (0..a.ncols()).map(|j| f(a[(i, j)])).collect())
            .collect()
    };
    api::ComplexMatrix {
        re: part(|z| z.re),
        im: part(|z| z.im),
    }
}

pub fn second_order(a: &Augmented) -> api::SecondOrderMatrices {
    let all = [
        &a.mass,
        &a.gyroscopic,
        &a.stiffness,
        &a.damping_rotating,
        &a.damping_nonrotating,
    ];
    let of = |f: fn(c64) -> f64| api::SecondOrderMatrices {
        mass: part(&a.mass, f),
        gyroscopic: part(&a.gyroscopic, f),
        stiffness: part(&a.stiffness, f),
        damping_rotating: part(&a.damping_rotating, f),
        damping_nonrotating: part(&a.damping_nonrotating, f),
        imaginary: None,
        spin: None,
    };
    let mut out = of(|z| z.re);
    if all.iter().any(|m| has_imaginary(m)) {
        out.imaginary = Some(Box::new(of(|z| z.im)));
    }
    if a.spin.iter().any(|&s| s != 1.0) {
        out.spin = Some(a.spin.clone());
    }
    out
}

/// State form; `m_inv` is `M^-1` (complex), placed on the velocity rows of `B`.
pub fn state(sm: &StateModel, m_inv: &CMat) -> api::StateMatrices {
    let (size, n) = (sm.size(), sm.n());
    api::StateMatrices {
        constant: complex(sm.a0()),
        per_speed: complex(sm.a1()),
        input: (0..size)
            .map(|i| {
                (0..n)
                    .map(|j| if i < n { m_inv[(i, j)].re } else { 0.0 })
                    .collect()
            })
            .collect(),
    }
}

pub fn coordinates(c: &[Coordinate]) -> Vec<api::CoordinateOut> {
    c.iter()
        .enumerate()
        .map(|(index, c)| match c {
            Coordinate::Physical { dof: d, conjugate } => api::CoordinateOut {
                index,
                conjugate: conjugate.then_some(true),
                kind: match d.kind {
                    DofKind::Translation => "translation",
                    DofKind::Rotation => "rotation",
                    DofKind::Mode => "mode",
                    DofKind::Twist => "twist",
                    DofKind::Axial => "axial",
                }
                .into(),
                node: Some(d.node),
                mode: None,
                branch: None,
                rotating: None,
                relaxation_rate: None,
                support: None,
            },
            Coordinate::Internal {
                mode,
                branch,
                rotating,
                rate,
            } => api::CoordinateOut {
                index,
                conjugate: None,
                kind: "internal".into(),
                node: None,
                mode: Some(mode + 1),
                branch: Some(branch + 1),
                rotating: Some(*rotating),
                relaxation_rate: Some(*rate),
                support: None,
            },
            Coordinate::Support {
                support,
                branch,
                conjugate,
                rate,
            } => api::CoordinateOut {
                index,
                conjugate: conjugate.then_some(true),
                kind: "support branch".into(),
                node: None,
                mode: None,
                branch: Some(branch + 1),
                rotating: Some(false),
                relaxation_rate: Some(*rate),
                support: Some(support.clone()),
            },
        })
        .collect()
}

pub fn damper(f: &DamperFit) -> api::DamperReport {
    api::DamperReport {
        mode: f.mode + 1,
        rotating: f.rotating,
        tuning_frequency: f.tuning_frequency,
        loss_factor: f.loss_factor,
        branches: f.branches,
        spacing: f.spacing,
        relaxation_rates: f.relaxation_rates.clone(),
        springs: f.spring.clone(),
        dampers: f.damper.clone(),
        band: f.band,
        max_deviation: f.max_deviation,
        rms_deviation: f.rms_deviation,
        storage_change_at_tuning: f.storage_change_at_tuning,
        max_storage_change: f.max_storage_change,
        added_states: f.added_states,
        curve: f
            .samples
            .iter()
            .map(|s| api::FitPoint {
                frequency: s.frequency,
                loss_factor: s.loss_factor,
                storage_change: s.storage_change,
            })
            .collect(),
    }
}

pub fn damping_matrices(r: &ModelMatrices, model: &str) -> api::DampingMatricesResponse {
    api::DampingMatricesResponse {
        warnings: vec![],
        model: model.into(),
        coordinates: coordinates(&r.augmented.coordinates),
        second_order: r.state.is_none().then(|| second_order(&r.augmented)),
        state: r.state.as_ref().map(|(sm, m_inv)| state(sm, m_inv)),
        equivalent_rotating: r.equivalent.as_ref().map(|(c_r, _)| part(c_r, |z| z.re)),
        equivalent_nonrotating: r.equivalent.as_ref().map(|(_, c_n)| part(c_n, |z| z.re)),
        equivalent_nonrotating_imaginary: r
            .equivalent
            .as_ref()
            .filter(|(_, c_n)| has_imaginary(c_n))
            .map(|(_, c_n)| part(c_n, |z| z.im)),
        modes: r
            .modes
            .iter()
            .enumerate()
            .map(|(i, &(w, eta_r, eta_n))| api::ModeLoss {
                mode: i + 1,
                natural_frequency: w,
                loss_factor_rotating: eta_r,
                loss_factor_nonrotating: eta_n,
            })
            .collect(),
        dampers: r.dampers.iter().map(damper).collect(),
        added_states: r.added_states,
        branches_rotating: r.branches.map(|b| b.0),
        branches_nonrotating: r.branches.map(|b| b.1),
        support_fits: vec![],
    }
}

/// A support's Maxwell fit.
pub fn support_fit(f: &SupportFit) -> api::SupportFitInfo {
    let [xx, xy, yx, yy] = f.deviation;
    api::SupportFitInfo {
        support: f.path.clone(),
        rates: f.rates.clone(),
        band: f.band,
        deviation: api::Matrix2Out { xx, xy, yx, yy },
        max_deviation: f.max_deviation(),
        speeds: f.speeds.clone(),
        shrunk: f.shrunk,
    }
}

pub fn fit_poles(p: &FitPoles) -> api::FitPolesInfo {
    let value = |s: c64| api::PoleValue {
        decay_rate: s.re,
        frequency: s.im,
    };
    api::FitPolesInfo {
        speed: p.speed,
        poles: p
            .pairs
            .iter()
            .map(|q| api::FitPolePair {
                consistent: value(q.consistent),
                fitted: value(q.fitted),
                distance: q.distance,
            })
            .collect(),
        max_distance: p.max_distance,
        max_decay_rate: p.max_decay_rate.0,
        fitted_max_decay_rate: p.max_decay_rate.1,
        unstable: p.unstable.iter().map(|&s| value(s)).collect(),
        lost: p.lost,
        merged: p.merged,
    }
}

pub fn unbalance_response(
    speeds: &[f64],
    nodes: &[usize],
    q: &[Vec<Orbit>],
    model: &str,
) -> api::UnbalanceResponseResponse {
    let note = match model {
        "hysteretic" => {
            "hysteretic: the rotor material sees zero frequency in synchronous whirl, where the \
             model is undefined; it is evaluated with sgn(0) = 0, so only the nonrotating loss \
             acts (the limit the other models share)"
        }
        _ => {
            "in synchronous whirl the rotor material sees zero frequency: rotating damping \
             (viscous, equivalent or nonviscous) does no work; only nonrotating damping acts"
        }
    };
    let column = |k: usize, f: &dyn Fn(&Orbit) -> f64| -> Vec<f64> {
        q.iter().map(|row| f(&row[k])).collect()
    };
    api::UnbalanceResponseResponse {
        nondimensional: false,
        output_unit: Default::default(),
        warnings: vec![],
        reduction: None,
        full_model: Default::default(),
        speeds: speeds.to_vec(),
        nodes: nodes
            .iter()
            .enumerate()
            .map(|(k, &node)| api::NodeUnbalance {
                node,
                amplitude: column(k, &|o| o.major()),
                phase: column(k, &|o| o.a.arg()),
                x_amplitude: column(k, &|o| o.xy()[0].norm()),
                x_phase: column(k, &|o| o.xy()[0].arg()),
                y_amplitude: column(k, &|o| o.xy()[1].norm()),
                y_phase: column(k, &|o| o.xy()[1].arg()),
                major: column(k, &|o| o.major()),
                minor: column(k, &|o| o.minor()),
                peaks: vec![],
            })
            .collect(),
        note: note.into(),
    }
}
