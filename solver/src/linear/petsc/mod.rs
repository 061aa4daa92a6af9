//! PETSc's Krylov solvers and preconditioners behind [`LinearSolver`]
//! (feature `petsc`; `[newton] linear = "petsc"`, `--linear petsc`).
//!
//! # The system PETSc sees
//!
//! Newton's system has the free displacement dofs first (in dof order),
//! then the constraint rows (multipliers, node ties). Algebraic multigrid
//! on elasticity wants whole nodes (block size = dimension) and the
//! rigid-body modes of their coordinates, so the system is re-numbered from
//! the [`SystemLayout`]: equation `i < n_free` becomes its dof `D node +
//! component`, a prescribed dof becomes a decoupled row `d u = 0` (`d` the
//! mean absolute diagonal of the free block, so that it does not disturb the
//! multigrid's scaling), and constraint `k` becomes `D nodes + k`:
//!
//! ```text
//! [ K   G^T ] [du]   [r_u]      field "u":      D nodes equations, block size D,
//! [ G   C   ] [dl] = [r_l]                      near-null space: rigid-body modes
//!                               field "lambda": the constraint rows
//! ```
//!
//! # The default: FGMRES on the saddle point, Schur-complement field split
//!
//! [`DEFAULT_OPTIONS`]: a right-preconditioned FGMRES (its residual is the
//! true one; restarted every 30 iterations) preconditioned by PCFIELDSPLIT's
//! upper block-triangular Schur factorisation
//!
//! ```text
//! P^-1 = [ K^-1  0 ] [ I  -G^T ] [ I  0    ]
//!        [ 0     I ] [ 0   I   ] [ 0  S^-1 ],   S ~ Sp = C - G diag(K)^-1 G^T  (`selfp`)
//! ```
//!
//! with `K^-1` one V-cycle of aggregation multigrid (GAMG, given the
//! rigid-body near-null space; plain aggregation, its tentative
//! prolongator unsmoothed: on the 3D scaling scene this takes less memory
//! than smoothed aggregation in about the same time, most across ranks,
//! docs/petsc.md) and `Sp^-1` block Jacobi with ILU(0) (one block per
//! rank). A system without constraint rows (no contact) is solved by FGMRES
//! with GAMG on the displacements. Why this route (and not the condensation of the
//! multipliers) is in docs/petsc.md, with the measurements.
//!
//! # When the default does not converge
//!
//! GAMG's aggregation (smoothed or plain) does not converge on every mesh
//! (the graded hexahedral 3D Hertz mesh stalls it), and no multigrid
//! V-cycle here converges on slender plates in persistent contact bending
//! along their length (the paper scenes, docs/petsc.md). The default
//! therefore climbs a ladder ([`Stage`]): a solve it does not converge is
//! retried from a solver rebuilt with the next stage's options after the
//! defaults, and the run keeps that stage from then on:
//!
//! 1. [`FALLBACK_OPTIONS`]: BoomerAMG (hypre's classical algebraic
//!    multigrid) on the displacements ([`KrylovCounts::switched_at`]);
//! 2. [`DIRECT_OPTIONS`]: MUMPS's LU of the whole system, FGMRES then
//!    taking one iteration ([`KrylovCounts::direct_at`]), its working
//!    memory per process bounded by `-mat_mumps_icntl_23` at 90 % of
//!    `MemAvailable` shared by this machine's ranks ([`direct_options`]),
//!    read once, when the run reaches the stage
//!    ([`KrylovCounts::direct_memory_mib`]; read at every solve, the memory
//!    the first factorisation holds would refuse the second): a
//!    factorisation that would need more fails at its start, as a solve
//!    that did not converge, instead of the system killing the process.
//!
//! `gapsim run` prints where each switch happened. A solve that has a
//! next stage also ends early when it stalls ([`STALL_WINDOW`]: its
//! residual has not fallen by 10 % over 100 iterations), instead of running
//! to `-ksp_max_it` before the retry. A user who names a `pc_type` (in the
//! solver's options or `PETSC_OPTIONS`) chose the preconditioner: nothing
//! is retried and no stall test is installed. A solve that does not
//! converge on the last stage is the error, saying which stages it went
//! through.
//!
//! # Options and tolerance
//!
//! Options are applied in this order, a later one overriding an earlier:
//! the defaults, the `PETSC_OPTIONS` environment, the solver's own string
//! (`[newton] petsc_options`, then `--petsc-options`). They are installed
//! into PETSc's options database before every set-up and solve, so two
//! solvers in one process (tests) do not see each other's. Each solve stops
//! at the relative residual Newton asks for ([`LinearSolver::set_forcing`]);
//! a solve that does not converge is a [`LinearError::NotConverged`] with
//! PETSc's reason.

