//! [`ContactSpace`] of 3D faces: [`FaceLayout`] (tri3 and quad4 faces,
//! `layout.rs`): the kernel evaluation of one point on
//! one master face, and the pairing passes (from scratch, by projection
//! only, the updates at a converged iterate) over the search of
//! `pairing.rs` (the rule is stated there). It keeps the
//! trait's defaults of an element without node ties and without a
//! per-point report (module docs of [`super::space`]; the 3D contact table
//! is [`FaceLayout::nodal_table`]).

use contact_kernels::{ApproxType, Formulation, KernelError};

use crate::ids::{ContactPointIndex, MasterFaceIndex};
use crate::mesh::Mesh;
use crate::mesh::face_shape::{inside, reach};
use crate::model::Model;
use crate::par;
use crate::system::{DofMap, System};

use super::pairing::MasterFaces;
use super::slip::FaceSlipBuffers;
use super::slip_term::FaceAnchor;
use crate::contact::MultiplierDof;
use crate::contact::assemble::{ContactShare, assemble_contact_of, assembles_root_terms};
use crate::contact::friction::{FrictionState, NodalFriction};
use crate::contact::report::ContactPointId;
use crate::contact::space::ContactSpace;
use crate::contact::term::WeightedPoint;
use crate::contact::{
    FACE_COORDS, FaceEval, FaceFound, FaceLayout, FaceLayoutError, KernelCounts, PAR_MIN_LEN,
    PointFailure, Taylor, XI_INSIDE_TOL, XI_STUCK_BAND, slave_side,
};

/// The points a thread takes at a time in the parallel slip pass (their
/// slips evaluated in batches of one formulation each).
const SLIP_CHUNK: usize = 32;

/// A 3D point's frozen expansion.
type FaceTaylor = Taylor<FaceEval, FACE_COORDS>;

impl ContactSpace<3> for FaceLayout {
    type Master = MasterFaceIndex;
    type Eval = FaceEval;
    type Found = FaceFound;
    type Expansion = FaceTaylor;
    type Anchor = FaceAnchor;
    type Indexes = Vec<Option<MasterFaces>>;

    fn build(model: &Model<3>, formulation: Option<Formulation>) -> Result<Self, FaceLayoutError> {
        FaceLayout::new(&model.mesh, &model.contacts, formulation)
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
        mesh: &Mesh<3>,
        u: &[f64],
        evals: &[Option<FaceEval>],
    ) -> Vec<Option<FaceAnchor>> {
        self.anchors_at(
            mesh,
            u,
            evals.iter().map(|e| e.as_ref().map(|e| (e.master, e.xi_m))),
        )
    }

    fn found_anchors(
        &self,
        mesh: &Mesh<3>,
        u: &[f64],
        found: &[Option<FaceFound>],
    ) -> Vec<Option<FaceAnchor>> {
        self.anchors_at(
            mesh,
            u,
            found.iter().map(|f| f.as_ref().map(|f| (f.master, f.xi_m))),
        )
    }

    fn add_slip(
        &self,
        mesh: &Mesh<3>,
        u: &[f64],
        i: ContactPointIndex,
        e: &mut FaceEval,
        anchor: FaceAnchor,
        ty: ApproxType,
    ) -> Result<(), KernelError> {
        let one = [(i, &*e, &anchor)];
        let mut slips = self.face_slips(mesh, u, &one, ty, &mut FaceSlipBuffers::default());
        e.slip = Some(slips.pop().expect("one result per point")?);
        Ok(())
    }

