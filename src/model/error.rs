//! Field errors: a JSON path and a reason.

/// One bad field of a request.
#[derive(Debug, Clone, PartialEq)]
pub struct FieldError {
    /// JSON path, e.g. `rotor.loss_factor_rotating` or `speeds[3]`.
    pub path: String,
    pub message: String,
}

/// Most field errors kept in one answer; the rest are counted.
pub const MAX_FIELD_ERRORS: usize = 100;

/// A request that does not describe a valid model: every bad field, with its path (the
/// first [`MAX_FIELD_ERRORS`] of them, and how many more there were).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Invalid {
    errors: Vec<FieldError>,
    omitted: usize,
}

impl Invalid {
    pub fn one(path: impl Into<String>, message: impl Into<String>) -> Self {
        let mut bad = Self::default();
        bad.push(path, message);
        bad
    }

    pub fn push(&mut self, path: impl Into<String>, message: impl Into<String>) {
        if self.errors.len() >= MAX_FIELD_ERRORS {
            self.omitted += 1;
            return;
        }
        self.errors.push(FieldError {
            path: path.into(),
            message: message.into(),
        });
    }

    /// Records the error of `r` (if any) at `path` and returns its value.
    pub fn check<T>(&mut self, path: &str, r: Result<T, String>) -> Option<T> {
        match r {
            Ok(v) => Some(v),
            Err(message) => {
                self.push(path, message);
                None
            }
        }
    }

    pub fn extend(&mut self, other: Invalid) {
        for e in other.errors {
            self.push(e.path, e.message);
        }
        self.omitted += other.omitted;
    }

    pub fn is_empty(&self) -> bool {
        self.errors.is_empty() && self.omitted == 0
    }

    /// The errors kept.
    pub fn errors(&self) -> &[FieldError] {
        &self.errors
    }

    /// Every path, prefixed (a job's `input.`).
    pub fn prefix_paths(&mut self, f: impl Fn(&str) -> String) {
        for e in &mut self.errors {
            e.path = f(&e.path);
        }
    }

    /// Errors found beyond those kept.
    pub fn omitted(&self) -> usize {
        self.omitted
    }

    /// All errors found.
    pub fn count(&self) -> usize {
        self.errors.len() + self.omitted
    }

    /// `Ok(v)` when nothing was recorded.
    pub fn into_result<T>(self, v: impl FnOnce() -> T) -> Result<T, Invalid> {
        if self.is_empty() { Ok(v()) } else { Err(self) }
    }
}

impl std::fmt::Display for Invalid {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let parts: Vec<String> = self
            .errors
            .iter()
            .take(5)
            .map(|e| format!("{}: {}", e.path, e.message))
            .collect();
        write!(f, "{}", parts.join("; "))?;
        let rest = self.count() - parts.len();
        if rest > 0 {
            write!(f, "; and {rest} more")?;
        }
        Ok(())
    }
}

impl std::error::Error for Invalid {}

/// A finite number (JSON cannot carry NaN, but overflowing literals and computed values can be).
pub fn finite(x: f64) -> Result<f64, String> {
    if x.is_finite() {
        Ok(x)
    } else {
        Err("must be a finite number".into())
    }
}

/// A finite, strictly positive number.
pub fn positive(x: f64) -> Result<f64, String> {
    let x = finite(x)?;
    if x > 0.0 {
        Ok(x)
    } else {
        Err(format!("must be > 0 (got {x})"))
    }
}

/// A finite, non-negative number.
pub fn non_negative(x: f64) -> Result<f64, String> {
    let x = finite(x)?;
    if x >= 0.0 {
        Ok(x)
    } else {
        Err(format!("must be >= 0 (got {x})"))
    }
}

/// A loss factor `eta = E''/E'` in [0, 1).
pub fn loss_factor(x: f64) -> Result<f64, String> {
    let x = finite(x)?;
    if (0.0..1.0).contains(&x) {
        Ok(x)
    } else {
        Err(format!("a loss factor must be in [0, 1) (got {x})"))
    }
}
