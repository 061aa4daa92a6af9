//! One attempt: Newton's method from the converged state of a [`Run`] to a
//! target load factor (see [`super`], steps 1–4 and the failure list).
//!
//! An attempt works on an [`Iterate`], a copy of the converged state, and
//! ends in an [`AttemptOutcome`]: converged (the caller commits it) or a
//! cut-back request with the reason, the residual history and the
//! iterations spent. Each iteration: contact evaluation
//! (`Run::evaluate_contact`), contact and solid assembly, the convergence
//! test (at a converged iterate the complete formulation lets the pairing
//! guard settle the pairing, `Run::settle_pairing`, before `Run::accept`),
//! the divergence tests, the regularised solve and the correction
//! ([`Iterate::correct`]).
//! Errors that a smaller increment cannot cure (a kernel failure at the
//! converged state, when the Taylor coefficients of Types 1–6 are built)
//! are returned as `Err` and stop the solve.
//!
//! Invariants: the iteration count is the number of linear solves; the
//! residual history holds one entry per evaluated iterate (one more per
//! pairing change of the complete formulation, which evaluates the same
//! iterate again); the order of the phases within an iteration is that of
//! [`Setup`](super::Setup) (contact, solid, regularised solve).

use std::time::Instant;

use contact_kernels::ApproxType;

use crate::contact::{PointEval, Taylor};
use crate::error::SolverError;
use crate::ids::{ContactPointIndex, MasterSegmentIndex};
use crate::options::Method;
use crate::solution::{ContactPointId, CutbackReason};

use super::iterate::Iterate;
use super::outcome::{AttemptOutcome, Converged, PointsReport};
use super::pairing::{GuardOutcome, PairingGuard};
use super::{DIVERGENCE_FACTOR, REPAIR_AT_ONCE_ITERATIONS, Run, STAGNATION_FACTOR};

