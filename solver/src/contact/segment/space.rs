//! [`ContactSpace`] of 2D segments: [`ContactLayout`]. The kernel
//! evaluations at the integration points (one point on one master
//! segment; every point at once through the trait's passes) and the
//! pairing passes (from scratch, by projection only, the updates at a
//! converged iterate) over the search of `search.rs`.
//!
//! Invariants: results are in point order; kernel calls are counted per
//! point and summed in point order; the first failing point (in point
//! order) is the one reported.

use contact_kernels::{ApproxType, Formulation, KernelError};

use crate::ids::{ContactPointIndex, DofId, MasterSegmentIndex, NodeId, PairId};
use crate::mesh::Mesh;
use crate::model::Model;
use crate::par;
use crate::system::{DofMap, System};

use super::SegmentTaylor;
use super::slip::SlipBuffers;
use crate::contact::MultiplierDof;
use crate::contact::assemble::{ContactShare, assemble_contact_of, assembles_root_terms};
use crate::contact::friction::{Anchor, FrictionState, NodalFriction};
use crate::contact::report::{ContactPointId, ContactPointReport};
use crate::contact::space::{ContactSpace, Update};
use crate::contact::ties::assemble_ties;
use crate::contact::{
    ContactLayout, FaceLayoutError, KernelCounts, NodeTie, PAR_MIN_LEN, Paired, PassIndexes,
    PointEval, PointFailure, Taylor, XI_INSIDE_TOL, XI_STUCK_BAND, slave_side,
};

impl ContactSpace<2> for ContactLayout {
    type Master = MasterSegmentIndex;
    type Eval = PointEval;
    type Found = Paired;
    type Expansion = SegmentTaylor;
    type Anchor = Anchor<MasterSegmentIndex>;
    type Indexes = PassIndexes;

    fn build(model: &Model<2>, formulation: Option<Formulation>) -> Result<Self, FaceLayoutError> {
        Ok(ContactLayout::new(model, formulation))
    }

    fn point_count(&self) -> usize {
        self.points.len()
    }

    fn multipliers(&self) -> &[MultiplierDof] {
        &self.multipliers
    }

    fn multiplier_count(&self) -> usize {
        self.multipliers.len() + self.friction.count()
    }

    fn has_friction(&self) -> bool {
        self.friction.any()
    }

    fn point_has_friction(&self, i: ContactPointIndex) -> bool {
        self.friction.on_pair(self.point(i).pair.index())
    }

    fn anchors(
        &self,
        _mesh: &Mesh<2>,
        _u: &[f64],
        evals: &[Option<PointEval>],
    ) -> Vec<Option<Anchor<MasterSegmentIndex>>> {
        evals
            .iter()
            .map(|e| {
                e.as_ref().map(|e| Anchor {
                    master: e.master,
                    xi_m: e.xi_m,
                })
            })
            .collect()
    }

    fn found_anchors(
        &self,
        _mesh: &Mesh<2>,
        _u: &[f64],
        found: &[Option<Paired>],
    ) -> Vec<Option<Anchor<MasterSegmentIndex>>> {
        found
            .iter()
            .map(|f| {
                f.as_ref().map(|f| Anchor {
                    master: f.0,
                    xi_m: f.1.xi_m,
                })
            })
            .collect()
    }

    fn add_slip(
        &self,
        mesh: &Mesh<2>,
        u: &[f64],
        i: ContactPointIndex,
        e: &mut PointEval,
        anchor: Anchor<MasterSegmentIndex>,
        ty: ApproxType,
    ) -> Result<(), KernelError> {
        self.slip_with(mesh, u, i, e, anchor, ty, &mut SlipBuffers::default())
    }

