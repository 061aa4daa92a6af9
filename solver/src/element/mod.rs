//! The solid elements and their seam: the element kinds a mesh holds (the
//! 4-node quadrilateral of [`quad`] and the 3-node triangle of [`tri`] in
//! 2D, the 8-node hexahedron of [`hex`] and the 4-node tetrahedron of
//! [`tet`] in 3D), the kinds of their facets ([`FaceKind`]), their
//! connectivity, their reference geometry and their response, so that the
//! mesh, the assembly, the stresses and the output dispatch through one
//! place instead of branching on the kind everywhere. Each kind owns its
//! VTK cell type ([`ElementKind::vtk_cell_type`]) and its edges.
//!
//! Every element is a total-Lagrangian St Venant–Kirchhoff element with
//! the same point kinematics ([`kinematics`], over the dimension `D`), one
//! isoparametric geometry ([`geometry`]: the reference gradients and
//! weights at the integration points, the degeneracy floor, the sums over
//! the points) and one integrand ([`solid`]: `B^T D B`, the geometric
//! stiffness, the energy and the stresses); they differ in their shape
//! functions and integration rule only (Q4: bilinear, 2x2 Gauss; T3:
//! linear, one point, exact; H8: trilinear, 2x2x2 Gauss; T4: linear, one
//! point, exact). The material is [`material`], the stress measures
//! [`Stress`]. Every element's geometry implements [`SolidElement`], one
//! interface for 2D and 3D; the variants of [`Element`],
//! [`ElementGeometry`] and [`ElementResponse`] call its methods. An
//! element with `n` nodes in `D` dimensions has `D n` dofs, ordered
//! `[u1x, u1y, (u1z,) u2x, ...]`; the seam's element buffers are sized for
//! the largest element (the hexahedron's 24 dofs) and every other kind
//! uses their first `D n` entries. The hexahedron's geometry and the 3D
//! responses are boxed in the enums, so that a 2D mesh's dense vectors of
//! geometries (and an assembly's of responses) keep the size of their 2D
//! variants.
//!
//! Invariants: an [`Element`]'s nodes run counter-clockwise (2D) or in
//! Gmsh's order with a positive Jacobian (3D); an [`ElementGeometry`]
//! exists only for finite coordinates and a reference Jacobian above the
//! degeneracy floor at every integration point
//! ([`geometry::Geometry::new`]); each kind's arithmetic is the one its
//! own functions performed before the geometry was shared, so a mesh
//! gives the same bits.

use std::fmt;
use std::ops::Deref;

use crate::ids::NodeId;

pub mod geometry;
pub mod hex;
pub mod kinematics;
pub mod material;
pub mod quad;
pub mod solid;
mod stress;
pub mod tet;
pub mod tri;

use hex::HexGeometry;
use material::Material;
use quad::QuadGeometry;
use solid::SolidResponse;
pub use stress::Stress;
use tet::TetGeometry;
use tri::TriGeometry;

/// `$body` for the value `$x` of whichever of the four kinds' variants
/// `$value` (of the enum `$enum`) holds.
macro_rules! each_kind {
    ($enum:ident, $value:expr, $x:ident => $body:expr) => {
        match $value {
            $enum::Quad4($x) => $body,
            $enum::Tri3($x) => $body,
            $enum::Hex8($x) => $body,
            $enum::Tet4($x) => $body,
        }
    };
}

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

/// The largest number of dofs of an element (the hexahedron's 24): the
/// size of the seam's element buffers.
pub const MAX_ELEMENT_DOFS: usize = 24;

/// Why [`ElementGeometry::new`] refused an element.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum ElementError {
    /// Its reference Jacobian is not positive.
    #[error(transparent)]
    Invalid(#[from] InvalidElement),
    /// The element's kind lives in another dimension than the coordinates
    /// given (a 2D element in a 3D mesh or the reverse).
    #[error("a {kind} is a {}D element, the mesh has {dim} coordinates", kind.dim())]
    WrongDimension {
        /// The element's kind.
        kind: ElementKind,
        /// The number of coordinates per node given.
        dim: usize,
    },
}

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

