//! The structured-block source: each `[[body]]` with `origin`, `size`,
//! `nx`, `ny` and, in 3D, `nz` (any of them: the others are then missing;
//! `D` numbers in `origin` and `size`) becomes a block of `nx rx` by
//! `ny ry` (by `nz rz`) elements (`[refine]`'s factors; [`crate::mesh::block`]
//! has the numbering), and its facets are the block's sides
//! ([`Mesh::block_side`]). A block has at most
//! [`MAX_BLOCK_ELEMENTS`] elements (refinement included), so that no scene
//! value overflows the counts or asks for more memory than a machine has.

use super::SourceDim;
use crate::material::Material;
use crate::mesh::{Block, Mesh};
use crate::model::Dim;
use crate::scene::{BodySpec, Scene, SceneError};

/// The most elements one block may have (`nx ny (nz)` times the
/// refinement factors); larger blocks are an error naming the body.
pub const MAX_BLOCK_ELEMENTS: usize = 10_000_000;

/// The element counts of a block of dimension `D`, by field name.
const COUNTS: [&str; 3] = ["nx", "ny", "nz"];

/// The fields of a block body of dimension `D` in backticks, separated by
/// `sep` and the last by `last` (`` `origin`, `size`, `nx` and `ny` ``).
pub(super) fn fields<const D: usize>(sep: &str, last: &str) -> String {
    let names: Vec<String> = ["origin", "size"]
        .iter()
        .chain(&COUNTS[..D])
        .map(|k| format!("`{k}`"))
        .collect();
    let (tail, head) = names.split_last().expect("a block has fields");
    format!("{}{last}{tail}", head.join(sep))
}

/// Appends the scene's block `body[i]` with its checked `material`,
/// checked first: every field given, at least one element along each
/// axis, a positive finite size, a finite origin and far corner, at most
/// [`MAX_BLOCK_ELEMENTS`] elements; then appended
/// ([`Mesh::add_block`]). Returns the mesh body's index. Errors name the
/// field.
pub(super) fn add_block<const D: usize>(
    scene: &Scene,
    mesh: &mut Mesh<D>,
    i: usize,
    material: Material,
) -> Result<usize, SceneError>
where
    Dim<D>: SourceDim<D>,
{
    let b: &BodySpec = &scene.bodies[i];
    let f = format!("body[{i}]");
    let prefix = <Dim<D> as SourceDim<D>>::PREFIX;
    let missing = |k: &str| {
        scene.invalid(
            format!("{f}.{k}"),
            format!(
                "missing field `{k}` (a {prefix}block body needs {})",
                fields::<D>(", ", " and ")
            ),
        )
    };
    if b.group.is_some() {
        return Err(scene.invalid(
            format!("{f}.group"),
            format!("a block body ({}) has no `group`", fields::<D>(", ", ", ")),
        ));
    }
    let point = |c: Option<crate::scene::Coords>, k: &str| {
        c.ok_or_else(|| missing(k))?.point::<D>().ok_or_else(|| {
            scene.invalid(
                format!("{f}.{k}"),
                format!(
                    "needs {} numbers [{}] in a {}D block",
                    <Dim<D> as SourceDim<D>>::NUMBERS,
                    <Dim<D> as crate::dim::SpaceDim<D>>::AXES.join(", "),
                    D
                ),
            )
        })
    };
    let origin = point(b.origin, "origin")?;
    let size = point(b.size, "size")?;
    let given = [b.nx, b.ny, b.nz];
    let mut n = [0; D];
    for (k, count) in n.iter_mut().enumerate() {
        *count = given[k].ok_or_else(|| missing(COUNTS[k]))?;
    }
    for (k, &v) in n.iter().enumerate() {
        if v == 0 {
            return Err(scene.invalid(format!("{f}.{}", COUNTS[k]), "must be at least 1"));
        }
    }
    if !size.iter().all(|&v| v > 0.0 && v.is_finite()) {
        return Err(scene.invalid(
            format!("{f}.size"),
            format!(
                "{} must be positive and finite",
                <Dim<D> as SourceDim<D>>::EXTENTS
            ),
        ));
    }
    if !origin.iter().all(|v| v.is_finite()) {
        return Err(scene.invalid(format!("{f}.origin"), "must be finite"));
    }
    if !(0..D).all(|k| (origin[k] + size[k]).is_finite()) {
        return Err(scene.invalid(
            format!("{f}.size"),
            "the far corner origin + size is not finite",
        ));
    }
    let r = &scene.refine;
    let factors = [r.x, r.y, r.z_factor()];
    let refined: [Option<usize>; D] = std::array::from_fn(|k| n[k].checked_mul(factors[k]));
    let count = refined
        .iter()
        .try_fold(1_usize, |acc, &k| acc.checked_mul(k?))
        .filter(|&c| c <= MAX_BLOCK_ELEMENTS);
    if count.is_none() {
        return Err(scene.invalid(
            f,
            format!(
                "more than {MAX_BLOCK_ELEMENTS} elements ({} times the [refine] factors)",
                COUNTS[..D].join(" x ")
            ),
        ));
    }
    let block = Block {
        origin,
        size,
        cells: refined.map(|k| k.unwrap_or(0)),
    };
    mesh.add_block(&b.name, material, block)
        .map_err(|e| scene.invalid(&f, e.to_string()))
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
