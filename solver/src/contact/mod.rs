//! Lagrange-multiplier contact elements and the step-wise Taylor scheme.
//!
//! # The contact element
//!
//! A contact pair has a slave face and a master face, each a chain of
//! 2-node segments ordered counter-clockwise around its own body. Every slave
//! segment carries `n_g` Gauss points `xi_s` (Gauss–Legendre on `[-1, 1]`,
//! weight `w`) integrated in the **reference** configuration with
//! `J0 = |X_s2 - X_s1| / 2`. Each integration point is paired with the master
//! segment it projects into (`xi_m` in `[-1, 1]`), and the generated kernel
//! (crate `contact-kernels`) evaluates the gap `g` of the four nodes
//! `q = [x_s1, x_s2, x_m1, x_m2]` (current coordinates) with its gradient
//! `g'` and Hessian `g''` with respect to those 8 coordinates.
//!
//! Multipliers live at the slave nodes (shared by neighbouring slave
//! segments), `lambda(xi_s) = N1(xi_s) l1 + N2(xi_s) l2`, and the element's
//! potential is `Pi_c = sum_gp w J0 lambda g`, so per integration point
//!
//! ```text
//! r_u     += w J0 lambda g'          K_uu += w J0 lambda g''
//! r_la    += w J0 N_a g              K_u,la = K_la,u += w J0 N_a g'
//! ```
//!
//! With this sign, a compressive contact has `lambda < 0`: the contact
//! pressure is `p = -lambda`.
//!
//! # Integration rule
//!
//! With `integration = "gauss"` (the default) the `n_g` points are the
//! Gauss rule on the whole slave segment. With `integration = "segmented"`
//! each slave segment is first split at the slave points whose projection
//! (in the pair's formulation) reaches a master node, and every piece gets
//! `n_g` Gauss points with weights scaled to the piece, so that the kink
//! of the integrand where the projection crosses a master node is
//! integrated exactly (the contact patch test). The split is computed in
//! the reference configuration when the layout is built; see `segmented`
//! for the formulas, the tolerance and the limits under sliding.
//!
//! # Types 1–6: Taylor coefficients frozen per load step
//!
//! At the start of a load step, at the converged displacements `u0`, every
//! integration point is (re-)paired and that type's kernel gives `g0`, `g'0`,
//! `g''0` (`g''0 = 0` for Type 1). During the step's Newton iterations, with
//! `d = u - u0` on the pair's 8 degrees of freedom,
//!
//! ```text
//! g~ = g0 + g'0 . d + 1/2 d . g''0 d,   g~' = g'0 + g''0 d,   g~'' = g''0,
//! ```
//!
//! so the Newton tangent is exact for the approximated problem. There is no
//! re-projection and no re-pairing until the step has converged. At the
//! converged end the points are re-paired and, where a point ended on
//! another master segment, the step is solved again with the expansion of
//! that segment's gap (still taken at the step start `u0`, where the point
//! projects onto the new segment's line outside the segment); see
//! [`crate::newton`], "Re-pairing at the step end".
//!
//! # Complete formulation
//!
//! Every iteration re-projects every integration point and evaluates the
//! exact (Type 6) kernel on its paired master segment. How the pairing
//! follows the projection is the subject of the next three sections.
//!
//! # Pairing
//!
//! A point is paired with its current master segment if it projects into it
//! (`|xi_m| <= 1 + 1e-9`); otherwise the search walks along the master
//! chain in the direction of `xi_m` and, failing that, tries every master
//! segment and keeps the one with the smallest `|g|` among those the point
//! projects into (the first in master order on a tie; on a master face of
//! [`INDEX_MIN_SEGMENTS`] segments or more, only the candidates the spatial
//! index proves can win are tried, see `master_search`). Only segments that **face** the point's slave segment
//! count (outward normals against each other, `n_s . n_m < 0`,
//! [`ContactLayout::faces_each_other`]): near the end of a curved slave
//! face the slave normal is nearly parallel to the master, and its line
//! meets the master face far away, behind the point (on the ironing punch,
//! a point at the arc's end paired 6.3 "inside" a strip segment 7 away and
//! pulled the punch into it). A point whose segment stops facing its
//! master is re-paired at the next pairing update. A point that projects into no master segment is
//! **inactive**: it contributes nothing, is counted and listed in the
//! solution, and is re-paired at the next step start (Types 1–6) or at the
//! next pairing update (complete). It is never extrapolated.
//!
//! # Pairing in the complete formulation
//!
//! With linear master segments the gap is continuous where a slave point's
//! projection crosses a master node, but its gradient is not: the contact
//! force `lambda w J0 g'` jumps with the angle between the two master
//! segments. Re-pairing a point at every iteration as soon as its
//! projection leaves its segment makes the residual a discontinuous
//! function of the displacements, and Newton can cycle for ever. This
//! happened on the paper scene refined 2 x 1 with 4 steps (step 3, load
//! factor 7.48 -> 7.49; 8 and 20 steps failed at the same load): slave
//! segment 4, Gauss point 0 alternated between master segments 9
//! (`xi_m = 0.99842`) and 10 (`xi_m = -0.99936`) at every iteration with the
//! residual stuck at `3.3e-2` until the iteration limit, cut back 8 times.
//!
//! The complete formulation therefore changes the pairing in two ways only:
//!
//! 1. in the first [`crate::newton::REPAIR_AT_ONCE_ITERATIONS`] iterates of
//!    an attempt (the predictor's large first corrections, which may carry
//!    points across several segments) a point that leaves its segment is
//!    re-paired at once, as above;
//! 2. after that the pairing is frozen and each point is projected onto its
//!    segment's line, also beyond the segment's ends
//!    ([`ContactLayout::evaluate_paired`]): the equations are smooth and
//!    Newton converges quadratically. At a converged iterate, every point
//!    whose projection lies outside its segment (`|xi_m| > 1 + 1e-9`) is
//!    re-paired ([`ContactLayout::pairing_updates`]) and Newton continues
//!    from that converged state with the new pairing.
//!
//! A step is accepted only at a converged iterate that needs no pairing
//! change: then every active point projects into its own master segment and
//! the state is an exact solution of the complete formulation (or a point
//! is held at a master node, next section). A tolerance band around
//! `xi_m = +-1` (hysteresis) also stops the cycling but accepts states
//! where a point is evaluated on the extension of a segment it has left,
//! with that segment's force; tried on the refined scenes, the result
//! depended on the path (2 x 1 with a band of `1e-3`: strain energy 0.93462
//! with 4 steps, 0.92277 with 8) or on which side a stuck point was kept
//! (8 x 1: 1.11392 or 1.11493; the tie below gives 1.11407 for every step
//! count). It was rejected.
//!
//! # Points stuck at a master node
//!
//! A pairing change at a converged iterate can cycle too: a point converged
//! on segment A projects beyond the node into B, and converged on B it
//! projects back into A. Then neither smooth branch has a solution
//! consistent with its own pairing — the point is **stuck at the node**,
//! where the discrete equations only have a solution in the nonsmooth
//! sense: the point sits exactly at the node and its force is a convex
//! combination of the two one-sided forces. (Refined paper scene, 2 x 1,
//! load factor 7.5: the point above, converged on segment 9, projects to
//! `xi_m = 1.00064`, converged on segment 10 to `xi_m = -1.00158`.)
//! The solver then **ties** the point to the node ([`NodeTie`]): with the
//! paired segment `p` and the other one `o`, the point's potential becomes
//!
//! ```text
//! lambda w J0 g_p + mu (g_o - g_p)  =  lambda w J0 ((1 - theta) g_p + theta g_o),
//! theta = mu / (lambda w J0),
//! ```
//!
//! with one more unknown `mu` per tie whose equation `g_o - g_p = 0` holds
//! exactly where the point projects onto the node (the two segments' lines
//! meet there; both kernels are exact Type 6 evaluations, so the tangent is
//! exact, see [`crate::contact::assemble_ties`]). A tie holds while
//! `theta` is in `[0, 1]` and the point projects onto the node (`|xi_m|`
//! on `p` within [`XI_STUCK_BAND`] of 1: where the two segments' lines
//! nearly coincide, `g_o = g_p` holds wherever the point is, and a tied
//! point slid away with the ironing punch, evaluated on `p`'s line 3 away
//! from `p`: the energy was 1.2 % off); at a converged iterate with
//! `theta < 0` or off the node the tie
//! is released to `p`, with `theta > 1` to `o`, and Newton continues (after a
//! release the point may switch once more: when other points moved
//! meanwhile, `theta` can pick the wrong side). Ties are part of the
//! converged state and carry over to the next step. A point that keeps
//! cycling after that, or cycles where no tie is possible (between a
//! segment and none at the end of a master chain), is kept on its current
//! pairing if its projection misses it by less than [`XI_STUCK_BAND`] and
//! is listed in [`crate::StepRecord::kept_outside`]; otherwise the attempt
//! fails ([`crate::CutbackReason::StuckAtMasterNode`]) and is cut back.
//! Ties are listed in [`crate::StepRecord::node_ties`].
//!
//! Measured on the paper scene refined 2x1, 3x1, 4x1, 2x2, 8x1, 4x2 and
//! 16x1 with 4, 6, ..., 20 steps, both formulations: every run converges
//! without cut-backs, the strain energy is the same for every step count to
//! `1e-9` relative (path independence), ties occur (2x1, 3x1, 8x1) with
//! `theta` between 0.19 and 0.87 (the same tied state from either side:
//! `theta` and `1 - theta`), and the band fallback was never needed. The
//! unrefined paper scene never changes a pairing, so its results and
//! iteration counts are unchanged.
//!
//! With the closest-point formulation the gap vector follows the master
//! normal, which differs on the two segments: there `g_o - g_p = 0` holds
//! the point on the bisector of the two segments' lines (equal gaps), which
//! passes through the node; with the gap near zero (contact) that is the
//! node.
//!
//! **3D faces are not tied.** The same tie between two master faces that
//! share an edge or a vertex (the dimension-generic `ties.rs` serves both)
//! was built and measured on `scenes/sliding3d.toml`, whose base is flat
//! but for the dent the block presses into it: the faces a point cycles
//! between meet at a kink of a few thousandths of a radian, where
//! `g_o = g_p` hardly constrains the point (its row is nearly singular).
//! At 40 steps the complete formulation then needed 148 Newton iterations
//! and a cut-back (a diverging attempt folded a slave face) instead of 122
//! and none, and the types' cycling points stayed cycling. So a 3D point
//! that keeps cycling takes the fallback below: it is kept on its master
//! face when its projection misses the face by less than
//! [`XI_STUCK_BAND`] (in *reach*, [`crate::contact::ContactSpace`]'s
//! module docs). Types 1–6 apply the same rule at their step ends
//! (`newton/repair.rs`).
//!
//! # Multipliers and modes
//!
//! * Persistent (equality) contact: a multiplier with at least one active
//!   integration point carries the constraint row `sum w J0 N_a g = 0`; a
//!   multiplier without any gets the row `l_a = 0` (unit diagonal).
//! * Unilateral contact (`g >= 0`, `p = -lambda >= 0`, `p g = 0`): a
//!   primal–dual active set on the multiplier nodes. At every Newton
//!   iteration, with the nodal weighted gap
//!   `g_a = sum w J0 N_a g / sum w J0 N_a`, node `a` is active when
//!   `p_a - c g_a >= 0` (`c = E / h`, the slave body's Young's modulus over
//!   the mean slave segment length); an active node carries the constraint
//!   row, an inactive one the row `l_a = 0`. The system's sparsity pattern
//!   is the same for both. Newton converges when the residual of the
//!   current active set is below tolerance; a step whose active set keeps
//!   changing runs into the iteration limit and is cut back. In the first
//!   iteration of an attempt, a pair without pressure and without an active
//!   node also activates the nodes that touch (`active_set`,
//!   `CLOSING_GAP`), so that a body held only by contact does not float.
//!
//! # Coulomb friction
//!
//! A unilateral pair with `friction = mu > 0` gives each slave node a
//! tangential multiplier (2D) or two (3D, along the node's tangent frame
//! of the last converged state, `face/slip.rs`) beside its normal one;
//! every point adds `w J0 T . s` (`s` the generated slip kernel's value,
//! measured from the point's projection at the last converged state) and
//! each node sticks,
//! slips or is open by a primal–dual active set on Coulomb's law; see
//! [`friction`] for the mathematics and docs/conventions.md, "Coulomb
//! friction", for the definitions and outputs.
//!
//! # Parts
//!
//! * this module: the per-point types ([`ContactPoint`], [`PointEval`],
//!   [`NodeTie`], [`PointFailure`], ...), the Gauss rule and shape functions;
//! * `layout`: [`ContactLayout`], the integration points, multipliers and
//!   master chains of all pairs (built once per solve; never changes);
//! * `segmented`: the integration rule on a slave segment, plain Gauss or
//!   segmented at the projections of the master nodes ([`crate::model::Integration`]);
//! * `search`: pairing by projection (walk along the master chain, then
//!   every segment, through the spatial index on long master faces);
//! * `master_search`: the search over every master segment through the
//!   spatial index (`face_index`), with the proof that it chooses what
//!   trying every segment in order chooses;
//! * `face_index`: the bounding-volume hierarchy over master faces;
//! * `clip`: slave/master face clipping for 3D faces;
//! * `face_rules`: the Gauss rules `gauss_points` gives on a segment, a
//!   quad4 and a tri3 slave face;
//! * `evaluate`: the kernel evaluations at every point, in parallel;
//! * `taylor`: the frozen Taylor expansion of Types 1–6 ([`Taylor`]);
//! * `active_set`: which multipliers carry a constraint row;
//! * `term`: what the assembly, the active set and the expansion read of
//!   a point and its evaluation, in 2D and 3D ([`WeightedPoint`],
//!   [`GapTerm`]);
//! * `face_layout`, `face_pairing`: the 3D contact element between tri3
//!   and quad4 faces ([`FaceLayout`], [`FaceEval`]): its points,
//!   multipliers and kernels, evaluation and pairing through the spatial
//!   index. It is verified on its own (`face_tests`: weights, gaps,
//!   pairing against the scan, residual and tangent against finite
//!   differences) and through Newton (`crate::contact::ContactSpace`,
//!   `solver/tests/contact3d.rs`).
//!
//! Invariants: the point order (pair by pair, slave segment by slave
//! segment, Gauss point by Gauss point) and the multiplier order (pair by
//! pair, in slave-face order) are fixed by the layout; every per-point
//! vector (pairings, evaluations) is in point order, and parallel
//! evaluations return in that order (`crate::par`).

