//! Gmsh MSH 4.1 meshes (ASCII and binary) and their physical groups, in
//! 2D and in 3D.
//!
//! [`MshMesh::read`] reads a 2D `.msh` file into a neutral structure that
//! knows nothing about bodies, materials or the solver: the nodes, the
//! elements of the four kinds a 2D linear mesh has (1-node points, 2-node
//! lines, 3-node triangles, 4-node quadrangles), each with the geometric
//! entity it lies on, and the named physical groups with their entities.
//! The queries answer by physical name: the elements of a physical surface
//! ([`MshMesh::surface_elements`]), the segments of a physical curve
//! ([`MshMesh::curve_segments`]), the nodes of a physical curve or point
//! ([`MshMesh::group_nodes`]). Turning groups into bodies, faces and
//! supports is the scene's mesh source's job.
//!
//! [`MshVolumeMesh::read`] (`volume.rs`) is the 3D path: the same file
//! format, nodes with z, and also 4-node tetrahedra (Gmsh type 4) and
//! 8-node hexahedra (type 5); physical volumes are bodies
//! ([`MshVolumeMesh::volume_elements`]), physical surfaces are groups of
//! faces oriented outward by the volume element that owns each
//! ([`MshVolumeMesh::surface_faces`]). [`MshMesh::read`] keeps refusing a
//! mesh off the plane z = 0, and volume elements.
//!
//! The sections are read by `mshio` (`$Entities`, `$Nodes`, `$Elements`),
//! except what it skips or drops: `$PhysicalNames` (`physical_names.rs`)
//! and dense node tags (`node_tags.rs`). Input that would make `mshio`
//! panic is rejected first (`guard.rs`), so that reading any bytes returns a
//! `Result`; the tests truncate and corrupt files to hold that.
//!
//! Invariants of an [`MshMesh`]:
//!
//! * the `$Nodes` and `$Elements` headers' counts are the numbers of nodes
//!   and elements their blocks hold;
//! * nodes are numbered densely from 0 in file order; `node_tag(i)` is the
//!   file's tag of node `i` and `node_index` inverts it; no two nodes, and
//!   no two elements, share a tag;
//! * every node is finite and lies in the plane z = 0 (within
//!   `1e-9 max(1, max |x|, |y|)`); only x and y are kept;
//! * every element is a point, line, triangle or quadrangle of
//!   [`MshElementType`], lies on an entity of its own dimension and refers
//!   to existing nodes, in the file's node order (Gmsh's: counter-clockwise
//!   about the surface's normal);
//! * elements are in file order (block by block);
//! * physical groups are those named in `$PhysicalNames` (unnamed physical
//!   tags are not reachable); no two groups of one dimension share a name.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use super::volume::{Cell, Face};

mod convert;
mod error;
mod guard;
mod node_tags;
mod physical_names;
mod volume;

#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests3d;

pub use error::{MshError, MshErrorKind};
pub use volume::{AnyMsh, MshVolumeMesh, SurfaceFace, read_any};

/// The element types read; everything else is an error.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum MshElementType {
    /// 1-node point (Gmsh type 15).
    Point,
    /// 2-node line (type 1).
    Line,
    /// 3-node triangle (type 2).
    Triangle,
    /// 4-node quadrangle (type 3).
    Quad,
    /// 4-node tetrahedron (type 4; read by [`MshVolumeMesh`] only).
    Tetrahedron,
    /// 8-node hexahedron (type 5; read by [`MshVolumeMesh`] only).
    Hexahedron,
}

impl MshElementType {
    /// Nodes per element.
    pub fn node_count(self) -> usize {
        match self {
            MshElementType::Point => 1,
            MshElementType::Line => 2,
            MshElementType::Triangle => 3,
            MshElementType::Quad | MshElementType::Tetrahedron => 4,
            MshElementType::Hexahedron => 8,
        }
    }

