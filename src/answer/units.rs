//! The unit of an answer's speeds and frequencies (the request's `output_unit`): every spin
//! speed, whirl frequency and natural frequency of modal, Campbell, stability, unbalance and
//! frequency response, critical speed map and Level I answers. Decay rates (1/s), amplitudes,
//! phases and ratios are the same in any unit. The analyses compute in rad/s; `execute`
//! rescales their answer, and the plots, which label rad/s and rpm themselves, are drawn from
//! the answer rescaled back to rad/s.

use super::Output;
use crate::model::api::{
    CampbellResponse, CriticalSpeedMapResponse, FrequencyResponseResponse, Level1Response,
    ModalResponse, ReductionInfo, ResponseReductionInfo, SpeedUnit, StabilityResponse,
    UnbalanceResponseResponse,
};

impl Output {
    /// The unit of the answer's speeds and frequencies (rad/s for the analyses without one).
    pub fn unit(&self) -> SpeedUnit {
        match self {
            Output::Modal(o) => o.output_unit,
            Output::Campbell(o) => o.output_unit,
            Output::Stability(o) => o.output_unit,
            Output::Unbalance(o) => o.output_unit,
            Output::CriticalMap(o) => o.output_unit,
            Output::Level1(o) => o.output_unit,
            Output::Frequency(o) => o.output_unit,
            Output::Damping(_) | Output::Time(_) | Output::Static(_) | Output::Report(_) => {
                SpeedUnit::RadPerSecond
            }
        }
    }

    /// The answer with its speeds and frequencies in `to` (and `output_unit` saying so); the
    /// analyses without a unit are left as they are.
    pub fn in_unit(&mut self, to: SpeedUnit) {
        let from = self.unit();
        if from == to {
            return;
        }
        let f = |w: f64| to.from_rad_s(from.to_rad_s(w));
        match self {
            Output::Modal(o) => modal(o, &f, to),
            Output::Campbell(o) => campbell(o, &f, to),
            Output::Stability(o) => stability(o, &f, to),
            Output::Unbalance(o) => unbalance(o, &f, to),
            Output::CriticalMap(o) => map(o, &f, to),
            Output::Level1(o) => level1(o, &f, to),
            Output::Frequency(o) => frequency(o, &f, to),
            Output::Damping(_) | Output::Time(_) | Output::Static(_) | Output::Report(_) => {}
        }
    }

    /// Marks the answer of the paper's nondimensional Jeffcott rotor as such (its plots then
    /// name no physical unit).
    pub fn set_nondimensional(&mut self, on: bool) {
        match self {
            Output::Campbell(o) => o.nondimensional = on,
            Output::Stability(o) => o.nondimensional = on,
            Output::Unbalance(o) => o.nondimensional = on,
            Output::Time(o) => o.nondimensional = on,
            _ => {}
        }
    }

    /// The answer in rad/s, as the plots read it (a copy only when it is in another unit).
    pub fn in_rad_s(&self) -> std::borrow::Cow<'_, Output> {
        if self.unit() == SpeedUnit::RadPerSecond {
            return std::borrow::Cow::Borrowed(self);
        }
        let mut o = self.clone();
        o.in_unit(SpeedUnit::RadPerSecond);
        std::borrow::Cow::Owned(o)
    }
}

type Scale<'a> = &'a dyn Fn(f64) -> f64;

fn all(v: &mut [f64], f: Scale) {
    v.iter_mut().for_each(|x| *x = f(*x));
}

fn some(v: &mut [Option<f64>], f: Scale) {
    v.iter_mut().flatten().for_each(|x| *x = f(*x));
}

fn reduction(r: &mut Option<ReductionInfo>, f: Scale) {
    if let Some(r) = r {
        r.band = f(r.band);
        r.checked_speed = f(r.checked_speed);
    }
}

fn response_reduction(r: &mut Option<ResponseReductionInfo>, f: Scale) {
    if let Some(r) = r {
        r.band = f(r.band);
        all(&mut r.checked, f);
    }
}

fn modal(o: &mut ModalResponse, f: Scale, to: SpeedUnit) {
    o.speed = f(o.speed);
    o.poles
        .iter_mut()
        .for_each(|p| p.frequency = f(p.frequency));
    all(&mut o.natural_frequencies, f);
    o.max_frequency = o.max_frequency.map(f);
    o.output_unit = to;
}

fn campbell(o: &mut CampbellResponse, f: Scale, to: SpeedUnit) {
    all(&mut o.speeds, f);
    for b in &mut o.branches {
        some(&mut b.frequency, f);
    }
    for b in &mut o.overdamped {
        some(&mut b.frequency, f);
    }
    all(&mut o.critical_speeds, f);
    o.criticals.iter_mut().for_each(|c| c.speed = f(c.speed));
    o.ambiguities.iter_mut().for_each(|a| a.speed = f(a.speed));
    o.threshold = o.threshold.map(f);
    reduction(&mut o.reduction, f);
    if let Some(i) = &mut o.interference {
        for e in &mut i.excitations {
            e.frequency = e.frequency.map(f);
        }
        all(&mut i.operating_range, f);
        for c in &mut i.criticals {
            c.speed = c.speed.map(f);
            c.frequency = f(c.frequency);
        }
        i.unit = to;
    }
    o.output_unit = to;
}

fn stability(o: &mut StabilityResponse, f: Scale, to: SpeedUnit) {
    o.threshold = o.threshold.map(f);
    o.frequency = o.frequency.map(f);
    all(&mut o.range, f);
    all(&mut o.speeds, f);
    o.max_frequency = o.max_frequency.map(f);
    reduction(&mut o.reduction, f);
    o.output_unit = to;
}

fn unbalance(o: &mut UnbalanceResponseResponse, f: Scale, to: SpeedUnit) {
    all(&mut o.speeds, f);
    for p in o.nodes.iter_mut().flat_map(|n| &mut n.peaks) {
        p.speed = f(p.speed);
        if let Some(h) = &mut p.half_power {
            all(h, f);
        }
    }
    response_reduction(&mut o.reduction, f);
    o.output_unit = to;
}

fn map(o: &mut CriticalSpeedMapResponse, f: Scale, to: SpeedUnit) {
    o.frequencies.iter_mut().for_each(|m| all(m, f));
    o.intersections
        .iter_mut()
        .for_each(|i| i.frequency = f(i.frequency));
    o.output_unit = to;
}

fn level1(o: &mut Level1Response, f: Scale, to: SpeedUnit) {
    o.speed = f(o.speed);
    some(&mut o.frequency, f);
    o.frequency_0 = o.frequency_0.map(f);
    o.rigid_critical_speed = o.rigid_critical_speed.map(f);
    if let Some(l2) = &mut o.level2 {
        for s in &mut l2.sources {
            s.frequency = s.frequency.map(f);
        }
    }
    o.output_unit = to;
}

fn frequency(o: &mut FrequencyResponseResponse, f: Scale, to: SpeedUnit) {
    o.speed = f(o.speed);
    all(&mut o.frequencies, f);
    response_reduction(&mut o.reduction, f);
    o.output_unit = to;
}
