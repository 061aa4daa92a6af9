//! What the model builder takes from a 3D scene ([`Build`] for `Dim<3>`,
//! see `build.rs`): what its mesh sources make ([`SourceDim`]: the
//! physical volumes of a 3D `[mesh]` file, whose tetrahedra and hexahedra
//! are the body's elements and whose physical surfaces are face groups
//! on one body; a block's six sides are [`Mesh::block_side`]'s quad4
//! faces), tractions per unit reference
//! area on faces ([`nodal_forces`]), and each pair's reading and
//! `gauss_points`: the `formulation` a reading of 3D faces
//! (`slave-normal` or `closest-point`: any other is refused naming
//! `contact[i].formulation`), `gauss_points` as given (absent: `None`, the
//! face kind's default, 2 x 2 on a quad4, 3 on a tri3, 7 per clipped
//! triangle with segmented integration), checked against the kinds of the
//! slave faces ([`face_rule`]) or the clipped triangles' rules (1, 3, 7);
//! and every pair laid out once ([`FaceLayout::new`]) so that what the
//! solve's layout refuses is a scene error naming `contact[i]`, then its
//! reference geometry checked as in 2D (`initial_contact.rs`: faces that
//! face each other, no initial penetration, a persistent pair that does
//! not start open, unless the `[[contact]]` acknowledges it).

use contact_kernels::Formulation;

use super::build::Build;
use super::initial_contact::{Acknowledged, check_initial_contact};
use super::source::{MeshFile, SourceDim, Sources};
use super::traction::nodal_forces;
use super::{ContactSpec, Scene, SceneError, TractionSpec};
use crate::contact::FaceLayout;
use crate::contact::face_rules::face_rule;
use crate::element::{Element, FaceKind};
use crate::ids::NodeId;
use crate::mesh::Mesh;
use crate::mesh::gmsh::{AnyMsh, MshError, MshVolumeMesh};
use crate::mesh::volume::Face;
use crate::model::{ContactPair, Dim, Integration, Model};

impl SourceDim<3> for Dim<3> {
    const NUMBERS: &'static str = "three";
    const GROUP: &'static str = "surface";
    const BODY: &'static str = "volume";
    const PREFIX: &'static str = "3D ";
    const EXTENTS: &'static str = "every extent";
    const INVERTED: &'static str = "";

    fn mesh_file(scene: &Scene, file: AnyMsh) -> Result<MshVolumeMesh, SceneError> {
        match file {
            AnyMsh::Volume(msh) => Ok(msh),
            // `prepare` found the scene 3D, so its mesh file is 3D
            AnyMsh::Planar(_) => Err(scene.invalid("mesh.file", "is a 2D mesh in a 3D scene")),
        }
    }

    /// The tetrahedra and hexahedra of the physical volume `group`.
    fn elements(msh: &MshVolumeMesh, group: &str) -> Result<Vec<(u64, Element<usize>)>, MshError> {
        Ok(msh
            .volume_elements(group)?
            .iter()
            .filter_map(|e| Some((e.tag, e.cell()?.into())))
            .collect())
    }

    /// The physical surface `group` as faces ([`MeshFile::group_faces`]).
    fn group_facets(file: &MeshFile<3>, group: &str) -> Result<(usize, Vec<Face<NodeId>>), String> {
        file.group_faces(group)
    }
}

impl Build<3> for Dim<3> {
    fn traction_force(scene: &Scene, f: &str, t: &TractionSpec) -> Result<[f64; 3], SceneError> {
        t.force_per_area
            .ok_or_else(|| scene.invalid(f, "give `force_per_area = [tx, ty, tz]`"))
    }

    /// The consistent nodal forces of each loaded face.
    fn traction_forces(
        scene: &Scene,
        mesh: &Mesh<3>,
        sources: &Sources<'_, 3>,
        f: &str,
        t: &TractionSpec,
        force: [f64; 3],
    ) -> Result<Vec<(NodeId, [f64; 3])>, SceneError> {
        let (_, faces) = scene.facets(mesh, sources, f, &t.body, t.side, &t.group)?;
        let mut forces = Vec::new();
        for face in faces {
            let x = face.map_nodes(|n| mesh.node_ref(n));
            let nodal = nodal_forces(&x, force);
            forces.extend(
                face.nodes()
                    .iter()
                    .copied()
                    .zip(nodal.nodes().iter().copied()),
            );
        }
        Ok(forces)
    }