mod active_set;
mod assemble;
pub mod clip;
pub mod face;
pub mod face_index;
pub mod face_rules;
pub mod friction;
mod layout_error;
pub mod reference;
mod report;
pub mod segment;
mod space;
mod taylor;
pub mod term;
mod ties;

use contact_kernels::{KernelError, Segment};

use crate::ids::{ContactPointIndex, MasterSegmentIndex, NodeId, PairId};

pub use active_set::ActiveSetView;
pub use assemble::{ContactShare, assemble_contact, assemble_contact_of, assembles_root_terms};
pub use face::{
    FACE_COORDS, FaceEval, FaceFound, FaceLayout, FaceNodalError, FaceNodalRow, FacePoint,
    MasterFaces, face_formulation,
};
pub use layout_error::{DualBasisError, FaceLayoutError};
pub use reference::ReferencePairing;
pub use report::{ContactPointId, ContactPointReport, MultiplierDofInfo};
pub use segment::{
    ContactLayout, ContactPoint, INDEX_MIN_SEGMENTS, MasterIndex, NodalContactError,
    NodalContactRow, NodalProjection, NodalState, Paired, PairingUpdate, PassIndexes, PointEval,
    SPLIT_TOL, SegmentTaylor, Tried, gap_is_distance, is_new_split, nodal_contact, segmented_rule,
    shape2, slave_coordinate_of_master_end, split_coordinates,
};
pub use space::{ContactSpace, EvalsResult, FoundResult, Update};
pub use taylor::Taylor;
pub use term::{GapTerm, MAX_POINT_MULTIPLIERS, MultiplierShape, WeightedPoint};
pub use ties::assemble_ties;