impl Run<'_> {
    /// Builds the frozen Taylor coefficients at the converged state (Types
    /// 1–6), re-pairing every point.
    fn ensure_taylor(&mut self, ty: ApproxType) -> Result<(), SolverError> {
        if self.taylor.is_some() {
            return Ok(());
        }
        // a tie of Types 1-6 lasts one step (`repair.rs`)
        self.ties.clear();
        self.tie_taylor.clear();
        let t = Instant::now();
        let (evals, counts) = self
            .setup
            .layout
            .evaluate_all(&self.setup.model.mesh, &self.u, &self.pairing, ty)
            .map_err(|f| self.setup.kernel_error(&f, self.load_factor))?;
        self.counts += counts;
        self.pairing = evals.iter().map(|e| e.map(|e| e.master)).collect();
        let taylor = evals
            .into_iter()
            .map(|e| e.map(|at_start| Taylor::at(at_start, &self.u)))
            .collect();
        self.taylor = Some(taylor);
        self.timings.contact_evaluation += t.elapsed();
        Ok(())
    }

    /// One Newton solve from the converged state to load factor `to` (module
    /// docs); for Types 1–6 followed by the step-end check and, while the
    /// pairing changes, repeated with the new pairing's expansion (see
    /// `repair.rs`).
    pub(super) fn attempt(&mut self, to: f64) -> Result<AttemptOutcome, SolverError> {
        let Method::Approx(ty) = self.opts.method else {
            return self.newton(to);
        };
        self.ensure_taylor(ty)?;
        self.repaired_attempt(ty, to)
    }

    /// Newton's method from the converged state to load factor `to` with
    /// the current Taylor coefficients (Types 1–6) or the complete
    /// formulation.
    pub(super) fn newton(&mut self, to: f64) -> Result<AttemptOutcome, SolverError> {
        self.newton_from(to, None)
    }

    /// [`Run::newton`] starting from the displacements and multipliers
    /// `warm` (an earlier attempt's converged end at the same `to`)
    /// instead of the converged state; the pairing and ties are the
    /// run's.
    pub(super) fn newton_from(
        &mut self,
        to: f64,
        warm: Option<(Vec<f64>, Vec<f64>)>,
    ) -> Result<AttemptOutcome, SolverError> {
        let (u, lambda) = warm.unwrap_or_else(|| (self.u.clone(), self.lambda.clone()));
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
        let mut extrapolated = false;
        if let (Some(l), Some(previous)) = (&lift, &self.previous_u)
            && let Some(s) = self.setup.extrapolation(l, &x.u, previous)
        {
            for (u, p) in x.u.iter_mut().zip(previous) {
                *u += s * (*u - p);
            }
            lift = self.setup.lift(&x.u, to);
            extrapolated = true;
        }
        let mut guard = PairingGuard::default();
        let mut residuals = Vec::new();
        // index into `residuals` of the first iterate with the current pairing
        let mut phase_start = 0;
        let mut it = 0;
        loop {
            self.check_stop()?;
            // contact
            let t = Instant::now();
            // complete formulation: re-pair at once in the first iterates,
            // until the first pairing change at a converged iterate
            let at_once = ((1..=REPAIR_AT_ONCE_ITERATIONS).contains(&it)
                || (it == 0 && extrapolated))
                && phase_start == 0;
            let (evals, others) = match self.evaluate_contact(&mut x, at_once) {
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
            self.timings.solid_assembly += t.elapsed();

            let norm = sys.residual_norm();
            residuals.push(norm);
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
                let mut kept = Vec::new();
                if self.opts.method == Method::Complete {
                    match self.settle_pairing(&mut guard, &mut x, &evals) {
                        Ok(Settling::Changed) => {
                            // the same iterate again, with the new pairing
                            phase_start = residuals.len();
                            continue;
                        }
                        Ok(Settling::Settled(k)) => kept = k,
                        Err(reason) => return Ok(AttemptOutcome::cut_back(reason, residuals, it)),
                    }
                }
                let points = self.accept(&mut x, &evals, &active, kept);
                let t = Instant::now();
                let reactions = self
                    .setup
                    .reactions(&x.u, &x.lambda, &x.ties, &evals, &others, &active, to);
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
            let solved = self
                .setup
                .solve(&mut sys, &active, self.opts.regularization);
            self.timings.linear_solve += t.elapsed();
            self.setup.recycle(sys);
            let dx = match solved {
                Ok(dx) => dx,
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

    /// The contact evaluation of the current iterate: Types 1–6 expand the
    /// frozen Taylor coefficients; the complete formulation evaluates the
    /// exact kernel (re-pairing every point when `at_once`) and takes the
    /// pairing the evaluation ended with.
    fn evaluate_contact(
        &mut self,
        x: &mut Iterate,
        at_once: bool,
    ) -> Result<(Vec<Option<PointEval>>, Vec<PointEval>), CutbackReason> {
        match self.opts.method {
            Method::Approx(_) => {
                let taylor = self.taylor.as_deref().unwrap_or(&[]);
                let evals: Vec<Option<PointEval>> =
                    taylor.iter().map(|t| t.map(|t| t.expand(&x.u))).collect();
                let others = self.tie_taylor.iter().map(|t| t.expand(&x.u)).collect();
                Ok((evals, others))
            }
            Method::Complete => {
                match self.setup.evaluate_complete(
                    &x.u,
                    &x.pairing,
                    &x.ties,
                    at_once,
                    &mut self.counts,
                ) {
                    Ok((evals, others)) => {
                        x.pairing = evals.iter().map(|e| e.map(|e| e.master)).collect();
                        Ok((evals, others))
                    }
                    Err(f) => Err(CutbackReason::Kernel {
                        point: self.setup.failure_point(&f),
                        error: f.error,
                    }),
                }
            }
        }
    }

    /// Complete formulation, at a converged iterate: the pairing guard's
    /// update (see [`PairingGuard::update`]); a stuck point or a kernel
    /// failure asks for a cut-back.
    fn settle_pairing(
        &mut self,
        guard: &mut PairingGuard,
        x: &mut Iterate,
        evals: &[Option<PointEval>],
    ) -> Result<Settling, CutbackReason> {
        let t = Instant::now();
        let outcome = guard.update(
            &self.setup,
            &x.u,
            &x.lambda,
            evals,
            &mut x.pairing,
            &mut x.ties,
        );
        self.timings.contact_evaluation += t.elapsed();
        match outcome {
            Ok((outcome, counts)) => {
                self.counts += counts;
                match outcome {
                    GuardOutcome::Changed => Ok(Settling::Changed),
                    GuardOutcome::Settled(k) => Ok(Settling::Settled(k)),
                    GuardOutcome::Stuck { point, xi_m } => {
                        let point = ContactPointId {
                            master_segment: x.pairing[point.index()].map(MasterSegmentIndex::index),
                            ..self.setup.point_id(point)
                        };
                        Err(CutbackReason::StuckAtMasterNode { point, xi_m })
                    }
                }
            }
            Err(f) => Err(CutbackReason::Kernel {
                point: self.setup.failure_point(&f),
                error: f.error,
            }),
        }
    }

    /// Accepts the iterate `x` with contact evaluations `evals` and active
    /// set `active` (the inactive multipliers are set to exactly zero), with
    /// the points `kept` outside their segment: the points' report.
    fn accept(
        &self,
        x: &mut Iterate,
        evals: &[Option<PointEval>],
        active: &[bool],
        kept: Vec<ContactPointIndex>,
    ) -> PointsReport {
        let unpaired = self
            .setup
            .layout
            .points
            .iter()
            .zip(evals)
            .filter(|(_, e)| e.is_none())
            .map(|(p, _)| ContactPointId {
                pair: p.pair.index(),
                slave_segment: p.slave_segment,
                gauss: p.gauss,
                master_segment: None,
            })
            .collect();
        // inactive rows read l_a = 0 (satisfied to round-off): make it exact
        for (l, &on) in x.lambda.iter_mut().zip(active) {
            if !on {
                *l = 0.0;
            }
        }
        let pairing = &x.pairing;
        let with_master = |i: ContactPointIndex| ContactPointId {
            master_segment: pairing[i.index()].map(MasterSegmentIndex::index),
            ..self.setup.point_id(i)
        };
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

/// The pairing guard's decision at a converged iterate, for the attempt.
enum Settling {
    /// Points were re-paired, tied or released: evaluate the same iterate
    /// again.
    Changed,
    /// The pairing stands; the points kept outside their segment.
    Settled(Vec<ContactPointIndex>),
}