/// What is fixed per element kind (the rows of [`ElementKind::info`]).
struct KindInfo {
    nodes: usize,
    dim: usize,
    vtk: u8,
    name: &'static str,
    edges: &'static [[usize; 2]],
}

impl ElementKind {
    /// The kind's row: node count, dimension, VTK cell type, name, edges.
    fn info(self) -> KindInfo {
        match self {
            ElementKind::Quad4 => KindInfo {
                nodes: 4,
                dim: 2,
                vtk: VTK_QUAD,
                name: "4-node quadrilateral",
                edges: &[[0, 1], [1, 2], [2, 3], [3, 0]],
            },
            ElementKind::Tri3 => KindInfo {
                nodes: 3,
                dim: 2,
                vtk: VTK_TRIANGLE,
                name: "3-node triangle",
                edges: &[[0, 1], [1, 2], [2, 0]],
            },
            ElementKind::Hex8 => KindInfo {
                nodes: 8,
                dim: 3,
                vtk: VTK_HEXAHEDRON,
                name: "8-node hexahedron",
                edges: &[
                    [0, 1],
                    [1, 2],
                    [2, 3],
                    [3, 0],
                    [4, 5],
                    [5, 6],
                    [6, 7],
                    [7, 4],
                    [0, 4],
                    [1, 5],
                    [2, 6],
                    [3, 7],
                ],
            },
            ElementKind::Tet4 => KindInfo {
                nodes: 4,
                dim: 3,
                vtk: VTK_TETRA,
                name: "4-node tetrahedron",
                edges: &[[0, 1], [0, 2], [0, 3], [1, 2], [1, 3], [2, 3]],
            },
        }
    }

    /// Nodes per element.
    pub fn node_count(self) -> usize {
        self.info().nodes
    }

    /// The spatial dimension (2 or 3): each node has this many dofs.
    pub fn dim(self) -> usize {
        self.info().dim
    }

    /// The VTK cell type ([`VTK_QUAD`] = 9, [`VTK_TRIANGLE`] = 5,
    /// [`VTK_HEXAHEDRON`] = 12, [`VTK_TETRA`] = 10; VTK's node orders are
    /// Gmsh's for all four).
    pub fn vtk_cell_type(self) -> u8 {
        self.info().vtk
    }

    /// Its edges as pairs of local nodes (what the degeneracy floor
    /// [`geometry::min_det`] measures).
    pub fn edges(self) -> &'static [[usize; 2]] {
        self.info().edges
    }
}

impl fmt::Display for ElementKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.info().name)
    }
}

/// The kind of a facet: an element's side in 2D (a segment), its face in
/// 3D (a quadrilateral's or a triangle's) — the surfaces that carry
/// contact and tractions.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum FaceKind {
    /// A 2-node segment, `xi` in `[-1, 1]`.
    Segment,
    /// A bilinear quadrilateral, `(u, v)` in `[-1, 1]^2`.
    Quad4,
    /// A linear triangle, the unit triangle in `(u, v)`.
    Tri3,
}

impl FaceKind {
    /// Nodes per facet.
    pub fn node_count(self) -> usize {
        match self {
            FaceKind::Segment => 2,
            FaceKind::Quad4 => 4,
            FaceKind::Tri3 => 3,
        }
    }
}

impl fmt::Display for FaceKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            FaceKind::Segment => "segment",
            FaceKind::Quad4 => "quad4",
            FaceKind::Tri3 => "tri3",
        })
    }
}

