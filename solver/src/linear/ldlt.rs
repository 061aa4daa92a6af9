//! faer's sparse symmetric LDL^T of the saddle-point system, with a
//! fill-reducing (AMD) ordering, iterative refinement and a per-solve
//! fallback to [`SparseLu`].
//!
//! The tangent `[K G^T; G -eps D]` is symmetric quasi-definite when `K` is
//! positive definite: an LDL^T without pivoting then exists for any
//! symmetric ordering, with a positive pivot for every row of `K` and a
//! negative one for every active multiplier. This solver factorises the
//! **lower triangle** of the assembled matrix (`row >= col`, duplicates
//! added), mirrored. Equations are numbered displacements first, then
//! multipliers and ties ([`crate::system::DofMap`]), so for an inactive
//! multiplier the lower triangle holds its decoupled unit diagonal only,
//! while the assembled matrix `A` also has the column `G^T` in the
//! displacement rows (`A = S + E`, `S` the mirrored lower triangle, `E` that
//! column). Every solve is refined against the assembled `A`:
//!
//! ```text
//! x_0 = S^-1 b,   x_{k+1} = x_k + S^-1 (b - A x_k)
//! ```
//!
//! The error obeys `e_{k+1} = -S^-1 E e_k`; `E` maps multipliers into
//! displacement rows only and `S^-1` keeps inactive multipliers decoupled,
//! so `(S^-1 E)^2 = 0`: one refinement step gives the solution of the
//! assembled (unsymmetric) system, i.e. the exact Newton step, and further
//! steps remove the round-off of the unpivoted factorisation (the tiny
//! `-eps` pivots of multipliers ordered before their displacement dofs). The
//! assembly is therefore unchanged, and Newton solves the same system as
//! with LU.
//!
//! Safety checks, each of which makes this solve fall back to LU (counted in
//! [`LinearSolver::fallbacks`], each with its reason in
//! [`LinearSolver::fallback_log`], [`super::fallback`]):
//!
//! - the numeric factorisation reports a zero or non-finite pivot;
//! - the solution is not finite, or its normwise backward error
//!   `|b - A x|_inf / (|A|_inf |x|_inf + |b|_inf)` still exceeds
//!   [`ACCEPT_BACKWARD_ERROR`] after [`MAX_REFINEMENTS`] refinement steps.
//!
//! The pivots' inertia is counted against the rows by kind
//! ([`super::inertia`]: every free-dof row positive, each constraint row by
//! the sign of its assembled diagonal, i.e. `K` positive definite on the
//! active constraints' null space), and a solve whose count differs is
//! recorded ([`LinearSolver::indefinite_log`]) but not handed to the LU: an
//! accepted backward error makes it the solution of the same system the LU
//! would solve, for the same Newton step, while the LU of a 3D model needs
//! several times the memory. A wrong-signed displacement pivot paired with
//! a wrong-signed multiplier pivot has the expected count: where `K` is
//! singular or indefinite along a mode that only contact holds (a body
//! held only by contact, the Hertz cylinder under finite strain; or a
//! displacement row whose assembled diagonal the geometric stiffness
//! `lambda g''` of a large multiplier made negative, the 3D Hertz scene on
//! tetrahedra with dual multipliers: free equation 11 with diagonal -0.41
//! in the indenter tip's constraint row, whose pivot came out +9.4e-7,
//! docs/benchmarks.md), refinement solves such a pair to a backward error
//! of about 1e-18. Fewer positive pivots than expected are `K` indefinite
//! where the constraints leave it free (buckling, or an iterate about to
//! invert elements); a numerically singular matrix shows up as a zero
//! pivot or in the backward error (and [`check_solution`]). When a wrong
//! count still fell back to the LU, two such solves on the 3D Hertz scene
//! on non-matching hexahedra at h = 0.07 (segmented, dual) took the
//! process to 23.4 GiB; kept, the run reaches the same energy in the same
//! iterations at 5.2 GiB (docs/benchmarks.md).
//!
//! The LU allocates within `MemAvailable`: one that does not fit is
//! [`LinearError::OutOfMemory`] ([`super::fallback`], "The LU's memory").
//!
//! Invariants (as [`SparseLu`]): the symbolic analysis (ordering, elimination
//! tree, supernodes) is kept while [`LinearSolver::analyse`] sees the same
//! index lists; a numeric factorisation lives from
//! [`LinearSolver::factor`] to the next [`LinearSolver::solve`], which
//! consumes it. The LU of a fallback is analysed on first use and then kept
//! with the same rule; its symbolic work counts in this solver's symbolic
//! statistics. Only the *memory* of the last factor's values is kept for the
//! next factorisation (which overwrites every entry), so that a Newton
//! iteration does not page in a fresh factor; it is released before an LU
//! fallback factorises, so at most one factor is held at a time. Inside
//! [`LinearSolver::solve_system`] the assembled values are borrowed by the
//! refinement, not copied; `|A|_inf` is accumulated in the first residual
//! pass.

