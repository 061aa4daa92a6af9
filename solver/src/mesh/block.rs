//! Structured blocks in `D = 2` or `3` dimensions: the body generator
//! behind a `[[body]]` with `origin`, `size`, `nx`, `ny` (and `nz` in 3D),
//! one [`Block<D>`] for both dimensions over the structured grid
//! [`super::grid`].
//!
//! A block with origin `x0`, size `s` and `n_d` cells along axis `d`
//! ([`Block::cells`]) has the nodes `p = (p_0, .., p_{D-1})`,
//! `0 <= p_d <= n_d`, at `x0_d + s_d p_d / n_d`, numbered with axis 0
//! fastest ([`Block::node`]): `j (nx + 1) + i` in 2D,
//! `(k (ny + 1) + j)(nx + 1) + i` in 3D. Its cells `c` are numbered the
//! same way over `n_d` (`j nx + i`, `(k ny + j) nx + i`), each with the
//! nodes at the corners of the dimension's parent element, in the element's
//! node order: in 2D a quadrilateral `(i,j), (i+1,j), (i+1,j+1), (i,j+1)`
//! (counter-clockwise), in 3D a [`Cell::Hex8`] with the same four at `k`,
//! then at `k + 1` (Gmsh's order; every corner Jacobian is
//! `abc / (8 nx ny nz)`).
//!
//! Its sides ([`Side`]): `left`/`right` at the smallest/largest x; in 2D
//! `bottom`/`top` at the smallest/largest y; in 3D `front`/`back` at the
//! smallest/largest y and `bottom`/`top` at the smallest/largest z (a 2D
//! block has no `front` or `back`). A side is made of the dimension's
//! facets, the facets of the cells along it (the cell's own outward facet),
//! so that they face out of the block:
//!
//! * 2D: 2-node segments ordered counter-clockwise around the body (so the
//!   outward normal of a segment with tangent `t` is `(t.y, -t.x)/|t|`):
//!   `bottom` left to right, `right` bottom to top, `top` right to left,
//!   `left` top to bottom;
//! * 3D: quad4 faces, each counter-clockwise seen from outside the block
//!   (the cell's face of [`HEX8_FACES`]: `xi = -1` for `left`, `xi = +1`
//!   `right`, `eta = -1` `front`, `eta = +1` `back`, `zeta = -1` `bottom`,
//!   `zeta = +1` `top`), ordered by the side's two in-plane indices, the
//!   one of the lower axis (x before y before z) running fastest.
//!
//! What differs between the dimensions (the cell, the facet, the order of
//! a side's facets) is [`BlockDim`], implemented here for `Dim<2>` and
//! `Dim<3>`. The body remembers its block ([`super::Body::block`]), which
//! is how [`Mesh::block_side`] finds the numbering again.

use serde::{Deserialize, Serialize};

use super::grid::Grid;
use super::volume::{Cell, Face, HEX8_FACES};
use super::{Dim, Mesh, MeshError};
use crate::element::{ElementKind, hex, quad};
use crate::ids::NodeId;
use crate::material::Material;

/// A structured block of `D` dimensions (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Block<const D: usize> {
    /// The corner of smallest coordinates (reference frame).
    pub origin: [f64; D],
    /// The extents along each axis (width, height (, depth)).
    pub size: [f64; D],
    /// Cells along each axis (`nx`, `ny` (, `nz`)).
    pub cells: [usize; D],
}

/// A side of a block (module docs), as written in scene files (`side`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Side {
    /// 2D: the smallest y; 3D: the smallest z.
    Bottom,
    /// The largest x.
    Right,
    /// 2D: the largest y; 3D: the largest z.
    Top,
    /// The smallest x.
    Left,
    /// The smallest y (3D only).
    Front,
    /// The largest y (3D only).
    Back,
}

impl Side {
    /// All six, in declaration order.
    pub const ALL: [Side; 6] = [
        Side::Bottom,
        Side::Right,
        Side::Top,
        Side::Left,
        Side::Front,
        Side::Back,
    ];

