//! Watching a solve from outside: a report at the end of every scheduled
//! load step and of every cut-back, and a stop request
//! ([`crate::solve_monitored`]).
//!
//! A [`Monitor`] is told when a scheduled step has converged
//! ([`Monitor::step_done`]) and when an attempt failed and its increment
//! is halved ([`Monitor::cut_back`]), so that a long run can show where it
//! is. [`Monitor::stop_requested`] is asked before every Newton iteration
//! and before every attempt; once it returns `true`, the solve stops with
//! [`crate::SolverError::Interrupted`] (the converged load factor reached
//! so far in it) and returns no solution. A monitor never changes a
//! result: the solve with any monitor that does not stop it is the solve
//! without one, bit for bit.

use std::time::Duration;

use crate::solution::Cutback;

/// Where a solve is at the end of a scheduled load step.
#[derive(Debug, Clone, PartialEq)]
pub struct StepProgress {
    /// The scheduled step just finished (1-based).
    pub step: usize,
    /// The scheduled steps of the solve.
    pub steps: usize,
    /// The converged load factor (the step's target).
    pub load_factor: f64,
    /// Newton iterations (linear solves) of the converged attempts of this
    /// step.
    pub iterations: usize,
    /// Cut-backs in this step.
    pub cutbacks: usize,
    /// Time since the solve started.
    pub elapsed: Duration,
}

/// What a solve reports to, and asks of, its caller (module docs). Every
/// method has a default that does nothing.
pub trait Monitor: Sync {
    /// A scheduled step has converged.
    fn step_done(&self, _progress: &StepProgress) {}

    /// An attempt failed; its increment is halved (or, past the cut-back
    /// limit, the solve gives up after this call).
    fn cut_back(&self, _cutback: &Cutback) {}

    /// Whether the solve should stop now.
    fn stop_requested(&self) -> bool {
        false
    }
}

/// The monitor of [`crate::solve`]: reports nowhere, never stops.
#[derive(Debug, Clone, Copy, Default)]
pub struct Silent;

impl Monitor for Silent {}