use std::time::{Duration, Instant};

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::ldlt::factor::LdltRegularization;
use faer::perm::PermRef;
use faer::prelude::*;
use faer::sparse::linalg::amd;
use faer::sparse::linalg::cholesky::supernodal::SupernodalLdltRef;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, LdltRef, SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering,
    factorize_symbolic_cholesky,
};
use faer::sparse::{Pair, SparseColMatRef, SymbolicSparseColMat, SymbolicSparseColMatRef};
use faer::{Conj, Side};

use super::fallback::{Fallback, FallbackReason, LuOutcome};
use super::inertia::{self, IndefiniteSolve, Inertia};
use super::{LinearError, LinearSolver, SparseLu, check_solution};
use crate::meminfo::AddressSpaceLimit;

/// A solve is accepted when its normwise backward error
/// `|b - A x|_inf / (|A|_inf |x|_inf + |b|_inf)` is at most this.
pub const ACCEPT_BACKWARD_ERROR: f64 = 1e-12;

/// Refinement steps against the assembled matrix before a solve falls back
/// to LU (one is needed whenever a multiplier is inactive, module docs).
pub const MAX_REFINEMENTS: usize = 3;

/// The cached symbolic data of one pattern.
struct Pattern {
    n: usize,
    rows: Vec<u32>,
    cols: Vec<u32>,
    /// Indices of the triplets in the lower triangle (`row >= col`).
    lower: Vec<usize>,
    /// Compressed-column structure of the lower triangle.
    symbolic: SymbolicSparseColMat<usize>,
    /// For each triplet of `lower`, its slot in the values of `symbolic`
    /// (duplicates share a slot and are added in triplet order).
    slot: Vec<usize>,
    cholesky: SymbolicCholesky<usize>,
    /// Workspace of the numeric factorisation and the solves, sized for
    /// `par`.
    buffer: MemBuffer,
    /// The parallelism of the numeric factorisation and the solves (faer's
    /// global setting at analysis time).
    par: Par,
}

/// A factorisation waiting for its solve.
enum Factor {
    /// The LDL^T values, with the assembled values for the refinement
    /// (`None` inside [`LinearSolver::solve_system`], which lends them).
    Ldlt {
        l_values: Vec<f64>,
        vals: Option<Vec<f64>>,
    },
    /// The LDL^T was unsafe: the fallback LU is factorised.
    Lu,
}

/// faer's sparse LDL^T with symbolic reuse, refinement and LU fallback
/// (module docs).
pub struct SparseLdlt {
    pattern: Option<Pattern>,
    numeric: Option<Factor>,
    lu: SparseLu,
    symbolic_factorisations: usize,
    symbolic_time: Duration,
    fallbacks: usize,
    refinements: usize,
    /// First constraint equation (see [`LinearSolver::set_constraints_from`]);
    /// `None`: no hint, plain AMD.
    constraints_from: Option<usize>,
    /// The memory of the last LDL^T values, reused by the next
    /// factorisation (its values are never read: the numeric factorisation
    /// overwrites every entry); released when a solve falls back to LU.
    spare: Vec<f64>,
    /// Numeric factorisations so far (the solves, counted from 1 in
    /// [`Fallback::solve`]).
    solves: usize,
    /// Every solve that fell back, with its reason.
    log: Vec<Fallback>,
    /// Every solve whose pivots did not have the expected inertia.
    indefinite: Vec<IndefiniteSolve>,
    /// The memory an LU fallback may take (`MemAvailable`; a test's own).
    available: fn() -> Option<u64>,
}