    /// The side's name as written in scene files.
    pub fn name(self) -> &'static str {
        match self {
            Side::Bottom => "bottom",
            Side::Right => "right",
            Side::Top => "top",
            Side::Left => "left",
            Side::Front => "front",
            Side::Back => "back",
        }
    }

    /// The axis normal to it in a block of `D` (2 or 3) dimensions (0 x,
    /// 1 y, 2 z) and whether it is at that axis' largest coordinate;
    /// `None` if such a block has no such side (`front` and `back` in 2D).
    pub fn axis<const D: usize>(self) -> Option<(usize, bool)> {
        if !(2..=3).contains(&D) {
            return None;
        }
        match self {
            Side::Left => Some((0, false)),
            Side::Right => Some((0, true)),
            Side::Front => (D == 3).then_some((1, false)),
            Side::Back => (D == 3).then_some((1, true)),
            Side::Bottom => Some((D - 1, false)),
            Side::Top => Some((D - 1, true)),
        }
    }
}

/// What a structured block takes from its dimension (module docs):
/// implemented for `Dim<2>` (quadrilaterals, segments) and `Dim<3>`
/// (hexahedra, quad4 faces).
pub trait BlockDim<const D: usize> {
    /// A cell with body-local nodes, as [`Mesh::add_body`] takes it:
    /// `[usize; 4]` (a quadrilateral) in 2D, a [`Cell`] (always
    /// [`Cell::Hex8`]) in 3D.
    type Cell: Copy + Into<crate::element::Element<usize>>;
    /// A facet of a side, with nodes of type `N`: `[N; 2]` in 2D,
    /// [`Face<N>`] (always [`Face::Quad4`]) in 3D.
    type Facet<N: Copy>;

    /// The cell `c` (`c_d < n_d`) of `block`, body-local nodes.
    fn cell(block: &Block<D>, c: [usize; D]) -> Self::Cell;

    /// The facet of `cell` that lies on `side` (outward), each node
    /// renamed by `node`; `None` if the dimension's blocks have no such
    /// side.
    fn facet<N: Copy>(
        cell: Self::Cell,
        side: Side,
        node: impl Fn(usize) -> N,
    ) -> Option<Self::Facet<N>>;

    /// Whether the facets of `side` run against the grid order of its
    /// cells (2D `top` and `left`, so that the chain runs counter-clockwise
    /// around the body).
    fn reversed(side: Side) -> bool;
}

impl BlockDim<2> for Dim<2> {
    type Cell = [usize; 4];
    type Facet<N: Copy> = [N; 2];

    fn cell(block: &Block<2>, c: [usize; 2]) -> [usize; 4] {
        block.grid().cell(c, &quad::CORNERS)
    }

    /// The quadrilateral's edge along the side ([`ElementKind::edges`]:
    /// `bottom` the first, then counter-clockwise).
    fn facet<N: Copy>(cell: [usize; 4], side: Side, node: impl Fn(usize) -> N) -> Option<[N; 2]> {
        let edge = match side {
            Side::Bottom => 0,
            Side::Right => 1,
            Side::Top => 2,
            Side::Left => 3,
            Side::Front | Side::Back => return None,
        };
        let local = ElementKind::Quad4.edges()[edge];
        Some(local.map(|k| node(cell[k])))
    }

    fn reversed(side: Side) -> bool {
        matches!(side, Side::Top | Side::Left)
    }
}

impl BlockDim<3> for Dim<3> {
    type Cell = Cell;
    type Facet<N: Copy> = Face<N>;

    fn cell(block: &Block<3>, c: [usize; 3]) -> Cell {
        Cell::Hex8(block.grid().cell(c, &hex::CORNERS))
    }

