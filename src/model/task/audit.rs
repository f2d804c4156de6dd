//! The audit analyses' requests parsed into tasks: critical speed map, static deflection,
//! Level I and frequency response (the report that runs them all is in `report`).

use super::loads::node_index;
use super::{CriticalMapTask, FrequencyTask, Level1Task, StaticTask};
use super::{Model, Task, TaskKind, sparse_harmonic_cost, sparse_sweep_cost, speed_at, sweep_cost};
use crate::linalg::sparse::DENSE_UP_TO;
use crate::model::api::{
    CriticalSpeedMapRequest, FrequencyResponseRequest, Level1Request, Motion, RotorInput,
    SpeedsInput, StaticRequest, StaticSupports,
};
use crate::model::error::{Invalid, finite, positive};
use crate::model::limits::{
    BYTES_PER_VALUE, Cost, DIAGRAM_POINTS, Limits, MAX_SPARSE_MODES, Size, map_is_sparse,
};
use crate::model::loads::Excitation;
use crate::model::rotor::{BeamRotor, Rotor};
use crate::model::speeds::{linear, logarithmic};
use serde_json::Value;

/// `B_c` of Wachel's anticipated cross-coupling for centrifugal compressor stages (API 617).
const B_C: f64 = 3.0;

/// Values of an automatic Level I range.
const AUTO_COUNT: usize = 21;

pub(super) use crate::model::speeds::RPM;

/// The beam rotor of an analysis that replaces or ignores its supports' dynamics.
pub(super) fn beam(
    input: &RotorInput,
    limits: &Limits,
    bad: Invalid,
) -> Result<BeamRotor, Invalid> {
    let mut bad = bad;
    match Rotor::parse(input, limits) {
        Ok(Rotor::Beam(b)) if bad.is_empty() => Ok(b),
        Ok(Rotor::Beam(_)) => Err(bad),
        Ok(_) => {
            bad.push(
                "rotor.type",
                "needs a `beam` rotor (a shaft whose supports can be told from it)",
            );
            Err(bad)
        }
        Err(e) => {
            bad.extend(e);
            Err(bad)
        }
    }
}

/// `count` values of a range, `log` spaced or linear; `max` values at most.
fn grid(
    at: &str,
    start: f64,
    stop: f64,
    count: i64,
    log: bool,
    max: usize,
    bad: &mut Invalid,
) -> Option<Vec<f64>> {
    let a = bad.check(&format!("{at}.start"), finite(start));
    let b = bad.check(&format!("{at}.stop"), finite(stop));
    let (a, b) = (a?, b?);
    let mut ok = true;
    if log && a <= 0.0 {
        bad.push(format!("{at}.start"), format!("must be > 0 (got {a})"));
        ok = false;
    } else if a < 0.0 {
        bad.push(format!("{at}.start"), format!("must be >= 0 (got {a})"));
        ok = false;
    }
    if b <= a {
        bad.push(
            format!("{at}.stop"),
            format!("must be > start ({a}) (got {b})"),
        );
        ok = false;
    }
    if count < 2 || count as u64 > max as u64 {
        bad.push(
            format!("{at}.count"),
            format!("must be 2 to {max} (got {count})"),
        );
        ok = false;
    }
    if !ok {
        return None;
    }
    let n = count as usize;
    Some(if log {
        logarithmic(a, b, n)
    } else {
        linear(a, b, n)
    })
}

/// Cost of `solves` dense symmetric or complex solves of the model's size.
fn solve_cost(size: Size, solves: usize, values: u64) -> Cost {
    let s = size.states() as u64;
    let extra = 3 * 16 * s * s;
    Cost::new(size, 1, 1, extra, values).with_work(size.eigen_work() * solves as f64)
}