mod ffi;
mod fill;
pub mod objects;
pub mod ranks;

use std::time::{Duration, Instant};

use fill::Fill;
use objects::{Comm, IndexSet, Ksp, Matrix, NearNullSpace, PetscError, Serial, Vector, serial};

use super::{Block, BlockPattern, KrylovCounts, LinearError, LinearSolver, SystemLayout};

/// The Krylov method and preconditioner of a system with constraint rows
/// (module docs). `-ksp_max_it` bounds one solve.
pub const DEFAULT_OPTIONS: &str = "-ksp_type fgmres -ksp_gmres_restart 30 -ksp_max_it 1000 \
     -pc_type fieldsplit -pc_fieldsplit_type schur -pc_fieldsplit_schur_fact_type upper \
     -pc_fieldsplit_schur_precondition selfp \
     -fieldsplit_u_ksp_type preonly -fieldsplit_u_pc_type gamg \
     -fieldsplit_u_pc_gamg_agg_nsmooths 0 \
     -fieldsplit_lambda_ksp_type preonly -fieldsplit_lambda_pc_type bjacobi";

/// The defaults of a system without constraint rows.
pub const DEFAULT_OPTIONS_UNCONSTRAINED: &str =
    "-ksp_type fgmres -ksp_gmres_restart 100 -ksp_max_it 1000 -pc_type gamg";

/// The first stage after the defaults (module docs, "When the default
/// does not converge"): BoomerAMG (hypre's classical algebraic multigrid)
/// on the displacements instead of GAMG. Not the default: on the 3D scaling
/// scene it takes more memory than GAMG (docs/petsc.md).
pub const FALLBACK_OPTIONS: &str = "-fieldsplit_u_pc_type hypre";

/// [`FALLBACK_OPTIONS`] of a system without constraint rows.
pub const FALLBACK_OPTIONS_UNCONSTRAINED: &str = "-pc_type hypre";

/// The last stage (module docs): MUMPS's LU of the whole system, with or
/// without constraint rows; [`direct_options`] adds its memory bound.
pub const DIRECT_OPTIONS: &str = "-pc_type lu -pc_factor_mat_solver_type mumps";

/// The share of `MemAvailable` MUMPS's working memory may take on this
/// machine (module docs), split among its ranks.
pub const DIRECT_MEMORY_SHARE: f64 = 0.9;

/// The default's stages (module docs, "When the default does not
/// converge"), in the order a run climbs them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Stage {
    /// [`DEFAULT_OPTIONS`] (GAMG on the displacements).
    Gamg,
    /// [`FALLBACK_OPTIONS`] (BoomerAMG on the displacements).
    BoomerAmg,
    /// [`DIRECT_OPTIONS`] (MUMPS's LU).
    Direct,
}

impl Stage {
    /// The stage a run is on after the switches in `counts`.
    fn of(counts: &KrylovCounts) -> Stage {
        match (counts.switched_at, counts.direct_at) {
            (_, Some(_)) => Stage::Direct,
            (Some(_), None) => Stage::BoomerAmg,
            (None, None) => Stage::Gamg,
        }
    }

    /// The stage after this one.
    fn next(self) -> Option<Stage> {
        match self {
            Stage::Gamg => Some(Stage::BoomerAmg),
            Stage::BoomerAmg => Some(Stage::Direct),
            Stage::Direct => None,
        }
    }

    /// What the stage adds after the defaults of a system with or without
    /// constraint rows, the direct stage's memory bound from `counts`.
    fn options(self, constrained: bool, counts: &KrylovCounts) -> String {
        match (self, constrained) {
            (Stage::Gamg, _) => String::new(),
            (Stage::BoomerAmg, true) => FALLBACK_OPTIONS.into(),
            (Stage::BoomerAmg, false) => FALLBACK_OPTIONS_UNCONSTRAINED.into(),
            (Stage::Direct, _) => direct_options(counts.direct_memory_mib),
        }
    }

