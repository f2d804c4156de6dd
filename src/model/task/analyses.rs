//! The frequency-domain requests parsed into tasks: one speed (`modal`), a sweep (`campbell`,
//! `stability`) and the damping model as matrices (`damping`).

use super::*;
use super::{CampbellTask, DampingTask, ModalTask, StabilityTask};

impl ModalRequest {
    pub fn parse(&self, limits: &Limits) -> Result<Task, Invalid> {
        let mut bad = Invalid::default();
        let speed = speed_at(&mut bad, "speed", self.speed);
        let bound = self
            .max_frequency
            .and_then(|f| typed_speed(&mut bad, "max_frequency", f, positive));
        // Only a bounded modal analysis holds a large rotor sparse: every pole of it is not
        // asked for.
        let (model, sparse) = Model::parse_held(
            bound.is_some(),
            self.motion,
            &self.rotor,
            &self.damping,
            limits,
            bad,
        )?;
        let size = model.size();
        let n = size.dofs as u64;
        let cost = match sparse {
            // At most one pole per two Arnoldi vectors, each with its shape on every node.
            true => {
                let poles = SPARSE_ARNOLDI as u64 / 2;
                let values = poles * (5 + 3 * model.rotor.node_count() as u64) + n;
                let linear = n * sparse_bytes_per_coordinate(model.rotor.doubled())
                    + model.damper_bytes(limits);
                let response_bytes = values * BYTES_PER_VALUE;
                Cost {
                    size,
                    peak_bytes: linear + values * 16 + response_bytes,
                    response_bytes,
                    work: SPARSE_WORK * n as f64,
                }
            }
            false => {
                let values =
                    size.states() as u64 * 5 + 2 * n * model.rotor.node_count() as u64 * 3 + n;
                Cost::new(size, 1, 1, 0, values).with_work(size.eigen_work())
            }
        };
        let speed = speed.expect("validated");
        Task {
            output_unit: self.output_unit.unwrap_or_default(),
            warnings: model.warnings(speed, speed),
            kind: TaskKind::Modal(ModalTask {
                model,
                speed,
                max_frequency: bound.unwrap_or(f64::INFINITY),
                sparse,
            }),
            cost,
        }
        .bounded(limits, "rotor")
    }
}

impl SweepRequest {
    /// The model (held sparse where `hold` and it may be, [`Model::parse_held`]) and speeds.
    fn parse_sweep(
        &self,
        limits: &Limits,
        hold: bool,
    ) -> Result<(Model, SpeedGrid, bool), Invalid> {
        let mut bad = Invalid::default();
        if let Some(f) = self.max_frequency {
            typed_speed(&mut bad, "max_frequency", f, positive);
        }
        if let Some(m) = self.modes
            && m < 1
        {
            bad.push("modes", format!("must be an integer >= 1 (got {m})"));
        }
        let grid = speeds(&self.speeds, limits, &mut bad);
        let (model, sparse) =
            Model::parse_held(hold, self.motion, &self.rotor, &self.damping, limits, bad)?;
        Ok((model, grid.expect("validated"), sparse))
    }

    /// `POST /v1/campbell`.
    pub fn parse_campbell(&self, limits: &Limits) -> Result<Task, Invalid> {
        // A bounded sweep (of the viscous or hysteretic model) may hold a large rotor sparse.
        let hold = self.max_frequency.is_some()
            && self.modes.is_none()
            && self.modal_reduction.unwrap_or(true);
        let (model, speeds, sparse) = self.parse_sweep(limits, hold)?;
        let size = model.size();
        let count = speeds.as_slice().len();
        let rotor_poles = 2 * size.dofs as u64;
        let modes = self.modes.map(|m| (m as u64).min(rotor_poles) as usize);
        if let Some(m) = self.modes
            && m as u64 > rotor_poles
        {
            return Err(Invalid::one(
                "modes",
                format!("this rotor has {rotor_poles} rotor poles (got {m})"),
            ));
        }
        // At most 2n branches (`modes` of them if given); with `max_frequency` fewer, known
        // only after the solve, and held sparse at most the reduced model's states. Two values
        // per branch and speed.
        let most = match sparse {
            true => rotor_poles.min(sparse_states(limits) as u64),
            false => rotor_poles,
        };
        let branches = modes.map_or(most, |m| m as u64);
        let values = count as u64 * (1 + 2 * branches);
        let cost = match sparse {
            true => sparse_sweep_cost(size, model.rotor.doubled(), count, limits, values)
                .plus_bytes(model.damper_bytes(limits)),
            false => sweep_cost(size, count, limits, true, values),
        };
        let bounded = self.max_frequency.is_none() && modes.is_none();
        let (lo, hi) = speeds.range();
        let interference = self.interference_spec(&model, &speeds)?;
        let task = Task {
            output_unit: self.output_unit.unwrap_or_default(),
            warnings: model.warnings(lo, hi),
            kind: TaskKind::Campbell(CampbellTask {
                model,
                speeds,
                max_frequency: self.max_frequency.map_or(f64::INFINITY, SpeedInput::rad_s),
                modes,
                // A train's torsional or axial system is small, and may turn freely.
                reduce: self.modal_reduction.unwrap_or(true) && interference.is_none(),
                sparse,
                max_states: sparse_states(limits),
                interference,
            }),
            cost,
        };
        if bounded {
            task.bounded(limits, "speeds")
        } else {
            Ok(task)
        }
    }

