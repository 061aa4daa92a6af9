//! Meshes of 4-node quadrilaterals made of several bodies that share no
//! nodes.
//!
//! Node `n` has reference coordinates `nodes_ref[n]` and the displacement
//! degrees of freedom `2n` (x) and `2n + 1` (y). Elements list their four
//! nodes counter-clockwise. Each body owns a contiguous range of nodes and of
//! elements.
//!
//! A structured rectangular block with origin `(x0, y0)`, size `(w, h)` and
//! `nx x ny` elements has the nodes `(i, j)`, `i = 0..=nx`, `j = 0..=ny`, at
//! `(x0 + i w/nx, y0 + j h/ny)`, numbered `j (nx + 1) + i` within the body,
//! and the elements `(i, j)` with nodes `(i,j), (i+1,j), (i+1,j+1), (i,j+1)`.
//!
//! A block's sides are chains of 2-node segments ordered counter-clockwise
//! around the body (so the outward normal of a segment with tangent `t` is
//! `(t.y, -t.x)/|t|`): `bottom` left to right, `right` bottom to top, `top`
//! right to left, `left` top to bottom.

use std::ops::Range;

use serde::{Deserialize, Serialize};

use crate::material::Material;
use crate::quad::{InvalidElement, QuadGeometry};

/// A structured rectangular block of elements.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Block {
    /// Lower-left corner (reference frame).
    pub origin: [f64; 2],
    /// Width and height.
    pub size: [f64; 2],
    /// Elements along x.
    pub nx: usize,
    /// Elements along y.
    pub ny: usize,
}

/// A side of a rectangular block.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Side {
    /// `y = y0`, segments left to right.
    Bottom,
    /// `x = x0 + w`, segments bottom to top.
    Right,
    /// `y = y0 + h`, segments right to left.
    Top,
    /// `x = x0`, segments top to bottom.
    Left,
}

impl Side {
    /// The side's name as written in scene files.
    pub fn name(self) -> &'static str {
        match self {
            Side::Bottom => "bottom",
            Side::Right => "right",
            Side::Top => "top",
            Side::Left => "left",
        }
    }
}

/// One body of the mesh.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Body {
    /// The body's name (unique in the mesh).
    pub name: String,
    /// Its material.
    pub material: Material,
    /// Its nodes (global indices).
    pub nodes: Range<usize>,
    /// Its elements (global indices).
    pub elements: Range<usize>,
    /// The block it was generated from, if any.
    pub block: Option<Block>,
}

/// Why a mesh could not be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MeshError {
    /// A block has zero elements along a direction or a non-positive size.
    #[error("block of body `{body}` is empty or has non-positive size")]
    EmptyBlock {
        /// The body.
        body: String,
    },
    /// An element's reference Jacobian is not positive.
    #[error(
        "element {element} of body `{body}` is inverted or degenerate (detJ0 = {det_j0:e}); nodes must run counter-clockwise"
    )]
    InvalidElement {
        /// The body.
        body: String,
        /// Global element index.
        element: usize,
        /// The smallest reference Jacobian determinant.
        det_j0: f64,
    },
    /// An element refers to a node outside its body.
    #[error(
        "element {element} of body `{body}` refers to node {node}, which the body does not have"
    )]
    BadConnectivity {
        /// The body.
        body: String,
        /// Element index within the body.
        element: usize,
        /// The offending (body-local) node index.
        node: usize,
    },
    /// A non-finite coordinate.
    #[error("body `{body}` has a non-finite node coordinate")]
    NonFinite {
        /// The body.
        body: String,
    },
}

/// Nodes, elements and bodies, with the element geometry precomputed.
#[derive(Debug, Clone, Default)]
pub struct Mesh {
    /// Reference coordinates of all nodes.
    pub nodes_ref: Vec<[f64; 2]>,
    /// Element connectivity (global node indices, counter-clockwise).
    pub elements: Vec<[usize; 4]>,
    /// The body of each element.
    pub element_body: Vec<usize>,
    /// The bodies.
    pub bodies: Vec<Body>,
    /// Reference geometry of each element.
    pub geometry: Vec<QuadGeometry>,
}

