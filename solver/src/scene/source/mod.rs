//! Mesh sources: where a scene's bodies come from.
//!
//! A scene's [`MeshSource<D>`] makes its bodies and answers the selections
//! whose meaning depends on how a body was made: a block body's sides,
//! and the physical groups of the `[mesh]` file (nodes; facets: curves in
//! 2D, surfaces in 3D). It is [`Sources`] in 2D and [`Solids`] in 3D
//! (`solid.rs`).
//!
//! In 2D, a [`BodySource`] makes the bodies it owns. There are two,
//! asked in this order who owns a body:
//!
//! * [`Blocks`] (`blocks.rs`): a `[[body]]` with the block fields
//!   (`origin`, `size`, `nx`, `ny`) is a structured rectangular block and
//!   its faces are its four sides;
//! * [`Gmsh`] (`gmsh.rs`): a `[[body]]` without them is a physical surface
//!   of the `[mesh]` file; its physical curves and points are faces, node
//!   groups and loaded curves, asked for by name.
//!
//! Selection by reference coordinates does not depend on the source and
//! stays with the mesh ([`Mesh::select_nodes_at`]). Questions by group name go
//! to every source in turn; the first that knows groups answers (the
//! blocks know none: the trait's defaults return `None`).
//!
//! Invariants every source keeps:
//!
//! * it appends each body to the mesh with fresh nodes (through
//!   [`Mesh::add_body`] or [`Mesh::add_block`]), so bodies share no nodes and
//!   the mesh's bodies are in the scene's `[[body]]` order;
//! * the faces it returns are chains of 2-node segments (global node
//!   indices) ordered counter-clockwise around their body, so that the
//!   outward normal of a segment with tangent `t` is `(t.y, -t.x)/|t|`.

use super::{Scene, SceneError, SideName};
use crate::ids::NodeId;
use crate::material::Material;
use crate::mesh::gmsh::MshMesh;
use crate::mesh::{Mesh, Side};
use crate::model::{Dim, FacetOf, SurfaceDim};

mod blocks;
mod blocks3d;
mod gmsh;
mod gmsh3d;
mod solid;

pub(super) use blocks::Blocks;
pub(crate) use blocks::MAX_BLOCK_ELEMENTS;
pub(super) use blocks::is_block;
pub(super) use gmsh::Gmsh;
pub(super) use solid::Solids;

/// The path of the mesh file `file` of the scene read from `origin`:
/// relative to the scene file's directory.
pub(super) fn resolve(origin: &str, file: &str) -> std::path::PathBuf {
    let file = std::path::Path::new(file);
    if file.is_absolute() {
        return file.to_owned();
    }
    match std::path::Path::new(origin).parent() {
        Some(dir) => dir.join(file),
        None => file.to_owned(),
    }
}

/// A physical curve on the boundary of one body: the mesh body's index and
/// its segments, counter-clockwise around the body.
pub(super) struct GroupFace {
    /// The mesh body whose boundary the curve is.
    pub(super) body: usize,
    /// The segments, oriented and chained counter-clockwise.
    pub(super) segments: Vec<[NodeId; 2]>,
}

/// A scene's mesh sources in dimension `D` (module docs).
pub(in crate::scene) trait MeshSource<const D: usize> {
    /// Appends the scene's `body[index]` with its (checked) `material` to
    /// `mesh` and returns the new body's index. Errors name the body's
    /// fields (`body[index].nx`, ...).
    fn add_body(
        &mut self,
        mesh: &mut Mesh<D>,
        index: usize,
        material: Material,
    ) -> Result<usize, SceneError>;

    /// The facets of `side` of the mesh body `body`, outward: `Ok(None)`
    /// if the body is not a block body, `Err` (a message) if `side` is
    /// not a side of the dimension's blocks.
    fn side(
        &self,
        mesh: &Mesh<D>,
        body: usize,
        side: SideName,
    ) -> Result<Option<Vec<FacetOf<D>>>, String>
    where
        Dim<D>: SurfaceDim<D>;

    /// The physical group `group` (a curve in 2D, a surface in 3D) as
    /// facets of one body, outward, and that body; errors name `field`.
    fn group_facets(
        &self,
        field: &str,
        group: &str,
    ) -> Result<(usize, Vec<FacetOf<D>>), SceneError>
    where
        Dim<D>: SurfaceDim<D>;

