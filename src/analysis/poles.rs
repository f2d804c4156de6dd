//! Poles of a damped model at one spin speed, classified.
//!
//! A model with `n` complex degrees of freedom has exactly `2n` rotor poles; the nonviscous
//! model adds one internal pole per branch. Internal poles are told apart by where their
//! elastic energy lies (in the branch springs, not in the rotor), which does not depend on the
//! units of the internal coordinates. Rotor poles whirl `forward` (`omega >= 0`) or `backward`.
//!
//! In doubled coordinates `(r, conj r)` every mode appears twice, as `s` with a shape `(a, b)`
//! and as `conj s` with `(conj b, conj a)` (MODEL.md section 8). Each is reported once: the
//! member whose `r` part `a` is the larger (for a planar mode, where they are equal, the one
//! with `omega >= 0`). A node's motion is then `a e^{st} + conj(b) e^{conj(s) t}`: an ellipse
//! whose forward and backward circular parts are `|a|` and `|b|` (for `omega >= 0`; swapped
//! otherwise), and the pole's whirl ratio is `(F - B) / (F + B)` over the translations: +1
//! circular forward, -1 circular backward, 0 planar.

use crate::damping::state::StateModel;
use crate::damping::{DampedModel, ModelKind};
use crate::linalg::{self, LinalgError, c64};
use crate::system::Layout;

/// Direction of whirl of a pole.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Whirl {
    Forward,
    Backward,
    Internal,
}

/// A pole `s` and its mode shape on the physical coordinates (unit norm; `(a, b)` in doubled
/// coordinates).
#[derive(Debug, Clone)]
pub struct Pole {
    pub s: c64,
    pub whirl: Whirl,
    pub shape: Vec<c64>,
    /// `(F - B) / (F + B)` of the forward and backward circular parts (module docs).
    pub whirl_ratio: f64,
}

impl Pole {
    pub fn decay_rate(&self) -> f64 {
        self.s.re
    }
    pub fn frequency(&self) -> f64 {
        self.s.im
    }
    /// `-sigma / |s|` (0 for a pole at the origin).
    pub fn damping_ratio(&self) -> f64 {
        damping_ratio(self.s)
    }
    /// `-2 pi sigma / |omega|`, `None` for a pole that does not oscillate
    /// ([`oscillates`](Self::oscillates)).
    pub fn log_decrement(&self) -> Option<f64> {
        log_decrement(self.s)
    }

    /// Whether the pole oscillates: `|omega| > NON_OSCILLATING |s|`.
    pub fn oscillates(&self) -> bool {
        oscillates(self.s)
    }

    /// The other member of a mirror pair in doubled coordinates: `conj s` with the shape
    /// `(conj b, conj a)` (module docs); the whirl ratio is that of the mode, the same.
    pub fn mirror(&self) -> Pole {
        let s = self.s.conj();
        Pole {
            s,
            whirl: if s.im >= 0.0 {
                Whirl::Forward
            } else {
                Whirl::Backward
            },
            shape: mirror_shape(&self.shape),
            whirl_ratio: self.whirl_ratio,
        }
    }
}

/// The shape `(conj b, conj a)` of the mirror of a doubled shape `(a, b)`.
pub fn mirror_shape(shape: &[c64]) -> Vec<c64> {
    let (a, b) = shape.split_at(shape.len() / 2);
    b.iter().chain(a).map(|z| z.conj()).collect()
}

/// Below this `|omega| / |s|` a pole does not oscillate: an overdamped (real) pole, whose
/// frequency is round-off (at rest) or the slow turn the gyroscopic coupling gives it at speed
/// (a log decrement past 6e6: it never completes a cycle).
pub const NON_OSCILLATING: f64 = 1e-6;

/// A pole whose frequency is at most this fraction of its decay rate, `|omega| <= 0.01
/// |sigma|` (a log decrement of at least 628: it decays by e^-628 per cycle), moves as an
/// overdamped one: real at rest, turned slowly at speed by the gyroscopic coupling of a heavily
/// damped support. A branch of such poles at every speed is not a Campbell branch.
pub const OVERDAMPED: f64 = 0.01;

/// Whether `s` is overdamped (see [`OVERDAMPED`]).
pub fn overdamped(s: c64) -> bool {
    s.re < 0.0 && s.im.abs() <= OVERDAMPED * -s.re
}

