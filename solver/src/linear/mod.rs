//! The linear solve of one Newton iteration, behind the [`LinearSolver`]
//! seam.
//!
//! Newton hands over the saddle-point system as coordinate triplets
//! (duplicates add) and a right-hand side. A solver works in three phases:
//!
//! 1. [`analyse`](LinearSolver::analyse) the triplet *index list* (the
//!    pattern). An implementation caches its symbolic analysis and redoes it
//!    only when the index list differs from the previous call's (compared
//!    entry by entry; [`crate::assembly`] keeps the order stable while the
//!    pairing is unchanged, so the analysis is reused across iterations);
//! 2. [`factor`](LinearSolver::factor) the values of the analysed pattern
//!    (in triplet order);
//! 3. [`solve`](LinearSolver::solve) with the last factorisation.
//!
//! [`LinearSolver::solve_system`] runs the three phases and then the checks
//! every implementation shares ([`check_solution`]): a non-finite solution or
//! one whose `|A| |x| / |b|` exceeds `1 /` [`NEAR_SINGULAR`] is reported as
//! singular, since a direct factorisation of a numerically singular matrix
//! may succeed with round-off pivots.
//!
//! Implementations: [`lu::SparseLu`] (faer's sparse LU; the default),
//! [`ldlt::SparseLdlt`] (faer's sparse symmetric LDL^T of the quasi-definite
//! system, refined against the assembled matrix, falling back to LU for a
//! solve it cannot do safely) and, with the `petsc` feature,
//! `petsc::PetscKrylov` (PETSc's Krylov methods and preconditioners, by
//! default FGMRES with a Schur-complement field split and algebraic
//! multigrid). Selected by [`LinearSolverKind`]; a new solver is a new file
//! here, a new variant there, and nothing in Newton changes.
//!
//! Newton also hands a solver the [`SystemLayout`] (which dof each
//! equation is, the nodes' coordinates: what algebraic multigrid needs) and,
//! before each solve, the relative residual it needs
//! ([`LinearSolver::set_forcing`]); a direct solver ignores both.

mod block;
pub mod fallback;
pub mod inertia;
pub mod ldlt;
pub mod lu;
#[cfg(feature = "petsc")]
pub mod petsc;
#[cfg(test)]
mod scene_tests;

use std::time::Duration;

pub use block::{Block, BlockPattern};
pub use fallback::{Fallback, FallbackReason, LuOutcome};
pub use inertia::{IndefiniteSolve, Inertia};
pub use ldlt::SparseLdlt;
pub use lu::SparseLu;

/// A solution with `|b|_inf < NEAR_SINGULAR |A|_max |x|_inf` counts as
/// numerically singular (its condition exceeds `1e13`: the pivots are
/// round-off, e.g. an unsupported rigid-body mode).
pub const NEAR_SINGULAR: f64 = 1e-13;

/// Why the linear system could not be solved.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LinearError {
    /// The pattern or the numeric factorisation failed (structurally or
    /// numerically singular), or the solution is not finite.
    #[error("singular system: {0}")]
    Singular(String),
    /// An iterative solve stopped without reaching its tolerance (what the
    /// library reported: its reason, iterations, residual).
    #[error("the iterative linear solve did not converge: {0}")]
    NotConverged(String),
    /// A call into PETSc failed (PETSc's message).
    #[error("{0}")]
    Petsc(String),
    /// PETSc refused the solver as configured: an unknown or unsupported
    /// option value, solver type or combination (PETSc's message). No
    /// shorter load step changes that, so Newton stops with it instead of
    /// cutting back ([`LinearError::cured_by_shorter_step`]).
    #[error("PETSc refused the solver's options: {0}")]
    Refused(String),
    /// A factorisation could not allocate its factor (for the LDLᵀ's LU
    /// fallback, within the memory available: [`fallback`]).
    #[error("out of memory: {0}")]
    OutOfMemory(String),
}

impl LinearError {
    /// Whether a shorter load step may solve where this failure happened: a
    /// singular or ill-conditioned system, a Krylov solve that did not
    /// converge, a failed PETSc call, a factor that did not fit may be the
    /// step's; a [`LinearError::Refused`] configuration is every step's.
    pub fn cured_by_shorter_step(&self) -> bool {
        !matches!(self, LinearError::Refused(_))
    }
}