    /// The hexahedron's face on the side ([`HEX8_FACES`]).
    fn facet<N: Copy>(cell: Cell, side: Side, node: impl Fn(usize) -> N) -> Option<Face<N>> {
        let face = match side {
            Side::Bottom => 0,
            Side::Top => 1,
            Side::Front => 2,
            Side::Right => 3,
            Side::Back => 4,
            Side::Left => 5,
        };
        match cell {
            Cell::Hex8(n) => Some(Face::Quad4(HEX8_FACES[face].map(|k| node(n[k])))),
            Cell::Tet4(_) => None,
        }
    }

    fn reversed(_: Side) -> bool {
        false
    }
}

/// A block that cannot be generated.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BlockError {
    /// Zero cells along an axis, or a size that is not positive and
    /// finite, or a non-finite origin.
    #[error(
        "a {}D block needs {} of at least 1, a positive finite size and a finite origin ({}, size = {size:?}, origin = {origin:?})",
        cells.len(),
        COUNTS[..cells.len()].join(", "),
        counts(cells)
    )]
    Empty {
        /// Cells along each axis.
        cells: Vec<usize>,
        /// The size.
        size: Vec<f64>,
        /// The origin.
        origin: Vec<f64>,
    },
    /// More nodes than a `usize` counts.
    #[error(
        "a {}D block of {} cells has too many nodes to number",
        cells.len(),
        cells.iter().map(usize::to_string).collect::<Vec<_>>().join(" x ")
    )]
    TooLarge {
        /// Cells along each axis.
        cells: Vec<usize>,
    },
    /// A side that blocks of the dimension do not have.
    #[error("a {dim}D block has no side `{}`", side.name())]
    NoSide {
        /// The side.
        side: Side,
        /// The block's dimension.
        dim: usize,
    },
}

/// The names of the cell counts along the axes.
const COUNTS: [&str; 3] = ["nx", "ny", "nz"];

/// `nx = 2, ny = 3`: the counts by name.
fn counts(cells: &[usize]) -> String {
    COUNTS
        .iter()
        .zip(cells)
        .map(|(k, n)| format!("{k} = {n}"))
        .collect::<Vec<_>>()
        .join(", ")
}

impl<const D: usize> Block<D> {
    /// Checks that the block can be generated: at least one cell along
    /// every axis, a positive finite size, a finite origin, a node count
    /// that fits a `usize`.
    pub fn check(&self) -> Result<(), BlockError> {
        let Block {
            origin,
            size,
            cells,
        } = *self;
        if cells.contains(&0)
            || !size.iter().all(|&s| s > 0.0 && s.is_finite())
            || !origin.iter().all(|v| v.is_finite())
        {
            return Err(BlockError::Empty {
                cells: cells.to_vec(),
                size: size.to_vec(),
                origin: origin.to_vec(),
            });
        }
        let fits = cells
            .iter()
            .try_fold(1_usize, |n, &m| n.checked_mul(m.checked_add(1)?))
            .is_some_and(|n| n < usize::MAX / 8);
        if fits {
            Ok(())
        } else {
            Err(BlockError::TooLarge {
                cells: cells.to_vec(),
            })
        }
    }

    /// The block's grid.
    fn grid(&self) -> Grid<D> {
        Grid {
            origin: self.origin,
            size: self.size,
            cells: self.cells,
        }
    }

    /// The body-local number of node `p` (`p_d <= n_d`; module docs).
    pub fn node(&self, p: [usize; D]) -> usize {
        self.grid().node(p)
    }

    /// The nodes' reference coordinates, in body-local order (module docs).
    pub fn nodes(&self) -> Result<Vec<[f64; D]>, BlockError> {
        self.check()?;
        Ok(self.grid().nodes())
    }
}

