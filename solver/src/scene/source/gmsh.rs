//! The Gmsh source: the `[mesh] file` (MSH 4.1, read by
//! [`crate::mesh::gmsh`]) and the bodies that are its physical surfaces.
//!
//! A `[[body]]` without block fields is the physical surface `group`
//! (default: its `name`). Its quadrangles and triangles (Gmsh types 3 and
//! 2, mixed freely) become the body's elements ([`Element::Quad4`],
//! [`Element::Tri3`]), in file order; its nodes are the nodes of those elements, in the file's
//! node order, appended fresh through [`Mesh::add_body`]. The source keeps
//! the map from the file's nodes to mesh nodes and every element edge,
//! directed as the element runs (counter-clockwise), so that physical
//! curves and points can be answered by name:
//!
//! * a face ([`BodySource::group_face`]): each segment of the curve is
//!   oriented as the one element that has it as an edge runs, so the face
//!   is counter-clockwise around its body with the outward normal, however
//!   the curve was drawn; then the segments are chained (each chain from
//!   its start, chains in the order of their first segment in the file).
//!   A segment that is no element's edge, or an edge of two elements, or
//!   segments on two bodies are errors naming the curve;
//! * node groups ([`BodySource::group_nodes`]) and loaded curves
//!   ([`BodySource::group_segments`]): every node must belong to a body.
//!
//! Invariants: bodies share no nodes (a node of the file in two bodies'
//! surfaces is an error naming it); an element that is inverted (drawn
//! clockwise) or degenerate is an error naming its tag and kind, as the
//! file's elements are used as drawn (Gmsh draws them counter-clockwise
//! about the surface's normal, +z for a plane surface); other element
//! types are refused by the reader, naming the type; errors name the file
//! and the group or element, the scene field is added by the caller.

use super::{BodySource, GroupFace, blocks::is_block};
use crate::ids::NodeId;
use crate::material::Material;
use crate::mesh::gmsh::{MshElementType, MshMesh};
use crate::mesh::{Element, Mesh, MeshError, Side};
use crate::scene::{Scene, SceneError};
use std::collections::HashMap;

/// The bodies of a scene that come from its `[mesh]` file.
pub(in crate::scene) struct Gmsh<'s> {
    scene: &'s Scene,
    /// The file's mesh, if the scene has a `[mesh]` section.
    msh: Option<MshMesh>,
    /// The mesh node of each of the file's nodes (dense index), once its
    /// body is added.
    node_of: Vec<Option<NodeId>>,
    /// The mesh body of each of the file's nodes that belongs to one.
    body_of: Vec<Option<usize>>,
    /// Every element edge `(from, to)` (the file's dense node indices) as
    /// its element runs, with the element's tag.
    edges: HashMap<(usize, usize), u64>,
}

impl<'s> Gmsh<'s> {
    /// The source of `scene` and its `[mesh] file` `msh`, read (if it has
    /// one).
    pub(in crate::scene) fn new(scene: &'s Scene, msh: Option<MshMesh>) -> Gmsh<'s> {
        let n = msh.as_ref().map_or(0, |m| m.nodes().len());
        Gmsh {
            scene,
            msh,
            node_of: vec![None; n],
            body_of: vec![None; n],
            edges: HashMap::new(),
        }
    }

    /// The file's tag of node `index` (for messages).
    fn tag(msh: &MshMesh, index: usize) -> u64 {
        msh.node_tag(index).unwrap_or(index as u64)
    }

    /// The mesh nodes of the file's nodes `nodes`; an error naming `group`
    /// for a node in no body.
    fn mesh_nodes(
        &self,
        msh: &MshMesh,
        group: &str,
        nodes: &[usize],
    ) -> Result<Vec<NodeId>, String> {
        nodes
            .iter()
            .map(|&n| {
                self.node_of[n].ok_or_else(|| {
                    format!(
                        "{}: node {} of physical group `{group}` belongs to no [[body]]",
                        msh.file().display(),
                        Self::tag(msh, n)
                    )
                })
            })
            .collect()
    }
}

impl BodySource for Gmsh<'_> {
    /// A `[[body]]` without block fields is a physical surface.
    fn owns(&self, index: usize) -> bool {
        !is_block(&self.scene.bodies[index])
    }