impl Default for SparseLdlt {
    fn default() -> SparseLdlt {
        SparseLdlt {
            pattern: None,
            numeric: None,
            lu: SparseLu::default(),
            symbolic_factorisations: 0,
            symbolic_time: Duration::ZERO,
            fallbacks: 0,
            refinements: 0,
            constraints_from: None,
            spare: Vec::new(),
            solves: 0,
            log: Vec::new(),
            indefinite: Vec::new(),
            available: crate::meminfo::available,
        }
    }
}

impl SparseLdlt {
    /// A solver with nothing cached.
    pub fn new() -> SparseLdlt {
        SparseLdlt::default()
    }

    /// Refinement steps taken so far (over all solves).
    pub fn refinements(&self) -> usize {
        self.refinements
    }

    /// A solver whose LU fallback may allocate `available()` bytes (`None`:
    /// no limit); the default's is `MemAvailable`
    /// ([`crate::meminfo::available`]).
    pub fn with_available_memory(available: fn() -> Option<u64>) -> SparseLdlt {
        SparseLdlt {
            available,
            ..SparseLdlt::default()
        }
    }

    /// Factorises with the fallback LU (analysing the pattern if needed),
    /// releasing the spare LDL^T values first, within the memory available
    /// ([`super::fallback`], "The LU's memory"); logs the fallback with its
    /// `reason`.
    fn factor_lu(&mut self, vals: &[f64], reason: FallbackReason) -> Result<(), LinearError> {
        self.spare = Vec::new();
        self.fallbacks += 1;
        let available = (self.available)();
        let factored = {
            let _limit = available.map(AddressSpaceLimit::new);
            self.lu_factor(vals)
        };
        let lu = match &factored {
            Ok(()) => LuOutcome::Solved,
            Err(LinearError::OutOfMemory(message)) => LuOutcome::OutOfMemory {
                available,
                message: message.clone(),
            },
            Err(e) => LuOutcome::Failed(e.to_string()),
        };
        let fallback = Fallback {
            solve: self.solves,
            reason,
            lu,
        };
        let message = fallback.to_string();
        self.log.push(fallback);
        match factored {
            Ok(()) => {
                self.numeric = Some(Factor::Lu);
                Ok(())
            }
            Err(LinearError::OutOfMemory(_)) => Err(LinearError::OutOfMemory(message)),
            Err(e) => Err(e),
        }
    }

    /// The LU's analysis (if needed) and factorisation of `vals`.
    fn lu_factor(&mut self, vals: &[f64]) -> Result<(), LinearError> {
        let p = self
            .pattern
            .as_ref()
            .ok_or_else(|| LinearError::Singular("no pattern".into()))?;
        self.lu.analyse(p.n, &p.rows, &p.cols)?;
        self.lu.factor(vals)
    }

