//! Types 1–6: frozen second-order expansions of one approximation type (see
//! [`super::treatment`] and [`crate::contact`], "Types 1–6: Taylor
//! coefficients frozen per load step").
//!
//! At the first attempt from a converged state every point is re-paired
//! and the type's kernel gives its [`Taylor`] expansion, at the attempt's
//! predictor or at the converged state ([`super`], "Where the expansions
//! are taken"); the Newton iterations expand it and never re-project. The
//! expansions stay across the attempts from that state when they were
//! taken at the converged state (a cut-back keeps them, with the
//! re-anchored ones of a longer attempt), are rebuilt at a shorter
//! attempt's own predictor when they were taken at a longer one's, and are
//! rebuilt after a commit.
//! At a converged solve the step-end check (`repair.rs`) re-pairs the
//! points, replaces the expansions of those that changed segment, ties
//! those cycling at a master node, and asks for the step to be solved
//! again; a tie lasts one step (the expansions are built without ties).
//!
//! Invariant: `points` has one entry per contact point, in point order,
//! and `ties` one per tie of the run's converged state, in tie order,
//! whenever an attempt is in progress.

use std::time::Instant;

use contact_kernels::ApproxType;

use crate::contact::ContactSpace;
use crate::error::SolverError;
use crate::ids::ContactPointIndex;
use crate::options::ExpansionPoint;
use crate::solution::CutbackReason;

use super::iterate::Iterate;
use super::outcome::{Converged, StepEnd};
use super::treatment::{ContactTreatment, Context, Evaluations, Settling, SolveEnd, StepStart};
use crate::model::{Dim, SurfaceDim};

/// The frozen expansions of one type (module docs).
pub(super) struct Frozen<const D: usize, S: ContactSpace<D>> {
    /// The approximation type whose kernel gives the expansions.
    pub(super) ty: ApproxType,
    /// Each point's expansion (`None`: the point is unpaired).
    pub(super) points: Vec<Option<S::Expansion>>,
    /// The expansion on the other segment of each tie of the run's
    /// converged state (`repair.rs`).
    pub(super) ties: Vec<S::Expansion>,
    /// Whether the expansions belong to the run's converged state (false
    /// before the first attempt and after a commit).
    current: bool,
    /// The step-end check's state within the current attempt.
    pub(super) check: Check<S::Master>,
    /// Projection and kernel calls of the step-end checks.
    pub(super) step_end_projections: u64,
    /// With friction, each point's anchor at the converged state (its
    /// projection there, where its slip is measured from); empty without.
    pub(super) anchors: Vec<Option<S::Anchor>>,
    /// The displacements the expansions were built at (the converged
    /// state or the predictor of the attempt that built them).
    pub(super) built_at: Vec<f64>,
}

/// The step-end check's state within one attempt (`repair.rs`).
#[derive(Debug)]
/// Per point, the pairings its expansion has had in the attempt.
pub(super) struct Check<M> {
    pub(super) tried: Vec<Vec<Option<M>>>,
    /// What the check has found so far (the repeats).
    pub(super) end: StepEnd,
    /// Per point: whether its expansion is not the step start's (taken at
    /// an attempt's end, here or in a longer attempt that was cut back).
    pub(super) moved: Vec<bool>,
    /// Points released from a tie in this attempt: never tied again.
    pub(super) released: Vec<ContactPointIndex>,
    /// Repeats for pairing changes.
    pub(super) switches: usize,
    /// Repeats for anchor updates.
    pub(super) updates: usize,
}

impl<M> Default for Check<M> {
    fn default() -> Self {
        Check {
            tried: Vec::new(),
            end: StepEnd::default(),
            moved: Vec::new(),
            released: Vec::new(),
            switches: 0,
            updates: 0,
        }
    }
}

impl<const D: usize, S: ContactSpace<D>> Frozen<D, S>
where
    Dim<D>: SurfaceDim<D>,
{
    /// The expansions of type `ty`, built at the first attempt.
    pub(super) fn new(ty: ApproxType) -> Frozen<D, S> {
        Frozen {
            ty,
            points: Vec::new(),
            ties: Vec::new(),
            current: false,
            check: Check::default(),
            step_end_projections: 0,
            anchors: Vec::new(),
            built_at: Vec::new(),
        }
    }

    /// Builds the expansions at the attempt's `predictor` (the one
    /// `[newton] expand_at` asks for) or at the converged state
    /// ([`super`], "Where the expansions are taken"),
    /// re-pairing every point; the converged state's ties are dropped (a
    /// tie of Types 1–6 lasts one step, `repair.rs`).
    fn build(
        &mut self,
        cx: &mut Context<'_, '_, D, S>,
        start: &mut StepStart<'_, S::Master>,
        predictor: Option<&[f64]>,
    ) -> Result<(), SolverError> {
        start.ties.clear();
        self.ties.clear();
        let t = Instant::now();
        let layout = &cx.setup.layout;
        let mesh = &cx.setup.model.mesh;
        // where the expansions are taken (`super`, "Where the expansions
        // are taken"): the attempt's predictor, or the converged state when
        // there is none or a point cannot be evaluated there
        let predicted = predictor.and_then(|p| {
            layout
                .evaluate_all(mesh, p, start.pairing, self.ty)
                .ok()
                .map(|e| (p, e))
        });
        let (at, (mut evals, counts)) = match predicted {
            Some(p) => p,
            None => (
                start.u,
                layout
                    .evaluate_all(mesh, start.u, start.pairing, self.ty)
                    .map_err(|f| cx.setup.kernel_error(&f, start.load_factor))?,
            ),
        };
        *cx.counts += counts;
        if layout.has_friction() {
            // the slip is measured from the converged state's projections
            // (docs/conventions.md, "Coulomb friction"), wherever the
            // expansions are taken
            self.anchors = if std::ptr::eq(at, start.u) {
                layout.anchors(mesh, start.u, &evals)
            } else {
                let (at_start, counts) = layout
                    .evaluate_all(mesh, start.u, start.pairing, self.ty)
                    .map_err(|f| cx.setup.kernel_error(&f, start.load_factor))?;
                *cx.counts += counts;
                layout.anchors(mesh, start.u, &at_start)
            };
            layout
                .add_slips(mesh, at, &mut evals, &self.anchors, self.ty, cx.counts)
                .map_err(|f| cx.setup.kernel_error(&f, start.load_factor))?;
        }
        *start.pairing = evals.iter().map(|e| e.as_ref().map(S::master)).collect();
        self.points = evals
            .into_iter()
            .map(|e| e.map(|at_start| S::expand_at(at_start, at)))
            .collect();
        self.built_at = at.to_vec();
        self.current = true;
        cx.timings.contact_evaluation += t.elapsed();
        Ok(())
    }
}