    /// Records in `counts` that the run switched to this stage after solve
    /// `counts.solves`; the direct stage's memory bound is read here, once,
    /// for a machine shared by `ranks` processes
    /// ([`KrylovCounts::direct_memory_mib`]).
    fn record(self, counts: &mut KrylovCounts, ranks: usize) {
        match self {
            Stage::Gamg => {}
            Stage::BoomerAmg => counts.switched_at = Some(counts.solves),
            Stage::Direct => {
                counts.direct_at = Some(counts.solves);
                counts.direct_memory_mib = direct_bound(crate::meminfo::available(), ranks);
            }
        }
    }

    /// The stage's preconditioner, as an error names it.
    fn name(self) -> &'static str {
        match self {
            Stage::Gamg => "GAMG on the displacements",
            Stage::BoomerAmg => "BoomerAMG on the displacements",
            Stage::Direct => "MUMPS's LU",
        }
    }
}

/// [`DIRECT_OPTIONS`] with MUMPS's working memory per process
/// (`-mat_mumps_icntl_23`) bounded at `bound` MiB ([`direct_bound`]);
/// unbounded (MUMPS's own estimate) without one.
fn direct_options(bound: Option<u64>) -> String {
    match bound {
        Some(mib) => format!("{DIRECT_OPTIONS} -mat_mumps_icntl_23 {mib}"),
        None => DIRECT_OPTIONS.into(),
    }
}

/// MUMPS's working memory per process, MiB: [`DIRECT_MEMORY_SHARE`] of
/// `available` bytes split among `ranks` processes (at least 1 MiB).
fn direct_bound(available: Option<u64>, ranks: usize) -> Option<u64> {
    available.map(|bytes| {
        let share = DIRECT_MEMORY_SHARE * bytes as f64 / ranks.max(1) as f64;
        ((share / (1024.0 * 1024.0)) as u64).max(1)
    })
}

/// The stall test of a solve that has a next stage (module docs, "When
/// the default does not converge"): it ends when its residual norm has not fallen below
/// [`STALL_FACTOR`] times its value [`STALL_WINDOW`] iterations earlier.
pub const STALL_WINDOW: usize = 100;
/// See [`STALL_WINDOW`].
pub const STALL_FACTOR: f64 = 0.9;

/// This process's rank in PETSc's world (initialising MPI and PETSc).
pub fn world_rank() -> Result<usize, LinearError> {
    Ok(serial()?.world_rank()?)
}

/// The PETSc solver of options `options`: [`PetscKrylov`] on one rank,
/// [`ranks::PetscRanks`] across several (a launch under `mpiexec -n N`).
/// A PETSc that cannot start gives the one-rank solver, which reports why
/// at its first call.
pub fn build(options: &str) -> Box<dyn LinearSolver> {
    let ranks = serial().and_then(|s| {
        Ok(super::Ranks {
            rank: s.world_rank()?,
            size: s.world_size()?,
        })
    });
    match ranks {
        Ok(r) if r.size > 1 => Box::new(ranks::PetscRanks::new(options, r)),
        _ => Box::new(PetscKrylov::new(options)),
    }
}

/// The options string installed for a system with or without constraint
/// rows, with the solver's own `options` (module docs, "Options and
/// tolerance"), on the default's stage `counts` has reached (its options
/// after the defaults).
fn options_for(options: &str, constrained: bool, counts: &KrylovCounts) -> String {
    let defaults = if constrained {
        DEFAULT_OPTIONS
    } else {
        DEFAULT_OPTIONS_UNCONSTRAINED
    };
    let stage = Stage::of(counts).options(constrained, counts);
    let env = std::env::var("PETSC_OPTIONS").unwrap_or_default();
    format!("{defaults} {stage} {env} {options}")
}

/// Whether the preconditioner is the default's: neither the solver's
/// `options` nor `PETSC_OPTIONS` name a `pc_type`.
fn default_preconditioner(options: &str) -> bool {
    let env = std::env::var("PETSC_OPTIONS").unwrap_or_default();
    !(options.contains("pc_type") || env.contains("pc_type"))
}

/// The stage a solve that did not converge is retried on: the next one,
/// when the preconditioner is the default's; `None` otherwise.
fn retry_stage(options: &str, counts: &KrylovCounts) -> Option<Stage> {
    Stage::of(counts)
        .next()
        .filter(|_| default_preconditioner(options))
}

