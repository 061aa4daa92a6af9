//! Sparse LU solution of the (unsymmetric-pivoted) saddle-point system with
//! faer, reusing the symbolic factorisation while the sparsity pattern is
//! unchanged.
//!
//! The matrix arrives as coordinate triplets (duplicates add). The triplet
//! *index list* is the pattern: when it equals the previous call's, the
//! stored symbolic structure, value permutation (`Argsort`) and symbolic LU
//! are reused and only the numeric factorisation runs.
//!
//! faer factorises a numerically singular matrix without error; the solution
//! is then non-finite or huge. Both are reported as singular (see
//! [`NEAR_SINGULAR`]).

use faer::prelude::*;
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use faer::sparse::{Argsort, Pair, SparseColMat, SymbolicSparseColMat};

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
}

/// The cached symbolic data of one pattern.
struct Pattern {
    rows: Vec<usize>,
    cols: Vec<usize>,
    symbolic: SymbolicSparseColMat<usize>,
    argsort: Argsort<usize>,
    lu: SymbolicLu<usize>,
}

/// A sparse direct solver with symbolic reuse.
#[derive(Default)]
pub struct SparseSolver {
    pattern: Option<Pattern>,
    symbolic_factorisations: usize,
    symbolic_time: std::time::Duration,
}

impl SparseSolver {
    /// A solver with nothing cached.
    pub fn new() -> SparseSolver {
        SparseSolver::default()
    }

    /// How many symbolic factorisations were computed so far.
    pub fn symbolic_factorisations(&self) -> usize {
        self.symbolic_factorisations
    }

    /// Time spent in symbolic analysis (pattern, ordering, symbolic LU).
    pub fn symbolic_time(&self) -> std::time::Duration {
        self.symbolic_time
    }

    /// Solves `A x = b` for the `n x n` matrix given by the triplets
    /// `(rows[k], cols[k], vals[k])`.
    pub fn solve(
        &mut self,
        n: usize,
        rows: &[usize],
        cols: &[usize],
        vals: &[f64],
        b: &[f64],
    ) -> Result<Vec<f64>, LinearError> {
        let same = self
            .pattern
            .as_ref()
            .is_some_and(|p| p.rows == rows && p.cols == cols);
        if !same {
            let t = std::time::Instant::now();
            self.pattern = None;
            let idx: Vec<Pair<usize, usize>> = rows
                .iter()
                .zip(cols)
                .map(|(&r, &c)| Pair { row: r, col: c })
                .collect();
            let (symbolic, argsort) = SymbolicSparseColMat::try_new_from_indices(n, n, &idx)
                .map_err(|e| LinearError::Singular(format!("pattern: {e:?}")))?;
            let lu = SymbolicLu::try_new(symbolic.as_ref())
                .map_err(|e| LinearError::Singular(format!("symbolic LU: {e:?}")))?;
            self.symbolic_factorisations += 1;
            self.pattern = Some(Pattern {
                rows: rows.to_vec(),
                cols: cols.to_vec(),
                symbolic,
                argsort,
                lu,
            });
            self.symbolic_time += t.elapsed();
        }
        let p = self
            .pattern
            .as_ref()
            .ok_or_else(|| LinearError::Singular("no pattern".into()))?;
        let a = SparseColMat::new_from_argsort(p.symbolic.clone(), &p.argsort, vals)
            .map_err(|e| LinearError::Singular(format!("values: {e:?}")))?;
        let lu = Lu::try_new_with_symbolic(p.lu.clone(), a.as_ref())
            .map_err(|e| LinearError::Singular(format!("numeric LU: {e:?}")))?;
        let mut x = Mat::<f64>::from_fn(n, 1, |i, _| b[i]);
        lu.solve_in_place(x.as_mut());
        let out: Vec<f64> = (0..n).map(|i| x[(i, 0)]).collect();
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
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A saddle-point system with a zero block, solved twice with the same
    /// pattern (one symbolic factorisation), and a singular one rejected.
    #[test]
    fn saddle_point_and_reuse() {
        // [2 1 1; 1 3 0; 1 0 0] x = [1, 2, 3]
        let rows = [0, 0, 0, 1, 1, 2, 2];
        let cols = [0, 1, 2, 0, 1, 0, 2];
        let vals = [2.0, 1.0, 1.0, 1.0, 3.0, 1.0, 0.0];
        let mut s = SparseSolver::new();
        let x = s.solve(3, &rows, &cols, &vals, &[1.0, 2.0, 3.0]).unwrap();
        assert!((x[0] - 3.0).abs() < 1e-12);
        assert!((x[1] + 1.0 / 3.0).abs() < 1e-12);
        assert!((2.0 * x[0] + x[1] + x[2] - 1.0).abs() < 1e-12);
        let vals2 = [4.0, 1.0, 1.0, 1.0, 3.0, 1.0, 0.0];
        let y = s.solve(3, &rows, &cols, &vals2, &[1.0, 2.0, 3.0]).unwrap();
        assert!((4.0 * y[0] + y[1] + y[2] - 1.0).abs() < 1e-12);
        assert_eq!(s.symbolic_factorisations(), 1);
        let singular = [1.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0];
        assert!(
            s.solve(3, &rows, &cols, &singular, &[1.0, 2.0, 3.0])
                .is_err()
        );
    }
}