    /// The trait's pass, with the slip kernel's buffers kept across the
    /// points (`slip.rs`).
    fn add_slips(
        &self,
        mesh: &Mesh<2>,
        u: &[f64],
        evals: &mut [Option<PointEval>],
        anchors: &[Option<Anchor<MasterSegmentIndex>>],
        ty: ApproxType,
        counts: &mut KernelCounts,
    ) -> Result<(), PointFailure> {
        let mut buffers = SlipBuffers::default();
        for (k, (e, anchor)) in evals.iter_mut().zip(anchors).enumerate() {
            let i = ContactPointIndex::new(k);
            let (Some(e), Some(anchor)) = (e, anchor) else {
                continue;
            };
            if !self.point_has_friction(i) {
                continue;
            }
            counts.evaluate += 1;
            self.slip_with(mesh, u, i, e, *anchor, ty, &mut buffers)
                .map_err(|error| PointFailure {
                    point: i,
                    master_segment: Some(e.master),
                    error,
                })?;
        }
        Ok(())
    }

    fn nodal_friction(
        &self,
        evals: &[Option<PointEval>],
        lambda: &[f64],
        active: &[bool],
    ) -> Vec<NodalFriction> {
        self.friction_view().nodal(evals, lambda, active)
    }

    fn friction_states(
        &self,
        evals: &[Option<PointEval>],
        lambda: &[f64],
        active: &[bool],
    ) -> Vec<FrictionState> {
        self.friction_view().states(evals, lambda, active)
    }

    fn formulations(&self) -> Vec<Formulation> {
        self.formulations.clone()
    }

    fn point_id(&self, i: ContactPointIndex, master: Option<MasterSegmentIndex>) -> ContactPointId {
        let p = self.point(i);
        ContactPointId {
            pair: p.pair.index(),
            slave_segment: p.slave_segment,
            gauss: p.gauss,
            master_segment: master.map(MasterSegmentIndex::index),
            on_faces: false,
        }
    }

    fn master(e: &PointEval) -> MasterSegmentIndex {
        e.master
    }

    fn gap(e: &PointEval) -> f64 {
        e.gap
    }

    fn found_master(f: &Paired) -> MasterSegmentIndex {
        f.0
    }

    fn found_gap(f: &Paired) -> f64 {
        f.1.gap
    }

    /// Pairs every point from scratch (sequentially): each point's search
    /// starts from the master segment found for the previous point of the
    /// same pair, so along a face the walk usually finds it in a step or
    /// two instead of trying every master segment.
    fn initial_pairing(
        &self,
        mesh: &Mesh,
        u: &[f64],
    ) -> Result<(Vec<Option<MasterSegmentIndex>>, KernelCounts), PointFailure> {
        let mut counts = KernelCounts::default();
        let indexes = self.pass_indexes();
        let mut out = Vec::with_capacity(self.points.len());
        let mut seed: Option<(PairId, MasterSegmentIndex)> = None;
        for (i, pt) in self.points.iter().enumerate() {
            let i = ContactPointIndex::new(i);
            let start = seed.filter(|(pair, _)| *pair == pt.pair).map(|(_, m)| m);
            let found = self
                .find_master(mesh, u, i, start, &indexes, &mut counts)?
                .map(|(m, _)| m);
            if let Some(m) = found {
                seed = Some((pt.pair, m));
            }
            out.push(found);
        }
        Ok((out, counts))
    }

    fn indexes(&self, _mesh: &Mesh<2>, _u: &[f64]) -> PassIndexes {
        self.pass_indexes()
    }

