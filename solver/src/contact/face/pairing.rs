//! The 3D contact element's evaluations ([`FaceEval`]) and pairing: which
//! master face a slave integration point projects into.
//!
//! # Pairing
//!
//! A point is paired with its current master face if it projects into it
//! (`xi_m` on the face within [`XI_INSIDE_TOL`]:
//! [`crate::mesh::face_shape::inside`]) and the two faces **face** each
//! other (`n_s . n_m < 0`, the outward normals `t_1 x t_2` of the slave
//! face at `xi_s` and of the master face at `xi_m`, as the 2D rule).
//! Otherwise it is paired with the master face, among all those it
//! projects into and faces, of the smallest `|g|` (the first in master
//! order on a tie), or with none (inactive).
//!
//! The search goes through a [`FaceIndex`] of the pair's master faces'
//! current boxes. Both readings make `x_ms` parallel to the normal `n`
//! (slave-normal: `x_ms` is orthogonal to the slave tangents;
//! closest-point: to the master tangents), so `|x_ms| = |g|`: a point
//! that projects into face `f` at gap `g` lies within `|g|` of a point of
//! `f`, hence of `f`'s box. The faces whose box lies within `r` of `x_s`
//! therefore include every face the point projects into with `|g| <= r`
//! (the query radius is inflated by `1e-6 (r + h)` against the rounding of
//! `x_m` and of the inside tolerance, `h` the mean master face size).
//! Starting from `r = h`: if the best candidate has `|g| <= r` it is the
//! best of all faces; if it has a larger `|g|`, the query is repeated with
//! `r = |g|`, after which the answer is exact; if there is none, `r` grows
//! fourfold until the query holds every face. Under slave-normal a point
//! found on no face within `h` is asked once more, along its line instead:
//! `x_m = x_s + g n_s` lies on the line through `x_s` along the slave
//! normal, so the faces whose box (inflated against the inside tolerance,
//! `LINE_MARGIN`) the line meets include every face it projects into,
//! whatever `|g|`. That query answers at once where the growing ball would
//! test every face of the pair (a point that projects into none, past the
//! master's edge: every Newton iteration of the complete formulation). With
//! no face on the line the first face is tried, so a slave-side failure is
//! the scan's. So the index chooses what trying every face in order
//! chooses (tested against that scan).
//!
//! Invariants: evaluations are in point order; a point is paired only with
//! a face it projects into and faces; slave-side kernel failures
//! ([`super::slave_side`]) are errors, master-side ones mean "not this
//! face".

use contact_kernels::{ApproxType, GapOut, Kernel, KernelError, Projector};
use nalgebra::{SMatrix, SVector};

use crate::element::FaceKind;
use crate::ids::{ContactPointIndex, DofId, MasterFaceIndex, NodeId};
use crate::mesh::Mesh;
use crate::mesh::face_shape::inside;
use crate::mesh::volume::{Face, dot};
use crate::par;

use super::layout::{FaceLayout, face_formulation};
use super::slip_term::FaceSlip;
use crate::contact::face_index::{Aabb, FaceIndex};
use crate::contact::term::GapTerm;
use crate::contact::{KernelCounts, PAR_MIN_LEN, PointFailure, XI_INSIDE_TOL, slave_side};

pub use crate::contact::term::FACE_COORDS;

/// The gap and its derivatives at one paired 3D integration point.
#[derive(Debug, Clone, PartialEq)]
pub struct FaceEval {
    /// Master face index within the pair.
    pub master: MasterFaceIndex,
    /// The master face's kind.
    pub master_kind: FaceKind,
    /// The slave face's nodes then the master face's; `node_count` used.
    pub nodes: [NodeId; 8],
    /// How many of `nodes` are used (6 to 8).
    pub node_count: usize,
    /// Gap (exact or Taylor-approximated).
    pub gap: f64,
    /// The projection `xi_m = (u, v)` on the master face.
    pub xi_m: [f64; 2],
    /// `dg/du` on the `3 node_count` coordinates of `nodes` (zero beyond).
    pub grad: SVector<f64, FACE_COORDS>,
    /// `d2g/du2`, `None` when the type has none (Type 1).
    pub hess: Option<SMatrix<f64, FACE_COORDS, FACE_COORDS>>,
    /// The slip from the point's anchor, when its pair has friction
    /// (`slip.rs`).
    pub slip: Option<Box<FaceSlip>>,
}