/// The [`LinearSolver`] methods that take the matrix, for a solver with
/// `analyse_parts` and `factor_parts` (the block optional) and
/// `solve_cached`: the block taken, the triplets alone as no block; after
/// a failed PETSc call in a factorisation or a solve the objects are
/// dropped (`pattern_reset`, [`reset_if_poisoned`]).
macro_rules! through_parts {
    () => {
        fn solve(&mut self, rhs: &[f64]) -> Result<Vec<f64>, LinearError> {
            reset_if_poisoned(self.solve_cached(rhs), || self.pattern_reset())
        }

        fn analyse(&mut self, n: usize, rows: &[u32], cols: &[u32]) -> Result<(), LinearError> {
            self.analyse_parts(n, None, rows, cols)
        }

        fn factor(&mut self, vals: &[f64]) -> Result<(), LinearError> {
            reset_if_poisoned(self.factor_parts(None, vals), || self.pattern_reset())
        }

        fn takes_block(&self) -> bool {
            true
        }

        fn analyse_with_block(
            &mut self,
            n: usize,
            block: &BlockPattern,
            rows: &[u32],
            cols: &[u32],
        ) -> Result<(), LinearError> {
            self.analyse_parts(n, Some(block), rows, cols)
        }

        fn factor_with_block(&mut self, block: &Block, vals: &[f64]) -> Result<(), LinearError> {
            reset_if_poisoned(self.factor_parts(Some(block), vals), || {
                self.pattern_reset()
            })
        }
    };
}
use through_parts;

/// What PETSc said of a Krylov solve that ended without converging.
fn not_converged(method: &str, out: &objects::KrylovOutcome, rtol: f64) -> String {
    let what = if out.stalled {
        format!(
            "stalled (its residual fell by less than {:.0} % over {STALL_WINDOW} iterations)",
            100.0 * (1.0 - STALL_FACTOR)
        )
    } else {
        format!("reported {}", out.reason)
    };
    format!(
        "PETSc's {method} {what} after {} iterations (residual {:.3e}, relative tolerance {rtol:.1e})",
        out.iterations, out.residual
    )
}

/// What the error of a solve that converged on no stage suggests.
const NOT_CONVERGED_HINT: &str = "other PETSc options (--petsc-options, docs/petsc.md) \
     or --linear ldlt may solve it";

/// PETSc's error codes of a configuration it refuses, whatever the matrix:
/// no support for the operation (`PETSC_ERR_SUP`), a wrong, out-of-range or
/// incompatible argument (`PETSC_ERR_ARG_WRONG`, `_OUTOFRANGE`,
/// `_INCOMP`), an unknown option value (`PETSC_ERR_USER`, as
/// `PetscOptionsGetEList` reports it) or type name
/// (`PETSC_ERR_ARG_UNKNOWN_TYPE`), no factorisation package
/// (`PETSC_ERR_MISSING_FACTOR`), options that may not change
/// (`PETSC_ERR_OPT_OVERWRITE`), a solver that does not run on this many
/// ranks (`PETSC_ERR_WRONG_MPI_SIZE`), incorrect user input
/// (`PETSC_ERR_USER_INPUT`): petscerror.h of PETSc 3.18.
const REFUSED_CODES: [i32; 10] = [56, 62, 63, 75, 83, 86, 92, 93, 94, 95];

impl From<PetscError> for LinearError {
    fn from(e: PetscError) -> LinearError {
        if REFUSED_CODES.contains(&e.code) {
            LinearError::Refused(e.to_string())
        } else {
            LinearError::Petsc(e.to_string())
        }
    }
}

/// Whether `e` came from a failed PETSc call. PETSc's error unwinds past
/// its own clean-up and may leave the Krylov solver mid-solve: the next
/// solve then fails with "Cannot embed PCPreSolve() more than twice"
/// whatever the matrix. The objects are therefore dropped after such a
/// failure, and the next analysis builds them afresh.
fn poisoned(e: &LinearError) -> bool {
    matches!(e, LinearError::Petsc(_) | LinearError::Refused(_))
}

/// `out`, after `reset` (dropping the objects) when it is a failed PETSc
/// call ([`poisoned`]).
fn reset_if_poisoned<T>(
    out: Result<T, LinearError>,
    reset: impl FnOnce(),
) -> Result<T, LinearError> {
    if out.as_ref().is_err_and(poisoned) {
        reset();
    }
    out
}

