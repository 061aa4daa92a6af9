//! One attempt: Newton's method from the converged state of a [`Run`] to a
//! target load factor (see [`super`], steps 1–4 and the failure list).
//!
//! An attempt works on copies of the converged state and ends in an
//! [`AttemptOutcome`]: converged (the caller commits it) or a cut-back
//! request with the reason, the residual history and the iterations spent.
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

use crate::contact::{NodeTie, PointEval, Taylor};
use crate::error::SolverError;
use crate::ids::{ContactPointIndex, DofId, MultiplierIndex};
use crate::options::Method;
use crate::solution::{ContactPointId, CutbackReason};

use super::pairing::{GuardOutcome, PairingGuard};
use super::{DIVERGENCE_FACTOR, REPAIR_AT_ONCE_ITERATIONS, Run, STAGNATION_FACTOR};

/// A converged attempt.
pub(super) struct Converged {
    pub(super) u: Vec<f64>,
    pub(super) lambda: Vec<f64>,
    pub(super) pairing: Vec<Option<usize>>,
    pub(super) iterations: usize,
    pub(super) residuals: Vec<f64>,
    pub(super) energy: f64,
    pub(super) active_multipliers: usize,
    pub(super) ties: Vec<NodeTie>,
    pub(super) unpaired: Vec<ContactPointId>,
    pub(super) node_ties: Vec<ContactPointId>,
    pub(super) kept_outside: Vec<ContactPointId>,
    pub(super) roundoff_floor: bool,
}

/// A failed attempt: the caller cuts the increment back.
pub(super) struct Failed {
    /// Why the attempt failed.
    pub(super) reason: CutbackReason,
    /// The residual norms of the evaluated iterates.
    pub(super) residuals: Vec<f64>,
    /// Linear solves spent.
    pub(super) iterations: usize,
}

/// How an attempt ended.
pub(super) enum AttemptOutcome {
    /// Converged: the new converged state.
    Converged(Converged),
    /// Failed: cut back.
    CutBack(Failed),
}

impl AttemptOutcome {
    fn cut_back(reason: CutbackReason, residuals: Vec<f64>, iterations: usize) -> AttemptOutcome {
        AttemptOutcome::CutBack(Failed {
            reason,
            residuals,
            iterations,
        })
    }
}