impl CriticalSpeedMapRequest {
    pub fn parse(&self, limits: &Limits) -> Result<Task, Invalid> {
        let mut bad = Invalid::default();
        let k = &self.stiffness;
        let stiffness = grid(
            "stiffness",
            k.start,
            k.stop,
            k.count,
            true,
            limits.max_speeds,
            &mut bad,
        );
        let modes = self.modes.unwrap_or(4);
        if modes < 1 {
            bad.push("modes", format!("must be >= 1 (got {modes})"));
        }
        // Past 600 coordinates the shaft is held sparse (`map_is_sparse`).
        let rotor = beam(&self.rotor, &limits.held_sparse(), bad)?;
        let dofs = 2 * rotor.nodes();
        if modes as u64 > dofs as u64 {
            return Err(Invalid::one(
                "modes",
                format!("the rotor has {dofs} modes (got {modes})"),
            ));
        }
        let stiffness = stiffness.expect("validated");
        let size = Size {
            assembled: dofs,
            dofs,
            internal: 0,
            problems: 1,
            points: 1,
        };
        let count = stiffness.len();
        let values = (count * (modes as usize + 1)) as u64 + 64;
        let solves = count + 16 * modes as usize;
        let sparse = map_is_sparse(dofs, modes as usize);
        if !sparse && dofs > limits.max_dofs {
            if modes as usize <= MAX_SPARSE_MODES {
                // Dense for its size: the dense limit's own message.
                beam(&self.rotor, limits, Invalid::default())?;
            }
            return Err(Invalid::one(
                "modes",
                format!(
                    "a rotor past {} degrees of freedom (WHIRL_MAX_DOFS) is held sparse for at \
                     most {MAX_SPARSE_MODES} modes (got {modes})",
                    limits.max_dofs
                ),
            ));
        }
        let cost = match sparse {
            false => solve_cost(size, solves, values),
            true => sparse_map_cost(size, modes as usize, solves, values),
        };
        Task {
            output_unit: self.output_unit.unwrap_or_default(),
            warnings: seal_note(&rotor, "the undamped critical speed map"),
            kind: TaskKind::CriticalMap(CriticalMapTask {
                rotor,
                stiffness,
                modes: modes as usize,
            }),
            cost,
        }
        .bounded(limits, "stiffness")
    }
}

/// The critical speed map of a rotor held sparse: per stiffness, a Lanczos run of about
/// `2 modes + 24` vectors (`16` bytes per coordinate each, with `M` times it) on a sparse
/// Cholesky factor (about 2 kB per coordinate), work `n (4 j^2 + 300)` a solve.
fn sparse_map_cost(size: Size, modes: usize, solves: usize, values: u64) -> Cost {
    let n = size.dofs as u64;
    let j = 2 * modes as u64 + 24;
    let response_bytes = values * BYTES_PER_VALUE;
    Cost {
        size,
        peak_bytes: n * (16 * j + 2048) + values * 16 + response_bytes,
        response_bytes,
        work: solves as f64 * n as f64 * (4.0 * (j * j) as f64 + 300.0),
    }
}

/// The line an answer carries when the rotor's seals were left out of it.
fn seal_note(rotor: &BeamRotor, analysis: &str) -> Vec<String> {
    if rotor.has_seals() {
        vec![format!(
            "rotor.seals: left out of {analysis}, as API 684 and ROSS do (seals carry no load \
             and their coefficients are not those of a bearing); they act in every dynamic \
             analysis"
        )]
    } else {
        vec![]
    }
}

/// Standard gravity (ISO 80000-3, CGPM 1901), m/s^2: the static analysis's default.
pub const STANDARD_GRAVITY: f64 = 9.80665;