    fn add_body(
        &mut self,
        mesh: &mut Mesh,
        i: usize,
        material: Material,
    ) -> Result<usize, SceneError> {
        let b = &self.scene.bodies[i];
        let f = format!("body[{i}]");
        let Some(msh) = &self.msh else {
            return Err(self.scene.invalid(
                f,
                "a body needs `origin`, `size`, `nx` and `ny` (a block), or a `[mesh] file` whose physical surface it is",
            ));
        };
        let (group, field) = match &b.group {
            Some(g) => (g.as_str(), format!("{f}.group")),
            None => (b.name.as_str(), format!("{f}.name")),
        };
        let elements = msh
            .surface_elements(group)
            .map_err(|e| self.scene.invalid(&field, e.to_string()))?;
        let file = msh.file().display();
        // the body's nodes: those of its elements, in the file's order
        let mut nodes: Vec<usize> = elements.iter().flat_map(|e| e.nodes().to_vec()).collect();
        nodes.sort_unstable();
        nodes.dedup();
        if let Some(&n) = nodes.iter().find(|&&n| self.body_of[n].is_some()) {
            let other = &mesh.bodies[self.body_of[n].unwrap_or(0)].name;
            return Err(self.scene.invalid(
                &field,
                format!(
                    "{file}: physical surface `{group}` shares node {} with body `{other}`; bodies share no nodes (give each body its own nodes, e.g. separate surfaces that only touch)",
                    Self::tag(msh, n)
                ),
            ));
        }
        let local: HashMap<usize, usize> = nodes.iter().enumerate().map(|(k, &n)| (n, k)).collect();
        let coords: Vec<[f64; 2]> = nodes.iter().map(|&n| msh.nodes()[n]).collect();
        let conn: Vec<Element<usize>> = elements
            .iter()
            .map(|e| {
                let n = e.nodes();
                match e.kind {
                    MshElementType::Triangle => {
                        Ok(Element::Tri3([local[&n[0]], local[&n[1]], local[&n[2]]]))
                    }
                    MshElementType::Quad => Ok(Element::Quad4([
                        local[&n[0]],
                        local[&n[1]],
                        local[&n[2]],
                        local[&n[3]],
                    ])),
                    // `surface_elements` holds 2D elements only
                    other => Err(self.scene.invalid(
                        &field,
                        format!(
                            "{file}: element {} of physical surface `{group}` is a {other:?}, not a surface element",
                            e.tag
                        ),
                    )),
                }
            })
            .collect::<Result<_, _>>()?;
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
                } => self.scene.invalid(
                    &field,
                    format!(
                        "{file}: element {} of physical surface `{group}` is inverted or degenerate ({kind}, detJ0 = {det_j0:e}); its nodes must run counter-clockwise",
                        elements[element - elem0].tag
                    ),
                ),
                e => self.scene.invalid(&field, format!("{file}: {e}")),
            })?;
        for (k, &n) in nodes.iter().enumerate() {
            self.node_of[n] = Some(NodeId::new(node0 + k));
            self.body_of[n] = Some(body);
        }
        mesh.bodies[body].node_tags = Some(nodes.iter().map(|&n| Self::tag(msh, n)).collect());
        for e in &elements {
            let n = e.nodes();
            for k in 0..n.len() {
                self.edges.insert((n[k], n[(k + 1) % n.len()]), e.tag);
            }
        }
        Ok(body)
    }

    fn face(&self, _mesh: &Mesh, _body: usize, _side: Side) -> Option<Vec<[NodeId; 2]>> {
        None
    }

    fn group_face(&self, group: &str) -> Option<Result<GroupFace, String>> {
        let msh = self.msh.as_ref()?;
        Some(self.face_of(msh, group))
    }

    fn group_nodes(&self, group: &str) -> Option<Result<Vec<NodeId>, String>> {
        let msh = self.msh.as_ref()?;
        Some(self.nodes_of(msh, group))
    }

    fn group_segments(&self, group: &str) -> Option<Result<Vec<[NodeId; 2]>, String>> {
        let msh = self.msh.as_ref()?;
        Some(self.segments_of(msh, group))
    }
}

