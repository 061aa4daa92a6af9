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
//! Implementations: [`lu::SparseLu`] (faer's sparse LU; the default) and
//! [`ldlt::SparseLdlt`] (faer's sparse symmetric LDL^T of the quasi-definite
//! system, refined against the assembled matrix, falling back to LU for a
//! solve it cannot do safely). Selected by [`LinearSolverKind`]; a new solver
//! is a new file here, a new variant there, and nothing in Newton changes.

pub mod ldlt;
pub mod lu;
#[cfg(test)]
mod scene_tests;

use std::time::Duration;

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
    fn analyse(&mut self, n: usize, rows: &[usize], cols: &[usize]) -> Result<(), LinearError>;

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

    /// Solves `A x = b` for the `n x n` matrix given by the triplets
    /// `(rows[k], cols[k], vals[k])`: [`analyse`](Self::analyse),
    /// [`factor`](Self::factor), [`solve`](Self::solve), then
    /// [`check_solution`].
    fn solve_system(
        &mut self,
        n: usize,
        rows: &[usize],
        cols: &[usize],
        vals: &[f64],
        b: &[f64],
    ) -> Result<Vec<f64>, LinearError> {
        self.analyse(n, rows, cols)?;
        self.factor(vals)?;
        let x = self.solve(b)?;
        check_solution(vals, b, x)
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
}

impl LinearSolverKind {
    /// Every kind (the tests run each).
    pub const ALL: [LinearSolverKind; 2] = [LinearSolverKind::Lu, LinearSolverKind::Ldlt];

    /// A new solver of this kind with nothing cached.
    pub fn build(self) -> Box<dyn LinearSolver> {
        match self {
            LinearSolverKind::Lu => Box::new(SparseLu::new()),
            LinearSolverKind::Ldlt => Box::new(SparseLdlt::new()),
        }
    }
}

impl std::fmt::Display for LinearSolverKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            LinearSolverKind::Lu => "lu",
            LinearSolverKind::Ldlt => "ldlt",
        })
    }
}

/// Error parsing a [`LinearSolverKind`].
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown linear solver `{0}` (expected `lu` or `ldlt`)")]
pub struct ParseLinearSolverError(pub String);

impl std::str::FromStr for LinearSolverKind {
    type Err = ParseLinearSolverError;
    /// `"lu"` or `"ldlt"`.
    fn from_str(s: &str) -> Result<LinearSolverKind, ParseLinearSolverError> {
        let t = s.trim();
        if t.eq_ignore_ascii_case("lu") {
            Ok(LinearSolverKind::Lu)
        } else if t.eq_ignore_ascii_case("ldlt") {
            Ok(LinearSolverKind::Ldlt)
        } else {
            Err(ParseLinearSolverError(s.to_owned()))
        }
    }
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
        for kind in LinearSolverKind::ALL {
            // [2 1 1; 1 3 0; 1 0 0] x = [1, 2, 3]
            let rows = [0, 0, 0, 1, 1, 2, 2];
            let cols = [0, 1, 2, 0, 1, 0, 2];
            let vals = [2.0, 1.0, 1.0, 1.0, 3.0, 1.0, 0.0];
            let mut s = kind.build();
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

    /// The phases in the wrong order are errors, not panics: no pattern to
    /// factor, no factorisation to solve with (one solve per factorisation).
    #[test]
    fn phases_out_of_order_are_errors() {
        for kind in LinearSolverKind::ALL {
            let mut s = kind.build();
            assert!(s.factor(&[1.0]).is_err());
            assert!(s.solve(&[1.0]).is_err());
            s.analyse(1, &[0], &[0]).unwrap();
            s.factor(&[2.0]).unwrap();
            assert_eq!(s.solve(&[1.0]), Ok(vec![0.5]));
            assert!(s.solve(&[1.0]).is_err());
        }
        assert!("qr".parse::<LinearSolverKind>().is_err());
    }
}
