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
use crate::analysis::large;
use crate::damping::dampers::ModalDampers;
use crate::model::damping::DampingModel;
use crate::system::RotorSystem;

/// The box a rotor held sparse is solved in, times its lowest undamped natural frequency at
/// rest: the first forward mode at speed, gyroscopically stiffened and moved by the
/// cross-coupling, stays well inside it, and the box holds few poles (each found exactly).
pub const HELD_BOX: f64 = 3.0;

/// The box of a rotor held sparse: [`HELD_BOX`] times its lowest undamped natural frequency at
/// rest.
pub fn held_box(system: &RotorSystem) -> Result<f64, AnalysisError> {
    Ok(HELD_BOX * large::lowest(system, 1, |_| 0.0)?.omega[0])
}

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
/// translation and q, N/m. A rotor `held` sparse (past 600 coordinates) is solved through
/// sparse factors, each configuration's candidates its full model's poles in a box of [`HELD_BOX`] times its lowest undamped natural frequency.
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
        true => Some(held_box(system)?),
        false => None,
    };
    let mut bare = system.clone();
    bare.supports.retain(|p| !p.support.seal);
    let seals = bare.supports.len() < system.supports.len();
    // The equivalent and nonviscous models' dampers, once with the seals and once without
    // (the cross-coupling changes none).
    let dampers_of = |s: &RotorSystem| match bound {
        Some(b) => large::dampers(s, damping, b),
        None => Ok(None),
    };
    let bare_dampers = dampers_of(&bare)?;
    let sealed_dampers = match seals {
        true => dampers_of(system)?,
        false => None,
    };
    let bare_d = bare_dampers.as_ref();
    let all_d = sealed_dampers.as_ref().or(bare_d);
    fn follow<'a>(
        s: &'a RotorSystem,
        damping: &'a DampingModel,
        speed: f64,
        at: &Placing,
        held: Option<(f64, Option<&'a ModalDampers>)>,
    ) -> Result<FirstForward<'a>, AnalysisError> {
        match held {
            Some((b, d)) => FirstForward::held(s, damping, speed, at, b, d),
            None => FirstForward::new(s, damping, speed, at),
        }
    }
    let bare_first = |at| follow(&bare, damping, speed, at, bound.map(|b| (b, bare_d)));
    let first = |at| follow(system, damping, speed, at, bound.map(|b| (b, all_d)));
    // Shares times q_A: the absolute cross-coupling of each stage, applied with q = 1.
    let stage_q: Vec<(usize, f64)> = stages.iter().map(|&(d, w)| (d, w * qa)).collect();
    let mut out = vec![(Source::Base, bare_first(&[])?.base())];
    if seals {
        out.push((Source::Seals, first(&[])?.base()));
    }
    if qa > 0.0 && !stage_q.is_empty() {
        out.push((Source::Stages, bare_first(&stage_q)?.at(1.0)?));
    }
    if !extra.is_empty() {
        out.push((Source::Additional, bare_first(extra)?.at(1.0)?));
    }
    let all: Vec<(usize, f64)> = stage_q.iter().chain(extra).copied().collect();
    let together = if all.is_empty() {
        first(&[])?.base()
    } else {
        first(&all)?.at(1.0)?
    };
    out.push((Source::All, together));
    Ok(out)
}
