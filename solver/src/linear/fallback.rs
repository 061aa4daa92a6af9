//! Why a solve of the LDLᵀ gave way to the LU, and whether the LU may run.
//!
//! [`super::SparseLdlt`] factorises the quasi-definite saddle point without
//! pivoting; a solve that fails one of its safety checks (its module docs)
//! is factorised again by [`super::SparseLu`]. Each such solve leaves a
//! [`Fallback`]: which check failed ([`FallbackReason`], with its numbers)
//! and what the LU did ([`LuOutcome`]), so that a run can say why it fell
//! back (`gapsim run`'s summary, [`crate::linear::LinearSolver::fallback_log`]).
//!
//! # The LU's memory
//!
//! With partial pivoting and an unsymmetric ordering, the LU of a 3D model
//! holds several times the LDLᵀ's factor (3D Hertz, one step, peak resident
//! memory: 9.2 GiB against 1.9 GiB on the hexahedral mesh, 1.05 against
//! 0.52 GiB on the tetrahedral one), allocated in the middle of a Newton
//! iteration that the memory guard before the solve ([`crate::memory`]) let
//! through on the LDLᵀ's estimate. No estimate made before the numeric LU
//! bounds it (its fill depends on the pivots it chooses), and where the
//! system overcommits memory, as Linux does by default, an allocation past
//! the memory there is does not fail: the process is killed when it
//! touches the pages. So the LU factorises under an address-space limit of
//! this process's present size plus `MemAvailable`
//! ([`crate::meminfo::AddressSpaceLimit`], Linux), read after the LDLᵀ's
//! values are released. An LU that needs more fails its allocation
//! ([`LuOutcome::OutOfMemory`]) and the solve is a
//! [`super::LinearError::OutOfMemory`], which Newton treats as any failed
//! solve: the attempt is cut back, and a smaller increment's LDLᵀ may pass
//! its checks. Measured on the 3D Hertz scene on non-matching hexahedra at
//! h = 0.07 (147228 equations, segmented integration, dual multipliers),
//! where the system killed the run without a limit: docs/benchmarks.md.

use std::fmt;

/// Which of the LDLᵀ's safety checks a solve failed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FallbackReason {
    /// faer's numeric factorisation stopped, or a pivot is zero or not
    /// finite.
    Pivot,
    /// The refined solution is not finite.
    NonFinite,
    /// The normwise backward error after the last refinement step.
    BackwardError {
        /// `|b - A x|_inf / (|A|_inf |x|_inf + |b|_inf)`.
        backward_error: f64,
        /// Refinement steps taken.
        refinements: usize,
    },
}

impl fmt::Display for FallbackReason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FallbackReason::Pivot => write!(f, "a zero or non-finite pivot"),
            FallbackReason::NonFinite => write!(f, "a non-finite solution"),
            FallbackReason::BackwardError {
                backward_error,
                refinements,
            } => write!(
                f,
                "backward error {backward_error:.1e} after {refinements} refinement steps"
            ),
        }
    }
}

/// What the LU did for a solve the LDLᵀ gave up.
#[derive(Debug, Clone, PartialEq)]
pub enum LuOutcome {
    /// It factorised and solved.
    Solved,
    /// It failed (its message: out of memory, singular).
    Failed(String),
    /// It could not allocate its factor within the memory the system had
    /// available (module docs).
    OutOfMemory {
        /// `MemAvailable` when it started, bytes (`None`: unknown, not
        /// limited; an allocation failed all the same).
        available: Option<u64>,
        /// Its error.
        message: String,
    },
}

/// One solve the LDLᵀ gave up (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct Fallback {
    /// The solve, counted from 1 over the solver's life.
    pub solve: usize,
    /// The check it failed.
    pub reason: FallbackReason,
    /// What the LU did.
    pub lu: LuOutcome,
}

impl fmt::Display for Fallback {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "solve {}: {}; ", self.solve, self.reason)?;
        match &self.lu {
            LuOutcome::Solved => write!(f, "solved by the LU"),
            LuOutcome::Failed(message) => write!(f, "the LU failed ({message})"),
            LuOutcome::OutOfMemory {
                available: Some(available),
                message,
            } => write!(
                f,
                "the LU did not fit in the {} MiB available ({message})",
                available >> 20
            ),
            LuOutcome::OutOfMemory {
                available: None,
                message,
            } => write!(f, "the LU ran out of memory ({message})"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_fallback_says_why_and_what_the_lu_did() {
        let f = Fallback {
            solve: 3,
            reason: FallbackReason::BackwardError {
                backward_error: 3e-9,
                refinements: 3,
            },
            lu: LuOutcome::OutOfMemory {
                available: Some(2 << 30),
                message: "numeric LU: Generic(OutOfMemory)".into(),
            },
        };
        assert_eq!(
            f.to_string(),
            "solve 3: backward error 3.0e-9 after 3 refinement steps; \
             the LU did not fit in the 2048 MiB available (numeric LU: Generic(OutOfMemory))"
        );
    }
}
