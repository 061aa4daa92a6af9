//! Coulomb friction with tangential multipliers (see [`super`], "Coulomb
//! friction"): the slip's terms, the nodal stick/slip/open decision and
//! the friction part of the Newton system, over any dimension's points
//! ([`WeightedPoint`]) and evaluations ([`GapTerm::slip`], a
//! [`PointSlip`]).
//!
//! # The mathematics
//!
//! A slave node `a` of a pair with coefficient `mu > 0` carries, beside its
//! normal multiplier `l_a` (pressure `p_a = -l_a`), tangential multipliers
//! `t_ak` along directions `d_ak` in the slip's components: in 2D one,
//! along the slip's one component (`d_a1 = 1`); in 3D two, along the unit
//! tangents of the node's frame at the last converged state (`face/slip.rs`)
//! in the slip's three global components. At a point the traction is
//! `T = sum_a N_a sum_k t_ak d_ak`, and each integration point adds
//! `w J0 T . s` to the contact potential, with `s` the slip of
//! docs/conventions.md ("The slip": the slave point's tangential
//! displacement relative to the master since the last converged state,
//! `xi_m0`), so per point
//!
//! ```text
//! r_u  += w J0 T . s'            K_uu += w J0 T . s''
//! K_u,tak += w J0 N_a d_ak . s'
//! ```
//!
//! The friction force on the slave is `-T . s'`: with `t > 0` it opposes a
//! slip along `+d`. The nodal weighted slip of the step is
//! `S_ak = sum w J0 N_a d_ak . s` and its weight `W_a = sum w J0 N_a`, over
//! the points of the node's slave faces that have a slip. Coulomb's law at
//! the node, `|t_a| <= mu p_a`, `t_a` along the slip when the node slips,
//! is the complementarity function of a primal–dual active set (Hüeber and
//! Wohlmuth's, on the normal active set of [`super::active_set`]): with the
//! trial `z_a = t_a + c S_a / W_a` (`c` the pair's complementarity
//! constant, the normal test's),
//!
//! * **open** (the normal multiplier inactive, or no point of the node has
//!   a slip): the rows `t_a = 0`;
//! * **stick** (`|z_a| <= mu p_a`): the rows `S_a = 0`, with the coupling
//!   `K_ta,u = sum w J0 N_a d_a . s'` (no slip in the step);
//! * **slip** (`|z_a| > mu p_a`): the rows `t_a - mu p_a z_a / |z_a| = 0`,
//!   i.e. `t_a + mu z^_a l_a = 0` (`z^_a = z_a / |z_a|`). In 2D the
//!   direction is a sign, constant near the solution, and the row's
//!   linearisation (`1` on `t_a`, `mu z^_a` on `l_a`) is exact. In 3D its
//!   consistent linearisation, with `r = mu p_a / |z_a|` (below 1 while
//!   sliding) and `P = I - z^ z^T`, is
//!   `(I - r P) d t_a + mu z^ d l_a - r P (c / W_a) d S_a`: the rows depend
//!   on the displacements through the slip, as a sticking row does.
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
//! A direction of `z_a = 0` (no tangential load and no slip: `sign(0) =
//! +1` in 2D, `(1, 0)` in 3D, with `r = 0`) is reached only with
//! `mu p_a < 0`, a tensile normal multiplier of an iterate, never at a
//! converged state of unilateral contact.
//!
//! Invariants: the tangential multipliers are numbered after every normal
//! one, node by node in the order of their nodes' normal multipliers (a
//! node's `directions` consecutive); a pair with `mu = 0` has none, so a
//! frictionless model's system is unchanged to the bit; sums over points
//! are in point order, over components and directions from the first term
//! (so the 2D sums are those of one component).

use nalgebra::SVector;

use crate::ids::{EquationIndex, MultiplierIndex};
use crate::system::{DofMap, System};