impl Mesh {
    /// An empty mesh.
    pub fn new() -> Mesh {
        Mesh::default()
    }

    /// Appends a body from explicit nodes and body-local connectivity.
    /// Returns the body's index.
    pub fn add_body(
        &mut self,
        name: &str,
        material: Material,
        nodes_ref: &[[f64; 2]],
        elements: &[[usize; 4]],
    ) -> Result<usize, MeshError> {
        self.push_body(name, material, nodes_ref, elements, None)
    }

    /// Appends a structured rectangular block (see the module docs).
    /// Returns the body's index.
    pub fn add_block(
        &mut self,
        name: &str,
        material: Material,
        block: Block,
    ) -> Result<usize, MeshError> {
        let Block {
            origin,
            size,
            nx,
            ny,
        } = block;
        if nx == 0 || ny == 0 || !(size[0] > 0.0) || !(size[1] > 0.0) {
            return Err(MeshError::EmptyBlock {
                body: name.to_owned(),
            });
        }
        let mut nodes = Vec::with_capacity((nx + 1) * (ny + 1));
        for j in 0..=ny {
            for i in 0..=nx {
                nodes.push([
                    origin[0] + size[0] * i as f64 / nx as f64,
                    origin[1] + size[1] * j as f64 / ny as f64,
                ]);
            }
        }
        let id = |i: usize, j: usize| j * (nx + 1) + i;
        let mut elements = Vec::with_capacity(nx * ny);
        for j in 0..ny {
            for i in 0..nx {
                elements.push([id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        self.push_body(name, material, &nodes, &elements, Some(block))
    }

    fn push_body(
        &mut self,
        name: &str,
        material: Material,
        nodes_ref: &[[f64; 2]],
        elements: &[[usize; 4]],
        block: Option<Block>,
    ) -> Result<usize, MeshError> {
        if nodes_ref.iter().flatten().any(|v| !v.is_finite()) {
            return Err(MeshError::NonFinite {
                body: name.to_owned(),
            });
        }
        let node0 = self.nodes_ref.len();
        let elem0 = self.elements.len();
        let body = self.bodies.len();
        let mut geometry = Vec::with_capacity(elements.len());
        let mut conn = Vec::with_capacity(elements.len());
        for (e, el) in elements.iter().enumerate() {
            if let Some(&node) = el.iter().find(|&&n| n >= nodes_ref.len()) {
                return Err(MeshError::BadConnectivity {
                    body: name.to_owned(),
                    element: e,
                    node,
                });
            }
            let x = el.map(|n| nodes_ref[n]);
            let geom = QuadGeometry::new(&x).map_err(|InvalidElement { det_j0 }| {
                MeshError::InvalidElement {
                    body: name.to_owned(),
                    element: elem0 + e,
                    det_j0,
                }
            })?;
            geometry.push(geom);
            conn.push(el.map(|n| n + node0));
        }
        self.nodes_ref.extend_from_slice(nodes_ref);
        self.elements.extend(conn);
        self.element_body
            .extend(std::iter::repeat_n(body, elements.len()));
        self.geometry.extend(geometry);
        self.bodies.push(Body {
            name: name.to_owned(),
            material,
            nodes: node0..node0 + nodes_ref.len(),
            elements: elem0..elem0 + elements.len(),
            block,
        });
        Ok(body)
    }

    /// Number of nodes.
    pub fn node_count(&self) -> usize {
        self.nodes_ref.len()
    }

    /// The index of the body called `name`.
    pub fn body_index(&self, name: &str) -> Option<usize> {
        self.bodies.iter().position(|b| b.name == name)
    }

    /// The segments (global node pairs) of a side of a block body, ordered
    /// counter-clockwise around the body. `None` if the body is not a block.
    pub fn block_side(&self, body: usize, side: Side) -> Option<Vec<[usize; 2]>> {
        let b = self.bodies.get(body)?;
        let Block { nx, ny, .. } = b.block?;
        let base = b.nodes.start;
        let id = |i: usize, j: usize| base + j * (nx + 1) + i;
        Some(match side {
            Side::Bottom => (0..nx).map(|i| [id(i, 0), id(i + 1, 0)]).collect(),
            Side::Right => (0..ny).map(|j| [id(nx, j), id(nx, j + 1)]).collect(),
            Side::Top => (0..nx).rev().map(|i| [id(i + 1, ny), id(i, ny)]).collect(),
            Side::Left => (0..ny).rev().map(|j| [id(0, j + 1), id(0, j)]).collect(),
        })
    }

    /// The length of the diagonal of the bounding box of all nodes (a
    /// length scale for tolerances).
    pub fn size(&self) -> f64 {
        let mut lo = [f64::INFINITY; 2];
        let mut hi = [f64::NEG_INFINITY; 2];
        for p in &self.nodes_ref {
            for c in 0..2 {
                lo[c] = lo[c].min(p[c]);
                hi[c] = hi[c].max(p[c]);
            }
        }
        if self.nodes_ref.is_empty() {
            0.0
        } else {
            (hi[0] - lo[0]).hypot(hi[1] - lo[1])
        }
    }

    /// The tolerance used when nodes are selected by coordinates.
    pub fn coordinate_tolerance(&self) -> f64 {
        1e-9 * self.size().max(1e-300)
    }

    /// Nodes (optionally only of `body`) whose reference coordinates match
    /// every given coordinate within [`Mesh::coordinate_tolerance`].
    pub fn select_nodes(&self, body: Option<usize>, x: Option<f64>, y: Option<f64>) -> Vec<usize> {
        let tol = self.coordinate_tolerance();
        let range = match body {
            Some(b) => self.bodies[b].nodes.clone(),
            None => 0..self.nodes_ref.len(),
        };
        range
            .filter(|&n| {
                let p = self.nodes_ref[n];
                x.is_none_or(|x| (p[0] - x).abs() <= tol)
                    && y.is_none_or(|y| (p[1] - y).abs() <= tol)
            })
            .collect()
    }

    /// The element displacement vector `[u1x, u1y, ..., u4y]` of element
    /// `e` from the global displacement vector.
    pub fn element_displacements(&self, e: usize, u: &[f64]) -> [f64; 8] {
        let el = &self.elements[e];
        std::array::from_fn(|k| u[2 * el[k / 2] + k % 2])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::PlaneModel;

    const MAT: Material = Material {
        young: 1.0,
        poisson: 0.0,
        model: PlaneModel::PlaneStress,
    };

    #[test]
    fn block_numbering_and_sides_are_counter_clockwise() {
        let mut m = Mesh::new();
        m.add_block(
            "a",
            MAT,
            Block {
                origin: [0.0, 0.0],
                size: [2.0, 1.0],
                nx: 2,
                ny: 1,
            },
        )
        .unwrap();
        m.add_block(
            "b",
            MAT,
            Block {
                origin: [0.0, 1.0],
                size: [2.0, 1.0],
                nx: 2,
                ny: 1,
            },
        )
        .unwrap();
        assert_eq!(m.node_count(), 12);
        assert_eq!(m.elements[2], [6, 7, 10, 9]);
        let top = m.block_side(0, Side::Top).unwrap();
        assert_eq!(top, vec![[5, 4], [4, 3]]);
        let bottom = m.block_side(1, Side::Bottom).unwrap();
        assert_eq!(bottom, vec![[6, 7], [7, 8]]);
        assert_eq!(m.block_side(0, Side::Left).unwrap(), vec![[3, 0]]);
        assert_eq!(m.block_side(0, Side::Right).unwrap(), vec![[2, 5]]);
        // interface nodes exist twice
        assert_eq!(m.select_nodes(None, None, Some(1.0)).len(), 6);
        assert_eq!(m.select_nodes(Some(1), Some(2.0), Some(2.0)), vec![11]);
    }

    #[test]
    fn clockwise_elements_are_rejected() {
        let mut m = Mesh::new();
        let err = m
            .add_body(
                "c",
                MAT,
                &[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
                &[[0, 3, 2, 1]],
            )
            .unwrap_err();
        assert!(matches!(err, MeshError::InvalidElement { .. }));
    }
}
