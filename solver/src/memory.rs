//! The memory a solve needs, estimated before the model is built, and the
//! refusal of a solve that cannot fit ([`crate::SolverError::Memory`]).
//!
//! # The estimate
//!
//! `bytes = equations x B(family, solver, equations)`, where `equations =
//! D x nodes` (the free displacements; the prescribed dofs are fewer than
//! the multipliers added, or negligible for the meshes this matters for)
//! and `B` the memory of the model, its assembly and the first
//! factorisation per equation, measured per [`MeshFamily`] and linear
//! solver as half the smallest peak per equation (peak resident memory
//! over equations), so that the estimate is a **lower bound**: a solve it
//! refuses would not have fitted; one it lets through may still need more
//! than it says.
//!
//! * **2D** ([`MeshFamily::Planar`]), one Newton iteration of the refined
//!   paper scene (`docs/scaling/scaling.md`): LU 7.3 to 8.6 KiB per
//!   equation from 1177 to 101725 equations, LDLᵀ 3.6 to 7.0 KiB from
//!   1177 to 981254; `B` is [`LU_BYTES_PER_EQUATION`] or
//!   [`LDLT_BYTES_PER_EQUATION`], half the smallest. A triangle mesh of the
//!   same nodes has a little less fill than a quadrilateral one, which the
//!   factor of two covers.
//! * **3D** ([`MeshFamily::Hexahedra`], [`MeshFamily::Tetrahedra`]): a 3D
//!   factor fills far more per equation, and more the larger the model (a
//!   separator of a 3D mesh of `n` nodes has `n^(2/3)` of them). One Newton
//!   iteration of `scenes/block3d.toml` refined (`docs/scaling/scaling3d.md`,
//!   LDLᵀ): 18.2 KiB per equation at 9747 equations, 20.7 at 28431, 28.3 at
//!   100860, peak memory growing as `equations^1.19`. Whole runs of
//!   `scenes/hertz3d.toml` with contact, one step (`/usr/bin/time -v`,
//!   peak resident memory): the hexahedral mesh (87012 equations) 26.6 KiB
//!   per equation with the LDLᵀ, 114.4 KiB with the LU (and 4.6 times the
//!   LDLᵀ's time); the tetrahedral mesh (21818 equations) 31.2 KiB with the
//!   LDLᵀ, 57.0 KiB with the LU. `B` is half the smallest peak per
//!   equation brought back to the reference size of 9747 equations,
//!   [`LDLT_3D_BYTES_PER_EQUATION`] (9 KiB) and [`LU_3D_BYTES_PER_EQUATION`]
//!   (24 KiB, from the tetrahedral run), times `(equations / 9747)^0.19`
//!   above it ([`FILL_GROWTH_3D`]): with the LDLᵀ 13.6 KiB per equation at
//!   87012 equations and 26.9 KiB (79 GiB) for the 3.1e6 equations of a
//!   100^3 block of hexahedra. Tetrahedra take the hexahedra's figure: their
//!   measured peak per equation is not lower (see
//!   [`MeshFamily::Tetrahedra`]).
//!
//! * **PETSc** (`--linear petsc`, feature `petsc`), whole runs of
//!   `scenes/pressed-block3d.toml` refined 4, 6 and 9 times
//!   (`scripts/petsc-scaling.sh`, docs/petsc.md): 5.8, 5.2 and 4.9 KiB
//!   per equation at 103813, 343207 and 1142398 equations (6.4, 5.6 and
//!   5.3 with GAMG's smoothed aggregation, 9.1, 8.5 and 8.4 before the
//!   solid block, 13.5, 11.8 and 11.7 before the triplet indices became
//!   32-bit), not growing (no fill): `B` is
//!   [`PETSC_3D_BYTES_PER_EQUATION`], 0.7 of the smallest, at every size. In 2D it takes the LDLᵀ's figure, a lower bound (a 2D
//!   block pressed on a base peaked at 6.7 KiB per equation through PETSc).
//!
//! # When
//!
//! [`crate::scene::check_scene`] runs before a scene's model is built (also
//! when a scene is loaded, which builds it once to validate it), with the
//! nodes of its block bodies (`(nx rx + 1)(ny ry + 1)` each in 2D,
//! `(nx rx + 1)(ny ry + 1)(nz rz + 1)` in 3D, from the scene alone: no mesh
//! is allocated); a Gmsh body's nodes are known only once its file is read,
//! so [`check_model`] runs again on the built model, before the first
//! factorisation is prepared. Each compares the estimate with
//! `MemAvailable` of `/proc/meminfo`; where that cannot be read (not
//! Linux, or no such line), the check is skipped.
//!
//! # What it does not count
//!
//! The LDLᵀ's fallback: a solve whose LDLᵀ fails its checks is factorised
//! again by the LU ([`crate::linear`]'s `ldlt.rs`), which in 3D needs
//! several times the LDLᵀ's memory. No estimate made before the solve can
//! know whether a fallback will happen, so the fallback guards itself: the
//! LU allocates under an address-space limit of what the system has
//! available, and one that does not fit fails the solve, which Newton cuts
//! back ([`crate::linear::fallback`], "The LU's memory"). Measured on the
//! 3D Hertz scene on non-matching hexahedra at h = 0.07 (147228 equations,
//! segmented integration, dual multipliers): before the limit, the second
//! solve's fallback took the process past 22 GiB, where the system killed
//! it; now that a solve without the expected inertia is kept rather than
//! handed to the LU ([`crate::linear::inertia`]), the run needs no LU and
//! peaks at 5.2 GiB (docs/benchmarks.md).

