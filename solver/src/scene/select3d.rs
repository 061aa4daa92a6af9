//! Selections in a 3D scene: nodes by reference coordinates (`x`, `y`,
//! `z`, `at`) or physical group, faces by block side or physical surface.
//!
//! As in 2D (`select.rs`), coordinates match every node within `1e-9`
//! times the diagonal of the bounding box of all nodes
//! ([`Mesh::select_nodes_at`]); faces are resolved
//! by the body's mesh source ([`Solids`]), each quad4 or tri3 face
//! counter-clockwise seen from outside its body.

use super::source::Solids;
use super::{Scene, SceneError, SideName};
use crate::ids::NodeId;
use crate::mesh::Mesh;
use crate::mesh::volume::Face;

impl Scene {
    /// The nodes (optionally of one body) of the item `field` of a 3D
    /// scene: its physical `group` (then no coordinates), or those at the
    /// reference coordinates `at`, or on the planes/lines `xyz` (any of x,
    /// y, z). Ascending, at least one.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn select_3d(
        &self,
        mesh: &Mesh<3>,
        sources: &Solids,
        field: &str,
        body: &Option<String>,
        group: &Option<String>,
        xyz: [Option<f64>; 3],
        at: Option<[f64; 3]>,
    ) -> Result<Vec<NodeId>, SceneError> {
        let b = self.body_index(mesh, format!("{field}.body"), body)?;
        let in_body = || {
            body.as_ref()
                .map(|b| format!(" in body `{b}`"))
                .unwrap_or_default()
        };
        let coordinates = xyz.iter().any(Option::is_some) || at.is_some();
        if let Some(group) = group {
            if coordinates {
                return Err(
                    self.invalid(field, "give either `group` or `x`/`y`/`z`/`at`, not both")
                );
            }
            let mut nodes = sources.group_nodes(&format!("{field}.group"), group)?;
            if let Some(b) = b {
                nodes.retain(|&n| mesh.bodies[b].has_node(n));
            }
            if nodes.is_empty() {
                return Err(self.invalid(
                    format!("{field}.group"),
                    format!("physical group `{group}` has no node{}", in_body()),
                ));
            }
            return Ok(nodes);
        }
        let want = match at {
            Some(_) if xyz.iter().any(Option::is_some) => {
                return Err(self.invalid(field, "give either `at` or `x`/`y`/`z`, not both"));
            }
            Some(p) => p.map(Some),
            None if !coordinates => {
                return Err(self.invalid(field, "select nodes with `x`, `y`, `z` or `at`"));
            }
            None => xyz,
        };
        let nodes = mesh.select_nodes_at(b, &want);
        if nodes.is_empty() {
            return Err(self.invalid(
                field,
                format!(
                    "no node at x = {:?}, y = {:?}, z = {:?}{}",
                    want[0],
                    want[1],
                    want[2],
                    in_body()
                ),
            ));
        }
        Ok(nodes)
    }

    /// The body and the faces named by `body`, `side` and `group` (the
    /// item `f`: a contact face or a traction): a 3D block body's side, or
    /// a physical surface on one body's boundary (whose `body`, if given,
    /// must be that body).
    pub(super) fn faces_3d(
        &self,
        mesh: &Mesh<3>,
        sources: &Solids,
        f: &str,
        body: &Option<String>,
        side: Option<SideName>,
        group: &Option<String>,
    ) -> Result<(usize, Vec<Face<NodeId>>), SceneError> {
        let b = self.body_index(mesh, format!("{f}.body"), body)?;
        match (group, side) {
            (Some(_), Some(_)) => Err(self.invalid(f, "give either `side` or `group`, not both")),
            (None, None) => Err(self.invalid(f, "give `body` and `side`, or `group`")),
            (None, Some(side)) => {
                let b = b.ok_or_else(|| {
                    self.invalid(format!("{f}.body"), "a `side` needs its `body`")
                })?;
                let faces = sources.side(b, side.side_3d()).ok_or_else(|| {
                    self.invalid(
                        format!("{f}.side"),
                        format!(
                            "body `{}` is not a block body (name a physical surface with `group`)",
                            mesh.bodies[b].name
                        ),
                    )
                })?;
                Ok((b, faces))
            }
            (Some(group), None) => {
                let (owner, faces) = sources.group_faces(&format!("{f}.group"), group)?;
                if let Some(b) = b.filter(|&b| b != owner) {
                    return Err(self.invalid(
                        format!("{f}.body"),
                        format!(
                            "physical surface `{group}` is on body `{}`, not `{}`",
                            mesh.bodies[owner].name, mesh.bodies[b].name
                        ),
                    ));
                }
                Ok((owner, faces))
            }
        }
    }
}
