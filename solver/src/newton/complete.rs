//! The complete formulation's treatment of contact (see [`super::treatment`]):
//! every iteration re-projects each point onto its paired master segment
//! and evaluates the exact gap with every derivative term
//! ([`DERIVATIVES`]); the pairing changes at once in the first iterates of
//! an attempt and otherwise only at a converged iterate, through the
//! pairing guard (`pairing.rs`; see [`crate::contact`], "Pairing in the
//! complete formulation" and "Points stuck at a master node"). A converged
//! solve whose pairing stands ends the attempt: there is no step-end
//! check.
//!
//! Invariant: the evaluations are in point order, the tied points' after
//! the regular ones in tie order; kernel calls are counted as they are
//! made.

use std::time::Instant;

use contact_kernels::ApproxType;

use crate::contact::ContactSpace;
use crate::contact::{KernelCounts, NodeTie, PointFailure};
use crate::error::SolverError;
use crate::solution::{ContactPointId, CutbackReason};

use super::iterate::Iterate;
use super::outcome::{AttemptOutcome, Converged};
use super::pairing::{GuardOutcome, PairingGuard};
use super::setup::Setup;
use super::treatment::{ContactTreatment, Context, Evaluations, Settling, SolveEnd, StepStart};
use crate::model::{Dim, SurfaceDim};

/// The kernel the complete formulation evaluates: Type 6 drops no term of
/// the gap's gradient and Hessian, so it is the exact linearisation.
pub(super) const DERIVATIVES: ApproxType = ApproxType::Type6;

/// The complete formulation (module docs); its state is the current
/// attempt's pairing guard and, with friction, every point's projection
/// at the run's converged state: the slip's anchors
/// ([`crate::contact::friction`]), taken at the first attempt from each
/// converged state.
pub(super) struct Complete<M, A> {
    /// The pairing changes of the current attempt.
    guard: PairingGuard<M>,
    /// Each point's anchor at the converged state (`None`: it projects
    /// nowhere); empty without friction.
    anchors: Vec<Option<A>>,
    /// Whether `anchors` belong to the run's converged state.
    anchored: bool,
}

impl<M, A> Default for Complete<M, A> {
    fn default() -> Self {
        Complete {
            guard: PairingGuard::default(),
            anchors: Vec::new(),
            anchored: false,
        }
    }
}

impl<const D: usize, S: ContactSpace<D>> ContactTreatment<D, S> for Complete<S::Master, S::Anchor>
where
    Dim<D>: SurfaceDim<D>,
{
    /// Starts the pairing guard; with friction, projects every point at the
    /// converged state once per converged state (the slip's anchors).
    fn begin_attempt(
        &mut self,
        cx: &mut Context<'_, '_, D, S>,
        start: StepStart<'_, S::Master>,
    ) -> Result<(), SolverError> {
        self.guard = PairingGuard::default();
        if cx.setup.layout.has_friction() && !self.anchored {
            let t = Instant::now();
            let (found, counts) = cx
                .setup
                .layout
                .project_all(&cx.setup.model.mesh, start.u, start.pairing)
                .map_err(|f| cx.setup.kernel_error(&f, start.load_factor))?;
            *cx.counts += counts;
            self.anchors = cx
                .setup
                .layout
                .found_anchors(&cx.setup.model.mesh, start.u, &found);
            self.anchored = true;
            cx.timings.contact_evaluation += t.elapsed();
        }
        Ok(())
    }

    /// The exact kernel at every point (re-pairing every point when
    /// `at_once`); the iterate takes the pairing the evaluation ended
    /// with.
    fn evaluate(
        &mut self,
        cx: &mut Context<'_, '_, D, S>,
        x: &mut Iterate<S::Master>,
        at_once: bool,
    ) -> Result<Evaluations<D, S>, CutbackReason> {
        let evaluated = evaluate(cx.setup, &x.u, &x.pairing, &x.ties, at_once, cx.counts).and_then(
            |(mut evals, others)| {
                if self.anchored {
                    cx.setup.layout.add_slips(
                        &cx.setup.model.mesh,
                        &x.u,
                        &mut evals,
                        &self.anchors,
                        DERIVATIVES,
                        cx.counts,
                    )?;
                }
                Ok((evals, others))
            },
        );
        match evaluated {
            Ok((evals, others)) => {
                x.pairing = evals.iter().map(|e| e.as_ref().map(S::master)).collect();
                Ok((evals, others))
            }
            Err(f) => Err(CutbackReason::Kernel {
                point: cx.setup.failure_point(&f),
                error: f.error,
            }),
        }
    }

    /// The pairing guard's update (see [`PairingGuard::update`]); a stuck
    /// point or a kernel failure asks for a cut-back.
    fn settle(
        &mut self,
        cx: &mut Context<'_, '_, D, S>,
        x: &mut Iterate<S::Master>,
        evals: &[Option<S::Eval>],
    ) -> Result<Settling, CutbackReason> {
        let t = Instant::now();
        let outcome = self.guard.update(
            cx.setup,
            &x.u,
            &x.lambda,
            evals,
            &mut x.pairing,
            &mut x.ties,
        );
        cx.timings.contact_evaluation += t.elapsed();
        match outcome {
            Ok((outcome, counts)) => {
                *cx.counts += counts;
                match outcome {
                    GuardOutcome::Changed => Ok(Settling::Changed),
                    GuardOutcome::Settled(k) => Ok(Settling::Settled(k)),
                    GuardOutcome::Stuck { point, xi_m } => {
                        let point: ContactPointId =
                            cx.setup.layout.point_id(point, x.pairing[point.index()]);
                        Err(CutbackReason::StuckAtMasterNode { point, xi_m })
                    }
                }
            }
            Err(f) => Err(CutbackReason::Kernel {
                point: cx.setup.failure_point(&f),
                error: f.error,
            }),
        }
    }

    fn end_solve(
        &mut self,
        _cx: &mut Context<'_, '_, D, S>,
        _start: StepStart<'_, S::Master>,
        c: Converged<D, S::Master>,
    ) -> Result<SolveEnd<D, S::Master>, SolverError> {
        Ok(SolveEnd::Done(Box::new(AttemptOutcome::Converged(c))))
    }

    fn committed(&mut self) {
        self.anchored = false;
    }

    fn step_end_projections(&self) -> u64 {
        0
    }
}

