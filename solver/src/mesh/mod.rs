//! Meshes in `D = 2` or `3` dimensions, made of several bodies that share
//! no nodes: of 4-node quadrilaterals and 3-node triangles (mixed freely)
//! in 2D ([`Mesh`], `D = 2` by default), of 8-node hexahedra and 4-node
//! tetrahedra (mixed freely) in 3D (`Mesh<3>`). One type and one code path
//! for both; a body's elements must be of the mesh's dimension
//! ([`MeshError::WrongDimension`]).
//!
//! Node `n` ([`NodeId`]) has reference coordinates `nodes_ref[n]` (`D`
//! numbers) and the displacement degrees of freedom `D n + c`, `c` the
//! component (0: x, 1: y, 2: z; [`crate::ids::DofId::in_dim`]); element
//! `e` ([`ElementId`]) has the connectivity `elements[e]` (an [`Element`]:
//! its kind and its nodes, counter-clockwise in 2D, in Gmsh's order in 3D)
//! and the geometry `geometry[e]` (an
//! [`ElementGeometry`]; the element kinds and their dispatch are in
//! [`crate::element`]). Each body owns a contiguous range of nodes and of
//! elements.
//!
//! The [`Mesh`] owns what every body has, however it was made: nodes,
//! connectivity, the body ranges and the selection of nodes by reference
//! coordinates; the element geometry is computed from them when it is
//! asked for ([`Mesh::geometry`]; a solve keeps the geometry of the
//! elements it assembles, [`Geometries`]). Bodies are appended one at a
//! time, each with fresh nodes ([`Mesh::add_body`] checks the connectivity
//! and that every element's reference Jacobian is positive, naming the
//! element and its kind otherwise), so that
//!
//! * bodies share no nodes, and a body's nodes and elements are contiguous;
//! * node and element numbers are those of the order in which bodies were
//!   appended, then the body-local order of the generator.
//!
//! Body generators live next to this file: [`block`] (structured blocks
//! of either dimension, [`Mesh::add_block`], with their sides as the
//! dimension's outward facets: counter-clockwise segment chains in 2D,
//! quad4 faces in 3D). A reader of an unstructured mesh file is another
//! generator that ends in [`Mesh::add_body`].
//!
//! The 3D readers and what they share: volume cells and their outward
//! faces ([`volume`]; a [`volume::Cell`] converts into an [`Element`]),
//! boundary-face extraction ([`faces`]) and the 3D Gmsh reader
//! ([`gmsh::MshVolumeMesh`]); their cells go into a `Mesh<3>` through
//! [`Mesh::add_body`].
//!
//! The dimension as a type, [`Dim<D>`], is defined here: what differs
//! between the dimensions beyond the sizes `D` fixes is a trait
//! implemented for `Dim<2>` and `Dim<3>` ([`block::BlockDim`] here, the
//! contact facet `crate::model::SurfaceDim` and the layers above).

use std::ops::Range;

use crate::element::MAX_ELEMENT_DOFS;
pub use crate::element::{Element, ElementGeometry, ElementKind};
use crate::element::{ElementError, InvalidElement};
use crate::ids::{DofId, ElementId, NodeId};
use crate::material::Material;

pub mod block;
pub mod coincident;
pub mod face_shape;
pub mod faces;
mod geometries;
pub mod gmsh;
mod grid;
pub mod inversion;
pub mod volume;

pub use block::{Block, BlockDim, BlockError, Side};
pub use geometries::Geometries;
pub use inversion::InvertedElement;

/// The spatial dimension `D` as a type (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Dim<const D: usize>;

/// One body of a mesh of `D` dimensions.
#[derive(Debug, Clone, PartialEq)]
pub struct Body<const D: usize = 2> {
    /// The body's name (unique in the mesh).
    pub name: String,
    /// Its material.
    pub material: Material,
    /// Its nodes (raw [`NodeId`] indices; see [`Body::node_ids`]).
    pub nodes: Range<usize>,
    /// Its elements (raw [`ElementId`] indices).
    pub elements: Range<usize>,
    /// The block it was generated from ([`Mesh::add_block`]), if any.
    pub block: Option<Block<D>>,
    /// The mesh file's node tag of each of its nodes (in body order), for
    /// a body read from a mesh file; `None` for a generated body, whose
    /// nodes have only their internal numbers (see [`Mesh::node_number`]).
    pub node_tags: Option<Vec<u64>>,
}

