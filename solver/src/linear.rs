//! Sparse LU solution of the (unsymmetric-pivoted) saddle-point system with
//! faer, reusing the symbolic factorisation while the sparsity pattern is
//! unchanged.
//!
//! The matrix arrives as coordinate triplets (duplicates add). The triplet
//! *index list* is the pattern: when it equals the previous call's, the
//! stored symbolic structure, value permutation (`Argsort`) and symbolic LU
//! are reused and only the numeric factorisation runs.

use faer::prelude::*;
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use faer::sparse::{Argsort, Pair, SparseColMat, SymbolicSparseColMat};

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
        let same = self.pattern.as_ref().is_some_and(|p| p.rows == rows && p.cols == cols);
        if !same {
            self.pattern = None;
            let idx: Vec<Pair<usize, usize>> = rows.iter().zip(cols).map(|(&r, &c)| Pair { row: r, col: c }).collect();
            let (symbolic, argsort) = SymbolicSparseColMat::try_new_from_indices(n, n, &idx)
                .map_err(|e| LinearError::Singular(format!("pattern: {e:?}")))?;
            let lu = SymbolicLu::try_new(symbolic.as_ref())
                .map_err(|e| LinearError::Singular(format!("symbolic LU: {e:?}")))?;
            self.symbolic_factorisations += 1;
            self.pattern = Some(Pattern { rows: rows.to_vec(), cols: cols.to_vec(), symbolic, argsort, lu });
        }
        let p = self.pattern.as_ref().ok_or_else(|| LinearError::Singular("no pattern".into()))?;
        let a = SparseColMat::new_from_argsort(p.symbolic.clone(), &p.argsort, vals)
            .map_err(|e| LinearError::Singular(format!("values: {e:?}")))?;
        let lu = Lu::try_new_with_symbolic(p.lu.clone(), a.as_ref())
            .map_err(|e| LinearError::Singular(format!("numeric LU: {e:?}")))?;
        let mut x = Mat::<f64>::from_fn(n, 1, |i, _| b[i]);
        lu.solve_in_place(x.as_mut());
        let out: Vec<f64> = (0..n).map(|i| x[(i, 0)]).collect();
        if let Some(i) = out.iter().position(|v| !v.is_finite()) {
            return Err(LinearError::Singular(format!("numerically singular (solution component {i} is {})", out[i])));
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
        assert!(s.solve(3, &rows, &cols, &singular, &[1.0, 2.0, 3.0]).is_err());
    }
}