    /// The element's dimension (0 to 3).
    pub fn dim(self) -> u8 {
        match self {
            MshElementType::Point => 0,
            MshElementType::Line => 1,
            MshElementType::Triangle | MshElementType::Quad => 2,
            MshElementType::Tetrahedron | MshElementType::Hexahedron => 3,
        }
    }

    /// Gmsh's element type number.
    pub fn gmsh_type(self) -> i32 {
        match self {
            MshElementType::Point => 15,
            MshElementType::Line => 1,
            MshElementType::Triangle => 2,
            MshElementType::Quad => 3,
            MshElementType::Tetrahedron => 4,
            MshElementType::Hexahedron => 5,
        }
    }

    /// Gmsh's name of the type (`8-node hexahedron`).
    pub fn name(self) -> &'static str {
        match self {
            MshElementType::Point => "1-node point",
            MshElementType::Line => "2-node line",
            MshElementType::Triangle => "3-node triangle",
            MshElementType::Quad => "4-node quadrangle",
            MshElementType::Tetrahedron => "4-node tetrahedron",
            MshElementType::Hexahedron => "8-node hexahedron",
        }
    }
}

/// A geometric entity of the file: its dimension and tag.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Entity {
    /// 0 point, 1 curve, 2 surface, 3 volume.
    pub dim: u8,
    /// The entity's tag (unique per dimension).
    pub tag: i32,
}

/// One element of the file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct MshElement {
    /// Gmsh's tag of the element.
    pub tag: u64,
    /// Its type.
    pub kind: MshElementType,
    /// The entity it lies on.
    pub entity: Entity,
    /// Its nodes (dense indices), padded with `usize::MAX`.
    nodes: [usize; 8],
}

impl MshElement {
    /// The element's nodes (dense indices), in the file's order;
    /// `kind.node_count()` of them.
    pub fn nodes(&self) -> &[usize] {
        &self.nodes[..self.kind.node_count()]
    }

    /// A volume element as a [`Cell`] (the file's node order is the
    /// cell's); `None` for elements of lower dimension.
    pub fn cell(&self) -> Option<Cell> {
        let n = self.nodes;
        match self.kind {
            MshElementType::Tetrahedron => Some(Cell::Tet4([n[0], n[1], n[2], n[3]])),
            MshElementType::Hexahedron => Some(Cell::Hex8(n)),
            _ => None,
        }
    }

    /// A triangle or quadrangle as a [`Face`] in the file's node order;
    /// `None` for other elements.
    pub fn face(&self) -> Option<Face> {
        let n = self.nodes;
        match self.kind {
            MshElementType::Triangle => Some(Face::Tri3([n[0], n[1], n[2]])),
            MshElementType::Quad => Some(Face::Quad4([n[0], n[1], n[2], n[3]])),
            _ => None,
        }
    }
}

/// A named physical group.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PhysicalGroup {
    /// Its name in `$PhysicalNames`.
    pub name: String,
    /// Its dimension (0 to 3).
    pub dim: u8,
    /// Its physical tag.
    pub tag: i32,
    /// The tags of the entities (of dimension `dim`) that belong to it,
    /// ascending.
    pub entities: Vec<i32>,
}

/// A Gmsh mesh of dimension `D` (2 or 3) as read from a file: the file,
/// the nodes (`D` coordinates), their tags, the elements and the named
/// physical groups. [`MshMesh`] (2D, the module docs give its invariants)
/// and [`MshVolumeMesh`] (3D, `volume.rs`) add the queries of their
/// dimension.
#[derive(Debug, Clone)]
pub struct Msh<const D: usize> {
    nodes: Vec<[f64; D]>,
    tables: Tables,
    /// The outward face of every triangle and quadrangle of a named
    /// physical surface, by the element's tag (3D; empty in 2D).
    faces: HashMap<u64, SurfaceFace>,
}

/// A 2D Gmsh mesh; see the module docs for its invariants.
pub type MshMesh = Msh<2>;