    /// The interference diagram of a torsional or axial sweep (none for a lateral one, which
    /// refuses `interference`).
    fn interference_spec(
        &self,
        model: &Model,
        speeds: &SpeedGrid,
    ) -> Result<Option<crate::model::train::Spec>, Invalid> {
        use crate::model::train::{Line, Spec};
        let crate::model::rotor::Rotor::Train(train) = &model.rotor else {
            return match self.interference {
                Some(_) => Err(Invalid::one(
                    "interference",
                    "the interference diagram is a torsional or axial analysis's: ask for \
                     `motion: torsional` (or `axial`)",
                )),
                None => Ok(None),
            };
        };
        let mut bad = Invalid::default();
        let input = self.interference.clone().unwrap_or_default();
        let orders = input.orders.clone().unwrap_or_else(|| vec![1.0, 2.0]);
        if orders.is_empty() || orders.len() > 16 {
            bad.push("interference.orders", "give 1 to 16 orders");
        }
        let mut lines = vec![];
        for (i, &k) in orders.iter().enumerate() {
            if let Some(k) = bad.check(&format!("interference.orders[{i}]"), positive(k)) {
                for ratio in train.shaft_ratios() {
                    lines.push(Line::Order { order: k, ratio });
                }
            }
        }
        if let Some(f) = input.line_frequency
            && let Some(f) = typed_speed(&mut bad, "interference.line_frequency", f, positive)
        {
            for multiple in [1.0, 2.0] {
                lines.push(Line::Fixed {
                    multiple,
                    frequency: multiple * f,
                });
            }
        }
        let unit = self.speeds.unit();
        let smallest = speeds
            .as_slice()
            .iter()
            .copied()
            .find(|&w| w > 0.0)
            .unwrap_or(f64::NAN);
        let range = match input.operating_range {
            Some([a, b]) if a.is_finite() && b.is_finite() && a > 0.0 && b >= a => {
                Some([unit.to_rad_s(a), unit.to_rad_s(b)])
            }
            Some(r) => {
                bad.push(
                    "interference.operating_range",
                    format!("must be [min, max] with 0 < min <= max (got {r:?})"),
                );
                None
            }
            None => Some([smallest, speeds.range().1]),
        };
        bad.into_result(|| {
            Some(Spec {
                lines,
                range: range.expect("validated"),
            })
        })
    }

    /// `POST /v1/stability`.
    pub fn parse_stability(&self, limits: &Limits) -> Result<Task, Invalid> {
        // A large rotor is held sparse only for the poles below `max_frequency` (ignored on a
        // rotor solved dense, whose every pole is considered).
        let hold = self.max_frequency.is_some() && self.modal_reduction.unwrap_or(true);
        let (model, speeds, sparse) = self.parse_sweep(limits, hold)?;
        let size = model.size();
        let count = speeds.as_slice().len();
        let values = 2 * count as u64 + 8;
        let (cost, held) = match sparse {
            true => (
                sparse_sweep_cost(size, model.rotor.doubled(), count, limits, values)
                    .plus_bytes(model.damper_bytes(limits)),
                Some((
                    self.max_frequency.map_or(f64::INFINITY, SpeedInput::rad_s),
                    sparse_states(limits),
                )),
            ),
            false => (sweep_cost(size, count, limits, false, values), None),
        };
        let (lo, hi) = speeds.range();
        let task = Task {
            output_unit: self.output_unit.unwrap_or_default(),
            warnings: model.warnings(lo, hi),
            kind: TaskKind::Stability(StabilityTask {
                model,
                speeds,
                held,
            }),
            cost,
        };
        task.whirl_read()?;
        Ok(task)
    }
}