/// Where each of Newton's equations sits in PETSc's numbering.
struct Numbering {
    /// PETSc's row of each of Newton's equations.
    rows: Vec<usize>,
    /// PETSc's size.
    n: usize,
    /// The displacement rows (`D nodes`; `first` when no layout was given).
    n_u: usize,
    /// PETSc's rows of the prescribed dofs (decoupled).
    decoupled: Vec<usize>,
    /// Block size of the displacement rows.
    dim: usize,
}

impl Numbering {
    fn new(
        n: usize,
        layout: Option<&SystemLayout>,
        first: usize,
    ) -> Result<Numbering, LinearError> {
        let Some(l) = layout else {
            // no layout: Newton's numbering, the constraint rows from `first`
            return Ok(Numbering {
                rows: (0..n).collect(),
                n,
                n_u: first.min(n),
                decoupled: vec![],
                dim: 1,
            });
        };
        let n_free = l.free_dofs.len();
        let n_u = l.coordinates.len();
        if n < n_free || l.dim == 0 || n_u % l.dim != 0 {
            return Err(LinearError::Petsc(format!(
                "the layout ({n_free} free dofs of {n_u} coordinates in {}D) does not fit {n} equations",
                l.dim
            )));
        }
        let (rows, free) = petsc_rows(n, l, |dof| dof)?;
        Ok(Numbering {
            rows,
            n: n_u + n - n_free,
            n_u,
            decoupled: (0..n_u).filter(|&d| !free[d]).collect(),
            dim: l.dim,
        })
    }
}

/// PETSc's objects of one pattern. Declared so that the solver goes before
/// the matrix and the splits it refers to.
struct Objects {
    ksp: Ksp,
    /// The field split's `u` and `lambda` (empty unless PCFIELDSPLIT).
    splits: Vec<IndexSet>,
    _near_null: Option<NearNullSpace>,
    a: Matrix,
    b: Vector,
    x: Vector,
    comm: Comm,
}

impl Objects {
    /// The processes this solver's objects span.
    fn ranks(&self, s: &Serial) -> Result<usize, LinearError> {
        Ok(match self.comm {
            Comm::One => 1,
            Comm::World => s.world_size()?,
        })
    }

    /// Solves with right-hand side `b` (this rank's part) to the relative
    /// residual `rtol` under the solver's `options`, counting into `counts`;
    /// the solution is left in `x`. A solve that does not converge is
    /// retried on the default's next stage, from a solver rebuilt with its
    /// options, which the run keeps (module docs, "When the default does not
    /// converge"); a solve that converges on no stage left, or that has no
    /// retry (a preconditioner of the user's), is the error naming PETSc's
    /// reason on each stage it tried.
    fn solve(
        &mut self,
        s: &Serial,
        b: &[f64],
        rtol: f64,
        (options, constrained): (&str, bool),
        counts: &mut KrylovCounts,
    ) -> Result<(), LinearError> {
        self.b.set(s, b)?;
        let installed = options_for(options, constrained, counts);
        let Some(mut failed) = self.run(s, rtol, &installed, counts)? else {
            return Ok(());
        };
        let mut tried = vec![];
        while let Some(stage) = retry_stage(options, counts) {
            tried.push(format!("{failed} with {}", Stage::of(counts).name()));
            stage.record(counts, self.ranks(s)?);
            let installed = options_for(options, constrained, counts);
            s.replace_options(&installed)?;
            self.ksp = Ksp::new(s, self.comm, &self.a)?;
            if retry_stage(options, counts).is_some() {
                self.ksp.watch_stall(s, STALL_WINDOW, STALL_FACTOR)?;
            }
            if let [u, lambda] = &self.splits[..]
                && self.ksp.is_fieldsplit(s)?
            {
                self.ksp.add_split(s, "u", u)?;
                self.ksp.add_split(s, "lambda", lambda)?;
            }
            self.ksp.set_up(s)?;
            match self.run(s, rtol, &installed, counts)? {
                None => return Ok(()),
                Some(e) => failed = e,
            }
        }
        let stage = Stage::of(counts);
        if default_preconditioner(options) {
            let since = match (tried.is_empty(), stage) {
                (false, _) | (true, Stage::Gamg) => String::new(),
                (true, Stage::BoomerAmg | Stage::Direct) => format!(
                    ", the default's since solve {}",
                    counts.direct_at.or(counts.switched_at).unwrap_or(0)
                ),
            };
            let env = std::env::var("PETSC_OPTIONS").unwrap_or_default();
            let own_bound = options.contains("icntl_23") || env.contains("icntl_23");
            let bound = match (stage, counts.direct_memory_mib) {
                (Stage::Direct, Some(mib)) if !own_bound => format!(
                    ", its working memory bounded at {mib} MiB per process \
                     (-mat_mumps_icntl_23)"
                ),
                _ => String::new(),
            };
            tried.push(format!("{failed} with {}{since}{bound}", stage.name()));
        } else {
            tried.push(failed);
        }
        Err(LinearError::NotConverged(format!(
            "{}; {NOT_CONVERGED_HINT}",
            tried.join("; retried: ")
        )))
    }