impl<const D: usize> Block<D>
where
    Dim<D>: BlockDim<D>,
{
    /// The cells, with body-local nodes, in body-local order (module docs).
    pub fn cells(&self) -> Result<Vec<<Dim<D> as BlockDim<D>>::Cell>, BlockError> {
        self.check()?;
        Ok(Grid::indices(self.cells)
            .map(|c| <Dim<D> as BlockDim<D>>::cell(self, c))
            .collect())
    }

    /// The facets of a side, with body-local nodes, outward and in the
    /// order of the module docs; an error if the block cannot be
    /// generated or has no such side.
    pub fn side(
        &self,
        side: Side,
    ) -> Result<Vec<<Dim<D> as BlockDim<D>>::Facet<usize>>, BlockError> {
        self.facets(side, |n| n)
    }

    /// [`Block::side`] with each node renamed by `node`.
    fn facets<N: Copy>(
        &self,
        side: Side,
        node: impl Fn(usize) -> N + Copy,
    ) -> Result<Vec<<Dim<D> as BlockDim<D>>::Facet<N>>, BlockError> {
        self.check()?;
        let no_side = BlockError::NoSide { side, dim: D };
        let Some((axis, high)) = side.axis::<D>() else {
            return Err(no_side);
        };
        // the cells along the side, the lower in-plane axis fastest
        let mut extent = self.cells;
        extent[axis] = 1;
        let at = if high { self.cells[axis] - 1 } else { 0 };
        let facets: Option<Vec<_>> = Grid::indices(extent)
            .map(|mut c| {
                c[axis] = at;
                let cell = <Dim<D> as BlockDim<D>>::cell(self, c);
                <Dim<D> as BlockDim<D>>::facet(cell, side, node)
            })
            .collect();
        let mut facets = facets.ok_or(no_side)?;
        if <Dim<D> as BlockDim<D>>::reversed(side) {
            facets.reverse();
        }
        Ok(facets)
    }
}

impl<const D: usize> Mesh<D>
where
    Dim<D>: BlockDim<D>,
{
    /// Appends a structured block (module docs): the body's nodes and
    /// elements in the order of [`Block::nodes`] and [`Block::cells`], so
    /// that [`Block::side`]'s body-local nodes plus the body's first node
    /// are its mesh nodes; the body remembers the block
    /// ([`super::Body::block`]). Returns the body's index.
    pub fn add_block(
        &mut self,
        name: &str,
        material: Material,
        block: Block<D>,
    ) -> Result<usize, MeshError> {
        let err = |error| MeshError::Block {
            body: name.to_owned(),
            error,
        };
        let nodes = block.nodes().map_err(err)?;
        let cells = block.cells().map_err(err)?;
        self.push_body(name, material, &nodes, &cells, Some(block))
    }

    /// The facets (global nodes) of a side of a block body, outward and in
    /// the order of the module docs. `None` if the body is not a block or
    /// its block has no such side.
    pub fn block_side(
        &self,
        body: usize,
        side: Side,
    ) -> Option<Vec<<Dim<D> as BlockDim<D>>::Facet<NodeId>>> {
        let b = self.bodies.get(body)?;
        let base = b.nodes.start;
        b.block?.facets(side, |n| NodeId::new(base + n)).ok()
    }
}

#[cfg(test)]
mod tests {
    use std::collections::HashSet;

    use super::*;
    use crate::mesh::faces::BoundaryFaces;
    use crate::mesh::tests::MAT;
    use crate::mesh::volume::dot;

