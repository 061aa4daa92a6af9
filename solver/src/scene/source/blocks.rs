//! The structured-block source: each `[[body]]` with `origin`, `size`, `nx`
//! and `ny` becomes a [`Block`] of `nx * refine.x` by `ny * refine.y`
//! elements ([`crate::mesh::block`] has the numbering), and its faces are
//! the block's sides.

use super::MeshSource;
use crate::ids::NodeId;
use crate::material::Material;
use crate::mesh::{Block, Mesh, Side};
use crate::scene::{Scene, SceneError};

/// The structured rectangular blocks of a scene.
pub(in crate::scene) struct Blocks<'s> {
    scene: &'s Scene,
}

impl<'s> Blocks<'s> {
    /// The blocks of `scene`.
    pub(in crate::scene) fn new(scene: &'s Scene) -> Blocks<'s> {
        Blocks { scene }
    }
}

impl MeshSource for Blocks<'_> {
    /// Every `[[body]]` is a block.
    fn owns(&self, _index: usize) -> bool {
        true
    }

    fn add_body(
        &mut self,
        mesh: &mut Mesh,
        i: usize,
        material: Material,
    ) -> Result<usize, SceneError> {
        let b = &self.scene.bodies[i];
        let f = format!("body[{i}]");
        for (k, v) in [("nx", b.nx), ("ny", b.ny)] {
            if v == 0 {
                return Err(self.scene.invalid(format!("{f}.{k}"), "must be at least 1"));
            }
        }
        if !(b.size[0] > 0.0 && b.size[1] > 0.0 && b.size.iter().all(|v| v.is_finite())) {
            return Err(self.scene.invalid(
                format!("{f}.size"),
                "width and height must be positive and finite",
            ));
        }
        if !b.origin.iter().all(|v| v.is_finite()) {
            return Err(self.scene.invalid(format!("{f}.origin"), "must be finite"));
        }
        let block = Block {
            origin: b.origin,
            size: b.size,
            nx: b.nx * self.scene.refine.x,
            ny: b.ny * self.scene.refine.y,
        };
        mesh.add_block(&b.name, material, block)
            .map_err(|e| self.scene.invalid(f.clone(), e.to_string()))
    }

    fn face(&self, mesh: &Mesh, body: usize, side: Side) -> Option<Vec<[NodeId; 2]>> {
        mesh.block_side(body, side)
    }
}