/// Whether `s` oscillates (see [`NON_OSCILLATING`]).
pub fn oscillates(s: c64) -> bool {
    s.im.abs() > NON_OSCILLATING * s.norm()
}

/// `-2 pi sigma / |omega|` of an oscillating pole `s`, else `None`.
pub fn log_decrement(s: c64) -> Option<f64> {
    oscillates(s).then(|| -2.0 * std::f64::consts::PI * s.re / s.im.abs())
}

/// `-sigma / |s|` (0 at the origin).
pub fn damping_ratio(s: c64) -> f64 {
    let m = s.norm();
    if m > 0.0 { -s.re / m } else { 0.0 }
}

/// Relative margin below which a pole counts as not unstable: `sigma > 1e-10 |s|`. It keeps an
/// undamped (conservative) rotor, whose decay rates are zero up to round-off, from reporting a
/// threshold of instability.
pub const INSTABILITY_MARGIN: f64 = 1e-10;

/// The poles of a model at one speed.
#[derive(Debug, Clone)]
pub struct PoleSet {
    pub speed: f64,
    /// Rotor poles by increasing |frequency| (backward first on ties).
    pub rotor: Vec<Pole>,
    /// Internal poles by increasing decay rate (most damped first).
    pub internal: Vec<Pole>,
    /// Rotor poles the model should have: `2n`.
    pub expected_rotor: usize,
    /// Whether the model is in doubled coordinates: each rotor pole stands for a mirror pair.
    pub doubled: bool,
}

impl PoleSet {
    /// Rotor poles the model leaves undefined at this speed (hysteretic model only).
    pub fn missing(&self) -> usize {
        self.expected_rotor.saturating_sub(self.rotor.len())
    }