/// A projection with `|xi_m| <= 1 + XI_INSIDE_TOL` lies inside the master
/// segment.
pub const XI_INSIDE_TOL: f64 = 1e-9;

/// Complete formulation, fallback for stuck points that cannot be tied
/// (module docs, "Points stuck at a master node"): such a point is kept on
/// its current master segment when its projection lies within this band of
/// the segment, `|xi_m| <= 1 + XI_STUCK_BAND`, and kept inactive when its
/// projection lies within the band of the master chain's end,
/// `|xi_m| >= 1 - XI_STUCK_BAND`.
pub const XI_STUCK_BAND: f64 = 1e-2;

/// Points per rayon task (contact evaluation is cheap per point; see
/// [`crate::par`]).
const PAR_MIN_LEN: usize = 256;

/// Gauss–Legendre points and weights on `[-1, 1]` (Newton iteration on the
/// Legendre polynomial, exact to rounding).
pub fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        let mut x = -(std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            let p = if n == 0 { 1.0 } else { p1 };
            let pm1 = if n <= 1 { 1.0 } else { p0 };
            dp = n as f64 * (x * p - pm1) / (x * x - 1.0);
            let dx = p / dp;
            x -= dx;
            if dx.abs() < 1e-16 {
                break;
            }
        }
        out.push((x, 2.0 / ((1.0 - x * x) * dp * dp)));
    }
    out
}