impl DampingMatricesRequest {
    pub fn parse(&self, limits: &Limits) -> Result<Task, Invalid> {
        let mut bad = Invalid::default();
        let fit = self.fit.clone().unwrap_or_default();
        let band = match fit.band {
            Some([lo, hi]) if lo.is_finite() && hi.is_finite() && lo > 0.0 && hi > lo => {
                Some([lo, hi])
            }
            Some(b) => {
                bad.push(
                    "fit.band",
                    format!("must be [low, high] with 0 < low < high (got {b:?})"),
                );
                None
            }
            None => None,
        };
        let auto = match fit.max_deviation {
            None => None,
            Some(d) if d.is_finite() && d > 0.0 => Some(d),
            Some(d) => {
                bad.push(
                    "fit.max_deviation",
                    format!("must be a number > 0 (got {d})"),
                );
                None
            }
        };
        if auto.is_some() {
            match &self.damping {
                DampingInput::Nonviscous(nv) => {
                    for (side, b) in [("rotating", &nv.rotating), ("nonrotating", &nv.nonrotating)]
                    {
                        if let Some(b) = b
                            && (b.branches.is_some() || b.nu.is_some())
                        {
                            bad.push(
                                format!("damping.{side}"),
                                "fit.max_deviation chooses the number of branches: omit \
                                 `branches` and `nu`",
                            );
                        }
                    }
                    if fit.band.is_none() {
                        bad.push("fit.band", "needed with fit.max_deviation");
                    }
                }
                _ => bad.push("fit.max_deviation", "applies to the nonviscous model only"),
            }
        }
        let speed = speed_at(&mut bad, "speed", self.speed.unwrap_or_default());
        let model = Model::parse(&self.rotor, &self.damping, limits, bad)?;
        let speed = speed.expect("validated");
        // The viscous model adds matrices where a support over whirl frequency is fitted.
        let fitted = model
            .rotor
            .general_supports()
            .iter()
            .any(|s| s.frequency_dependent());
        if matches!(model.damping, DampingModel::Hysteretic)
            || (matches!(model.damping, DampingModel::Viscous) && !fitted)
        {
            return Err(Invalid::one(
                "damping.model",
                format!(
                    "`{}` adds no matrices: this endpoint returns the `equivalent` or \
                     `nonviscous` model, or the branches fitted to a support over whirl \
                     frequency (hysteretic damping has no time-domain form; nonviscous is its \
                     time-domain model)",
                    model.damping.name()
                ),
            ));
        }
        let state_form = self.form == Some(MatrixForm::State);
        // With an automatic fit the branches are chosen later (the fit refuses more states
        // than the limit before building); the memory is bounded by the most it may choose.
        let size = if auto.is_some() {
            let most = BranchSet::MAX_BRANCHES;
            let s = model.size_with(Some((most, most)));
            let cap = limits.max_states.saturating_sub(2 * s.dofs);
            Size {
                internal: s.internal.min(cap),
                ..s
            }
        } else {
            model.size()
        };
        let q = (size.dofs + size.internal) as u64;
        let s = size.states() as u64;
        let mut values = 5 * q * q + q * 8;
        if state_form {
            values += 4 * s * s + s * size.dofs as u64;
        }
        let extra = 5 * 8 * q * q
            + if state_form {
                16 * s * size.dofs as u64
            } else {
                0
            };
        let cost = Cost::new(size, 0, 0, extra, values)
            .with_work(size.eigen_work() / 10.0 + model.fit_work());
        Task {
            output_unit: Default::default(),
            warnings: model.warnings(speed, speed),
            kind: TaskKind::Damping(DampingTask {
                model,
                state_form,
                band,
                max_deviation: auto,
                max_states: limits.max_states,
                speed,
            }),
            cost,
        }
        .bounded(limits, "damping")
    }
}
