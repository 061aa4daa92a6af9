//! Coulomb friction with tangential multipliers (see [`super`], "Coulomb
//! friction"): the slip's terms, the nodal stick/slip/open decision and
//! the friction part of the Newton system, over any dimension's points
//! ([`WeightedPoint`]) and evaluations ([`GapTerm::slip`]).
//!
//! # The mathematics
//!
//! A slave node `a` of a pair with coefficient `mu > 0` carries, beside its
//! normal multiplier `l_a` (pressure `p_a = -l_a`), one tangential
//! multiplier `t_a`; along the slave face `t(xi_s) = sum_a N_a t_a`. Each
//! integration point adds `w J0 t(xi_s) s` to the contact potential, with
//! `s` the slip of docs/conventions.md ("The slip": the slave point's
//! tangential displacement relative to the master since the last converged
//! state, `xi_m0`), so per point
//!
//! ```text
//! r_u  += w J0 t s'            K_uu += w J0 t s''
//! K_u,ta += w J0 N_a s'
//! ```
//!
//! The friction force on the slave is `-t s'`: with `t > 0` it opposes a
//! slip in the `+s` direction. The nodal weighted slip of the step is
//! `S_a = sum w J0 N_a s` and its weight `W_a = sum w J0 N_a`, over the
//! points of the node's slave faces that have a slip. Coulomb's law at the
//! node, `|t_a| <= mu p_a`, `t_a` along the slip when the node slips, is
//! the complementarity function of a primal–dual active set (Hüeber and
//! Wohlmuth's, on the normal active set of [`super::active_set`]): with the
//! trial `z_a = t_a + c S_a / W_a` (`c` the pair's complementarity
//! constant, the normal test's),
//!
//! * **open** (the normal multiplier inactive, or no point of the node has
//!   a slip): the row `t_a = 0`;
//! * **stick** (`|z_a| <= mu p_a`): the row `S_a = 0`, with the coupling
//!   `K_ta,u = sum w J0 N_a s'` (no slip in the step);
//! * **slip** (`|z_a| > mu p_a`): the row `t_a - mu p_a sign(z_a) = 0`,
//!   i.e. `t_a + mu sign(z_a) l_a = 0`, whose linearisation (`1` on `t_a`,
//!   `mu sign(z_a)` on `l_a`) is exact in 2D, where the direction is a
//!   sign, constant near the solution.
//!
//! The states are decided afresh at every Newton iteration from the
//! iterate's multipliers and slips, as the normal active set is; Newton
//! converges when the residual of the current states is below tolerance,
//! and a step whose states keep changing runs into the iteration limit and
//! is cut back. Since `S_a` is the slip within the step (the slip is zero
//! at `xi_m = xi_m0`), the direction of a sliding node is that of its
//! slip in the step: at a reversal the node first sticks (`|z_a|` falls
//! below the bound as `t_a` is unloaded) and then slips the other way.
//!
//! A sign of `z_a = 0` (no tangential load and no slip) is taken as `+1`;
//! it is reached only with `mu p_a < 0`, a tensile normal multiplier of an
//! iterate, never at a converged state of unilateral contact.
//!
//! Invariants: the tangential multipliers are numbered after every normal
//! one, in the order of their nodes' normal multipliers; a pair with
//! `mu = 0` has none, so a frictionless model's system is unchanged to the
//! bit; sums over points are in point order.

use crate::ids::{EquationIndex, MultiplierIndex};
use crate::system::{DofMap, System};

use super::MultiplierDof;
pub use super::term::SlipTerm;
use super::term::{GapTerm, WeightedPoint};

/// Where a point's slip is measured from: the master and the projection
/// onto it at the last converged state (2D: `xi_m0` on a segment).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Anchor<M> {
    /// The master segment the point projected into.
    pub master: M,
    /// `xi_m0`.
    pub xi_m: f64,
}

/// A frictional node at a converged state, for reports: its normal
/// multiplier, its state, the slip of the last step `S_a / W_a` and the
/// accumulated slip length (the sum of `|S_a / W_a|` over the converged
/// steps at whose end the node was in contact, stick or slip).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NodalFriction {
    /// The node's normal multiplier (its tangential one is the state's
    /// multiplier at the normal count plus this entry's index).
    pub multiplier: MultiplierIndex,
    /// Open, stick or slip.
    pub state: FrictionState,
    /// The weighted mean slip of the last step, `S_a / W_a` (0 where no
    /// point of the node has a slip).
    pub step_slip: f64,
    /// The accumulated slip length since the start of the solve.
    pub slip: f64,
}

/// A frictional node's state at an iterate (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FrictionState {
    /// Not in contact: `t_a = 0`.
    Open,
    /// No slip in the step: `S_a = 0`.
    Stick,
    /// Sliding: `t_a = mu p_a direction`, `direction` `+1` or `-1` (the
    /// sign of the slip in the step).
    Slip {
        /// `sign(z_a)`.
        direction: f64,
    },
}

impl FrictionState {
    /// The state's name in reports (`open`, `stick`, `slip`).
    pub fn name(self) -> &'static str {
        match self {
            FrictionState::Open => "open",
            FrictionState::Stick => "stick",
            FrictionState::Slip { .. } => "slip",
        }
    }
}

