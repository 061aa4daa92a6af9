//! Mesh sources: where a scene's bodies come from, in either dimension.
//!
//! A scene's [`Sources<D>`] makes its bodies and answers the selections
//! whose meaning depends on how a body was made: a block body's sides,
//! and the physical groups of the `[mesh]` file (nodes; facets: curves in
//! 2D, surfaces in 3D). Who makes a body:
//!
//! * a block (`blocks.rs`): a `[[body]]` with any of the block fields
//!   (`origin`, `size`, `nx`, `ny`, and `nz` in 3D) is a structured block
//!   and its facets are its sides;
//! * the mesh file (`gmsh.rs`): a `[[body]]` without them is a physical
//!   surface (2D) or volume (3D) of the `[mesh] file`; its physical groups
//!   are facets, node groups and (in 2D) loaded curves, asked for by name.
//!
//! A block and its sides are [`crate::mesh::Block`]'s, one generator for
//! both dimensions (its dimension's part through
//! [`crate::mesh::BlockDim`]); the mesh remembers each block body's block.
//! What else differs between the dimensions (which file elements make a
//! body, a group's facets, the words of messages) comes from
//! [`SourceDim`], implemented for `Dim<2>` in `planar.rs` and for `Dim<3>`
//! in `solid.rs`.
//!
//! Selection by reference coordinates does not depend on the source and
//! stays with the mesh ([`Mesh::select_nodes_at`]).
//!
//! Invariants:
//!
//! * each body is appended to the mesh with fresh nodes, so bodies share
//!   no nodes and the mesh's bodies are in the scene's `[[body]]` order;
//! * the facets returned are outward: 2-node segments (global node
//!   indices) ordered counter-clockwise around their body in 2D, so that
//!   the outward normal of a segment with tangent `t` is `(t.y, -t.x)/|t|`;
//!   tri3 and quad4 faces counter-clockwise seen from outside their body
//!   in 3D (outward normal `t_1 x t_2`).

use super::{Scene, SceneError};
use crate::dim::SpaceDim;
use crate::element::Element;
use crate::ids::NodeId;
use crate::material::Material;
use crate::mesh::gmsh::{AnyMsh, Msh, MshError};
use crate::mesh::{BlockDim, Mesh, Side};
use crate::model::{Dim, FacetOf, SurfaceDim};

mod blocks;
mod gmsh;

pub(crate) use blocks::MAX_BLOCK_ELEMENTS;
pub(super) use blocks::is_block;
pub(super) use gmsh::MeshFile;

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

/// What the mesh sources take from the dimension (module docs); a block's
/// side is made of the dimension's contact facets.
pub(in crate::scene) trait SourceDim<const D: usize>:
    SpaceDim<D> + BlockDim<D, Facet<NodeId> = <Self as SurfaceDim<D>>::Facet>
{
    /// How many numbers a point has, in words (`two`, `three`).
    const NUMBERS: &'static str;
    /// What a physical group of facets is (`curve`, `surface`).
    const GROUP: &'static str;
    /// What a body of the mesh file is (a physical `surface`, `volume`).
    const BODY: &'static str;
    /// How messages name the dimension's block bodies and mesh files:
    /// empty in 2D, `3D ` in 3D.
    const PREFIX: &'static str;
    /// What must be positive and finite in a block's `size`.
    const EXTENTS: &'static str;
    /// What the message for an inverted element of the mesh file adds.
    const INVERTED: &'static str;

    /// The mesh file of a scene of this dimension, out of the file read;
    /// an error naming `mesh.file` if it is of the other dimension.
    fn mesh_file(scene: &Scene, file: AnyMsh) -> Result<Msh<D>, SceneError>;

    /// The elements (with their tags) of the file's physical surface (2D)
    /// or volume (3D) `group`, in file order and node order.
    fn elements(msh: &Msh<D>, group: &str) -> Result<Vec<(u64, Element<usize>)>, MshError>;

    /// The physical group `group` of `file` as facets of one body, outward,
    /// and that body.
    fn group_facets(file: &MeshFile<D>, group: &str) -> Result<(usize, Vec<FacetOf<D>>), String>
    where
        Dim<D>: SurfaceDim<D>;
}

