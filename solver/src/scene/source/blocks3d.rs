//! The 3D block source: a `[[body]]` of a 3D scene with `origin`, `size`,
//! `nx`, `ny` and `nz` (three numbers in `origin` and `size`) becomes a
//! [`Block3d`] of `nx rx` by `ny ry` by `nz rz` hexahedra (`[refine]`'s
//! factors; [`crate::mesh::block3d`] has the numbering), and its faces are
//! the block's six sides, quad4 faces counter-clockwise seen from outside.
//! A block has at most [`MAX_BLOCK_ELEMENTS`] elements, refinement
//! included.

use super::MAX_BLOCK_ELEMENTS;
use crate::mesh::block3d::Block3d;
use crate::scene::{BodySpec, Scene, SceneError};

/// The block of the scene's 3D `body[i]`, checked: every field given, at
/// least one element along each axis, a positive finite size, a finite
/// origin and far corner, at most [`MAX_BLOCK_ELEMENTS`] elements. Errors
/// name the field.
pub(super) fn block(scene: &Scene, i: usize) -> Result<Block3d, SceneError> {
    let b: &BodySpec = &scene.bodies[i];
    let f = format!("body[{i}]");
    let missing = |k: &str| {
        scene.invalid(
            format!("{f}.{k}"),
            format!(
                "missing field `{k}` (a 3D block body needs `origin`, `size`, `nx`, `ny` and `nz`)"
            ),
        )
    };
    if b.group.is_some() {
        return Err(scene.invalid(
            format!("{f}.group"),
            "a block body (`origin`, `size`, `nx`, `ny`, `nz`) has no `group`",
        ));
    }
    let three = |c: Option<crate::scene::Coords>, k: &str| {
        c.ok_or_else(|| missing(k))?.point::<3>().ok_or_else(|| {
            scene.invalid(
                format!("{f}.{k}"),
                "needs three numbers [x, y, z] in a 3D block",
            )
        })
    };
    let origin = three(b.origin, "origin")?;
    let size = three(b.size, "size")?;
    let nx = b.nx.ok_or_else(|| missing("nx"))?;
    let ny = b.ny.ok_or_else(|| missing("ny"))?;
    let nz = b.nz.ok_or_else(|| missing("nz"))?;
    for (k, v) in [("nx", nx), ("ny", ny), ("nz", nz)] {
        if v == 0 {
            return Err(scene.invalid(format!("{f}.{k}"), "must be at least 1"));
        }
    }
    if !size.iter().all(|&v| v > 0.0 && v.is_finite()) {
        return Err(scene.invalid(
            format!("{f}.size"),
            "every extent must be positive and finite",
        ));
    }
    if !origin.iter().all(|v| v.is_finite()) {
        return Err(scene.invalid(format!("{f}.origin"), "must be finite"));
    }
    if !(0..3).all(|k| (origin[k] + size[k]).is_finite()) {
        return Err(scene.invalid(
            format!("{f}.size"),
            "the far corner origin + size is not finite",
        ));
    }
    let r = &scene.refine;
    let n = [
        nx.checked_mul(r.x),
        ny.checked_mul(r.y),
        nz.checked_mul(r.z_factor()),
    ];
    let count = n
        .iter()
        .try_fold(1_usize, |acc, &k| acc.checked_mul(k?))
        .filter(|&c| c <= MAX_BLOCK_ELEMENTS);
    let (Some(nx), Some(ny), Some(nz), Some(_)) = (n[0], n[1], n[2], count) else {
        return Err(scene.invalid(
            f,
            format!(
                "more than {MAX_BLOCK_ELEMENTS} elements (nx x ny x nz times the [refine] factors)"
            ),
        ));
    };
    let block = Block3d {
        origin,
        size,
        nx,
        ny,
        nz,
    };
    block.check().map_err(|e| scene.invalid(f, e.to_string()))?;
    Ok(block)
}