/// The tangential multipliers of a layout (module docs).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Friction {
    /// Coulomb's coefficient of each pair.
    pub mu: Vec<f64>,
    /// The number of normal multipliers (the first tangential multiplier's
    /// index).
    pub normal_count: usize,
    /// Each tangential multiplier's node, as its normal multiplier.
    pub normal: Vec<MultiplierIndex>,
    /// Each normal multiplier's tangential one (`None`: frictionless pair).
    pub tangential_of: Vec<Option<MultiplierIndex>>,
}

impl Friction {
    /// One tangential multiplier per normal one of a pair with `mu > 0`
    /// (`mu` per pair).
    pub fn new(multipliers: &[MultiplierDof], mu: Vec<f64>) -> Friction {
        let normal_count = multipliers.len();
        let mut normal = Vec::new();
        let tangential_of = multipliers
            .iter()
            .enumerate()
            .map(|(m, dof)| {
                (mu[dof.pair.index()] > 0.0).then(|| {
                    normal.push(MultiplierIndex::new(m));
                    MultiplierIndex::new(normal_count + normal.len() - 1)
                })
            })
            .collect();
        Friction {
            mu,
            normal_count,
            normal,
            tangential_of,
        }
    }

    /// The number of tangential multipliers.
    pub fn count(&self) -> usize {
        self.normal.len()
    }

    /// Whether any pair has friction.
    pub fn any(&self) -> bool {
        !self.normal.is_empty()
    }

    /// Whether `pair` has friction.
    pub fn on_pair(&self, pair: usize) -> bool {
        self.mu.get(pair).is_some_and(|&mu| mu > 0.0)
    }

    /// `t(xi_s) = sum_a N_a t_a` of a point (summed from its first
    /// frictional node), or `None` when none of its nodes has friction.
    fn traction<P: WeightedPoint>(&self, pt: &P, lambda: &[f64]) -> Option<f64> {
        let mut t: Option<f64> = None;
        for (m, n_a) in pt.multiplier_shape().iter() {
            if let Some(k) = self.tangential_of[m.index()] {
                let v = n_a * lambda[k.index()];
                t = Some(t.map_or(v, |t| t + v));
            }
        }
        t
    }

    /// Per tangential multiplier: the weight `W_a = sum w J0 N_a` and the
    /// weighted slip `S_a = sum w J0 N_a s` over the points with a slip, in
    /// point order.
    pub fn nodal_slips<P: WeightedPoint, E: GapTerm<N>, const N: usize>(
        &self,
        points: &[P],
        evals: &[Option<E>],
    ) -> (Vec<f64>, Vec<f64>) {
        let mut weight = vec![0.0; self.count()];
        let mut slip = vec![0.0; self.count()];
        for (pt, ev) in points.iter().zip(evals) {
            let Some(s) = ev.as_ref().and_then(|e| e.slip()) else {
                continue;
            };
            let w = pt.weight_ref();
            for (m, n_a) in pt.multiplier_shape().iter() {
                if let Some(k) = self.tangential_of[m.index()] {
                    let k = k.index() - self.normal_count;
                    weight[k] += w * n_a;
                    slip[k] += w * n_a * s.slip;
                }
            }
        }
        (weight, slip)
    }

    /// Each tangential multiplier's state at `(evals, lambda)` with the
    /// normal active set `active` (its first `normal_count` entries) and
    /// each pair's complementarity constant (module docs).
    pub fn states<P: WeightedPoint, E: GapTerm<N>, const N: usize>(
        &self,
        points: &[P],
        evals: &[Option<E>],
        lambda: &[f64],
        active: &[bool],
        pairs: &[MultiplierDof],
        complementarity: &[f64],
    ) -> Vec<FrictionState> {
        let (weight, slip) = self.nodal_slips(points, evals);
        self.states_of(&weight, &slip, lambda, active, pairs, complementarity)
    }

    /// Each frictional node's state and step slip at a converged iterate
    /// (the accumulated `slip` left 0 for the run to add up), the nodal
    /// sums taken once.
    #[allow(clippy::too_many_arguments)] // `states`' inputs
    pub fn nodal<P: WeightedPoint, E: GapTerm<N>, const N: usize>(
        &self,
        points: &[P],
        evals: &[Option<E>],
        lambda: &[f64],
        active: &[bool],
        pairs: &[MultiplierDof],
        complementarity: &[f64],
    ) -> Vec<NodalFriction> {
        let (weight, slip) = self.nodal_slips(points, evals);
        let states = self.states_of(&weight, &slip, lambda, active, pairs, complementarity);
        self.normal
            .iter()
            .zip(states)
            .enumerate()
            .map(|(k, (&multiplier, state))| NodalFriction {
                multiplier,
                state,
                step_slip: if weight[k] > 0.0 {
                    slip[k] / weight[k]
                } else {
                    0.0
                },
                slip: 0.0,
            })
            .collect()
    }