/// One element type through one interface, in 2D and 3D: `D` dimensions,
/// `N` nodes, `M = D N` dofs (ordered `[u1x, u1y, (u1z,) u2x, ...]`), `V`
/// Voigt components (3 in 2D, 6 in 3D). Implemented by the reference
/// geometries [`QuadGeometry`] (`<2, 4, 8, 3>`), [`TriGeometry`]
/// (`<2, 3, 6, 3>`), [`hex::HexGeometry`] (`<3, 8, 24, 6>`) and
/// [`tet::TetGeometry`] (`<3, 4, 12, 6>`), all one
/// [`geometry::Geometry`]; the seam's dispatch arms are calls of these
/// methods.
pub trait SolidElement<const D: usize, const N: usize, const M: usize, const V: usize>:
    Sized + Copy + fmt::Debug
{
    /// The element's kind (`KIND.node_count() == N`, `KIND.dim() == D`).
    const KIND: ElementKind;

    /// The geometry of the element whose reference node coordinates are
    /// `x_ref` (in the kind's node order); fails for a non-positive,
    /// degenerate or non-finite reference Jacobian.
    fn from_reference(x_ref: &[[f64; D]; N]) -> Result<Self, InvalidElement>;

    /// Its kind.
    fn kind(&self) -> ElementKind {
        Self::KIND
    }

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

    /// The smallest `det F` over the integration points at the
    /// displacements `u`, `F = I + du/dX` (the in-plane `2 x 2` in 2D),
    /// whatever the material's kinematics: the current element's volume
    /// ratio, at most zero where it is inverted or flattened (NaN for
    /// non-finite `u`).
    fn min_det_f(&self, u: &[f64; M]) -> f64;
}

/// The connectivity of one element: its nodes, counter-clockwise (2D) or in
/// Gmsh's order (3D). `N` is
/// the node index: [`NodeId`] in a [`crate::mesh::Mesh`], a body-local
/// `usize` when a body is added. Dereferences to the slice of its nodes.
/// Its `Debug` is the node list alone (the kind is its length), as the
/// plain `[NodeId; 4]` of a quadrilateral mesh printed before.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Element<N = NodeId> {
    /// A 4-node quadrilateral.
    Quad4([N; 4]),
    /// A 3-node triangle.
    Tri3([N; 3]),
    /// An 8-node hexahedron.
    Hex8([N; 8]),
    /// A 4-node tetrahedron.
    Tet4([N; 4]),
}

impl<N> Element<N> {
    /// Its kind.
    pub fn kind(&self) -> ElementKind {
        match self {
            Element::Quad4(_) => ElementKind::Quad4,
            Element::Tri3(_) => ElementKind::Tri3,
            Element::Hex8(_) => ElementKind::Hex8,
            Element::Tet4(_) => ElementKind::Tet4,
        }
    }

    /// Its nodes, counter-clockwise.
    pub fn nodes(&self) -> &[N] {
        each_kind!(Element, self, n => n)
    }

