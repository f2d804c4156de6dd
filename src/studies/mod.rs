//! Studies: one job request over many values of its parameters. A [`Study`] is the request
//! checked (pointers that name values of the input, a design its parameters fit, a sample
//! count within the limit); [`Study::plan`] gives every sample's parameter values
//! ([`design`]: grid, Monte Carlo, Latin hypercube, by inversion of [`dist`]'s
//! distributions), [`Study::input`] the input a sample runs; [`summary`] reduces the samples'
//! outputs to statistics and rank correlations, [`table`] to CSV. No HTTP and no store here:
//! `jobs` queues the samples, `service` answers.

pub mod design;
pub mod dist;
pub mod pointer;
pub mod summary;
pub mod table;

use serde_json::Value;

use crate::model::Invalid;
use crate::model::api::{
    AnalysisName, Distribution, DistributionKind, StudyDesign, StudyParameter, StudyRequest,
};
use dist::{Dist, Shape};

/// Most parameters and outputs of a study.
pub const MAX_POINTERS: usize = 32;

/// How a parameter varies.
#[derive(Debug, Clone)]
pub enum Values {
    List(Vec<Value>),
    Random(Dist),
}

#[derive(Debug, Clone)]
pub struct Parameter {
    pub pointer: String,
    pub values: Values,
}

/// A checked study request.
#[derive(Debug, Clone)]
pub struct Study {
    pub analysis: AnalysisName,
    pub input: Value,
    pub parameters: Vec<Parameter>,
    pub design: StudyDesign,
    pub samples: usize,
    pub seed: u64,
    pub outputs: Vec<String>,
}

impl Study {
    /// Checks `req` (every problem named by its field); `seed` when the request has none.
    pub fn parse(req: &StudyRequest, max_samples: usize, seed: u64) -> Result<Study, Invalid> {
        let mut bad = Invalid::default();
        if !req.input.is_object() {
            bad.push(
                "input",
                "must be a JSON object: the body of the analysis's endpoint",
            );
        }
        if req.parameters.is_empty() || req.parameters.len() > MAX_POINTERS {
            bad.push("parameters", format!("1 to {MAX_POINTERS} parameters"));
        }
        if req.outputs.is_empty() || req.outputs.len() > MAX_POINTERS {
            bad.push("outputs", format!("1 to {MAX_POINTERS} output pointers"));
        }
        let random = req.design != StudyDesign::Grid;
        let mut parameters = vec![];
        for (i, p) in req.parameters.iter().enumerate() {
            let here = format!("parameters[{i}]");
            if let Some(param) = parameter(p, &req.input, random, &here, &mut bad) {
                if let Some(j) = parameters
                    .iter()
                    .position(|q: &Parameter| q.pointer == param.pointer)
                {
                    bad.push(
                        format!("{here}.pointer"),
                        format!("the same as parameters[{j}]"),
                    );
                }
                parameters.push(param);
            }
        }
        for (i, o) in req.outputs.iter().enumerate() {
            bad.check(&format!("outputs[{i}]"), pointer::check(o));
        }
        let samples = count(req, &parameters, max_samples, &mut bad);
        bad.into_result(|| Study {
            analysis: req.analysis,
            input: req.input.clone(),
            parameters,
            design: req.design,
            samples,
            seed: req.seed.unwrap_or(seed),
            outputs: req.outputs.clone(),
        })
    }

    /// Every sample's parameter values, in the order of the parameters.
    pub fn plan(&self) -> Vec<Vec<Value>> {
        match self.design {
            StudyDesign::Grid => design::grid(
                &self
                    .parameters
                    .iter()
                    .map(|p| match &p.values {
                        Values::List(v) => v.clone(),
                        Values::Random(_) => vec![],
                    })
                    .collect::<Vec<_>>(),
            ),
            d => {
                let dists: Vec<Dist> = self
                    .parameters
                    .iter()
                    .filter_map(|p| match &p.values {
                        Values::Random(d) => Some(*d),
                        Values::List(_) => None,
                    })
                    .collect();
                let latin = d == StudyDesign::LatinHypercube;
                design::draws(&dists, self.samples, self.seed, latin)
            }
        }
    }

    /// The input of the sample with these parameter values.
    pub fn input(&self, values: &[Value]) -> Value {
        let mut input = self.input.clone();
        for (p, v) in self.parameters.iter().zip(values) {
            pointer::set(&mut input, &p.pointer, v.clone());
        }
        input
    }

    pub fn pointers(&self) -> Vec<String> {
        self.parameters.iter().map(|p| p.pointer.clone()).collect()
    }
}