    /// One Krylov solve of `b` into `x` under `options`, counted; what
    /// PETSc said when it did not converge.
    fn run(
        &mut self,
        s: &Serial,
        rtol: f64,
        options: &str,
        counts: &mut KrylovCounts,
    ) -> Result<Option<String>, LinearError> {
        self.ksp.set_rtol(s, rtol)?;
        s.replace_options(options)?;
        let out = self.ksp.solve(s, &self.b, &mut self.x)?;
        counts.solves += 1;
        counts.iterations += out.iterations;
        counts.max_iterations = counts.max_iterations.max(out.iterations);
        if counts.method.is_empty() {
            counts.method = self.ksp.describe(s)?;
        }
        if out.converged {
            return Ok(None);
        }
        Ok(Some(not_converged(&self.ksp.describe(s)?, &out, rtol)))
    }
}

/// PETSc's row of each of `n` Newton equations of the layout `l`: a free
/// dof's `petsc_dof(dof)`, constraint `k` row `D nodes + k`; and which dofs
/// are free. A dof listed twice or out of range is refused.
fn petsc_rows(
    n: usize,
    l: &SystemLayout,
    petsc_dof: impl Fn(usize) -> usize,
) -> Result<(Vec<usize>, Vec<bool>), LinearError> {
    let (n_free, n_u) = (l.free_dofs.len(), l.coordinates.len());
    let mut rows = Vec::with_capacity(n);
    let mut free = vec![false; n_u];
    for &dof in &l.free_dofs {
        if dof >= n_u || free[dof] {
            return Err(LinearError::Petsc(format!(
                "dof {dof} listed twice or out of range"
            )));
        }
        free[dof] = true;
        rows.push(petsc_dof(dof));
    }
    rows.extend((n_free..n).map(|i| n_u + i - n_free));
    Ok((rows, free))
}

/// The cached pattern: the numbering, what fills PETSc's matrix, PETSc's
/// objects.
struct Pattern {
    numbering: Numbering,
    fill: Fill,
    objects: Objects,
}

/// The compressed rows of PETSc's matrix from Newton's triplets (and the
/// decoupled rows' diagonals), sorted columns in each row, duplicates
/// merged; and each triplet's entry. A counting sort by row, then each
/// row's few entries sorted by column: linear in the triplets, with 4 bytes
/// of work space per triplet.
fn compress(nb: &Numbering, rows: &[u32], cols: &[u32]) -> Result<Compressed, LinearError> {
    let m = rows.len();
    let total = m + nb.decoupled.len();
    let too_big = || LinearError::Petsc(format!("{total} triplets exceed the 32-bit index range"));
    if total >= u32::MAX as usize {
        return Err(too_big());
    }
    let at = |t: usize| -> (usize, usize) {
        if t < m {
            (nb.rows[rows[t] as usize], nb.rows[cols[t] as usize])
        } else {
            let d = nb.decoupled[t - m];
            (d, d)
        }
    };
    let mut start = vec![0usize; nb.n + 1];
    for t in 0..total {
        start[at(t).0 + 1] += 1;
    }
    for i in 0..nb.n {
        start[i + 1] += start[i];
    }
    let mut order = vec![0u32; total];
    let mut next = start.clone();
    for t in 0..total {
        let r = at(t).0;
        order[next[r]] = t as u32;
        next[r] += 1;
    }
    drop(next);
    let mut row_ptr = Vec::with_capacity(nb.n + 1);
    let mut pcols: Vec<i32> = Vec::new();
    let mut slot = vec![0u32; total];
    row_ptr.push(0i32);
    for r in 0..nb.n {
        let bucket = &mut order[start[r]..start[r + 1]];
        bucket.sort_unstable_by_key(|&t| at(t as usize).1);
        let mut last = usize::MAX;
        for &t in bucket.iter() {
            let c = at(t as usize).1;
            if c != last {
                pcols.push(i32::try_from(c).map_err(|_| too_big())?);
                last = c;
            }
            slot[t as usize] = (pcols.len() - 1) as u32;
        }
        row_ptr.push(i32::try_from(pcols.len()).map_err(|_| too_big())?);
    }
    Ok(Compressed {
        row_ptr,
        cols: pcols,
        slot,
    })
}