/// What a 2D and a 3D mesh have alike: the file, the node tags, the
/// elements and the groups, with the queries by group name.
#[derive(Debug, Clone)]
struct Tables {
    file: PathBuf,
    node_tags: Vec<u64>,
    node_index: HashMap<u64, usize>,
    elements: Vec<MshElement>,
    groups: Vec<PhysicalGroup>,
}

/// The dimensions a query accepts, and how its error says so.
struct Expect {
    dims: &'static [u8],
    what: &'static str,
}

const SURFACE: Expect = Expect {
    dims: &[2],
    what: "2 (a physical surface)",
};
const CURVE: Expect = Expect {
    dims: &[1],
    what: "1 (a physical curve)",
};
const CURVE_OR_POINT: Expect = Expect {
    dims: &[0, 1],
    what: "0 or 1 (a physical point or curve)",
};
const BELOW_VOLUME: Expect = Expect {
    dims: &[0, 1, 2],
    what: "0, 1 or 2 (a physical point, curve or surface)",
};

/// Reads the file at `path`, or names it in the error.
fn read_file(path: &Path) -> Result<Vec<u8>, MshError> {
    std::fs::read(path).map_err(|e| MshError {
        file: path.to_owned(),
        kind: MshErrorKind::Io(e),
    })
}

impl<const D: usize> Msh<D> {
    /// Reads the `.msh` file at `path` (MSH 4.1, ASCII or binary) as a
    /// mesh of dimension `D`. Errors name `path`.
    pub fn read(path: impl AsRef<Path>) -> Result<Msh<D>, MshError> {
        let path = path.as_ref();
        Msh::from_bytes(&read_file(path)?, path)
    }

    /// Reads the contents of a `.msh` file as a mesh of dimension `D`;
    /// `file` is the name errors give. Never panics, whatever the bytes.
    pub fn from_bytes(bytes: &[u8], file: impl Into<PathBuf>) -> Result<Msh<D>, MshError> {
        let file = file.into();
        match convert::read(bytes, convert::Dimension::of::<D>()) {
            Ok(parts) => Msh::from_parts(parts, file),
            Err(kind) => Err(MshError { file, kind }),
        }
    }

    /// The mesh of the parts of a file read in dimension `D`: in 3D every
    /// volume element checked and every surface element oriented
    /// (`volume.rs`).
    fn from_parts(parts: convert::Parts, file: PathBuf) -> Result<Msh<D>, MshError> {
        let convert::Parts {
            nodes,
            node_tags,
            node_index,
            elements,
            groups,
        } = parts;
        let tables = Tables {
            file,
            node_tags,
            node_index,
            elements,
            groups,
        };
        let faces = if D == 3 {
            volume::orient(&nodes, &tables).map_err(|kind| tables.error(kind))?
        } else {
            HashMap::new()
        };
        Ok(Msh {
            nodes: nodes
                .iter()
                .map(|n| std::array::from_fn(|k| n[k]))
                .collect(),
            tables,
            faces,
        })
    }

    /// The file the mesh was read from.
    pub fn file(&self) -> &Path {
        &self.tables.file
    }

    /// Reference coordinates (`D` of them: x, y (, z)) of the nodes, by
    /// dense index.
    pub fn nodes(&self) -> &[[f64; D]] {
        &self.nodes
    }

    /// The file's tag of node `index`.
    pub fn node_tag(&self, index: usize) -> Option<u64> {
        self.tables.node_tags.get(index).copied()
    }

    /// The dense index of the node with the file's tag `tag`.
    pub fn node_index(&self, tag: u64) -> Option<usize> {
        self.tables.node_index.get(&tag).copied()
    }

    /// Every element, in file order.
    pub fn elements(&self) -> &[MshElement] {
        &self.tables.elements
    }

    /// The named physical groups, in `$PhysicalNames` order.
    pub fn groups(&self) -> &[PhysicalGroup] {
        &self.tables.groups
    }

