//! The slip of the 3D points of pairs with friction
//! ([`crate::contact::friction`]): the generated face slip kernel (three
//! global components, docs/conventions.md, "The slip") of the point's
//! (slave face, master face) kernel, from the master point the slave point
//! faced at the last converged state (its *anchor*: a master face,
//! `xi_m0`, and the tangent frames of the slave face's nodes there).
//!
//! # The tangent frames
//!
//! A frictional slave node `a` carries two tangential multipliers, acting
//! along the unit tangents `d_a1`, `d_a2` of its frame at the last
//! converged state `u0`: with the node's normal
//!
//! ```text
//! n_a = sum w J0 N_a n / |sum w J0 N_a n|
//! ```
//!
//! (over the points of its slave faces, `n` the slave face's unit outward
//! normal at the point in the configuration `u0`), `e` the global axis
//! with the smallest `|n_a . e|` (the first of equals), `d_a1 = (e -
//! (e . n_a) n_a) / |...|` and `d_a2 = n_a x d_a1`. The frame is fixed
//! within a load step (Newton's tangent needs no derivative of it) and
//! taken again at every converged state, so it follows the surface's
//! rotation step by step.
//!
//! # An anchor on another master face
//!
//! A point evaluated on another master face than its anchor's (it crossed
//! a master edge in the step) takes as `xi_m0` the anchor's material point
//! expressed on the new face: the reference position `X0` of the anchor on
//! its face, projected onto the new face's reference surface (extended
//! beyond its edges), by Gauss–Newton on `|X(xi) - X0|^2` from the face's
//! centre (one step on a tri3). As in 2D this is exact for a rigid or
//! uniformly stretched flat master.
//!
//! Invariant: a formulation without a slip is `NotCompiled` (every
//! shipped face formulation defines one).

use contact_kernels::{ApproxType, Formulation, Kernel, KernelError, Slip, SlipBatch};
use nalgebra::{SMatrix, SVector};

use super::slip_term::{FaceAnchor, FaceSlip, Frame};
use crate::contact::term::{FACE_COORDS, MAX_POINT_MULTIPLIERS};
use crate::contact::{FaceEval, FaceLayout};
use crate::ids::{ContactPointIndex, MasterFaceIndex};
use crate::mesh::Mesh;
use crate::mesh::face_shape::FaceShape;
use crate::mesh::volume::{Face, cross};

/// The face slip kernels of a pass, one per (formulation, type), each
/// with its batch and the inputs gathered for it, kept across the points
/// of a pass.
#[derive(Debug, Default)]
pub(super) struct FaceSlipBuffers(Vec<SlipGroup>);

/// The points of one (formulation, type) in a batch: their inputs, which
/// points they are, and the kernel with its outputs.
#[derive(Debug)]
struct SlipGroup {
    formulation: Formulation,
    ty: ApproxType,
    slip: Slip,
    batch: SlipBatch,
    qs: Vec<f64>,
    xi_s: Vec<f64>,
    xi_m0: Vec<f64>,
    members: Vec<usize>,
}

impl FaceSlipBuffers {
    /// The group of `(formulation, ty)`, made on first use.
    fn group(
        &mut self,
        formulation: Formulation,
        ty: ApproxType,
    ) -> Result<&mut SlipGroup, KernelError> {
        let k = match self
            .0
            .iter()
            .position(|g| g.formulation == formulation && g.ty == ty)
        {
            Some(k) => k,
            None => {
                let Some(slip) = Kernel::new(formulation, ty)?.slip() else {
                    return Err(KernelError::NotCompiled(formulation));
                };
                self.0.push(SlipGroup {
                    formulation,
                    ty,
                    slip,
                    batch: SlipBatch::new(&slip),
                    qs: Vec::new(),
                    xi_s: Vec::new(),
                    xi_m0: Vec::new(),
                    members: Vec::new(),
                });
                self.0.len() - 1
            }
        };
        Ok(&mut self.0[k])
    }
}

/// `v / |v|`, or `None` for a zero or non-finite `v`.
fn unit(v: [f64; 3]) -> Option<[f64; 3]> {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    (n > 0.0 && n.is_finite()).then(|| v.map(|c| c / n))
}