/// What Newton's equations are, for a solver that needs more than the
/// matrix (algebraic multigrid: whole nodes, rigid-body modes).
#[derive(Debug, Clone, PartialEq)]
pub struct SystemLayout {
    /// The dimension `D` (dofs per node).
    pub dim: usize,
    /// The dof (`D node + component`) of each free equation `0..n_free`;
    /// equations from `free_dofs.len()` on are constraint rows.
    pub free_dofs: Vec<usize>,
    /// Every node's reference coordinates, node-major (`D` per node).
    pub coordinates: Vec<f64>,
    /// The rank that owns each node's equations across MPI ranks (see
    /// [`Ranks`]); empty on one rank.
    pub node_rank: Vec<usize>,
}

/// The MPI ranks a solve runs on: `size` processes launched together
/// (`mpiexec -n size`), this one `rank`. One rank unless the solver is
/// PETSc's and the launch had several.
///
/// Across ranks every rank holds the whole model and state; each assembles
/// its own elements and slave nodes' contact, the residual and the energy
/// are summed over the ranks ([`LinearSolver::sum_over_ranks`]) and the
/// linear solve runs on all of them, each owning a contiguous range of the
/// equations; every rank gets the whole correction, so every decision of
/// Newton's loop is the same on every rank.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Ranks {
    /// This process's rank, `0..size`.
    pub rank: usize,
    /// How many ranks the launch has.
    pub size: usize,
}

impl Ranks {
    /// One rank.
    pub const ONE: Ranks = Ranks { rank: 0, size: 1 };

    /// Whether this is rank 0 (which assembles the terms not split across
    /// the ranks and writes the output).
    pub fn is_root(&self) -> bool {
        self.rank == 0
    }
}

/// An iterative solver's work so far.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct KrylovCounts {
    /// The method and preconditioner (`fgmres/fieldsplit`).
    pub method: String,
    /// Solves.
    pub solves: usize,
    /// Iterations over all solves.
    pub iterations: usize,
    /// The most iterations of one solve.
    pub max_iterations: usize,
    /// The MPI ranks the solves ran across (0 and 1: one process).
    pub ranks: usize,
    /// The solve (counted from 1) after which the default's multigrid on
    /// the displacements gave way to the fallback's (the PETSc solver's
    /// module docs, "When the default does not converge"); `None` while it
    /// has not.
    pub switched_at: Option<usize>,
    /// The solve (counted from 1) after which the default's last fallback,
    /// a direct factorisation (MUMPS's LU of the whole system), took over
    /// (the same docs); `None` while it has not.
    pub direct_at: Option<usize>,
    /// MUMPS's working memory per process (MiB, `-mat_mumps_icntl_23`)
    /// the direct stage was given when the run reached it: read once then,
    /// since what its own factorisations hold afterwards is no longer
    /// available memory, and a bound read again would refuse the next
    /// factorisation of the same size; `None` before, or where the available
    /// memory is unknown (MUMPS's own estimate then).
    pub direct_memory_mib: Option<u64>,
}

/// A sparse direct solver for the Newton system, with the symbolic analysis
/// kept across calls while the pattern is unchanged (module docs).
pub trait LinearSolver: Send {
    /// Makes `(rows[k], cols[k])` the pattern of an `n x n` matrix: reuses the
    /// cached analysis when the index lists equal the previous call's,
    /// otherwise analyses them (counted in
    /// [`symbolic_factorisations`](Self::symbolic_factorisations) and
    /// [`symbolic_time`](Self::symbolic_time)). After an error no pattern is
    /// cached.
    fn analyse(&mut self, n: usize, rows: &[u32], cols: &[u32]) -> Result<(), LinearError>;

    /// Factorises the matrix with values `vals` (in the order of the
    /// analysed triplets).
    fn factor(&mut self, vals: &[f64]) -> Result<(), LinearError>;

    /// Solves with the factorisation of the last [`factor`](Self::factor)
    /// call, which it consumes (one solve per factorisation, so no factor is
    /// held between Newton iterations); `rhs` has the analysed size.
    fn solve(&mut self, rhs: &[f64]) -> Result<Vec<f64>, LinearError>;

    /// How many symbolic analyses were computed so far.
    fn symbolic_factorisations(&self) -> usize;

    /// Time spent in symbolic analysis so far.
    fn symbolic_time(&self) -> Duration;

    /// How many solves so far fell back to another factorisation because
    /// this one was not safe for them (0 for a solver without a fallback).
    fn fallbacks(&self) -> usize {
        0
    }

