//! The nodal contact table of a 3D state: one row per slave node (per
//! multiplier), what the 3D `contact.csv` is written from
//! (`crate::report::ContactTable` for `Dim<3>`, header
//! `pair,node,x,y,z,gap,pressure,xi_m_u,xi_m_v,master_face,master_node_1,...,master_node_4,tributary_area,node_numbering,master_numbering,clamped,...`: the friction columns follow).
//!
//! - `pressure`: `p = -lambda` of the node's multiplier;
//! - `gap`, `xi_m_u`, `xi_m_v`, `master_face` and its nodes: the node
//!   taken as a point of its **first adjacent slave face** (the first face
//!   of the pair's slave list that has it, at that face's corner
//!   coordinates) and paired as an integration point is
//!   ([`super::face_pairing`]: the master face it projects into, facing,
//!   with the smallest `|g|`); a node that projects into no master face
//!   has no gap (`None`), never NaN;
//! - `tributary_area`: `sum w J0 N_a` over the node's integration points
//!   (whether paired or not: the slave area the node stands for).
//!
//! Invariants: rows pair by pair, in multiplier order (each pair's slave
//! nodes in the order they first appear on its faces); every number is
//! finite.

use thiserror::Error;

use crate::ids::{MasterFaceIndex, NodeId, PairId};
use crate::mesh::Mesh;
use crate::mesh::face_shape::{FaceShape, QUAD4_CORNERS};
use crate::mesh::volume::Face;

use super::pairing::Probe;
use crate::contact::term::WeightedPoint;
use crate::contact::{FaceLayout, KernelCounts, MultiplierDof};

/// One slave node's row (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct FaceNodalRow {
    /// The pair.
    pub pair: PairId,
    /// The slave node.
    pub node: NodeId,
    /// Its current coordinates.
    pub x: [f64; 3],
    /// The gap at the node (`None`: it projects into no master face).
    pub gap: Option<f64>,
    /// `-lambda` of its multiplier.
    pub pressure: f64,
    /// The projection on the master face.
    pub xi_m: Option<[f64; 2]>,
    /// The master face, with its nodes.
    pub master: Option<(MasterFaceIndex, Face<NodeId>)>,
    /// `sum w J0 N_a` over the node's integration points.
    pub tributary_area: f64,
}

/// A slave-side kernel failure at a node of the table.
#[derive(Debug, Clone, PartialEq, Error)]
#[error("contact pair {pair}, slave node {node}: {error}")]
pub struct FaceNodalError {
    /// The pair.
    pub pair: usize,
    /// The node.
    pub node: usize,
    /// The kernel's error.
    pub error: contact_kernels::KernelError,
}

/// The parametric coordinates of corner `k` of a face of `kind`'s shape.
fn corner(face: &Face<NodeId>, k: usize) -> [f64; 2] {
    match face {
        Face::Tri3(_) => [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]][k],
        Face::Quad4(_) => QUAD4_CORNERS[k],
    }
}

impl FaceLayout {
    /// The slave node of multiplier `dof` as a point: at its corner of the
    /// first slave face of its pair that has it (`None`: no face has it).
    pub(super) fn corner_probe(&self, dof: &MultiplierDof) -> Option<Probe> {
        self.slaves[dof.pair.index()].iter().find_map(|f| {
            f.nodes()
                .iter()
                .position(|&n| n == dof.node)
                .map(|k| Probe {
                    pair: dof.pair,
                    slave: *f,
                    xi_s: corner(f, k),
                })
        })
    }

    /// The nodal table (module docs) at displacements `u` and multipliers
    /// `lambda`, with the projection calls made.
    pub fn nodal_table(
        &self,
        mesh: &Mesh<3>,
        u: &[f64],
        lambda: &[f64],
    ) -> Result<(Vec<FaceNodalRow>, KernelCounts), FaceNodalError> {
        let mut tributary = vec![0.0; self.multipliers.len()];
        for pt in &self.points {
            let w = pt.weight_ref();
            // the slave face's shape functions, whatever the multiplier
            // basis (docs/conventions.md: `sum w J0 N_a`)
            let s = FaceShape::at(pt.slave.kind(), pt.xi_s);
            for a in 0..s.count {
                tributary[pt.multipliers[a].index()] += w * s.n[a];
            }
        }
        let indexes = self.master_indexes(mesh, u);
        let mut counts = KernelCounts::default();
        let mut rows = Vec::with_capacity(self.multipliers.len());
        for (m, dof) in self.multipliers.iter().enumerate() {
            let probe = self.corner_probe(dof);
            let found = match &probe {
                Some(p) => self
                    .find_master(mesh, u, p, &indexes, &mut counts, true)
                    .map_err(|(_, error)| FaceNodalError {
                        pair: dof.pair.index(),
                        node: dof.node.index(),
                        error,
                    })?,
                None => None,
            };
            rows.push(FaceNodalRow {
                pair: dof.pair,
                node: dof.node,
                x: Self::current(mesh, u, dof.node),
                gap: found.map(|(_, g, _)| g),
                pressure: -lambda[m],
                xi_m: found.map(|(_, _, xi)| xi),
                master: found.map(|(f, _, _)| (f, self.masters_of(dof.pair)[f.index()])),
                tributary_area: tributary[m],
            });
        }
        Ok((rows, counts))
    }
}
