//! What a request may ask for, and what it will cost: computed from the validated input,
//! before anything proportional to it is allocated.
//!
//! Sizes, with `n` the complex degrees of freedom the analysis solves (after Guyan reduction)
//! and `p` the internal coordinates of the nonviscous model (at most `modes x (m_r + m_n)`
//! branches, one set per side that has loss):
//!
//! - states `S = 2n + p` of each first-order eigenproblem (the hysteretic model solves four);
//! - a dense complex eigendecomposition holds about `EIGEN_MATRICES` `S x S` complex matrices
//!   (the matrix, its balanced copy, the Schur factors, the vectors) while it runs, and a
//!   sweep runs one per compute thread;
//! - a pole set keeps `(2n + p)` poles with an `n`-entry shape each; sweeps stream them through
//!   the tracker a batch at a time, so only a batch is alive;
//! - the answer's size is counted in values, at [`BYTES_PER_VALUE`] bytes of JSON each.
//!
//! The estimate is an upper bound of the heap an analysis holds at its peak (checked against a
//! counting allocator in `tests/limits.rs`); the service admits analyses against a memory
//! budget with it.

/// Limits of one request (configurable; see the README's table).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    /// Most complex degrees of freedom of the assembled rotor, before reduction.
    pub max_dofs: usize,
    /// Most complex degrees of freedom of a rotor whose analysis holds it sparse (a bounded
    /// Campbell diagram of a large rotor, `analysis::large`): a bound on what is parsed before
    /// the memory estimate, which is what limits such a model.
    pub max_sparse_dofs: usize,
    /// The setting `max_dofs` came from, for messages: `WHIRL_MAX_DOFS`, or
    /// `WHIRL_MAX_SPARSE_DOFS` where a sweep was parsed for the sparse path.
    pub dofs_setting: &'static str,
    /// Largest first-order eigenproblem, internal coordinates included.
    pub max_states: usize,
    /// Most spin speeds in a sweep.
    pub max_speeds: usize,
    /// Most output values of a time response (samples x nodes).
    pub max_samples: usize,
    /// Most steps of the implicit integrator.
    pub max_steps: usize,
    /// Largest answer, bytes of JSON (estimated from the number of values).
    pub max_response_bytes: u64,
    /// Compute threads one analysis uses (for the memory estimate of parallel sweeps).
    pub threads: usize,
}

impl Limits {
    /// These limits for a rotor held sparse: its size bounded by `max_sparse_dofs` (and the
    /// memory estimate), not by the dense `max_dofs`.
    pub fn held_sparse(&self) -> Limits {
        Limits {
            max_dofs: self.max_sparse_dofs.max(self.max_dofs),
            dofs_setting: "WHIRL_MAX_SPARSE_DOFS",
            ..*self
        }
    }
}

impl Default for Limits {
    fn default() -> Self {
        Limits {
            max_dofs: 1000,
            max_sparse_dofs: 200_000,
            dofs_setting: "WHIRL_MAX_DOFS",
            max_states: 2000,
            max_speeds: 2000,
            max_samples: 2_000_000,
            max_steps: 500_000,
            max_response_bytes: 128 << 20,
            threads: 2,
        }
    }
}

/// Coordinates `N` of a full second-order model (`n`, or `2 n` doubled) above which a bounded
/// sweep's reduction holds it sparse (`analysis::large`); below, the dense path is as fast.
pub const SPARSE_FROM: usize = 600;

/// Most vectors of the Arnoldi space of the sparse path's check (`analysis::large`): about
/// twice the poles in its disc.
pub const SPARSE_ARNOLDI: usize = 240;

/// Largest reduced model of the sparse path (states; refused above, `analysis::large`): what
/// its dense sweep is estimated at.
pub const SPARSE_REDUCED_STATES: usize = 480;

/// Heap per coordinate `N` of the sparse path, bytes, besides its reduced model: the Arnoldi
/// space (`2 N` complex entries per vector, [`SPARSE_ARNOLDI`] vectors), the Lanczos and static
/// correction bases (real, `n` entries: `N`, or `N / 2` doubled; at most
/// [`SPARSE_REDUCED_STATES`] / 2 vectors, a quarter of that doubled; six copies while the basis
/// is formed), the sparse matrices and their factors (a few hundred bytes per coordinate).
pub fn sparse_bytes_per_coordinate(doubled: bool) -> u64 {
    let copies = if doubled { 2 } else { 1 };
    let vectors = (SPARSE_REDUCED_STATES / (2 * copies)) as u64;
    2 * 16 * SPARSE_ARNOLDI as u64 + 6 * 8 * vectors / copies as u64 + 2048
}

/// Heap per coordinate `N` of one harmonic solve of a rotor held sparse: `Z(i omega)`'s
/// entries as built (three matrices' bands, 32 bytes each) and compressed, its LU factors with
/// their fill, the model's matrices at the speed, and the right-hand side and solution
/// (measured about 1.4 kB on a 2000-element shaft on cross-coupled bearings, `tests/memory.rs`).
pub const SPARSE_HARMONIC_BYTES: u64 = 4096;

/// Most modes the equivalent and nonviscous models of a rotor held sparse put dampers on
/// (`damping::dampers`; x/y modes of doubled coordinates count one each).
pub const MAX_DAMPED_MODES: usize = 120;

