//! Selections in a scene: nodes by reference coordinates or physical
//! group, bodies by name, faces by body and side or by physical curve.
//!
//! Selection by coordinates (`x`, `y`, `at`, optionally within a `body`) is
//! geometric and works on any mesh: it matches every node within
//! [`Mesh::coordinate_tolerance`]. Which segments a face names depends on
//! how its body was made, so faces are resolved by the body's mesh source
//! ([`Sources::face`]); physical groups (`group`) by the source that read
//! the mesh file ([`Sources::group_nodes`], [`Sources::group_face`],
//! [`Sources::group_segments`]). A traction loads a face of either kind.

use super::source::Sources;
use super::{FaceSpec, Scene, SceneError, SideName, TractionSpec};
use crate::ids::NodeId;
use crate::mesh::{Mesh, Side};

impl Scene {
    /// The index of the body named `body` (in a mesh of either dimension),
    /// if one is named; an error for `field` listing the scene's bodies if
    /// there is none of that name.
    pub(super) fn body_index<const D: usize>(
        &self,
        mesh: &Mesh<D>,
        field: String,
        body: &Option<String>,
    ) -> Result<Option<usize>, SceneError> {
        match body {
            None => Ok(None),
            Some(name) => mesh.body_index(name).map(Some).ok_or_else(|| {
                let names: Vec<&str> = self.bodies.iter().map(|b| b.name.as_str()).collect();
                self.invalid(
                    field,
                    format!("no body named `{name}` (bodies: {})", names.join(", ")),
                )
            }),
        }
    }

    /// The nodes (optionally of one body) of the physical `group` if one is
    /// given (then not `x`, `y` or `at`), ascending; otherwise those of
    /// [`Scene::select`]. At least one node.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn select_in(
        &self,
        mesh: &Mesh,
        sources: &Sources,
        field: &str,
        body: &Option<String>,
        group: &Option<String>,
        x: Option<f64>,
        y: Option<f64>,
        at: Option<[f64; 2]>,
    ) -> Result<Vec<NodeId>, SceneError> {
        let Some(group) = group else {
            return self.select(mesh, field, body, x, y, at);
        };
        let b = self.body_index(mesh, format!("{field}.body"), body)?;
        if x.is_some() || y.is_some() || at.is_some() {
            return Err(self.invalid(field, "give either `group` or `x`/`y`/`at`, not both"));
        }
        let mut nodes = sources.group_nodes(&format!("{field}.group"), group)?;
        if let Some(b) = b {
            nodes.retain(|&n| mesh.bodies[b].has_node(n));
        }
        if nodes.is_empty() {
            return Err(self.invalid(
                format!("{field}.group"),
                format!("physical group `{group}` has no node{}", in_body(body)),
            ));
        }
        Ok(nodes)
    }

    /// The nodes (optionally of one body) at the reference coordinates the
    /// item `field` gives: `at`, or `x` and/or `y`. At least one node.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn select(
        &self,
        mesh: &Mesh,
        field: &str,
        body: &Option<String>,
        x: Option<f64>,
        y: Option<f64>,
        at: Option<[f64; 2]>,
    ) -> Result<Vec<NodeId>, SceneError> {
        let b = self.body_index(mesh, format!("{field}.body"), body)?;
        let (x, y) = match (at, x, y) {
            (Some(_), Some(_), _) | (Some(_), _, Some(_)) => {
                return Err(self.invalid(field, "give either `at` or `x`/`y`, not both"));
            }
            (Some(p), None, None) => (Some(p[0]), Some(p[1])),
            (None, None, None) => {
                return Err(self.invalid(field, "select nodes with `x`, `y` or `at`"));
            }
            (None, x, y) => (x, y),
        };
        let nodes = mesh.select_nodes(b, x, y);
        if nodes.is_empty() {
            return Err(self.invalid(
                field,
                format!("no node at x = {x:?}, y = {y:?}{}", in_body(body)),
            ));
        }
        Ok(nodes)
    }

    /// The body and the segments of the face `spec`, the `which` face
    /// (`slave` or `master`) of the item `field`, counter-clockwise around
    /// its body: a body's `side`, or a physical curve (`group`).
    pub(super) fn face(
        &self,
        mesh: &Mesh,
        sources: &Sources,
        field: &str,
        which: &str,
        spec: &FaceSpec,
    ) -> Result<(usize, Vec<[NodeId; 2]>), SceneError> {
        let f = format!("{field}.{which}");
        let b = self.body_index(mesh, format!("{f}.body"), &spec.body)?;
        match (&spec.group, spec.side) {
            (Some(_), Some(_)) => Err(self.invalid(f, "give either `side` or `group`, not both")),
            (None, None) => Err(self.invalid(f, "give `body` and `side`, or `group`")),
            (None, Some(side)) => {
                let b = b.ok_or_else(|| {
                    self.invalid(format!("{f}.body"), "a `side` needs its `body`")
                })?;
                let side = self.side_2d(format!("{f}.side"), side)?;
                let segments = sources
                    .face(mesh, b, side)
                    .ok_or_else(|| self.invalid(f, "not a block body"))?;
                Ok((b, segments))
            }
            (Some(group), None) => {
                let face = sources.group_face(&format!("{f}.group"), group)?;
                if let Some(b) = b.filter(|&b| b != face.body) {
                    return Err(self.invalid(
                        format!("{f}.body"),
                        format!(
                            "physical curve `{group}` is on body `{}`, not `{}`",
                            mesh.bodies[face.body].name, mesh.bodies[b].name
                        ),
                    ));
                }
                Ok((face.body, face.segments))
            }
        }
    }

    /// The segments that the traction `spec`, item `field`, loads: a block
    /// body's `side`, counter-clockwise around the body as in a contact
    /// face, or the physical curve `group` in the file's order and direction
    /// (every node of it in `body`, if one is named).
    pub(super) fn traction_segments(
        &self,
        mesh: &Mesh,
        sources: &Sources,
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
                let side = self.side_2d(format!("{field}.side"), side)?;
                sources.face(mesh, b, side).ok_or_else(|| {
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

impl Scene {
    /// The 2D side `side` names (the item `field`'s); `front` and `back`
    /// are refused (already by `check_dimension`, before any face is
    /// resolved).
    fn side_2d(&self, field: String, side: SideName) -> Result<Side, SceneError> {
        side.side_2d().ok_or_else(|| {
            self.invalid(field, format!("`{}` is a side of a 3D block", side.name()))
        })
    }
}

fn in_body(body: &Option<String>) -> String {
    body.as_ref()
        .map(|b| format!(" in body `{b}`"))
        .unwrap_or_default()
}