/// How a node is numbered in the output ([`Mesh::node_number`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NodeNumbering {
    /// The node tag of the mesh file the node's body was read from.
    MeshFile,
    /// The internal 0-based index (a generated body, e.g. a block).
    Internal,
}

impl NodeNumbering {
    /// `msh` or `internal`, as `contact.csv` writes it.
    pub fn as_str(self) -> &'static str {
        match self {
            NodeNumbering::MeshFile => "msh",
            NodeNumbering::Internal => "internal",
        }
    }
}

impl<const D: usize> Body<D> {
    /// Its nodes, in increasing order.
    pub fn node_ids(&self) -> impl Iterator<Item = NodeId> + use<D> {
        self.nodes.clone().map(NodeId::new)
    }

    /// Whether `node` is one of its nodes.
    pub fn has_node(&self, node: NodeId) -> bool {
        self.nodes.contains(&node.index())
    }
}

/// Why a mesh could not be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MeshError {
    /// A block that cannot be generated ([`Block::check`]).
    #[error("block of body `{body}`: {error}")]
    Block {
        /// The body.
        body: String,
        /// Why.
        error: BlockError,
    },
    /// An element's reference Jacobian is not positive (or, for a
    /// triangle, its area is at the level of rounding).
    #[error(
        "element {element} ({kind}) of body `{body}` is inverted or degenerate (detJ0 = {det_j0:e}); nodes must run counter-clockwise"
    )]
    InvalidElement {
        /// The body.
        body: String,
        /// Global element index.
        element: usize,
        /// Its kind.
        kind: ElementKind,
        /// The smallest reference Jacobian determinant.
        det_j0: f64,
    },
    /// An element refers to a node outside its body.
    #[error(
        "element {element} of body `{body}` refers to node {node}, which the body does not have"
    )]
    BadConnectivity {
        /// The body.
        body: String,
        /// Element index within the body.
        element: usize,
        /// The offending (body-local) node index.
        node: usize,
    },
    /// A non-finite coordinate.
    #[error("body `{body}` has a non-finite node coordinate")]
    NonFinite {
        /// The body.
        body: String,
    },
    /// An element of another dimension than the mesh (a 2D element in a
    /// 3D mesh or the reverse).
    #[error(
        "element {element} of body `{body}` is a {kind} ({}D), the mesh is {dim}D",
        kind.dim()
    )]
    WrongDimension {
        /// The body.
        body: String,
        /// Element index within the body.
        element: usize,
        /// Its kind.
        kind: ElementKind,
        /// The mesh's dimension.
        dim: usize,
    },
}

/// Nodes, elements and bodies in `D` dimensions (2 by default). Every
/// element's reference geometry is checked when its body is added and not
/// kept: a solve computes the geometry of the elements it assembles
/// ([`Geometries`]), any other is [`Mesh::geometry`].
#[derive(Debug, Clone)]
pub struct Mesh<const D: usize = 2> {
    /// Reference coordinates of all nodes (indexed by [`NodeId`]).
    pub nodes_ref: Vec<[f64; D]>,
    /// Element connectivity (counter-clockwise in 2D, Gmsh's order in 3D;
    /// indexed by [`ElementId`]).
    pub elements: Vec<Element>,
    /// The body of each element.
    pub element_body: Vec<usize>,
    /// The bodies.
    pub bodies: Vec<Body<D>>,
}

impl<const D: usize> Default for Mesh<D> {
    fn default() -> Self {
        Mesh::EMPTY
    }
}

impl<const D: usize> Mesh<D> {
    /// The mesh without nodes, elements or bodies.
    pub const EMPTY: Mesh<D> = Mesh {
        nodes_ref: Vec::new(),
        elements: Vec::new(),
        element_body: Vec::new(),
        bodies: Vec::new(),
    };

    /// An empty mesh.
    pub fn new() -> Mesh<D> {
        Mesh::EMPTY
    }

    /// Appends a body from explicit nodes (`D` coordinates each) and
    /// body-local connectivity: in 2D quadrilaterals (`[usize; 4]`),
    /// triangles (`[usize; 3]`) or a mix ([`Element<usize>`]),
    /// counter-clockwise; in 3D hexahedra (`[usize; 8]`), tetrahedra
    /// ([`Element::Tet4`]) or a mix (elements, or the
    /// [`volume::Cell`]s of a 3D generator or reader), in Gmsh's order. An
    /// element of the other dimension is [`MeshError::WrongDimension`].
    /// Returns the body's index.
    pub fn add_body<E: Copy + Into<Element<usize>>>(
        &mut self,
        name: &str,
        material: Material,
        nodes_ref: &[[f64; D]],
        elements: &[E],
    ) -> Result<usize, MeshError> {
        self.push_body(name, material, nodes_ref, elements, None)
    }

