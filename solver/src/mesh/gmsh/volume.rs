//! [`MshVolumeMesh`]: a 3D Gmsh mesh, read as a volume-mesh description.
//!
//! The file is read as a 2D one is (the same guard, sections and checks),
//! except that nodes may lie anywhere and 4-node tetrahedra (Gmsh type 4)
//! and 8-node hexahedra (type 5) are read too. Physical volumes are bodies
//! ([`MshVolumeMesh::volume_elements`], as [`Cell`]s through
//! [`MshElement::cell`]); physical surfaces are groups of faces
//! ([`MshVolumeMesh::surface_faces`]); physical points, curves and
//! surfaces name node sets ([`MshVolumeMesh::group_nodes`]).
//!
//! Invariants, beyond those of the 2D reader (module docs of
//! [`super`]) except planarity:
//!
//! * every tetrahedron and hexahedron is positive: its Jacobian exceeds
//!   the elements' floor `16 eps l^3` at every corner ([`Cell::is_valid`]);
//!   otherwise the read fails naming the element's tag and the corner node;
//! * every triangle and quadrangle on an entity of a named physical surface
//!   is a boundary face of exactly one volume element of the file
//!   ([`BoundaryFaces`] of all its tetrahedra and hexahedra, matched by
//!   node set), which orients it: its [`SurfaceFace::face`] runs
//!   counter-clockwise seen from outside that element (normal
//!   `t_1 x t_2` outward), starting at the file element's first node,
//!   whatever order the file lists its nodes in. A face that no volume
//!   element has, or that lies between two, fails the read naming the
//!   element's tag and its group.
//!
//! Whether bodies share nodes is not checked here: that is for whoever
//! turns the groups into bodies, as for 2D meshes.

use std::collections::HashMap;
use std::path::Path;

use super::{Expect, Msh, MshElement, MshError, MshErrorKind, MshMesh, Tables, convert, read_file};
use crate::mesh::faces::{BoundaryFaces, FaceLookup, starting_at};
use crate::mesh::volume::{Cell, Face};

const VOLUME: Expect = Expect {
    dims: &[3],
    what: "3 (a physical volume)",
};
const SURFACE: Expect = super::SURFACE;

/// A 3D Gmsh mesh; see the module docs for its invariants.
pub type MshVolumeMesh = Msh<3>;

/// A triangle or quadrangle of a physical surface, oriented by the volume
/// element that owns it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SurfaceFace {
    /// Gmsh tag of the surface element.
    pub element: u64,
    /// Gmsh tag of the volume element it bounds.
    pub owner: u64,
    /// Its nodes (dense indices), counter-clockwise seen from outside the
    /// owner, from the file element's first node on.
    pub face: Face,
}

impl MshVolumeMesh {
    /// The tetrahedra and hexahedra of the physical volume `name`, in file
    /// order (each a [`Cell`] through [`MshElement::cell`]). Errors: no
    /// group of that name, not a volume, no such elements.
    pub fn volume_elements(&self, name: &str) -> Result<Vec<&MshElement>, MshError> {
        let elements = self.tables.elements_of(name, &VOLUME)?;
        self.tables
            .non_empty(elements, name, "tetrahedra or hexahedra")
    }

    /// The faces of the physical surface `name`, in file order, each
    /// oriented outward by its owning volume element (module docs).
    /// Errors: no group of that name, not a surface, no triangles or
    /// quadrangles.
    pub fn surface_faces(&self, name: &str) -> Result<Vec<SurfaceFace>, MshError> {
        let faces: Vec<SurfaceFace> = self
            .tables
            .elements_of(name, &SURFACE)?
            .into_iter()
            .filter_map(|e| self.faces.get(&e.tag).copied())
            .collect();
        self.tables
            .non_empty(faces, name, "triangles or quadrangles")
    }
}

/// A Gmsh file read as what it holds ([`read_any`]).
#[derive(Debug, Clone)]
pub enum AnyMsh {
    /// No tetrahedra or hexahedra: a 2D mesh, read by [`MshMesh::read`].
    Planar(MshMesh),
    /// Tetrahedra or hexahedra: a 3D mesh.
    Volume(MshVolumeMesh),
}

/// Reads the `.msh` file at `path` as the mesh it holds: a 3D mesh when an
/// element block lies on a volume or holds three-dimensional elements
/// (read or not), else a 2D mesh exactly as [`MshMesh::read`] reads it.
/// The error is that mesh's reader's: a 3D file's own problem (a NaN
/// coordinate, a duplicated node tag, a second-order tetrahedron) is
/// reported as such, never as the 2D reader's complaint about its z.
/// Errors name `path`.
pub fn read_any(path: impl AsRef<Path>) -> Result<AnyMsh, MshError> {
    let path = path.as_ref();
    let bytes = read_file(path)?;
    let fail = |kind| MshError {
        file: path.to_owned(),
        kind,
    };
    match convert::read_detected(&bytes).map_err(fail)? {
        (convert::Dimension::Volume, parts) => {
            Msh::from_parts(parts, path.to_owned()).map(AnyMsh::Volume)
        }
        (convert::Dimension::Planar, parts) => {
            Msh::from_parts(parts, path.to_owned()).map(AnyMsh::Planar)
        }
    }
}

/// Checks every volume element's Jacobian, then orients every triangle and
/// quadrangle of a named physical surface by its owner (module docs).
pub(super) fn orient(
    nodes: &[[f64; 3]],
    tables: &Tables,
) -> Result<HashMap<u64, SurfaceFace>, MshErrorKind> {
    let mut cells: Vec<Cell> = Vec::new();
    let mut owners: Vec<u64> = Vec::new();
    for e in &tables.elements {
        let Some(cell) = e.cell() else { continue };
        let x = cell.map_nodes(|n| nodes[n]);
        if !x.is_valid() {
            let (det_j, corner) = x.min_corner_jacobian();
            let node = cell.nodes()[corner];
            return Err(MshErrorKind::InvertedElement {
                element: e.tag,
                kind: e.kind.name(),
                node: tables.node_tags.get(node).copied().unwrap_or(node as u64),
                det_j,
            });
        }
        cells.push(cell);
        owners.push(e.tag);
    }
    // the first named physical surface of each surface entity
    let mut group_of: HashMap<i32, &str> = HashMap::new();
    for g in tables.groups.iter().filter(|g| g.dim == 2) {
        for &entity in &g.entities {
            group_of.entry(entity).or_insert(&g.name);
        }
    }
    let boundary = BoundaryFaces::of(&cells);
    let mut faces = HashMap::new();
    for e in &tables.elements {
        let Some(face) = e.face() else { continue };
        let Some(&group) = group_of.get(&e.entity.tag).filter(|_| e.entity.dim == 2) else {
            continue;
        };
        let unowned = |why: String| MshErrorKind::UnownedFace {
            element: e.tag,
            kind: e.kind.name(),
            group: group.to_owned(),
            why,
        };
        match boundary.find(face.nodes()) {
            FaceLookup::Boundary(b) => {
                faces.insert(
                    e.tag,
                    SurfaceFace {
                        element: e.tag,
                        owner: owners[b.cell],
                        face: starting_at(b.face, face.nodes()[0]),
                    },
                );
            }
            FaceLookup::Interior { cells } => {
                return Err(unowned(format!(
                    "lies between {cells} volume elements; a group's faces must be on the boundary of one"
                )));
            }
            FaceLookup::Missing => {
                return Err(unowned(
                    "is no face of a volume element (a surface group of a 3D mesh is made of faces of its tetrahedra and hexahedra)"
                        .to_owned(),
                ));
            }
        }
    }
    Ok(faces)
}
