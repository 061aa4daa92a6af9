//! The solid-element seam: the element kinds a mesh holds (the 4-node
//! quadrilateral of [`crate::quad`] and the 3-node triangle of
//! [`crate::tri`]), their connectivity, their reference geometry and their
//! response, so that the mesh, the assembly, the stresses and the output
//! dispatch through one place instead of branching on the kind everywhere.
//!
//! Both elements are total-Lagrangian St Venant–Kirchhoff elements with the
//! same point kinematics (`kinematics.rs`); they differ in their shape
//! functions and integration rule only (Q4: bilinear, 2x2 Gauss; T3:
//! linear, one point, exact). An element with `n` nodes has `2n` dofs,
//! ordered `[u1x, u1y, u2x, u2y, ...]`; element buffers are sized for the
//! largest element (8 dofs) and a triangle uses their first 6 entries.
//!
//! Invariants: an [`Element`]'s nodes run counter-clockwise; an
//! [`ElementGeometry`] exists only for a positive reference Jacobian (see
//! [`QuadGeometry::new`], [`TriGeometry::new`]); dispatching a quadrilateral
//! through this seam performs exactly the operations of
//! [`quad_response`], [`quad_energy`] and [`quad_mean_stress`], so a mesh of
//! quadrilaterals gives the same bits as before triangles existed.

use std::fmt;
use std::ops::Deref;

use crate::ids::NodeId;
use crate::material::Material;
use crate::quad::{
    InvalidElement, QuadGeometry, QuadResponse, QuadStress, quad_energy, quad_mean_stress,
    quad_point_stresses, quad_response,
};
use crate::report::{VTK_QUAD, VTK_TRIANGLE};
use crate::tri::{
    TriGeometry, TriResponse, tri_energy, tri_mean_stress, tri_point_stresses, tri_response,
};

/// The largest number of dofs of an element (the quadrilateral's 8).
pub const MAX_ELEMENT_DOFS: usize = 8;

/// The kind of a solid element.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ElementKind {
    /// The 4-node bilinear quadrilateral ([`crate::quad`]).
    Quad4,
    /// The 3-node linear triangle ([`crate::tri`]).
    Tri3,
}

impl ElementKind {
    /// Nodes per element.
    pub fn node_count(self) -> usize {
        match self {
            ElementKind::Quad4 => 4,
            ElementKind::Tri3 => 3,
        }
    }

    /// The VTK cell type ([`VTK_QUAD`] = 9, [`VTK_TRIANGLE`] = 5).
    pub fn vtk_cell_type(self) -> u8 {
        match self {
            ElementKind::Quad4 => VTK_QUAD,
            ElementKind::Tri3 => VTK_TRIANGLE,
        }
    }
}

impl fmt::Display for ElementKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            ElementKind::Quad4 => "4-node quadrilateral",
            ElementKind::Tri3 => "3-node triangle",
        })
    }
}

/// The connectivity of one element: its nodes, counter-clockwise. `N` is
/// the node index: [`NodeId`] in a [`crate::mesh::Mesh`], a body-local
/// `usize` when a body is added. Dereferences to the slice of its nodes.
/// Its `Debug` is the node list alone (the kind is its length), as the
/// plain `[NodeId; 4]` of a quadrilateral mesh printed before.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub enum Element<N = NodeId> {
    /// A 4-node quadrilateral.
    Quad4([N; 4]),
    /// A 3-node triangle.
    Tri3([N; 3]),
}

impl<N> Element<N> {
    /// Its kind.
    pub fn kind(&self) -> ElementKind {
        match self {
            Element::Quad4(_) => ElementKind::Quad4,
            Element::Tri3(_) => ElementKind::Tri3,
        }
    }

    /// Its nodes, counter-clockwise.
    pub fn nodes(&self) -> &[N] {
        match self {
            Element::Quad4(n) => n,
            Element::Tri3(n) => n,
        }
    }

    /// The same element with every node mapped by `f`.
    pub fn map_nodes<M>(self, f: impl FnMut(N) -> M) -> Element<M> {
        match self {
            Element::Quad4(n) => Element::Quad4(n.map(f)),
            Element::Tri3(n) => Element::Tri3(n.map(f)),
        }
    }
}

impl<N: fmt::Debug> fmt::Debug for Element<N> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(self.nodes(), f)
    }
}

impl<N> Deref for Element<N> {
    type Target = [N];
    fn deref(&self) -> &[N] {
        self.nodes()
    }
}

impl<'a, N> IntoIterator for &'a Element<N> {
    type Item = &'a N;
    type IntoIter = std::slice::Iter<'a, N>;
    fn into_iter(self) -> Self::IntoIter {
        self.nodes().iter()
    }
}

impl<N> From<[N; 4]> for Element<N> {
    fn from(nodes: [N; 4]) -> Self {
        Element::Quad4(nodes)
    }
}

impl<N> From<[N; 3]> for Element<N> {
    fn from(nodes: [N; 3]) -> Self {
        Element::Tri3(nodes)
    }
}