    /// [`LinearSolver::factor`] without keeping a copy of `vals`: the LDL^T
    /// of the lower triangle when it is safe (module docs), else the LU.
    fn factor_values(&mut self, vals: &[f64]) -> Result<(), LinearError> {
        self.numeric = None;
        self.solves += 1;
        let p = self
            .pattern
            .as_mut()
            .ok_or_else(|| LinearError::Singular("no pattern".into()))?;
        if vals.len() != p.rows.len() {
            return Err(LinearError::Singular(format!(
                "{} values for {} analysed entries",
                vals.len(),
                p.rows.len()
            )));
        }
        // the lower triangle's values in compressed-column order, and the
        // assembled diagonal (duplicates added in triplet order)
        let mut lower_vals = vec![0.0_f64; p.symbolic.compute_nnz()];
        let mut diagonal = vec![0.0_f64; p.n];
        for (&k, &slot) in p.lower.iter().zip(&p.slot) {
            lower_vals[slot] += vals[k];
            if p.rows[k] == p.cols[k] {
                diagonal[p.rows[k] as usize] += vals[k];
            }
        }
        let expected_positive = inertia::expected_positive_pivots(&diagonal, self.constraints_from);
        drop(diagonal);
        let a = SparseColMatRef::new(p.symbolic.as_ref(), &lower_vals);
        let mut l_values = std::mem::take(&mut self.spare);
        l_values.resize(p.cholesky.len_val(), 0.0);
        if matches!(p.cholesky.raw(), SymbolicCholeskyRaw::Simplicial(_)) {
            // the supernodal factorisation clears its values itself
            l_values.fill(0.0);
        }
        let factored = p
            .cholesky
            .factorize_numeric_ldlt(
                &mut l_values,
                a,
                Side::Lower,
                LdltRegularization::default(),
                p.par,
                MemStack::new(&mut p.buffer),
                Default::default(),
            )
            .map(|_| ())
            .map_err(|_| FallbackReason::Pivot);
        let safe = factored.and_then(|()| pivot_inertia(&p.cholesky, &l_values, expected_positive));
        match safe {
            Ok(inertia) => {
                if !inertia.is_expected() {
                    self.indefinite.push(IndefiniteSolve {
                        solve: self.solves,
                        inertia,
                    });
                }
                self.numeric = Some(Factor::Ldlt {
                    l_values,
                    vals: None,
                });
                Ok(())
            }
            Err(reason) => {
                drop(l_values);
                drop(lower_vals);
                self.factor_lu(vals, reason)
            }
        }
    }

    /// Solves with the LDL^T values `l_values`, refines against the
    /// assembled values `vals` and checks the backward error (module docs);
    /// falls back to LU when the check fails. Keeps `l_values` as the spare.
    fn solve_ldlt(
        &mut self,
        l_values: Vec<f64>,
        vals: &[f64],
        rhs: &[f64],
    ) -> Result<Vec<f64>, LinearError> {
        let p = self
            .pattern
            .as_mut()
            .ok_or_else(|| LinearError::Singular("no pattern".into()))?;
        let n = p.n;
        if rhs.len() != n {
            return Err(LinearError::Singular(format!(
                "right-hand side of size {} for {n} equations",
                rhs.len()
            )));
        }
        let par = p.par;
        let ldlt = LdltRef::new(&p.cholesky, &l_values);
        let mut x = rhs.to_vec();
        ldlt.solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(&mut x, n, 1),
            par,
            MemStack::new(&mut p.buffer),
        );
        let b_norm = max_abs(rhs);
        let mut r = vec![0.0_f64; n];
        // |A|_inf: the absolute row sums, accumulated in the first
        // residual pass (in triplet order)
        let mut row_sums = vec![0.0_f64; n];
        let mut a_norm = None;
        let mut refinements = 0;
        let accepted: Result<(), FallbackReason> = loop {
            // r = b - A x with the assembled (possibly unsymmetric) matrix
            r.copy_from_slice(rhs);
            let a_inf = match a_norm {
                Some(a) => {
                    for ((&row, &col), &v) in p.rows.iter().zip(&p.cols).zip(vals) {
                        r[row as usize] -= v * x[col as usize];
                    }
                    a
                }
                None => {
                    for ((&row, &col), &v) in p.rows.iter().zip(&p.cols).zip(vals) {
                        let (row, col) = (row as usize, col as usize);
                        r[row] -= v * x[col];
                        row_sums[row] += v.abs();
                    }
                    let a = row_sums.iter().copied().fold(0.0, f64::max);
                    *a_norm.insert(a)
                }
            };
            let finite = x.iter().all(|v| v.is_finite());
            let (r_max, x_max) = (max_abs(&r), max_abs(&x));
            if !finite || !r_max.is_finite() {
                break Err(FallbackReason::NonFinite);
            }
            let scale = a_inf * x_max + b_norm;
            if r_max <= ACCEPT_BACKWARD_ERROR * scale {
                break Ok(());
            }
            if refinements == MAX_REFINEMENTS {
                break Err(FallbackReason::BackwardError {
                    backward_error: r_max / scale,
                    refinements,
                });
            }
            refinements += 1;
            ldlt.solve_in_place_with_conj(
                Conj::No,
                MatMut::from_column_major_slice_mut(&mut r, n, 1),
                par,
                MemStack::new(&mut p.buffer),
            );
            for (xi, ri) in x.iter_mut().zip(&r) {
                *xi += ri;
            }
        };
        self.refinements += refinements;
        let reason = match accepted {
            Ok(()) => {
                self.spare = l_values;
                return Ok(x);
            }
            Err(reason) => reason,
        };
        drop((l_values, x, r, row_sums));
        self.factor_lu(vals, reason)?;
        self.numeric = None;
        self.lu.solve(rhs)
    }
}