impl<const D: usize, S: ContactSpace<D>> Frozen<D, S>
where
    Dim<D>: SurfaceDim<D>,
{
    /// Point `i`'s evaluation `e` at displacements `u` with its slip from
    /// the step's anchor, when its pair has friction (`repair.rs`'s new
    /// expansions); a slip the kernel cannot evaluate is its error.
    pub(super) fn with_slip(
        &self,
        cx: &mut Context<'_, '_, D, S>,
        u: &[f64],
        i: ContactPointIndex,
        mut e: S::Eval,
    ) -> Result<S::Eval, contact_kernels::KernelError> {
        let layout = &cx.setup.layout;
        if let Some(Some(anchor)) = self.anchors.get(i.index())
            && layout.point_has_friction(i)
        {
            cx.counts.evaluate += 1;
            layout.add_slip(&cx.setup.model.mesh, u, i, &mut e, *anchor, self.ty)?;
        }
        Ok(e)
    }
}

impl<const D: usize, S: ContactSpace<D>> ContactTreatment<D, S> for Frozen<D, S>
where
    Dim<D>: SurfaceDim<D>,
{
    /// Builds the expansions if the converged state has none yet, and
    /// starts the attempt's step-end check.
    fn begin_attempt(
        &mut self,
        cx: &mut Context<'_, '_, D, S>,
        mut start: StepStart<'_, S::Master>,
    ) -> Result<(), SolverError> {
        // expansions built at a longer attempt's predictor are rebuilt at
        // this one's (a cut-back's shorter step has another predictor)
        let predictor = predictor_to_expand_at(cx, &start);
        if !self.current || self.built_at != predictor.unwrap_or(start.u) {
            self.build(cx, &mut start, predictor)?;
        }
        self.check = Check {
            tried: start.pairing.iter().map(|p| vec![*p]).collect(),
            end: StepEnd::default(),
            moved: self.anchored_elsewhere(&start),
            released: Vec::new(),
            switches: 0,
            updates: 0,
        };
        Ok(())
    }

    /// Every point's expansion and every tie's second one at `x`.
    fn evaluate(
        &mut self,
        _cx: &mut Context<'_, '_, D, S>,
        x: &mut Iterate<S::Master>,
        _at_once: bool,
    ) -> Result<Evaluations<D, S>, CutbackReason> {
        let evals: Vec<Option<S::Eval>> = self
            .points
            .iter()
            .map(|t| t.as_ref().map(|t| S::expand(t, &x.u)))
            .collect();
        let others = self.ties.iter().map(|t| S::expand(t, &x.u)).collect();
        Ok((evals, others))
    }

    /// The pairing of a frozen step stands until its end.
    fn settle(
        &mut self,
        _cx: &mut Context<'_, '_, D, S>,
        _x: &mut Iterate<S::Master>,
        _evals: &[Option<S::Eval>],
    ) -> Result<Settling, CutbackReason> {
        Ok(Settling::Settled(Vec::new()))
    }

    /// The step-end check (`repair.rs`).
    fn end_solve(
        &mut self,
        cx: &mut Context<'_, '_, D, S>,
        start: StepStart<'_, S::Master>,
        c: Converged<D, S::Master>,
    ) -> Result<SolveEnd<D, S::Master>, SolverError> {
        self.check_end(cx, start, c)
    }

    fn committed(&mut self) {
        self.current = false;
    }

    fn step_end_projections(&self) -> u64 {
        self.step_end_projections
    }
}

/// The predictor an attempt's expansions are to be taken at (`[newton]
/// expand_at`, [`super`], "Where the expansions are taken"), `None` for
/// the converged state.
fn predictor_to_expand_at<'s, const D: usize, S: ContactSpace<D>>(
    cx: &Context<'_, '_, D, S>,
    start: &StepStart<'s, S::Master>,
) -> Option<&'s [f64]>
where
    Dim<D>: SurfaceDim<D>,
{
    match cx.opts.expand_at {
        ExpansionPoint::Predictor => start.predictor,
        ExpansionPoint::Start => None,
    }
}