    /// The same element with every node mapped by `f`.
    pub fn map_nodes<M>(self, f: impl FnMut(N) -> M) -> Element<M> {
        match self {
            Element::Quad4(n) => Element::Quad4(n.map(f)),
            Element::Tri3(n) => Element::Tri3(n.map(f)),
            Element::Hex8(n) => Element::Hex8(n.map(f)),
            Element::Tet4(n) => Element::Tet4(n.map(f)),
        }
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

impl<N> From<[N; 8]> for Element<N> {
    fn from(nodes: [N; 8]) -> Self {
        Element::Hex8(nodes)
    }
}

/// The coordinates `x` (`D` per node) as `E` per node, when `D == E`.
fn coordinates<const D: usize, const E: usize, const N: usize>(
    x: &[[f64; D]; N],
    kind: ElementKind,
) -> Result<[[f64; E]; N], ElementError> {
    let mut out = [[0.0; E]; N];
    for (o, p) in out.iter_mut().zip(x) {
        *o = <[f64; E]>::try_from(&p[..])
            .map_err(|_| ElementError::WrongDimension { kind, dim: D })?;
    }
    Ok(out)
}

/// The first `M` entries of an element buffer.
fn first<const M: usize>(u: &[f64; MAX_ELEMENT_DOFS]) -> &[f64; M] {
    const { assert!(M <= MAX_ELEMENT_DOFS) };
    u.first_chunk::<M>()
        .unwrap_or_else(|| unreachable!("M <= MAX_ELEMENT_DOFS"))
}

/// The reference geometry of one element, computed once per mesh.
///
/// The 2D variants differ in size (a triangle's is smaller); they stay
/// unboxed: geometries live in one dense vector indexed by element, read
/// in every iteration, and a box per element would cost an indirection
/// for every quadrilateral. The hexahedron's (1.6 kB) is boxed, so that
/// the vector of a 2D mesh keeps the quadrilateral's size.
#[derive(Debug, Clone, PartialEq)]
pub enum ElementGeometry {
    /// A quadrilateral's (per Gauss point).
    Quad4(QuadGeometry),
    /// A triangle's (constant).
    Tri3(TriGeometry),
    /// A hexahedron's (per Gauss point).
    Hex8(Box<HexGeometry>),
    /// A tetrahedron's (constant).
    Tet4(TetGeometry),
}

impl ElementGeometry {
    /// The geometry of the element whose reference node coordinates are
    /// `x_ref` (`D` per node: counter-clockwise in 2D, Gmsh's order in 3D);
    /// fails for a kind of another dimension than `D` and for a
    /// non-finite, non-positive or degenerate reference Jacobian.
    pub fn new<const D: usize>(x_ref: &Element<[f64; D]>) -> Result<ElementGeometry, ElementError> {
        let kind = x_ref.kind();
        Ok(match x_ref {
            Element::Quad4(x) => ElementGeometry::Quad4(QuadGeometry::new(&coordinates(x, kind)?)?),
            Element::Tri3(x) => ElementGeometry::Tri3(TriGeometry::new(&coordinates(x, kind)?)?),
            Element::Hex8(x) => {
                ElementGeometry::Hex8(Box::new(HexGeometry::new(&coordinates(x, kind)?)?))
            }
            Element::Tet4(x) => ElementGeometry::Tet4(TetGeometry::new(&coordinates(x, kind)?)?),
        })
    }

    /// Its kind.
    pub fn kind(&self) -> ElementKind {
        each_kind!(ElementGeometry, self, g => g.kind())
    }

    /// The reference area (2D, unit thickness) or volume (3D).
    pub fn area_ref(&self) -> f64 {
        each_kind!(ElementGeometry, self, g => g.measure_ref())
    }

    /// Internal force, tangent and energy at the element displacements `u`
    /// (the first `D n` entries are used).
    pub fn response(&self, u: &[f64; MAX_ELEMENT_DOFS], material: &Material) -> ElementResponse {
        each_kind!(ElementGeometry, self, g => g.response(first(u), material).into())
    }

    /// The strain energy at the element displacements `u`.
    pub fn energy(&self, u: &[f64; MAX_ELEMENT_DOFS], material: &Material) -> f64 {
        each_kind!(ElementGeometry, self, g => g.energy(first(u), material))
    }

    /// The stresses at each of its integration points (four for a
    /// quadrilateral, eight for a hexahedron, one for a triangle or a
    /// tetrahedron).
    pub fn point_stresses(
        &self,
        u: &[f64; MAX_ELEMENT_DOFS],
        material: &Material,
    ) -> Vec<ElementStress> {
        each_kind!(ElementGeometry, self, g => g
            .point_stresses(first(u), material)
            .into_iter()
            .map(ElementStress::from)
            .collect())
    }

    /// The element's stresses averaged over its integration points.
    pub fn mean_stress(&self, u: &[f64; MAX_ELEMENT_DOFS], material: &Material) -> ElementStress {
        each_kind!(ElementGeometry, self, g => g.mean_stress(first(u), material).into())
    }

    /// The smallest `det F` over its integration points at the element
    /// displacements `u` ([`SolidElement::min_det_f`]).
    pub fn min_det_f(&self, u: &[f64; MAX_ELEMENT_DOFS]) -> f64 {
        each_kind!(ElementGeometry, self, g => g.min_det_f(first(u)))
    }
}

/// The stresses of one element or point in its own dimension: the three
/// in-plane components of a 2D element, the six of a 3D one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ElementStress {
    /// A 2D element's (`[xx, yy, xy]`).
    Plane(Stress<3>),
    /// A 3D element's (`[xx, yy, zz, yz, xz, xy]`).
    Solid(Stress<6>),
}

impl From<Stress<3>> for ElementStress {
    fn from(s: Stress<3>) -> Self {
        ElementStress::Plane(s)
    }
}

impl From<Stress<6>> for ElementStress {
    fn from(s: Stress<6>) -> Self {
        ElementStress::Solid(s)
    }
}

impl ElementStress {
    /// The 2D stresses (`None` for a 3D element's).
    pub fn plane(self) -> Option<Stress<3>> {
        match self {
            ElementStress::Plane(s) => Some(s),
            ElementStress::Solid(_) => None,
        }
    }

