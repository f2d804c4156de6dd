//! The report: the audit's analyses planned as tasks, run one after the other.

use super::audit::{RPM, beam};
use super::loads::node_index;
use super::{Task, TaskKind};
use crate::model::api::{
    BearingSetInput, CriticalSpeedMapRequest, DampingInput, EquivalentInput, Level1Request,
    LogRange, NoOptions, NonviscousInput, ReportRequest, RotorInput, SpeedRange, SpeedsInput,
    StaticRequest, StaticSupports, SteadyUnbalanceInput, SweepRequest, UnbalanceResponseRequest,
};
use crate::model::error::Invalid;
use crate::model::error::positive;
use crate::model::limits::{Cost, Limits};
use crate::model::rotor::BeamRotor;
use crate::model::speeds::operating_range;

/// The tasks a report runs.
#[derive(Debug, Clone)]
pub struct ReportPlan {
    /// The rotor as given (the report shows it).
    pub rotor: RotorInput,
    pub range: (f64, f64),
    pub map: Task,
    pub statics: Task,
    /// Under the request's damping model.
    pub campbell: Task,
    pub unbalance: Task,
    pub unbalances: Vec<SteadyUnbalanceInput>,
    /// Per compared model: its name, Campbell, Level I and unbalance tasks.
    pub models: Vec<ModelPlan>,
    /// Close-clearance locations `(node, minimum diametral clearance m)`.
    pub clearances: Vec<(usize, f64)>,
    /// SHA-256 (hex) of the request written again as compact JSON.
    pub input_sha256: String,
    /// The same audit on each bearing set: its name and plan.
    pub sets: Vec<(String, ReportPlan)>,
    /// The torsional section (the report's own, not a bearing set's).
    pub torsion: Option<super::TorsionPlan>,
}

impl ReportPlan {
    /// Every task, in the order the report runs them.
    pub fn tasks(&self) -> Vec<&Task> {
        let mut all = vec![&self.map, &self.statics, &self.campbell, &self.unbalance];
        for m in &self.models {
            all.extend([&m.campbell, &m.level1, &m.unbalance]);
        }
        all.extend(self.torsion.iter().flat_map(|t| t.tasks()));
        all
    }

    /// The tasks that run (a model's parts equal to the report's are not run twice), in the
    /// order of the report's parts.
    pub fn run_tasks(&self) -> Vec<&Task> {
        let mut all = vec![&self.map, &self.statics, &self.campbell, &self.unbalance];
        for m in &self.models {
            if m.primary {
                all.push(&m.level1);
            } else {
                all.extend([&m.campbell, &m.level1, &m.unbalance]);
            }
        }
        all.extend(self.torsion.iter().flat_map(|t| t.tasks()));
        all
    }
}

#[derive(Debug, Clone)]
pub struct ModelPlan {
    pub name: &'static str,
    /// The request's own model: its Campbell and unbalance are the report's (run once).
    pub primary: bool,
    pub campbell: Task,
    pub level1: Task,
    pub unbalance: Task,
}

impl ReportRequest {
    /// The models compared: the request's, or H, E, NVD (with the request's options where it
    /// is one of them) and viscous; on supports over whirl frequency (`whirl`), H and viscous,
    /// the models whose poles and responses read them in the frequency domain.
    fn models(&self, whirl: bool) -> Vec<DampingInput> {
        if let Some(m) = &self.models {
            return m.clone();
        }
        if whirl {
            return vec![
                DampingInput::Hysteretic(NoOptions {}),
                DampingInput::Viscous(NoOptions {}),
            ];
        }
        let nv = match &self.damping {
            DampingInput::Nonviscous(n) => n.clone(),
            _ => NonviscousInput::default(),
        };
        let eq = match &self.damping {
            DampingInput::Equivalent(e) => e.clone(),
            _ => EquivalentInput::default(),
        };
        vec![
            DampingInput::Hysteretic(NoOptions {}),
            DampingInput::Equivalent(eq),
            DampingInput::Nonviscous(nv),
            DampingInput::Viscous(NoOptions {}),
        ]
    }