/// The complete formulation's contact evaluation at one iterate: the
/// [`DERIVATIVES`] kernel of every point on its paired master segment
/// (see [`ContactLayout::evaluate_paired`](crate::contact::ContactLayout::evaluate_paired);
/// with `at_once`, re-paired by
/// [`ContactLayout::evaluate_all`](crate::contact::ContactLayout::evaluate_all))
/// and of every tied point on its other segment. A kernel failure may
/// force a re-pairing: the caller takes the new pairing from the
/// evaluations' master segments. Kernel calls are added to `counts_out`
/// (on failure only those of the first pass). Shared by the solve and
/// [`super::IterationProbe`].
pub(super) fn evaluate<const D: usize, S: ContactSpace<D>>(
    setup: &Setup<'_, D, S>,
    u: &[f64],
    pairing: &[Option<S::Master>],
    ties: &[NodeTie<S::Master>],
    at_once: bool,
    counts_out: &mut KernelCounts,
) -> Result<Evaluations<D, S>, PointFailure<S::Master>>
where
    Dim<D>: SurfaceDim<D>,
{
    let mesh = &setup.model.mesh;
    let layout = &setup.layout;
    let (mut evals, counts) = if at_once {
        layout.evaluate_all(mesh, u, pairing, DERIVATIVES)?
    } else {
        layout.evaluate_paired(mesh, u, pairing, DERIVATIVES)?
    };
    *counts_out += counts;
    let mut counts = KernelCounts::default();
    for t in ties {
        if evals[t.point.index()]
            .as_ref()
            .is_none_or(|e| S::master(e) != t.paired)
        {
            evals[t.point.index()] = Some(
                layout
                    .evaluate_on(mesh, u, t.point, t.paired, DERIVATIVES, &mut counts)
                    .map_err(|error| PointFailure {
                        point: t.point,
                        master_segment: Some(t.paired),
                        error,
                    })?,
            );
        }
    }
    let others = ties
        .iter()
        .map(|t| {
            layout
                .evaluate_on(mesh, u, t.point, t.other, DERIVATIVES, &mut counts)
                .map_err(|error| PointFailure {
                    point: t.point,
                    master_segment: Some(t.other),
                    error,
                })
        })
        .collect::<Result<Vec<_>, _>>()?;
    *counts_out += counts;
    Ok((evals, others))
}
