//! The memory check of a scene before its model is built
//! ([`crate::memory`] has the estimate): the equations of its block bodies,
//! from the scene alone (no mesh is allocated).

use crate::linear::LinearSolverKind;
use crate::memory::{MemoryError, available, check};

use super::{MAX_BLOCK_ELEMENTS, Scene};

/// The equations of a scene's block bodies: the dofs of their nodes,
/// `2 (nx rx + 1)(ny ry + 1)` per 2D block, `3 (nx rx + 1)(ny ry + 1)(nz
/// rz + 1)` per 3D block (one with `nz`), `[refine]` factors included.
/// Bodies that are not complete blocks count nothing here, nor do blocks
/// above the block limit ([`MAX_BLOCK_ELEMENTS`] elements):
/// building the model refuses those with an error naming the body.
pub fn scene_equations(scene: &Scene) -> u64 {
    let (rx, ry) = (scene.refine.x as u64, scene.refine.y as u64);
    let rz = scene.refine.z_factor() as u64;
    let limit = MAX_BLOCK_ELEMENTS as u64;
    scene
        .bodies
        .iter()
        .filter_map(|b| {
            let nx = (b.nx? as u64).checked_mul(rx)?;
            let ny = (b.ny? as u64).checked_mul(ry)?;
            let Some(nz) = b.nz else {
                nx.checked_mul(ny).filter(|&n| n <= limit)?;
                // nx ny <= limit, so (nx + 1)(ny + 1) <= 2 limit + 2: no overflow
                return Some(2 * (nx + 1) * (ny + 1));
            };
            let nz = (nz as u64).checked_mul(rz)?;
            nx.checked_mul(ny)?
                .checked_mul(nz)
                .filter(|&n| n <= limit)?;
            // nx ny nz <= limit, so (nx + 1)(ny + 1)(nz + 1) <= 8 limit
            Some(3 * (nx + 1) * (ny + 1) * (nz + 1))
        })
        .fold(0, u64::saturating_add)
}

/// [`check`] on a scene's block bodies, before its model is built
/// ([`Scene::build_model`] calls it first, so loading a scene checks it
/// too). The linear solver may still be chosen after loading, so the
/// estimate is the LDLᵀ's, the smaller one.
pub fn check_scene(scene: &Scene) -> Result<(), MemoryError> {
    check(scene_equations(scene), LinearSolverKind::Ldlt, available())
}