/// A scene's mesh sources in dimension `D` (module docs).
pub(in crate::scene) struct Sources<'s, const D: usize>
where
    Dim<D>: SourceDim<D>,
{
    scene: &'s Scene,
    file: Option<MeshFile<D>>,
}

impl<'s, const D: usize> Sources<'s, D>
where
    Dim<D>: SourceDim<D>,
{
    /// The sources of `scene` and its `[mesh] file`, read (if it has one).
    pub(in crate::scene) fn new(
        scene: &'s Scene,
        file: Option<AnyMsh>,
    ) -> Result<Sources<'s, D>, SceneError> {
        let file = file
            .map(|f| <Dim<D> as SourceDim<D>>::mesh_file(scene, f))
            .transpose()?;
        Ok(Sources {
            scene,
            file: file.map(MeshFile::new),
        })
    }

    /// Appends the scene's `body[i]` with its checked `material` and
    /// returns the mesh body's index. Errors name the body's fields
    /// (`body[i].nx`, ...).
    pub(in crate::scene) fn add_body(
        &mut self,
        mesh: &mut Mesh<D>,
        i: usize,
        material: Material,
    ) -> Result<usize, SceneError> {
        let scene = self.scene;
        if is_block(&scene.bodies[i]) {
            return blocks::add_block::<D>(scene, mesh, i, material);
        }
        let Some(file) = &mut self.file else {
            return Err(scene.invalid(
                format!("body[{i}]"),
                format!(
                    "a {}body needs {} (a block), or a {}`[mesh] file` whose physical {} it is",
                    <Dim<D> as SourceDim<D>>::PREFIX,
                    blocks::fields::<D>(", ", " and "),
                    <Dim<D> as SourceDim<D>>::PREFIX,
                    <Dim<D> as SourceDim<D>>::BODY,
                ),
            ));
        };
        file.add_body(scene, mesh, i, material)
    }

    /// The facets of `side` of the mesh body `body`, outward
    /// ([`Mesh::block_side`]): `Ok(None)` if the body is not a block body,
    /// `Err` (a message) if `side` is not a side of the dimension's blocks
    /// (only 2D blocks lack sides: `front` and `back`).
    pub(in crate::scene) fn side(
        &self,
        mesh: &Mesh<D>,
        body: usize,
        side: Side,
    ) -> Result<Option<Vec<FacetOf<D>>>, String> {
        if side.axis::<D>().is_none() {
            return Err(format!("`{}` is a side of a 3D block", side.name()));
        }
        Ok(mesh.block_side(body, side))
    }

    /// The answer of the mesh file, or an error for `field` if there is
    /// none.
    pub(in crate::scene) fn by_group<T>(
        &self,
        field: &str,
        ask: impl Fn(&MeshFile<D>) -> Result<T, String>,
    ) -> Result<T, SceneError> {
        match &self.file {
            Some(file) => ask(file).map_err(|m| self.scene.invalid(field, m)),
            None => Err(self
                .scene
                .invalid(field, "physical groups need a `[mesh] file`")),
        }
    }

    /// The physical group `group` (a curve in 2D, a surface in 3D) as
    /// facets of one body, outward, and that body; errors name `field`.
    pub(in crate::scene) fn group_facets(
        &self,
        field: &str,
        group: &str,
    ) -> Result<(usize, Vec<FacetOf<D>>), SceneError> {
        self.by_group(field, |f| <Dim<D> as SourceDim<D>>::group_facets(f, group))
    }

    /// The mesh nodes of the physical group `group`, ascending; errors
    /// name `field`.
    pub(in crate::scene) fn group_nodes(
        &self,
        field: &str,
        group: &str,
    ) -> Result<Vec<NodeId>, SceneError> {
        self.by_group(field, |f| f.group_nodes(group))
    }
}

impl Sources<'_, 2> {
    /// The segments of the physical curve `group`, in file order; errors
    /// name `field`.
    pub(in crate::scene) fn group_segments(
        &self,
        field: &str,
        group: &str,
    ) -> Result<Vec<[NodeId; 2]>, SceneError> {
        self.by_group(field, |f| f.group_segments(group))
    }
}