/// The fill-reducing ordering (`fwd[new] = old`, `inv[old] = new`) of the
/// lower-triangle pattern `lower`: AMD, then every constraint equation
/// (`>= first`) moved to just after the last of its non-constraint
/// neighbours, so its pivot is the Schur complement `-eps - g^T S^-1 g`
/// rather than the tiny `-eps` (module docs). Stable otherwise.
fn constrained_amd(
    lower: SymbolicSparseColMatRef<'_, usize>,
    first: usize,
) -> Result<(Vec<usize>, Vec<usize>), LinearError> {
    let n = lower.nrows();
    let nnz = lower.compute_nnz();
    let mut fwd = vec![0usize; n];
    let mut inv = vec![0usize; n];
    let mut buffer = MemBuffer::try_new(amd::order_maybe_unsorted_scratch::<usize>(n, nnz))
        .map_err(|_| LinearError::Singular("AMD workspace: out of memory".into()))?;
    amd::order_maybe_unsorted(
        &mut fwd,
        &mut inv,
        lower,
        amd::Control::default(),
        MemStack::new(&mut buffer),
    )
    .map_err(|e| LinearError::Singular(format!("AMD ordering: {e:?}")))?;
    // key 2 pos for an unknown, 2 pos(last neighbour) + 1 for a constraint
    let mut key: Vec<usize> = (0..n).map(|i| 2 * inv[i]).collect();
    let mut moved = vec![false; n];
    for j in 0..first.min(n) {
        for &r in lower.row_idx_of_col_raw(j) {
            if r >= first {
                let k = 2 * inv[j] + 1;
                key[r] = if moved[r] { key[r].max(k) } else { k };
                moved[r] = true;
            }
        }
    }
    fwd.sort_by_key(|&i| (key[i], i));
    for (new, &old) in fwd.iter().enumerate() {
        inv[old] = new;
    }
    Ok((fwd, inv))
}

/// Nonzeros of the lower triangle of `L`, diagonal included, for the
/// lower-triangle pattern `lower` eliminated in the order `inv` (`inv[old] =
/// new`; `None`: the identity): the exact structural count, by row subtrees
/// of the elimination tree. Row `k` of `L` has an entry in column `i < k`
/// exactly when `i` lies on the tree path from some `j` with `a_kj != 0`,
/// `j < k`, up to `k`; walking those paths, stopping at nodes already
/// visited for row `k`, also builds the tree (the parent of `i` is the first
/// row that reaches it). `O(nnz(L))` time, `O(nnz(A))` memory. A supernodal
/// factor computes more entries than this (the zeros admitted by supernode
/// relaxation and the strict upper triangles of its dense diagonal blocks).
fn exact_factor_nonzeros(
    lower: SymbolicSparseColMatRef<'_, usize>,
    inv: Option<&[usize]>,
) -> usize {
    const NONE: usize = usize::MAX;
    let n = lower.nrows();
    let new = |i: usize| inv.map_or(i, |p| p[i]);
    // the permuted strictly upper triangle, by column: row_idx[ptr[k]..ptr[k + 1]]
    let mut ptr = vec![0usize; n + 1];
    for j in 0..n {
        for &r in lower.row_idx_of_col_raw(j) {
            if r != j {
                ptr[new(r).max(new(j)) + 1] += 1;
            }
        }
    }
    for k in 0..n {
        ptr[k + 1] += ptr[k];
    }
    let mut next = ptr.clone();
    let mut row_idx = vec![0usize; ptr[n]];
    for j in 0..n {
        for &r in lower.row_idx_of_col_raw(j) {
            if r != j {
                let (lo, hi) = (new(r).min(new(j)), new(r).max(new(j)));
                row_idx[next[hi]] = lo;
                next[hi] += 1;
            }
        }
    }
    let mut parent = vec![NONE; n];
    let mut visited = vec![NONE; n];
    let mut nonzeros = n;
    for k in 0..n {
        visited[k] = k;
        for &j in &row_idx[ptr[k]..ptr[k + 1]] {
            let mut i = j;
            while visited[i] != k {
                visited[i] = k;
                nonzeros += 1;
                if parent[i] == NONE {
                    parent[i] = k;
                }
                i = parent[i];
            }
        }
    }
    nonzeros
}

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0_f64, |m, x| m.max(x.abs()))
}

