//! One attempt: Newton's method from the converged state of a [`Run`] to a
//! target load factor (see [`super`], steps 1–4 and the failure list),
//! the same loop for every treatment of contact ([`super::treatment`]).
//!
//! An attempt works on an [`Iterate`], a copy of the converged state, and
//! ends in an [`AttemptOutcome`]: converged (the caller commits it) or a
//! cut-back request with the reason, the residual history and the
//! iterations spent. It starts with the treatment's
//! [`begin_attempt`](ContactTreatment::begin_attempt) and runs Newton
//! solves until the treatment's
//! [`end_solve`](ContactTreatment::end_solve) accepts one (Types 1–6 solve
//! the step again while the pairing at its end changes, `repair.rs`).
//! Each iteration: the check that the iterate inverts no element (one
//! that does is cut back: [`crate::mesh::inversion`]), the treatment's
//! contact evaluation, contact and solid assembly, the convergence test (at a converged iterate the treatment
//! settles the pairing, before `Run::accept`), the divergence tests, the
//! regularised solve and the correction ([`Iterate::correct`]).
//! Errors that a smaller increment cannot cure (a kernel failure at the
//! converged state, when the Taylor coefficients of Types 1–6 are built)
//! are returned as `Err` and stop the solve.
//!
//! Invariants: the iteration count is the number of linear solves; the
//! residual history holds one entry per evaluated iterate (one more per
//! pairing change at a converged iterate, which evaluates the same
//! iterate again); the order of the phases within an iteration is that of
//! [`Setup`](super::Setup) (contact, solid, regularised solve).

use std::time::Instant;

use crate::contact::ContactSpace;
use crate::error::SolverError;
use crate::ids::ContactPointIndex;
use crate::monitor::IterationProgress;
use crate::solution::CutbackReason;

use super::iterate::Iterate;
use super::outcome::{AttemptOutcome, Converged, PointsReport};
use super::treatment::{ContactTreatment, Context, Settling, SolveEnd, StepStart};
use super::{DIVERGENCE_FACTOR, REPAIR_AT_ONCE_ITERATIONS, Run, STAGNATION_FACTOR};
use crate::model::{Dim, SurfaceDim};