/// A parameter checked against the input and the design (`None` after a problem).
fn parameter(
    p: &StudyParameter,
    input: &Value,
    random: bool,
    here: &str,
    bad: &mut Invalid,
) -> Option<Parameter> {
    let at = format!("{here}.pointer");
    if let Err(e) = pointer::check(&p.pointer) {
        bad.push(at, e);
        return None;
    }
    if p.pointer.is_empty() {
        bad.push(
            at,
            "names the whole input: name a value in it, e.g. \"/rotor/mass\"",
        );
        return None;
    }
    if pointer::get(input, &p.pointer).is_none() {
        bad.push(
            at,
            format!(
                "{:?} names nothing in `input`: a parameter replaces a value given there",
                p.pointer
            ),
        );
        return None;
    }
    let values = match (&p.values, &p.distribution, random) {
        (Some(v), None, false) if !v.is_empty() => Values::List(v.clone()),
        (Some(_), None, false) => {
            bad.push(format!("{here}.values"), "at least one value");
            return None;
        }
        (None, Some(d), true) => {
            let dist =
                distribution(d).map_err(|(f, m)| bad.push(format!("{here}.distribution.{f}"), m));
            Values::Random(dist.ok()?)
        }
        (_, _, false) => {
            bad.push(
                here,
                "a grid parameter has `values` (and no `distribution`)",
            );
            return None;
        }
        (_, _, true) => {
            bad.push(
                here,
                "a parameter of a random design has a `distribution` (and no `values`)",
            );
            return None;
        }
    };
    Some(Parameter {
        pointer: p.pointer.clone(),
        values,
    })
}

/// A distribution checked: its own fields given, finite, in range; `(field, problem)`.
fn distribution(d: &Distribution) -> Result<Dist, (&'static str, String)> {
    let need = |v: Option<f64>, f: &'static str| -> Result<f64, (&'static str, String)> {
        match v {
            Some(x) if x.is_finite() => Ok(x),
            Some(_) => Err((f, "must be finite".into())),
            None => Err((
                f,
                format!("required for a {:?} distribution", d.kind).to_lowercase(),
            )),
        }
    };
    let unused: &[(&'static str, Option<f64>)] = match d.kind {
        DistributionKind::Uniform => &[
            ("mean", d.mean),
            ("std", d.std),
            ("mu", d.mu),
            ("sigma", d.sigma),
        ],
        DistributionKind::Normal => &[
            ("low", d.low),
            ("high", d.high),
            ("mu", d.mu),
            ("sigma", d.sigma),
        ],
        DistributionKind::Lognormal => &[
            ("low", d.low),
            ("high", d.high),
            ("mean", d.mean),
            ("std", d.std),
        ],
    };
    if let Some((f, _)) = unused.iter().find(|(_, v)| v.is_some()) {
        return Err((f, "not a parameter of this distribution's type".into()));
    }
    let shape = match d.kind {
        DistributionKind::Uniform => {
            let (low, high) = (need(d.low, "low")?, need(d.high, "high")?);
            if high <= low {
                return Err(("high", format!("must be above low ({low})")));
            }
            Shape::Uniform { low, high }
        }
        DistributionKind::Normal => {
            let (mean, std) = (need(d.mean, "mean")?, need(d.std, "std")?);
            if std <= 0.0 {
                return Err(("std", "must be > 0".into()));
            }
            Shape::Normal { mean, std }
        }
        DistributionKind::Lognormal => {
            let (mu, sigma) = (need(d.mu, "mu")?, need(d.sigma, "sigma")?);
            if sigma <= 0.0 {
                return Err(("sigma", "must be > 0".into()));
            }
            Shape::Lognormal { mu, sigma }
        }
    };
    for (f, v) in [("min", d.min), ("max", d.max)] {
        if v.is_some_and(|x| !x.is_finite()) {
            return Err((f, "must be finite".into()));
        }
    }
    if let (Some(lo), Some(hi)) = (d.min, d.max)
        && hi <= lo
    {
        return Err(("max", format!("must be above min ({lo})")));
    }
    Dist::new(shape, d.min, d.max).map_err(|m| ("min", m))
}

/// The number of samples, within `max`.
fn count(req: &StudyRequest, params: &[Parameter], max: usize, bad: &mut Invalid) -> usize {
    let limit = format!("at most {max} samples (WHIRL_MAX_STUDY_SAMPLES)");
    if req.design == StudyDesign::Grid {
        let product = params.iter().try_fold(1usize, |n, p| match &p.values {
            Values::List(v) => n.checked_mul(v.len()),
            Values::Random(_) => Some(n),
        });
        match (product, req.samples) {
            (Some(n), _) if n > max => {
                bad.push("parameters", format!("the grid has {n} samples: {limit}"))
            }
            (None, _) => bad.push("parameters", format!("the grid is too large: {limit}")),
            (Some(n), Some(s)) if s != n as u64 => bad.push(
                "samples",
                format!(
                    "{s}, but the grid has {n} (the product of the lists' lengths); leave it out"
                ),
            ),
            (Some(n), _) => return n,
        }
        return 0;
    }
    match req.samples {
        Some(s) if s >= 1 && s <= max as u64 => s as usize,
        Some(s) => {
            bad.push(
                "samples",
                format!("{s}: from 1 to {max} (WHIRL_MAX_STUDY_SAMPLES)"),
            );
            0
        }
        None => {
            bad.push(
                "samples",
                "required for a random design: how many samples to draw",
            );
            0
        }
    }
}