    /// The mesh nodes of the physical group `group`, ascending; errors
    /// name `field`.
    fn group_nodes(&self, field: &str, group: &str) -> Result<Vec<NodeId>, SceneError>;
}

impl MeshSource<2> for Sources<'_> {
    fn add_body(
        &mut self,
        mesh: &mut Mesh,
        index: usize,
        material: Material,
    ) -> Result<usize, SceneError> {
        Sources::add_body(self, mesh, index, material)
    }

    fn side(
        &self,
        mesh: &Mesh,
        body: usize,
        side: SideName,
    ) -> Result<Option<Vec<[NodeId; 2]>>, String> {
        let side = side
            .side_2d()
            .ok_or_else(|| format!("`{}` is a side of a 3D block", side.name()))?;
        Ok(self.face(mesh, body, side))
    }

    fn group_facets(
        &self,
        field: &str,
        group: &str,
    ) -> Result<(usize, Vec<[NodeId; 2]>), SceneError> {
        let face = self.group_face(field, group)?;
        Ok((face.body, face.segments))
    }

    fn group_nodes(&self, field: &str, group: &str) -> Result<Vec<NodeId>, SceneError> {
        Sources::group_nodes(self, field, group)
    }
}

/// A way of making some of a 2D scene's bodies.
pub(super) trait BodySource {
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

    /// The physical curve `group` as a face of one body (counter-clockwise
    /// around it); `None` if this source knows no groups, `Err` (a message)
    /// if the group is unknown, of the wrong dimension or not on one body's
    /// boundary.
    fn group_face(&self, _group: &str) -> Option<Result<GroupFace, String>> {
        None
    }

    /// The mesh nodes of the physical curve or point `group`, ascending;
    /// `None` if this source knows no groups.
    fn group_nodes(&self, _group: &str) -> Option<Result<Vec<NodeId>, String>> {
        None
    }

    /// The segments of the physical curve `group` in the file's order and
    /// direction; `None` if this source knows no groups.
    fn group_segments(&self, _group: &str) -> Option<Result<Vec<[NodeId; 2]>, String>> {
        None
    }
}

/// A scene's mesh sources, and which one made each body of the mesh.
pub(super) struct Sources<'s> {
    scene: &'s Scene,
    sources: Vec<Box<dyn BodySource + 's>>,
    /// The source of each mesh body, by index into `sources`.
    made_by: Vec<usize>,
}

impl<'s> Sources<'s> {
    /// The sources of `scene`, in the order they are asked who owns a body;
    /// `msh` is its `[mesh] file`, read (if it has one).
    pub(super) fn of(scene: &'s Scene, msh: Option<MshMesh>) -> Sources<'s> {
        Sources {
            scene,
            sources: vec![
                Box::new(Blocks::new(scene)),
                Box::new(Gmsh::new(scene, msh)),
            ],
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

impl Sources<'_> {
    /// The first answer of a source that knows groups, or an error for
    /// `field` if none does.
    fn by_group<T>(
        &self,
        field: &str,
        ask: impl Fn(&dyn BodySource) -> Option<Result<T, String>>,
    ) -> Result<T, SceneError> {
        self.sources
            .iter()
            .find_map(|s| ask(s.as_ref()))
            .unwrap_or_else(|| Err("physical groups need a `[mesh] file`".to_owned()))
            .map_err(|m| self.scene.invalid(field, m))
    }

    /// The physical curve `group` as a face (see [`BodySource::group_face`]);
    /// errors name `field`.
    pub(super) fn group_face(&self, field: &str, group: &str) -> Result<GroupFace, SceneError> {
        self.by_group(field, |s| s.group_face(group))
    }

    /// The nodes of the physical curve or point `group`, ascending; errors
    /// name `field`.
    pub(super) fn group_nodes(&self, field: &str, group: &str) -> Result<Vec<NodeId>, SceneError> {
        self.by_group(field, |s| s.group_nodes(group))
    }

    /// The segments of the physical curve `group`, in file order; errors
    /// name `field`.
    pub(super) fn group_segments(
        &self,
        field: &str,
        group: &str,
    ) -> Result<Vec<[NodeId; 2]>, SceneError> {
        self.by_group(field, |s| s.group_segments(group))
    }
}
