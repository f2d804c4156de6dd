//! Rotors held sparse: which analyses and models may hold a large rotor in sparse matrices
//! rather than parse it against the dense limits, and what the equivalent and nonviscous
//! models' dampers then cost.

use super::*;

impl Model {
    /// [`Model::parse`], the rotor held sparse where `allow` and it may be: a beam rotor
    /// without Guyan reduction past [`SPARSE_FROM`] coordinates, whose size is then bounded by
    /// `max_sparse_dofs` and the memory estimate, under every damping model (the equivalent
    /// and nonviscous models with their dampers on the lowest modes, `damping::dampers`,
    /// `modes` checked against [`MAX_DAMPED_MODES`]); any other is parsed against the dense
    /// limits. `(model, held sparse)`.
    pub fn parse_held(
        allow: bool,
        motion: Motion,
        rotor: &RotorInput,
        damping: &DampingInput,
        limits: &Limits,
        bad: Invalid,
    ) -> Result<(Self, bool), Invalid> {
        if !motion.is_lateral() {
            // A train's torsional or axial system: one coordinate per node, never held sparse.
            return Ok((
                Model::parse_motion(rotor, damping, motion, limits, bad)?,
                false,
            ));
        }
        if allow {
            let relaxed = Limits {
                max_states: usize::MAX,
                ..limits.held_sparse()
            };
            // Errors phrased against the sparse limits; a model that parses but cannot be held
            // sparse (small, Guyan-reduced, a matrix rotor) is parsed again with the dense ones.
            let model = Model::parse(rotor, damping, &relaxed, bad.clone())?;
            if model.held_sparse() {
                model.check_dampers(bad)?;
                return Ok((model, true));
            }
        }
        Ok((Model::parse(rotor, damping, limits, bad)?, false))
    }

    /// Whether this model may be held sparse (see [`Model::parse_held`]; the model's damping
    /// was checked by the caller).
    fn held_sparse(&self) -> bool {
        let size = self.size();
        matches!(self.rotor, Rotor::Beam(_))
            && size.dofs > SPARSE_FROM
            && size.assembled == size.dofs
    }

    /// Heap of the equivalent or nonviscous model's dampers when held sparse (0 for the others).
    pub fn damper_bytes(&self, limits: &Limits) -> u64 {
        match self.damping.on_modes() {
            true => self.size().dofs as u64 * damper_bytes_per_coordinate(limits.threads.max(1)),
            false => 0,
        }
    }

    /// The equivalent and nonviscous models held sparse put dampers on at most
    /// [`MAX_DAMPED_MODES`] modes (each a column of the rotor's size).
    fn check_dampers(&self, bad: Invalid) -> Result<(), Invalid> {
        let modes = match &self.damping {
            DampingModel::Equivalent { modes } => *modes,
            DampingModel::Nonviscous(spec) => spec.modes,
            _ => None,
        };
        let limit = match self.rotor.doubled() {
            true => MAX_DAMPED_MODES / 2,
            false => MAX_DAMPED_MODES,
        };
        match modes {
            Some(m) if m > limit => {
                let mut bad = bad;
                bad.push(
                    "damping.modes",
                    format!(
                        "a rotor of this size ({} coordinates) is held sparse, its dampers on \
                         at most {limit} modes (got {m}); without `modes`, every mode up to \
                         16 times the analysis's band (`max_frequency`, the highest speed or \
                         frequency)",
                        self.size().dofs
                    ),
                );
                Err(bad)
            }
            _ => Ok(()),
        }
    }
}
