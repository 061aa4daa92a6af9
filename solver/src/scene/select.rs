//! Selections in a scene: nodes by reference coordinates, bodies by name,
//! faces by body and side.
//!
//! Selection by coordinates (`x`, `y`, `at`, optionally within a `body`) is
//! geometric and works on any mesh: it matches every node within
//! [`Mesh::coordinate_tolerance`]. Which segments a face names depends on
//! how its body was made, so faces are resolved by the body's mesh source
//! ([`Sources::face`]).

use super::source::Sources;
use super::{FaceSpec, Scene, SceneError};
use crate::ids::NodeId;
use crate::mesh::Mesh;

impl Scene {
    /// The index of the body named `body`, if one is named; an error for
    /// `field` listing the scene's bodies if there is none of that name.
    pub(super) fn body_index(
        &self,
        mesh: &Mesh,
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

    /// The segments of the face `spec`, the `which` face (`slave` or
    /// `master`) of the item `field`, counter-clockwise around its body.
    pub(super) fn face(
        &self,
        mesh: &Mesh,
        sources: &Sources,
        field: &str,
        which: &str,
        spec: &FaceSpec,
    ) -> Result<Vec<[NodeId; 2]>, SceneError> {
        let b = self
            .body_index(
                mesh,
                format!("{field}.{which}.body"),
                &Some(spec.body.clone()),
            )?
            .ok_or_else(|| self.invalid(format!("{field}.{which}.body"), "missing"))?;
        sources
            .face(mesh, b, spec.side)
            .ok_or_else(|| self.invalid(format!("{field}.{which}"), "not a block body"))
    }
}

fn in_body(body: &Option<String>) -> String {
    body.as_ref()
        .map(|b| format!(" in body `{b}`"))
        .unwrap_or_default()
}