use crate::element::ElementKind;
use crate::linear::LinearSolverKind;
use crate::model::Model;
use crate::model::{Dim, SurfaceDim};

/// LU, 2D: the bytes per equation of the model and the first
/// factorisation (module docs: half of the smallest measured 7.3 KiB).
pub const LU_BYTES_PER_EQUATION: u64 = 3 * 1024 + 512;

/// LDLᵀ, 2D: the bytes per equation of the model and the first
/// factorisation (module docs: half of the smallest measured 3.6 KiB).
pub const LDLT_BYTES_PER_EQUATION: u64 = 1024 + 768;

/// LDLᵀ, 3D, at [`FILL_GROWTH_3D`]'s reference size and below (module
/// docs: half of the smallest measured 18.2 KiB).
pub const LDLT_3D_BYTES_PER_EQUATION: u64 = 9 * 1024;

/// LU, 3D, at [`FILL_GROWTH_3D`]'s reference size and below (module
/// docs: half of the tetrahedral Hertz run's 57.0 KiB brought back to the
/// reference size, the smaller of the two LU runs).
pub const LU_3D_BYTES_PER_EQUATION: u64 = 24 * 1024;

/// PETSc's Krylov solve, 3D (module docs: 0.7 of the smallest measured,
/// 4.9 KiB, rounded to the half KiB; multigrid's memory grows linearly, so no growth
/// with the size). In 2D the LDLᵀ's [`LDLT_BYTES_PER_EQUATION`], which the
/// PETSc path's measured peaks exceed.
pub const PETSC_3D_BYTES_PER_EQUATION: u64 = 3 * 1024 + 512;

/// The growth of a 3D model's bytes per equation: `(equations /
/// reference)^exponent` above the reference size (module docs).
pub const FILL_GROWTH_3D: (f64, f64) = (9747.0, 0.19);

/// The elements whose measured peaks the estimate scales.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeshFamily {
    /// 2D quadrilaterals and triangles.
    Planar,
    /// 3D meshes with hexahedra (blocks, or hexahedra among tetrahedra).
    Hexahedra,
    /// 3D meshes of tetrahedra only. Measured peaks per equation (whole
    /// run, `scenes/hertz3d.toml` on `scenes/hertz3d-tet.msh`: 31.2 KiB
    /// with the LDLᵀ at 21818 equations) are not below the hexahedra's (20.7
    /// KiB at 28431 equations, `scenes/block3d.toml`), so they take the
    /// hexahedra's figure.
    Tetrahedra,
}

impl MeshFamily {
    /// The family of a mesh of dimension `D` whose elements have the kinds
    /// `kinds`: 2D planar; 3D hexahedra when one is a hexahedron.
    pub fn of<const D: usize>(mut kinds: impl Iterator<Item = ElementKind>) -> MeshFamily {
        if D == 2 {
            MeshFamily::Planar
        } else if kinds.any(|k| k == ElementKind::Hex8) {
            MeshFamily::Hexahedra
        } else {
            MeshFamily::Tetrahedra
        }
    }