impl<'a, const D: usize, S: ContactSpace<D>> Run<'a, D, S>
where
    Dim<D>: SurfaceDim<D>,
{
    /// The contact treatment with what it works on: the solve's context and
    /// the run's converged state.
    #[allow(clippy::type_complexity)] // the three borrows of the run
    fn split_treatment<'s>(
        &'s mut self,
        predictor: Option<&'s [f64]>,
    ) -> (
        &'s mut dyn ContactTreatment<D, S>,
        Context<'s, 'a, D, S>,
        StepStart<'s, S::Master>,
    ) {
        (
            &mut *self.treatment,
            Context {
                setup: &self.setup,
                opts: self.opts,
                counts: &mut self.counts,
                timings: &mut self.timings,
            },
            StepStart {
                u: &self.u,
                pairing: &mut self.pairing,
                ties: &mut self.ties,
                load_factor: self.load_factor,
                predictor,
            },
        )
    }

    /// One attempt from the converged state to load factor `to` (module
    /// docs): Newton solves until the treatment accepts one.
    pub(super) fn attempt(&mut self, to: f64) -> Result<AttemptOutcome<D, S::Master>, SolverError> {
        let predictor = self.predictor(to);
        let (treatment, mut cx, start) = self.split_treatment(predictor.as_deref());
        treatment.begin_attempt(&mut cx, start)?;
        let mut warm = None;
        loop {
            let outcome = self.newton_from(to, warm.take(), predictor.as_deref())?;
            let AttemptOutcome::Converged(c) = outcome else {
                return Ok(outcome);
            };
            let (treatment, mut cx, start) = self.split_treatment(predictor.as_deref());
            match treatment.end_solve(&mut cx, start, c)? {
                SolveEnd::Done(outcome) => return Ok(*outcome),
                SolveEnd::Again { warm: w, spent } => {
                    self.repeated_iterations += spent;
                    warm = Some(w);
                }
            }
        }
    }

    /// The secant predictor of an attempt towards `to` (module docs of
    /// `super`, "Prescribed increments"): the converged displacements
    /// extrapolated along the last step's increment, where the prescribed
    /// dofs move and the last step moved them the same way; `None`
    /// otherwise (Newton starts from the converged state).
    fn predictor(&self, to: f64) -> Option<Vec<f64>> {
        let lift = self.setup.lift(&self.u, to)?;
        let previous = self.previous_u.as_ref()?;
        let s = self.setup.extrapolation(&lift, &self.u, previous)?;
        Some(
            self.u
                .iter()
                .zip(previous)
                .map(|(u, p)| u + s * (u - p))
                .collect(),
        )
    }

    /// Newton's method to load factor `to` from the displacements and
    /// multipliers `warm` (an earlier solve's converged end at the same
    /// `to`), or else from the `predictor` ([`Run::predictor`]) or the
    /// converged state; the pairing and ties are the run's.
    fn newton_from(
        &mut self,
        to: f64,
        warm: Option<(Vec<f64>, Vec<f64>)>,
        predictor: Option<&[f64]>,
    ) -> Result<AttemptOutcome<D, S::Master>, SolverError> {
        let extrapolated = warm.is_none() && predictor.is_some();
        let (u, lambda) = warm.unwrap_or_else(|| {
            let u = predictor.map_or_else(|| self.u.clone(), <[f64]>::to_vec);
            (u, self.lambda.clone())
        });
        let mut x = Iterate {
            u,
            lambda,
            pairing: self.pairing.clone(),
            ties: self.ties.clone(),
        };
        // the prescribed increment enters through the linearised predictor
        // (module docs of `super`, "Prescribed increments"); the prescribed
        // dofs take their values at `to` with the first correction
        let mut lift = self.setup.lift(&x.u, to);
        let mut residuals = Vec::new();
        // index into `residuals` of the first iterate with the current pairing
        let mut phase_start = 0;
        let mut it = 0;
        loop {
            self.check_stop()?;
            // an iterate that inverts an element is rejected, whatever its
            // residual would be
            let t = Instant::now();
            let inverted = self.setup.most_inverted(&x.u)?;
            self.timings.solid_assembly += t.elapsed();
            if let Some(inverted) = inverted {
                return Ok(AttemptOutcome::cut_back(
                    CutbackReason::InvertedElement(inverted),
                    residuals,
                    it,
                ));
            }
            // contact
            let t = Instant::now();
            // a re-projecting treatment re-pairs at once in the first
            // iterates, until the first pairing change at a converged iterate
            let at_once = ((1..=REPAIR_AT_ONCE_ITERATIONS).contains(&it)
                || (it == 0 && extrapolated))
                && phase_start == 0;
            let (treatment, mut cx, _) = self.split_treatment(None);
            let (evals, others) = match treatment.evaluate(&mut cx, &mut x, at_once) {
                Ok(e) => e,
                Err(reason) => {
                    self.timings.contact_evaluation += t.elapsed();
                    return Ok(AttemptOutcome::cut_back(reason, residuals, it));
                }
            };
            let (mut sys, active) =
                self.setup
                    .contact_system(&evals, &others, &x.lambda, &x.ties, it == 0);
            self.timings.contact_evaluation += t.elapsed();
            // solid
            let t = Instant::now();
            let f_ext = self.setup.add_solid(&x.u, lift.as_deref(), to, &mut sys);
            self.setup.sum_over_ranks(&mut sys)?;
            self.timings.solid_assembly += t.elapsed();

            let norm = sys.residual_norm();
            residuals.push(norm);
            self.monitor.iteration(&IterationProgress {
                target: to,
                iteration: it,
                residual: norm,
                elapsed: self.started.elapsed(),
            });
            if !norm.is_finite() {
                return Ok(AttemptOutcome::cut_back(
                    CutbackReason::NonFiniteResidual,
                    residuals,
                    it,
                ));
            }
            let tol_abs = self.opts.tolerance * f_ext.max(1.0);
            let last = residuals.len() - 1;
            let at_floor = last >= phase_start + 2
                && norm <= STAGNATION_FACTOR * tol_abs
                && norm >= 0.5 * residuals[last - 1];
            if lift.is_none() && (norm <= tol_abs || at_floor) {
                let (treatment, mut cx, _) = self.split_treatment(None);
                let kept = match treatment.settle(&mut cx, &mut x, &evals) {
                    Ok(Settling::Changed) => {
                        // the same iterate again, with the new pairing
                        phase_start = residuals.len();
                        continue;
                    }
                    Ok(Settling::Settled(kept)) => kept,
                    Err(reason) => return Ok(AttemptOutcome::cut_back(reason, residuals, it)),
                };
                let points = self.accept(&mut x, &evals, &active, kept);
                let friction = self.setup.layout.nodal_friction(&evals, &x.lambda, &active);
                let t = Instant::now();
                let reactions = self
                    .setup
                    .reactions(&x.u, &x.lambda, &x.ties, &evals, &others, &active, to)?;
                self.timings.reactions += t.elapsed();
                return Ok(AttemptOutcome::Converged(Converged {
                    state: x,
                    iterations: it,
                    residuals,
                    energy: sys.energy,
                    roundoff_floor: norm > tol_abs,
                    points,
                    reactions,
                    active,
                    friction,
                    step_end: None,
                }));
            }
            if it == self.opts.max_iterations {
                return Ok(AttemptOutcome::cut_back(
                    CutbackReason::MaxIterations { residual: norm },
                    residuals,
                    it,
                ));
            }
            let bound = DIVERGENCE_FACTOR * residuals[0].max(1.0);
            if norm > bound {
                return Ok(AttemptOutcome::cut_back(
                    CutbackReason::Diverging {
                        residual: norm,
                        bound,
                    },
                    residuals,
                    it,
                ));
            }
            let t = Instant::now();
            let solved = self.setup.solve(
                &mut sys,
                &active,
                self.opts.regularization,
                (norm, residuals[phase_start.min(last)], tol_abs),
            );
            self.timings.linear_solve += t.elapsed();
            self.setup.recycle(sys);
            let dx = match solved {
                Ok(dx) => dx,
                // refused by the solver whatever the step: no cut-back
                Err(e) if !e.cured_by_shorter_step() => return Err(SolverError::Linear(e)),
                Err(e) => {
                    return Ok(AttemptOutcome::cut_back(
                        CutbackReason::Singular {
                            message: e.to_string(),
                        },
                        residuals,
                        it,
                    ));
                }
            };
            x.correct(&self.setup.dofs, &dx);
            if lift.take().is_some() {
                self.setup.prescribe(&mut x.u, to);
            }
            it += 1;
        }
    }

    /// Accepts the iterate `x` with contact evaluations `evals` and active
    /// set `active` (the inactive multipliers are set to exactly zero), with
    /// the points `kept` outside their segment: the points' report.
    fn accept(
        &self,
        x: &mut Iterate<S::Master>,
        evals: &[Option<S::Eval>],
        active: &[bool],
        kept: Vec<ContactPointIndex>,
    ) -> PointsReport {
        let unpaired = evals
            .iter()
            .enumerate()
            .filter(|(_, e)| e.is_none())
            .map(|(i, _)| self.setup.point_id(ContactPointIndex::new(i)))
            .collect();
        // inactive rows read l_a = 0 (satisfied to round-off): make it exact
        for (l, &on) in x.lambda.iter_mut().zip(active) {
            if !on {
                *l = 0.0;
            }
        }
        let pairing = &x.pairing;
        let with_master = |i: ContactPointIndex| self.setup.layout.point_id(i, pairing[i.index()]);
        let node_ties = x.ties.iter().map(|t| with_master(t.point)).collect();
        let kept_outside = kept.into_iter().map(with_master).collect();
        PointsReport {
            active_multipliers: active.iter().filter(|a| **a).count(),
            unpaired,
            node_ties,
            kept_outside,
        }
    }
}