    fn push_body<E: Copy + Into<Element<usize>>>(
        &mut self,
        name: &str,
        material: Material,
        nodes_ref: &[[f64; D]],
        elements: &[E],
        block: Option<Block<D>>,
    ) -> Result<usize, MeshError> {
        if nodes_ref.iter().flatten().any(|v| !v.is_finite()) {
            return Err(MeshError::NonFinite {
                body: name.to_owned(),
            });
        }
        let node0 = self.nodes_ref.len();
        let elem0 = self.elements.len();
        let body = self.bodies.len();
        let mut conn = Vec::with_capacity(elements.len());
        for (e, &el) in elements.iter().enumerate() {
            let el: Element<usize> = el.into();
            if let Some(&node) = el.iter().find(|&&n| n >= nodes_ref.len()) {
                return Err(MeshError::BadConnectivity {
                    body: name.to_owned(),
                    element: e,
                    node,
                });
            }
            checked_geometry(name, (elem0 + e, e), &el.map_nodes(|n| nodes_ref[n]))?;
            conn.push(el.map_nodes(|n| NodeId::new(n + node0)));
        }
        self.nodes_ref.extend_from_slice(nodes_ref);
        self.elements.extend(conn);
        self.element_body
            .extend(std::iter::repeat_n(body, elements.len()));
        self.bodies.push(Body {
            name: name.to_owned(),
            material,
            nodes: node0..node0 + nodes_ref.len(),
            elements: elem0..elem0 + elements.len(),
            block,
            node_tags: None,
        });
        Ok(body)
    }

    /// The number the output gives node `node`: its mesh file's tag when
    /// its body was read from a file ([`Body::node_tags`]), else its
    /// internal 0-based index; and which of the two it is.
    pub fn node_number(&self, node: usize) -> (u64, NodeNumbering) {
        let tag = self.bodies.iter().find_map(|b| {
            let tags = b.node_tags.as_ref()?;
            b.nodes
                .contains(&node)
                .then(|| tags.get(node - b.nodes.start).copied())
                .flatten()
        });
        match tag {
            Some(t) => (t, NodeNumbering::MeshFile),
            None => (node as u64, NodeNumbering::Internal),
        }
    }

    /// Number of nodes.
    pub fn node_count(&self) -> usize {
        self.nodes_ref.len()
    }

    /// All nodes, in increasing order.
    pub fn node_ids(&self) -> impl Iterator<Item = NodeId> + use<D> {
        (0..self.nodes_ref.len()).map(NodeId::new)
    }

    /// The reference coordinates of `node`.
    #[inline]
    pub fn node_ref(&self, node: NodeId) -> [f64; D] {
        self.nodes_ref[node.index()]
    }

    /// Number of elements.
    pub fn element_count(&self) -> usize {
        self.elements.len()
    }

    /// All elements, in increasing order.
    pub fn element_ids(&self) -> impl Iterator<Item = ElementId> + use<D> {
        (0..self.elements.len()).map(ElementId::new)
    }

    /// The connectivity of element `e` (its kind and its nodes,
    /// counter-clockwise).
    #[inline]
    pub fn element(&self, e: ElementId) -> &Element {
        &self.elements[e.index()]
    }

    /// The index of the body called `name`.
    pub fn body_index(&self, name: &str) -> Option<usize> {
        self.bodies.iter().position(|b| b.name == name)
    }

    /// The length of the diagonal of the bounding box of all nodes (a
    /// length scale for tolerances): the extents along the `D` axes
    /// combined by `hypot`, axis after axis.
    pub fn size(&self) -> f64 {
        let mut lo = [f64::INFINITY; D];
        let mut hi = [f64::NEG_INFINITY; D];
        for p in &self.nodes_ref {
            for c in 0..D {
                lo[c] = lo[c].min(p[c]);
                hi[c] = hi[c].max(p[c]);
            }
        }
        if self.nodes_ref.is_empty() {
            0.0
        } else {
            length(&std::array::from_fn::<f64, D, _>(|c| hi[c] - lo[c]))
        }
    }

    /// The tolerance used when nodes are selected by coordinates.
    pub fn coordinate_tolerance(&self) -> f64 {
        1e-9 * self.size().max(1e-300)
    }