    /// Its name in messages.
    pub fn name(self) -> &'static str {
        match self {
            MeshFamily::Planar => "2D elements",
            MeshFamily::Hexahedra => "3D hexahedra",
            MeshFamily::Tetrahedra => "3D tetrahedra",
        }
    }
}

/// The bytes per equation of a model of `equations` equations of `family`
/// solved with `linear` (module docs).
pub fn bytes_per_equation(equations: u64, family: MeshFamily, linear: LinearSolverKind) -> u64 {
    use LinearSolverKind::{Ldlt, Lu, Petsc};
    let solid = match (family, linear) {
        (MeshFamily::Planar, Petsc) => return LDLT_BYTES_PER_EQUATION,
        (_, Petsc) => return PETSC_3D_BYTES_PER_EQUATION,
        (MeshFamily::Planar, Lu) => return LU_BYTES_PER_EQUATION,
        (MeshFamily::Planar, Ldlt) => return LDLT_BYTES_PER_EQUATION,
        (_, Lu) => LU_3D_BYTES_PER_EQUATION,
        (_, Ldlt) => LDLT_3D_BYTES_PER_EQUATION,
    };
    let (reference, exponent) = FILL_GROWTH_3D;
    let growth = (equations as f64 / reference).max(1.0).powf(exponent);
    (solid as f64 * growth) as u64
}

/// The memory estimate of a model of `equations` equations of `family`
/// solved with `linear` (module docs), in bytes; saturates instead of
/// overflowing.
pub fn estimate(equations: u64, family: MeshFamily, linear: LinearSolverKind) -> u64 {
    equations.saturating_mul(bytes_per_equation(equations, family, linear))
}

pub use crate::meminfo::available;

/// A model whose estimate exceeds the available memory.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(
    "not enough memory: {equations} equations of {} need at least {} MiB for the model and the first factorisation ({} bytes per equation with the {linear} solver, a lower bound measured on this kind of model, see solver::memory), but only {} MiB are available (MemAvailable in /proc/meminfo){}",
    family.name(),
    needed >> 20,
    needed / (*equations).max(1),
    available >> 20,
    if *linear == LinearSolverKind::Lu { "; the ldlt solver needs about half (`--linear ldlt`)" } else { "" }
)]
pub struct MemoryError {
    /// The estimated equations (the dimension times the nodes).
    pub equations: u64,
    /// The elements the estimate is for.
    pub family: MeshFamily,
    /// The linear solver the estimate is for.
    pub linear: LinearSolverKind,
    /// The estimate, bytes.
    pub needed: u64,
    /// `MemAvailable`, bytes.
    pub available: u64,
}

