//! Which multipliers carry a constraint row (see [`super`], "Multipliers
//! and modes"): persistent pairs, every multiplier with an active
//! integration point; unilateral pairs, the primal–dual active set.
//!
//! Invariant: the nodal weights and weighted gaps are summed in point order.

use crate::model::ContactMode;

use super::{ContactLayout, PointEval, shape2};

impl ContactLayout {
    /// Which multipliers carry a constraint row (see the module docs):
    /// persistent pairs: those with an active integration point;
    /// unilateral pairs: the primal–dual active set at `(evals, lambda)`.
    pub fn active_multipliers(
        &self,
        evals: &[Option<PointEval>],
        lambda: &[f64],
        length_scale: f64,
    ) -> Vec<bool> {
        let n = self.multipliers.len();
        let mut weight = vec![0.0; n];
        let mut weighted_gap = vec![0.0; n];
        for (pt, ev) in self.points.iter().zip(evals) {
            if let Some(ev) = ev {
                let nsh = shape2(pt.xi_s);
                for a in 0..2 {
                    let m = pt.multipliers[a].index();
                    weight[m] += pt.weight_ref * nsh[a];
                    weighted_gap[m] += pt.weight_ref * nsh[a] * ev.gap;
                }
            }
        }
        (0..n)
            .map(|m| {
                if !(weight[m] > 0.0) {
                    return false;
                }
                let pair = self.multipliers[m].pair.index();
                match self.modes[pair] {
                    ContactMode::Persistent => true,
                    ContactMode::Unilateral => {
                        let c = self.complementarity[pair];
                        let pressure = -lambda[m];
                        pressure - c * weighted_gap[m] / weight[m] >= -c * 1e-12 * length_scale
                    }
                }
            })
            .collect()
    }
}
