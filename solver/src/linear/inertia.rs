//! The inertia of the contact saddle point, and the solves whose stiffness
//! is indefinite where the active constraints leave it free.
//!
//! The tangent `A = [K G^T; G -eps D]` (`G` the active constraints' rows,
//! of full row rank; inactive multipliers decoupled with a unit diagonal)
//! has, when `K` is positive definite on the null space of `G`, one
//! positive eigenvalue per free-dof row and per inactive multiplier and one
//! negative eigenvalue per active multiplier and tie: with `Z` a basis of
//! that null space, `In(A) = In(Z^T K Z) + (m, m, 0)` for `m` active rows
//! (Haynsworth; the `-eps D` block moves no count while `eps` is small).
//! By Sylvester's law an LDL^T's pivots have the same signs, so counting
//! the positive pivots against the [expected](expected_positive_pivots)
//! number tests exactly that `K` is positive definite where the constraints
//! leave it free, whatever the sign of any single diagonal: a displacement
//! row whose assembled diagonal is negative (the geometric stiffness
//! `lambda g''` of a large multiplier) but which its constraint holds still
//! counts as positive, and so does a body held only by contact.
//!
//! Fewer positive pivots than expected mean that `K` has that many negative
//! eigenvalues where the constraints leave it free: buckling, or an iterate
//! about to invert elements. The Newton step is still the solution of the
//! linear system, which [`super::SparseLdlt`] checks by its backward error
//! (its module docs); such a solve is recorded as an [`IndefiniteSolve`],
//! not handed to the LU, whose factor of a 3D model needs several times
//! the memory for the same step.

use std::fmt;

/// The pivots' inertia against a quasi-definite matrix's (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Inertia {
    /// Positive pivots.
    pub positive: usize,
    /// Positive pivots of a matrix whose `K` is positive definite on the
    /// active constraints' null space: free-dof rows and constraint rows
    /// with a positive assembled diagonal.
    pub expected: usize,
}

impl Inertia {
    /// Whether the count is the expected one.
    pub fn is_expected(&self) -> bool {
        self.positive == self.expected
    }
}

impl fmt::Display for Inertia {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} positive pivots, {} expected",
            self.positive, self.expected
        )
    }
}

/// A solve whose pivots do not have the expected inertia.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct IndefiniteSolve {
    /// The solve, counted from 1 over the solver's life.
    pub solve: usize,
    /// Its pivots' count.
    pub inertia: Inertia,
}

impl fmt::Display for IndefiniteSolve {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "solve {}: {}", self.solve, self.inertia)
    }
}

/// How many positive pivots a matrix whose `K` is positive definite on the
/// active constraints' null space has (module docs): one per free-dof row
/// (`..constraints_from`), whatever its assembled `diagonal`, and one per
/// constraint row whose assembled diagonal is positive (an inactive
/// multiplier's unit diagonal; an active multiplier or a tie has
/// `-eps D <= 0`). Without the layout hint (`None`) every row is counted by
/// its diagonal.
pub fn expected_positive_pivots(diagonal: &[f64], constraints_from: Option<usize>) -> usize {
    let first = constraints_from.map_or(0, |f| f.min(diagonal.len()));
    first + diagonal[first..].iter().filter(|&&d| d > 0.0).count()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Free-dof rows count whatever their diagonal; constraint rows by it.
    #[test]
    fn free_rows_count_whatever_their_diagonal() {
        let diagonal = [-0.41, 2.0, 0.0, 1.0, -1e-8];
        assert_eq!(expected_positive_pivots(&diagonal, Some(2)), 3);
        assert_eq!(expected_positive_pivots(&diagonal, None), 2);
        assert_eq!(expected_positive_pivots(&diagonal, Some(9)), 5);
        let i = Inertia {
            positive: 2,
            expected: 3,
        };
        assert!(!i.is_expected());
        assert_eq!(
            IndefiniteSolve {
                solve: 4,
                inertia: i
            }
            .to_string(),
            "solve 4: 2 positive pivots, 3 expected"
        );
    }
}