impl Run<'_> {
    /// Builds the frozen Taylor coefficients at the converged state (Types
    /// 1–6), re-pairing every point.
    fn ensure_taylor(&mut self, ty: ApproxType) -> Result<(), SolverError> {
        if self.taylor.is_some() {
            return Ok(());
        }
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
            .map(|e| {
                e.map(|at_start| Taylor {
                    u0: nalgebra::SVector::<f64, 8>::from_fn(|k, _| {
                        self.u[2 * at_start.nodes[k / 2] + k % 2]
                    }),
                    at_start,
                })
            })
            .collect();
        self.taylor = Some(taylor);
        self.timings.contact_evaluation += t.elapsed();
        Ok(())
    }

    /// One Newton solve from the converged state to load factor `to` (module
    /// docs).
    pub(super) fn attempt(&mut self, to: f64) -> Result<AttemptOutcome, SolverError> {
        if let Method::Approx(ty) = self.opts.method {
            self.ensure_taylor(ty)?;
        }
        let mut u = self.u.clone();
        self.setup.prescribe(&mut u, to);
        let mut lambda = self.lambda.clone();
        let mut pairing = self.pairing.clone();
        let mut ties = self.ties.clone();
        let mut guard = PairingGuard::default();
        let mut residuals = Vec::new();
        // index into `residuals` of the first iterate with the current pairing
        let mut phase_start = 0;
        let mut it = 0;
        loop {
            // contact
            let t = Instant::now();
            let (evals, others) = match self.opts.method {
                Method::Approx(_) => {
                    let taylor = self.taylor.as_deref().unwrap_or(&[]);
                    let evals: Vec<Option<PointEval>> =
                        taylor.iter().map(|t| t.map(|t| t.expand(&u))).collect();
                    (evals, Vec::new())
                }
                Method::Complete => {
                    // re-pair at once in the first iterates, until the first
                    // pairing change at a converged iterate
                    let at_once = (1..=REPAIR_AT_ONCE_ITERATIONS).contains(&it) && phase_start == 0;
                    match self.setup.evaluate_complete(
                        &u,
                        &pairing,
                        &ties,
                        at_once,
                        &mut self.counts,
                    ) {
                        Ok((evals, others)) => {
                            pairing = evals.iter().map(|e| e.map(|e| e.master)).collect();
                            (evals, others)
                        }
                        Err(f) => {
                            self.timings.contact_evaluation += t.elapsed();
                            let point = self.setup.failure_point(&f);
                            return Ok(AttemptOutcome::cut_back(
                                CutbackReason::Kernel {
                                    point,
                                    error: f.error,
                                },
                                residuals,
                                it,
                            ));
                        }
                    }
                }
            };
            let (mut sys, active) = self.setup.contact_system(&evals, &others, &lambda, &ties);
            self.timings.contact_evaluation += t.elapsed();
            // solid
            let t = Instant::now();
            let f_ext = self.setup.add_solid(&u, to, &mut sys);
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
            if norm <= tol_abs || at_floor {
                let mut kept = Vec::new();
                if self.opts.method == Method::Complete {
                    let t = Instant::now();
                    let outcome =
                        guard.update(&self.setup, &u, &lambda, &evals, &mut pairing, &mut ties);
                    self.timings.contact_evaluation += t.elapsed();
                    match outcome {
                        Ok((outcome, counts)) => {
                            self.counts += counts;
                            match outcome {
                                GuardOutcome::Changed => {
                                    // the same iterate again, with the new pairing
                                    phase_start = residuals.len();
                                    continue;
                                }
                                GuardOutcome::Settled(k) => kept = k,
                                GuardOutcome::Stuck { point, xi_m } => {
                                    let point = ContactPointId {
                                        master_segment: pairing[point.index()],
                                        ..self.setup.point_id(point)
                                    };
                                    return Ok(AttemptOutcome::cut_back(
                                        CutbackReason::StuckAtMasterNode { point, xi_m },
                                        residuals,
                                        it,
                                    ));
                                }
                            }
                        }
                        Err(f) => {
                            let point = self.setup.failure_point(&f);
                            return Ok(AttemptOutcome::cut_back(
                                CutbackReason::Kernel {
                                    point,
                                    error: f.error,
                                },
                                residuals,
                                it,
                            ));
                        }
                    }
                }
                let unpaired = self
                    .setup
                    .layout
                    .points
                    .iter()
                    .zip(&evals)
                    .filter(|(_, e)| e.is_none())
                    .map(|(p, _)| ContactPointId {
                        pair: p.pair.index(),
                        slave_segment: p.slave_segment,
                        gauss: p.gauss,
                        master_segment: None,
                    })
                    .collect();
                // inactive rows read l_a = 0 (satisfied to round-off): make it exact
                for (l, &on) in lambda.iter_mut().zip(&active) {
                    if !on {
                        *l = 0.0;
                    }
                }
                let with_master = |i: ContactPointIndex| ContactPointId {
                    master_segment: pairing[i.index()],
                    ..self.setup.point_id(i)
                };
                let node_ties = ties.iter().map(|t| with_master(t.point)).collect();
                let kept_outside = kept.into_iter().map(with_master).collect();
                return Ok(AttemptOutcome::Converged(Converged {
                    u,
                    lambda,
                    pairing,
                    ties,
                    iterations: it,
                    residuals,
                    energy: sys.energy,
                    active_multipliers: active.iter().filter(|a| **a).count(),
                    unpaired,
                    node_ties,
                    kept_outside,
                    roundoff_floor: norm > tol_abs,
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
            let dofs = &self.setup.dofs;
            for (dof, ud) in u.iter_mut().enumerate() {
                if let Some(e) = dofs.eq(DofId::new(dof)) {
                    *ud -= dx[e.index()];
                }
            }
            for (m, l) in lambda.iter_mut().enumerate() {
                *l -= dx[dofs.mult_eq(MultiplierIndex::new(m)).index()];
            }
            for (k, tie) in ties.iter_mut().enumerate() {
                tie.mu -= dx[dofs.tie_eq(k).index()];
            }
            it += 1;
        }
    }
}
