//! What the model builder takes from a 2D scene ([`Build`] for `Dim<2>`,
//! see `build.rs`): what its mesh sources make ([`SourceDim`]: the
//! physical surfaces of a 2D `[mesh]` file, whose triangles and
//! quadrangles are the body's elements and whose physical curves are
//! faces; a block's sides are [`Mesh::block_side`]'s segments), tractions per
//! unit reference length on segments, and the pairs' reference geometry
//! (`initial_contact.rs`: faces that face each other, no initial
//! penetration, a persistent pair that does not start open, unless the
//! `[[contact]]` allows it).

use super::build::Build;
use super::initial_contact::{Acknowledged, check_initial_contact, reference_pairings_2d};
use super::source::{MeshFile, SourceDim, Sources};
use super::{ContactSpec, Scene, SceneError, TractionSpec};
use crate::element::Element;
use crate::ids::NodeId;
use crate::mesh::Mesh;
use crate::mesh::gmsh::{AnyMsh, MshError, MshMesh};
use crate::mesh::volume::Face;
use crate::model::{ContactPair, Dim, Model, Multipliers};

impl SourceDim<2> for Dim<2> {
    const NUMBERS: &'static str = "two";
    const GROUP: &'static str = "curve";
    const BODY: &'static str = "surface";
    const PREFIX: &'static str = "";
    const EXTENTS: &'static str = "width and height";
    const INVERTED: &'static str = "; its nodes must run counter-clockwise";

    fn mesh_file(scene: &Scene, file: AnyMsh) -> Result<MshMesh, SceneError> {
        match file {
            AnyMsh::Planar(msh) => Ok(msh),
            // `prepare` found the scene 2D, so its mesh file is 2D
            AnyMsh::Volume(_) => Err(scene.invalid("mesh.file", "is a 3D mesh in a 2D scene")),
        }
    }

    /// The triangles and quadrangles of the physical surface `group`.
    fn elements(msh: &MshMesh, group: &str) -> Result<Vec<(u64, Element<usize>)>, MshError> {
        Ok(msh
            .surface_elements(group)?
            .iter()
            .filter_map(|e| {
                let element = match e.face()? {
                    Face::Tri3(n) => Element::Tri3(n),
                    Face::Quad4(n) => Element::Quad4(n),
                };
                Some((e.tag, element))
            })
            .collect())
    }

    /// The physical curve `group` as a face ([`MeshFile::group_face`]).
    fn group_facets(file: &MeshFile<2>, group: &str) -> Result<(usize, Vec<[NodeId; 2]>), String> {
        file.group_face(group)
    }
}

impl Build<2> for Dim<2> {
    fn traction_force(scene: &Scene, f: &str, t: &TractionSpec) -> Result<[f64; 2], SceneError> {
        t.force_per_length
            .ok_or_else(|| scene.invalid(f, "give `force_per_length = [tx, ty]`"))
    }

    /// `t L / 2` at each node of each loaded segment of reference length
    /// `L` ([`Scene::traction_segments`]).
    fn traction_forces(
        scene: &Scene,
        mesh: &Mesh<2>,
        sources: &Sources<'_, 2>,
        f: &str,
        t: &TractionSpec,
        force: [f64; 2],
    ) -> Result<Vec<(NodeId, [f64; 2])>, SceneError> {
        let mut forces = Vec::new();
        for seg in scene.traction_segments(mesh, sources, f, t)? {
            let (a, b) = (mesh.node_ref(seg[0]), mesh.node_ref(seg[1]));
            let half = (b[0] - a[0]).hypot(b[1] - a[1]) / 2.0;
            for n in seg {
                forces.push((n, [force[0] * half, force[1] * half]));
            }
        }
        Ok(forces)
    }

    fn check_spec(
        scene: &Scene,
        f: &str,
        c: &ContactSpec,
        _slave: &[[NodeId; 2]],
    ) -> Result<(), SceneError> {
        if c.multipliers == Multipliers::Dual {
            return Err(scene.invalid(
                format!("{f}.multipliers"),
                "`multipliers = \"dual\"` is built for 3D faces only; a 2D pair takes `\"standard\"` (the default)",
            ));
        }
        scene.check_contact(f, c)
    }

    fn check_pair(
        scene: &Scene,
        mesh: &Mesh<2>,
        f: &str,
        c: &ContactSpec,
        pair: &ContactPair<2>,
    ) -> Result<(), SceneError> {
        let ack = Acknowledged::of(c);
        if ack.everything() {
            return Ok(());
        }
        let paired = reference_pairings_2d(mesh, pair, pair.formulation);
        check_initial_contact(mesh, &pair.name, &paired, ack).map_err(|m| scene.invalid(f, m))
    }

    fn check_model(_: &Scene, _: &Model<2>) -> Result<(), SceneError> {
        Ok(())
    }
}

impl Scene {
    /// The segments that the traction `spec`, item `field`, loads: a block
    /// body's `side`, counter-clockwise around the body as in a contact
    /// face, or the physical curve `group` in the file's order and direction
    /// (every node of it in `body`, if one is named).
    pub(super) fn traction_segments(
        &self,
        mesh: &Mesh,
        sources: &Sources<'_, 2>,
        field: &str,
        spec: &TractionSpec,
    ) -> Result<Vec<[NodeId; 2]>, SceneError> {
        let b = self.body_index(mesh, format!("{field}.body"), &spec.body)?;
        match (&spec.group, spec.side) {
            (Some(_), Some(_)) => {
                Err(self.invalid(field, "give either `side` or `group`, not both"))
            }
            (None, None) => Err(self.invalid(field, "give `body` and `side`, or `group`")),
            (None, Some(side)) => {
                let b = b.ok_or_else(|| {
                    self.invalid(format!("{field}.body"), "a `side` needs its `body`")
                })?;
                let segments = sources
                    .side(mesh, b, side)
                    .map_err(|m| self.invalid(format!("{field}.side"), m))?;
                segments.ok_or_else(|| {
                    self.invalid(
                        format!("{field}.side"),
                        format!(
                            "body `{}` is not a block body (load a physical curve with `group`)",
                            mesh.bodies[b].name
                        ),
                    )
                })
            }
            (Some(group), None) => {
                let segments = sources.group_segments(&format!("{field}.group"), group)?;
                if let Some(b) = b {
                    let body = &mesh.bodies[b];
                    if let Some(&n) = segments.iter().flatten().find(|&&n| !body.has_node(n)) {
                        let owner = mesh
                            .bodies
                            .iter()
                            .find(|o| o.has_node(n))
                            .map_or("no body", |o| o.name.as_str());
                        return Err(self.invalid(
                            format!("{field}.body"),
                            format!(
                                "physical curve `{group}` has a node of `{owner}`, not of `{}`",
                                body.name
                            ),
                        ));
                    }
                }
                Ok(segments)
            }
        }
    }
}
