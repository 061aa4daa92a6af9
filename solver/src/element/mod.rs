//! The solid elements and their seam: the element kinds a mesh holds (the
//! 4-node quadrilateral of [`quad`] and the 3-node triangle of [`tri`]),
//! their connectivity, their reference geometry and their response, so that
//! the mesh, the assembly, the stresses and the output dispatch through one
//! place instead of branching on the kind everywhere. Each kind owns its
//! VTK cell type ([`ElementKind::vtk_cell_type`]).
//!
//! Every element is a total-Lagrangian St Venant–Kirchhoff element with
//! the same point kinematics ([`kinematics`], over the dimension `D`) and
//! one integrand ([`solid`]: `B^T D B`, the geometric stiffness, the energy
//! and the stresses, written once); they differ in their shape functions
//! and integration rule only (Q4: bilinear, 2x2 Gauss; T3: linear, one
//! point, exact; in 3D H8 ([`hex`]): trilinear, 2x2x2 Gauss; T4 ([`tet`]):
//! linear, one point, exact). The material is [`material`], the stress
//! measures [`Stress`]. Every element type implements [`SolidElement`],
//! one interface for 2D and 3D; the mesh holds 2D elements, and the 3D
//! ones ([`ElementKind::Hex8`], [`ElementKind::Tet4`]) join [`Element`],
//! [`ElementGeometry`] and [`ElementResponse`] as variants calling their
//! [`SolidElement`] methods once the mesh has three coordinates.
//! A 2D element with `n` nodes has `2n` dofs, ordered
//! `[u1x, u1y, u2x, u2y, ...]`; the seam's element buffers are sized for
//! the largest 2D element (8 dofs) and a triangle uses their first 6
//! entries.
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

pub mod hex;
pub mod kinematics;
pub mod material;
pub mod quad;
pub mod solid;
mod stress;
pub mod tet;
pub mod tri;

use material::Material;
use quad::{
    QuadGeometry, QuadResponse, quad_energy, quad_mean_stress, quad_point_stresses, quad_response,
};
use solid::SolidResponse;
pub use stress::Stress;
use tri::{
    TriGeometry, TriResponse, tri_energy, tri_mean_stress, tri_point_stresses, tri_response,
};

/// VTK cell type of a 4-node quadrilateral.
pub const VTK_QUAD: u8 = 9;

/// VTK cell type of a 3-node triangle.
pub const VTK_TRIANGLE: u8 = 5;

/// VTK cell type of an 8-node hexahedron.
pub const VTK_HEXAHEDRON: u8 = 12;

/// VTK cell type of a 4-node tetrahedron.
pub const VTK_TETRA: u8 = 10;

/// A reference element whose Jacobian is not positive somewhere (inverted,
/// degenerate, badly distorted, or with a non-finite coordinate).
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[error(
    "the reference Jacobian determinant is {det_j0:e}, not positive (an inverted, degenerate or non-finite element)"
)]
pub struct InvalidElement {
    /// The smallest `detJ0` over the element's integration points (NaN
    /// for a non-finite coordinate).
    pub det_j0: f64,
}

/// The largest number of dofs of a 2D element (the quadrilateral's 8): the
/// size of the seam's element buffers.
pub const MAX_ELEMENT_DOFS: usize = 8;

/// The kind of a solid element.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ElementKind {
    /// The 4-node bilinear quadrilateral ([`quad`]).
    Quad4,
    /// The 3-node linear triangle ([`tri`]).
    Tri3,
    /// The 8-node trilinear hexahedron ([`hex`]).
    Hex8,
    /// The 4-node linear tetrahedron ([`tet`]).
    Tet4,
}

impl ElementKind {
    /// Nodes per element.
    pub fn node_count(self) -> usize {
        match self {
            ElementKind::Quad4 => 4,
            ElementKind::Tri3 => 3,
            ElementKind::Hex8 => 8,
            ElementKind::Tet4 => 4,
        }
    }

    /// The spatial dimension (2 or 3): each node has this many dofs.
    pub fn dim(self) -> usize {
        match self {
            ElementKind::Quad4 | ElementKind::Tri3 => 2,
            ElementKind::Hex8 | ElementKind::Tet4 => 3,
        }
    }

    /// The VTK cell type ([`VTK_QUAD`] = 9, [`VTK_TRIANGLE`] = 5,
    /// [`VTK_HEXAHEDRON`] = 12, [`VTK_TETRA`] = 10; VTK's node orders are
    /// Gmsh's for all four).
    pub fn vtk_cell_type(self) -> u8 {
        match self {
            ElementKind::Quad4 => VTK_QUAD,
            ElementKind::Tri3 => VTK_TRIANGLE,
            ElementKind::Hex8 => VTK_HEXAHEDRON,
            ElementKind::Tet4 => VTK_TETRA,
        }
    }
}

impl fmt::Display for ElementKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            ElementKind::Quad4 => "4-node quadrilateral",
            ElementKind::Tri3 => "3-node triangle",
            ElementKind::Hex8 => "8-node hexahedron",
            ElementKind::Tet4 => "4-node tetrahedron",
        })
    }
}

/// One element type through one interface, in 2D and 3D: `D` dimensions,
/// `N` nodes, `M = D N` dofs (ordered `[u1x, u1y, (u1z,) u2x, ...]`), `V`
/// Voigt components (3 in 2D, 6 in 3D). Implemented by the reference
/// geometries [`QuadGeometry`] (`<2, 4, 8, 3>`), [`TriGeometry`]
/// (`<2, 3, 6, 3>`), [`hex::HexGeometry`] (`<3, 8, 24, 6>`) and
/// [`tet::TetGeometry`] (`<3, 4, 12, 6>`); the seam's dispatch arms are
/// calls of these methods.
pub trait SolidElement<const D: usize, const N: usize, const M: usize, const V: usize>:
    Sized + Copy + fmt::Debug
{
    /// The element's kind (`KIND.node_count() == N`, `KIND.dim() == D`).
    const KIND: ElementKind;

    /// The geometry of the element whose reference node coordinates are
    /// `x_ref` (in the kind's node order); fails for a non-positive,
    /// degenerate or non-finite reference Jacobian.
    fn from_reference(x_ref: &[[f64; D]; N]) -> Result<Self, InvalidElement>;

    /// The reference area (2D, unit thickness) or volume (3D).
    fn measure_ref(&self) -> f64;

    /// Internal force, tangent and strain energy at the displacements `u`.
    fn response(&self, u: &[f64; M], material: &Material) -> SolidResponse<M>;

    /// The strain energy at the displacements `u`.
    fn energy(&self, u: &[f64; M], material: &Material) -> f64;

    /// The stresses at each integration point.
    fn point_stresses(&self, u: &[f64; M], material: &Material) -> Vec<Stress<V>>;

    /// The stresses averaged over the integration points.
    fn mean_stress(&self, u: &[f64; M], material: &Material) -> Stress<V>;
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
    pub fn point_stresses(&self, u: &[f64; MAX_ELEMENT_DOFS], material: &Material) -> Vec<Stress> {
        match self {
            ElementGeometry::Quad4(g) => quad_point_stresses(g, u, material).to_vec(),
            ElementGeometry::Tri3(g) => tri_point_stresses(g, &tri_dofs(u), material).to_vec(),
        }
    }

    /// The element's stresses averaged over its integration points.
    pub fn mean_stress(&self, u: &[f64; MAX_ELEMENT_DOFS], material: &Material) -> Stress {
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
mod solid_tests;
#[cfg(test)]
mod tests;
