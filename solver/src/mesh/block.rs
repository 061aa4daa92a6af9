//! Structured rectangular blocks: the body generator behind `[[body]]`
//! with `origin`, `size`, `nx` and `ny` in a scene.
//!
//! A structured rectangular block with origin `(x0, y0)`, size `(w, h)` and
//! `nx x ny` elements has the nodes `(i, j)`, `i = 0..=nx`, `j = 0..=ny`, at
//! `(x0 + i w/nx, y0 + j h/ny)`, numbered `j (nx + 1) + i` within the body,
//! and the elements `(i, j)` with nodes `(i,j), (i+1,j), (i+1,j+1), (i,j+1)`
//! (the 2D [`super::grid`], as the 3D blocks').
//!
//! A block's sides are chains of 2-node segments ordered counter-clockwise
//! around the body (so the outward normal of a segment with tangent `t` is
//! `(t.y, -t.x)/|t|`): `bottom` left to right, `right` bottom to top, `top`
//! right to left, `left` top to bottom. The body remembers its [`Block`]
//! ([`super::Body::block`]), which is how [`Mesh::block_side`] finds the
//! numbering again.

use serde::{Deserialize, Serialize};

use super::grid::Grid;
use super::{Mesh, MeshError};
use crate::element::quad::CORNERS;
use crate::ids::NodeId;
use crate::material::Material;

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

impl Mesh {
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
        let grid = Grid {
            origin,
            size,
            cells: [nx, ny],
        };
        let elements = grid.cells(&CORNERS);
        self.push_body(name, material, &grid.nodes(), &elements, Some(block))
    }

    /// The segments (global node pairs) of a side of a block body, ordered
    /// counter-clockwise around the body. `None` if the body is not a block.
    pub fn block_side(&self, body: usize, side: Side) -> Option<Vec<[NodeId; 2]>> {
        let b = self.bodies.get(body)?;
        let Block { nx, ny, .. } = b.block?;
        let base = b.nodes.start;
        let id = |i: usize, j: usize| NodeId::new(base + j * (nx + 1) + i);
        Some(match side {
            Side::Bottom => (0..nx).map(|i| [id(i, 0), id(i + 1, 0)]).collect(),
            Side::Right => (0..ny).map(|j| [id(nx, j), id(nx, j + 1)]).collect(),
            Side::Top => (0..nx).rev().map(|i| [id(i + 1, ny), id(i, ny)]).collect(),
            Side::Left => (0..ny).rev().map(|j| [id(0, j + 1), id(0, j)]).collect(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::tests::MAT;

    #[test]
    fn block_numbering_and_sides_are_counter_clockwise() {
        let mut m = Mesh::new();
        for (name, y0) in [("a", 0.0), ("b", 1.0)] {
            let block = Block {
                origin: [0.0, y0],
                size: [2.0, 1.0],
                nx: 2,
                ny: 1,
            };
            m.add_block(name, MAT, block).unwrap();
        }
        assert_eq!(m.node_count(), 12);
        let raw = |segs: Vec<[NodeId; 2]>| segs.iter().map(|s| s.map(NodeId::index)).collect();
        assert_eq!(
            m.elements[2].map_nodes(NodeId::index),
            crate::mesh::Element::Quad4([6, 7, 10, 9])
        );
        let top: Vec<[usize; 2]> = raw(m.block_side(0, Side::Top).unwrap());
        assert_eq!(top, vec![[5, 4], [4, 3]]);
        let bottom: Vec<[usize; 2]> = raw(m.block_side(1, Side::Bottom).unwrap());
        assert_eq!(bottom, vec![[6, 7], [7, 8]]);
        let left: Vec<[usize; 2]> = raw(m.block_side(0, Side::Left).unwrap());
        assert_eq!(left, vec![[3, 0]]);
        let right: Vec<[usize; 2]> = raw(m.block_side(0, Side::Right).unwrap());
        assert_eq!(right, vec![[2, 5]]);
        // interface nodes exist twice
        assert_eq!(m.select_nodes(None, None, Some(1.0)).len(), 6);
        assert_eq!(
            m.select_nodes(Some(1), Some(2.0), Some(2.0)),
            vec![NodeId::new(11)]
        );
    }
}