    /// Pairs point `i` (from its current master `start`) and evaluates the
    /// kernel of type `ty` there. `Ok(None)`: the point projects into no
    /// master segment.
    #[allow(clippy::too_many_arguments)] // the pass's state: mesh, u, indexes, counts
    fn pair_and_evaluate(
        &self,
        mesh: &Mesh,
        u: &[f64],
        i: ContactPointIndex,
        start: Option<MasterSegmentIndex>,
        ty: ApproxType,
        indexes: &PassIndexes,
        counts: &mut KernelCounts,
    ) -> Result<Option<PointEval>, PointFailure> {
        let eval = |master: MasterSegmentIndex, counts: &mut KernelCounts| {
            self.evaluate_on(mesh, u, i, master, ty, counts)
        };
        if let Some(m) = start {
            match eval(m, counts) {
                Ok(e)
                    if e.xi_m.abs() <= 1.0 + XI_INSIDE_TOL
                        && self.faces_each_other(mesh, u, i, m) =>
                {
                    return Ok(Some(e));
                }
                Ok(_) => {}
                Err(e) if slave_side(&e) => {
                    return Err(PointFailure {
                        point: i,
                        master_segment: Some(m),
                        error: e,
                    });
                }
                Err(_) => {}
            }
        }
        match self.find_master(mesh, u, i, start, indexes, counts)? {
            None => Ok(None),
            Some((m, _)) => eval(m, counts).map(Some).map_err(|error| PointFailure {
                point: i,
                master_segment: Some(m),
                error,
            }),
        }
    }

    /// Evaluates the kernel of type `ty` for point `i` on master segment
    /// `master`, wherever on the segment's line the point projects.
    fn evaluate_on(
        &self,
        mesh: &Mesh,
        u: &[f64],
        i: ContactPointIndex,
        master: MasterSegmentIndex,
        ty: ApproxType,
        counts: &mut KernelCounts,
    ) -> Result<PointEval, KernelError> {
        let pt = self.point(i);
        counts.evaluate += 1;
        let nodes = self.nodes(pt, master);
        contact_kernels::evaluate(
            self.formulations[pt.pair.index()],
            ty,
            &Self::q(mesh, u, nodes),
            pt.xi_s,
        )
        .map(|k| PointEval {
            master,
            nodes,
            gap: k.gap,
            xi_m: k.xi_m,
            grad: k.grad,
            hess: k.hess,
            slip: None,
        })
    }

    /// Re-pairs every point by projection only (no derivatives): the exact
    /// gap and `xi_m` at displacements `u`, for reports.
    fn project_all(
        &self,
        mesh: &Mesh,
        u: &[f64],
        pairing: &[Option<MasterSegmentIndex>],
    ) -> Result<(Vec<Option<Paired>>, KernelCounts), PointFailure> {
        let indexes = self.pass_indexes();
        par::try_map_counted(self.points.len(), PAR_MIN_LEN, |i, c| {
            let start = pairing[i];
            self.find_master(mesh, u, ContactPointIndex::new(i), start, &indexes, c)
        })
    }

    /// The pairing changes due at a converged iterate of the complete
    /// formulation (module docs, "Complete formulation"): every active point
    /// whose projection has left its master segment (`|xi_m| > 1 +`
    /// [`XI_INSIDE_TOL`] in `evals`) is searched for from that segment, every
    /// inactive point from scratch. Returns `(point, new pairing)` for the
    /// points whose master segment changes, in point order, with the
    /// projection onto the new segment (`None`: the point now projects into
    /// no master segment).
    fn pairing_updates(
        &self,
        mesh: &Mesh,
        u: &[f64],
        evals: &[Option<PointEval>],
    ) -> Result<(Vec<Update<Self, 2>>, KernelCounts), PointFailure> {
        let mut counts = KernelCounts::default();
        let indexes = self.pass_indexes();
        let mut out = Vec::new();
        for (i, ev) in evals.iter().enumerate() {
            let i = ContactPointIndex::new(i);
            let current = match ev {
                Some(e)
                    if e.xi_m.abs() <= 1.0 + XI_INSIDE_TOL
                        && self.faces_each_other(mesh, u, i, e.master) =>
                {
                    continue;
                }
                Some(e) => Some(e.master),
                None => None,
            };
            let found = self.find_master(mesh, u, i, current, &indexes, &mut counts)?;
            if found.map(|(m, _)| m) != current {
                out.push((i, found));
            }
        }
        Ok((out, counts))
    }

