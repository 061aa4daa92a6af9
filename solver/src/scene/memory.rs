//! The memory check of a scene before its model is built
//! ([`crate::memory`] has the estimate): the equations of its block bodies,
//! from the scene alone (no mesh is allocated).

use crate::linear::LinearSolverKind;
use crate::memory::{MemoryError, MeshFamily, available, check};

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
/// too): 3D blocks as hexahedra, 2D blocks as planar elements. The linear
/// solver may still be chosen after loading, so the estimate is the
/// smallest of the solvers compiled in.
pub fn check_scene(scene: &Scene) -> Result<(), MemoryError> {
    check_scene_within(scene, available())
}

/// [`check_scene`] against `available` bytes (`None`: unknown, accepted).
pub fn check_scene_within(scene: &Scene, available: Option<u64>) -> Result<(), MemoryError> {
    let family = if scene.bodies.iter().any(|b| b.nz.is_some()) {
        MeshFamily::Hexahedra
    } else {
        MeshFamily::Planar
    };
    let equations = scene_equations(scene);
    let smallest = LinearSolverKind::ALL
        .iter()
        .copied()
        .min_by_key(|&k| crate::memory::estimate(equations, family, k))
        .unwrap_or(LinearSolverKind::Ldlt);
    check(equations, family, smallest, available)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::memory::estimate;

    /// A 3D block of `n x n x n` hexahedra (scene text).
    fn cube(n: usize) -> Scene {
        let text = format!(
            r#"
[material]
young = 1000.0
poisson = 0.3

[[body]]
name = "block"
origin = [0.0, 0.0, 0.0]
size = [1.0, 1.0, 1.0]
nx = {n}
ny = {n}
nz = {n}

[[fix]]
z = 0.0

[loading]
load_factor_end = 1.0
steps = [1]
"#
        );
        super::super::error::parse(&text, "cube.toml").unwrap()
    }

    /// A 3D block scene is estimated as hexahedra with the smallest figure
    /// of the solvers compiled in, refused one byte below its estimate and
    /// accepted at it; the 100^3 block the 2D figure let start (3.1e6
    /// equations) is refused within 8 GiB (with any solver), before any
    /// mesh is allocated.
    #[test]
    fn a_3d_block_scene_is_refused_at_the_edge_of_its_estimate() {
        let scene = cube(20);
        let n = scene_equations(&scene);
        assert_eq!(n, 3 * 21 * 21 * 21);
        let needed = LinearSolverKind::ALL
            .iter()
            .map(|&k| estimate(n, MeshFamily::Hexahedra, k))
            .min()
            .unwrap();
        assert!(check_scene_within(&scene, Some(needed)).is_ok());
        let err = check_scene_within(&scene, Some(needed - 1)).unwrap_err();
        assert_eq!(err.family, MeshFamily::Hexahedra);
        assert_eq!(err.needed, needed);

        let big = cube(100);
        let err = check_scene_within(&big, Some(8 << 30)).unwrap_err();
        let msg = err.to_string();
        assert!(
            msg.starts_with("not enough memory: 3090903 equations of 3D hexahedra need at least ")
                && msg.contains("but only 8192 MiB are available"),
            "{msg}"
        );
    }
}
