//! [`ContactSpace`]: what the Newton loop reads of the contact element of
//! one dimension: 2D segments ([`ContactLayout`](crate::contact::ContactLayout),
//! `segment/space.rs`) or 3D faces ([`FaceLayout`](crate::contact::FaceLayout),
//! `face/space.rs`), each implementing it directly. The passes over every
//! point that are the same in both (pair and evaluate every point, evaluate
//! on the given masters) are the trait's provided methods, written once
//! over the element's one-point step ([`ContactSpace::pair_and_evaluate`])
//! and its per-pass search indexes ([`ContactSpace::Indexes`]).
//!
//! The element's mathematics is the same in both (see [`crate::contact`]
//! and `crate::contact::face`): integration points on the slave
//! side, each paired with a master segment or face (`Master`), whose
//! evaluation (`Eval`: gap, gradient, Hessian) the assembly adds as
//! `w J0 lambda g`; the frozen Taylor expansions of Types 1–6
//! (`Expansion`) over the evaluation's coordinates; a projection without
//! derivatives (`Found`) for the step-end checks and reports.
//!
//! The projection's *reach* is how far a master parameter lies from its
//! face's centre, 1 on the boundary: `|xi_m|` on a segment, `max(|u|, |v|)`
//! on a quad4, `1 + max(-u, -v, u + v - 1)` on a tri3. The pairing guard
//! reads it against [`crate::contact::XI_STUCK_BAND`].
//!
//! Node ties (a point held at the node between two master segments,
//! `crate::contact`, "Points stuck at a master node") are an optional
//! capability: the trait's defaults are an element without ties
//! ([`ContactSpace::can_tie`] false, so no tie is ever made and the other
//! tie hooks are never reached), which the 3D faces keep; the 2D segments
//! override them with the dimension-generic tie
//! ([`crate::contact::assemble_ties`]).
//!
//! Invariant: the 2D implementation calls exactly the functions the
//! Newton loop called before this seam, in the same order, so 2D results
//! are unchanged to the bit.

use std::sync::OnceLock;

use contact_kernels::{ApproxType, Formulation, KernelError};

use crate::ids::ContactPointIndex;
use crate::mesh::Mesh;
use crate::model::Model;
use crate::model::{Dim, SurfaceDim};
use crate::par;
use crate::system::{DofMap, System};

use super::assemble::ContactShare;
use super::friction::{FrictionState, NodalFriction};
use super::layout_error::FaceLayoutError;
use super::report::{ContactPointId, ContactPointReport, MultiplierDofInfo};
use super::{KernelCounts, MultiplierDof, NodeTie, PAR_MIN_LEN, PointFailure, slave_side};

/// Every point's evaluation (`None`: unpaired) and the kernel calls.
pub type EvalsResult<S, const D: usize> = Result<
    (Vec<Option<<S as ContactSpace<D>>::Eval>>, KernelCounts),
    PointFailure<<S as ContactSpace<D>>::Master>,
>;

/// Every point's projection (`None`: projects nowhere) and the calls.
pub type FoundResult<S, const D: usize> = Result<
    (Vec<Option<<S as ContactSpace<D>>::Found>>, KernelCounts),
    PointFailure<<S as ContactSpace<D>>::Master>,
>;

/// A due pairing change: the point and its new master with the
/// projection onto it (`None`: it projects nowhere).
pub type Update<S, const D: usize> = (ContactPointIndex, Option<<S as ContactSpace<D>>::Found>);

