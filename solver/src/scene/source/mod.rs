//! Mesh sources: where a scene's bodies come from.
//!
//! A [`MeshSource`] makes the bodies it owns and answers the selections
//! whose meaning depends on how a body was made. Today there is one source,
//! [`Blocks`]: every `[[body]]` is a structured rectangular block
//! (`origin`, `size`, `nx`, `ny`) and its faces are its four sides.
//! Selection by reference coordinates does not depend on the source and
//! stays with the mesh ([`Mesh::select_nodes`]).
//!
//! A reader of mesh files (`[mesh] file = ...`, bodies, curves and points
//! by physical name) is another source in a file next to `blocks.rs`:
//! [`Sources::of`] lists it after the blocks and it owns the bodies that
//! are not blocks; it appends each through [`Mesh::add_body`], keeping the
//! map from the file's node tags to mesh nodes, and answers faces and node
//! groups by name (a trait method each, with a default of `None` so the
//! blocks need not change), orienting each edge by the element that owns
//! it.
//!
//! Invariants every source keeps:
//!
//! * it appends each body to the mesh with fresh nodes (through
//!   [`Mesh::add_body`] or [`Mesh::add_block`]), so bodies share no nodes and
//!   the mesh's bodies are in the scene's `[[body]]` order;
//! * the faces it returns are chains of 2-node segments (global node
//!   indices) ordered counter-clockwise around their body, so that the
//!   outward normal of a segment with tangent `t` is `(t.y, -t.x)/|t|`.

use super::{Scene, SceneError};
use crate::ids::NodeId;
use crate::material::Material;
use crate::mesh::{Mesh, Side};

mod blocks;

pub(super) use blocks::Blocks;

/// A way of making some of a scene's bodies.
pub(super) trait MeshSource {
    /// Whether this source makes the scene's `body[index]`.
    fn owns(&self, index: usize) -> bool;

    /// Appends the scene's `body[index]` with its (checked) `material` to
    /// `mesh` and returns the new body's index. Errors name the body's
    /// fields (`body[index].nx`, ...).
    fn add_body(
        &mut self,
        mesh: &mut Mesh,
        index: usize,
        material: Material,
    ) -> Result<usize, SceneError>;

    /// The segments of `side` of the mesh body `body`, which this source
    /// made, counter-clockwise around the body; `None` if the body has no
    /// such face.
    fn face(&self, mesh: &Mesh, body: usize, side: Side) -> Option<Vec<[NodeId; 2]>>;
}

/// A scene's mesh sources, and which one made each body of the mesh.
pub(super) struct Sources<'s> {
    scene: &'s Scene,
    sources: Vec<Box<dyn MeshSource + 's>>,
    /// The source of each mesh body, by index into `sources`.
    made_by: Vec<usize>,
}

impl<'s> Sources<'s> {
    /// The sources of `scene`, in the order they are asked who owns a body.
    pub(super) fn of(scene: &'s Scene) -> Sources<'s> {
        Sources {
            scene,
            sources: vec![Box::new(Blocks::new(scene))],
            made_by: Vec::new(),
        }
    }

    /// Appends the scene's `body[index]` through the first source that owns
    /// it and returns the mesh body's index.
    pub(super) fn add_body(
        &mut self,
        mesh: &mut Mesh,
        index: usize,
        material: Material,
    ) -> Result<usize, SceneError> {
        let s = self
            .sources
            .iter()
            .position(|s| s.owns(index))
            .ok_or_else(|| {
                self.scene
                    .invalid(format!("body[{index}]"), "no mesh source makes this body")
            })?;
        let body = self.sources[s].add_body(mesh, index, material)?;
        // every body comes through here, one at a time
        debug_assert_eq!(body, self.made_by.len());
        self.made_by.push(s);
        Ok(body)
    }

    /// The segments of `side` of the mesh body `body`, from the source that
    /// made it; `None` if it has no such face.
    pub(super) fn face(&self, mesh: &Mesh, body: usize, side: Side) -> Option<Vec<[NodeId; 2]>> {
        let s = *self.made_by.get(body)?;
        self.sources.get(s)?.face(mesh, body, side)
    }
}