    /// Every solve so far that did not pass this solver's checks, with the
    /// check it failed and what the fallback did (empty for a solver
    /// without a fallback).
    fn fallback_log(&self) -> &[Fallback] {
        &[]
    }

    /// Every solve so far whose factorisation showed a stiffness indefinite
    /// where the active constraints leave it free ([`inertia`]; empty for a
    /// solver that does not count its pivots).
    fn indefinite_log(&self) -> &[IndefiniteSolve] {
        &[]
    }

    /// Nonzeros of the factor of the last analysed pattern (the fill): the
    /// lower triangle of `L`, diagonal included, for [`SparseLdlt`]. `None`
    /// when nothing is analysed yet or the factorisation does not expose its
    /// size (faer 0.24's sparse LU keeps `L` and `U` private, and their
    /// structure depends on the row pivots chosen in the numeric phase).
    fn factor_nonzeros(&self) -> Option<usize> {
        None
    }

    /// Tells the solver that equations `first..` are constraint rows
    /// (multipliers and ties, numbered after the free dofs; see
    /// [`crate::system::DofMap`]). A symmetric solver orders them after
    /// the unknowns they constrain; the default ignores the hint.
    fn set_constraints_from(&mut self, first: usize) {
        let _ = first;
    }

    /// Tells the solver what the equations are (module docs); the default
    /// passes on the first constraint row to
    /// [`set_constraints_from`](Self::set_constraints_from).
    fn set_layout(&mut self, layout: &SystemLayout) {
        self.set_constraints_from(layout.free_dofs.len());
    }

    /// The relative residual `|b - A x| / |b|` the next solve must reach
    /// (Newton's forcing term); a direct solver ignores it.
    fn set_forcing(&mut self, rtol: f64) {
        let _ = rtol;
    }

    /// An iterative solver's iteration counts; `None` for a direct one.
    fn krylov(&self) -> Option<KrylovCounts> {
        None
    }

    /// The ranks this solver spans ([`Ranks`]; one for every solver but
    /// PETSc's launched on several).
    fn ranks(&self) -> Ranks {
        Ranks::ONE
    }

    /// Every rank's `values` summed entry by entry, on every rank
    /// (collective across [`LinearSolver::ranks`]; nothing on one rank).
    fn sum_over_ranks(&self, values: &mut [f64]) -> Result<(), LinearError> {
        let _ = values;
        Ok(())
    }

    /// Every rank's `values`' largest entry by entry, on every rank
    /// (collective; nothing on one rank).
    fn max_over_ranks(&self, values: &mut [f64]) -> Result<(), LinearError> {
        let _ = values;
        Ok(())
    }

    /// The rank of each vertex of a graph of `n_total` vertices (the
    /// elements, adjacent when they share a facet), of which this rank
    /// gives the rows `first..first + row_ptr.len() - 1` (compressed rows,
    /// global columns; the ranks' rows in rank order; `weights`, each
    /// row's positive weight): a graph partition across the ranks, cutting
    /// few edges, the ranks' sums of weights balanced. Collective; every
    /// vertex on rank 0 on one rank.
    fn partition(
        &self,
        n_total: usize,
        row_ptr: &[i32],
        cols: &[i32],
        weights: &[i32],
    ) -> Result<Vec<usize>, LinearError> {
        let _ = (row_ptr, cols, weights);
        Ok(vec![0; n_total])
    }

    /// Whether Newton hands this solver the tangent's solid entries as a
    /// compressed [`Block`] beside the triplets
    /// ([`solve_system_with`](Self::solve_system_with)) rather than as
    /// triplets: for a solver whose own matrix is in compressed rows, the
    /// triplets (16 bytes per element entry) would be the largest buffer of
    /// a 3D run. `false` by default.
    fn takes_block(&self) -> bool {
        false
    }

    /// [`analyse`](Self::analyse) of the matrix whose entries are `block`'s
    /// and the triplets' `(rows[k], cols[k])` (duplicates add). By default
    /// the block's entries are handed to [`analyse`](Self::analyse) as
    /// triplets before the others.
    fn analyse_with_block(
        &mut self,
        n: usize,
        block: &BlockPattern,
        rows: &[u32],
        cols: &[u32],
    ) -> Result<(), LinearError> {
        let all_rows: Vec<u32> = block.entry_rows().chain(rows.iter().copied()).collect();
        let all_cols: Vec<u32> = block.cols().iter().chain(cols).copied().collect();
        self.analyse(n, &all_rows, &all_cols)
    }