/// The reference geometry of one element, computed once per mesh. Its
/// `Debug` is the element's own (`QuadGeometry { .. }`, `TriGeometry { ..
/// }`), which names the kind.
///
/// The variants differ in size (a triangle's is smaller); they stay
/// unboxed: geometries live in one dense vector indexed by element, read
/// in every iteration, and a box per element would cost an indirection
/// for every quadrilateral.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Copy, PartialEq)]
pub enum ElementGeometry {
    /// A quadrilateral's (per Gauss point).
    Quad4(QuadGeometry),
    /// A triangle's (constant).
    Tri3(TriGeometry),
}

impl fmt::Debug for ElementGeometry {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ElementGeometry::Quad4(g) => fmt::Debug::fmt(g, f),
            ElementGeometry::Tri3(g) => fmt::Debug::fmt(g, f),
        }
    }
}

impl ElementGeometry {
    /// The geometry of the element whose reference node coordinates are
    /// `x_ref` (counter-clockwise); fails for a non-positive (or, for a
    /// triangle, degenerate or non-finite) reference Jacobian.
    pub fn new(x_ref: &Element<[f64; 2]>) -> Result<ElementGeometry, InvalidElement> {
        Ok(match x_ref {
            Element::Quad4(x) => ElementGeometry::Quad4(QuadGeometry::new(x)?),
            Element::Tri3(x) => ElementGeometry::Tri3(TriGeometry::new(x)?),
        })
    }

    /// Its kind.
    pub fn kind(&self) -> ElementKind {
        match self {
            ElementGeometry::Quad4(_) => ElementKind::Quad4,
            ElementGeometry::Tri3(_) => ElementKind::Tri3,
        }
    }

    /// The reference area.
    pub fn area_ref(&self) -> f64 {
        match self {
            ElementGeometry::Quad4(g) => g.area_ref(),
            ElementGeometry::Tri3(g) => g.area_ref(),
        }
    }

    /// Internal force, tangent and energy at the element displacements `u`
    /// (the first `2 n` entries are used).
    pub fn response(&self, u: &[f64; MAX_ELEMENT_DOFS], material: &Material) -> ElementResponse {
        match self {
            ElementGeometry::Quad4(g) => ElementResponse::Quad4(quad_response(g, u, material)),
            ElementGeometry::Tri3(g) => {
                ElementResponse::Tri3(tri_response(g, &tri_dofs(u), material))
            }
        }
    }

    /// The strain energy at the element displacements `u`.
    pub fn energy(&self, u: &[f64; MAX_ELEMENT_DOFS], material: &Material) -> f64 {
        match self {
            ElementGeometry::Quad4(g) => quad_energy(g, u, material),
            ElementGeometry::Tri3(g) => tri_energy(g, &tri_dofs(u), material),
        }
    }

    /// The stresses at each of its integration points (four for a
    /// quadrilateral, one for a triangle).
    pub fn point_stresses(
        &self,
        u: &[f64; MAX_ELEMENT_DOFS],
        material: &Material,
    ) -> Vec<QuadStress> {
        match self {
            ElementGeometry::Quad4(g) => quad_point_stresses(g, u, material).to_vec(),
            ElementGeometry::Tri3(g) => tri_point_stresses(g, &tri_dofs(u), material).to_vec(),
        }
    }

    /// The element's stresses averaged over its integration points.
    pub fn mean_stress(&self, u: &[f64; MAX_ELEMENT_DOFS], material: &Material) -> QuadStress {
        match self {
            ElementGeometry::Quad4(g) => quad_mean_stress(g, u, material),
            ElementGeometry::Tri3(g) => tri_mean_stress(g, &tri_dofs(u), material),
        }
    }
}

/// The triangle's 6 dofs of an element buffer.
fn tri_dofs(u: &[f64; MAX_ELEMENT_DOFS]) -> [f64; 6] {
    std::array::from_fn(|k| u[k])
}

/// What one element contributes: internal force, tangent and energy.
/// Unboxed (see [`ElementGeometry`]): responses are computed per element
/// and iteration, and boxing would add an allocation to each.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ElementResponse {
    /// A quadrilateral's.
    Quad4(QuadResponse),
    /// A triangle's.
    Tri3(TriResponse),
}

impl ElementResponse {
    /// `f_int` (`2 n` entries, in the element's dof order).
    pub fn f_int(&self) -> &[f64] {
        match self {
            ElementResponse::Quad4(r) => &r.f_int,
            ElementResponse::Tri3(r) => &r.f_int,
        }
    }

    /// Row `p` of the tangent `d f_int / d u` (`2 n` entries).
    pub fn k_row(&self, p: usize) -> &[f64] {
        match self {
            ElementResponse::Quad4(r) => &r.k[p],
            ElementResponse::Tri3(r) => &r.k[p],
        }
    }

    /// The strain energy.
    pub fn energy(&self) -> f64 {
        match self {
            ElementResponse::Quad4(r) => r.energy,
            ElementResponse::Tri3(r) => r.energy,
        }
    }
}

#[cfg(test)]
mod tests;
