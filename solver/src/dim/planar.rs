//! [`ContactSpace`] of 2D segments: [`ContactLayout`], each method the
//! call the Newton loop made before the seam (so 2D results are
//! unchanged to the bit).

use contact_kernels::{ApproxType, Formulation, KernelError};

use crate::assembly::{DofMap, System, assemble_contact, assemble_ties};
use crate::contact::{
    ContactLayout, FaceLayoutError, KernelCounts, NodeTie, Paired, PointEval, PointFailure, Taylor,
    XI_STUCK_BAND,
};
use crate::ids::{ContactPointIndex, DofId, MasterSegmentIndex, NodeId};
use crate::mesh::Mesh;
use crate::model::Model;
use crate::solution::{ContactPointId, ContactPointReport, MultiplierDofInfo};

use super::space::{ContactSpace, EvalsResult, FoundResult, Update};

impl ContactSpace<2> for ContactLayout {
    type Master = MasterSegmentIndex;
    type Eval = PointEval;
    type Found = Paired;
    type Expansion = Taylor;

    fn build(model: &Model<2>, formulation: Option<Formulation>) -> Result<Self, FaceLayoutError> {
        Ok(ContactLayout::new(model, formulation))
    }

    fn point_count(&self) -> usize {
        self.points.len()
    }

    fn multiplier_count(&self) -> usize {
        self.multipliers.len()
    }

    fn multiplier_dofs(&self) -> Vec<MultiplierDofInfo> {
        super::space::multiplier_dofs(&self.multipliers)
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

    fn initial_pairing(
        &self,
        mesh: &Mesh<2>,
        u: &[f64],
    ) -> Result<(Vec<Option<MasterSegmentIndex>>, KernelCounts), PointFailure> {
        ContactLayout::initial_pairing(self, mesh, u)
    }

    fn evaluate_all(
        &self,
        mesh: &Mesh<2>,
        u: &[f64],
        pairing: &[Option<MasterSegmentIndex>],
        ty: ApproxType,
    ) -> EvalsResult<Self, 2> {
        ContactLayout::evaluate_all(self, mesh, u, pairing, ty)
    }

    fn evaluate_paired(
        &self,
        mesh: &Mesh<2>,
        u: &[f64],
        pairing: &[Option<MasterSegmentIndex>],
        ty: ApproxType,
    ) -> EvalsResult<Self, 2> {
        ContactLayout::evaluate_paired(self, mesh, u, pairing, ty)
    }

    fn evaluate_on(
        &self,
        mesh: &Mesh<2>,
        u: &[f64],
        i: ContactPointIndex,
        master: MasterSegmentIndex,
        ty: ApproxType,
        counts: &mut KernelCounts,
    ) -> Result<PointEval, KernelError> {
        ContactLayout::evaluate_on(self, mesh, u, i, master, ty, counts)
    }

    fn project_all(
        &self,
        mesh: &Mesh<2>,
        u: &[f64],
        pairing: &[Option<MasterSegmentIndex>],
    ) -> FoundResult<Self, 2> {
        ContactLayout::project_all(self, mesh, u, pairing)
    }

    fn pairing_updates(
        &self,
        mesh: &Mesh<2>,
        u: &[f64],
        evals: &[Option<PointEval>],
    ) -> Result<(Vec<Update<Self, 2>>, KernelCounts), PointFailure> {
        ContactLayout::pairing_updates(self, mesh, u, evals)
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
        let mut active = self.active_multipliers(evals, lambda, length_scale);
        if first {
            self.close_touching(evals, lambda, &mut active);
        }
        active
    }

    fn assemble(
        &self,
        evals: &[Option<PointEval>],
        lambda: &[f64],
        active: &[bool],
        dofs: &DofMap,
        sys: &mut System,
    ) {
        assemble_contact(self, evals, lambda, active, dofs, sys);
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

    fn expand_at(e: PointEval, u: &[f64]) -> Taylor {
        Taylor::at(e, u)
    }

    fn expand(x: &Taylor, u: &[f64]) -> PointEval {
        x.expand(u)
    }

    fn expanded(x: &Taylor) -> &PointEval {
        &x.at_start
    }

    fn moved(t: &Taylor, u: &[f64]) -> bool {
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
        tie.theta(self, lambda)
    }

    fn at_node(e: &PointEval) -> bool {
        (e.xi_m.abs() - 1.0).abs() <= XI_STUCK_BAND
    }
}
