//! How contact is treated in a solve: the seam between the Newton loop and
//! the contact formulation's treatments.
//!
//! A contact integration point contributes `w J0 lambda g` to the
//! potential (see [`crate::contact`]); what differs between the treatments
//! is which function `g(u)` (with `g'` and `g''`) the Newton iterations of
//! a load step see, and what happens at the step's converged end.
//!
//! * **Complete** (`complete.rs`): every iteration re-projects each point
//!   onto its paired master segment at the current displacements and
//!   evaluates the exact gap with every derivative term (the Type 6
//!   kernel, [`super::complete::DERIVATIVES`]). The pairing changes in the
//!   first iterates of an attempt and then only at a converged iterate
//!   (the pairing guard, `pairing.rs`; points cycling at a master node are
//!   tied to it); a converged iterate that needs no pairing change ends
//!   the step.
//! * **Frozen expansions of Type k**, k = 1..6 (`frozen.rs`): at the step
//!   start `u0` every point is re-paired and the type's kernel gives `g0`,
//!   `g'0`, `g''0`; during the step, with `d = u - u0` on the point's 8
//!   dofs,
//!
//!   ```text
//!   g~ = g0 + g'0 . d + 1/2 d . g''0 d,   g~' = g'0 + g''0 d,   g~'' = g''0
//!   ```
//!
//!   (exact tangent of the approximated problem, no re-projection). At a
//!   converged end the points are re-paired by projection and, where one
//!   ended on another master segment, the step is solved again with the
//!   new segment's expansion (`repair.rs`); the step's Taylor remainder is
//!   measured there.
//!
//! The Newton loop (`attempt.rs`) calls a [`ContactTreatment`] in this
//! order: [`begin_attempt`](ContactTreatment::begin_attempt) once per
//! attempt, at the run's converged state; per iteration
//! [`evaluate`](ContactTreatment::evaluate); at a converged iterate
//! [`settle`](ContactTreatment::settle); at a converged Newton solve
//! [`end_solve`](ContactTreatment::end_solve) (accept, or solve the step
//! again from that solve's end); after a commit
//! [`committed`](ContactTreatment::committed). `Run::new` picks the
//! treatment from the method once; nothing else in `newton/` matches on
//! the method, so another treatment (or another kind of contact point)
//! plugs in here without a branch in the loop.
//!
//! Invariants: a treatment changes the run's converged state only through
//! [`StepStart`] (the pairing and the ties) in `begin_attempt` and
//! `end_solve`, and an iterate only through `evaluate` and `settle`; its
//! evaluations are in point order and add their kernel calls to
//! [`Context::counts`].

use crate::contact::ContactSpace;
use crate::contact::{KernelCounts, NodeTie};
use crate::error::SolverError;
use crate::ids::ContactPointIndex;
use crate::options::SolveOptions;
use crate::solution::{CutbackReason, Timings};

use super::iterate::Iterate;
use super::outcome::{AttemptOutcome, Converged};
use super::setup::Setup;
use crate::model::{Dim, SurfaceDim};

/// The contact evaluations of one iterate: one per point (`None`: the point
/// is unpaired) and, for each node tie, the tied point's evaluation on the
/// tie's other segment.
pub(super) type Evaluations<const D: usize, S> = (
    Vec<Option<<S as ContactSpace<D>>::Eval>>,
    Vec<<S as ContactSpace<D>>::Eval>,
);

/// What a treatment works with: the discretised problem, the options and
/// the run's counters.
pub(super) struct Context<'r, 'a, const D: usize, S>
where
    Dim<D>: SurfaceDim<D>,
{
    /// The discretised problem (layout, equation numbering).
    pub(super) setup: &'r Setup<'a, D, S>,
    /// The solve's options (`repair`, `taylor_tolerance`).
    pub(super) opts: &'r SolveOptions,
    /// The run's kernel calls.
    pub(super) counts: &'r mut KernelCounts,
    /// The run's phase timings (contact evaluation).
    pub(super) timings: &'r mut Timings,
}

/// The run's converged state, where the step starts: what a treatment may
/// read, and the pairing and ties it may change (module docs).
pub(super) struct StepStart<'r, M> {
    /// The converged displacements.
    pub(super) u: &'r [f64],
    /// Each point's master segment (or face).
    pub(super) pairing: &'r mut Vec<Option<M>>,
    /// The points held at a master node.
    pub(super) ties: &'r mut Vec<NodeTie<M>>,
    /// The converged load factor (named by a step-start kernel failure).
    pub(super) load_factor: f64,
    /// The attempt's secant predictor, where its first Newton solve starts
    /// (`None`: it starts from `u`).
    pub(super) predictor: Option<&'r [f64]>,
}

/// The treatment's decision at a converged iterate.
pub(super) enum Settling {
    /// Points were re-paired, tied or released: evaluate the same iterate
    /// again.
    Changed,
    /// The pairing stands; the points kept outside their segment.
    Settled(Vec<ContactPointIndex>),
}

/// The treatment's decision at the end of a converged Newton solve.
pub(super) enum SolveEnd<const D: usize, M> {
    /// The attempt ends with this outcome (boxed: an outcome carries the
    /// converged state's report, ten times the size of `Again`).
    Done(Box<AttemptOutcome<D, M>>),
    /// Solve the step again (same target), Newton starting from `warm`
    /// (the displacements and multipliers of the discarded solve's end),
    /// which spent `spent` linear solves.
    Again {
        /// Displacements and multipliers to start from.
        warm: (Vec<f64>, Vec<f64>),
        /// Linear solves of the discarded solve.
        spent: usize,
    },
}

/// How contact is treated (module docs): its evaluation at an iterate and
/// its logic at the step's start and end.
pub(super) trait ContactTreatment<const D: usize, S: ContactSpace<D>>
where
    Dim<D>: SurfaceDim<D>,
{
    /// Before an attempt from the converged state `start`; an error stops
    /// the solve (a kernel failure at a converged state, which no smaller
    /// increment cures).
    fn begin_attempt(
        &mut self,
        cx: &mut Context<'_, '_, D, S>,
        start: StepStart<'_, S::Master>,
    ) -> Result<(), SolverError>;

    /// The contact evaluations at iterate `x` (which may re-pair `x`);
    /// `at_once`: the iterate is one of the attempt's first (module docs
    /// of [`super`]), where a re-projecting treatment re-pairs every point.
    /// A kernel failure asks for a cut-back.
    fn evaluate(
        &mut self,
        cx: &mut Context<'_, '_, D, S>,
        x: &mut Iterate<S::Master>,
        at_once: bool,
    ) -> Result<Evaluations<D, S>, CutbackReason>;

    /// At an iterate `x` that meets the tolerance, evaluated as `evals`:
    /// whether its pairing stands (then the iterate is accepted).
    fn settle(
        &mut self,
        cx: &mut Context<'_, '_, D, S>,
        x: &mut Iterate<S::Master>,
        evals: &[Option<S::Eval>],
    ) -> Result<Settling, CutbackReason>;

    /// At the end of a converged Newton solve `c` of the attempt: its
    /// outcome, or the request to solve the step again.
    fn end_solve(
        &mut self,
        cx: &mut Context<'_, '_, D, S>,
        start: StepStart<'_, S::Master>,
        c: Converged<D, S::Master>,
    ) -> Result<SolveEnd<D, S::Master>, SolverError>;

    /// A converged attempt became the run's converged state.
    fn committed(&mut self);

    /// Projection and kernel calls of the step-end checks
    /// ([`crate::Solution::step_end_projections`]).
    fn step_end_projections(&self) -> u64;
}
