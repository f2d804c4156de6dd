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
/// translation and q, N/m.
pub fn level2(
    system: &RotorSystem,
    damping: &DampingModel,
    speed: f64,
    stages: &Placing,
    qa: f64,
    extra: &Placing,
) -> Result<Vec<(Source, ForwardPole)>, AnalysisError> {
    let mut bare = system.clone();
    bare.supports.retain(|p| !p.support.seal);
    let seals = bare.supports.len() < system.supports.len();
    // Shares times q_A: the absolute cross-coupling of each stage, applied with q = 1.
    let stage_q: Vec<(usize, f64)> = stages.iter().map(|&(d, w)| (d, w * qa)).collect();
    let mut out = vec![(
        Source::Base,
        FirstForward::new(&bare, damping, speed, &[])?.base(),
    )];
    if seals {
        out.push((
            Source::Seals,
            FirstForward::new(system, damping, speed, &[])?.base(),
        ));
    }
    if qa > 0.0 && !stage_q.is_empty() {
        out.push((
            Source::Stages,
            FirstForward::new(&bare, damping, speed, &stage_q)?.at(1.0)?,
        ));
    }
    if !extra.is_empty() {
        out.push((
            Source::Additional,
            FirstForward::new(&bare, damping, speed, extra)?.at(1.0)?,
        ));
    }
    let all: Vec<(usize, f64)> = stage_q.iter().chain(extra).copied().collect();
    let together = if all.is_empty() {
        FirstForward::new(system, damping, speed, &[])?.base()
    } else {
        FirstForward::new(system, damping, speed, &all)?.at(1.0)?
    };
    out.push((Source::All, together));
    Ok(out)
}