use super::MultiplierDof;
pub use super::term::SlipTerm;
use super::term::{GapTerm, PointSlip, WeightedPoint};

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
    /// The node's normal multiplier.
    pub multiplier: MultiplierIndex,
    /// Its first tangential multiplier (2D: its only one; 3D: the one
    /// along `frame[0]`, the next along `frame[1]`).
    pub tangential: MultiplierIndex,
    /// Open, stick or slip.
    pub state: FrictionState,
    /// The weighted mean slip of the last step along each direction,
    /// `S_ak / W_a` (0 where no point of the node has a slip; 2D: the
    /// second entry 0).
    pub step_slip: [f64; 2],
    /// The accumulated slip length since the start of the solve.
    pub slip: f64,
    /// 3D: the node's two unit tangents (global components) its
    /// tangential multipliers act along; `None` in 2D (one multiplier,
    /// along the slave tangent of docs/conventions.md) and where no point
    /// of the node has a slip.
    pub frame: Option<[[f64; 3]; 2]>,
}

impl NodalFriction {
    /// The length of the last step's slip, `|S_a / W_a|`.
    pub fn step_length(&self) -> f64 {
        let [a, b] = self.step_slip;
        if b == 0.0 { a.abs() } else { a.hypot(b) }
    }
}

/// A frictional node's state at an iterate (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FrictionState {
    /// Not in contact: `t_a = 0`.
    Open,
    /// No slip in the step: `S_a = 0`.
    Stick,
    /// Sliding: `t_a = mu p_a z_a / |z_a|`.
    Slip {
        /// `z_a / |z_a|` (2D: `sign(z_a)` and 0).
        direction: [f64; 2],
        /// `mu p_a / |z_a|`, below 1 at a sliding node of a converged
        /// state (the 3D linearisation's, module docs).
        ratio: f64,
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
    /// Tangential multipliers per node: 1 in 2D, 2 in 3D.
    pub directions: usize,
    /// Each frictional node's normal multiplier, in frictional node order.
    pub normal: Vec<MultiplierIndex>,
    /// Each normal multiplier's frictional node (`None`: frictionless
    /// pair).
    pub node_of: Vec<Option<usize>>,
}

/// The most tangential directions per node.
const MAX_DIRECTIONS: usize = 2;

impl Friction {
    /// `directions` tangential multipliers per normal one of a pair with
    /// `mu > 0` (`mu` per pair), numbered node by node after every normal
    /// multiplier.
    pub fn new(multipliers: &[MultiplierDof], mu: Vec<f64>, directions: usize) -> Friction {
        assert!((1..=MAX_DIRECTIONS).contains(&directions));
        let mut normal = Vec::new();
        let node_of = multipliers
            .iter()
            .enumerate()
            .map(|(m, dof)| {
                (mu[dof.pair.index()] > 0.0).then(|| {
                    normal.push(MultiplierIndex::new(m));
                    normal.len() - 1
                })
            })
            .collect();
        Friction {
            mu,
            normal_count: multipliers.len(),
            directions,
            normal,
            node_of,
        }
    }

    /// The number of tangential multipliers.
    pub fn count(&self) -> usize {
        self.directions * self.normal.len()
    }

    /// Whether any pair has friction.
    pub fn any(&self) -> bool {
        !self.normal.is_empty()
    }

    /// Whether `pair` has friction.
    pub fn on_pair(&self, pair: usize) -> bool {
        self.mu.get(pair).is_some_and(|&mu| mu > 0.0)
    }

    /// The tangential multiplier of frictional node `k` along direction
    /// `d`.
    pub fn tangential(&self, k: usize, d: usize) -> MultiplierIndex {
        MultiplierIndex::new(self.normal_count + self.directions * k + d)
    }

    /// The point's frictional nodes: `(entry j of its multiplier shape,
    /// frictional node k, N_a)`, and how many.
    fn entries<P: WeightedPoint>(&self, pt: &P) -> ([(usize, usize, f64); 4], usize) {
        let mut out = [(0, 0, 0.0); 4];
        let mut count = 0;
        for (j, (m, n_a)) in pt.multiplier_shape().iter().enumerate() {
            if let Some(k) = self.node_of[m.index()] {
                out[count] = (j, k, n_a);
                count += 1;
            }
        }
        (out, count)
    }

