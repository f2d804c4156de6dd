//! The forced responses' requests parsed into tasks: time response (loads, speed law,
//! samples) and steady unbalance response.

use super::*;
use super::{TimeTask, UnbalanceTask};
use crate::model::loads::{Generated, Source, Torque};
use crate::model::torque::{MotorStart, ShortCircuit};

/// A node of a rotor with `nodes` nodes, or the error at `at`.
pub(super) fn node_index(bad: &mut Invalid, at: String, k: i64, nodes: usize) -> Option<usize> {
    if k >= 0 && (k as u64) < nodes as u64 {
        Some(k as usize)
    } else {
        bad.push(
            at,
            format!("node {k} does not exist (nodes 0 to {})", nodes - 1),
        );
        None
    }
}

/// The nodes to report: the requested ones (validated) or all.
pub(super) fn report_nodes(
    bad: &mut Invalid,
    requested: &Option<Vec<i64>>,
    nodes: usize,
) -> Vec<usize> {
    match requested {
        None => (0..nodes).collect(),
        Some(list) => {
            if list.is_empty() {
                bad.push("nodes", "needs at least one node (or omit it for all)");
            }
            list.iter()
                .enumerate()
                .filter_map(|(i, &k)| node_index(bad, format!("nodes[{i}]"), k, nodes))
                .collect()
        }
    }
}

