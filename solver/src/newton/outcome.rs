//! How an attempt ended: the outcomes that the Newton solve
//! ([`super::attempt`]), the step-end check of Types 1–6 (`repair.rs`) and
//! the driver over the schedule (`Run::execute`) hand to each other.
//!
//! An attempt either converged ([`Converged`]: the new converged state with
//! its report, which the caller commits), failed ([`Failed`]: the caller
//! cuts the increment back), or converged with a Taylor remainder above the
//! `taylor_tolerance` ([`AttemptOutcome::TooCoarse`]). These types hold data
//! only; who produces and who consumes them is in the modules above.

use crate::contact::friction::NodalFriction;
use crate::solution::{ContactPointId, CutbackReason};

use super::iterate::Iterate;

/// A converged attempt.
pub(super) struct Converged<const D: usize, M> {
    /// The converged iterate (inactive multipliers exactly zero).
    pub(super) state: Iterate<M>,
    /// Linear solves spent.
    pub(super) iterations: usize,
    /// The residual norms of the evaluated iterates.
    pub(super) residuals: Vec<f64>,
    /// Strain energy at the converged iterate.
    pub(super) energy: f64,
    /// Accepted at the round-off floor rather than below the tolerance.
    pub(super) roundoff_floor: bool,
    /// The contact points' state at the converged iterate.
    pub(super) points: PointsReport,
    /// The support groups' reactions at the converged iterate (see
    /// `reactions.rs`).
    pub(super) reactions: Vec<[f64; D]>,
    /// Which multipliers carry a constraint row at the converged iterate.
    pub(super) active: Vec<bool>,
    /// With friction, every frictional node's state and step slip at the
    /// converged iterate (its `slip` not yet accumulated).
    pub(super) friction: Vec<NodalFriction>,
    /// Types 1–6: what the step-end check found (`repair.rs`); `None` for
    /// the complete formulation.
    pub(super) step_end: Option<StepEnd>,
}

/// The contact points' state at a converged iterate, for the step record.
pub(super) struct PointsReport {
    /// Multipliers carrying a constraint row.
    pub(super) active_multipliers: usize,
    /// Points that project into no master segment.
    pub(super) unpaired: Vec<ContactPointId>,
    /// Points tied to a master node.
    pub(super) node_ties: Vec<ContactPointId>,
    /// Points kept on a segment their projection misses (within the band).
    pub(super) kept_outside: Vec<ContactPointId>,
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
pub(super) enum AttemptOutcome<const D: usize, M> {
    /// Converged: the new converged state.
    Converged(Converged<D, M>),
    /// Failed: cut back.
    CutBack(Failed),
    /// Types 1–6 with a `taylor_tolerance`: converged, but the Taylor
    /// remainder exceeds the tolerance; halve the increment if the
    /// schedule allows, else accept it.
    TooCoarse(Converged<D, M>),
}

impl<const D: usize, M> AttemptOutcome<D, M> {
    pub(super) fn cut_back(
        reason: CutbackReason,
        residuals: Vec<f64>,
        iterations: usize,
    ) -> AttemptOutcome<D, M> {
        AttemptOutcome::CutBack(Failed {
            reason,
            residuals,
            iterations,
        })
    }
}

/// What the step-end check found for an accepted attempt.
#[derive(Debug, Clone, Default, PartialEq)]
pub(super) struct StepEnd {
    /// Times the step was solved again with a new pairing.
    pub(super) repeats: usize,
    /// Largest `|g_true - g~| / L_s` over the active points; `None` when
    /// no point is active.
    pub(super) remainder: Option<f64>,
    /// Points whose pairing at the end differs from their expansion's
    /// (`master_segment`: the expansion's).
    pub(super) unsettled: Vec<ContactPointId>,
    /// Points cycling between two masters at the end, kept on their
    /// expansion's master because their projection misses it by less
    /// than [`crate::contact::XI_STUCK_BAND`] (`master_segment`: that
    /// master), as the complete formulation keeps a stuck point it cannot
    /// tie.
    pub(super) kept_outside: Vec<ContactPointId>,
}