    /// Per frictional node the weight `W_a = sum w J0 N_a`, and per
    /// tangential multiplier (node by node) the weighted slip
    /// `S_ak = sum w J0 N_a d_ak . s`, over the points with a slip, in point
    /// order.
    pub fn nodal_slips<P: WeightedPoint, E: GapTerm<N>, const N: usize>(
        &self,
        points: &[P],
        evals: &[Option<E>],
    ) -> (Vec<f64>, Vec<f64>) {
        let mut weight = vec![0.0; self.normal.len()];
        let mut slip = vec![0.0; self.count()];
        for (pt, ev) in points.iter().zip(evals) {
            let Some(s) = ev.as_ref().and_then(|e| e.slip()) else {
                continue;
            };
            let w = pt.weight_ref();
            let (entries, count) = self.entries(pt);
            for &(j, k, n_a) in &entries[..count] {
                weight[k] += w * n_a;
                for d in 0..self.directions {
                    slip[self.directions * k + d] += w * n_a * along(s, j, d);
                }
            }
        }
        (weight, slip)
    }

    /// Each frictional node's state at `(evals, lambda)` with the normal
    /// active set `active` (its first `normal_count` entries) and each
    /// pair's complementarity constant (module docs).
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

    /// Each frictional node's state, step slip and frame at a converged
    /// iterate (the accumulated `slip` left 0 for the run to add up), the
    /// nodal sums taken once.
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
        let mut frames: Vec<Option<[[f64; 3]; 2]>> = vec![None; self.normal.len()];
        if self.directions == 2 {
            for (pt, ev) in points.iter().zip(evals) {
                let Some(s) = ev.as_ref().and_then(|e| e.slip()) else {
                    continue;
                };
                let (entries, count) = self.entries(pt);
                for &(j, k, _) in &entries[..count] {
                    frames[k].get_or_insert_with(|| [s.direction(j, 0), s.direction(j, 1)]);
                }
            }
        }
        self.normal
            .iter()
            .zip(states)
            .enumerate()
            .map(|(k, (&multiplier, state))| NodalFriction {
                multiplier,
                tangential: self.tangential(k, 0),
                state,
                step_slip: std::array::from_fn(|d| {
                    if d < self.directions && weight[k] > 0.0 {
                        slip[self.directions * k + d] / weight[k]
                    } else {
                        0.0
                    }
                }),
                slip: 0.0,
                frame: frames[k],
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
        let dirs = self.directions;
        self.normal
            .iter()
            .enumerate()
            .map(|(k, &m)| {
                if !active[m.index()] || !(weight[k] > 0.0) {
                    return FrictionState::Open;
                }
                let pair = pairs[m.index()].pair.index();
                let mut z = [0.0; MAX_DIRECTIONS];
                for (d, z) in z.iter_mut().enumerate().take(dirs) {
                    let t = lambda[self.tangential(k, d).index()];
                    *z = t + complementarity[pair] * slip[dirs * k + d] / weight[k];
                }
                let norm = if dirs == 1 {
                    z[0].abs()
                } else {
                    z[0].hypot(z[1])
                };
                let bound = self.mu[pair] * -lambda[m.index()];
                if norm <= bound {
                    FrictionState::Stick
                } else if dirs == 1 {
                    FrictionState::Slip {
                        direction: [if z[0] < 0.0 { -1.0 } else { 1.0 }, 0.0],
                        ratio: if norm > 0.0 { bound / norm } else { 0.0 },
                    }
                } else if norm > 0.0 {
                    FrictionState::Slip {
                        direction: [z[0] / norm, z[1] / norm],
                        ratio: bound / norm,
                    }
                } else {
                    FrictionState::Slip {
                        direction: [1.0, 0.0],
                        ratio: 0.0,
                    }
                }
            })
            .collect()
    }

    /// Per frictional node, the `directions x directions` block by which
    /// its rows take the weighted slip's derivatives `dS_ak/du` (module
    /// docs): the identity where it sticks; in 3D where it slips
    /// `-ratio c / W_a (I - z^ z^T)`; `None` elsewhere (open, or sliding in
    /// 2D, where the row does not depend on the slip).
    /// `weight`: [`Friction::nodal_slips`]' nodal weights.
    fn slip_rows(
        &self,
        weight: &[f64],
        states: &[FrictionState],
        pairs: &[MultiplierDof],
        complementarity: &[f64],
    ) -> Vec<Option<[[f64; 2]; 2]>> {
        self.normal
            .iter()
            .zip(states)
            .enumerate()
            .map(|(k, (&m, state))| match *state {
                FrictionState::Stick => Some([[1.0, 0.0], [0.0, 1.0]]),
                FrictionState::Slip {
                    direction: z,
                    ratio,
                } if self.directions == 2 => {
                    let c = complementarity[pairs[m.index()].pair.index()];
                    let g = -ratio * c / weight[k];
                    Some(std::array::from_fn(|a| {
                        std::array::from_fn(|b| g * (if a == b { 1.0 } else { 0.0 } - z[a] * z[b]))
                    }))
                }
                FrictionState::Open | FrictionState::Slip { .. } => None,
            })
            .collect()
    }

    /// Adds the friction part of the Newton system (module docs): per
    /// point with a slip the terms `w J0 T . s'`, `w J0 T . s''`
    /// (`T = sum_a N_a sum_k t_ak d_ak`), the coupling `w J0 N_a d_ak . s'`
    /// into the displacement rows, the rows' dependence on it (a sticking
    /// row's `dS_ak/du` with its residual `S_ak`; a sliding 3D row's
    /// through `z_a`; zero otherwise); then per sliding node its rows
    /// `t_a + mu z^_a l_a` with their derivatives in `t_a` and `l_a` (the
    /// entries on `l_a` and, in 3D, between a node's multipliers pushed for
    /// every node, so the pattern does not depend on the states). The
    /// open rows (`t_a = 0`) and the zero diagonal of the others are
    /// [`super::assemble_contact`]'s, whose active set marks a tangential
    /// multiplier active unless its node is open.
    /// The states are those of `(evals, lambda, active)`, decided here
    /// from the nodal sums the rows take too (one pass over the points).
    #[allow(clippy::too_many_arguments)] // the assembly's inputs
    pub fn assemble<P: WeightedPoint, E: GapTerm<N>, const N: usize>(
        &self,
        points: &[P],
        evals: &[Option<E>],
        lambda: &[f64],
        active: &[bool],
        pairs: &[MultiplierDof],
        complementarity: &[f64],
        dofs: &DofMap,
        sys: &mut System,
    ) {
        if !self.any() {
            return;
        }
        let dirs = self.directions;
        let (weight, slip) = self.nodal_slips(points, evals);
        let states = &self.states_of(&weight, &slip, lambda, active, pairs, complementarity)[..];
        let rows = self.slip_rows(&weight, states, pairs, complementarity);
        for (pt, ev) in points.iter().zip(evals) {
            let Some(ev) = ev else { continue };
            let Some(s) = ev.slip() else { continue };
            let (entries, count) = self.entries(pt);
            if count == 0 {
                continue;
            }
            let comps = s.components();
            // T = sum_a N_a sum_k t_ak d_ak, from the first term.
            let mut traction = [0.0; 3];
            let mut first = true;
            for &(j, k, n_a) in &entries[..count] {
                for d in 0..dirs {
                    let v = n_a * lambda[self.tangential(k, d).index()];
                    let dir = s.direction(j, d);
                    for c in 0..comps {
                        if first {
                            traction[c] = v * dir[c];
                        } else {
                            traction[c] += v * dir[c];
                        }
                    }
                    first = false;
                }
            }
            let w = pt.weight_ref();
            let eqs: [Option<EquationIndex>; N] =
                std::array::from_fn(|k| ev.dof(k).and_then(|d| dofs.eq(d)));
            for p in 0..N {
                if let Some(ep) = eqs[p] {
                    let mut v = w * traction[0] * s.grad(0)[p];
                    for c in 1..comps {
                        v += w * traction[c] * s.grad(c)[p];
                    }
                    sys.residual[ep.index()] += v;
                }
            }
            if let Some(h0) = s.hess(0) {
                // sum_c w T_c s_c'' (one component: (w T) s'' entry by entry)
                let contracted = (comps > 1).then(|| {
                    let mut m = h0 * (w * traction[0]);
                    for c in 1..comps {
                        m +=
                            s.hess(c).expect("every component has its Hessian") * (w * traction[c]);
                    }
                    m
                });
                let wt = w * traction[0];
                for p in 0..N {
                    let Some(ep) = eqs[p] else { continue };
                    for q in 0..N {
                        if let Some(eq) = eqs[q] {
                            let v = contracted.as_ref().map_or(wt * h0[(p, q)], |m| m[(p, q)]);
                            sys.push(ep, eq, v);
                        }
                    }
                }
            }
            for &(j, k, n_a) in &entries[..count] {
                let row: [EquationIndex; MAX_DIRECTIONS] =
                    std::array::from_fn(|d| dofs.mult_eq(self.tangential(k, d.min(dirs - 1))));
                let grads: [SVector<f64, N>; MAX_DIRECTIONS] = std::array::from_fn(|d| {
                    if d < dirs {
                        along_grad(s, j, d)
                    } else {
                        SVector::zeros()
                    }
                });
                if states[k] == FrictionState::Stick {
                    for d in 0..dirs {
                        sys.residual[row[d].index()] += w * n_a * along(s, j, d);
                    }
                }
                for p in 0..N {
                    let Some(ep) = eqs[p] else { continue };
                    let v: [f64; MAX_DIRECTIONS] = std::array::from_fn(|d| w * n_a * grads[d][p]);
                    for d in 0..dirs {
                        sys.push(ep, row[d], v[d]);
                        let dv = match (&rows[k], states[k]) {
                            (Some(_), FrictionState::Stick) => v[d],
                            (Some(g), _) => g[d][0] * v[0] + g[d][1] * v[1],
                            (None, _) => 0.0,
                        };
                        sys.push(row[d], ep, dv);
                    }
                }
            }
        }
        for (k, (&m, state)) in self.normal.iter().zip(states).enumerate() {
            let normal = dofs.mult_eq(m);
            for d in 0..dirs {
                let tk = self.tangential(k, d);
                let row = dofs.mult_eq(tk);
                match *state {
                    FrictionState::Slip { direction, ratio } => {
                        let mu = self.mu[pairs[m.index()].pair.index()];
                        sys.residual[row.index()] =
                            lambda[tk.index()] + mu * direction[d] * lambda[m.index()];
                        if dirs == 1 {
                            sys.push(row, row, 1.0);
                        } else {
                            for e in 0..dirs {
                                let delta = if d == e { 1.0 } else { 0.0 };
                                let col = dofs.mult_eq(self.tangential(k, e));
                                let v = delta - ratio * (delta - direction[d] * direction[e]);
                                sys.push(row, col, v);
                            }
                        }
                        sys.push(row, normal, mu * direction[d]);
                    }
                    FrictionState::Open | FrictionState::Stick => {
                        sys.push(row, normal, 0.0);
                        for e in (0..dirs).filter(|&e| e != d) {
                            sys.push(row, dofs.mult_eq(self.tangential(k, e)), 0.0);
                        }
                    }
                }
            }
        }
    }
}

/// A layout's friction as its [`super::ContactSpace`] methods use it: the
/// tangential multipliers with the layout's points, multipliers and
/// complementarity constants.
#[derive(Debug, Clone, Copy)]
pub struct FrictionView<'a, P> {
    /// The tangential multipliers.
    pub friction: &'a Friction,
    /// The layout's integration points.
    pub points: &'a [P],
    /// The layout's normal multipliers.
    pub pairs: &'a [MultiplierDof],
    /// Each pair's complementarity constant.
    pub complementarity: &'a [f64],
}