impl StaticRequest {
    pub fn parse(&self, limits: &Limits) -> Result<Task, Invalid> {
        let mut bad = Invalid::default();
        let g = bad.check(
            "gravity",
            positive(self.gravity.unwrap_or(STANDARD_GRAVITY)),
        );
        let speed = speed_at(&mut bad, "speed", self.speed.unwrap_or_default());
        // Held sparse past 600 unknowns (work linear in the mesh).
        let rotor = beam(&self.rotor, &limits.held_sparse(), bad)?;
        let supports = self.supports.unwrap_or_default();
        if rotor.supports().len() + rotor.general_supports().len() == 0 {
            return Err(Invalid::one("rotor.supports", "the shaft needs supports"));
        }
        let dofs = 2 * rotor.nodes();
        let size = Size {
            assembled: dofs,
            dofs: 2 * dofs,
            internal: 0,
            problems: 1,
            points: 1,
        };
        // Per node: its deflection (6); per element: two stations and the diagram's points
        // (6 values each).
        let elements = rotor.elements().len() as u64;
        let values = 6 * rotor.nodes() as u64 + 6 * (2 + DIAGRAM_POINTS as u64) * elements + 64;
        let cost = match 2 * dofs <= DENSE_UP_TO {
            true => solve_cost(size, 1, values),
            false => sparse_static_cost(size, values),
        };
        Task {
            output_unit: Default::default(),
            warnings: seal_note(&rotor, "the static analysis"),
            kind: TaskKind::Static(StaticTask {
                rotor,
                gravity: g.expect("validated"),
                rigid: supports == StaticSupports::Rigid,
                speed: speed.expect("validated"),
            }),
            cost,
        }
        .bounded(limits, "rotor")
    }
}

/// The static analysis of a rotor held sparse: the assembled shaft, the system of both planes
/// and its factor, a few kilobytes per coordinate at most (a beam couples neighbouring nodes
/// only), and the answer's values. A 20,000-element shaft on cross-coupled bearings (80,004
/// unknowns) peaked at 108 MB more than the idle server against this estimate's 386 MB.
fn sparse_static_cost(size: Size, values: u64) -> Cost {
    let response_bytes = values * BYTES_PER_VALUE;
    Cost {
        size,
        peak_bytes: STATIC_BYTES_PER_DOF * size.dofs as u64 + values * 16 + response_bytes,
        response_bytes,
        work: STATIC_WORK_PER_DOF * size.dofs as f64,
    }
}

/// Heap per real coordinate of a sparse static analysis (its estimate).
pub const STATIC_BYTES_PER_DOF: u64 = 4096;

/// Flops per real coordinate of a sparse static analysis (assembly, ordering, factor, solve).
const STATIC_WORK_PER_DOF: f64 = 2e4;

/// The nodes and shares of the Level I cross-coupling, and API 617's q_A (N/m) from the
/// machine data.
fn placing(
    r: &Level1Request,
    nodes: usize,
    speed: Option<f64>,
    bad: &mut Invalid,
) -> (Vec<(usize, f64)>, Option<f64>) {
    if let Some(m) = &r.machine {
        if m.stages.is_empty() {
            bad.push("machine.stages", "needs at least one stage");
        }
        let mut out = vec![];
        for (i, s) in m.stages.iter().enumerate() {
            let at = format!("machine.stages[{i}]");
            let n = node_index(bad, format!("{at}.node"), s.node, nodes);
            let p = bad.check(&format!("{at}.power"), positive(s.power));
            let d = bad.check(&format!("{at}.diameter"), positive(s.diameter));
            let h = bad.check(&format!("{at}.width"), positive(s.width));
            let rho = bad.check(
                &format!("{at}.density_ratio"),
                positive(s.density_ratio.unwrap_or(1.0)),
            );
            if let (Some(n), Some(p), Some(d), Some(h), Some(rho), Some(w)) =
                (n, p, d, h, rho, speed)
            {
                if w <= 0.0 {
                    bad.push("speed", "q_A needs a speed > 0");
                    continue;
                }
                // Wachel: q_A = B_c T / (D_c H_c) (rho_d / rho_s), the stage torque T = P / Omega:
                // W / (rad/s) = N m, over m^2: N/m. (API 617's 9.55 P / N with P in kW and N in
                // rpm is T in kN m, which over D_c H_c in mm^2 needs a further 1e3 for kN/mm.)
                let qa = B_C * (p / w) / (d * h) * rho;
                out.push((n, qa));
            }
        }
        let total: f64 = out.iter().map(|s| s.1).sum();
        if total > 0.0 {
            let shares = out.iter().map(|&(n, q)| (n, q / total)).collect();
            return (shares, Some(total));
        }
        return (vec![], None);
    }
    let list: Vec<(String, i64)> = match (&r.node, &r.nodes) {
        (Some(n), None) => vec![("node".into(), *n)],
        (None, Some(list)) if !list.is_empty() => list
            .iter()
            .enumerate()
            .map(|(i, &n)| (format!("nodes[{i}]"), n))
            .collect(),
        (None, Some(_)) => {
            bad.push("nodes", "needs at least one node");
            vec![]
        }
        (Some(_), Some(_)) => {
            bad.push("node", "give `node` or `nodes`, not both");
            vec![]
        }
        (None, None) => {
            bad.push("node", "needs `node` or `nodes` (or `machine`)");
            vec![]
        }
    };
    let picked: Vec<usize> = list
        .into_iter()
        .filter_map(|(at, n)| node_index(bad, at, n, nodes))
        .collect();
    let w = 1.0 / picked.len().max(1) as f64;
    (picked.into_iter().map(|n| (n, w)).collect(), None)
}