/// The frame of a node of unit normal `n` (module docs).
pub fn frame_of(n: [f64; 3]) -> Frame {
    let mut axis = 0;
    for c in 1..3 {
        if n[c].abs() < n[axis].abs() {
            axis = c;
        }
    }
    let mut e = [0.0; 3];
    e[axis] = 1.0;
    let en = e[0] * n[0] + e[1] * n[1] + e[2] * n[2];
    let d1 = unit([e[0] - en * n[0], e[1] - en * n[1], e[2] - en * n[2]])
        .expect("an axis is never parallel to a unit normal's smallest component");
    [d1, cross(n, d1)]
}

impl FaceLayout {
    /// Each frictional node's frame at displacements `u` (module docs),
    /// in frictional node order; a node whose normals cancel keeps the
    /// frame of `+z`.
    pub(super) fn node_frames(&self, mesh: &Mesh<3>, u: &[f64]) -> Vec<Frame> {
        let mut normals = vec![[0.0; 3]; self.friction.normal.len()];
        for pt in &self.points {
            if !self.friction.on_pair(pt.pair.index()) {
                continue;
            }
            let face = Self::current_face(mesh, u, &pt.slave);
            let Some(n) = unit(face.normal_at(pt.xi_s)) else {
                continue;
            };
            let shape = FaceShape::at(pt.slave.kind(), pt.xi_s);
            for a in 0..shape.count {
                if let Some(k) = self.friction.node_of[pt.multipliers[a].index()] {
                    for c in 0..3 {
                        normals[k][c] += pt.weight_ref * shape.n[a] * n[c];
                    }
                }
            }
        }
        normals
            .into_iter()
            .map(|n| frame_of(unit(n).unwrap_or([0.0, 0.0, 1.0])))
            .collect()
    }

    /// Point `i`'s slave nodes' frames out of `frames` (node order).
    fn point_frames(
        &self,
        i: ContactPointIndex,
        frames: &[Frame],
    ) -> [Frame; MAX_POINT_MULTIPLIERS] {
        let pt = self.point(i);
        std::array::from_fn(|a| {
            self.friction.node_of[pt.multipliers[a].index()].map_or([[0.0; 3]; 2], |k| frames[k])
        })
    }

    /// The anchors of the points paired as `at` (master face and `xi_m`)
    /// at the converged state `u`.
    pub(super) fn anchors_at(
        &self,
        mesh: &Mesh<3>,
        u: &[f64],
        at: impl Iterator<Item = Option<(MasterFaceIndex, [f64; 2])>>,
    ) -> Vec<Option<FaceAnchor>> {
        let frames = self.node_frames(mesh, u);
        at.enumerate()
            .map(|(k, at)| {
                let i = ContactPointIndex::new(k);
                let (master, xi_m) = at?;
                self.friction
                    .on_pair(self.point(i).pair.index())
                    .then(|| FaceAnchor {
                        master,
                        xi_m,
                        frames: self.point_frames(i, &frames),
                    })
            })
            .collect()
    }

    /// The slips of `points` (each point `i` evaluated as `e`, from its
    /// anchor) at displacements `u`, kernel type `ty`: one result per point,
    /// in order. The points of one formulation go through one
    /// `Slip::eval_batch` call (its lane kernels where the CPU has them),
    /// which gives each point the bits and the error of `Slip::eval`.
    pub(super) fn face_slips(
        &self,
        mesh: &Mesh<3>,
        u: &[f64],
        points: &[(ContactPointIndex, &FaceEval, &FaceAnchor)],
        ty: ApproxType,
        buffers: &mut FaceSlipBuffers,
    ) -> Vec<Result<Box<FaceSlip>, KernelError>> {
        let mut results: Vec<Option<Result<Box<FaceSlip>, KernelError>>> =
            (0..points.len()).map(|_| None).collect();
        for (k, &(i, e, anchor)) in points.iter().enumerate() {
            let probe = self.probe(i);
            let group = self
                .formulation_of(&probe, e.master)
                .and_then(|f| buffers.group(f, ty));
            let group = match group {
                Ok(g) => g,
                Err(error) => {
                    results[k] = Some(Err(error));
                    continue;
                }
            };
            let xi_m0 = if anchor.master == e.master {
                anchor.xi_m
            } else {
                self.face_anchor_on(mesh, &probe, anchor.master, anchor.xi_m, e.master)
            };
            let q = Self::q(mesh, u, &e.nodes[..e.node_count]);
            group.qs.extend_from_slice(&q[..3 * e.node_count]);
            group.xi_s.extend_from_slice(&probe.xi_s);
            group.xi_m0.extend_from_slice(&xi_m0);
            group.members.push(k);
        }
        for g in buffers.0.iter_mut().filter(|g| !g.members.is_empty()) {
            let shapes = g.slip.eval_batch(&g.qs, &g.xi_s, &g.xi_m0, &mut g.batch);
            for (p, &k) in g.members.iter().enumerate() {
                results[k] = Some(match shapes {
                    Ok(_) => slip_of(&g.batch, p, g.slip.kernel().coords()).map(|v| {
                        Box::new(FaceSlip {
                            frames: points[k].2.frames,
                            ..v
                        })
                    }),
                    Err(e) => Err(e),
                });
            }
            g.qs.clear();
            g.xi_s.clear();
            g.xi_m0.clear();
            g.members.clear();
        }
        results
            .into_iter()
            .map(|r| r.expect("every point is evaluated or refused"))
            .collect()
    }