impl TimeResponseRequest {
    pub fn parse(&self, limits: &Limits) -> Result<Task, Invalid> {
        let mut bad = Invalid::default();
        if matches!(self.damping, DampingInput::Hysteretic(_)) {
            bad.push(
                "damping.model",
                "the hysteretic model is defined for harmonic motion only and cannot be \
                 integrated in time; use `nonviscous` (its time-domain model) or `equivalent`",
            );
        }
        let speed = match (self.speed, &self.speed_profile) {
            (Some(w), None) => speed_at(&mut bad, "speed", w).map(SpeedLaw::Constant),
            (None, Some(p)) => {
                let (p, at) = p.rad_s();
                let law = Pwl::parse(&p, at, false, &mut bad);
                if p.iter().any(|q| q[1] < 0.0) {
                    bad.push(at, "speeds must be >= 0");
                }
                law.map(SpeedLaw::Profile)
            }
            (Some(_), Some(_)) => {
                bad.push("speed", "give `speed` or `speed_profile`, not both");
                None
            }
            // Torsion and axial motion do not depend on the speed.
            (None, None) if !self.motion.is_lateral() => Some(SpeedLaw::Constant(0.0)),
            (None, None) => {
                bad.push("speed", "give `speed` (constant) or `speed_profile`");
                None
            }
        };
        let duration = bad.check("duration", positive(self.duration));
        let dt = bad.check("output_interval", positive(self.output_interval));
        let tolerance = match self.tolerance {
            None => Some(1e-6),
            Some(x) if (1e-12..=1e-2).contains(&x) => Some(x),
            Some(x) => {
                bad.push("tolerance", format!("must be in [1e-12, 1e-2] (got {x})"));
                None
            }
        };
        // The output size is known from the request alone: check it before anything else.
        let requested_nodes = self.nodes.as_ref().map(Vec::len);
        let samples = match (duration, dt) {
            (Some(d), Some(h)) => Some(sample_count(d, h)),
            _ => None,
        };
        // Held sparse, a rotor is integrated on a checked reduction only.
        let reduce = self.modal_reduction.unwrap_or(true);
        let (model, sparse) =
            Model::parse_held(reduce, self.motion, &self.rotor, &self.damping, limits, bad)?;
        let mut bad = Invalid::default();
        let nodes = model.rotor.node_count();
        let node = |bad: &mut Invalid, at: String, k: i64| node_index(bad, at, k, nodes);
        // A torsional or axial response also reports every element's load.
        let elements = if self.motion.is_lateral() {
            0
        } else {
            nodes.saturating_sub(1)
        };
        let reported = requested_nodes.unwrap_or(nodes).max(1) + elements;
        let samples = samples.expect("validated");
        if samples.saturating_mul(reported) > limits.max_samples {
            // A count beyond any limit is shown as the ratio it comes from, not as a
            // saturated integer.
            let count = if samples < usize::MAX {
                samples.to_string()
            } else {
                format!("{:.3e}", self.duration / self.output_interval)
            };
            bad.push(
                "output_interval",
                format!(
                    "duration / output_interval gives {count} samples, x {reported} nodes: \
                     more than the limit of {} values (WHIRL_MAX_SAMPLES); use a longer \
                     interval, a shorter duration or fewer nodes",
                    limits.max_samples
                ),
            );
            return Err(bad);
        }
        let mut forces = vec![];
        for (i, f) in self.forces.iter().enumerate() {
            let at = format!("forces[{i}]");
            let n = node(&mut bad, format!("{at}.node"), f.node);
            let dir = bad.check(&format!("{at}.direction"), finite(f.direction));
            if !self.motion.is_lateral() && f.direction != 0.0 {
                bad.push(
                    format!("{at}.direction"),
                    "a torsional or axial load acts along the axis: it has no direction (give \
                     its sign in `history`)",
                );
            }
            let h = Pwl::parse(&f.history, &format!("{at}.history"), true, &mut bad);
            if let (Some(node), Some(direction), Some(history)) = (n, dir, h) {
                forces.push(Force {
                    node,
                    direction,
                    history,
                });
            }
        }
        if !self.motion.is_lateral() && !self.unbalances.is_empty() {
            bad.push(
                "unbalances",
                "an unbalance excites lateral motion only: give torsional or axial loads as \
                 `forces` (torques in N m for torsion)",
            );
        }
        let mut unbalances = vec![];
        for (i, u) in self.unbalances.iter().enumerate() {
            let at = format!("unbalances[{i}]");
            let n = node(&mut bad, format!("{at}.node"), u.node);
            let amount = bad.check(&format!("{at}.amount"), non_negative(u.amount));
            let phase = bad.check(&format!("{at}.phase"), finite(u.phase));
            let from = bad.check(&format!("{at}.from"), non_negative(u.from));
            if let (Some(node), Some(amount), Some(phase), Some(from)) = (n, amount, phase, from) {
                unbalances.push(Unbalance {
                    node,
                    amount,
                    phase,
                    from,
                });
            }
        }
        let generated = self.generated(&mut bad, nodes);
        if sparse && !generated.is_empty() {
            let field = match generated.motor {
                Some(_) => "motor_start",
                None => "short_circuit",
            };
            bad.push(
                field,
                format!(
                    "a machine's torques are applied to a train solved on all its modes: this \
                     one, {nodes} nodes, is past the dense limits; use fewer elements"
                ),
            );
        }
        let out = report_nodes(&mut bad, &self.nodes, nodes);
        if !bad.is_empty() {
            return Err(bad);
        }
        let spec = TimeSpec {
            speed: speed.expect("validated"),
            forces,
            unbalances,
            duration: duration.expect("validated"),
            output_interval: dt.expect("validated"),
            nodes: out,
            tolerance: tolerance.expect("validated"),
            max_steps: limits.max_steps,
            reduce,
            generated,
        };
        // The step count before any work: a fast run-up is refused here, not after minutes of
        // integration at the step limit.
        let fewest = spec.fewest_steps();
        if fewest > limits.max_steps as f64 {
            let field = if !spec.generated.is_empty() {
                if self.motor_start.is_some() {
                    "motor_start"
                } else {
                    "short_circuit"
                }
            } else if self.speed_profile.is_some() {
                "speed_profile"
            } else {
                "speed"
            };
            let what = if spec.generated.is_empty() {
                "the unbalances turn"
            } else {
                "the generated torques turn"
            };
            bad.push(
                field,
                format!(
                    "{what} through {:.3e} rad in this run: at least {:.3e} \
                     integration steps ({} rad a step at tolerance {:e}), more than the limit \
                     of {} (WHIRL_MAX_STEPS); use a slower speed profile, a shorter duration \
                     or a looser tolerance",
                    fewest * crate::model::loads::step_angle(spec.tolerance),
                    fewest,
                    crate::model::loads::step_angle(spec.tolerance),
                    spec.tolerance,
                    limits.max_steps
                ),
            );
            return Err(bad);
        }
        let size = model.size();
        let (s, n) = (size.states() as u64, size.dofs as u64);
        let values = samples as u64 * (1 + 2 * reported as u64);
        // Histories (complex) and, exact: V^-1 loads and the output rows of V; implicit: the
        // LU of the stage matrix and a few state vectors. Both within a second eigen's heap.
        let loads = (spec.forces.len() + spec.unbalances.len()) as u64;
        let extra = samples as u64 * reported as u64 * 16
            + 16 * s * (loads + reported as u64 + 16)
            + 16 * n * n;
        let steps = if spec.speed.constant().is_some() && spec.generated.is_empty() {
            0.0
        } else {
            (samples as f64).max(1e4).max(fewest)
        };
        let work = size.eigen_work() + steps * 8.0 * (s * s) as f64 + model.fit_work();
        let cost = match sparse {
            true => {
                // The outputs' histories, and the reduced model's as `extra` counts the full's.
                let r = sparse_states(limits) as u64;
                let extra = samples as u64 * reported as u64 * 16
                    + 16 * r * (loads + reported as u64 + 16)
                    + 4 * r * r;
                sparse_time_cost(size, model.rotor.doubled(), limits, extra, values)
                    .plus_bytes(model.damper_bytes(limits))
            }
            false => Cost::new(size, 2, 0, extra, values).with_work(work),
        };
        let (lo, hi) = spec.speed.range(spec.duration);
        Task {
            output_unit: Default::default(),
            warnings: model.warnings(lo, hi),
            kind: TaskKind::Time(TimeTask {
                model,
                spec,
                sparse,
            }),
            cost,
        }
        .bounded(limits, "output_interval")
    }
}

