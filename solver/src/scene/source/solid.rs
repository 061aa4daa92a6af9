//! The mesh sources of a 3D scene: its 3D blocks ([`super::blocks3d`]) and
//! the physical volumes of its 3D `[mesh]` file ([`super::gmsh3d`]),
//! asked in this order who owns a body (a `[[body]]` with block fields is
//! a block), and the faces and groups that depend on how a body was made:
//! a block's sides, a file's physical surfaces and node groups.
//!
//! Invariants, as for the 2D sources: each body is appended with fresh
//! nodes, in `[[body]]` order; faces are quad4 or tri3 faces of mesh nodes,
//! counter-clockwise seen from outside their body (outward normal `t_1 x
//! t_2`).

use super::gmsh3d::VolumeFile;
use super::{blocks3d, is_block};
use crate::ids::NodeId;
use crate::material::Material;
use crate::mesh::Mesh;
use crate::mesh::block3d::{Block3d, Side3d};
use crate::mesh::gmsh::MshVolumeMesh;
use crate::mesh::volume::Face;
use crate::scene::{Scene, SceneError, SideName};

use super::MeshSource;

/// A 3D scene's mesh sources, and the block of each block body.
pub(in crate::scene) struct Solids<'s> {
    scene: &'s Scene,
    file: Option<VolumeFile>,
    /// Per mesh body: its block and first node, for a block body.
    blocks: Vec<Option<(Block3d, usize)>>,
}

impl<'s> Solids<'s> {
    /// The sources of the 3D `scene` and its `[mesh] file` `msh`, read (if
    /// it has one).
    pub(in crate::scene) fn new(scene: &'s Scene, msh: Option<MshVolumeMesh>) -> Solids<'s> {
        Solids {
            scene,
            file: msh.map(VolumeFile::new),
            blocks: Vec::new(),
        }
    }

    /// Appends the scene's `body[i]` with its checked `material` and
    /// returns the mesh body's index.
    pub(in crate::scene) fn add_body(
        &mut self,
        mesh: &mut Mesh<3>,
        i: usize,
        material: Material,
    ) -> Result<usize, SceneError> {
        let scene = self.scene;
        let f = format!("body[{i}]");
        if is_block(&scene.bodies[i]) {
            let block = blocks3d::block(scene, i)?;
            let node0 = mesh.node_count();
            let body = mesh
                .add_block3d(&scene.bodies[i].name, material, block)
                .map_err(|e| scene.invalid(&f, e.to_string()))?;
            self.blocks.push(Some((block, node0)));
            return Ok(body);
        }
        let Some(file) = &mut self.file else {
            return Err(scene.invalid(
                f,
                "a 3D body needs `origin`, `size`, `nx`, `ny` and `nz` (a block), or a 3D `[mesh] file` whose physical volume it is",
            ));
        };
        let body = file.add_body(scene, mesh, i, material)?;
        self.blocks.push(None);
        Ok(body)
    }

    /// The faces of `side` of the mesh body `body` (mesh nodes), if it is
    /// a block: [`Block3d::side`]'s body-local nodes plus the body's first
    /// node ([`Mesh::add_block3d`] numbers the body so).
    pub(in crate::scene) fn side(&self, body: usize, side: Side3d) -> Option<Vec<Face<NodeId>>> {
        let (block, node0) = (*self.blocks.get(body)?)?;
        let faces = block.side(side).ok()?;
        Some(
            faces
                .into_iter()
                .map(|f| f.map_nodes(|n| NodeId::new(node0 + n)))
                .collect(),
        )
    }

    /// The first answer of the mesh file, or an error for `field` if there
    /// is none.
    fn by_group<T>(
        &self,
        field: &str,
        ask: impl Fn(&VolumeFile) -> Result<T, String>,
    ) -> Result<T, SceneError> {
        match &self.file {
            Some(file) => ask(file).map_err(|m| self.scene.invalid(field, m)),
            None => Err(self
                .scene
                .invalid(field, "physical groups need a `[mesh] file`")),
        }
    }

    /// The physical surface `group` as faces of one body (see
    /// [`VolumeFile::group_faces`]); errors name `field`.
    pub(in crate::scene) fn group_faces(
        &self,
        field: &str,
        group: &str,
    ) -> Result<(usize, Vec<Face<NodeId>>), SceneError> {
        self.by_group(field, |f| f.group_faces(group))
    }

    /// The nodes of the physical group `group`, ascending; errors name
    /// `field`.
    pub(in crate::scene) fn group_nodes(
        &self,
        field: &str,
        group: &str,
    ) -> Result<Vec<NodeId>, SceneError> {
        self.by_group(field, |f| f.group_nodes(group))
    }
}

impl MeshSource<3> for Solids<'_> {
    fn add_body(
        &mut self,
        mesh: &mut Mesh<3>,
        index: usize,
        material: Material,
    ) -> Result<usize, SceneError> {
        Solids::add_body(self, mesh, index, material)
    }

    fn side(
        &self,
        _: &Mesh<3>,
        body: usize,
        side: SideName,
    ) -> Result<Option<Vec<Face<NodeId>>>, String> {
        Ok(Solids::side(self, body, side.side_3d()))
    }

    fn group_facets(
        &self,
        field: &str,
        group: &str,
    ) -> Result<(usize, Vec<Face<NodeId>>), SceneError> {
        self.group_faces(field, group)
    }

    fn group_nodes(&self, field: &str, group: &str) -> Result<Vec<NodeId>, SceneError> {
        Solids::group_nodes(self, field, group)
    }
}
