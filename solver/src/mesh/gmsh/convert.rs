//! From the bytes of a file to the parts of an [`MshMesh`](super::MshMesh)
//! or an [`MshVolumeMesh`](super::MshVolumeMesh): the guard, `mshio`, the
//! physical names and node tags, then the checks that give the mesh its
//! invariants. The [`Dimension`] says which: a planar mesh of points,
//! lines and surface elements, or a volume mesh that may also hold
//! tetrahedra and hexahedra and nodes anywhere.

use std::collections::HashMap;

use mshio::error::MshParserErrorKind;
use mshio::{ElementType, MshFile, MshParserError};

use super::error::MshErrorKind;
use super::guard::{self, line_of};
use super::{Entity, MshElement, MshElementType, PhysicalGroup, node_tags, physical_names};

/// Relative tolerance on |z| (times `max(1, max |x|, |y|)`).
const PLANAR_TOLERANCE: f64 = 1e-9;

/// Which mesh is read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Dimension {
    /// A 2D mesh: nodes in the plane z = 0, no volume elements.
    Planar,
    /// A 3D mesh: nodes anywhere, tetrahedra and hexahedra too.
    Volume,
}

impl Dimension {
    /// The mesh of dimension `D` (2 or 3).
    pub(super) fn of<const D: usize>() -> Dimension {
        const { assert!(D == 2 || D == 3, "a Gmsh mesh is 2D or 3D") };
        if D == 2 {
            Dimension::Planar
        } else {
            Dimension::Volume
        }
    }

    /// The element types it reads, as its error names them.
    fn element_types(self) -> &'static str {
        match self {
            Dimension::Planar => {
                "1-node points, 2-node lines, 3-node triangles and 4-node quadrangles"
            }
            Dimension::Volume => {
                "1-node points, 2-node lines, 3-node triangles, 4-node quadrangles, 4-node tetrahedra and 8-node hexahedra"
            }
        }
    }
}

/// What an [`MshMesh`](super::MshMesh) is made of.
pub(super) struct Parts {
    /// (x, y, z); z is within the planar tolerance of 0 in a planar mesh.
    pub(super) nodes: Vec<[f64; 3]>,
    pub(super) node_tags: Vec<u64>,
    pub(super) node_index: HashMap<u64, usize>,
    pub(super) elements: Vec<MshElement>,
    pub(super) groups: Vec<PhysicalGroup>,
}

/// Reads and checks a whole file.
pub(super) fn read(bytes: &[u8], dimension: Dimension) -> Result<Parts, MshErrorKind> {
    let encoding = guard::check(bytes)?;
    let msh = mshio::parse_msh_bytes(bytes).map_err(|e| malformed(bytes, &e))?;
    parts(bytes, encoding, &msh, dimension)
}

/// Reads and checks a whole file as the mesh it holds: a volume mesh when
/// one of its element blocks lies on a volume entity or holds elements of
/// a three-dimensional type (read or not: a second-order tetrahedron makes
/// a 3D file, refused by the 3D reader naming its type), else a planar
/// mesh. The error is that mesh's reader's (a file that does not parse
/// fails alike in both).
pub(super) fn read_detected(bytes: &[u8]) -> Result<(Dimension, Parts), MshErrorKind> {
    let encoding = guard::check(bytes)?;
    let msh = mshio::parse_msh_bytes(bytes).map_err(|e| malformed(bytes, &e))?;
    let volume = msh.data.elements.as_ref().is_some_and(|section| {
        section
            .element_blocks
            .iter()
            .any(|b| b.entity_dim == 3 || is_volume_type(b.element_type))
    });
    let dimension = if volume {
        Dimension::Volume
    } else {
        Dimension::Planar
    };
    Ok((dimension, parts(bytes, encoding, &msh, dimension)?))
}

