//! Node ties of the 2D complete formulation (`crate::contact`, "Points
//! stuck at a master node"): a tie's weight and its part of the Newton
//! system.

use crate::contact::NodeTie;
use crate::system::{DofMap, System};

use super::{ContactLayout, PointEval, shape2};

impl NodeTie {
    /// The weight `theta = mu / (lambda w J0)` of the `other` segment's
    /// gradient in the point's contact force (`1 - theta` for the paired
    /// one); `None` when the point carries no multiplier. The tie holds for
    /// `theta` in `[0, 1]`.
    pub fn theta(&self, layout: &ContactLayout, lambda: &[f64]) -> Option<f64> {
        let pt = layout.point(self.point);
        let nsh = shape2(pt.xi_s);
        let lam =
            nsh[0] * lambda[pt.multipliers[0].index()] + nsh[1] * lambda[pt.multipliers[1].index()];
        let force = lam * pt.weight_ref;
        (force != 0.0).then(|| self.mu / force)
    }
}

/// Adds the node ties of the complete formulation (see
/// [`crate::contact`], "Points stuck at a master node"): tie `k`, with the
/// point's evaluation on its paired segment `evals[point]` (its regular
/// term, added by [`crate::contact::assemble_contact`]) and on the other segment
/// `others[k]`, adds the potential `mu (g_o - g_p)`:
///
/// ```text
/// r_u  += mu (g_o' - g_p')        K_uu += mu (g_o'' - g_p'')
/// r_mu  = g_o - g_p               K_u,mu = K_mu,u = g_o' - g_p'
/// ```
///
/// with the tie's equation [`DofMap::tie_eq`] (after the free dofs and
/// multipliers) and an explicit zero `K_mu,mu`.
pub fn assemble_ties(
    ties: &[NodeTie],
    evals: &[Option<PointEval>],
    others: &[PointEval],
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
        sys.residual[row.index()] = other.gap - paired.gap;
        for (ev, sign) in [(other, 1.0), (paired, -1.0)] {
            let eqs = dofs.node_eqs(&ev.nodes);
            for p in 0..8 {
                let Some(ep) = eqs[p] else { continue };
                sys.residual[ep.index()] += sign * tie.mu * ev.grad[p];
                sys.push(ep, row, sign * ev.grad[p]);
                sys.push(row, ep, sign * ev.grad[p]);
                if let Some(h) = &ev.hess {
                    for q in 0..8 {
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