impl GapTerm<FACE_COORDS> for FaceEval {
    type Slip = Box<FaceSlip>;

    fn gap(&self) -> f64 {
        self.gap
    }

    fn grad(&self) -> &SVector<f64, FACE_COORDS> {
        &self.grad
    }

    fn hess(&self) -> Option<&SMatrix<f64, FACE_COORDS, FACE_COORDS>> {
        self.hess.as_ref()
    }

    fn dof(&self, k: usize) -> Option<DofId> {
        (k / 3 < self.node_count).then(|| DofId::in_dim::<3>(self.nodes[k / 3], k % 3))
    }

    fn with_values(
        &self,
        gap: f64,
        grad: SVector<f64, FACE_COORDS>,
        slip: Option<Box<FaceSlip>>,
    ) -> FaceEval {
        // field by field: the old slip is not copied
        FaceEval {
            master: self.master,
            master_kind: self.master_kind,
            nodes: self.nodes,
            node_count: self.node_count,
            gap,
            xi_m: self.xi_m,
            grad,
            hess: self.hess,
            slip,
        }
    }

    fn slip(&self) -> Option<&Box<FaceSlip>> {
        self.slip.as_ref()
    }
}

/// A 3D point's projection onto a master face (no derivatives): the step
/// end's re-pairing and the pairing guard's updates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FaceFound {
    /// The master face within the pair.
    pub master: MasterFaceIndex,
    /// Its kind.
    pub kind: FaceKind,
    /// The exact gap.
    pub gap: f64,
    /// The projection `xi_m = (u, v)`.
    pub xi_m: [f64; 2],
}

/// A point of a slave face to pair and evaluate: an integration point
/// ([`FaceLayout::probe`]) or a slave node as a point of its first slave
/// face (the nodal table).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Probe {
    /// The contact pair.
    pub pair: crate::ids::PairId,
    /// The slave face.
    pub slave: Face<NodeId>,
    /// The point's parametric coordinates on it.
    pub xi_s: [f64; 2],
}

/// A kernel failure on a master face (`None`: before any face was tried).
pub(super) type Failure = (Option<MasterFaceIndex>, KernelError);

/// The line query's margin, in units of [`XI_INSIDE_TOL`] times the largest
/// diagonal of a master face's box. A face's points at `xi` up to `tol`
/// outside it lie within `tol` (quad4) or `2 tol` (tri3) times that
/// diagonal of its box: there the negative shape-function weights sum to at
/// most `tol` (about) or `2 tol`, and `x = A + M (A - B)` with `A`, `B` in
/// the nodes' hull and `M` that sum. 8 leaves a wide berth.
const LINE_MARGIN: f64 = 8.0;

/// The master faces' index of one pair at one configuration, with the
/// mean face size `h` and the largest extent of a face's box.
#[derive(Debug)]
pub struct MasterFaces {
    index: FaceIndex<3>,
    size: f64,
    extent: f64,
}

impl FaceLayout {
    /// Integration point `i` as a probe.
    pub fn probe(&self, i: ContactPointIndex) -> Probe {
        let pt = self.point(i);
        Probe {
            pair: pt.pair,
            slave: pt.slave,
            xi_s: pt.xi_s,
        }
    }