    fn check_spec(
        scene: &Scene,
        f: &str,
        c: &ContactSpec,
        slave: &[Face<NodeId>],
    ) -> Result<(), SceneError> {
        if !matches!(
            c.formulation,
            Formulation::SlaveNormal | Formulation::ClosestPoint
        ) {
            return Err(scene.invalid(
                format!("{f}.formulation"),
                format!(
                    "`{}` is not a reading of 3D faces: a 3D pair takes `slave-normal` or `closest-point` (the kernel of each slave face on a master face is the reading's for the two faces' kinds)",
                    c.formulation
                ),
            ));
        }
        check_face_gauss_points(scene, f, c, slave)
    }

    fn check_pair(
        _: &Scene,
        _: &Mesh<3>,
        _: &str,
        _: &ContactSpec,
        _: &ContactPair<3>,
    ) -> Result<(), SceneError> {
        Ok(())
    }

    /// What the solve's layout of the pairs refuses (a clipping that
    /// fails, a degenerate slave face) is refused here, by pair; then the
    /// pair's reference geometry (`initial_contact.rs`: faces that face
    /// each other, no initial penetration, a persistent pair closed,
    /// unless the `[[contact]]` acknowledges it), as in 2D.
    fn check_model(scene: &Scene, model: &Model<3>) -> Result<(), SceneError> {
        for (i, (pair, spec)) in model.contacts.iter().zip(&scene.contacts).enumerate() {
            let f = format!("contact[{i}]");
            let layout = FaceLayout::new(&model.mesh, std::slice::from_ref(pair), None)
                .map_err(|e| scene.invalid(&f, e.to_string()))?;
            let ack = Acknowledged::of(spec);
            if ack.everything() {
                continue;
            }
            let paired = layout
                .reference_pairings(&model.mesh, 0)
                .map_err(|e| scene.invalid(&f, e.to_string()))?;
            check_initial_contact(&model.mesh, &pair.name, &paired, ack)
                .map_err(|m| scene.invalid(&f, m))?;
        }
        Ok(())
    }
}

/// `gauss_points` of the 3D pair `f` (`c`), if given: with Gauss
/// integration a rule on every kind of its `slave` faces ([`face_rule`]:
/// 1..=8 per direction on a quad4, 1, 3, 4, 6 or 7 on a tri3), with
/// segmented integration a rule on the clipped triangles (1, 3 or 7); an
/// error names `{f}.gauss_points` and the counts there are.
fn check_face_gauss_points(
    scene: &Scene,
    f: &str,
    c: &ContactSpec,
    slave: &[Face<NodeId>],
) -> Result<(), SceneError> {
    let Some(n) = c.gauss_points else {
        return Ok(());
    };
    let field = format!("{f}.gauss_points");
    match c.integration {
        Integration::Segmented => {
            if !SEGMENTED_POINTS.contains(&n) {
                return Err(scene.invalid(
                    field,
                    format!(
                        "segmented integration takes a rule of 1, 3 or 7 points on each clipped triangle, got {n}"
                    ),
                ));
            }
        }
        Integration::Gauss => {
            let mut kinds: Vec<FaceKind> = Vec::new();
            for face in slave {
                if !kinds.contains(&face.kind()) {
                    kinds.push(face.kind());
                }
            }
            for kind in kinds {
                let per = if kind == FaceKind::Quad4 {
                    " per direction (n x n points)"
                } else {
                    ""
                };
                face_rule(kind, n).map_err(|e| {
                    scene.invalid(
                        &field,
                        format!("{e}{per}, for the pair's {kind} slave faces"),
                    )
                })?;
            }
        }
    }
    Ok(())
}

/// The point counts of the triangle rules of segmented integration
/// (`contact::clip::TriangleRule`: centroid, three points, Radon's seven).
const SEGMENTED_POINTS: [usize; 3] = [1, 3, 7];
