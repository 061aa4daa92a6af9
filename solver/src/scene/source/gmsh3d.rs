//! The 3D Gmsh source: a `[mesh] file` holding tetrahedra or hexahedra
//! (read by [`MshVolumeMesh`]) and the bodies that are its physical
//! volumes.
//!
//! A `[[body]]` of a 3D scene without block fields is the physical volume
//! `group` (default: its `name`). Its tetrahedra and hexahedra (Gmsh types
//! 4 and 5, mixed freely, each positive at every corner: the reader checks
//! it) become the body's elements in file order, in Gmsh's node order; its
//! nodes are the nodes of those elements, in the file's node order,
//! appended fresh. The source keeps the map from the file's nodes to mesh
//! nodes and the body of every volume element it added, so that groups are
//! answered by name:
//!
//! * a face group ([`VolumeFile::group_faces`]): the triangles and
//!   quadrangles of a physical surface, each oriented outward by the one
//!   volume element that owns it (the reader refuses a face that no volume
//!   element has, or that two have, naming it); every face's owner must be
//!   an element of a `[[body]]`, and all of them of one body;
//! * a node group ([`VolumeFile::group_nodes`]): the nodes of a physical
//!   point, curve or surface, each of which must belong to a body.
//!
//! Invariants: bodies share no nodes (a node of the file in two bodies'
//! volumes is an error naming it); errors name the file and the group or
//! element, the scene field is added by the caller.

use std::collections::HashMap;

use crate::element::Element;
use crate::ids::NodeId;
use crate::material::Material;
use crate::mesh::gmsh::MshVolumeMesh;
use crate::mesh::volume::{Cell, Face};
use crate::mesh::{Mesh, MeshError};
use crate::scene::{Scene, SceneError};

/// The bodies of a 3D scene that come from its `[mesh]` file.
pub(super) struct VolumeFile {
    msh: MshVolumeMesh,
    /// The mesh node of each of the file's nodes (dense index), once its
    /// body is added.
    node_of: Vec<Option<NodeId>>,
    /// The mesh body of each of the file's nodes that belongs to one.
    body_of: Vec<Option<usize>>,
    /// The mesh body of each volume element added, by the element's tag.
    element_body: HashMap<u64, usize>,
}

impl VolumeFile {
    /// The source of the file's mesh `msh`.
    pub(super) fn new(msh: MshVolumeMesh) -> VolumeFile {
        let n = msh.nodes().len();
        VolumeFile {
            msh,
            node_of: vec![None; n],
            body_of: vec![None; n],
            element_body: HashMap::new(),
        }
    }

    /// The file's tag of node `index` (for messages).
    fn tag(&self, index: usize) -> u64 {
        self.msh.node_tag(index).unwrap_or(index as u64)
    }