/// [`compress`]'s result: PETSc's row pointers and columns, each triplet's
/// entry.
struct Compressed {
    row_ptr: Vec<i32>,
    cols: Vec<i32>,
    slot: Vec<u32>,
}

/// PETSc's Krylov solve of the Newton system (module docs).
pub struct PetscKrylov {
    options: String,
    layout: Option<SystemLayout>,
    first_constraint: Option<usize>,
    pattern: Option<Pattern>,
    factored: bool,
    rtol: f64,
    counts: KrylovCounts,
    symbolic_factorisations: usize,
    symbolic_time: Duration,
}

// SAFETY: PETSc's objects are only touched under `serial()`'s process-wide
// guard (every method below takes it first, `Drop` too), so moving the owner
// to another thread is sound.
unsafe impl Send for PetscKrylov {}

impl PetscKrylov {
    /// A solver with PETSc options `options` (PETSc's syntax; after the
    /// defaults and `PETSC_OPTIONS`) and nothing cached.
    pub fn new(options: &str) -> PetscKrylov {
        PetscKrylov {
            options: options.to_owned(),
            layout: None,
            first_constraint: None,
            pattern: None,
            factored: false,
            rtol: 1e-8,
            counts: KrylovCounts::default(),
            symbolic_factorisations: 0,
            symbolic_time: Duration::ZERO,
        }
    }

    /// The options string installed for a system with or without constraint
    /// rows (module docs, "Options and tolerance").
    fn options_for(&self, constrained: bool) -> String {
        options_for(&self.options, constrained, &self.counts)
    }

    /// The options of the cached pattern's system.
    fn pattern_options(&self) -> String {
        let constrained = self
            .pattern
            .as_ref()
            .is_some_and(|p| p.numbering.n > p.numbering.n_u);
        self.options_for(constrained)
    }

    fn build(
        &self,
        s: &Serial,
        n: usize,
        block: Option<&BlockPattern>,
        (rows, cols): (&[u32], &[u32]),
    ) -> Result<Pattern, LinearError> {
        let first = self
            .layout
            .as_ref()
            .map(|l| l.free_dofs.len())
            .or(self.first_constraint)
            .unwrap_or(n);
        let numbering = Numbering::new(n, self.layout.as_ref(), first)?;
        let n_free = first.min(n);
        let fill = Fill::new(&numbering, n_free, block, rows, cols)?;
        // every row's entries (all in this rank's columns)
        let mut counts = vec![0i32; numbering.n];
        fill.entries(&numbering, block, |r, _| counts[r] += 1);
        let constrained = numbering.n > numbering.n_u;
        s.replace_options(&self.options_for(constrained))?;
        let zeros = vec![0; numbering.n];
        let a = Matrix::new(s, Comm::One, numbering.n, numbering.n, (&counts, &zeros))?;
        drop((counts, zeros));
        let mut ksp = Ksp::new(s, Comm::One, &a)?;
        if retry_stage(&self.options, &self.counts).is_some() {
            ksp.watch_stall(s, STALL_WINDOW, STALL_FACTOR)?;
        }
        let mut splits = vec![];
        let mut near_null = None;
        let coords = self.layout.as_ref().map(|l| &l.coordinates);
        if constrained && ksp.is_fieldsplit(s)? {
            let mut u = IndexSet::range(s, Comm::One, 0, numbering.n_u, numbering.dim)?;
            if let Some(c) = coords.filter(|_| numbering.dim > 1) {
                let sp = NearNullSpace::rigid_body(s, Comm::One, c, numbering.dim)?;
                u.attach_near_null_space(s, &sp)?;
                near_null = Some(sp);
            }
            let lambda =
                IndexSet::range(s, Comm::One, numbering.n_u, numbering.n - numbering.n_u, 1)?;
            ksp.add_split(s, "u", &u)?;
            ksp.add_split(s, "lambda", &lambda)?;
            splits = vec![u, lambda];
        }
        let b = Vector::new(s, Comm::One, numbering.n, 1)?;
        let x = Vector::new(s, Comm::One, numbering.n, 1)?;
        Ok(Pattern {
            numbering,
            fill,
            objects: Objects {
                ksp,
                splits,
                _near_null: near_null,
                a,
                b,
                x,
                comm: Comm::One,
            },
        })
    }
}

