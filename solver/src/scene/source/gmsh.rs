//! The Gmsh source: the `[mesh] file` (MSH 4.1, read by
//! [`crate::mesh::gmsh`]) and the bodies that are its physical surfaces
//! (2D) or volumes (3D).
//!
//! A `[[body]]` without block fields is the physical surface or volume
//! `group` (default: its `name`). Its elements (2D: quadrangles and
//! triangles, Gmsh types 3 and 2; 3D: hexahedra and tetrahedra, types 5
//! and 4, each positive at every corner: the reader checks it; mixed
//! freely) become the body's elements in file order, in the file's node
//! order; its nodes are the nodes of those elements, in the file's node
//! order, appended fresh through [`Mesh::add_body`]. The source keeps the
//! map from the file's nodes to mesh nodes and the body of every element
//! it added, so that groups can be answered by name:
//!
//! * in 2D a face ([`MeshFile::group_face`]): each segment of the physical
//!   curve is oriented as the one element that has it as an edge runs
//!   (counter-clockwise), so the face is counter-clockwise around its body
//!   with the outward normal, however the curve was drawn; then the
//!   segments are chained (each chain from its start, chains in the order
//!   of their first segment in the file). A segment that is no element's
//!   edge, or an edge of two elements, or segments on two bodies are
//!   errors naming the curve;
//! * in 3D a face group ([`MeshFile::group_faces`]): the triangles and
//!   quadrangles of a physical surface, each oriented outward by the one
//!   volume element that owns it (the reader refuses a face that no volume
//!   element has, or that two have, naming it); every face's owner must be
//!   an element of a `[[body]]`, and all of them of one body;
//! * node groups ([`MeshFile::group_nodes`]: physical points and curves,
//!   and surfaces in 3D) and, in 2D, loaded curves
//!   ([`MeshFile::group_segments`]): every node must belong to a body.
//!
//! Invariants: bodies share no nodes (a node of the file in two bodies is
//! an error naming it); an element that is inverted or degenerate is an
//! error naming its tag and kind, as the file's elements are used as drawn
//! (in 2D Gmsh draws them counter-clockwise about the surface's normal, +z
//! for a plane surface); other element types are refused by the reader,
//! naming the type; a body that falls apart at unmerged nodes (two nodes
//! at one point in pieces its elements do not connect,
//! [`crate::mesh::coincident`]) is an error naming the two tags and the
//! point; errors name the file and the group or element, the scene field
//! is added by the caller.

use std::collections::{HashMap, HashSet};

use super::SourceDim;
use crate::ids::NodeId;
use crate::material::Material;
use crate::mesh::coincident::falls_apart;
use crate::mesh::gmsh::Msh;
use crate::mesh::volume::Face;
use crate::mesh::{Mesh, MeshError};
use crate::model::Dim;
use crate::scene::{Scene, SceneError};

/// The bodies of a scene that come from its `[mesh]` file.
pub(in crate::scene) struct MeshFile<const D: usize> {
    msh: Msh<D>,
    /// The mesh node of each of the file's nodes (dense index), once its
    /// body is added.
    node_of: Vec<Option<NodeId>>,
    /// The mesh body of each of the file's nodes that belongs to one.
    body_of: Vec<Option<usize>>,
    /// The mesh body of each element added, by the element's tag.
    element_body: HashMap<u64, usize>,
}

