//! [`ContactSpace`] of 3D faces: [`FaceLayout`] (tri3 and quad4 faces,
//! `crate::contact::face_layout`, pairing by `face_pairing`). It keeps the
//! trait's defaults of an element without node ties and without a
//! per-point report (module docs of [`super::space`]; the 3D contact table
//! is [`FaceLayout::nodal_table`]).

use contact_kernels::{ApproxType, Formulation, KernelError};

use crate::assembly::{DofMap, System, assemble_contact_terms};
use crate::contact::{
    FACE_COORDS, FaceEval, FaceFound, FaceLayout, FaceLayoutError, KernelCounts, PointFailure,
    Taylor, WeightedPoint, XI_STUCK_BAND,
};
use crate::ids::{ContactPointIndex, MasterFaceIndex};
use crate::mesh::Mesh;
use crate::mesh::face_shape::reach;
use crate::model::Model;
use crate::solution::{ContactPointId, MultiplierDofInfo};

use super::space::{ContactSpace, EvalsResult, FoundResult, Update};

/// A 3D point's frozen expansion.
type FaceTaylor = Taylor<FaceEval, FACE_COORDS>;

impl ContactSpace<3> for FaceLayout {
    type Master = MasterFaceIndex;
    type Eval = FaceEval;
    type Found = FaceFound;
    type Expansion = FaceTaylor;

    fn build(model: &Model<3>, formulation: Option<Formulation>) -> Result<Self, FaceLayoutError> {
        FaceLayout::new(&model.mesh, &model.contacts, formulation)
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
        self.readings.clone()
    }

    fn point_id(&self, i: ContactPointIndex, master: Option<MasterFaceIndex>) -> ContactPointId {
        let p = self.point(i);
        ContactPointId {
            pair: p.pair.index(),
            slave_segment: p.slave_face,
            gauss: p.gauss,
            master_segment: master.map(MasterFaceIndex::index),
            on_faces: true,
        }
    }

    fn master(e: &FaceEval) -> MasterFaceIndex {
        e.master
    }

    fn gap(e: &FaceEval) -> f64 {
        e.gap
    }

    fn found_master(f: &FaceFound) -> MasterFaceIndex {
        f.master
    }

    fn found_gap(f: &FaceFound) -> f64 {
        f.gap
    }

    fn initial_pairing(
        &self,
        mesh: &Mesh<3>,
        u: &[f64],
    ) -> Result<(Vec<Option<MasterFaceIndex>>, KernelCounts), PointFailure<MasterFaceIndex>> {
        FaceLayout::initial_pairing(self, mesh, u)
    }

    fn evaluate_all(
        &self,
        mesh: &Mesh<3>,
        u: &[f64],
        pairing: &[Option<MasterFaceIndex>],
        ty: ApproxType,
    ) -> EvalsResult<Self, 3> {
        FaceLayout::evaluate_all(self, mesh, u, pairing, ty)
    }

    fn evaluate_paired(
        &self,
        mesh: &Mesh<3>,
        u: &[f64],
        pairing: &[Option<MasterFaceIndex>],
        ty: ApproxType,
    ) -> EvalsResult<Self, 3> {
        FaceLayout::evaluate_paired(self, mesh, u, pairing, ty)
    }

    fn evaluate_on(
        &self,
        mesh: &Mesh<3>,
        u: &[f64],
        i: ContactPointIndex,
        master: MasterFaceIndex,
        ty: ApproxType,
        counts: &mut KernelCounts,
    ) -> Result<FaceEval, KernelError> {
        FaceLayout::evaluate_on(self, mesh, u, i, master, ty, counts)
    }

    fn project_all(
        &self,
        mesh: &Mesh<3>,
        u: &[f64],
        pairing: &[Option<MasterFaceIndex>],
    ) -> FoundResult<Self, 3> {
        FaceLayout::project_all(self, mesh, u, pairing)
    }

    fn pairing_updates(
        &self,
        mesh: &Mesh<3>,
        u: &[f64],
        evals: &[Option<FaceEval>],
    ) -> Result<(Vec<Update<Self, 3>>, KernelCounts), PointFailure<MasterFaceIndex>> {
        FaceLayout::pairing_updates(self, mesh, u, evals)
    }

    fn stuck_xi(&self, e: &FaceEval) -> f64 {
        reach(e.master_kind, e.xi_m)
    }

    fn found_stuck_xi(&self, f: &FaceFound) -> f64 {
        reach(f.kind, f.xi_m)
    }

    fn within_band(&self, e: &FaceEval) -> bool {
        reach(e.master_kind, e.xi_m) <= 1.0 + XI_STUCK_BAND
    }

    fn found_at_boundary(&self, f: &FaceFound) -> bool {
        reach(f.kind, f.xi_m) >= 1.0 - XI_STUCK_BAND
    }

    fn active(
        &self,
        evals: &[Option<FaceEval>],
        lambda: &[f64],
        length_scale: f64,
        first: bool,
    ) -> Vec<bool> {
        let view = self.active_set_view();
        let mut active = view.active_multipliers(evals, lambda, length_scale);
        if first {
            view.close_touching(evals, lambda, &mut active);
        }
        active
    }

    fn assemble(
        &self,
        evals: &[Option<FaceEval>],
        lambda: &[f64],
        active: &[bool],
        dofs: &DofMap,
        sys: &mut System,
    ) {
        assemble_contact_terms(&self.points, evals, lambda, active, dofs, sys);
    }

    fn expand_at(e: FaceEval, u: &[f64]) -> FaceTaylor {
        Taylor::at(e, u)
    }

    fn expand(x: &FaceTaylor, u: &[f64]) -> FaceEval {
        x.expand(u)
    }

    fn expanded(x: &FaceTaylor) -> &FaceEval {
        &x.at_start
    }

    fn moved(t: &FaceTaylor, u: &[f64]) -> bool {
        let e = &t.at_start;
        (0..3 * e.node_count)
            .any(|k| t.u0[k] != u[crate::ids::DofId::in_dim::<3>(e.nodes[k / 3], k % 3).index()])
    }

    fn remainder_length(
        &self,
        mesh: &Mesh<3>,
        i: ContactPointIndex,
        active: &[bool],
    ) -> Option<f64> {
        let pt = self.point(i);
        if !pt.multiplier_shape().iter().any(|(m, _)| active[m.index()]) {
            return None;
        }
        Some(pt.slave.map_nodes(|n| mesh.node_ref(n)).size())
    }
}