    /// [`factor`](Self::factor) with the block `block` (over the last
    /// [`analyse_with_block`](Self::analyse_with_block)'s pattern) and the
    /// triplets' `vals`. By default the block's values go to
    /// [`factor`](Self::factor) before the triplets'.
    fn factor_with_block(&mut self, block: &Block, vals: &[f64]) -> Result<(), LinearError> {
        let all: Vec<f64> = block.values.iter().chain(vals).copied().collect();
        self.factor(&all)
    }

    /// [`solve_system`](Self::solve_system) of the matrix of `block` (if
    /// any) and the triplets: [`analyse_with_block`](Self::analyse_with_block),
    /// [`factor_with_block`](Self::factor_with_block), [`solve`](Self::solve),
    /// then [`check_solution`] with the largest contribution over the block
    /// and the triplets of all ranks.
    fn solve_system_with(
        &mut self,
        n: usize,
        block: Option<&Block>,
        (rows, cols, vals): (&[u32], &[u32], &[f64]),
        b: &[f64],
    ) -> Result<Vec<f64>, LinearError> {
        let Some(block) = block else {
            return self.solve_system(n, rows, cols, vals, b);
        };
        self.analyse_with_block(n, &block.pattern, rows, cols)?;
        self.factor_with_block(block, vals)?;
        let x = self.solve(b)?;
        let mut largest = [vals.iter().fold(block.max_abs, |m, v| m.max(v.abs()))];
        self.max_over_ranks(&mut largest)?;
        check_solution(&largest, b, x)
    }

    /// Solves `A x = b` for the `n x n` matrix given by the triplets
    /// `(rows[k], cols[k], vals[k])`: [`analyse`](Self::analyse),
    /// [`factor`](Self::factor), [`solve`](Self::solve), then
    /// [`check_solution`] with the largest entry over all ranks.
    fn solve_system(
        &mut self,
        n: usize,
        rows: &[u32],
        cols: &[u32],
        vals: &[f64],
        b: &[f64],
    ) -> Result<Vec<f64>, LinearError> {
        self.analyse(n, rows, cols)?;
        self.factor(vals)?;
        let x = self.solve(b)?;
        // across ranks each holds its own triplets: the largest of all
        let mut largest = [vals.iter().fold(0.0_f64, |m, v| m.max(v.abs()))];
        self.max_over_ranks(&mut largest)?;
        check_solution(&largest, b, x)
    }
}

/// Which [`LinearSolver`] a solve uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum LinearSolverKind {
    /// [`SparseLu`].
    #[default]
    Lu,
    /// [`SparseLdlt`].
    Ldlt,
    /// PETSc's Krylov solve (`petsc::PetscKrylov`); parsed only when the
    /// `petsc` feature is compiled in.
    Petsc,
}

impl LinearSolverKind {
    /// Every kind compiled in (the tests run each).
    #[cfg(not(feature = "petsc"))]
    pub const ALL: &[LinearSolverKind] = &[LinearSolverKind::Lu, LinearSolverKind::Ldlt];
    /// Every kind compiled in (the tests run each).
    #[cfg(feature = "petsc")]
    pub const ALL: &[LinearSolverKind] = &[
        LinearSolverKind::Lu,
        LinearSolverKind::Ldlt,
        LinearSolverKind::Petsc,
    ];

    /// A new solver of this kind with nothing cached; `options` are the
    /// PETSc options of [`LinearSolverKind::Petsc`] (ignored by the others).
    /// Without the `petsc` feature, `Petsc` (which no parse gives) builds
    /// the LDL^T.
    pub fn build(self, options: &str) -> Box<dyn LinearSolver> {
        let _ = options;
        match self {
            LinearSolverKind::Lu => Box::new(SparseLu::new()),
            LinearSolverKind::Ldlt => Box::new(SparseLdlt::new()),
            #[cfg(feature = "petsc")]
            LinearSolverKind::Petsc => petsc::build(options),
            #[cfg(not(feature = "petsc"))]
            LinearSolverKind::Petsc => Box::new(SparseLdlt::new()),
        }
    }

    /// Whether this solver is compiled in.
    pub fn available(self) -> bool {
        self != LinearSolverKind::Petsc || cfg!(feature = "petsc")
    }
}

impl std::fmt::Display for LinearSolverKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            LinearSolverKind::Lu => "lu",
            LinearSolverKind::Ldlt => "ldlt",
            LinearSolverKind::Petsc => "petsc",
        })
    }
}

