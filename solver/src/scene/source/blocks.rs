//! The structured-block source: each `[[body]]` with `origin`, `size`, `nx`
//! and `ny` (any of them: the others are then missing) becomes a [`Block`] of `nx * refine.x` by `ny * refine.y`
//! elements ([`crate::mesh::block`] has the numbering), and its faces are
//! the block's sides. A block has at most [`MAX_BLOCK_ELEMENTS`] elements
//! (refinement included), so that no scene value overflows the counts or
//! asks for more memory than a machine has.

use super::BodySource;
use crate::ids::NodeId;
use crate::material::Material;
use crate::mesh::{Block, Mesh, Side};
use crate::scene::{BodySpec, Scene, SceneError};

/// The most elements one block may have (`nx ny` times the refinement
/// factors); larger blocks are an error naming the body.
pub const MAX_BLOCK_ELEMENTS: usize = 10_000_000;

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

impl BodySource for Blocks<'_> {
    /// A `[[body]]` with any of the block fields is a block.
    fn owns(&self, index: usize) -> bool {
        is_block(&self.scene.bodies[index])
    }

    fn add_body(
        &mut self,
        mesh: &mut Mesh,
        i: usize,
        material: Material,
    ) -> Result<usize, SceneError> {
        let b = &self.scene.bodies[i];
        let f = format!("body[{i}]");
        let missing = |k: &str| {
            self.scene.invalid(
                format!("{f}.{k}"),
                format!("missing field `{k}` (a block body needs `origin`, `size`, `nx` and `ny`)"),
            )
        };
        if b.group.is_some() {
            return Err(self.scene.invalid(
                format!("{f}.group"),
                "a block body (`origin`, `size`, `nx`, `ny`) has no `group`",
            ));
        }
        // a 2D scene's blocks have two numbers in both (`check_dimension`)
        let two = |c: Option<crate::scene::Coords>, k: &str| {
            c.ok_or_else(|| missing(k))?.point::<2>().ok_or_else(|| {
                self.scene
                    .invalid(format!("{f}.{k}"), "needs two numbers [x, y] in a 2D block")
            })
        };
        let origin = two(b.origin, "origin")?;
        let size = two(b.size, "size")?;
        let nx = b.nx.ok_or_else(|| missing("nx"))?;
        let ny = b.ny.ok_or_else(|| missing("ny"))?;
        for (k, v) in [("nx", nx), ("ny", ny)] {
            if v == 0 {
                return Err(self.scene.invalid(format!("{f}.{k}"), "must be at least 1"));
            }
        }
        if !(size[0] > 0.0 && size[1] > 0.0 && size.iter().all(|v| v.is_finite())) {
            return Err(self.scene.invalid(
                format!("{f}.size"),
                "width and height must be positive and finite",
            ));
        }
        if !origin.iter().all(|v| v.is_finite()) {
            return Err(self.scene.invalid(format!("{f}.origin"), "must be finite"));
        }
        if !(0..2).all(|k| (origin[k] + size[k]).is_finite()) {
            return Err(self.scene.invalid(
                format!("{f}.size"),
                "the far corner origin + size is not finite",
            ));
        }
        let (nx, ny) = (
            nx.checked_mul(self.scene.refine.x),
            ny.checked_mul(self.scene.refine.y),
        );
        let Some((nx, ny)) = nx
            .zip(ny)
            .filter(|&(nx, ny)| nx.checked_mul(ny).is_some_and(|n| n <= MAX_BLOCK_ELEMENTS))
        else {
            return Err(self.scene.invalid(
                f.clone(),
                format!(
                    "more than {MAX_BLOCK_ELEMENTS} elements (nx x ny times the [refine] factors)"
                ),
            ));
        };
        let block = Block {
            origin,
            size,
            nx,
            ny,
        };
        mesh.add_block(&b.name, material, block)
            .map_err(|e| self.scene.invalid(f.clone(), e.to_string()))
    }

    fn face(&self, mesh: &Mesh, body: usize, side: Side) -> Option<Vec<[NodeId; 2]>> {
        mesh.block_side(body, side)
    }
}

/// Whether `body` gives any of the block fields (`origin`, `size`, `nx`,
/// `ny`, `nz`).
pub(in crate::scene) fn is_block(body: &BodySpec) -> bool {
    body.origin.is_some()
        || body.size.is_some()
        || body.nx.is_some()
        || body.ny.is_some()
        || body.nz.is_some()
}
