//! API 617's Level II stability analysis: the first forward mode's log decrement at the
//! maximum continuous speed on the bearings alone, then with each destabilising source added
//! alone (the seals, the stages' anticipated cross-coupling q_A, further cross-coupled
//! stiffness), then with all of them together. Every result must keep a log decrement of at
//! least 0.1 (API 617).
//!
//! Each configuration follows its own first forward mode ([`FirstForward`]): found without
//! cross-coupling on that system (with or without its seals), then followed by shape as the
//! configuration's cross-coupling is applied at full size.

use super::level1::{FirstForward, ForwardPole, Placing};
use crate::analysis::AnalysisError;
use crate::model::damping::DampingModel;
use crate::system::RotorSystem;

/// The box a rotor held sparse is solved in, times its lowest undamped natural frequency at
/// rest: the first forward mode at speed, gyroscopically stiffened and moved by the
/// cross-coupling, stays well inside it, and the box holds few poles (each found exactly).
pub const HELD_BOX: f64 = 3.0;

/// A destabilising source of Level II, or their absence, or all of them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Source {
    /// The bearings alone (no seals, no cross-coupling).
    Base,
    /// The seals (`rotor.seals`) alone.
    Seals,
    /// The stages' anticipated cross-coupling q_A alone.
    Stages,
    /// The further cross-coupled stiffness alone.
    Additional,
    /// Everything together.
    All,
}

impl Source {
    pub fn name(self) -> &'static str {
        match self {
            Source::Base => "bearings alone",
            Source::Seals => "seals",
            Source::Stages => "stages' q_A",
            Source::Additional => "additional cross-coupling",
            Source::All => "all together",
        }
    }
}

/// Level II at `speed`: the first forward mode under each configuration that applies. `stages`
/// holds each stage's translation and share of `qa`; `extra` each further cross-coupling's
/// translation and q, N/m. A rotor `held` sparse (the viscous and hysteretic models past 600
/// coordinates) is solved through sparse factors, each configuration's candidates its full
/// model's poles in a box of [`HELD_BOX`] times its lowest undamped natural frequency.
pub fn level2(
    system: &RotorSystem,
    damping: &DampingModel,
    speed: f64,
    stages: &Placing,
    qa: f64,
    extra: &Placing,
    held: bool,
) -> Result<Vec<(Source, ForwardPole)>, AnalysisError> {
    let bound = match held {
        true => {
            let basis = crate::analysis::large::lowest(system, 1, |_| 0.0)?;
            Some(HELD_BOX * basis.omega[0])
        }
        false => None,
    };
    fn follow<'a>(
        s: &'a RotorSystem,
        damping: &'a DampingModel,
        speed: f64,
        at: &Placing,
        bound: Option<f64>,
    ) -> Result<FirstForward<'a>, AnalysisError> {
        match bound {
            Some(b) => FirstForward::held(s, damping, speed, at, b),
            None => FirstForward::new(s, damping, speed, at),
        }
    }
    let first = |s, at| follow(s, damping, speed, at, bound);
    let mut bare = system.clone();
    bare.supports.retain(|p| !p.support.seal);
    let seals = bare.supports.len() < system.supports.len();
    // Shares times q_A: the absolute cross-coupling of each stage, applied with q = 1.
    let stage_q: Vec<(usize, f64)> = stages.iter().map(|&(d, w)| (d, w * qa)).collect();
    let mut out = vec![(Source::Base, first(&bare, &[])?.base())];
    if seals {
        out.push((Source::Seals, first(system, &[])?.base()));
    }
    if qa > 0.0 && !stage_q.is_empty() {
        out.push((Source::Stages, first(&bare, &stage_q)?.at(1.0)?));
    }
    if !extra.is_empty() {
        out.push((Source::Additional, first(&bare, extra)?.at(1.0)?));
    }
    let all: Vec<(usize, f64)> = stage_q.iter().chain(extra).copied().collect();
    let together = if all.is_empty() {
        first(system, &[])?.base()
    } else {
        first(system, &all)?.at(1.0)?
    };
    out.push((Source::All, together));
    Ok(out)
}