impl<const D: usize> MeshFile<D> {
    /// The source of the file's mesh `msh`.
    pub(super) fn new(msh: Msh<D>) -> MeshFile<D> {
        let n = msh.nodes().len();
        MeshFile {
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

    /// Appends the scene's `body[i]`, the physical surface (2D) or volume
    /// (3D) `group` (default: its `name`), with its checked `material`;
    /// returns the mesh body.
    pub(super) fn add_body(
        &mut self,
        scene: &Scene,
        mesh: &mut Mesh<D>,
        i: usize,
        material: Material,
    ) -> Result<usize, SceneError>
    where
        Dim<D>: SourceDim<D>,
    {
        let b = &scene.bodies[i];
        let f = format!("body[{i}]");
        let (group, field) = match &b.group {
            Some(g) => (g.as_str(), format!("{f}.group")),
            None => (b.name.as_str(), format!("{f}.name")),
        };
        let what = <Dim<D> as SourceDim<D>>::BODY;
        let msh = &self.msh;
        let file = msh.file().display();
        let elements = <Dim<D> as SourceDim<D>>::elements(msh, group)
            .map_err(|e| scene.invalid(&field, e.to_string()))?;
        // the body's nodes: those of its elements, in the file's order
        let mut nodes: Vec<usize> = elements
            .iter()
            .flat_map(|(_, e)| e.nodes().to_vec())
            .collect();
        nodes.sort_unstable();
        nodes.dedup();
        if let Some(&n) = nodes.iter().find(|&&n| self.body_of[n].is_some()) {
            let other = self.body_of[n].map_or("", |o| mesh.bodies[o].name.as_str());
            return Err(scene.invalid(
                &field,
                format!(
                    "{file}: physical {what} `{group}` shares node {} with body `{other}`; bodies share no nodes (give each body its own nodes, e.g. separate {what}s that only touch)",
                    self.tag(n)
                ),
            ));
        }
        let local: HashMap<usize, usize> = nodes.iter().enumerate().map(|(k, &n)| (n, k)).collect();
        let coords: Vec<[f64; D]> = nodes.iter().map(|&n| msh.nodes()[n]).collect();
        let conn: Vec<_> = elements
            .iter()
            .map(|(_, e)| e.map_nodes(|n| local[&n]))
            .collect();
        let local_elements: Vec<&[usize]> = conn.iter().map(|e| e.nodes()).collect();
        if let Some(f) = falls_apart(&coords, &local_elements) {
            let at: Vec<String> = coords[f.a].iter().map(|c| format!("{c}")).collect();
            return Err(scene.invalid(
                &field,
                format!(
                    "{file}: physical {what} `{group}` falls apart: nodes {} and {} sit at the same point ({}) but are different nodes, so the elements on either side are not connected (the body is in {} pieces); merge the duplicate nodes in Gmsh (`Coherence Mesh;` in a .geo file, `gmsh.model.mesh.removeDuplicateNodes()` in the API) or make the pieces separate bodies",
                    self.tag(nodes[f.a]),
                    self.tag(nodes[f.b]),
                    at.join(", "),
                    f.pieces
                ),
            ));
        }
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
                        "{file}: element {} of physical {what} `{group}` is inverted or degenerate ({kind}, detJ0 = {det_j0:e}){}",
                        elements[element - elem0].0,
                        <Dim<D> as SourceDim<D>>::INVERTED
                    ),
                ),
                e => scene.invalid(&field, format!("{file}: {e}")),
            })?;
        for (k, &n) in nodes.iter().enumerate() {
            self.node_of[n] = Some(NodeId::new(node0 + k));
            self.body_of[n] = Some(body);
        }
        for (tag, _) in &elements {
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
}

impl<const D: usize> MeshFile<D> {
    /// The mesh nodes of the physical group `group` (a point or curve; in
    /// 3D also a surface), ascending.
    pub(super) fn group_nodes(&self, group: &str) -> Result<Vec<NodeId>, String> {
        let nodes = self.msh.group_nodes(group).map_err(|e| e.to_string())?;
        let mut nodes = self.mesh_nodes(group, &nodes)?;
        nodes.sort_unstable();
        Ok(nodes)
    }
}

impl MeshFile<2> {
    /// The physical curve `group` as a face of one body: the body and the
    /// segments, oriented and chained counter-clockwise around it (module
    /// docs).
    pub(in crate::scene) fn group_face(
        &self,
        group: &str,
    ) -> Result<(usize, Vec<[NodeId; 2]>), String> {
        let segments = self.msh.curve_segments(group).map_err(|e| e.to_string())?;
        let file = self.msh.file().display();
        let not_on_boundary = |[a, b]: [usize; 2], why: &str| {
            format!(
                "{file}: physical curve `{group}` is not on the boundary of a body: its segment from node {} to node {} {why}",
                self.tag(a),
                self.tag(b)
            )
        };
        // every edge of an element of a body, directed as the element runs
        let edges: HashSet<(usize, usize)> = self
            .msh
            .elements()
            .iter()
            .filter(|e| self.element_body.contains_key(&e.tag))
            .flat_map(|e| {
                let n = e.nodes();
                (0..n.len()).map(move |k| (n[k], n[(k + 1) % n.len()]))
            })
            .collect();
        let mut body = None;
        let mut oriented = Vec::with_capacity(segments.len());
        for [a, b] in segments {
            let forward = edges.contains(&(a, b));
            let backward = edges.contains(&(b, a));
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
        Ok((body, segments))
    }

    /// The segments of the physical curve `group` in the file's order and
    /// direction.
    pub(super) fn group_segments(&self, group: &str) -> Result<Vec<[NodeId; 2]>, String> {
        let segments = self.msh.curve_segments(group).map_err(|e| e.to_string())?;
        segments
            .iter()
            .map(|s| {
                let n = self.mesh_nodes(group, s)?;
                Ok([n[0], n[1]])
            })
            .collect()
    }
}

impl MeshFile<3> {
    /// The physical surface `group` as faces of one body: the body and the
    /// faces (mesh nodes), each counter-clockwise seen from outside its
    /// owning element, in file order (module docs).
    pub(in crate::scene) fn group_faces(
        &self,
        group: &str,
    ) -> Result<(usize, Vec<Face<NodeId>>), String> {
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
