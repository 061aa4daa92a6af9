//! [`MshError`]: every way reading a Gmsh file or querying its groups can
//! fail. Each error names the file (`MshError::file`) and the item
//! ([`MshErrorKind`]): a byte offset and line, an element, a node tag, a
//! group name.

use std::path::PathBuf;

/// Reading a `.msh` file, or a query on what was read, failed.
#[derive(Debug, thiserror::Error)]
#[error("{}: {kind}", file.display())]
pub struct MshError {
    /// The file, as given to the reader.
    pub file: PathBuf,
    /// What went wrong, and where.
    pub kind: MshErrorKind,
}

/// What went wrong in a [`MshError`].
#[derive(Debug, thiserror::Error)]
pub enum MshErrorKind {
    /// The file could not be read.
    #[error("cannot read the file: {0}")]
    Io(#[source] std::io::Error),
    /// The file does not begin with a `$MeshFormat` section.
    #[error("not a Gmsh mesh file: it does not begin with `$MeshFormat`")]
    NotMsh,
    /// The `$MeshFormat` header is not `4.1 <0|1> <size>`.
    #[error("malformed `$MeshFormat` header: {0}")]
    BadHeader(String),
    /// A format version other than 4.1.
    #[error(
        "MSH format version {0} is not supported; write MSH 4.1 (gmsh -format msh41, or Mesh.MshFileVersion = 4.1)"
    )]
    UnsupportedVersion(String),
    /// The file is malformed or ends early. `offset` is the byte where the
    /// parser stopped, `line` its line (1-based; meaningful in ASCII files).
    #[error("malformed or truncated file at byte {offset} (line {line}): {what}{context}")]
    Malformed {
        /// Byte offset into the file.
        offset: usize,
        /// Line of that byte, 1-based.
        line: usize,
        /// What the parser expected or found.
        what: String,
        /// Where it was (`, in nodes section > node block 3 of 16`), or empty.
        context: String,
    },
    /// The `$PhysicalNames` section is malformed.
    #[error("malformed `$PhysicalNames` at line {line}: {what}")]
    BadPhysicalNames {
        /// Line in the file, 1-based.
        line: usize,
        /// What is wrong with it.
        what: String,
    },
    /// Two physical groups of the same dimension have the same name.
    #[error("physical name `{name}` is given to two groups of dimension {dim}")]
    DuplicateGroupName {
        /// The name.
        name: String,
        /// Their dimension.
        dim: u8,
    },
    /// An element type the reader does not read: other than 1-node points,
    /// 2-node lines, 3-node triangles and 4-node quadrangles, and in a 3D
    /// mesh 4-node tetrahedra and 8-node hexahedra.
    #[error(
        "unsupported element type: {name} (type {gmsh_type}), {count} of them on entity {entity_dim}/{entity_tag}; only {read} are read{hint}"
    )]
    UnsupportedElement {
        /// The type's name (`9-node second order quadrangle`).
        name: String,
        /// Gmsh's type number.
        gmsh_type: i32,
        /// How many elements of this type the block has.
        count: usize,
        /// Dimension of the entity the block belongs to.
        entity_dim: i32,
        /// Tag of that entity.
        entity_tag: i32,
        /// The types that are read (`1-node points, ...`).
        read: &'static str,
        /// What to do instead (`; gapsim's elements are linear: ...`), or
        /// empty.
        hint: &'static str,
    },
    /// An element block's entity dimension differs from its elements'.
    #[error(
        "element block of entity {entity_dim}/{entity_tag} holds {name} elements of dimension {element_dim}"
    )]
    ElementDimension {
        /// The type's name.
        name: String,
        /// The dimension of its elements.
        element_dim: u8,
        /// Dimension of the block's entity.
        entity_dim: i32,
        /// Tag of that entity.
        entity_tag: i32,
    },
    /// An element refers to a node tag the `$Nodes` section does not have.
    #[error("element {element} refers to node {node}, which the file does not have")]
    UnknownNode {
        /// Gmsh tag of the element.
        element: u64,
        /// The missing node tag.
        node: u64,
    },
    /// Two nodes share a tag.
    #[error("node tag {0} appears twice")]
    DuplicateNode(u64),
    /// Two elements share a tag.
    #[error("element tag {0} appears twice")]
    DuplicateElement(u64),
    /// A section's header declares another number of items than its
    /// blocks hold.
    #[error(
        "the `{section}` section's header declares {declared} {items}, but its blocks hold {found}"
    )]
    WrongCount {
        /// `$Nodes` or `$Elements`.
        section: &'static str,
        /// `nodes` or `elements`.
        items: &'static str,
        /// The header's number.
        declared: u64,
        /// The number the blocks hold.
        found: u64,
    },
    /// A node coordinate is NaN or infinite.
    #[error("node {node} has a non-finite coordinate ({x}, {y}, {z})")]
    NonFiniteNode {
        /// Gmsh tag of the node.
        node: u64,
        /// Its coordinates.
        x: f64,
        /// y.
        y: f64,
        /// z.
        z: f64,
    },
    /// A node is off the plane z = 0: the mesh is not two-dimensional.
    #[error(
        "node {node} has z = {z}, more than {tolerance:e} off the plane z = 0; gapsim reads 2D meshes in the xy-plane"
    )]
    NotPlanar {
        /// Gmsh tag of the node.
        node: u64,
        /// Its z coordinate.
        z: f64,
        /// The tolerance it exceeds.
        tolerance: f64,
    },
    /// No physical group has this name.
    #[error("no physical group is named `{name}`; the file has {}", known_names(.known))]
    UnknownGroup {
        /// The name asked for.
        name: String,
        /// The names the file has (sorted).
        known: Vec<String>,
    },
    /// The group exists, but not with the dimension the query needs.
    #[error("physical group `{name}` has dimension {found}, but {expected} is needed here")]
    WrongDimension {
        /// The name asked for.
        name: String,
        /// The dimension(s) it has.
        found: String,
        /// What the query needs (`2 (a surface)`).
        expected: &'static str,
    },
    /// A volume element whose Jacobian is not positive at a corner
    /// (inverted, or degenerate: at most `16 eps l^3`, `l` its longest
    /// edge; see [`crate::mesh::volume::Cell::is_valid`]).
    #[error(
        "element {element} ({kind}) is inverted or degenerate: its Jacobian at node {node} is {det_j:e}; nodes must be in Gmsh's order (a tetrahedron's 0, 1, 2 counter-clockwise seen from node 3, a hexahedron's 0-3 counter-clockwise seen from 4-7)"
    )]
    InvertedElement {
        /// Gmsh tag of the element.
        element: u64,
        /// Its type's name (`8-node hexahedron`).
        kind: &'static str,
        /// The file's tag of the corner node with the smallest Jacobian.
        node: u64,
        /// That Jacobian determinant.
        det_j: f64,
    },
    /// A triangle or quadrangle of a physical surface that is no boundary
    /// face of a volume element: on no volume element, or between two.
    #[error("element {element} ({kind}) of physical surface `{group}` {why}")]
    UnownedFace {
        /// Gmsh tag of the surface element.
        element: u64,
        /// Its type's name.
        kind: &'static str,
        /// The (first) physical surface it belongs to.
        group: String,
        /// Why (`is no face of a volume element`).
        why: String,
    },
    /// The group has no elements of the kind the query reads.
    #[error("physical group `{name}` has no {what}")]
    EmptyGroup {
        /// The group's name.
        name: String,
        /// What was looked for (`triangles or quadrangles`).
        what: &'static str,
    },
}

/// `` `a`, `b` `` or `no named physical groups`.
fn known_names(known: &[String]) -> String {
    if known.is_empty() {
        "no named physical groups (no `$PhysicalNames` section)".to_owned()
    } else {
        let names: Vec<String> = known.iter().map(|n| format!("`{n}`")).collect();
        names.join(", ")
    }
}
