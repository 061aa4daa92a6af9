//! Watching a solve from outside: a report at the end of every scheduled
//! load step and of every cut-back, and a stop request
//! ([`crate::solve_monitored`]).
//!
//! A [`Monitor`] is told when a scheduled step has converged
//! ([`Monitor::step_done`]), when an attempt failed and its increment
//! is halved ([`Monitor::cut_back`]) and of every Newton iterate's residual
//! ([`Monitor::iteration`]), so that a long run can show where it is, also
//! inside a step. [`Monitor::stop_requested`] is asked before every Newton iteration
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

/// Where a solve is inside an attempt: one evaluated Newton iterate.
#[derive(Debug, Clone, PartialEq)]
pub struct IterationProgress {
    /// The load factor the attempt is heading for.
    pub target: f64,
    /// The iterate's number in this Newton solve (0: its start).
    pub iteration: usize,
    /// Its residual norm.
    pub residual: f64,
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

    /// A Newton iterate has been evaluated (its residual assembled).
    fn iteration(&self, _progress: &IterationProgress) {}

    /// Whether the solve should stop now.
    fn stop_requested(&self) -> bool {
        false
    }
}

/// The monitor of [`crate::solve`]: reports nowhere, never stops.
#[derive(Debug, Clone, Copy, Default)]
pub struct Silent;

impl Monitor for Silent {}

#[cfg(test)]
mod tests {
    use std::sync::Mutex;

    use super::*;
    use crate::{Scene, SolveOptions, SolverError, solve, solve_monitored};

    /// Records every report; stops once `stop_after` steps are done.
    struct Recorder {
        steps: Mutex<Vec<StepProgress>>,
        iterates: Mutex<Vec<IterationProgress>>,
        stop_after: usize,
    }

    impl Monitor for Recorder {
        fn step_done(&self, progress: &StepProgress) {
            self.steps.lock().unwrap().push(progress.clone());
        }

        fn iteration(&self, progress: &IterationProgress) {
            self.iterates.lock().unwrap().push(progress.clone());
        }

        fn stop_requested(&self) -> bool {
            self.steps.lock().unwrap().len() >= self.stop_after
        }
    }

    fn paper() -> (Scene, SolveOptions) {
        let scene = Scene::from_toml_str(crate::scenes::STACKED_CANTILEVER, "paper").unwrap();
        let options = SolveOptions::from_scene(&scene);
        (scene, options)
    }

    /// A monitor that does not stop the solve changes nothing in it, and
    /// hears of every scheduled step with its iterations.
    #[test]
    fn a_monitor_hears_every_step_and_changes_nothing() {
        let (scene, options) = paper();
        let recorder = Recorder {
            steps: Mutex::new(Vec::new()),
            iterates: Mutex::new(Vec::new()),
            stop_after: usize::MAX,
        };
        let watched = solve_monitored::<2>(&scene, &options, &recorder).unwrap();
        let plain = solve::<2>(&scene, &options).unwrap();
        assert_eq!(
            watched.strain_energy.to_bits(),
            plain.strain_energy.to_bits()
        );
        assert_eq!(watched.final_state, plain.final_state);
        let steps = recorder.steps.into_inner().unwrap();
        assert_eq!(steps.len(), options.steps);
        for (k, p) in steps.iter().enumerate() {
            assert_eq!((p.step, p.steps), (k + 1, options.steps));
            assert_eq!(p.iterations, plain.step_records[k].iterations);
            assert_eq!(p.load_factor, plain.step_records[k].load_factor);
        }
        // every iterate is reported: a step's converged attempt ends with
        // the reports of its residual history, bit for bit, in time order
        let iterates = recorder.iterates.into_inner().unwrap();
        for record in &plain.step_records {
            let toward: Vec<u64> = iterates
                .iter()
                .filter(|i| i.target == record.load_factor)
                .map(|i| i.residual.to_bits())
                .collect();
            let tail = &toward[toward.len() - record.residuals.len()..];
            let expected: Vec<u64> = record.residuals.iter().map(|r| r.to_bits()).collect();
            assert_eq!(tail, expected.as_slice());
        }
        assert!(iterates.windows(2).all(|w| w[0].elapsed <= w[1].elapsed));
    }

    /// Asked to stop after the first step, the solve stops at once with
    /// the load factor it reached.
    #[test]
    fn a_stop_request_ends_the_solve_at_the_converged_load_factor() {
        let (scene, options) = paper();
        let recorder = Recorder {
            steps: Mutex::new(Vec::new()),
            iterates: Mutex::new(Vec::new()),
            stop_after: 1,
        };
        let err = solve_monitored::<2>(&scene, &options, &recorder).unwrap_err();
        let first = solve::<2>(&scene, &options).unwrap().step_records[0].load_factor;
        assert_eq!(err, SolverError::Interrupted { load_factor: first });
        assert_eq!(recorder.steps.into_inner().unwrap().len(), 1);
    }
}
