//! The tangent-only multiplier regularisation (see [`super`], "Multiplier
//! regularisation").
//!
//! Invariants: only the tangent changes, never the residual, so converged
//! states are those of the unregularised problem; the added entries are one
//! diagonal triplet per multiplier, after all other contributions, whether
//! the multiplier is active or not, so the pattern does not depend on the
//! active set.

use crate::ids::MultiplierIndex;
use crate::linear::LinearError;
use crate::system::{DofMap, System};

/// Adds the tangent-only multiplier regularisation (module docs): `-eps` on
/// the diagonal of the active multiplier rows (an explicit zero on the
/// inactive ones, so the pattern does not depend on the active set), with
/// `eps = delta max|G|^2 / max|K_uu|`. Nothing when `delta` is 0 or there
/// are no multipliers. Across MPI ranks the maxima are taken over every
/// rank's triplets (`max_over_ranks`, collective) and only the rank that
/// assembles the contact (`adds`) adds the diagonal.
pub(super) fn regularize(
    sys: &mut System,
    dofs: &DofMap,
    active: &[bool],
    delta: f64,
    max_over_ranks: impl FnOnce(&mut [f64]) -> Result<(), LinearError>,
    adds: bool,
) -> Result<(), LinearError> {
    if !(delta > 0.0) || dofs.n_mult == 0 {
        return Ok(());
    }
    let n_free = dofs.n_free;
    // the block's entries are all K_uu's
    let block_max = sys.block.as_ref().map_or(0.0, |b| b.max_abs);
    let (mut k_max, mut g_max) = (block_max, 0.0_f64);
    for ((&r, &c), &v) in sys.rows.iter().zip(&sys.cols).zip(&sys.vals) {
        let (r, c) = (r as usize, c as usize);
        if r < n_free && c < n_free {
            k_max = k_max.max(v.abs());
        } else if r < n_free || c < n_free {
            g_max = g_max.max(v.abs());
        }
    }
    let mut maxima = [k_max, g_max];
    max_over_ranks(&mut maxima)?;
    let [k_max, g_max] = maxima;
    if !adds {
        return Ok(());
    }
    let eps = if k_max > 0.0 {
        delta * g_max * g_max / k_max
    } else {
        0.0
    };
    // exactly these, so that a full buffer is not doubled for them
    sys.rows.reserve_exact(active.len());
    sys.cols.reserve_exact(active.len());
    sys.vals.reserve_exact(active.len());
    for (m, &on) in active.iter().enumerate() {
        let row = dofs.mult_eq(MultiplierIndex::new(m));
        sys.push(row, row, if on { -eps } else { 0.0 });
    }
    Ok(())
}
