//! Which multipliers carry a constraint row (see [`super`], "Multipliers
//! and modes"): persistent pairs, every multiplier with an active
//! integration point; unilateral pairs, the primal–dual active set.
//!
//! A body held only by contact (the Hertz cylinder) touches its master at a
//! point at the start: every nodal weighted gap of its unilateral pair is
//! positive (the neighbours of the touching node are a little off), the
//! primal–dual test activates none, and the first tangent is singular (the
//! body floats). [`ContactLayout::close_touching`] therefore activates, in
//! the first iteration of an attempt only, in a unilateral pair without
//! pressure and without an active node, the nodes whose weighted gap is at
//! most [`CLOSING_GAP`] times their tributary length (the nodes that
//! touch). (Activating only the closest node works too; on the fine Hertz
//! mesh it took 23 iterations in one step instead of 21, 31 in four instead
//! of 29.) The ratio of the touching node grows with the segment length
//! (about `h / (30 R)` at a smooth convex contact), so on a coarse mesh no
//! node may meet it: then the pair's node with the smallest ratio is
//! activated alone if its ratio is at most [`NEARLY_TOUCHING`] (the Hertz
//! cylinder on a mesh with segments of 0.36, ratio 0.012); a pair whose
//! bodies are apart by more than that is left open. Pairs that start in contact along a face
//! (gaps zero: active by the primal–dual test) or pressed (non-zero
//! multipliers) never meet this rule, so their iterations are unchanged.
//!
//! The rules work on any dimension's points and evaluations
//! ([`ActiveSetView`], over [`WeightedPoint`] and [`GapTerm`]): 2D
//! segments ([`super::ContactLayout`]) and 3D faces ([`super::FaceLayout`]), where
//! the tributary length is a tributary area.
//!
//! Invariant: the nodal weights and weighted gaps are summed in point order.

use crate::model::ContactMode;

use super::MultiplierDof;
use super::term::{GapTerm, WeightedPoint};

/// A node of a unilateral pair whose weighted gap is at most this times its
/// tributary length `sum w J0 N_a` counts as touching at the start of an
/// attempt ([`ActiveSetView::close_touching`]). At a smooth convex contact
/// with segments of length `h` and curvature radius `R` the touching node's
/// ratio is about `h / (30 R)`.
pub const CLOSING_GAP: f64 = 1e-2;

/// When no node of a unilateral pair meets [`CLOSING_GAP`], its node with
/// the smallest ratio is activated if the ratio is at most this (module
/// docs).
pub const NEARLY_TOUCHING: f64 = 1e-1;

/// What the active set reads of a layout of any dimension: its points,
/// multipliers, the pairs' modes and active-set constants.
#[derive(Debug, Clone, Copy)]
pub struct ActiveSetView<'a, P> {
    /// The integration points, in point order.
    pub points: &'a [P],
    /// The multiplier dofs.
    pub multipliers: &'a [MultiplierDof],
    /// Each pair's mode.
    pub modes: &'a [ContactMode],
    /// Each pair's active-set constant `c`.
    pub complementarity: &'a [f64],
}

impl<P: WeightedPoint> ActiveSetView<'_, P> {
    /// Per multiplier: the tributary length (or area) `sum w J0 N_a` and
    /// the weighted gap `sum w J0 N_a g` over the paired points, in point
    /// order.
    pub fn nodal_sums<E: GapTerm<N>, const N: usize>(
        &self,
        evals: &[Option<E>],
    ) -> (Vec<f64>, Vec<f64>) {
        let n = self.multipliers.len();
        let mut weight = vec![0.0; n];
        let mut weighted_gap = vec![0.0; n];
        for (pt, ev) in self.points.iter().zip(evals) {
            if let Some(ev) = ev {
                let w = pt.weight_ref();
                for (m, n_a) in pt.multiplier_shape().iter() {
                    let m = m.index();
                    weight[m] += w * n_a;
                    weighted_gap[m] += w * n_a * ev.gap();
                }
            }
        }
        (weight, weighted_gap)
    }

    /// See [`ContactLayout::close_touching`].
    pub fn close_touching<E: GapTerm<N>, const N: usize>(
        &self,
        evals: &[Option<E>],
        lambda: &[f64],
        active: &mut [bool],
    ) {
        let (weight, weighted_gap) = self.nodal_sums(evals);
        for (pair, &mode) in self.modes.iter().enumerate() {
            if mode != ContactMode::Unilateral {
                continue;
            }
            let of_pair: Vec<usize> = (0..self.multipliers.len())
                .filter(|&m| self.multipliers[m].pair.index() == pair)
                .collect();
            if of_pair.iter().any(|&m| active[m] || lambda[m] != 0.0) {
                continue;
            }
            let ratio = |m: usize| weighted_gap[m] / weight[m] / weight[m];
            let mut closed = false;
            for &m in &of_pair {
                if weight[m] > 0.0 && weighted_gap[m] / weight[m] <= CLOSING_GAP * weight[m] {
                    active[m] = true;
                    closed = true;
                }
            }
            if !closed {
                let closest = of_pair
                    .iter()
                    .copied()
                    .filter(|&m| weight[m] > 0.0)
                    .min_by(|&a, &b| ratio(a).total_cmp(&ratio(b)));
                if let Some(m) = closest.filter(|&m| ratio(m) <= NEARLY_TOUCHING) {
                    active[m] = true;
                }
            }
        }
    }

    /// See [`ContactLayout::active_multipliers`].
    pub fn active_multipliers<E: GapTerm<N>, const N: usize>(
        &self,
        evals: &[Option<E>],
        lambda: &[f64],
        length_scale: f64,
    ) -> Vec<bool> {
        let n = self.multipliers.len();
        let (weight, weighted_gap) = self.nodal_sums(evals);
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