impl Drop for PetscKrylov {
    fn drop(&mut self) {
        self.pattern_reset();
    }
}

impl PetscKrylov {
    /// [`LinearSolver::analyse_with_block`] with the block optional.
    fn analyse_parts(
        &mut self,
        n: usize,
        block: Option<&BlockPattern>,
        rows: &[u32],
        cols: &[u32],
    ) -> Result<(), LinearError> {
        let same = self
            .pattern
            .as_ref()
            .is_some_and(|p| p.numbering.rows.len() == n && p.fill.holds(block, rows, cols));
        if same {
            return Ok(());
        }
        let s = serial()?;
        let t = Instant::now();
        self.pattern = None;
        self.factored = false;
        self.pattern = Some(self.build(&s, n, block, (rows, cols))?);
        self.symbolic_factorisations += 1;
        self.symbolic_time += t.elapsed();
        Ok(())
    }

    /// [`LinearSolver::solve`] with the cached objects.
    fn solve_cached(&mut self, rhs: &[f64]) -> Result<Vec<f64>, LinearError> {
        if !std::mem::take(&mut self.factored) {
            return Err(LinearError::Singular("no factorisation".into()));
        }
        let s = serial()?;
        let rtol = self.rtol;
        let p = self
            .pattern
            .as_mut()
            .ok_or_else(|| LinearError::Singular("no pattern".into()))?;
        if rhs.len() != p.numbering.rows.len() {
            return Err(LinearError::Singular(format!(
                "right-hand side of {} for {} equations",
                rhs.len(),
                p.numbering.rows.len()
            )));
        }
        let mut b = vec![0.0; p.numbering.n];
        for (i, &v) in rhs.iter().enumerate() {
            b[p.numbering.rows[i]] = v;
        }
        let constrained = p.numbering.n > p.numbering.n_u;
        let o = &mut p.objects;
        o.solve(&s, &b, rtol, (&self.options, constrained), &mut self.counts)?;
        let x = o.x.get(&s)?;
        Ok(p.numbering.rows.iter().map(|&r| x[r]).collect())
    }

    /// [`LinearSolver::factor_with_block`] with the block optional.
    fn factor_parts(&mut self, block: Option<&Block>, vals: &[f64]) -> Result<(), LinearError> {
        self.factored = false;
        let s = serial()?;
        let options = self.pattern_options();
        let Some(p) = self.pattern.as_mut() else {
            return Err(LinearError::Singular("no pattern".into()));
        };
        // the decoupled rows' diagonal: the mean absolute diagonal of the
        // free displacement rows
        let mean = |diagonal: &mut dyn Iterator<Item = (usize, f64)>| {
            let (mut sum, mut count) = (0.0_f64, 0usize);
            for (_, v) in diagonal {
                sum += v.abs();
                count += 1;
            }
            Ok(if sum > 0.0 { sum / count as f64 } else { 1.0 })
        };
        let Pattern {
            numbering,
            fill,
            objects,
        } = p;
        fill.fill_matrix(&s, &mut objects.a, numbering, (block, vals), mean)?;
        s.replace_options(&options)?;
        objects.ksp.set_up(&s)?;
        self.factored = true;
        Ok(())
    }
}

impl LinearSolver for PetscKrylov {
    through_parts!();

    fn symbolic_factorisations(&self) -> usize {
        self.symbolic_factorisations
    }

    fn symbolic_time(&self) -> Duration {
        self.symbolic_time
    }

    fn set_constraints_from(&mut self, first: usize) {
        self.first_constraint = Some(first);
    }

    fn set_layout(&mut self, layout: &SystemLayout) {
        self.layout = Some(layout.clone());
        self.pattern_reset();
    }

    fn set_forcing(&mut self, rtol: f64) {
        self.rtol = rtol;
    }

    fn krylov(&self) -> Option<KrylovCounts> {
        Some(self.counts.clone())
    }
}

impl PetscKrylov {
    /// Drops the cached pattern's PETSc objects under the guard (module
    /// docs of `objects`); without PETSc there is nothing to destroy.
    fn pattern_reset(&mut self) {
        if self.pattern.is_some()
            && let Ok(_s) = serial()
        {
            self.pattern = None;
        }
    }
}

#[cfg(test)]
mod tests;