impl Level1Request {
    pub fn parse(&self, limits: &Limits) -> Result<Task, Invalid> {
        let mut bad = Invalid::default();
        let speed = speed_at(&mut bad, "speed", self.speed);
        let qs = match &self.cross_coupling {
            Some(c) => grid(
                "cross_coupling",
                c.start,
                c.stop,
                c.count,
                false,
                limits.max_speeds,
                &mut bad,
            ),
            None => Some(vec![]),
        };
        // Held sparse, Level I runs on a checked reduction only.
        let reduce = self.modal_reduction.unwrap_or(true);
        let (model, sparse) = Model::parse_held(
            reduce,
            Motion::Lateral,
            &self.rotor,
            &self.damping,
            limits,
            bad,
        )?;
        let mut bad = Invalid::default();
        let (at, qa) = placing(self, model.rotor.node_count(), speed, &mut bad);
        let density = match self.machine.as_ref().and_then(|m| m.mean_gas_density) {
            Some(rho) => bad.check("machine.mean_gas_density", positive(rho)),
            None => None,
        };
        let mut extra = vec![];
        let more = self
            .machine
            .as_ref()
            .and_then(|m| m.additional_cross_coupling.as_ref());
        for (i, c) in more.into_iter().flatten().enumerate() {
            let at = format!("machine.additional_cross_coupling[{i}]");
            let n = node_index(
                &mut bad,
                format!("{at}.node"),
                c.node,
                model.rotor.node_count(),
            );
            let q = bad.check(&format!("{at}.q"), finite(c.q));
            if let (Some(n), Some(q)) = (n, q) {
                extra.push((n, q));
            }
        }
        if !bad.is_empty() {
            return Err(bad);
        }
        let qs = qs.expect("validated");
        let speed = speed.expect("validated");
        let mut size = model.size();
        // The skew supports are isotropic: the coordinates stay as they are.
        size.points = size.points.max(1);
        let solves = qs.len().max(AUTO_COUNT) + 60;
        let model_doubled = model.rotor.doubled();
        let values = 3 * qs.len().max(AUTO_COUNT) as u64 + 32;
        let damper_bytes = model.damper_bytes(limits);
        let task = Task {
            output_unit: self.output_unit.unwrap_or_default(),
            warnings: model.warnings(speed, speed),
            kind: TaskKind::Level1(Level1Task {
                model,
                speed,
                at,
                qs,
                qa,
                density,
                extra,
                reduce,
                sparse,
            }),
            cost: match sparse {
                true => sparse_sweep_cost(size, model_doubled, solves, limits, values)
                    .plus_bytes(damper_bytes),
                false => sweep_cost(size, 1, limits, false, values)
                    .with_work(size.eigen_work() * solves as f64),
            },
        };
        task.whirl_read()?;
        Ok(task)
    }
}