/// The contact element of dimension `D` as the Newton loop sees it
/// (module docs).
pub trait ContactSpace<const D: usize>: Sized + Sync + 'static {
    /// A master segment or face of one pair.
    type Master: Copy + PartialEq + std::fmt::Debug + Send + Sync;
    /// One point's kernel evaluation on its master.
    type Eval: Clone + std::fmt::Debug + Send + Sync;
    /// One point's projection onto a master (no derivatives).
    type Found: Copy + std::fmt::Debug + Send + Sync;
    /// A point's frozen Taylor expansion (Types 1–6).
    type Expansion: Clone + std::fmt::Debug;
    /// Where a point's slip is measured from (module docs of
    /// [`super::friction`]).
    type Anchor: Copy + std::fmt::Debug + Send + Sync;
    /// The master search's indexes of one pass over every point, built
    /// (or begun, lazily) at the pass's displacements.
    type Indexes: Send + Sync;

    /// Lays out the contact pairs of `model`, every pair's formulation
    /// (reading) replaced by `formulation` when given.
    fn build(model: &Model<D>, formulation: Option<Formulation>) -> Result<Self, FaceLayoutError>
    where
        Dim<D>: SurfaceDim<D>;
    /// The number of integration points.
    fn point_count(&self) -> usize;
    /// The multiplier dofs, in multiplier order.
    fn multipliers(&self) -> &[MultiplierDof];
    /// The number of multiplier dofs: the normal ones, then the
    /// tangential ones of the pairs with friction ([`super::friction`]).
    fn multiplier_count(&self) -> usize {
        self.multipliers().len()
    }
    /// Whether a pair has friction (default: none; friction is an
    /// optional capability of an element).
    fn has_friction(&self) -> bool {
        false
    }
    /// Whether point `i`'s pair has friction (default: never).
    fn point_has_friction(&self, _i: ContactPointIndex) -> bool {
        false
    }
    /// Each point's anchor at the converged state `u` from its evaluation
    /// there (module docs of [`super::friction`]; `None`: unpaired, or an
    /// element without friction, the default).
    fn anchors(
        &self,
        _mesh: &Mesh<D>,
        _u: &[f64],
        evals: &[Option<Self::Eval>],
    ) -> Vec<Option<Self::Anchor>> {
        vec![None; evals.len()]
    }
    /// [`anchors`](Self::anchors) from the projections at `u`.
    fn found_anchors(
        &self,
        _mesh: &Mesh<D>,
        _u: &[f64],
        found: &[Option<Self::Found>],
    ) -> Vec<Option<Self::Anchor>> {
        vec![None; found.len()]
    }
    /// Adds to `e`, point `i`'s evaluation at displacements `u`, its slip
    /// (the kernel of type `ty`) measured from `anchor` (module docs of
    /// [`super::friction`]). Default: nothing (no friction).
    #[allow(clippy::too_many_arguments)] // one point's evaluation
    fn add_slip(
        &self,
        _mesh: &Mesh<D>,
        _u: &[f64],
        _i: ContactPointIndex,
        _e: &mut Self::Eval,
        _anchor: Self::Anchor,
        _ty: ApproxType,
    ) -> Result<(), KernelError> {
        Ok(())
    }
    /// [`add_slip`](Self::add_slip) at every evaluated point of a pair
    /// with friction that has an anchor, in point order (the kernel calls
    /// counted); the first failure names its point. Default: nothing (no
    /// friction).
    fn add_slips(
        &self,
        _mesh: &Mesh<D>,
        _u: &[f64],
        _evals: &mut [Option<Self::Eval>],
        _anchors: &[Option<Self::Anchor>],
        _ty: ApproxType,
        _counts: &mut KernelCounts,
    ) -> Result<(), PointFailure<Self::Master>> {
        Ok(())
    }
    /// Each tangential multiplier's state at `(evals, lambda)` with the
    /// active set `active` (default: none).
    fn friction_states(
        &self,
        _evals: &[Option<Self::Eval>],
        _lambda: &[f64],
        _active: &[bool],
    ) -> Vec<FrictionState> {
        Vec::new()
    }
    /// Each tangential multiplier's node, state and step slip at a
    /// converged iterate (default: none).
    fn nodal_friction(
        &self,
        _evals: &[Option<Self::Eval>],
        _lambda: &[f64],
        _active: &[bool],
    ) -> Vec<NodalFriction> {
        Vec::new()
    }
    /// The slave node and pair of every multiplier.
    fn multiplier_dofs(&self) -> Vec<MultiplierDofInfo> {
        self.multipliers()
            .iter()
            .map(|m| MultiplierDofInfo {
                pair: m.pair.index(),
                node: m.node.index(),
            })
            .collect()
    }
    /// Each pair's formulation.
    fn formulations(&self) -> Vec<Formulation>;
    /// Point `i` for reports, with `master` (in 3D the slave "segment" is
    /// the slave face, the Gauss point the point's index on it, the master
    /// segment the master face).
    fn point_id(&self, i: ContactPointIndex, master: Option<Self::Master>) -> ContactPointId;

    /// The master of an evaluation.
    fn master(e: &Self::Eval) -> Self::Master;
    /// The gap of an evaluation.
    fn gap(e: &Self::Eval) -> f64;
    /// The master of a projection.
    fn found_master(f: &Self::Found) -> Self::Master;
    /// The gap of a projection.
    fn found_gap(f: &Self::Found) -> f64;

    /// Pairs every point from scratch at displacements `u`.
    #[allow(clippy::type_complexity)] // the layouts' own signature
    fn initial_pairing(
        &self,
        mesh: &Mesh<D>,
        u: &[f64],
    ) -> Result<(Vec<Option<Self::Master>>, KernelCounts), PointFailure<Self::Master>>;
    /// The master search's indexes for one pass at displacements `u`.
    fn indexes(&self, mesh: &Mesh<D>, u: &[f64]) -> Self::Indexes;
    /// Pairs point `i` (from its current master `start`: kept where the
    /// point still projects into it and the two face each other, else
    /// searched for through `indexes`) and evaluates type `ty` there.
    /// `Ok(None)`: the point projects into no master.
    #[allow(clippy::too_many_arguments)] // the pass's state: mesh, u, indexes, counts
    fn pair_and_evaluate(
        &self,
        mesh: &Mesh<D>,
        u: &[f64],
        i: ContactPointIndex,
        start: Option<Self::Master>,
        ty: ApproxType,
        indexes: &Self::Indexes,
        counts: &mut KernelCounts,
    ) -> Result<Option<Self::Eval>, PointFailure<Self::Master>>;
    /// Pairs every point (each from its master of `pairing`) and evaluates
    /// type `ty` at displacements `u`, in parallel (`crate::par`): the
    /// evaluations in point order (`None`: projects nowhere), the kernel
    /// calls summed in point order, the first failing point's failure.
    fn evaluate_all(
        &self,
        mesh: &Mesh<D>,
        u: &[f64],
        pairing: &[Option<Self::Master>],
        ty: ApproxType,
    ) -> EvalsResult<Self, D> {
        let indexes = self.indexes(mesh, u);
        par::try_map_counted(self.point_count(), PAR_MIN_LEN, |k, c| {
            let i = ContactPointIndex::new(k);
            self.pair_and_evaluate(mesh, u, i, pairing[k], ty, &indexes, c)
        })
    }
    /// Evaluates type `ty` at every point on the master `pairing` gives
    /// it, without re-pairing: the projection onto the master's line or
    /// plane is used also where it falls outside the master (the complete
    /// formulation's Newton iterations, `crate::contact`). `None` points
    /// stay inactive. Only a point whose kernel fails on its master for a
    /// master-side reason (the projection out of reach, say) is re-paired
    /// by search, as [`evaluate_all`](Self::evaluate_all) does; the
    /// indexes are built for the first such point.
    fn evaluate_paired(
        &self,
        mesh: &Mesh<D>,
        u: &[f64],
        pairing: &[Option<Self::Master>],
        ty: ApproxType,
    ) -> EvalsResult<Self, D> {
        let indexes = OnceLock::new();
        par::try_map_counted(self.point_count(), PAR_MIN_LEN, |k, c| {
            let i = ContactPointIndex::new(k);
            let Some(m) = pairing[k] else {
                return Ok(None);
            };
            match self.evaluate_on(mesh, u, i, m, ty, c) {
                Ok(e) => Ok(Some(e)),
                Err(error) if slave_side(&error) => Err(PointFailure {
                    point: i,
                    master_segment: Some(m),
                    error,
                }),
                Err(_) => {
                    let indexes = indexes.get_or_init(|| self.indexes(mesh, u));
                    self.pair_and_evaluate(mesh, u, i, None, ty, indexes, c)
                }
            }
        })
    }
    /// Evaluates type `ty` for point `i` on `master`.
    fn evaluate_on(
        &self,
        mesh: &Mesh<D>,
        u: &[f64],
        i: ContactPointIndex,
        master: Self::Master,
        ty: ApproxType,
        counts: &mut KernelCounts,
    ) -> Result<Self::Eval, KernelError>;
    /// Re-pairs every point by projection only (from `pairing`).
    fn project_all(
        &self,
        mesh: &Mesh<D>,
        u: &[f64],
        pairing: &[Option<Self::Master>],
    ) -> FoundResult<Self, D>;
    /// The pairing changes due at a converged iterate of the complete
    /// formulation evaluated as `evals`, in point order.
    #[allow(clippy::type_complexity)] // the layouts' own signature
    fn pairing_updates(
        &self,
        mesh: &Mesh<D>,
        u: &[f64],
        evals: &[Option<Self::Eval>],
    ) -> Result<(Vec<Update<Self, D>>, KernelCounts), PointFailure<Self::Master>>;
    /// The report of every point at its projection `found` (default:
    /// none; 3D reports the nodal table instead, `crate::report`).
    fn reports(&self, _found: &[Option<Self::Found>]) -> Vec<ContactPointReport> {
        Vec::new()
    }

    /// The parameter a point stuck beyond its master reports: `xi_m` on a
    /// segment, the reach on a face (module docs).
    fn stuck_xi(&self, e: &Self::Eval) -> f64;
    /// The same of a projection.
    fn found_stuck_xi(&self, f: &Self::Found) -> f64;
    /// Whether an evaluation's projection lies within the stuck band of
    /// its master (`reach <= 1 + XI_STUCK_BAND`, in 2D exactly the
    /// earlier `|xi_m| <= 1 + XI_STUCK_BAND`).
    fn within_band(&self, e: &Self::Eval) -> bool;
    /// Whether a projection lies within the stuck band of its master's
    /// boundary (`reach >= 1 - XI_STUCK_BAND`).
    fn found_at_boundary(&self, f: &Self::Found) -> bool;

    /// The active multipliers at `(evals, lambda)`; in the `first`
    /// iteration of an attempt also the touching nodes of unilateral pairs
    /// without contact.
    fn active(
        &self,
        evals: &[Option<Self::Eval>],
        lambda: &[f64],
        length_scale: f64,
        first: bool,
    ) -> Vec<bool>;
    /// Adds the contact element at `evals` to `sys`: the whole element, or
    /// with a `share` one MPI rank's part of it ([`ContactShare`]).
    fn assemble(
        &self,
        evals: &[Option<Self::Eval>],
        lambda: &[f64],
        active: &[bool],
        dofs: &DofMap,
        share: Option<&ContactShare>,
        sys: &mut System,
    );
    // Node ties: an optional capability (module docs). The defaults are an
    // element without ties: none is ever made, so the other hooks are
    // never reached.

    /// Adds the node ties (with `others`, their evaluations on the other
    /// master) to `sys` (default: there are none).
    fn assemble_ties(
        ties: &[NodeTie<Self::Master>],
        evals: &[Option<Self::Eval>],
        others: &[Self::Eval],
        dofs: &DofMap,
        sys: &mut System,
    ) {
        debug_assert!(ties.is_empty(), "no ties without `can_tie`");
        let _ = (evals, others, dofs, sys);
    }

    /// The expansion of `e`, evaluated at displacements `u`.
    fn expand_at(e: Self::Eval, u: &[f64]) -> Self::Expansion;
    /// The expansion's value at displacements `u`.
    fn expand(x: &Self::Expansion, u: &[f64]) -> Self::Eval;
    /// The evaluation an expansion was taken of.
    fn expanded(x: &Self::Expansion) -> &Self::Eval;
    /// Whether `u` differs from the expansion's point on its coordinates.
    fn moved(x: &Self::Expansion, u: &[f64]) -> bool;
    /// The length a step-end Taylor remainder of point `i` is measured in
    /// (the slave segment's length, the slave face's size), `None` when
    /// none of its multipliers is `active`.
    fn remainder_length(
        &self,
        mesh: &Mesh<D>,
        i: ContactPointIndex,
        active: &[bool],
    ) -> Option<f64>;

    /// Whether point `i` may be tied between masters `p` and `o` (they
    /// share a node; default: never).
    fn can_tie(&self, _i: ContactPointIndex, _p: Self::Master, _o: Self::Master) -> bool {
        false
    }
    /// A tie's weight `theta` at multipliers `lambda` (default: none).
    fn tie_theta(&self, _tie: &NodeTie<Self::Master>, _lambda: &[f64]) -> Option<f64> {
        None
    }
    /// Whether a tied point's evaluation is at its master's node (default:
    /// never).
    fn at_node(_e: &Self::Eval) -> bool {
        false
    }
}