    /// Nodes (optionally only of `body`) whose reference `x` and `y` match
    /// the given ones within [`Mesh::coordinate_tolerance`] (any `z` in
    /// 3D; [`Mesh::select_nodes_at`] with `z` free).
    pub fn select_nodes(&self, body: Option<usize>, x: Option<f64>, y: Option<f64>) -> Vec<NodeId> {
        self.select_nodes_at(body, &[x, y])
    }

    /// Nodes (optionally only of `body`) whose reference coordinates match
    /// every given one within [`Mesh::coordinate_tolerance`]: `at[c]` is
    /// coordinate `c` (x, y, z), `None` or missing (`at` shorter than `D`)
    /// matches any; entries beyond `D` must be `None` (a `z` in a 2D mesh
    /// matches no node).
    pub fn select_nodes_at(&self, body: Option<usize>, at: &[Option<f64>]) -> Vec<NodeId> {
        let tol = self.coordinate_tolerance();
        let range = match body {
            Some(b) => self.bodies[b].nodes.clone(),
            None => 0..self.nodes_ref.len(),
        };
        if at.iter().skip(D).any(Option::is_some) {
            return Vec::new();
        }
        range
            .filter(|&n| {
                let p = self.nodes_ref[n];
                at.iter()
                    .zip(&p)
                    .all(|(c, &v)| c.is_none_or(|c| (v - c).abs() <= tol))
            })
            .map(NodeId::new)
            .collect()
    }

    /// The element displacement vector `[u1x, u1y, (u1z,) u2x, ...]` of
    /// element `e` from the global displacement vector: `D n` values for
    /// its `n` nodes, then zeros (a triangle fills 6 of the
    /// [`MAX_ELEMENT_DOFS`] entries, a quadrilateral 8, a tetrahedron 12).
    pub fn element_displacements(&self, e: ElementId, u: &[f64]) -> [f64; MAX_ELEMENT_DOFS] {
        let el = self.element(e);
        let n = D * el.len();
        std::array::from_fn(|k| {
            if k < n {
                u[DofId::in_dim::<D>(el[k / D], k % D).index()]
            } else {
                0.0
            }
        })
    }

    /// The reference geometry of element `e`, computed from its nodes'
    /// reference coordinates (the check [`Mesh::add_body`] made: it fails
    /// only if the nodes were moved since).
    pub fn geometry(&self, e: ElementId) -> Result<ElementGeometry, MeshError> {
        let body = &self.bodies[self.element_body[e.index()]];
        checked_geometry(
            &body.name,
            (e.index(), e.index() - body.elements.start),
            &self.element(e).map_nodes(|n| self.nodes_ref[n.index()]),
        )
    }
}

/// The reference geometry of an element of body `body` with node
/// coordinates `x` (`element`: its global index and its index within the
/// body), every failure as the mesh's error: the one check of an element's
/// reference geometry, when its body is added and when it is computed
/// again ([`Mesh::geometry`]).
fn checked_geometry<const D: usize>(
    body: &str,
    (element, local): (usize, usize),
    x: &Element<[f64; D]>,
) -> Result<ElementGeometry, MeshError> {
    ElementGeometry::new(x).map_err(|err| match err {
        ElementError::Invalid(InvalidElement { det_j0 }) => MeshError::InvalidElement {
            body: body.to_owned(),
            element,
            kind: x.kind(),
            det_j0,
        },
        ElementError::WrongDimension { kind, dim } => MeshError::WrongDimension {
            body: body.to_owned(),
            element: local,
            kind,
            dim,
        },
    })
}

/// The Euclidean length of `d`, by `hypot` axis after axis (in 2D the bits
/// of `d[0].hypot(d[1])`).
pub fn length<const D: usize>(d: &[f64; D]) -> f64 {
    // 0.hypot(a) is |a| and hypot ignores signs: in 2D a.hypot(b) exactly
    d.iter().fold(0.0, |l: f64, &c| l.hypot(c))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::PlaneModel;

    /// The mesh tests' material.
    pub(in crate::mesh) const MAT: Material = Material {
        young: 1.0,
        poisson: 0.0,
        model: PlaneModel::PlaneStress,
        kinematics: crate::material::Kinematics::Finite,
    };

    #[test]
    fn clockwise_elements_are_rejected() {
        let mut m = Mesh::new();
        let err = m
            .add_body(
                "c",
                MAT,
                &[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
                &[[0, 3, 2, 1]],
            )
            .unwrap_err();
        assert!(matches!(err, MeshError::InvalidElement { .. }));
    }
}
