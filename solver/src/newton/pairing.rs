//! The pairing guard of the complete formulation: how the pairing changes at
//! a converged iterate (see [`crate::contact`], "Pairing in the complete
//! formulation" and "Points stuck at a master node").
//!
//! Invariants: within one attempt a point switches away from a given
//! pairing at most once; a point that comes back to a pairing it has left
//! is tied to the node between the two segments (when they are adjacent)
//! or settled, and a settled point never switches again in that attempt
//! (it is kept within [`XI_STUCK_BAND`] or the attempt fails as stuck).
//! Updates are applied in point order.

use crate::contact::{ContactSpace, Update};
use crate::contact::{KernelCounts, NodeTie, PointFailure};

use crate::ids::ContactPointIndex;

use super::setup::Setup;
use crate::model::{Dim, SurfaceDim};

/// What [`PairingGuard::apply`] decided at a converged iterate.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum GuardOutcome {
    /// Some points were re-paired or tied: iterate on.
    Changed,
    /// The pairing stands. Lists the points kept on a pairing their
    /// projection misses by less than [`XI_STUCK_BAND`].
    Settled(Vec<ContactPointIndex>),
    /// A point's pairing cycles and its projection misses by more than the
    /// band.
    Stuck {
        /// The point.
        point: ContactPointIndex,
        /// Its projection coordinate (on its master segment, or for an
        /// inactive point on the segment it projects into).
        xi_m: f64,
    },
}

/// The pairing changes of one attempt of the complete formulation (module
/// docs of [`crate::contact`], "Pairing in the complete formulation" and
/// "Points stuck at a master node").
#[derive(Debug)]
/// `(point, pairing)` the point has been switched away from.
pub(super) struct PairingGuard<M> {
    left: Vec<(ContactPointIndex, Option<M>)>,
    /// Points released from a tie in this attempt: one more switch (the
    /// side `theta` chose may be wrong when other points moved meanwhile).
    released: Vec<ContactPointIndex>,
    /// Points that made their last allowed switch in this attempt.
    settled: Vec<ContactPointIndex>,
}

impl<M> Default for PairingGuard<M> {
    fn default() -> Self {
        PairingGuard {
            left: Vec::new(),
            released: Vec::new(),
            settled: Vec::new(),
        }
    }
}

impl<M: Copy + PartialEq> PairingGuard<M> {
    /// Applies the pairing `updates` due at a converged iterate with
    /// contact evaluations `evals` (see
    /// [`ContactSpace::pairing_updates`]; tied points excluded) to
    /// `pairing`, tying a point whose pairing cycles between two adjacent
    /// master segments (appended to `ties`).
    fn apply<const D: usize, S: ContactSpace<D, Master = M>>(
        &mut self,
        layout: &S,
        updates: &[Update<S, D>],
        evals: &[Option<S::Eval>],
        pairing: &mut [Option<M>],
        ties: &mut Vec<NodeTie<M>>,
    ) -> GuardOutcome {
        let mut changed = false;
        let mut kept = Vec::new();
        for &(i, target) in updates {
            let current = pairing[i.index()];
            let to = target.as_ref().map(S::found_master);
            // how far the projection misses the current pairing
            let (xi_m, within) = match (&evals[i.index()], &target) {
                (Some(e), _) => (layout.stuck_xi(e), layout.within_band(e)),
                (None, Some(p)) => (layout.found_stuck_xi(p), layout.found_at_boundary(p)),
                (None, None) => (f64::NAN, true),
            };
            if self.settled.contains(&i) {
                if !within {
                    return GuardOutcome::Stuck { point: i, xi_m };
                }
                kept.push(i);
                continue;
            }
            if let Some(k) = self.released.iter().position(|&j| j == i) {
                self.released.swap_remove(k);
                self.settled.push(i);
            } else if self.left.contains(&(i, to)) {
                // back to a pairing the point has left: stuck at the node
                // between the two (or at the chain's end)
                if let (Some(p), Some(o)) = (current, to)
                    && layout.can_tie(i, p, o)
                {
                    ties.push(NodeTie {
                        point: i,
                        paired: p,
                        other: o,
                        mu: 0.0,
                    });
                    changed = true;
                    continue;
                }
                self.settled.push(i);
                if within {
                    kept.push(i);
                    continue;
                }
                // no tie possible: back to the other side, once
            }
            self.left.push((i, current));
            pairing[i.index()] = to;
            changed = true;
        }
        if changed {
            GuardOutcome::Changed
        } else {
            GuardOutcome::Settled(kept)
        }
    }

    /// The pairing update of the complete formulation at a converged
    /// iterate (module docs of [`crate::contact`]): releases the ties whose
    /// `theta` left `[0, 1]` (to the paired segment for `theta < 0`, to the
    /// other one for `theta > 1`), then re-pairs the untied points whose
    /// projection left their segment, tying those that cycle.
    ///
    /// Returns the outcome with the kernel calls made.
    #[allow(clippy::type_complexity)] // the layouts' own signature
    pub(super) fn update<const D: usize, S: ContactSpace<D, Master = M>>(
        &mut self,
        setup: &Setup<'_, D, S>,
        u: &[f64],
        lambda: &[f64],
        evals: &[Option<S::Eval>],
        pairing: &mut [Option<M>],
        ties: &mut Vec<NodeTie<M>>,
    ) -> Result<(GuardOutcome, KernelCounts), PointFailure<M>>
    where
        Dim<D>: SurfaceDim<D>,
    {
        let layout = &setup.layout;
        let (updates, counts) = layout.pairing_updates(&setup.model.mesh, u, evals)?;
        let updates: Vec<_> = updates
            .into_iter()
            .filter(|(i, _)| ties.iter().all(|t| t.point != *i))
            .collect();
        let mut released = false;
        ties.retain(|t| {
            let theta = layout.tie_theta(t, lambda).unwrap_or(-1.0);
            // where the two segments' lines (nearly) coincide, `g_o = g_p`
            // does not hold the point at the node: it may slide away with
            // the tie; a point that left the node is released
            let at_node = evals[t.point.index()].as_ref().is_none_or(S::at_node);
            if at_node && (0.0..=1.0).contains(&theta) {
                return true;
            }
            if theta > 1.0 {
                pairing[t.point.index()] = Some(t.other);
            }
            self.released.push(t.point);
            released = true;
            false
        });
        let outcome = self.apply(layout, &updates, evals, pairing, ties);
        let outcome = match outcome {
            GuardOutcome::Settled(_) if released => GuardOutcome::Changed,
            o => o,
        };
        Ok((outcome, counts))
    }
}