    /// The slave face's nodes then master face `master`'s of probe `pt`.
    fn pair_nodes(&self, pt: &Probe, master: MasterFaceIndex) -> ([NodeId; 8], usize) {
        let m = self.masters_of(pt.pair)[master.index()];
        let mut nodes = [NodeId::new(0); 8];
        let mut count = 0;
        for &n in pt.slave.nodes().iter().chain(m.nodes()) {
            nodes[count] = n;
            count += 1;
        }
        (nodes, count)
    }

    /// The current coordinates `q` of `nodes` (3 per node, at most 8
    /// nodes), in the first `3 nodes.len()` entries.
    pub(super) fn q(mesh: &Mesh<3>, u: &[f64], nodes: &[NodeId]) -> [f64; FACE_COORDS] {
        let mut q = [0.0; FACE_COORDS];
        for (k, &n) in nodes.iter().enumerate() {
            q[3 * k..3 * k + 3].copy_from_slice(&Self::current(mesh, u, n));
        }
        q
    }

    /// The kernel formulation of probe `pt` on master face `master`.
    pub(super) fn formulation_of(
        &self,
        pt: &Probe,
        master: MasterFaceIndex,
    ) -> Result<contact_kernels::Formulation, KernelError> {
        let reading = self.readings[pt.pair.index()];
        let m = self.masters_of(pt.pair)[master.index()];
        face_formulation(reading, pt.slave.kind(), m.kind())
            .ok_or(KernelError::NotCompiled(reading))
    }

    /// [`Self::evaluate_on`] for any probe.
    pub(super) fn evaluate_probe(
        &self,
        mesh: &Mesh<3>,
        u: &[f64],
        pt: &Probe,
        master: MasterFaceIndex,
        ty: ApproxType,
        counts: &mut KernelCounts,
    ) -> Result<FaceEval, KernelError> {
        counts.evaluate += 1;
        let kernel = Kernel::new(self.formulation_of(pt, master)?, ty)?;
        let (nodes, node_count) = self.pair_nodes(pt, master);
        let n = 3 * node_count;
        let q = Self::q(mesh, u, &nodes[..node_count]);
        let mut out = GapOut::new(&kernel);
        kernel.eval(&q[..n], pt.xi_s, &mut out)?;
        let g = out.grad();
        let xi = out.xi_m_all();
        Ok(FaceEval {
            master,
            master_kind: self.masters_of(pt.pair)[master.index()].kind(),
            nodes,
            node_count,
            gap: out.gap(),
            xi_m: [xi[0], xi[1]],
            grad: SVector::from_fn(|k, _| if k < n { g[k] } else { 0.0 }),
            hess: out
                .hess()
                .map(|h| SMatrix::from_fn(|r, c| if r < n && c < n { h[r * n + c] } else { 0.0 })),
            slip: None,
        })
    }

    /// Whether point `i`'s slave face at `xi_s` and master face `master`
    /// at `xi_m` face each other at displacements `u` (module docs).
    pub fn faces_each_other(
        &self,
        mesh: &Mesh<3>,
        u: &[f64],
        i: ContactPointIndex,
        master: MasterFaceIndex,
        xi_m: [f64; 2],
    ) -> bool {
        self.facing(mesh, u, &self.probe(i), master, xi_m)
    }

    /// [`Self::faces_each_other`] for any probe.
    fn facing(
        &self,
        mesh: &Mesh<3>,
        u: &[f64],
        pt: &Probe,
        master: MasterFaceIndex,
        xi_m: [f64; 2],
    ) -> bool {
        let s = Self::current_face(mesh, u, &pt.slave);
        let m = Self::current_face(mesh, u, &self.masters_of(pt.pair)[master.index()]);
        dot(s.normal_at(pt.xi_s), m.normal_at(xi_m)) < 0.0
    }