/// Whether Gmsh's element type `t` is three-dimensional (tetrahedra,
/// hexahedra, prisms and pyramids of the first and second order).
fn is_volume_type(t: ElementType) -> bool {
    matches!(t as i32, 4..=7 | 11..=14 | 17..=19)
}

/// The parts of the parsed file `msh` (`bytes`, in `encoding`), read as a
/// mesh of `dimension`.
fn parts(
    bytes: &[u8],
    encoding: guard::Encoding,
    msh: &MshFile<u64, i32, f64>,
    dimension: Dimension,
) -> Result<Parts, MshErrorKind> {
    let names = physical_names::parse(bytes)?;
    let (nodes, node_tags, node_index) = nodes(bytes, encoding, msh, dimension)?;
    let elements = elements(msh, &node_index, dimension)?;
    let groups = groups(msh, names)?;
    Ok(Parts {
        nodes,
        node_tags,
        node_index,
        elements,
        groups,
    })
}

/// `mshio`'s error as [`MshErrorKind::Malformed`]: where it stopped, the
/// innermost message and the contexts around it (outermost first).
fn malformed(bytes: &[u8], error: &MshParserError<&[u8]>) -> MshErrorKind {
    let offset = error
        .backtrace
        .first()
        .and_then(|(rest, _)| offset_in(bytes, rest))
        .unwrap_or(bytes.len());
    // The backtrace runs from the innermost entry outwards; nom's own
    // entries say nothing a reader of the file can use.
    let entries: Vec<&MshParserErrorKind> = error.filter_msh_errors().map(|(_, k)| k).collect();
    let what = entries
        .iter()
        .find(|k| k.context().is_none())
        .map(|k| k.to_string().trim_end_matches('.').to_owned())
        .unwrap_or_else(|| "unexpected input".to_owned());
    let contexts: Vec<&str> = entries.iter().rev().filter_map(|k| k.context()).collect();
    let context = if contexts.is_empty() {
        String::new()
    } else {
        format!(", in {}", contexts.join(" > "))
    };
    MshErrorKind::Malformed {
        offset,
        line: line_of(bytes, offset),
        what,
        context,
    }
}

/// Where the slice `rest` starts in `bytes`, if it is part of it.
fn offset_in(bytes: &[u8], rest: &[u8]) -> Option<usize> {
    let offset = (rest.as_ptr() as usize).checked_sub(bytes.as_ptr() as usize)?;
    (offset <= bytes.len()).then_some(offset)
}

type Nodes = (Vec<[f64; 3]>, Vec<u64>, HashMap<u64, usize>);

/// The nodes in file order, their tags and the map from tags.
fn nodes(
    bytes: &[u8],
    encoding: guard::Encoding,
    msh: &MshFile<u64, i32, f64>,
    dimension: Dimension,
) -> Result<Nodes, MshErrorKind> {
    let Some(section) = &msh.data.nodes else {
        return Ok((Vec::new(), Vec::new(), HashMap::new()));
    };
    let tags = node_tags::node_tags(bytes, encoding)?;
    let mismatch = || MshErrorKind::Malformed {
        offset: 0,
        line: 1,
        what: "the node tags do not match the node blocks".to_owned(),
        context: ", in the `$Nodes` section".to_owned(),
    };
    if tags.len() != section.node_blocks.len() {
        return Err(mismatch());
    }
    let extent = section
        .node_blocks
        .iter()
        .flat_map(|b| &b.nodes)
        .fold(1.0_f64, |m, n| m.max(n.x.abs()).max(n.y.abs()));
    let tolerance = PLANAR_TOLERANCE * extent;
    let found = section.node_blocks.iter().map(|b| b.nodes.len()).sum();
    check_count("$Nodes", "nodes", section.num_nodes, found)?;
    let mut coordinates = Vec::new();
    let mut node_tags = Vec::new();
    let mut node_index = HashMap::new();
    for (block, block_tags) in section.node_blocks.iter().zip(&tags) {
        if block.nodes.len() != block_tags.len() {
            return Err(mismatch());
        }
        for (node, &tag) in block.nodes.iter().zip(block_tags) {
            if !(node.x.is_finite() && node.y.is_finite() && node.z.is_finite()) {
                return Err(MshErrorKind::NonFiniteNode {
                    node: tag,
                    x: node.x,
                    y: node.y,
                    z: node.z,
                });
            }
            if dimension == Dimension::Planar && node.z.abs() > tolerance {
                return Err(MshErrorKind::NotPlanar {
                    node: tag,
                    z: node.z,
                    tolerance,
                });
            }
            if node_index.insert(tag, coordinates.len()).is_some() {
                return Err(MshErrorKind::DuplicateNode(tag));
            }
            coordinates.push([node.x, node.y, node.z]);
            node_tags.push(tag);
        }
    }
    Ok((coordinates, node_tags, node_index))
}