    /// Appends the scene's `body[i]`, the physical volume `group` (default:
    /// its `name`), with its checked `material`; returns the mesh body.
    pub(super) fn add_body(
        &mut self,
        scene: &Scene,
        mesh: &mut Mesh<3>,
        i: usize,
        material: Material,
    ) -> Result<usize, SceneError> {
        let b = &scene.bodies[i];
        let f = format!("body[{i}]");
        let (group, field) = match &b.group {
            Some(g) => (g.as_str(), format!("{f}.group")),
            None => (b.name.as_str(), format!("{f}.name")),
        };
        let msh = &self.msh;
        let file = msh.file().display();
        let elements = msh
            .volume_elements(group)
            .map_err(|e| scene.invalid(&field, e.to_string()))?;
        let cells: Vec<(u64, Cell)> = elements
            .iter()
            .filter_map(|e| Some((e.tag, e.cell()?)))
            .collect();
        // the body's nodes: those of its elements, in the file's order
        let mut nodes: Vec<usize> = cells.iter().flat_map(|(_, c)| c.nodes().to_vec()).collect();
        nodes.sort_unstable();
        nodes.dedup();
        if let Some(&n) = nodes.iter().find(|&&n| self.body_of[n].is_some()) {
            let other = self.body_of[n].map_or("", |o| mesh.bodies[o].name.as_str());
            return Err(scene.invalid(
                &field,
                format!(
                    "{file}: physical volume `{group}` shares node {} with body `{other}`; bodies share no nodes (give each body its own nodes, e.g. separate volumes that only touch)",
                    self.tag(n)
                ),
            ));
        }
        let local: HashMap<usize, usize> = nodes.iter().enumerate().map(|(k, &n)| (n, k)).collect();
        let coords: Vec<[f64; 3]> = nodes.iter().map(|&n| msh.nodes()[n]).collect();
        let conn: Vec<Element<usize>> = cells
            .iter()
            .map(|(_, c)| c.map_nodes(|n| local[&n]).into())
            .collect();
        let elem0 = mesh.element_count();
        let node0 = mesh.node_count();
        let body = mesh
            .add_body(&b.name, material, &coords, &conn)
            .map_err(|e| match e {
                MeshError::InvalidElement {
                    element,
                    kind,
                    det_j0,
                    ..
                } => scene.invalid(
                    &field,
                    format!(
                        "{file}: element {} of physical volume `{group}` is inverted or degenerate ({kind}, detJ0 = {det_j0:e})",
                        cells[element - elem0].0
                    ),
                ),
                e => scene.invalid(&field, format!("{file}: {e}")),
            })?;
        for (k, &n) in nodes.iter().enumerate() {
            self.node_of[n] = Some(NodeId::new(node0 + k));
            self.body_of[n] = Some(body);
        }
        for (tag, _) in &cells {
            self.element_body.insert(*tag, body);
        }
        mesh.bodies[body].node_tags = Some(nodes.iter().map(|&n| self.tag(n)).collect());
        Ok(body)
    }

    /// The mesh nodes of the file's nodes `nodes`; an error naming `group`
    /// for a node in no body.
    fn mesh_nodes(&self, group: &str, nodes: &[usize]) -> Result<Vec<NodeId>, String> {
        nodes
            .iter()
            .map(|&n| {
                self.node_of[n].ok_or_else(|| {
                    format!(
                        "{}: node {} of physical group `{group}` belongs to no [[body]]",
                        self.msh.file().display(),
                        self.tag(n)
                    )
                })
            })
            .collect()
    }

    /// The physical surface `group` as faces of one body: the body and the
    /// faces (mesh nodes), each counter-clockwise seen from outside its
    /// owning element, in file order (module docs).
    pub(super) fn group_faces(&self, group: &str) -> Result<(usize, Vec<Face<NodeId>>), String> {
        let faces = self.msh.surface_faces(group).map_err(|e| e.to_string())?;
        let file = self.msh.file().display();
        let mut body = None;
        let mut out = Vec::with_capacity(faces.len());
        for sf in faces {
            let owner = self.element_body.get(&sf.owner).copied().ok_or_else(|| {
                format!(
                    "{file}: element {} of physical surface `{group}` is a face of volume element {}, which belongs to no [[body]]",
                    sf.element, sf.owner
                )
            })?;
            match body {
                None => body = Some(owner),
                Some(first) if first != owner => {
                    return Err(format!(
                        "{file}: physical surface `{group}` lies on more than one body; a face group is on one body"
                    ));
                }
                Some(_) => {}
            }
            let nodes = self.mesh_nodes(group, sf.face.nodes())?;
            out.push(match sf.face {
                Face::Quad4(_) => Face::Quad4([nodes[0], nodes[1], nodes[2], nodes[3]]),
                Face::Tri3(_) => Face::Tri3([nodes[0], nodes[1], nodes[2]]),
            });
        }
        let body = body.ok_or_else(|| format!("{file}: physical surface `{group}` is empty"))?;
        Ok((body, out))
    }

    /// The mesh nodes of the physical point, curve or surface `group`,
    /// ascending.
    pub(super) fn group_nodes(&self, group: &str) -> Result<Vec<NodeId>, String> {
        let nodes = self.msh.group_nodes(group).map_err(|e| e.to_string())?;
        let mut nodes = self.mesh_nodes(group, &nodes)?;
        nodes.sort_unstable();
        Ok(nodes)
    }
}