    pub fn parse(&self, limits: &Limits) -> Result<Task, Invalid> {
        let mut bad = Invalid::default();
        let range = operating_range(&self.operating_range, "operating_range", &mut bad);
        // A rotor past the dense limits is held sparse by every part of the report (each part's
        // parse decides), under every damping model.
        let rotor = beam(&self.rotor, &limits.held_sparse(), bad)?;
        let (lo, hi) = range.expect("validated");
        let speeds = self
            .speeds
            .clone()
            .unwrap_or(SpeedsInput::Range(SpeedRange {
                start: 0.0,
                stop: SWEEP_OVER_MCS * hi,
                count: 121,
                unit: None,
            }));
        // API 684's unbalance: 6350 W / N g mm at the heaviest disk (or mid-shaft).
        let unbalances = self.unbalances.clone().unwrap_or_else(|| {
            let node = rotor
                .disks()
                .iter()
                .max_by(|a, b| a.mass.total_cmp(&b.mass))
                .map_or(rotor.shaft_nodes() / 2, |d| d.node);
            let w_kg = rotor_mass(&rotor);
            let u = 6350.0 * w_kg / (hi * RPM) * 1e-6;
            vec![SteadyUnbalanceInput {
                node: node as i64,
                amount: u,
                phase: 0.0,
            }]
        });
        let nodes = self.nodes.clone().unwrap_or_else(|| {
            let mut n: Vec<i64> = unbalances.iter().map(|u| u.node).collect();
            n.extend(rotor.supports().iter().map(|s| s.node as i64));
            n.extend(rotor.general_supports().iter().map(|s| s.node as i64));
            n.sort_unstable();
            n.dedup();
            n
        });
        let cc_nodes = self
            .cross_coupling_nodes
            .clone()
            .unwrap_or_else(|| vec![unbalances.first().map_or(0, |u| u.node)]);
        let max_frequency = self
            .max_frequency
            .or(Some((1.5 * SWEEP_OVER_MCS * hi).into()));
        let mut bad = Invalid::default();
        let mut clearances = vec![];
        for (i, c) in self.clearances.iter().flatten().enumerate() {
            let at = format!("clearances[{i}]");
            let node = node_index(&mut bad, format!("{at}.node"), c.node, rotor.nodes());
            let d = bad.check(&format!("{at}.diametral"), positive(c.diametral));
            if let (Some(n), Some(d)) = (node, d) {
                clearances.push((n, d));
            }
        }
        bad.into_result(|| ())?;
        let map = CriticalSpeedMapRequest {
            rotor: self.rotor.clone(),
            stiffness: self.stiffness.clone().unwrap_or(LogRange {
                start: 1e5,
                stop: 1e10,
                count: 31,
            }),
            modes: Some(4),
            output_unit: None,
        }
        .parse(limits)?;
        let statics = StaticRequest {
            rotor: self.rotor.clone(),
            gravity: None,
            supports: Some(StaticSupports::Elastic),
            speed: Some(hi.into()),
        }
        .parse(limits)?;
        let campbell_for = |damping: &DampingInput| {
            SweepRequest {
                rotor: self.rotor.clone(),
                damping: damping.clone(),
                speeds: speeds.clone(),
                max_frequency,
                modes: None,
                modal_reduction: None,
                output_unit: None,
                motion: Default::default(),
                interference: None,
            }
            .parse_campbell(limits)
        };
        // A finer grid for the response: its peaks are a few rad/s wide.
        let response_speeds = self
            .speeds
            .clone()
            .unwrap_or(SpeedsInput::Range(SpeedRange {
                start: 0.0,
                stop: SWEEP_OVER_MCS * hi,
                count: 481,
                unit: None,
            }));
        let unbalance_for = |damping: &DampingInput| {
            UnbalanceResponseRequest {
                rotor: self.rotor.clone(),
                damping: damping.clone(),
                speeds: response_speeds.clone(),
                unbalances: unbalances.clone(),
                nodes: Some(nodes.clone()),
                operating_range: Some(self.operating_range),
                modal_reduction: None,
                output_unit: None,
            }
            .parse(limits)
        };
        let campbell = campbell_for(&self.damping)?;
        let unbalance = unbalance_for(&self.damping)?;
        let mut models = vec![];
        let whirl = rotor
            .general_supports()
            .iter()
            .any(|g| g.frequency_dependent());
        for (i, d) in self.models(whirl).iter().enumerate() {
            let level1 = Level1Request {
                rotor: self.rotor.clone(),
                damping: d.clone(),
                speed: hi.into(),
                node: None,
                nodes: if self.machine.is_some() {
                    None
                } else {
                    Some(cc_nodes.clone())
                },
                cross_coupling: self.cross_coupling.clone(),
                machine: self.machine.clone(),
                modal_reduction: None,
                output_unit: None,
            }
            .parse(limits)
            .map_err(|mut e| {
                e.prefix_paths(|p| match p.strip_prefix("damping") {
                    Some(rest) => format!("models[{i}]{rest}"),
                    None => p.to_string(),
                });
                e
            })?;
            let name = level1.model().map_or("", |m| m.damping.name());
            let same = serde_json::to_value(d).ok() == serde_json::to_value(&self.damping).ok();
            models.push(ModelPlan {
                name,
                primary: same,
                campbell: campbell_for(d)?,
                unbalance: unbalance_for(d)?,
                level1,
            });
        }
        let plan = ReportPlan {
            rotor: self.rotor.clone(),
            range: (lo, hi),
            map,
            statics,
            campbell,
            unbalance,
            unbalances,
            models,
            clearances,
            input_sha256: sha256_hex(&serde_json::to_vec(self).unwrap_or_default()),
            sets: vec![],
            torsion: match &self.torsion {
                Some(t) => Some(self.torsion_plan(t, &speeds, (lo, hi), limits)?),
                None => None,
            },
        };
        let mut cost = combined(&plan.run_tasks());
        let mut plan = plan;
        for (i, set) in self.cases.iter().flatten().enumerate() {
            let (sub, c) = self.bearing_set(i, set, limits)?;
            cost.work += c.work;
            cost.response_bytes += c.response_bytes;
            cost.peak_bytes = cost.peak_bytes.max(c.peak_bytes) + c.response_bytes;
            plan.sets.push((set.name.clone(), sub));
        }
        // The unbalance cases, one response each (their nodes are known only when run).
        for _ in 0..MAX_CASES {
            cost.work += plan.unbalance.cost.work;
            cost.response_bytes += plan.unbalance.cost.response_bytes;
            cost.peak_bytes += plan.unbalance.cost.response_bytes;
        }
        Task {
            output_unit: Default::default(),
            warnings: plan.campbell.warnings.clone(),
            kind: TaskKind::Report(Box::new(plan)),
            cost,
        }
        .bounded(limits, "speeds")
    }
}