/// Whether the header of `section` declares as many `items` as its blocks
/// hold (`found`).
fn check_count(
    section: &'static str,
    items: &'static str,
    declared: u64,
    found: usize,
) -> Result<(), MshErrorKind> {
    if declared != found as u64 {
        return Err(MshErrorKind::WrongCount {
            section,
            items,
            declared,
            found: found as u64,
        });
    }
    Ok(())
}

/// The elements in file order, with dense node indices.
fn elements(
    msh: &MshFile<u64, i32, f64>,
    node_index: &HashMap<u64, usize>,
    dimension: Dimension,
) -> Result<Vec<MshElement>, MshErrorKind> {
    let Some(section) = &msh.data.elements else {
        return Ok(Vec::new());
    };
    let found = section
        .element_blocks
        .iter()
        .map(|b| b.elements.len())
        .sum();
    check_count("$Elements", "elements", section.num_elements, found)?;
    let mut seen = std::collections::HashSet::new();
    let mut elements = Vec::new();
    for block in &section.element_blocks {
        let kind = match block.element_type {
            ElementType::Pnt => MshElementType::Point,
            ElementType::Lin2 => MshElementType::Line,
            ElementType::Tri3 => MshElementType::Triangle,
            ElementType::Qua4 => MshElementType::Quad,
            ElementType::Tet4 if dimension == Dimension::Volume => MshElementType::Tetrahedron,
            ElementType::Hex8 if dimension == Dimension::Volume => MshElementType::Hexahedron,
            other => {
                return Err(MshErrorKind::UnsupportedElement {
                    name: type_name(other),
                    gmsh_type: other as i32,
                    count: block.elements.len(),
                    entity_dim: block.entity_dim,
                    entity_tag: block.entity_tag,
                    read: dimension.element_types(),
                    hint: unsupported_hint(other),
                });
            }
        };
        if block.entity_dim != i32::from(kind.dim()) {
            return Err(MshErrorKind::ElementDimension {
                name: type_name(block.element_type),
                element_dim: kind.dim(),
                entity_dim: block.entity_dim,
                entity_tag: block.entity_tag,
            });
        }
        let entity = Entity {
            dim: kind.dim(),
            tag: block.entity_tag,
        };
        for element in &block.elements {
            if !seen.insert(element.element_tag) {
                return Err(MshErrorKind::DuplicateElement(element.element_tag));
            }
            let mut nodes = [usize::MAX; 8];
            for (slot, &tag) in nodes.iter_mut().zip(&element.nodes) {
                *slot = *node_index.get(&tag).ok_or(MshErrorKind::UnknownNode {
                    element: element.element_tag,
                    node: tag,
                })?;
            }
            elements.push(MshElement {
                tag: element.element_tag,
                kind,
                entity,
                nodes,
            });
        }
    }
    Ok(elements)
}

