//! The memory a solve needs, estimated before the model is built, and the
//! refusal of a solve that cannot fit ([`crate::SolverError::Memory`]).
//!
//! # The estimate
//!
//! `bytes = equations x B`, where `equations = D x nodes` (the free
//! displacements; the prescribed dofs are fewer than the multipliers
//! added, or negligible for the meshes this matters for) and `B` is
//! [`LU_BYTES_PER_EQUATION`] or [`LDLT_BYTES_PER_EQUATION`], the memory of
//! the model, its assembly and the first factorisation per equation. `B`
//! is half the smallest peak per equation measured on the refined paper
//! scene (`docs/scaling/scaling.md`, one Newton iteration, peak resident
//! memory over equations): LU 7.3 to 8.6 KiB per equation from 1177 to
//! 101725 equations, LDLᵀ 3.6 to 7.0 KiB from 1177 to 981254 equations.
//! The factor's fill grows faster than the equations (`equations^1.19`
//! there), so larger models need more per equation, not less; and a
//! triangle mesh of the same nodes has a little less fill than a
//! quadrilateral one, which the factor of two covers. The estimate is
//! therefore a lower bound: a solve it refuses would not have fitted; one
//! it lets through may still need more than it says.
//!
//! # When
//!
//! [`crate::scene::check_scene`] runs before a scene's model is built (also when a
//! scene is loaded, which builds it once to validate it), with the nodes
//! of its block bodies (`(nx rx + 1)(ny ry + 1)` each, from the scene
//! alone: no mesh is allocated); a Gmsh body's nodes are known only once
//! its file is read, so [`check_model`] runs again on the built model,
//! before the first factorisation is prepared. Each compares the
//! estimate with `MemAvailable` of `/proc/meminfo`; where that cannot be
//! read (not Linux, or no such line), the check is skipped.

use crate::linear::LinearSolverKind;
use crate::model::Model;
use crate::model::{Dim, SurfaceDim};

/// LU: the bytes per equation of the model and the first factorisation
/// (module docs: half of the smallest measured 7.3 KiB).
pub const LU_BYTES_PER_EQUATION: u64 = 3 * 1024 + 512;

/// LDLᵀ: the bytes per equation of the model and the first factorisation
/// (module docs: half of the smallest measured 3.6 KiB).
pub const LDLT_BYTES_PER_EQUATION: u64 = 1024 + 768;

/// The memory estimate of a model of `equations` equations solved with
/// `linear` (module docs), in bytes; saturates instead of overflowing.
pub fn estimate(equations: u64, linear: LinearSolverKind) -> u64 {
    let per = match linear {
        LinearSolverKind::Lu => LU_BYTES_PER_EQUATION,
        LinearSolverKind::Ldlt => LDLT_BYTES_PER_EQUATION,
    };
    equations.saturating_mul(per)
}

/// `MemAvailable` of `/proc/meminfo` in bytes, `None` where it cannot be
/// read.
pub fn available() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    mem_available(&text)
}

/// `MemAvailable` (in bytes) of the text of `/proc/meminfo`.
fn mem_available(meminfo: &str) -> Option<u64> {
    let line = meminfo
        .lines()
        .find_map(|l| l.strip_prefix("MemAvailable:"))?;
    let mut words = line.split_whitespace();
    let value: u64 = words.next()?.parse().ok()?;
    let scale = match words.next() {
        Some("kB") => 1024,
        None => 1,
        Some(_) => return None,
    };
    value.checked_mul(scale)
}

/// A model whose estimate exceeds the available memory.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(
    "not enough memory: {equations} equations need at least {} MiB for the model and the first factorisation ({} bytes per equation with the {linear} solver, see solver::memory), but only {} MiB are available (MemAvailable in /proc/meminfo)",
    needed >> 20,
    needed / (*equations).max(1),
    available >> 20
)]
pub struct MemoryError {
    /// The estimated equations (twice the nodes).
    pub equations: u64,
    /// The linear solver the estimate is for.
    pub linear: LinearSolverKind,
    /// The estimate, bytes.
    pub needed: u64,
    /// `MemAvailable`, bytes.
    pub available: u64,
}

/// Refuses `equations` when their estimate exceeds `available` bytes;
/// `None` (unknown) accepts.
pub fn check(
    equations: u64,
    linear: LinearSolverKind,
    available: Option<u64>,
) -> Result<(), MemoryError> {
    let needed = estimate(equations, linear);
    match available {
        Some(available) if needed > available => Err(MemoryError {
            equations,
            linear,
            needed,
            available,
        }),
        _ => Ok(()),
    }
}

/// [`check`] on a built model (every body, Gmsh ones included), before
/// the solve allocates its linear system.
pub fn check_model<const D: usize>(
    model: &Model<D>,
    linear: LinearSolverKind,
) -> Result<(), MemoryError>
where
    Dim<D>: SurfaceDim<D>,
{
    let equations = (model.mesh.node_count() as u64).saturating_mul(D as u64);
    check(equations, linear, available())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mem_available_is_read_in_bytes() {
        let text = "MemTotal:       24000000 kB\nMemFree:  100 kB\nMemAvailable:   22000000 kB\n";
        assert_eq!(mem_available(text), Some(22_000_000 * 1024));
        assert_eq!(mem_available("MemTotal: 5 kB\n"), None);
        assert_eq!(mem_available("MemAvailable: x kB\n"), None);
        assert_eq!(mem_available("MemAvailable: 5 MB\n"), None);
    }

    #[test]
    fn the_estimate_is_below_every_measured_peak() {
        // (equations, peak MiB) of docs/scaling/scaling.md
        let lu = [
            (1177, 9),
            (3235, 23),
            (10375, 79),
            (31235, 236),
            (101725, 856),
        ];
        let ldlt = [
            (1177, 8),
            (3235, 16),
            (10375, 44),
            (31235, 121),
            (101725, 382),
            (295345, 1290),
            (981254, 3429),
        ];
        for (kind, table) in [
            (LinearSolverKind::Lu, &lu[..]),
            (LinearSolverKind::Ldlt, &ldlt[..]),
        ] {
            for &(n, mib) in table {
                let e = estimate(n, kind);
                assert!(e < mib * 1024 * 1024, "{kind} {n}: {e}");
                // and not absurdly low: at least a third of the peak
                assert!(3 * e > mib * 1024 * 1024 / 2, "{kind} {n}: {e}");
            }
        }
    }

    #[test]
    fn too_large_is_refused_with_both_figures_and_unknown_memory_is_accepted() {
        let n = 18_006_002; // a 3000 x 3000 block: 2 x 3001^2
        let err = check(n, LinearSolverKind::Lu, Some(16 << 30)).unwrap_err();
        let msg = err.to_string();
        let needed_mib = estimate(n, LinearSolverKind::Lu) >> 20;
        assert!(
            msg.contains(&format!("{n} equations"))
                && msg.contains(&format!("{needed_mib} MiB"))
                && msg.contains("16384 MiB"),
            "{msg}"
        );
        assert!(check(n, LinearSolverKind::Lu, None).is_ok());
        assert!(check(1000, LinearSolverKind::Ldlt, Some(16 << 30)).is_ok());
    }
}
