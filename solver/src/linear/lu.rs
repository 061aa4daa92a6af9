//! faer's sparse LU of the (unsymmetric-pivoted) saddle-point system, the
//! default [`LinearSolver`].
//!
//! The cached pattern holds the triplet index lists, the symbolic structure
//! of the compressed-column matrix, the value permutation (`Argsort`) and
//! the symbolic LU; while [`LinearSolver::analyse`] sees the same index
//! lists only the numeric factorisation runs.
//!
//! faer factorises a numerically singular matrix without error; the solution
//! is then non-finite or huge, which [`super::check_solution`] reports.
//!
//! Invariant: a numeric factorisation lives from [`LinearSolver::factor`] to
//! the next [`LinearSolver::solve`], which consumes it, so no factor is held
//! between Newton iterations (the memory profile of a solve is that of one
//! factorisation at a time).

use std::time::{Duration, Instant};

use faer::prelude::*;
use faer::sparse::linalg::LuError;
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use faer::sparse::{Argsort, FaerError, Pair, SparseColMat, SymbolicSparseColMat};

use super::{LinearError, LinearSolver};

/// The cached symbolic data of one pattern.
struct Pattern {
    n: usize,
    rows: Vec<u32>,
    cols: Vec<u32>,
    symbolic: SymbolicSparseColMat<usize>,
    argsort: Argsort<usize>,
    lu: SymbolicLu<usize>,
}

/// faer's sparse LU with symbolic reuse.
#[derive(Default)]
pub struct SparseLu {
    pattern: Option<Pattern>,
    numeric: Option<Lu<usize, f64>>,
    symbolic_factorisations: usize,
    symbolic_time: Duration,
}

impl SparseLu {
    /// A solver with nothing cached.
    pub fn new() -> SparseLu {
        SparseLu::default()
    }
}

impl LinearSolver for SparseLu {
    fn analyse(&mut self, n: usize, rows: &[u32], cols: &[u32]) -> Result<(), LinearError> {
        let same = self
            .pattern
            .as_ref()
            .is_some_and(|p| p.rows == rows && p.cols == cols);
        if !same {
            let t = Instant::now();
            self.pattern = None;
            let idx: Vec<Pair<usize, usize>> = rows
                .iter()
                .zip(cols)
                .map(|(&r, &c)| Pair {
                    row: r as usize,
                    col: c as usize,
                })
                .collect();
            let (symbolic, argsort) = SymbolicSparseColMat::try_new_from_indices(n, n, &idx)
                .map_err(|e| LinearError::Singular(format!("pattern: {e:?}")))?;
            let lu = SymbolicLu::try_new(symbolic.as_ref())
                .map_err(|e| LinearError::Singular(format!("symbolic LU: {e:?}")))?;
            self.symbolic_factorisations += 1;
            self.pattern = Some(Pattern {
                n,
                rows: rows.to_vec(),
                cols: cols.to_vec(),
                symbolic,
                argsort,
                lu,
            });
            self.symbolic_time += t.elapsed();
        }
        Ok(())
    }

    fn factor(&mut self, vals: &[f64]) -> Result<(), LinearError> {
        self.numeric = None;
        let p = self
            .pattern
            .as_ref()
            .ok_or_else(|| LinearError::Singular("no pattern".into()))?;
        let a = SparseColMat::new_from_argsort(p.symbolic.clone(), &p.argsort, vals)
            .map_err(|e| LinearError::Singular(format!("values: {e:?}")))?;
        let lu = Lu::try_new_with_symbolic(p.lu.clone(), a.as_ref()).map_err(|e| match e {
            LuError::Generic(FaerError::OutOfMemory) => {
                LinearError::OutOfMemory(format!("numeric LU: {e:?}"))
            }
            e => LinearError::Singular(format!("numeric LU: {e:?}")),
        })?;
        self.numeric = Some(lu);
        Ok(())
    }

    fn solve(&mut self, rhs: &[f64]) -> Result<Vec<f64>, LinearError> {
        let lu = self
            .numeric
            .take()
            .ok_or_else(|| LinearError::Singular("no factorisation".into()))?;
        let n = self.pattern.as_ref().map_or(rhs.len(), |p| p.n);
        let mut x = Mat::<f64>::from_fn(n, 1, |i, _| rhs[i]);
        lu.solve_in_place(x.as_mut());
        Ok((0..n).map(|i| x[(i, 0)]).collect())
    }

    fn symbolic_factorisations(&self) -> usize {
        self.symbolic_factorisations
    }

    fn symbolic_time(&self) -> Duration {
        self.symbolic_time
    }
}