/// The inertia of the factorisation `l_values` against `expected`
/// positive pivots ([`super::inertia`]), or [`FallbackReason::Pivot`] when
/// a pivot is zero or not finite.
fn pivot_inertia(
    cholesky: &SymbolicCholesky<usize>,
    l_values: &[f64],
    expected: usize,
) -> Result<Inertia, FallbackReason> {
    let mut positive = 0;
    let mut ok = |d: f64| {
        positive += usize::from(d > 0.0);
        d.is_finite() && d != 0.0
    };
    let each = match cholesky.raw() {
        SymbolicCholeskyRaw::Simplicial(s) => {
            // the diagonal is the first entry of each column of the factor
            let col_ptr = s.factor().col_ptr();
            (0..s.nrows()).all(|j| ok(l_values[col_ptr[j]]))
        }
        SymbolicCholeskyRaw::Supernodal(s) => {
            let ldlt = SupernodalLdltRef::new(s, l_values);
            (0..s.n_supernodes()).all(|k| {
                let node = ldlt.supernode(k);
                let val = node.val();
                (0..val.ncols()).all(|c| ok(val[(c, c)]))
            })
        }
    };
    if each {
        Ok(Inertia { positive, expected })
    } else {
        Err(FallbackReason::Pivot)
    }
}

impl LinearSolver for SparseLdlt {
    fn analyse(&mut self, n: usize, rows: &[u32], cols: &[u32]) -> Result<(), LinearError> {
        let same = self
            .pattern
            .as_ref()
            .is_some_and(|p| p.rows == rows && p.cols == cols);
        if !same {
            let t = Instant::now();
            self.pattern = None;
            if let Some(k) = rows
                .iter()
                .zip(cols)
                .position(|(&r, &c)| r as usize >= n || c as usize >= n)
            {
                return Err(LinearError::Singular(format!(
                    "pattern: entry {k} outside the {n} x {n} matrix"
                )));
            }
            let lower: Vec<usize> = (0..rows.len()).filter(|&k| rows[k] >= cols[k]).collect();
            let idx: Vec<Pair<usize, usize>> = lower
                .iter()
                .map(|&k| Pair {
                    row: rows[k] as usize,
                    col: cols[k] as usize,
                })
                .collect();
            let (symbolic, _) = SymbolicSparseColMat::try_new_from_indices(n, n, &idx)
                .map_err(|e| LinearError::Singular(format!("pattern: {e:?}")))?;
            // the slot of each lower triplet: its row among the sorted,
            // deduplicated rows of its column
            let slot: Vec<usize> = idx
                .iter()
                .map(|e| {
                    let start = symbolic.col_ptr()[e.col];
                    let rows_of_col = symbolic.row_idx_of_col_raw(e.col);
                    rows_of_col
                        .binary_search(&e.row)
                        .map(|i| start + i)
                        .map_err(|_| LinearError::Singular("pattern: lost entry".into()))
                })
                .collect::<Result<_, _>>()?;
            drop(idx);
            let ordering = match self.constraints_from {
                Some(first) if first < n => Some(constrained_amd(symbolic.as_ref(), first)?),
                _ => None,
            };
            let cholesky = factorize_symbolic_cholesky(
                symbolic.as_ref(),
                Side::Lower,
                match &ordering {
                    Some((fwd, inv)) => {
                        SymmetricOrdering::Custom(PermRef::new_checked(fwd, inv, n))
                    }
                    None => SymmetricOrdering::Amd,
                },
                CholeskySymbolicParams::default(),
            )
            .map_err(|e| LinearError::Singular(format!("symbolic LDL^T: {e:?}")))?;
            let par = faer::get_global_parallelism();
            let scratch = cholesky
                .factorize_numeric_ldlt_scratch::<f64>(par, Default::default())
                .or(cholesky.solve_in_place_scratch::<f64>(1, par));
            let buffer = MemBuffer::try_new(scratch)
                .map_err(|_| LinearError::Singular("LDL^T workspace: out of memory".into()))?;
            self.symbolic_factorisations += 1;
            self.pattern = Some(Pattern {
                n,
                rows: rows.to_vec(),
                cols: cols.to_vec(),
                lower,
                symbolic,
                slot,
                cholesky,
                buffer,
                par,
            });
            self.symbolic_time += t.elapsed();
        }
        Ok(())
    }