    /// `max (sigma - margin |s|)` over all poles: > 0 iff some pole is unstable.
    pub fn growth(&self) -> f64 {
        self.all()
            .map(|p| p.s.re - INSTABILITY_MARGIN * p.s.norm())
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// Largest decay rate, without margin.
    pub fn max_decay_rate(&self) -> f64 {
        self.all().map(|p| p.s.re).fold(f64::NEG_INFINITY, f64::max)
    }

    /// The pole with the largest growth.
    pub fn least_stable(&self) -> Option<&Pole> {
        self.all().max_by(|a, b| {
            (a.s.re - INSTABILITY_MARGIN * a.s.norm())
                .total_cmp(&(b.s.re - INSTABILITY_MARGIN * b.s.norm()))
        })
    }

    /// Mode number of a pole: its rank by |frequency| among the poles of its whirl, from 1.
    pub fn mode_number(&self, pole: &Pole) -> usize {
        let list = if pole.whirl == Whirl::Internal {
            &self.internal
        } else {
            &self.rotor
        };
        list.iter()
            .filter(|p| p.whirl == pole.whirl && p.s.im.abs() < pole.s.im.abs())
            .count()
            + 1
    }

    pub fn all(&self) -> impl Iterator<Item = &Pole> {
        self.rotor.iter().chain(self.internal.iter())
    }
}

/// Poles of `model` at spin speed `speed`.
pub fn poles_at(model: &DampedModel, speed: f64) -> Result<PoleSet, LinalgError> {
    // Each pole with the weight of its rotating branches on `r` (doubled internal poles).
    type Weighted = Vec<(Pole, f64)>;
    let (mut rotor, mut internal): (Weighted, Weighted) = (vec![], vec![]);
    let n = model.dofs();
    let doubled = model.layout == Layout::Doubled;
    match &model.kind {
        ModelKind::Linear(m) => {
            let e = linalg::eigen(&m.at(speed))?;
            // Without internal coordinates every pole is a rotor pole: no energies to weigh
            // (their `x^H K x` per pole took 18% of a whole-spectrum sweep at 404 states).
            let all_rotor = e.values.len() <= 2 * n + m.branches().from_supports;
            let mut scored: Vec<(f64, (Pole, f64))> = (0..e.values.len())
                .map(|j| {
                    let (x, y) = split(m, &e.vectors, j);
                    let fraction = if all_rotor {
                        1.0
                    } else {
                        m.rotor_energy_fraction(&x, &y)
                    };
                    (fraction, pole(e.values[j], x, y, m, doubled))
                })
                .collect();
            // Exactly 2N rotor poles, and one per support branch: those whose energy is most in
            // the rotor and its supports.
            scored.sort_by(|a, b| b.0.total_cmp(&a.0));
            let kept = 2 * n + m.branches().from_supports;
            for (k, (_, (mut p, w))) in scored.into_iter().enumerate() {
                if k >= kept {
                    p.whirl = Whirl::Internal;
                    internal.push((p, w));
                } else {
                    rotor.push((p, w));
                }
            }
        }
        ModelKind::Hysteretic(signed) => {
            for sm in signed {
                let e = linalg::eigen(&sm.model.at(speed))?;
                for j in 0..e.values.len() {
                    if sm.consistent(e.values[j], speed) {
                        let (x, y) = split(&sm.model, &e.vectors, j);
                        rotor.push(pole(e.values[j], x, y, &sm.model, doubled));
                    }
                }
            }
        }
    }
    let (rotor, mut internal): (Vec<Pole>, Vec<Pole>) = if doubled {
        (once_each(rotor), once_each(internal))
    } else {
        (
            rotor.into_iter().map(|p| p.0).collect(),
            internal.into_iter().map(|p| p.0).collect(),
        )
    };
    internal.sort_by(|a, b| a.s.re.total_cmp(&b.s.re));
    Ok(PoleSet {
        speed,
        rotor: by_frequency(rotor),
        internal,
        expected_rotor: 2 * model.rotor_dofs(),
        doubled,
    })
}

/// Rotor poles by increasing |frequency|, backward first on ties (a pole set's order).
fn by_frequency(mut rotor: Vec<Pole>) -> Vec<Pole> {
    rotor.sort_by(|a, b| {
        a.s.im
            .abs()
            .total_cmp(&b.s.im.abs())
            .then(a.s.im.total_cmp(&b.s.im))
    });
    rotor
}

/// The rotor poles `s` with shapes `x` on the physical coordinates (no internal coordinates:
/// the full model of a rotor held sparse) as a pole set at `speed` reports them: each mirror
/// pair once in doubled coordinates, ordered by |frequency|. Its `expected_rotor` is the
/// number reported (a bounded set, whose count is not known before the solve).
pub fn rotor_set(speed: f64, pairs: Vec<(c64, Vec<c64>)>, doubled: bool) -> PoleSet {
    let weighted: Vec<(Pole, f64)> = pairs
        .into_iter()
        .map(|(s, x)| (shaped(s, x, doubled), 0.0))
        .collect();
    let rotor = match doubled {
        true => once_each(weighted),
        false => weighted.into_iter().map(|p| p.0).collect(),
    };
    PoleSet {
        speed,
        expected_rotor: rotor.len(),
        rotor: by_frequency(rotor),
        internal: vec![],
        doubled,
    }
}

/// The pole `s` of the state model `m` with the state eigenvector `z = [v, x, y]`, as a pole
/// set reports it before choosing mirror members (doubled: `doubled`).
pub fn pole_of_state(s: c64, z: &[c64], m: &StateModel, doubled: bool) -> Pole {
    let n = m.n();
    pole(s, z[n..2 * n].to_vec(), z[2 * n..].to_vec(), m, doubled).0
}

/// How much more a doubled pole's shape is in `r` than in `conj r`, in [-1, 1] (for an
/// internal pole with no rotor motion, its rotating branches on either copy).
fn forward_weight(p: &Pole, y_weight: f64) -> f64 {
    let h = p.shape.len() / 2;
    let a: f64 = p.shape[..h].iter().map(|z| z.norm_sqr()).sum();
    let b: f64 = p.shape[h..].iter().map(|z| z.norm_sqr()).sum();
    if a + b > 1e-20 {
        (a - b) / (a + b)
    } else {
        y_weight
    }
}

/// Each mirror pair `(s, conj s)` of a doubled model once (see the module docs): every pole is
/// paired with the nearest conjugate of its value, the most definitely forward or backward
/// first, and the member with more of its shape in `r` is kept (for a planar mode, the one with
/// `omega >= 0`). A real pole without a partner is its own mirror: kept.
fn once_each(poles: Vec<(Pole, f64)>) -> Vec<Pole> {
    const TIE: f64 = 1e-8;
    const REAL: f64 = 1e-9;
    let f: Vec<f64> = poles.iter().map(|(p, w)| forward_weight(p, *w)).collect();
    let mut order: Vec<usize> = (0..poles.len()).collect();
    order.sort_by(|&i, &j| f[j].abs().total_cmp(&f[i].abs()));
    let mut used = vec![false; poles.len()];
    let mut out = vec![];
    for &i in &order {
        if used[i] {
            continue;
        }
        used[i] = true;
        let target = poles[i].0.s.conj();
        let near = |j: usize| (poles[j].0.s - target).norm();
        // A real pole is an eigenvalue of the real system once, and its own mirror: two close
        // real poles (an overdamped mode's x and y, 4e-7 apart on tests/data/ross/loaded.json)
        // are two poles, not a pair.
        let real = target.im.abs() <= REAL * target.norm();
        let mirror = (0..poles.len())
            .filter(|&j| !real && !used[j])
            .filter(|&j| near(j) <= 1e-6 * target.norm().max(f64::MIN_POSITIVE))
            .min_by(|&j, &k| near(j).total_cmp(&near(k)));
        let keep = match mirror {
            None => i,
            Some(j) => {
                used[j] = true;
                if f[i] > f[j] + TIE {
                    i
                } else if f[j] > f[i] + TIE {
                    j
                } else if poles[i].0.s.im >= poles[j].0.s.im {
                    i
                } else {
                    j
                }
            }
        };
        out.push(poles[keep].0.clone());
    }
    out
}

/// A pole with its shape `x` (and, for a doubled internal pole, the weight of its rotating
/// branches on `r` against `conj r` in `.1`).
fn pole(s: c64, x: Vec<c64>, y: Vec<c64>, m: &StateModel, doubled: bool) -> (Pole, f64) {
    let y_weight = if doubled {
        let br = m.branches();
        let (mut yr, mut yc) = (0.0, 0.0);
        for (j, v) in y.iter().enumerate() {
            if br.spin[j] > 0.0 {
                yr += v.norm_sqr();
            } else if br.spin[j] < 0.0 {
                yc += v.norm_sqr();
            }
        }
        if yr + yc > 0.0 {
            (yr - yc) / (yr + yc)
        } else {
            0.0
        }
    } else {
        0.0
    };
    (shaped(s, x, doubled), y_weight)
}

/// The pole `s` with its shape `x` on the physical coordinates, its whirl and whirl ratio.
fn shaped(s: c64, x: Vec<c64>, doubled: bool) -> Pole {
    let whirl = if s.im >= 0.0 {
        Whirl::Forward
    } else {
        Whirl::Backward
    };
    let ratio = if doubled {
        let h = x.len() / 2;
        let a = x[..h].iter().map(|z| z.norm_sqr()).sum::<f64>().sqrt();
        let b = x[h..].iter().map(|z| z.norm_sqr()).sum::<f64>().sqrt();
        let (f, bw) = if s.im >= 0.0 { (a, b) } else { (b, a) };
        if f + b > 0.0 {
            (f - bw) / (f + bw)
        } else {
            0.0
        }
    } else if s.im >= 0.0 {
        1.0
    } else {
        -1.0
    };
    Pole {
        s,
        whirl,
        shape: normalise(x),
        whirl_ratio: ratio,
    }
}

/// The displacement part `x` and internal part `y` of eigenvector `j` of a state `[v, x, y]`.
fn split(m: &StateModel, vectors: &linalg::CMat, j: usize) -> (Vec<c64>, Vec<c64>) {
    let n = m.n();
    let x = (n..2 * n).map(|r| vectors[(r, j)]).collect();
    let y = (2 * n..m.size()).map(|r| vectors[(r, j)]).collect();
    (x, y)
}

/// Unit norm, largest component real and positive: a shape comparable across speeds. Scaled by
/// the largest component first, so that no norm over- or underflows.
fn normalise(mut x: Vec<c64>) -> Vec<c64> {
    let big = x
        .iter()
        .cloned()
        .max_by(|a, b| a.norm().total_cmp(&b.norm()));
    let Some(big) = big.filter(|b| b.norm() > 0.0 && b.norm().is_finite()) else {
        return x;
    };
    let phase = big.conj() / big.norm();
    let scale = big.norm();
    for v in x.iter_mut() {
        *v = *v * phase / scale;
    }
    let norm = x.iter().map(|v| v.norm_sqr()).sum::<f64>().sqrt();
    for v in x.iter_mut() {
        *v /= norm;
    }
    x
}