impl Gmsh<'_> {
    /// [`BodySource::group_face`] of the file's mesh `msh`.
    fn face_of(&self, msh: &MshMesh, group: &str) -> Result<GroupFace, String> {
        let segments = msh.curve_segments(group).map_err(|e| e.to_string())?;
        let file = msh.file().display();
        let not_on_boundary = |[a, b]: [usize; 2], why: &str| {
            format!(
                "{file}: physical curve `{group}` is not on the boundary of a body: its segment from node {} to node {} {why}",
                Self::tag(msh, a),
                Self::tag(msh, b)
            )
        };
        let mut body = None;
        let mut oriented = Vec::with_capacity(segments.len());
        for [a, b] in segments {
            let forward = self.edges.contains_key(&(a, b));
            let backward = self.edges.contains_key(&(b, a));
            let seg = match (forward, backward) {
                (true, false) => [a, b],
                (false, true) => [b, a],
                (true, true) => {
                    return Err(not_on_boundary([a, b], "lies between two elements"));
                }
                (false, false) => {
                    return Err(not_on_boundary(
                        [a, b],
                        "is no edge of an element of a [[body]]",
                    ));
                }
            };
            let owner = self.body_of[a];
            match body {
                None => body = owner,
                Some(first) if owner != Some(first) => {
                    return Err(format!(
                        "{file}: physical curve `{group}` lies on more than one body; a face is on one body"
                    ));
                }
                Some(_) => {}
            }
            oriented.push(seg);
        }
        let body = body.ok_or_else(|| format!("{file}: physical curve `{group}` is empty"))?;
        let segments = chain(&oriented)
            .into_iter()
            .map(|s| s.map(|n| self.node_of[n].unwrap_or(NodeId::new(0))))
            .collect();
        Ok(GroupFace { body, segments })
    }

    /// [`BodySource::group_nodes`] of the file's mesh `msh`.
    fn nodes_of(&self, msh: &MshMesh, group: &str) -> Result<Vec<NodeId>, String> {
        let nodes = msh.group_nodes(group).map_err(|e| e.to_string())?;
        let mut nodes = self.mesh_nodes(msh, group, &nodes)?;
        nodes.sort_unstable();
        Ok(nodes)
    }

    /// [`BodySource::group_segments`] of the file's mesh `msh`.
    fn segments_of(&self, msh: &MshMesh, group: &str) -> Result<Vec<[NodeId; 2]>, String> {
        let segments = msh.curve_segments(group).map_err(|e| e.to_string())?;
        segments
            .iter()
            .map(|s| {
                let n = self.mesh_nodes(msh, group, s)?;
                Ok([n[0], n[1]])
            })
            .collect()
    }
}

/// The oriented segments `segments` in chain order: each chain from its
/// first segment (one whose start ends no other segment; for a closed
/// curve, the first in the file), following the shared nodes; chains in the
/// order of their first segment in `segments`. Every segment appears once.
fn chain(segments: &[[usize; 2]]) -> Vec<[usize; 2]> {
    let starting: HashMap<usize, usize> = segments
        .iter()
        .enumerate()
        .map(|(k, s)| (s[0], k))
        .collect();
    let ending: std::collections::HashSet<usize> = segments.iter().map(|s| s[1]).collect();
    let mut used = vec![false; segments.len()];
    let mut out = Vec::with_capacity(segments.len());
    // open chains first from their starts, then what is left (closed loops)
    let starts = (0..segments.len())
        .filter(|&k| !ending.contains(&segments[k][0]))
        .chain(0..segments.len());
    for start in starts {
        let mut k = start;
        while !used[k] {
            used[k] = true;
            out.push(segments[k]);
            match starting.get(&segments[k][1]) {
                Some(&next) => k = next,
                None => break,
            }
        }
    }
    out
}

#[cfg(test)]
mod tests;