/// The report runs at most this many unbalance cases (the lowest forward critical speeds);
/// API 684 needs the modes in the operating range and up to the margin above it, rarely more
/// than three.
pub const MAX_CASES: usize = 4;

/// The default sweeps reach 1.3 x the maximum continuous speed: API 684's separation margin
/// above it reaches 26%.
pub const SWEEP_OVER_MCS: f64 = 1.3;

impl ReportRequest {
    /// The plan of the same report on bearing set `i`: the rotor's supports (and seals) those of
    /// the set; errors under `cases[i]`.
    fn bearing_set(
        &self,
        i: usize,
        set: &BearingSetInput,
        limits: &Limits,
    ) -> Result<(ReportPlan, Cost), Invalid> {
        let mut rotor = self.rotor.clone();
        let RotorInput::Beam(b) = &mut rotor else {
            return Err(Invalid::one(
                format!("cases[{i}]"),
                "bearing sets need a beam rotor",
            ));
        };
        b.supports = set.supports.clone();
        if let Some(s) = &set.seals {
            b.seals = s.clone();
        }
        let sub = ReportRequest {
            rotor,
            cases: None,
            torsion: None,
            ..self.clone()
        };
        let task = sub.parse(limits).map_err(|mut e| {
            e.prefix_paths(|p| {
                for part in ["supports", "seals"] {
                    if let Some(rest) = p.strip_prefix(&format!("rotor.{part}")) {
                        return format!("cases[{i}].{part}{rest}");
                    }
                }
                format!("cases[{i}]: {p}")
            });
            e
        })?;
        match task.kind {
            TaskKind::Report(plan) => Ok((*plan, task.cost)),
            _ => Err(Invalid::one(format!("cases[{i}]"), "not a report")),
        }
    }
}

/// Lower-case hex of the SHA-256 of `bytes`.
fn sha256_hex(bytes: &[u8]) -> String {
    use sha2::Digest;
    sha2::Sha256::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// Mass of shaft (sleeves included) and disks, kg.
fn rotor_mass(rotor: &BeamRotor) -> f64 {
    rotor.shaft_mass() + rotor.disks().iter().map(|d| d.mass).sum::<f64>()
}

/// Tasks run two at a time (`analysis::run`'s report lanes): the two largest heaps, the sum
/// of the work and the answers.
fn combined(tasks: &[&Task]) -> Cost {
    let mut c = tasks[0].cost;
    let mut second = 0;
    for t in &tasks[1..] {
        if t.cost.peak_bytes > c.peak_bytes {
            second = c.peak_bytes;
            c.size = t.cost.size;
            c.peak_bytes = t.cost.peak_bytes;
        } else {
            second = second.max(t.cost.peak_bytes);
        }
        c.response_bytes += t.cost.response_bytes;
        c.work += t.cost.work;
    }
    c.peak_bytes += second + c.response_bytes;
    c
}
