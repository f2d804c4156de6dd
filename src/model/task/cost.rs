//! The cost estimates of the sweeps, harmonic and time responses: sizes, memory and work, known
//! before anything is built.

use super::*;

/// Cost of a sweep of `speeds` pole sets solved in parallel and streamed through the tracker,
/// answering `values` numbers.
/// A bounded sweep of a large rotor held sparse (`analysis::large`): linear in its coordinates
/// ([`sparse_bytes_per_coordinate`]), and the dense sweep of its reduced model, of at most
/// [`sparse_states`] states (a larger one is refused when it is found).
pub(super) fn sparse_sweep_cost(
    size: Size,
    doubled: bool,
    speeds: usize,
    limits: &Limits,
    values: u64,
) -> Cost {
    let dense = sweep_cost(reduced_size(size, limits), speeds, limits, true, values);
    let linear = size.dofs as u64 * sparse_bytes_per_coordinate(doubled);
    Cost {
        peak_bytes: dense.peak_bytes + linear,
        ..dense
    }
    .with_work(dense.work + SPARSE_WORK * size.dofs as f64)
}

/// A harmonic response of a rotor held sparse: one sparse factor of `Z(i omega)` per compute
/// thread (and the model's matrices at the speed), each linear in the coordinates
/// ([`SPARSE_HARMONIC_BYTES`]), `solves` of them.
pub(super) fn sparse_harmonic_cost(size: Size, limits: &Limits, solves: u64, values: u64) -> Cost {
    let n = size.dofs as u64;
    let threads = limits.threads.max(1) as u64;
    let response_bytes = values * BYTES_PER_VALUE;
    Cost {
        size,
        peak_bytes: (threads + 1) * n * SPARSE_HARMONIC_BYTES + values * 16 + response_bytes,
        response_bytes,
        work: solves as f64 * SPARSE_HARMONIC_WORK * n as f64,
    }
}

/// Flops per coordinate of one sparse harmonic solve (factor and substitution), for the work
/// estimate only.
const SPARSE_HARMONIC_WORK: f64 = 2e3;

/// A time response of a rotor held sparse: its reduction found and checked through sparse
/// factors (linear in the coordinates, [`sparse_bytes_per_coordinate`]) and integrated as a
/// dense model of at most [`sparse_states`] states, with `extra` bytes besides (histories,
/// outputs) and `values` answered.
pub(super) fn sparse_time_cost(
    size: Size,
    doubled: bool,
    limits: &Limits,
    extra: u64,
    values: u64,
) -> Cost {
    let reduced = reduced_size(size, limits);
    let dense = Cost::new(reduced, 2, 0, extra, values);
    let linear = size.dofs as u64 * sparse_bytes_per_coordinate(doubled);
    Cost {
        size,
        peak_bytes: dense.peak_bytes + linear,
        ..dense
    }
    .with_work(reduced.eigen_work() + SPARSE_WORK * size.dofs as f64)
}

/// The largest reduced model of a rotor of `size` held sparse (at most [`sparse_states`]).
fn reduced_size(size: Size, limits: &Limits) -> Size {
    let dofs = (sparse_states(limits) / 2).min(size.dofs);
    Size {
        assembled: dofs,
        dofs,
        internal: 0,
        ..size
    }
}

/// Largest reduced model of a sparse sweep.
pub fn sparse_states(limits: &Limits) -> usize {
    SPARSE_REDUCED_STATES.min(limits.max_states)
}

/// Flops per coordinate of the sparse path (factors, Lanczos and Arnoldi steps with their
/// reorthogonalisation), for the work estimate only.
pub(super) const SPARSE_WORK: f64 = 2e5;

pub(super) fn sweep_cost(
    size: Size,
    speeds: usize,
    limits: &Limits,
    tracked: bool,
    values: u64,
) -> Cost {
    let threads = limits.threads.max(1);
    let batch = BATCH_PER_THREAD * threads;
    // Tracker: every branch's poles over the sweep and its last shape.
    let branches = 2 * size.dofs as u64;
    let tracker = if tracked {
        branches * (speeds as u64 * 16 + size.dofs as u64 * 16 + 64)
    } else {
        0
    };
    let summaries = speeds as u64 * 64;
    Cost::new(size, threads, batch + 2, tracker + summaries, values)
        .with_work(size.eigen_work() * (speeds as f64 + 20.0))
}