    /// Projects probe `pt` onto master face `master`: `Ok(Some((g, xi_m)))`
    /// when it projects into the face and (when `require_facing`) the faces
    /// face each other, `Ok(None)` when not (or on a master-side kernel
    /// failure), `Err` on a slave-side failure.
    pub(super) fn project_into(
        &self,
        mesh: &Mesh<3>,
        u: &[f64],
        pt: &Probe,
        master: MasterFaceIndex,
        counts: &mut KernelCounts,
        require_facing: bool,
    ) -> Result<Option<(f64, [f64; 2])>, Failure> {
        let fail = |error| (Some(master), error);
        let projector = self.formulation_of(pt, master).and_then(Projector::new);
        let projector = projector.map_err(fail)?;
        let (nodes, node_count) = self.pair_nodes(pt, master);
        let n = 3 * node_count;
        let q = Self::q(mesh, u, &nodes[..node_count]);
        let mut scratch = [0.0; FACE_COORDS];
        counts.project += 1;
        match projector.project(&q[..n], pt.xi_s, &mut scratch[..n]) {
            Ok(p) => {
                let xi = p.xi_m_all();
                let xi_m = [xi[0], xi[1]];
                let kind = self.masters_of(pt.pair)[master.index()].kind();
                Ok((inside(kind, xi_m, XI_INSIDE_TOL)
                    && (!require_facing || self.facing(mesh, u, pt, master, xi_m)))
                .then_some((p.gap, xi_m)))
            }
            Err(e) if slave_side(&e) => Err(fail(e)),
            Err(_) => Ok(None),
        }
    }

    /// The index of every pair's master faces at displacements `u`.
    pub(super) fn master_indexes(&self, mesh: &Mesh<3>, u: &[f64]) -> Vec<Option<MasterFaces>> {
        self.masters
            .iter()
            .map(|faces| {
                let coords: Vec<Face<[f64; 3]>> = faces
                    .iter()
                    .map(|f| Self::current_face(mesh, u, f))
                    .collect();
                let nodes: Vec<&[[f64; 3]]> = coords.iter().map(|f| f.nodes()).collect();
                let size =
                    coords.iter().map(|f| f.size()).sum::<f64>() / coords.len().max(1) as f64;
                let extent = (nodes.iter().enumerate())
                    .filter_map(|(f, n)| Aabb::around(f, n, 0.0).ok())
                    .map(|b| b.diagonal())
                    .fold(0.0, f64::max);
                FaceIndex::from_faces(&nodes, 0.0)
                    .ok()
                    .map(|index| MasterFaces {
                        index,
                        size,
                        extent,
                    })
            })
            .collect()
    }