/// Refuses `equations` of `family` when their estimate exceeds
/// `available` bytes; `None` (unknown) accepts.
pub fn check(
    equations: u64,
    family: MeshFamily,
    linear: LinearSolverKind,
    available: Option<u64>,
) -> Result<(), MemoryError> {
    let needed = estimate(equations, family, linear);
    match available {
        Some(available) if needed > available => Err(MemoryError {
            equations,
            family,
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
    let family = MeshFamily::of::<D>(model.mesh.elements.iter().map(|e| e.kind()));
    check(equations, family, linear, available())
}

#[cfg(test)]
mod tests {
    use super::*;

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
                let e = estimate(n, MeshFamily::Planar, kind);
                assert!(e < mib * 1024 * 1024, "{kind} {n}: {e}");
                // and not absurdly low: at least a third of the peak
                assert!(3 * e > mib * 1024 * 1024 / 2, "{kind} {n}: {e}");
            }
        }
    }

    /// The 3D estimate stays below every measured 3D peak (one iteration
    /// of the refined `scenes/block3d.toml`, LDLᵀ, and the extrapolated
    /// peak of its 1045572-equation refinement) and not absurdly low.
    #[test]
    fn the_3d_estimate_is_below_every_measured_peak() {
        // (equations, peak MiB) of docs/scaling/scaling3d.md; the last
        // extrapolated there (49.1 GiB)
        for (n, mib) in [(9747, 173), (28431, 576), (100860, 2785), (1045572, 50278)] {
            let e = estimate(n, MeshFamily::Hexahedra, LinearSolverKind::Ldlt);
            assert!(e < mib * 1024 * 1024, "{n}: {e}");
            assert!(4 * e > mib * 1024 * 1024, "{n}: {e}");
        }
        // whole runs of scenes/hertz3d.toml (one step): (family, solver,
        // equations, peak KiB)
        for (family, linear, n, kib) in [
            (
                MeshFamily::Hexahedra,
                LinearSolverKind::Ldlt,
                87012,
                2311252,
            ),
            (MeshFamily::Hexahedra, LinearSolverKind::Lu, 87012, 9957388),
            (
                MeshFamily::Tetrahedra,
                LinearSolverKind::Ldlt,
                21818,
                680260,
            ),
            (MeshFamily::Tetrahedra, LinearSolverKind::Lu, 21818, 1243284),
        ] {
            let e = estimate(n, family, linear);
            assert!(e < kib * 1024, "{family:?} {linear} {n}: {e}");
            assert!(4 * e > kib * 1024, "{family:?} {linear} {n}: {e}");
        }
        // the 100^3 block of hexahedra (3 x 101^3 equations) needs more
        // than this machine's 24 GiB; the 2D figure would have let it start
        let n = 3 * 101_u64.pow(3);
        assert!(estimate(n, MeshFamily::Hexahedra, LinearSolverKind::Ldlt) > 24 << 30);
        assert!(estimate(n, MeshFamily::Planar, LinearSolverKind::Ldlt) < 24 << 30);
        // the LU needs more than the LDLT, tetrahedra as much as hexahedra
        assert!(
            estimate(n, MeshFamily::Hexahedra, LinearSolverKind::Lu)
                > estimate(n, MeshFamily::Hexahedra, LinearSolverKind::Ldlt)
        );
        assert_eq!(
            estimate(n, MeshFamily::Tetrahedra, LinearSolverKind::Ldlt),
            estimate(n, MeshFamily::Hexahedra, LinearSolverKind::Ldlt)
        );
    }

    #[test]
    fn too_large_is_refused_with_both_figures_and_unknown_memory_is_accepted() {
        let n = 18_006_002; // a 3000 x 3000 block: 2 x 3001^2
        let planar = MeshFamily::Planar;
        let err = check(n, planar, LinearSolverKind::Lu, Some(16 << 30)).unwrap_err();
        let msg = err.to_string();
        let needed_mib = estimate(n, planar, LinearSolverKind::Lu) >> 20;
        assert!(
            msg.contains(&format!("{n} equations of 2D elements"))
                && msg.contains(&format!("{needed_mib} MiB"))
                && msg.contains("16384 MiB")
                && msg.contains("`--linear ldlt`"),
            "{msg}"
        );
        assert!(check(n, planar, LinearSolverKind::Lu, None).is_ok());
        assert!(check(1000, planar, LinearSolverKind::Ldlt, Some(16 << 30)).is_ok());
    }

    /// At the edge: an estimate equal to the available memory is accepted,
    /// one byte less available refuses it, in both dimensions.
    #[test]
    fn the_limit_is_the_available_memory_to_the_byte() {
        for (n, family) in [
            (300_000, MeshFamily::Planar),
            (300_000, MeshFamily::Hexahedra),
            (300_000, MeshFamily::Tetrahedra),
        ] {
            for linear in [LinearSolverKind::Lu, LinearSolverKind::Ldlt] {
                let needed = estimate(n, family, linear);
                assert!(check(n, family, linear, Some(needed)).is_ok());
                let err = check(n, family, linear, Some(needed - 1)).unwrap_err();
                assert_eq!((err.needed, err.available), (needed, needed - 1));
                assert!(err.to_string().contains(family.name()), "{err}");
            }
        }
    }

    #[test]
    fn the_family_of_a_mesh() {
        use ElementKind::*;
        assert_eq!(
            MeshFamily::of::<2>([Quad4, Tri3].into_iter()),
            MeshFamily::Planar
        );
        assert_eq!(
            MeshFamily::of::<3>([Tet4, Hex8].into_iter()),
            MeshFamily::Hexahedra
        );
        assert_eq!(
            MeshFamily::of::<3>([Tet4].into_iter()),
            MeshFamily::Tetrahedra
        );
    }
}
