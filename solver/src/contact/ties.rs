//! Node ties of the complete formulation, in both dimensions
//! ([`crate::contact`], "Points stuck at a master node"): a tie's weight
//! and its part of the Newton system.
//!
//! A tied point sits where two master elements meet (2D: the node two
//! segments share; 3D: the edge or vertex two faces share) and neither
//! side's projection is consistent. Its potential is
//! `lambda w J0 g_p + mu (g_o - g_p)`: the equation `g_o = g_p` holds the
//! point on the bisector of the two masters (in 3D it may still slide
//! along their common edge), and `theta = mu / (lambda w J0)` is the share
//! of the `other` master's gradient in the point's contact force. The
//! points and evaluations are the dimension-generic ones of
//! [`super::term`] (2D: `N = 8`; 3D: `N = 24`, padding coordinates
//! skipped).

use crate::contact::NodeTie;
use crate::ids::EquationIndex;
use crate::system::{DofMap, System};

use super::{GapTerm, WeightedPoint};

impl<M> NodeTie<M> {
    /// The weight `theta = mu / (lambda w J0)` of the `other` master's
    /// gradient in the contact force of the tied point `pt` (`1 - theta`
    /// for the paired one); `None` when the point carries no multiplier.
    /// The tie holds for `theta` in `[0, 1]`.
    pub fn theta<P: WeightedPoint>(&self, pt: &P, lambda: &[f64]) -> Option<f64> {
        let force = pt.multiplier_shape().lambda(lambda) * pt.weight_ref();
        (force != 0.0).then(|| self.mu / force)
    }
}

/// Adds the node ties of the complete formulation (module docs): tie `k`,
/// with the point's evaluation on its paired master `evals[point]` (its
/// regular term, added by [`crate::contact::assemble_contact`]) and on the
/// other master `others[k]`, adds the potential `mu (g_o - g_p)`:
///
/// ```text
/// r_u  += mu (g_o' - g_p')        K_uu += mu (g_o'' - g_p'')
/// r_mu  = g_o - g_p               K_u,mu = K_mu,u = g_o' - g_p'
/// ```
///
/// with the tie's equation [`DofMap::tie_eq`] (after the free dofs and
/// multipliers) and an explicit zero `K_mu,mu`.
pub fn assemble_ties<M, E: GapTerm<N>, const N: usize>(
    ties: &[NodeTie<M>],
    evals: &[Option<E>],
    others: &[E],
    dofs: &DofMap,
    sys: &mut System,
) {
    for (k, (tie, other)) in ties.iter().zip(others).enumerate() {
        let row = dofs.tie_eq(k);
        let Some(paired) = &evals[tie.point.index()] else {
            // an inactive point cannot be tied; keep the row regular
            sys.residual[row.index()] = tie.mu;
            sys.push(row, row, 1.0);
            continue;
        };
        sys.residual[row.index()] = other.gap() - paired.gap();
        for (ev, sign) in [(other, 1.0), (paired, -1.0)] {
            let eqs: [Option<EquationIndex>; N] =
                std::array::from_fn(|k| ev.dof(k).and_then(|d| dofs.eq(d)));
            let grad = ev.grad();
            for p in 0..N {
                let Some(ep) = eqs[p] else { continue };
                sys.residual[ep.index()] += sign * tie.mu * grad[p];
                sys.push(ep, row, sign * grad[p]);
                sys.push(row, ep, sign * grad[p]);
                if let Some(h) = ev.hess() {
                    for q in 0..N {
                        if let Some(eq) = eqs[q] {
                            sys.push(ep, eq, sign * tie.mu * h[(p, q)]);
                        }
                    }
                }
            }
        }
        sys.push(row, row, 0.0);
    }
}