/// Heap per coordinate `N` of those dampers, bytes: each damped mode's shape and column (and
/// its column's spun copy), and one solve per damper in each shift-invert factor alive (one
/// per compute thread and the check's).
pub fn damper_bytes_per_coordinate(threads: usize) -> u64 {
    16 * MAX_DAMPED_MODES as u64 * (3 + 2 * (threads as u64 + 1))
}

/// Most modes of a critical speed map held sparse: each stiffness's Lanczos run keeps about
/// twice as many vectors of the rotor's size (more, and the dense solve is the cheaper).
pub const MAX_SPARSE_MODES: usize = 100;

/// Whether a critical speed map of a shaft of `dofs` complex coordinates asking `modes` is
/// solved sparse: past `SPARSE_FROM` coordinates, for at most [`MAX_SPARSE_MODES`] modes.
pub fn map_is_sparse(dofs: usize, modes: usize) -> bool {
    dofs > SPARSE_FROM && modes <= MAX_SPARSE_MODES
}

/// Points per element of a static analysis's diagram, ends included.
pub const DIAGRAM_POINTS: usize = 9;

/// JSON bytes per number in an answer (a full-precision double and its separator).
pub const BYTES_PER_VALUE: u64 = 24;

/// `S x S` complex matrices alive during one dense eigendecomposition.
pub const EIGEN_MATRICES: u64 = 8;

/// Pole sets computed ahead of the tracker, per compute thread.
pub const BATCH_PER_THREAD: usize = 4;

/// Sizes of the model a task solves.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Size {
    /// Complex degrees of freedom as assembled (before Guyan reduction).
    pub assembled: usize,
    /// Complex degrees of freedom solved.
    pub dofs: usize,
    /// Internal coordinates (upper bound).
    pub internal: usize,
    /// Linear problems per speed (4 for the hysteretic model).
    pub problems: usize,
    /// State matrices kept per problem: one, or one per speed of the supports' tables.
    pub points: usize,
}

impl Size {
    pub fn states(&self) -> usize {
        2 * self.dofs + self.internal
    }

    /// Heap of the assembled rotor, its modal bases, its realizations and its first-order
    /// models (`dofs` is the size of the coordinates solved: doubled when they are).
    pub fn model_bytes(&self) -> u64 {
        let (na, n, s) = (
            self.assembled as u64,
            self.dofs as u64,
            self.states() as u64,
        );
        // 8 real assembled matrices and Guyan's products; modal basis and second-order form
        // (kept with its branch couplings U, U^H for harmonic solves, `damping::harmonic`);
        // A0, A1 per problem and the solve that builds them (n x (4n + p) complex, twice).
        let assembly = 12 * 8 * na * na;
        let basis = 16 * 8 * n * n;
        let second_order = 96 * n * n + 2 * 16 * n * self.internal as u64;
        let state = self.problems as u64 * self.points.max(1) as u64 * 2 * 16 * s * s;
        let build = 2 * 16 * n * (4 * n + self.internal as u64) + 16 * n * n;
        assembly + basis + second_order + state + build
    }

    /// Heap of one dense eigendecomposition of one state matrix.
    pub fn eigen_bytes(&self) -> u64 {
        let s = self.states() as u64;
        EIGEN_MATRICES * 16 * s * s
    }

    /// Heap of one pole set with shapes.
    pub fn pole_set_bytes(&self) -> u64 {
        let (n, s) = (self.dofs as u64, self.states() as u64);
        s * (n * 16 + 64)
    }

    /// Rough floating-point work of one eigendecomposition (for scheduling only).
    pub fn eigen_work(&self) -> f64 {
        let s = self.states() as f64;
        self.problems as f64 * 30.0 * s * s * s
    }
}

/// What a validated task will cost.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cost {
    pub size: Size,
    /// Upper bound of the heap the analysis holds at its peak, bytes.
    pub peak_bytes: u64,
    /// Estimated size of the JSON answer, bytes.
    pub response_bytes: u64,
    /// Rough floating-point work (flops), to tell short analyses from long ones.
    pub work: f64,
}

impl Cost {
    /// A cost from the model's size, the eigensolves running at once, the pole sets alive at
    /// once, the other heap it needs and the number of values it answers.
    pub fn new(
        size: Size,
        concurrent_solves: usize,
        pole_sets: usize,
        extra: u64,
        values: u64,
    ) -> Self {
        let response_bytes = values * BYTES_PER_VALUE;
        // The answer exists twice at the end: as values and as its JSON text.
        let peak_bytes = size.model_bytes()
            + concurrent_solves as u64 * size.eigen_bytes()
            + pole_sets as u64 * size.pole_set_bytes()
            + extra
            + values * 16
            + response_bytes;
        Cost {
            size,
            peak_bytes,
            response_bytes,
            work: 0.0,
        }
    }

    pub fn with_work(mut self, work: f64) -> Self {
        self.work = work;
        self
    }

    /// This cost with `bytes` more heap at its peak.
    pub fn plus_bytes(mut self, bytes: u64) -> Self {
        self.peak_bytes += bytes;
        self
    }
}