    /// The anchor at `xi0` on master face `from` of probe `pt`'s pair, as
    /// parameters of master face `to` (module docs).
    pub(super) fn face_anchor_on(
        &self,
        mesh: &Mesh<3>,
        pt: &super::pairing::Probe,
        from: MasterFaceIndex,
        xi0: [f64; 2],
        to: MasterFaceIndex,
    ) -> [f64; 2] {
        let masters = self.masters_of(pt.pair);
        let reference = |f: MasterFaceIndex| masters[f.index()].map_nodes(|n| mesh.node_ref(n));
        let x0 = reference(from).point_and_tangents(xi0)[0];
        let face: Face<[f64; 3]> = reference(to);
        let mut xi = match face {
            Face::Tri3(_) => [1.0 / 3.0, 1.0 / 3.0],
            Face::Quad4(_) => [0.0, 0.0],
        };
        for _ in 0..20 {
            let [x, t1, t2] = face.point_and_tangents(xi);
            let r = [x0[0] - x[0], x0[1] - x[1], x0[2] - x[2]];
            let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
            let (a11, a12, a22) = (dot(t1, t1), dot(t1, t2), dot(t2, t2));
            let (b1, b2) = (dot(t1, r), dot(t2, r));
            let det = a11 * a22 - a12 * a12;
            if !(det.abs() > 0.0) {
                break;
            }
            let d = [(a22 * b1 - a12 * b2) / det, (a11 * b2 - a12 * b1) / det];
            xi = [xi[0] + d[0], xi[1] + d[1]];
            if d[0].abs() + d[1].abs() < 1e-14 {
                break;
            }
        }
        xi
    }
}

/// Point `p` of `batch` (`n` coordinates) as a [`FaceSlip`] on
/// [`FACE_COORDS`] coordinates (zero on padding), without its frames; its
/// error where it failed.
fn slip_of(batch: &SlipBatch, p: usize, n: usize) -> Result<FaceSlip, KernelError> {
    let v = batch.slip(p).map_err(|e| *e)?;
    let grad = |c: usize| -> Result<SVector<f64, FACE_COORDS>, KernelError> {
        let g = batch.grad(p, c).map_err(|e| *e)?;
        Ok(SVector::from_fn(|k, _| if k < n { g[k] } else { 0.0 }))
    };
    let hess = |c: usize| -> Result<Option<SMatrix<f64, FACE_COORDS, FACE_COORDS>>, KernelError> {
        Ok(batch
            .hess(p, c)
            .map_err(|e| *e)?
            .map(|h| SMatrix::from_fn(|r, s| if r < n && s < n { h[r * n + s] } else { 0.0 })))
    };
    let hessians = match (hess(0)?, hess(1)?, hess(2)?) {
        (Some(a), Some(b), Some(c)) => Some([a, b, c]),
        _ => None,
    };
    Ok(FaceSlip {
        slip: [v[0], v[1], v[2]],
        grad: [grad(0)?, grad(1)?, grad(2)?],
        hess: hessians,
        frames: [[[0.0; 3]; 2]; MAX_POINT_MULTIPLIERS],
    })
}
