//! The unknowns of an attempt: a copy of the converged state that Newton's
//! corrections update (see [`super::attempt`]).
//!
//! Invariant: an iterate is its attempt's own copy; the run's converged
//! state changes only when a converged attempt is committed.

use crate::contact::NodeTie;
use crate::ids::{DofId, MultiplierIndex};
use crate::system::DofMap;

/// The unknowns of an attempt's current iterate (copies of the converged
/// state at the start).
pub(super) struct Iterate<M> {
    /// Displacements (all dofs).
    pub(super) u: Vec<f64>,
    /// Multipliers.
    pub(super) lambda: Vec<f64>,
    /// Each point's master segment.
    pub(super) pairing: Vec<Option<M>>,
    /// Node ties (points held at a master node, [`NodeTie`]).
    pub(super) ties: Vec<NodeTie<M>>,
}

impl<M> Iterate<M> {
    /// Applies the Newton correction: `x -= dx` on the free dofs, the
    /// multipliers and the ties' multipliers.
    pub(super) fn correct(&mut self, dofs: &DofMap, dx: &[f64]) {
        for (dof, ud) in self.u.iter_mut().enumerate() {
            if let Some(e) = dofs.eq(DofId::new(dof)) {
                *ud -= dx[e.index()];
            }
        }
        for (m, l) in self.lambda.iter_mut().enumerate() {
            *l -= dx[dofs.mult_eq(MultiplierIndex::new(m)).index()];
        }
        for (k, tie) in self.ties.iter_mut().enumerate() {
            tie.mu -= dx[dofs.tie_eq(k).index()];
        }
    }
}