    fn factor(&mut self, vals: &[f64]) -> Result<(), LinearError> {
        self.factor_values(vals)?;
        if let Some(Factor::Ldlt { vals: kept, .. }) = &mut self.numeric {
            *kept = Some(vals.to_vec());
        }
        Ok(())
    }

    fn solve(&mut self, rhs: &[f64]) -> Result<Vec<f64>, LinearError> {
        match self.numeric.take() {
            Some(Factor::Ldlt {
                l_values,
                vals: Some(vals),
            }) => self.solve_ldlt(l_values, &vals, rhs),
            Some(Factor::Lu) => self.lu.solve(rhs),
            _ => Err(LinearError::Singular("no factorisation".into())),
        }
    }

    /// As the trait's: the phases and [`check_solution`], with the
    /// assembled values lent to the refinement rather than copied.
    fn solve_system(
        &mut self,
        n: usize,
        rows: &[u32],
        cols: &[u32],
        vals: &[f64],
        b: &[f64],
    ) -> Result<Vec<f64>, LinearError> {
        self.analyse(n, rows, cols)?;
        self.factor_values(vals)?;
        let x = match self.numeric.take() {
            Some(Factor::Ldlt { l_values, .. }) => self.solve_ldlt(l_values, vals, b)?,
            Some(Factor::Lu) => self.lu.solve(b)?,
            None => return Err(LinearError::Singular("no factorisation".into())),
        };
        check_solution(vals, b, x)
    }

    fn symbolic_factorisations(&self) -> usize {
        self.symbolic_factorisations + self.lu.symbolic_factorisations()
    }

    fn symbolic_time(&self) -> Duration {
        self.symbolic_time + self.lu.symbolic_time()
    }

    fn fallbacks(&self) -> usize {
        self.fallbacks
    }

    fn fallback_log(&self) -> &[Fallback] {
        &self.log
    }

    fn indefinite_log(&self) -> &[IndefiniteSolve] {
        &self.indefinite
    }

    /// Computed on each call (`O(nnz(L))`, no numeric work; see
    /// [`exact_factor_nonzeros`]), so the analysis does not pay for it.
    fn factor_nonzeros(&self) -> Option<usize> {
        self.pattern.as_ref().map(|p| {
            exact_factor_nonzeros(
                p.symbolic.as_ref(),
                p.cholesky.perm().map(|perm| perm.arrays().1),
            )
        })
    }

    fn set_constraints_from(&mut self, first: usize) {
        if self.constraints_from != Some(first) {
            self.constraints_from = Some(first);
            self.pattern = None;
        }
    }
}

#[cfg(test)]
#[path = "ldlt_tests.rs"]
mod tests;