    #[test]
    fn block_numbering_and_sides_are_counter_clockwise() {
        let mut m = Mesh::new();
        for (name, y0) in [("a", 0.0), ("b", 1.0)] {
            let block = Block {
                origin: [0.0, y0],
                size: [2.0, 1.0],
                cells: [2, 1],
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
        // a 2D block has no front or back
        assert_eq!(m.block_side(0, Side::Front), None);
        // interface nodes exist twice
        assert_eq!(m.select_nodes(None, None, Some(1.0)).len(), 6);
        assert_eq!(
            m.select_nodes(Some(1), Some(2.0), Some(2.0)),
            vec![NodeId::new(11)]
        );
    }

    #[test]
    fn a_2d_side_is_a_chain_and_the_boundary() {
        let block = Block {
            origin: [1.0, -2.0],
            size: [2.0, 3.0],
            cells: [3, 2],
        };
        let nodes = block.nodes().unwrap();
        let mut chain = Vec::new();
        for side in [Side::Bottom, Side::Right, Side::Top, Side::Left] {
            let segments = block.side(side).unwrap();
            let (axis, high) = side.axis::<2>().unwrap();
            let plane = block.origin[axis] + if high { block.size[axis] } else { 0.0 };
            for s in &segments {
                assert!(s.iter().all(|&n| (nodes[n][axis] - plane).abs() < 1e-12));
            }
            chain.extend(segments);
        }
        // one closed chain, counter-clockwise: every segment ends where the
        // next starts, around the whole boundary (2 (nx + ny) segments)
        assert_eq!(chain.len(), 2 * (3 + 2));
        for (k, s) in chain.iter().enumerate() {
            assert_eq!(s[1], chain[(k + 1) % chain.len()][0]);
        }
        let area2: f64 = chain
            .iter()
            .map(|&[a, b]| nodes[a][0] * nodes[b][1] - nodes[b][0] * nodes[a][1])
            .sum();
        assert!((area2 / 2.0 - 6.0).abs() < 1e-12, "{area2}");
        assert_eq!(
            block.side(Side::Back),
            Err(BlockError::NoSide {
                side: Side::Back,
                dim: 2
            })
        );
    }

    const BLOCK: Block<3> = Block {
        origin: [1.0, -2.0, 0.5],
        size: [2.0, 3.0, 1.5],
        cells: [2, 3, 4],
    };

    /// Everything the 3D block's geometry promises, for `block`.
    fn check_block(block: Block<3>) {
        let Block {
            origin,
            size,
            cells: n,
        } = block;
        let [nx, ny, nz] = n;
        let nodes = block.nodes().unwrap();
        let cells = block.cells().unwrap();
        assert_eq!(nodes.len(), (nx + 1) * (ny + 1) * (nz + 1));
        assert_eq!(cells.len(), nx * ny * nz);
        let expected_det = size[0] * size[1] * size[2] / (8 * nx * ny * nz) as f64;
        for cell in &cells {
            let x = cell.map_nodes(|n| nodes[n]);
            let (det, _) = x.min_corner_jacobian();
            assert!((det - expected_det).abs() <= 1e-12 * expected_det, "{det}");
            assert!(x.is_valid());
        }
        assert_eq!(
            nodes[block.node([nx, ny, nz])],
            [
                origin[0] + size[0],
                origin[1] + size[1],
                origin[2] + size[2]
            ]
        );

        let mut all_sides = HashSet::new();
        for side in Side::ALL {
            let faces = block.side(side).unwrap();
            let (axis, high) = side.axis::<3>().unwrap();
            assert_eq!(
                faces.len(),
                n.iter().product::<usize>() / n[axis],
                "{side:?}"
            );
            let plane = origin[axis] + if high { size[axis] } else { 0.0 };
            let mut outward = [0.0; 3];
            outward[axis] = if high { 1.0 } else { -1.0 };
            for face in &faces {
                let x = face.map_nodes(|n| nodes[n]);
                assert!(x.nodes().iter().all(|p| (p[axis] - plane).abs() < 1e-12));
                let normal = x.normal();
                let length = dot(normal, normal).sqrt();
                // along the outward axis, with the face's area / 4
                assert!(
                    (dot(normal, outward) - length).abs() <= 1e-12 * length,
                    "{side:?} {normal:?}"
                );
                assert!(all_sides.insert(sorted(face)), "a face twice");
            }
        }
        // the block's boundary is exactly its six sides, each face with
        // the orientation the side gives it
        let boundary = BoundaryFaces::of(&cells);
        assert_eq!(boundary.len(), 2 * (nx * ny + ny * nz + nx * nz));
        assert_eq!(boundary.len(), all_sides.len());
        for side in Side::ALL {
            for face in block.side(side).unwrap() {
                let crate::mesh::faces::FaceLookup::Boundary(b) = boundary.find(face.nodes())
                else {
                    panic!("{face:?} is not a boundary face")
                };
                assert_eq!(b.face, face);
            }
        }
    }

    fn sorted(face: &Face) -> Vec<usize> {
        let mut n = face.nodes().to_vec();
        n.sort_unstable();
        n
    }

    #[test]
    fn block_geometry_sides_and_boundary() {
        check_block(BLOCK);
        check_block(Block {
            cells: [1, 1, 1],
            ..BLOCK
        });
    }

    #[test]
    fn a_refined_block_keeps_its_shape() {
        let [nx, ny, nz] = BLOCK.cells;
        let refined = Block {
            cells: [2 * nx, 2 * ny, 3 * nz],
            ..BLOCK
        };
        check_block(refined);
        // every node of the coarse block is a node of the refined one
        let fine: Vec<[f64; 3]> = refined.nodes().unwrap();
        for p in BLOCK.nodes().unwrap() {
            assert!(
                fine.iter()
                    .any(|q| (0..3).all(|c| (p[c] - q[c]).abs() < 1e-12)),
                "{p:?}"
            );
        }
    }

    #[test]
    fn numbering_and_a_side_in_detail() {
        let block = Block {
            origin: [0.0; 3],
            size: [1.0; 3],
            cells: [2, 1, 1],
        };
        assert_eq!(
            block.cells().unwrap()[1],
            Cell::Hex8([1, 2, 5, 4, 7, 8, 11, 10])
        );
        // the bottom, seen from below: counter-clockwise there
        assert_eq!(
            block.side(Side::Bottom).unwrap(),
            vec![Face::Quad4([0, 3, 4, 1]), Face::Quad4([1, 4, 5, 2])]
        );
        assert_eq!(
            block.side(Side::Right).unwrap(),
            vec![Face::Quad4([2, 5, 11, 8])]
        );
        // the mesh's side is the block's, offset by the body's first node
        let mut mesh = Mesh::<3>::new();
        mesh.add_block("a", MAT, block).unwrap();
        mesh.add_block("b", MAT, block).unwrap();
        assert_eq!(
            mesh.block_side(1, Side::Right),
            Some(vec![Face::Quad4([14, 17, 23, 20].map(NodeId::new))])
        );
    }

    #[test]
    fn empty_and_huge_blocks_are_errors() {
        for bad in [
            Block {
                cells: [2, 3, 0],
                ..BLOCK
            },
            Block {
                size: [1.0, 0.0, 1.0],
                ..BLOCK
            },
            Block {
                size: [1.0, f64::NAN, 1.0],
                ..BLOCK
            },
            Block {
                origin: [f64::INFINITY, 0.0, 0.0],
                ..BLOCK
            },
        ] {
            assert!(matches!(bad.nodes(), Err(BlockError::Empty { .. })));
            assert!(bad.cells().is_err() && bad.side(Side::Top).is_err());
        }
        let huge = Block {
            cells: [usize::MAX, 3, 4],
            ..BLOCK
        };
        assert!(matches!(huge.check(), Err(BlockError::TooLarge { .. })));
        let huge = Block {
            cells: [1 << 22; 3],
            ..BLOCK
        };
        assert!(matches!(huge.cells(), Err(BlockError::TooLarge { .. })));
        assert_eq!(
            Block {
                cells: [2, 3, 0],
                ..BLOCK
            }
            .check()
            .unwrap_err()
            .to_string(),
            "a 3D block needs nx, ny, nz of at least 1, a positive finite size and a finite origin \
             (nx = 2, ny = 3, nz = 0, size = [2.0, 3.0, 1.5], origin = [1.0, -2.0, 0.5])"
        );
        // 2D blocks are checked the same way
        let flat = Block {
            origin: [0.0, 0.0],
            size: [1.0, f64::INFINITY],
            cells: [1, 1],
        };
        let mut mesh = Mesh::new();
        let err = mesh.add_block("flat", MAT, flat).unwrap_err();
        assert_eq!(
            err.to_string(),
            "block of body `flat`: a 2D block needs nx, ny of at least 1, a positive finite size \
             and a finite origin (nx = 1, ny = 1, size = [1.0, inf], origin = [0.0, 0.0])"
        );
    }
}