impl<P: WeightedPoint> FrictionView<'_, P> {
    /// [`Friction::states`] of the layout.
    pub fn states<E: GapTerm<N>, const N: usize>(
        &self,
        evals: &[Option<E>],
        lambda: &[f64],
        active: &[bool],
    ) -> Vec<FrictionState> {
        let f = self.friction;
        f.states(
            self.points,
            evals,
            lambda,
            active,
            self.pairs,
            self.complementarity,
        )
    }

    /// [`Friction::nodal`] of the layout.
    pub fn nodal<E: GapTerm<N>, const N: usize>(
        &self,
        evals: &[Option<E>],
        lambda: &[f64],
        active: &[bool],
    ) -> Vec<NodalFriction> {
        let f = self.friction;
        f.nodal(
            self.points,
            evals,
            lambda,
            active,
            self.pairs,
            self.complementarity,
        )
    }

    /// Appends to the normal active set `active` the tangential
    /// multipliers' flags: active unless their node is open.
    pub fn extend_active<E: GapTerm<N>, const N: usize>(
        &self,
        evals: &[Option<E>],
        lambda: &[f64],
        active: &mut Vec<bool>,
    ) {
        if !self.friction.any() {
            return;
        }
        let states = self.states(evals, lambda, active);
        let dirs = self.friction.directions;
        for s in states {
            active.extend(std::iter::repeat_n(s != FrictionState::Open, dirs));
        }
    }

    /// [`Friction::assemble`] at the states of `(evals, lambda, active)`.
    pub fn assemble<E: GapTerm<N>, const N: usize>(
        &self,
        evals: &[Option<E>],
        lambda: &[f64],
        active: &[bool],
        dofs: &DofMap,
        sys: &mut System,
    ) {
        if !self.friction.any() {
            return;
        }
        self.friction.assemble(
            self.points,
            evals,
            lambda,
            active,
            self.pairs,
            self.complementarity,
            dofs,
            sys,
        );
    }
}