    /// The nodes (dense indices, ascending, each once) of the elements of
    /// the physical groups `name` below the mesh's dimension: a point or
    /// curve, and in 3D a surface (of all of them if several dimensions
    /// share the name). Errors: no group of that name, none below the
    /// mesh's dimension, no elements.
    pub fn group_nodes(&self, name: &str) -> Result<Vec<usize>, MshError> {
        let (expect, what) = if D == 2 {
            (&CURVE_OR_POINT, "point or line elements")
        } else {
            (&BELOW_VOLUME, "point, line or surface elements")
        };
        self.tables.nodes_of(name, expect, what)
    }
}

impl MshMesh {
    /// The triangles and quadrangles of the physical surface `name`, in
    /// file order. Errors: no group of that name, not a surface, no such
    /// elements.
    pub fn surface_elements(&self, name: &str) -> Result<Vec<&MshElement>, MshError> {
        let elements = self.tables.elements_of(name, &SURFACE)?;
        self.tables
            .non_empty(elements, name, "triangles or quadrangles")
    }

    /// The 2-node line elements of the physical curve `name`, as node
    /// pairs in file order, each as the file draws it (the orientation of
    /// the curve, not of any surface). Errors: no group of that name, not a
    /// curve, no line elements.
    pub fn curve_segments(&self, name: &str) -> Result<Vec<[usize; 2]>, MshError> {
        let segments: Vec<[usize; 2]> = self
            .tables
            .elements_of(name, &CURVE)?
            .into_iter()
            .filter(|e| e.kind == MshElementType::Line)
            .map(|e| [e.nodes[0], e.nodes[1]])
            .collect();
        self.tables.non_empty(segments, name, "line elements")
    }
}

impl Tables {
    /// The elements of the dimension(s) `expect` allows on the entities of
    /// the groups named `name`.
    fn elements_of(&self, name: &str, expect: &Expect) -> Result<Vec<&MshElement>, MshError> {
        let named: Vec<&PhysicalGroup> = self.groups.iter().filter(|g| g.name == name).collect();
        if named.is_empty() {
            let mut known: Vec<String> = self.groups.iter().map(|g| g.name.clone()).collect();
            known.sort();
            known.dedup();
            return Err(self.error(MshErrorKind::UnknownGroup {
                name: name.to_owned(),
                known,
            }));
        }
        let entities: Vec<Entity> = named
            .iter()
            .filter(|g| expect.dims.contains(&g.dim))
            .flat_map(|g| g.entities.iter().map(|&tag| Entity { dim: g.dim, tag }))
            .collect();
        if !named.iter().any(|g| expect.dims.contains(&g.dim)) {
            let found: Vec<String> = named.iter().map(|g| g.dim.to_string()).collect();
            return Err(self.error(MshErrorKind::WrongDimension {
                name: name.to_owned(),
                found: found.join(" and "),
                expected: expect.what,
            }));
        }
        Ok(self
            .elements
            .iter()
            .filter(|e| e.kind.dim() == e.entity.dim && entities.contains(&e.entity))
            .collect())
    }

    /// The nodes (ascending, each once) of the elements [`Tables::elements_of`]
    /// finds; `what` names them in the error for none.
    fn nodes_of(
        &self,
        name: &str,
        expect: &Expect,
        what: &'static str,
    ) -> Result<Vec<usize>, MshError> {
        let mut nodes: Vec<usize> = self
            .elements_of(name, expect)?
            .into_iter()
            .flat_map(|e| e.nodes().iter().copied())
            .collect();
        nodes.sort_unstable();
        nodes.dedup();
        self.non_empty(nodes, name, what)
    }

    /// `items` of the group `name`, or the error that it has no `what`.
    fn non_empty<T>(
        &self,
        items: Vec<T>,
        name: &str,
        what: &'static str,
    ) -> Result<Vec<T>, MshError> {
        if items.is_empty() {
            return Err(self.error(MshErrorKind::EmptyGroup {
                name: name.to_owned(),
                what,
            }));
        }
        Ok(items)
    }

    fn error(&self, kind: MshErrorKind) -> MshError {
        MshError {
            file: self.file.clone(),
            kind,
        }
    }
}