/// One multiplier degree of freedom.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MultiplierDof {
    /// Contact pair.
    pub pair: PairId,
    /// Slave node it lives at.
    pub node: NodeId,
}

/// How many kernel calls were made.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct KernelCounts {
    /// `contact_kernels::evaluate` calls (gap with derivatives).
    pub evaluate: u64,
    /// `contact_kernels::project` calls (gap and `xi_m` only).
    pub project: u64,
}

impl std::ops::AddAssign for KernelCounts {
    fn add_assign(&mut self, o: KernelCounts) {
        self.evaluate += o.evaluate;
        self.project += o.project;
    }
}

/// A kernel failure at one integration point (of a 2D pair; with
/// `M = MasterFaceIndex`, of a 3D pair).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointFailure<M = MasterSegmentIndex> {
    /// Index into [`ContactLayout::points`] (or [`FaceLayout::points`]).
    pub point: ContactPointIndex,
    /// The master segment (or face) tried, if any.
    pub master_segment: Option<M>,
    /// The kernel's error.
    pub error: KernelError,
}

/// Complete formulation: a slave integration point held at the master node
/// shared by two adjacent master segments (module docs, "Points stuck at a
/// master node"). The point's contact potential is
/// `lambda w J0 g_p + mu (g_o - g_p)`, with `g_p` its gap on the `paired`
/// segment and `g_o` on the `other` one. Generic over the master's index
/// so that the Newton loop names one type in 2D and 3D; only 2D segments
/// are ever tied ([`crate::contact::ContactSpace::can_tie`]; why not 3D
/// faces: module docs, "Points stuck at a master node").
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NodeTie<M = MasterSegmentIndex> {
    /// Index into [`ContactLayout::points`].
    pub point: ContactPointIndex,
    /// The master segment the point is paired with (its regular term).
    pub paired: M,
    /// The adjacent master segment beyond the node.
    pub other: M,
    /// The tie's multiplier `mu`.
    pub mu: f64,
}