/// Error parsing a [`LinearSolverKind`].
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ParseLinearSolverError {
    /// Not a solver's name.
    #[error("unknown linear solver `{0}` (expected `lu`, `ldlt` or `petsc`)")]
    Unknown(String),
    /// `petsc` in a build without the `petsc` feature.
    #[error(
        "the `petsc` linear solver is not compiled into this build: build with `--features petsc` \
         (PETSc >= 3.18 found by pkg-config; docs/petsc.md)"
    )]
    NotCompiled,
}

impl std::str::FromStr for LinearSolverKind {
    type Err = ParseLinearSolverError;
    /// `"lu"`, `"ldlt"` or (with the `petsc` feature) `"petsc"`.
    fn from_str(s: &str) -> Result<LinearSolverKind, ParseLinearSolverError> {
        let t = s.trim();
        let kind = [
            LinearSolverKind::Lu,
            LinearSolverKind::Ldlt,
            LinearSolverKind::Petsc,
        ]
        .into_iter()
        .find(|k| t.eq_ignore_ascii_case(&k.to_string()))
        .ok_or_else(|| ParseLinearSolverError::Unknown(s.to_owned()))?;
        if kind.available() {
            Ok(kind)
        } else {
            Err(ParseLinearSolverError::NotCompiled)
        }
    }
}

/// Refuses a solve that `kind` cannot do in this process, before any work:
/// only the `petsc` solver runs across MPI ranks; any other under
/// `mpiexec -n N` with `N > 1` would solve the whole model on every rank
/// and write the same files from each.
pub fn check_launch(kind: LinearSolverKind) -> Result<(), LinearError> {
    if kind == LinearSolverKind::Petsc {
        return Ok(());
    }
    match launched_ranks() {
        Some(n) if n > 1 => Err(LinearError::Petsc(format!(
            "this run was launched on {n} MPI ranks (mpiexec -n {n}), and only the petsc linear solver \
             runs across ranks (--linear petsc, in a build with the petsc feature); the {kind} solver \
             would solve the whole scene on every rank: run it without mpiexec"
        ))),
        _ => Ok(()),
    }
}

/// How many processes the MPI launcher started together, from its
/// environment (Open MPI's `OMPI_COMM_WORLD_SIZE`, MPICH's and Intel MPI's
/// `PMI_SIZE`); `None` outside a launch. Read without initialising MPI, so
/// a build without the `petsc` feature knows it too.
pub fn launched_ranks() -> Option<usize> {
    ["OMPI_COMM_WORLD_SIZE", "PMI_SIZE"]
        .iter()
        .find_map(|v| std::env::var(v).ok()?.trim().parse().ok())
}

/// This process's rank for `kind`'s solve: PETSc's rank in its world
/// (initialising MPI), 0 for the others (which refuse a launch on several
/// ranks, [`check_launch`]).
pub fn launch_rank(kind: LinearSolverKind) -> Result<usize, LinearError> {
    #[cfg(feature = "petsc")]
    if kind == LinearSolverKind::Petsc {
        return petsc::world_rank();
    }
    let _ = kind;
    Ok(0)
}