    /// The trait's pass, in parallel over chunks of [`SLIP_CHUNK`] points
    /// (a face slip kernel with its three Hessians is a gap kernel's work
    /// three times over), each chunk's points of one formulation in one
    /// batch (`face_slips`); results, counts and the first failure in point
    /// order.
    fn add_slips(
        &self,
        mesh: &Mesh<3>,
        u: &[f64],
        evals: &mut [Option<FaceEval>],
        anchors: &[Option<FaceAnchor>],
        ty: ApproxType,
        counts: &mut KernelCounts,
    ) -> Result<(), PointFailure<MasterFaceIndex>> {
        let shared: &[Option<FaceEval>] = evals;
        let chunks = shared.len().div_ceil(SLIP_CHUNK);
        let (slips, c) = par::try_map_counted(chunks, 1, |chunk, c: &mut KernelCounts| {
            let first = chunk * SLIP_CHUNK;
            let points: Vec<_> = (first..shared.len().min(first + SLIP_CHUNK))
                .filter_map(|k| match (&shared[k], anchors.get(k)) {
                    (Some(e), Some(Some(anchor))) => Some((ContactPointIndex::new(k), e, anchor)),
                    _ => None,
                })
                .collect();
            c.evaluate += points.len() as u64;
            let results = self.face_slips(mesh, u, &points, ty, &mut FaceSlipBuffers::default());
            points
                .iter()
                .zip(results)
                .map(|(&(i, e, _), r)| {
                    r.map(|slip| (i, slip)).map_err(|error| PointFailure {
                        point: i,
                        master_segment: Some(e.master),
                        error,
                    })
                })
                .collect::<Result<Vec<_>, _>>()
        })?;
        *counts += c;
        for (i, slip) in slips.into_iter().flatten() {
            if let Some(e) = &mut evals[i.index()] {
                e.slip = Some(slip);
            }
        }
        Ok(())
    }

    fn nodal_friction(
        &self,
        evals: &[Option<FaceEval>],
        lambda: &[f64],
        active: &[bool],
    ) -> Vec<NodalFriction> {
        self.friction_view().nodal(evals, lambda, active)
    }