/// Errors that concern the slave segment or the input itself; no other
/// master segment avoids them. (`CoordinateCount`: a formulation of 3-node
/// segments given the solver's two-node ones, e.g. `--formulation
/// quadratic-slave-normal`, fails loudly instead of finding no contact.)
pub(crate) fn slave_side(e: &KernelError) -> bool {
    matches!(
        e,
        KernelError::NonFinite { .. }
            | KernelError::NotCompiled(_)
            | KernelError::CoordinateCount { .. }
            | KernelError::DegenerateSegment {
                segment: Segment::Slave,
                ..
            }
            | KernelError::FoldedSegment {
                segment: Segment::Slave,
                ..
            }
            | KernelError::DegenerateFace {
                face: Segment::Slave,
                ..
            }
            | KernelError::FoldedFace {
                face: Segment::Slave,
                ..
            }
            | KernelError::SlavePointOutside { .. }
            | KernelError::ParamCount { .. }
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss_legendre_integrates_polynomials_exactly() {
        for n in 1..=8 {
            let rule = gauss_legendre(n);
            assert_eq!(rule.len(), n);
            for k in 0..2 * n {
                let exact = if k % 2 == 1 {
                    0.0
                } else {
                    2.0 / (k as f64 + 1.0)
                };
                let q: f64 = rule.iter().map(|(x, w)| w * x.powi(k as i32)).sum();
                assert!((q - exact).abs() < 1e-14, "n={n} k={k}: {q} vs {exact}");
            }
        }
        let r2 = gauss_legendre(2);
        assert!((r2[0].0 + 1.0 / 3f64.sqrt()).abs() < 1e-15 && (r2[0].1 - 1.0).abs() < 1e-15);
    }
}