    /// The states from the nodal sums `weight` and `slip` (module docs).
    fn states_of(
        &self,
        weight: &[f64],
        slip: &[f64],
        lambda: &[f64],
        active: &[bool],
        pairs: &[MultiplierDof],
        complementarity: &[f64],
    ) -> Vec<FrictionState> {
        self.normal
            .iter()
            .enumerate()
            .map(|(k, &m)| {
                if !active[m.index()] || !(weight[k] > 0.0) {
                    return FrictionState::Open;
                }
                let pair = pairs[m.index()].pair.index();
                let t = lambda[self.normal_count + k];
                let z = t + complementarity[pair] * slip[k] / weight[k];
                let bound = self.mu[pair] * -lambda[m.index()];
                if z.abs() <= bound {
                    FrictionState::Stick
                } else {
                    FrictionState::Slip {
                        direction: if z < 0.0 { -1.0 } else { 1.0 },
                    }
                }
            })
            .collect()
    }

    /// Adds the friction part of the Newton system (module docs): per
    /// point with a slip the terms `w J0 t s'`, `w J0 t s''`, the coupling
    /// `w J0 N_a s'` both ways (zero in a row that is not sticking) and a
    /// sticking row's residual `w J0 N_a s`; then per sliding node its row
    /// `t_a + mu sign(z_a) l_a` (the entry on `l_a` pushed for every
    /// tangential multiplier, so the pattern does not depend on the
    /// states). The open rows (`t_a = 0`) and the zero diagonal of the
    /// others are [`super::assemble_contact`]'s, whose active set marks a
    /// tangential multiplier active unless it is open.
    #[allow(clippy::too_many_arguments)] // the assembly's inputs
    pub fn assemble<P: WeightedPoint, E: GapTerm<N>, const N: usize>(
        &self,
        points: &[P],
        evals: &[Option<E>],
        lambda: &[f64],
        states: &[FrictionState],
        pairs: &[MultiplierDof],
        dofs: &DofMap,
        sys: &mut System,
    ) {
        if !self.any() {
            return;
        }
        for (pt, ev) in points.iter().zip(evals) {
            let Some(ev) = ev else { continue };
            let Some(s) = ev.slip() else { continue };
            let Some(t) = self.traction(pt, lambda) else {
                continue;
            };
            let w = pt.weight_ref();
            let eqs: [Option<EquationIndex>; N] =
                std::array::from_fn(|k| ev.dof(k).and_then(|d| dofs.eq(d)));
            for p in 0..N {
                if let Some(ep) = eqs[p] {
                    sys.residual[ep.index()] += w * t * s.grad[p];
                }
            }
            if let Some(h) = &s.hess {
                for p in 0..N {
                    let Some(ep) = eqs[p] else { continue };
                    for q in 0..N {
                        if let Some(eq) = eqs[q] {
                            sys.push(ep, eq, w * t * h[(p, q)]);
                        }
                    }
                }
            }
            for (m, n_a) in pt.multiplier_shape().iter() {
                let Some(k) = self.tangential_of[m.index()] else {
                    continue;
                };
                let row = dofs.mult_eq(k);
                let stick = states[k.index() - self.normal_count] == FrictionState::Stick;
                if stick {
                    sys.residual[row.index()] += w * n_a * s.slip;
                }
                for p in 0..N {
                    if let Some(ep) = eqs[p] {
                        let v = w * n_a * s.grad[p];
                        sys.push(ep, row, v);
                        sys.push(row, ep, if stick { v } else { 0.0 });
                    }
                }
            }
        }
        for (k, (&m, state)) in self.normal.iter().zip(states).enumerate() {
            let tk = MultiplierIndex::new(self.normal_count + k);
            let row = dofs.mult_eq(tk);
            let normal = dofs.mult_eq(m);
            match *state {
                FrictionState::Slip { direction } => {
                    let mu = self.mu[pairs[m.index()].pair.index()];
                    sys.residual[row.index()] =
                        lambda[tk.index()] + mu * direction * lambda[m.index()];
                    sys.push(row, row, 1.0);
                    sys.push(row, normal, mu * direction);
                }
                FrictionState::Open | FrictionState::Stick => sys.push(row, normal, 0.0),
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ids::{NodeId, PairId};

    fn dof(pair: usize, node: usize) -> MultiplierDof {
        MultiplierDof {
            pair: PairId::new(pair),
            node: NodeId::new(node),
        }
    }

    #[test]
    fn tangential_multipliers_follow_the_normal_ones_of_frictional_pairs() {
        let dofs = [dof(0, 4), dof(0, 5), dof(1, 7), dof(1, 8), dof(1, 9)];
        let f = Friction::new(&dofs, vec![0.0, 0.3]);
        assert_eq!(f.count(), 3);
        assert_eq!(f.normal_count, 5);
        assert_eq!(f.normal, [2, 3, 4].map(MultiplierIndex::new));
        assert_eq!(
            f.tangential_of,
            [None, None, Some(5), Some(6), Some(7)].map(|o| o.map(MultiplierIndex::new))
        );
        let none = Friction::new(&dofs, vec![0.0, 0.0]);
        assert!(!none.any() && none.count() == 0);
    }
}