impl TimeResponseRequest {
    /// The torques electrical machines generate: torsional responses only.
    fn generated(&self, bad: &mut Invalid, nodes: usize) -> Generated {
        let mut out = Generated::default();
        let mut node = |bad: &mut Invalid, at: String, k: i64| node_index(bad, at, k, nodes);
        let torsional = self.motion == Motion::Torsional;
        if let Some(m) = &self.motor_start {
            if torsional {
                out.motor = MotorStart::parse(m, "motor_start", bad, &mut node);
            } else {
                bad.push(
                    "motor_start",
                    "a motor's start-up needs `motion: torsional`",
                );
            }
        }
        if let Some(s) = &self.short_circuit {
            if torsional {
                if let Some(s) = ShortCircuit::parse(s, "short_circuit", bad, &mut node) {
                    out.torques.push(Torque {
                        node: s.node,
                        source: Source::Fault(std::sync::Arc::new(s)),
                    });
                }
            } else {
                bad.push("short_circuit", "a short circuit needs `motion: torsional`");
            }
        }
        out
    }
}

impl UnbalanceResponseRequest {
    pub fn parse(&self, limits: &Limits) -> Result<Task, Invalid> {
        let mut bad = Invalid::default();
        let grid = speeds(&self.speeds, limits, &mut bad);
        if self.unbalances.is_empty() {
            bad.push("unbalances", "needs at least one unbalance");
        }
        let (model, sparse) = Model::parse_held(
            true,
            Motion::Lateral,
            &self.rotor,
            &self.damping,
            limits,
            bad,
        )?;
        let mut bad = Invalid::default();
        let nodes = model.rotor.node_count();
        let mut unbalances = vec![];
        for (i, u) in self.unbalances.iter().enumerate() {
            let at = format!("unbalances[{i}]");
            let n = node_index(&mut bad, format!("{at}.node"), u.node, nodes);
            let amount = bad.check(&format!("{at}.amount"), non_negative(u.amount));
            let phase = bad.check(&format!("{at}.phase"), finite(u.phase));
            if let (Some(n), Some(a), Some(p)) = (n, amount, phase) {
                unbalances.push((n, a, p));
            }
        }
        let out = report_nodes(&mut bad, &self.nodes, nodes);
        let range = self
            .operating_range
            .as_ref()
            .and_then(|r| crate::model::speeds::operating_range(r, "operating_range", &mut bad));
        if !bad.is_empty() {
            return Err(bad);
        }
        let speeds = grid.expect("validated");
        let size = model.size();
        let count = speeds.as_slice().len() as u64;
        let values = count * (1 + 8 * out.len() as u64);
        let s = size.states() as u64;
        let threads = limits.threads.max(1) as u64;
        // Per thread: the state matrix, the system and its LU.
        let extra = threads * 3 * 16 * s * s + count * out.len() as u64 * 16;
        let work = count as f64 * (s * s * s) as f64 * 3.0;
        // The sweep, then at most about two sweeps more to refine the peaks.
        let cost = match sparse {
            true => sparse_harmonic_cost(size, limits, 3 * count + 64, values)
                .plus_bytes(model.damper_bytes(limits)),
            false => Cost::new(size, 0, 0, extra, values).with_work(work),
        };
        let (lo, hi) = speeds.range();
        // An unbalance whirls at the speed: a table over whirl frequency is read there too.
        let mut warnings = model.warnings(lo, hi);
        warnings.extend(model.whirl_warnings(lo, hi));
        Task {
            output_unit: self.output_unit.unwrap_or_default(),
            warnings,
            kind: TaskKind::Unbalance(UnbalanceTask {
                model,
                speeds,
                unbalances,
                nodes: out,
                range,
                reduce: self.modal_reduction.unwrap_or(true),
                sparse,
            }),
            cost,
        }
        .bounded(limits, "speeds")
    }
}