/// The point's slip along direction `d` of the node at entry `j`,
/// `d_jd . s` (summed from the first component).
fn along<S: PointSlip<N>, const N: usize>(s: &S, j: usize, d: usize) -> f64 {
    let dir = s.direction(j, d);
    let mut v = dir[0] * s.value(0);
    for (c, dc) in dir.iter().enumerate().take(s.components()).skip(1) {
        v += dc * s.value(c);
    }
    v
}

/// The gradient of [`along`].
fn along_grad<S: PointSlip<N>, const N: usize>(s: &S, j: usize, d: usize) -> SVector<f64, N> {
    let dir = s.direction(j, d);
    let mut g = s.grad(0) * dir[0];
    for (c, dc) in dir.iter().enumerate().take(s.components()).skip(1) {
        g += s.grad(c) * *dc;
    }
    g
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
        let f = Friction::new(&dofs, vec![0.0, 0.3], 1);
        assert_eq!(f.count(), 3);
        assert_eq!(f.normal_count, 5);
        assert_eq!(f.normal, [2, 3, 4].map(MultiplierIndex::new));
        assert_eq!(f.node_of, [None, None, Some(0), Some(1), Some(2)]);
        assert_eq!(f.tangential(2, 0), MultiplierIndex::new(7));
        let f3 = Friction::new(&dofs, vec![0.0, 0.3], 2);
        assert_eq!(f3.count(), 6);
        assert_eq!(f3.tangential(1, 1), MultiplierIndex::new(8));
        let none = Friction::new(&dofs, vec![0.0, 0.0], 1);
        assert!(!none.any() && none.count() == 0);
    }
}
