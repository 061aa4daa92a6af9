//! Selections in a scene of either dimension: nodes by reference
//! coordinates or physical group, bodies by name, the facets of a contact
//! surface or traction by body and side or by physical group.
//!
//! Selection by coordinates (`x`, `y`, `z`, `at`, optionally within a
//! `body`) is geometric and works on any mesh: it matches every node within
//! [`Mesh::coordinate_tolerance`] ([`Mesh::select_nodes_at`]). Which facets
//! a side names depends on how its body was made, so sides are resolved
//! by the body's mesh source ([`Sources::side`]); physical groups
//! (`group`) by the source that read the mesh file
//! ([`Sources::group_nodes`], [`Sources::group_facets`]).

use super::source::{SourceDim, Sources};
use super::{Scene, SceneError};
use crate::dim::SpaceDim;
use crate::ids::NodeId;
use crate::mesh::Mesh;
use crate::mesh::Side;
use crate::model::{Dim, FacetOf};

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

    /// The nodes (optionally of one body) of the item `field`: its
    /// physical `group` (then no coordinates), or those at the reference
    /// coordinates `at`, or on the lines/planes `axes` (any of x, y, z; the
    /// dimension's first ones, the others `None`). Ascending, at least
    /// one.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn select<const D: usize>(
        &self,
        mesh: &Mesh<D>,
        sources: &Sources<'_, D>,
        field: &str,
        body: &Option<String>,
        group: &Option<String>,
        axes: &[Option<f64>; 3],
        at: Option<[f64; D]>,
    ) -> Result<Vec<NodeId>, SceneError>
    where
        Dim<D>: SourceDim<D>,
    {
        let names = <Dim<D> as SpaceDim<D>>::AXES;
        let listed = |sep: &str| format!("`{}`", names.join(&format!("`{sep}`")));
        let b = self.body_index(mesh, format!("{field}.body"), body)?;
        let axes: [Option<f64>; D] = std::array::from_fn(|c| axes[c]);
        let coordinates = axes.iter().any(Option::is_some) || at.is_some();
        if let Some(group) = group {
            if coordinates {
                return Err(self.invalid(
                    field,
                    format!("give either `group` or {}/`at`, not both", listed("/")),
                ));
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
            return Ok(nodes);
        }
        let want = match at {
            Some(_) if axes.iter().any(Option::is_some) => {
                return Err(self.invalid(
                    field,
                    format!("give either `at` or {}, not both", listed("/")),
                ));
            }
            Some(p) => p.map(Some),
            None if !coordinates => {
                return Err(
                    self.invalid(field, format!("select nodes with {} or `at`", listed(", ")))
                );
            }
            None => axes,
        };
        let nodes = mesh.select_nodes_at(b, &want);
        if nodes.is_empty() {
            let at: Vec<String> = names
                .iter()
                .zip(&want)
                .map(|(name, v)| format!("{name} = {v:?}"))
                .collect();
            return Err(self.invalid(
                field,
                format!("no node at {}{}", at.join(", "), in_body(body)),
            ));
        }
        Ok(nodes)
    }

    /// The body and the facets named by `body`, `side` and `group` (the
    /// item `f`: a contact surface or a 3D traction), outward: a block
    /// body's side, or a physical group (a curve in 2D, a surface in 3D)
    /// on one body's boundary, whose `body`, if given, must be that body.
    pub(super) fn facets<const D: usize>(
        &self,
        mesh: &Mesh<D>,
        sources: &Sources<'_, D>,
        f: &str,
        body: &Option<String>,
        side: Option<Side>,
        group: &Option<String>,
    ) -> Result<(usize, Vec<FacetOf<D>>), SceneError>
    where
        Dim<D>: SourceDim<D>,
    {
        let b = self.body_index(mesh, format!("{f}.body"), body)?;
        match (group, side) {
            (Some(_), Some(_)) => Err(self.invalid(f, "give either `side` or `group`, not both")),
            (None, None) => Err(self.invalid(f, "give `body` and `side`, or `group`")),
            (None, Some(side)) => {
                let b = b.ok_or_else(|| {
                    self.invalid(format!("{f}.body"), "a `side` needs its `body`")
                })?;
                let facets = sources
                    .side(mesh, b, side)
                    .map_err(|m| self.invalid(format!("{f}.side"), m))?;
                let facets = facets.ok_or_else(|| {
                    self.invalid(
                        format!("{f}.side"),
                        format!(
                            "body `{}` is not a block body (name a physical {} with `group`)",
                            mesh.bodies[b].name,
                            <Dim<D> as SourceDim<D>>::GROUP
                        ),
                    )
                })?;
                Ok((b, facets))
            }
            (Some(group), None) => {
                let (owner, facets) = sources.group_facets(&format!("{f}.group"), group)?;
                if let Some(b) = b.filter(|&b| b != owner) {
                    return Err(self.invalid(
                        format!("{f}.body"),
                        format!(
                            "physical {} `{group}` is on body `{}`, not `{}`",
                            <Dim<D> as SourceDim<D>>::GROUP,
                            mesh.bodies[owner].name,
                            mesh.bodies[b].name
                        ),
                    ));
                }
                Ok((owner, facets))
            }
        }
    }
}

/// ` in body `b`` when a body is named, for messages.
fn in_body(body: &Option<String>) -> String {
    body.as_ref()
        .map(|b| format!(" in body `{b}`"))
        .unwrap_or_default()
}