    /// The 3D stresses (`None` for a 2D element's).
    pub fn solid(self) -> Option<Stress<6>> {
        match self {
            ElementStress::Solid(s) => Some(s),
            ElementStress::Plane(_) => None,
        }
    }

    /// The second Piola–Kirchhoff stress in Voigt order.
    pub fn pk2(&self) -> &[f64] {
        match self {
            ElementStress::Plane(s) => &s.pk2,
            ElementStress::Solid(s) => &s.pk2,
        }
    }

    /// The Cauchy stress in Voigt order.
    pub fn cauchy(&self) -> &[f64] {
        match self {
            ElementStress::Plane(s) => &s.cauchy,
            ElementStress::Solid(s) => &s.cauchy,
        }
    }

    /// The Green–Lagrange strain (tensor shear) in Voigt order.
    pub fn green(&self) -> &[f64] {
        match self {
            ElementStress::Plane(s) => &s.green,
            ElementStress::Solid(s) => &s.green,
        }
    }
}

/// What one element contributes: internal force, tangent and energy.
/// The 2D variants are unboxed (see [`ElementGeometry`]): responses are
/// computed per element and iteration, and boxing would add an allocation
/// to each; the 3D ones (4.6 kB and 1.2 kB) are boxed, so that a 2D
/// assembly's vector of responses keeps the quadrilateral's size.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq)]
pub enum ElementResponse {
    /// A quadrilateral's.
    Quad4(SolidResponse<8>),
    /// A triangle's.
    Tri3(SolidResponse<6>),
    /// A hexahedron's.
    Hex8(Box<SolidResponse<24>>),
    /// A tetrahedron's.
    Tet4(Box<SolidResponse<12>>),
}

impl From<SolidResponse<8>> for ElementResponse {
    fn from(r: SolidResponse<8>) -> Self {
        ElementResponse::Quad4(r)
    }
}

impl From<SolidResponse<6>> for ElementResponse {
    fn from(r: SolidResponse<6>) -> Self {
        ElementResponse::Tri3(r)
    }
}

impl From<SolidResponse<24>> for ElementResponse {
    fn from(r: SolidResponse<24>) -> Self {
        ElementResponse::Hex8(Box::new(r))
    }
}

impl From<SolidResponse<12>> for ElementResponse {
    fn from(r: SolidResponse<12>) -> Self {
        ElementResponse::Tet4(Box::new(r))
    }
}

impl ElementResponse {
    /// `f_int` (`D n` entries, in the element's dof order).
    pub fn f_int(&self) -> &[f64] {
        each_kind!(ElementResponse, self, r => &r.f_int)
    }

    /// Row `p` of the tangent `d f_int / d u` (`D n` entries).
    pub fn k_row(&self, p: usize) -> &[f64] {
        each_kind!(ElementResponse, self, r => &r.k[p])
    }

    /// The strain energy.
    pub fn energy(&self) -> f64 {
        each_kind!(ElementResponse, self, r => r.energy)
    }
}

#[cfg(test)]
mod solid_tests;
#[cfg(test)]
mod tests;