    fn reports(&self, found: &[Option<Paired>]) -> Vec<ContactPointReport> {
        self.points
            .iter()
            .zip(found)
            .map(|(p, proj)| ContactPointReport {
                pair: p.pair.index(),
                slave_segment: p.slave_segment,
                gauss: p.gauss,
                xi_s: p.xi_s,
                slave_nodes: p.slave_nodes.map(NodeId::index),
                master_segment: proj.map(|(m, _)| m.index()),
                master_nodes: proj
                    .map(|(m, _)| self.masters_of(p.pair)[m.index()].map(NodeId::index)),
                xi_m: proj.map(|(_, pr)| pr.xi_m),
                gap: proj.map(|(_, pr)| pr.gap),
            })
            .collect()
    }

    fn stuck_xi(&self, e: &PointEval) -> f64 {
        e.xi_m
    }

    fn found_stuck_xi(&self, f: &Paired) -> f64 {
        f.1.xi_m
    }

    fn within_band(&self, e: &PointEval) -> bool {
        e.xi_m.abs() <= 1.0 + XI_STUCK_BAND
    }

    fn found_at_boundary(&self, f: &Paired) -> bool {
        f.1.xi_m.abs() >= 1.0 - XI_STUCK_BAND
    }

    fn active(
        &self,
        evals: &[Option<PointEval>],
        lambda: &[f64],
        length_scale: f64,
        first: bool,
    ) -> Vec<bool> {
        let view = self.active_set_view();
        let mut active = view.active_multipliers(evals, lambda, length_scale);
        if first {
            view.close_touching(evals, lambda, &mut active);
        }
        self.friction_view()
            .extend_active(evals, lambda, &mut active);
        active
    }

    fn assemble(
        &self,
        evals: &[Option<PointEval>],
        lambda: &[f64],
        active: &[bool],
        dofs: &DofMap,
        share: Option<&ContactShare>,
        sys: &mut System,
    ) {
        assemble_contact_of(&self.points, evals, lambda, active, dofs, share, sys);
        if assembles_root_terms(share) {
            self.friction_view()
                .assemble(evals, lambda, active, dofs, sys);
        }
    }

    fn assemble_ties(
        ties: &[NodeTie],
        evals: &[Option<PointEval>],
        others: &[PointEval],
        dofs: &DofMap,
        sys: &mut System,
    ) {
        assemble_ties(ties, evals, others, dofs, sys);
    }

    fn expand_at(e: PointEval, u: &[f64]) -> SegmentTaylor {
        Taylor::at(e, u)
    }

    fn expand(x: &SegmentTaylor, u: &[f64]) -> PointEval {
        x.expand(u)
    }

    fn expanded(x: &SegmentTaylor) -> &PointEval {
        &x.at_start
    }

    fn moved(t: &SegmentTaylor, u: &[f64]) -> bool {
        (0..8).any(|k| t.u0[k] != u[DofId::of(t.at_start.nodes[k / 2], k % 2).index()])
    }

    fn remainder_length(
        &self,
        mesh: &Mesh<2>,
        i: ContactPointIndex,
        active: &[bool],
    ) -> Option<f64> {
        let pt = self.point(i);
        if !pt.multipliers.iter().any(|m| active[m.index()]) {
            return None;
        }
        let [a, b] = pt.slave_nodes.map(|n| mesh.node_ref(n));
        Some((b[0] - a[0]).hypot(b[1] - a[1]))
    }

    fn can_tie(&self, i: ContactPointIndex, p: MasterSegmentIndex, o: MasterSegmentIndex) -> bool {
        self.shared_node(self.point(i).pair, p, o).is_some()
    }

    fn tie_theta(&self, tie: &NodeTie, lambda: &[f64]) -> Option<f64> {
        tie.theta(self.point(tie.point), lambda)
    }

    fn at_node(e: &PointEval) -> bool {
        (e.xi_m.abs() - 1.0).abs() <= XI_STUCK_BAND
    }
}