/// The excitation of a frequency response.
fn excitation(v: &Option<Value>, bad: &mut Invalid) -> Option<Excitation> {
    match v {
        None => Some(Excitation::Direction(0.0)),
        Some(Value::Number(n)) => match n.as_f64() {
            Some(t) if t.is_finite() => Some(Excitation::Direction(t)),
            _ => {
                bad.push("input.direction", "must be a finite angle in rad");
                None
            }
        },
        Some(Value::String(s)) if s == "forward" => Some(Excitation::Forward),
        Some(Value::String(s)) if s == "backward" => Some(Excitation::Backward),
        Some(other) => {
            bad.push(
                "input.direction",
                format!("must be an angle in rad, \"forward\" or \"backward\" (got {other})"),
            );
            None
        }
    }
}

impl FrequencyResponseRequest {
    pub fn parse(&self, limits: &Limits) -> Result<Task, Invalid> {
        let mut bad = Invalid::default();
        let speed = speed_at(&mut bad, "speed", self.speed);
        let exc = excitation(&self.input.direction, &mut bad);
        if !self.motion.is_lateral() && !matches!(exc, None | Some(Excitation::Direction(0.0))) {
            bad.push(
                "input.direction",
                "a torsional or axial load acts along the axis: it has no direction",
            );
        }
        // One frequency is a valid question here (a sweep needs two speeds).
        let unit = self.frequencies.unit();
        let freqs = match self.frequencies.list() {
            Some([f]) => {
                let at = match self.frequencies {
                    SpeedsInput::Values(_) => "frequencies.values[0]",
                    _ => "frequencies[0]",
                };
                bad.check(at, positive(*f)).map(|f| vec![unit.to_rad_s(f)])
            }
            _ => match crate::model::speeds::SpeedGrid::parse(&self.frequencies, limits.max_speeds)
            {
                Ok(g) => Some(g.as_slice().to_vec()),
                Err(mut e) => {
                    // The grid's messages name `speeds`: this field is `frequencies`.
                    e.prefix_paths(|p| p.replacen("speeds", "frequencies", 1));
                    bad.extend(e);
                    None
                }
            },
        };
        if let Some(g) = &freqs
            && g[0] <= 0.0
        {
            bad.push(
                "frequencies",
                "must be > 0 (the response to a static load is /v1/static)",
            );
        }
        let (model, sparse) =
            Model::parse_held(true, self.motion, &self.rotor, &self.damping, limits, bad)?;
        let mut bad = Invalid::default();
        let nodes = model.rotor.node_count();
        let input = node_index(&mut bad, "input.node".into(), self.input.node, nodes);
        let output = node_index(&mut bad, "output.node".into(), self.output.node, nodes);
        if !bad.is_empty() {
            return Err(bad);
        }
        let frequencies = freqs.expect("validated");
        let size = model.size();
        let count = frequencies.len() as u64;
        // A train's answer carries each element's amplitude, phase and stress per frequency.
        let elements = if self.motion.is_lateral() {
            0
        } else {
            nodes.saturating_sub(1) as u64
        };
        let values = count * (10 + 3 * elements) + 16;
        let s = size.states() as u64;
        let threads = limits.threads.max(1) as u64;
        let extra = threads * 3 * 16 * s * s + count * 64;
        let work = count as f64 * (s * s * s) as f64 * 3.0;
        let speed = speed.expect("validated");
        let damper_bytes = model.damper_bytes(limits);
        let (lo, hi) = frequencies
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(a, b), w| {
                (a.min(w.abs()), b.max(w.abs()))
            });
        let mut warnings = model.warnings(speed, speed);
        warnings.extend(model.whirl_warnings(lo, hi));
        Task {
            output_unit: self.output_unit.unwrap_or_default(),
            warnings,
            kind: TaskKind::Frequency(FrequencyTask {
                model,
                speed,
                input: (input.expect("validated"), exc.expect("validated")),
                output: output.expect("validated"),
                frequencies,
                reduce: self.modal_reduction.unwrap_or(true),
                sparse,
            }),
            cost: match sparse {
                true => sparse_harmonic_cost(size, limits, count, values).plus_bytes(damper_bytes),
                false => Cost::new(size, 0, 0, extra, values).with_work(work),
            },
        }
        .bounded(limits, "frequencies")
    }
}