    fn friction_states(
        &self,
        evals: &[Option<FaceEval>],
        lambda: &[f64],
        active: &[bool],
    ) -> Vec<FrictionState> {
        self.friction_view().states(evals, lambda, active)
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

    /// Pairs every point from scratch at displacements `u`: each point's
    /// master face (`None`: projects into none) and the projection calls.
    fn initial_pairing(
        &self,
        mesh: &Mesh<3>,
        u: &[f64],
    ) -> Result<(Vec<Option<MasterFaceIndex>>, KernelCounts), PointFailure<MasterFaceIndex>> {
        self.pair_all(mesh, u, &self.master_indexes(mesh, u))
    }

    fn indexes(&self, mesh: &Mesh<3>, u: &[f64]) -> Vec<Option<MasterFaces>> {
        self.master_indexes(mesh, u)
    }

    /// Pairs point `i` (from its current master `start`) and evaluates the
    /// kernel of type `ty` there; `Ok(None)`: it projects into no master
    /// face.
    #[allow(clippy::too_many_arguments)] // the pass's state: mesh, u, indexes, counts
    fn pair_and_evaluate(
        &self,
        mesh: &Mesh<3>,
        u: &[f64],
        i: ContactPointIndex,
        start: Option<MasterFaceIndex>,
        ty: ApproxType,
        indexes: &Vec<Option<MasterFaces>>,
        counts: &mut KernelCounts,
    ) -> Result<Option<FaceEval>, PointFailure<MasterFaceIndex>> {
        let fail = |m, error| PointFailure {
            point: i,
            master_segment: m,
            error,
        };
        if let Some(m) = start {
            let kind = self.masters_of(self.point(i).pair)[m.index()].kind();
            match self.evaluate_on(mesh, u, i, m, ty, counts) {
                Ok(e)
                    if inside(kind, e.xi_m, XI_INSIDE_TOL)
                        && self.faces_each_other(mesh, u, i, m, e.xi_m) =>
                {
                    return Ok(Some(e));
                }
                Ok(_) => {}
                Err(e) if slave_side(&e) => return Err(fail(Some(m), e)),
                Err(_) => {}
            }
        }
        let found = self
            .find_master(mesh, u, &self.probe(i), indexes, counts, true)
            .map_err(|(m, e)| fail(m, e))?;
        match found {
            None => Ok(None),
            Some((m, _, _)) => self
                .evaluate_on(mesh, u, i, m, ty, counts)
                .map(Some)
                .map_err(|e| fail(Some(m), e)),
        }
    }

    /// Evaluates the kernel of type `ty` for point `i` on master face
    /// `master`, wherever on the face's surface the point projects.
    fn evaluate_on(
        &self,
        mesh: &Mesh<3>,
        u: &[f64],
        i: ContactPointIndex,
        master: MasterFaceIndex,
        ty: ApproxType,
        counts: &mut KernelCounts,
    ) -> Result<FaceEval, KernelError> {
        self.evaluate_probe(mesh, u, &self.probe(i), master, ty, counts)
    }

    /// Re-pairs every point by projection only (no derivatives), each
    /// from its master face of `pairing`: kept where the point still
    /// projects into it and the faces face each other, else searched for
    /// through the index ([`Self::initial_pairing`]'s choice).
    #[allow(clippy::type_complexity)] // as initial_pairing's
    fn project_all(
        &self,
        mesh: &Mesh<3>,
        u: &[f64],
        pairing: &[Option<MasterFaceIndex>],
    ) -> Result<(Vec<Option<FaceFound>>, KernelCounts), PointFailure<MasterFaceIndex>> {
        let indexes = std::sync::OnceLock::new();
        par::try_map_counted(self.points.len(), PAR_MIN_LEN, |k, c| {
            let i = ContactPointIndex::new(k);
            let fail = |(m, error)| PointFailure {
                point: i,
                master_segment: m,
                error,
            };
            let pt = self.probe(i);
            if let Some(m) = pairing[k]
                && let Some((gap, xi_m)) =
                    self.project_into(mesh, u, &pt, m, c, true).map_err(fail)?
            {
                return Ok(Some(self.found(&pt, m, gap, xi_m)));
            }
            let indexes = indexes.get_or_init(|| self.master_indexes(mesh, u));
            Ok(self
                .find_master(mesh, u, &pt, indexes, c, true)
                .map_err(fail)?
                .map(|(m, gap, xi_m)| self.found(&pt, m, gap, xi_m)))
        })
    }

    /// The pairing changes due at a converged iterate of the complete
    /// formulation, as in 2D: every point whose projection has left its
    /// master face (beyond [`XI_INSIDE_TOL`]) or whose faces no longer face
    /// each other is searched for, every unpaired point too; returns
    /// `(point, new pairing)` for the points whose master face changes, in
    /// point order.
    #[allow(clippy::type_complexity)] // as initial_pairing's
    fn pairing_updates(
        &self,
        mesh: &Mesh<3>,
        u: &[f64],
        evals: &[Option<FaceEval>],
    ) -> Result<
        (Vec<(ContactPointIndex, Option<FaceFound>)>, KernelCounts),
        PointFailure<MasterFaceIndex>,
    > {
        let mut counts = KernelCounts::default();
        let mut indexes = None;
        let mut out = Vec::new();
        for (k, ev) in evals.iter().enumerate() {
            let i = ContactPointIndex::new(k);
            let pair = self.point(i).pair;
            let current = match ev {
                Some(e)
                    if inside(
                        self.masters_of(pair)[e.master.index()].kind(),
                        e.xi_m,
                        XI_INSIDE_TOL,
                    ) && self.faces_each_other(mesh, u, i, e.master, e.xi_m) =>
                {
                    continue;
                }
                Some(e) => Some(e.master),
                None => None,
            };
            let indexes = indexes.get_or_insert_with(|| self.master_indexes(mesh, u));
            let pt = self.probe(i);
            let found = self
                .find_master(mesh, u, &pt, indexes, &mut counts, true)
                .map_err(|(m, error)| PointFailure {
                    point: i,
                    master_segment: m,
                    error,
                })?
                .map(|(m, gap, xi_m)| self.found(&pt, m, gap, xi_m));
            if found.map(|f| f.master) != current {
                out.push((i, found));
            }
        }
        Ok((out, counts))
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
        self.friction_view()
            .extend_active(evals, lambda, &mut active);
        active
    }

    fn assemble(
        &self,
        evals: &[Option<FaceEval>],
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