/// The checks shared by every solver: `x` is returned when it is finite and
/// `|A| |x| / |b|` (an estimate of the condition number seen by this
/// right-hand side) stays below `1 /` [`NEAR_SINGULAR`].
pub fn check_solution(vals: &[f64], b: &[f64], out: Vec<f64>) -> Result<Vec<f64>, LinearError> {
    if let Some(i) = out.iter().position(|v| !v.is_finite()) {
        return Err(LinearError::Singular(format!(
            "numerically singular (solution component {i} is {})",
            out[i]
        )));
    }
    // |A| |x| / |b| estimates the condition number seen by this right-hand
    // side; beyond 1/NEAR_SINGULAR the pivots are round-off noise
    let a_max = vals.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let x_max = out.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let b_max = b.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    if b_max < NEAR_SINGULAR * a_max * x_max {
        return Err(LinearError::Singular(format!(
            "numerically singular (|A| |x| / |b| = {:.1e} exceeds {:.0e})",
            a_max * x_max / b_max,
            1.0 / NEAR_SINGULAR
        )));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A saddle-point system with a zero block, solved twice with the same
    /// pattern (one symbolic factorisation), and a singular one rejected.
    #[test]
    fn saddle_point_and_reuse() {
        for &kind in LinearSolverKind::ALL {
            // [2 1 1; 1 3 0; 1 0 0] x = [1, 2, 3]
            let rows = [0, 0, 0, 1, 1, 2, 2];
            let cols = [0, 1, 2, 0, 1, 0, 2];
            let vals = [2.0, 1.0, 1.0, 1.0, 3.0, 1.0, 0.0];
            let mut s = kind.build("");
            let x = s
                .solve_system(3, &rows, &cols, &vals, &[1.0, 2.0, 3.0])
                .unwrap();
            let analyses = s.symbolic_factorisations();
            assert!((x[0] - 3.0).abs() < 1e-12);
            assert!((x[1] + 1.0 / 3.0).abs() < 1e-12);
            assert!((2.0 * x[0] + x[1] + x[2] - 1.0).abs() < 1e-12);
            let vals2 = [4.0, 1.0, 1.0, 1.0, 3.0, 1.0, 0.0];
            let y = s
                .solve_system(3, &rows, &cols, &vals2, &[1.0, 2.0, 3.0])
                .unwrap();
            assert!((4.0 * y[0] + y[1] + y[2] - 1.0).abs() < 1e-12);
            // the same pattern is not analysed again (an LDL^T falling back
            // to LU has analysed both on the first solve)
            assert_eq!(s.symbolic_factorisations(), analyses);
            let singular = [1.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0];
            assert!(
                s.solve_system(3, &rows, &cols, &singular, &[1.0, 2.0, 3.0])
                    .is_err()
            );
            assert_eq!(kind.to_string().parse::<LinearSolverKind>(), Ok(kind));
        }
    }

    /// Every solver solves the matrix of a block beside triplets as that
    /// of the same contributions in triplets (to round-off: a solver
    /// without a block of its own gets the block's sums as triplets), and
    /// the block's largest contribution counts in the singularity check.
    #[test]
    fn a_block_beside_triplets_is_their_matrix() {
        use crate::ids::EquationIndex;
        // [2 1 1; 1 3 0; 1 0 0] x = [1, 2, 3]: the 2 x 2 block of the first
        // two rows in the block, the constraint row and column as triplets
        let pattern =
            std::sync::Arc::new(BlockPattern::from_rows(&[vec![0, 1], vec![0, 1]]).unwrap());
        for &kind in LinearSolverKind::ALL {
            let mut block = Block::new(pattern.clone());
            for (r, c, v) in [
                (0, 0, 1.5),
                (0, 1, 1.0),
                (1, 0, 1.0),
                (1, 1, 3.0),
                (0, 0, 0.5),
            ] {
                assert!(block.add(EquationIndex::new(r), EquationIndex::new(c), v));
            }
            let (rows, cols, vals) = ([0, 2, 2], [2, 0, 2], [1.0, 1.0, 0.0]);
            let mut s = kind.build("");
            let x = s
                .solve_system_with(3, Some(&block), (&rows, &cols, &vals), &[1.0, 2.0, 3.0])
                .unwrap();
            assert!((x[0] - 3.0).abs() < 1e-12, "{kind}: {x:?}");
            assert!((x[1] + 1.0 / 3.0).abs() < 1e-12, "{kind}: {x:?}");
            assert!(
                (2.0 * x[0] + x[1] + x[2] - 1.0).abs() < 1e-12,
                "{kind}: {x:?}"
            );
            // a block of a huge entry makes the same solution numerically
            // singular
            block.max_abs = 1e20;
            assert!(
                s.solve_system_with(3, Some(&block), (&rows, &cols, &vals), &[1.0, 2.0, 3.0])
                    .is_err(),
                "{kind}"
            );
        }
    }

    /// The phases in the wrong order are errors, not panics: no pattern to
    /// factor, no factorisation to solve with (one solve per factorisation).
    #[test]
    fn phases_out_of_order_are_errors() {
        for &kind in LinearSolverKind::ALL {
            let mut s = kind.build("");
            assert!(s.factor(&[1.0]).is_err());
            assert!(s.solve(&[1.0]).is_err());
            s.analyse(1, &[0], &[0]).unwrap();
            s.factor(&[2.0]).unwrap();
            assert_eq!(s.solve(&[1.0]), Ok(vec![0.5]));
            assert!(s.solve(&[1.0]).is_err());
        }
        assert!("qr".parse::<LinearSolverKind>().is_err());
        assert_eq!(
            "petsc".parse::<LinearSolverKind>().is_ok(),
            cfg!(feature = "petsc")
        );
    }
}