    /// The master face probe `pt` projects into with the smallest `|g|`
    /// (module docs), with the gap and projection there, through the
    /// pair's index (`None` in `indexes`: a configuration the index
    /// refuses, e.g. non-finite, scanned face by face); the two faces must
    /// face each other when `require_facing` (the pairing's rule), or not
    /// (the reference checks of a scene).
    pub(super) fn find_master(
        &self,
        mesh: &Mesh<3>,
        u: &[f64],
        pt: &Probe,
        indexes: &[Option<MasterFaces>],
        counts: &mut KernelCounts,
        require_facing: bool,
    ) -> Result<Option<(MasterFaceIndex, f64, [f64; 2])>, Failure> {
        let n_faces = self.masters_of(pt.pair).len();
        type Best = Option<(usize, f64, [f64; 2])>;
        let best_of = |cands: &[usize], counts: &mut KernelCounts| -> Result<Best, Failure> {
            let mut best: Best = None;
            for &f in cands {
                if let Some((g, xi)) =
                    self.project_into(mesh, u, pt, MasterFaceIndex::new(f), counts, require_facing)?
                    && best.is_none_or(|(_, b, _)| g.abs() < b.abs())
                {
                    best = Some((f, g, xi));
                }
            }
            Ok(best)
        };
        let found = |b: Best| b.map(|(f, g, xi)| (MasterFaceIndex::new(f), g, xi));
        let Some(faces) = &indexes[pt.pair.index()] else {
            let all: Vec<usize> = (0..n_faces).collect();
            return Ok(found(best_of(&all, counts)?));
        };
        let slave = Self::current_face(mesh, u, &pt.slave);
        let x_s = slave.point_and_tangents(pt.xi_s)[0];
        let mut r = faces.size.max(f64::MIN_POSITIVE);
        loop {
            let slack = 1e-6 * (r + faces.size);
            let cands = match faces.index.query_point(&x_s, r + slack) {
                Ok(c) => c,
                Err(_) => (0..n_faces).collect(),
            };
            match best_of(&cands, counts)? {
                Some(b) if b.1.abs() <= r => return Ok(found(Some(b))),
                Some(b) => r = b.1.abs(),
                None if cands.len() == n_faces => return Ok(None),
                None => {
                    if let Some(line) = self.slave_normal_line(&slave, pt, faces) {
                        // every face the point can project into (module docs)
                        let radius = slack + LINE_MARGIN * XI_INSIDE_TOL * faces.extent;
                        let cands = faces.index.query_line(&x_s, &line, radius).ok();
                        if let Some(mut cands) = cands {
                            if cands.is_empty() {
                                // the scan's first face: its slave-side
                                // failure, if any, is the scan's
                                cands.push(0);
                            }
                            return Ok(found(best_of(&cands, counts)?));
                        }
                    }
                    r *= 4.0
                }
            }
        }
    }

    /// The direction of the line a slave-normal point projects along (its
    /// slave face's normal at `xi_s`, module docs), `None` for the other
    /// reading, master faces of no finite size or a normal that is not a
    /// finite non-zero vector (then the search grows its ball instead).
    fn slave_normal_line(
        &self,
        slave: &Face<[f64; 3]>,
        pt: &Probe,
        faces: &MasterFaces,
    ) -> Option<[f64; 3]> {
        if self.readings[pt.pair.index()] != contact_kernels::Formulation::SlaveNormal
            || !faces.extent.is_finite()
        {
            return None;
        }
        let n = slave.normal_at(pt.xi_s);
        let len = dot(n, n).sqrt();
        (len.is_finite() && len > 0.0).then(|| n.map(|c| c / len))
    }

    /// [`Self::initial_pairing`] trying every master face in order (no
    /// index): the reference the index's choices are tested against.
    pub fn pairing_by_scan(
        &self,
        mesh: &Mesh<3>,
        u: &[f64],
    ) -> Result<(Vec<Option<MasterFaceIndex>>, KernelCounts), PointFailure<MasterFaceIndex>> {
        let none: Vec<Option<MasterFaces>> = self.masters.iter().map(|_| None).collect();
        self.pair_all(mesh, u, &none)
    }

    /// A projection of probe `pt` onto master face `m`.
    pub(super) fn found(
        &self,
        pt: &Probe,
        m: MasterFaceIndex,
        gap: f64,
        xi_m: [f64; 2],
    ) -> FaceFound {
        FaceFound {
            master: m,
            kind: self.masters_of(pt.pair)[m.index()].kind(),
            gap,
            xi_m,
        }
    }

    /// Every point's master face with `indexes` (in parallel).
    pub(super) fn pair_all(
        &self,
        mesh: &Mesh<3>,
        u: &[f64],
        indexes: &[Option<MasterFaces>],
    ) -> Result<(Vec<Option<MasterFaceIndex>>, KernelCounts), PointFailure<MasterFaceIndex>> {
        par::try_map_counted(self.points.len(), PAR_MIN_LEN, |k, c| {
            let i = ContactPointIndex::new(k);
            self.find_master(mesh, u, &self.probe(i), indexes, c, true)
                .map(|f| f.map(|(m, _, _)| m))
                .map_err(|(m, error)| PointFailure {
                    point: i,
                    master_segment: m,
                    error,
                })
        })
    }
}
