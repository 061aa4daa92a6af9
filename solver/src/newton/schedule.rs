//! The load schedule: `N` equal scheduled steps from 0 to the model's final
//! load factor, each reached by one or more attempts whose increment is
//! halved after every failure (bisection cut-back); the rest of a step is
//! then done with the halved increment.
//!
//! Invariants: a scheduled step ends exactly on its target `end step / N`
//! (an increment within `1e-9` relative of the remainder takes the target
//! itself); a step gives up after more than `max_cutbacks` cut-backs or when
//! a further halving could not advance the load factor (`|increment / 2| <=
//! 1e-12 |end|`).

use crate::error::SolverError;
use crate::solution::CutbackReason;

/// One scheduled step in progress: its target and the current increment.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct ScheduledStep {
    /// The final load factor of the schedule.
    end: f64,
    /// This step's target load factor.
    target: f64,
    /// The increment of the next attempt (halved by each cut-back).
    increment: f64,
    /// Cut-backs so far in this step.
    cuts: usize,
}

impl ScheduledStep {
    /// Step `step` (1-based) of `steps` towards `end`, starting at the
    /// converged load factor `load_factor`.
    pub(super) fn new(step: usize, steps: usize, end: f64, load_factor: f64) -> ScheduledStep {
        let target = end * step as f64 / steps as f64;
        ScheduledStep {
            end,
            target,
            increment: target - load_factor,
            cuts: 0,
        }
    }

    /// The target load factor of the next attempt from the converged
    /// `load_factor`, or `None` when the step is done.
    pub(super) fn next_target(&self, load_factor: f64) -> Option<f64> {
        let (end, target) = (self.end, self.target);
        if !((target - load_factor).abs() > 1e-12 * end.abs().max(f64::MIN_POSITIVE)) {
            return None;
        }
        let remaining = target - load_factor;
        Some(if self.increment / remaining >= 1.0 - 1e-9 {
            target
        } else {
            load_factor + self.increment
        })
    }

    /// Records a failed attempt: halves the increment, or returns
    /// `Err(cutbacks)` (the cut-backs before this failure) when the step
    /// gives up (module docs).
    pub(super) fn cut_back(&mut self, max_cutbacks: usize) -> Result<(), usize> {
        self.cuts += 1;
        // a further halving could not advance the load factor
        let exhausted = (self.increment / 2.0).abs() <= 1e-12 * self.end.abs();
        if self.cuts > max_cutbacks || exhausted {
            return Err(self.cuts - 1);
        }
        self.increment /= 2.0;
        Ok(())
    }
}

/// The error that ends a solve whose step `step`, from the converged
/// `load_factor`, failed towards `attempted` after `cutbacks` cut-backs with
/// `reason`.
pub(super) fn give_up(
    step: usize,
    load_factor: f64,
    attempted: f64,
    cutbacks: usize,
    reason: CutbackReason,
) -> SolverError {
    match reason {
        CutbackReason::Singular { message } => SolverError::Singular {
            load_factor,
            attempted,
            cutbacks,
            message,
        },
        CutbackReason::Kernel { point, error } => SolverError::Kernel {
            point,
            load_factor: attempted,
            error,
        },
        reason => SolverError::Diverged {
            step,
            load_factor,
            attempted,
            cutbacks,
            reason,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A step that fails twice: halved, halved again, then completed with
    /// the quarter increment; the last cut-back allowed is the
    /// `max_cutbacks`-th.
    #[test]
    fn bisection_reaches_the_target() {
        let mut s = ScheduledStep::new(1, 4, 2.0, 0.0);
        assert_eq!(s.next_target(0.0), Some(0.5));
        assert_eq!(s.cut_back(2), Ok(()));
        assert_eq!(s.next_target(0.0), Some(0.25));
        assert_eq!(s.cut_back(2), Ok(()));
        assert_eq!(s.next_target(0.0), Some(0.125));
        assert_eq!(s.next_target(0.125), Some(0.25));
        assert_eq!(s.next_target(0.375), Some(0.5));
        assert_eq!(s.next_target(0.5), None);
        assert_eq!(s.cut_back(2), Err(2));
        // the second step starts from the first one's target
        assert_eq!(
            ScheduledStep::new(2, 4, 2.0, 0.5).next_target(0.5),
            Some(1.0)
        );
    }
}