/// What to do about an element type that is not read: higher-order
/// elements re-meshed with first-order ones, prisms and pyramids meshed
/// as tetrahedra or hexahedra.
fn unsupported_hint(t: ElementType) -> &'static str {
    match t as i32 {
        6 | 7 => {
            "; mesh the volumes with tetrahedra or hexahedra only (no prisms or pyramids: in Gmsh, no `Recombine` of extruded layers into prisms, or `Mesh.SubdivisionAlgorithm = 2` to split them into hexahedra)"
        }
        1..=5 | 15 => "",
        _ => {
            "; gapsim's elements are linear: mesh with first-order elements (Gmsh's default: `-order 1` on the command line, `Mesh.ElementOrder = 1` in a .geo file, `gmsh.option.setNumber(\"Mesh.ElementOrder\", 1)` in the API)"
        }
    }
}

/// The named groups, each with the entities whose physical tags name it.
fn groups(
    msh: &MshFile<u64, i32, f64>,
    names: Vec<physical_names::PhysicalName>,
) -> Result<Vec<PhysicalGroup>, MshErrorKind> {
    // (dim, physical tag) of every entity
    let mut tagged: Vec<(u8, i32, i32)> = Vec::new(); // (dim, physical, entity)
    if let Some(entities) = &msh.data.entities {
        let mut add = |dim: u8, entity: i32, physical: &[i32]| {
            tagged.extend(physical.iter().map(|&p| (dim, p, entity)));
        };
        for p in &entities.points {
            add(0, p.tag, &p.physical_tags);
        }
        for c in &entities.curves {
            add(1, c.tag, &c.physical_tags);
        }
        for s in &entities.surfaces {
            add(2, s.tag, &s.physical_tags);
        }
        for v in &entities.volumes {
            add(3, v.tag, &v.physical_tags);
        }
    }
    let mut groups: Vec<PhysicalGroup> = Vec::new();
    for name in names {
        if groups
            .iter()
            .any(|g| g.dim == name.dim && g.name == name.name)
        {
            return Err(MshErrorKind::DuplicateGroupName {
                name: name.name,
                dim: name.dim,
            });
        }
        let mut entities: Vec<i32> = tagged
            .iter()
            .filter(|&&(dim, physical, _)| dim == name.dim && physical == name.tag)
            .map(|&(_, _, entity)| entity)
            .collect();
        entities.sort_unstable();
        entities.dedup();
        groups.push(PhysicalGroup {
            name: name.name,
            dim: name.dim,
            tag: name.tag,
            entities,
        });
    }
    Ok(groups)
}

/// Gmsh's name of an element type (`9-node second order quadrangle`).
fn type_name(t: ElementType) -> String {
    let name = match t as i32 {
        1 => "2-node line",
        2 => "3-node triangle",
        3 => "4-node quadrangle",
        4 => "4-node tetrahedron",
        5 => "8-node hexahedron",
        6 => "6-node prism",
        7 => "5-node pyramid",
        8 => "3-node second order line",
        9 => "6-node second order triangle",
        10 => "9-node second order quadrangle",
        11 => "10-node second order tetrahedron",
        12 => "27-node second order hexahedron",
        13 => "18-node second order prism",
        14 => "14-node second order pyramid",
        15 => "1-node point",
        16 => "8-node second order quadrangle",
        17 => "20-node second order hexahedron",
        18 => "15-node second order prism",
        19 => "13-node second order pyramid",
        20 => "9-node third order incomplete triangle",
        21 => "10-node third order triangle",
        22 => "12-node fourth order incomplete triangle",
        23 => "15-node fourth order triangle",
        24 => "15-node fifth order incomplete triangle",
        25 => "21-node fifth order triangle",
        26 => "4-node third order line",
        27 => "5-node fourth order line",
        28 => "6-node fifth order line",
        29 => "20-node third order tetrahedron",
        30 => "35-node fourth order tetrahedron",
        31 => "56-node fifth order tetrahedron",
        _ => {
            return match t.nodes() {
                Ok(n) => format!("{n}-node {t:?} element"),
                Err(()) => format!("{t:?} element"),
            };
        }
    };
    name.to_owned()
}
