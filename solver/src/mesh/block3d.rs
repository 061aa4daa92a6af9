//! Structured 3D blocks of hexahedra: the 3D body generator, with its six
//! sides as quad4 faces.
//!
//! A block with origin `(x0, y0, z0)`, size `(a, b, c)` and `nx x ny x nz`
//! cells has the nodes `(i, j, k)`, `i = 0..=nx`, `j = 0..=ny`,
//! `k = 0..=nz`, at `(x0 + i a/nx, y0 + j b/ny, z0 + k c/nz)`, numbered
//! `(k (ny + 1) + j)(nx + 1) + i` within the body, and the cells `(i, j, k)`
//! numbered `(k ny + j) nx + i`, each a [`Cell::Hex8`] with the nodes
//! `(i,j,k), (i+1,j,k), (i+1,j+1,k), (i,j+1,k)`, then the same at `k + 1`
//! (Gmsh's order; every corner Jacobian is `abc / (8 nx ny nz)`): the 3D
//! [`super::grid`], as the 2D blocks'.
//!
//! Its sides ([`Side3d`]): `left`/`right` at the smallest/largest x,
//! `front`/`back` at the smallest/largest y, `bottom`/`top` at the
//! smallest/largest z. A side's faces are the faces of the cells along it
//! ([`super::volume::HEX8_FACES`]: the cell's face `xi = -1` for `left`,
//! `xi = +1` for `right`, `eta = -1` front, `eta = +1` back, `zeta = -1`
//! bottom, `zeta = +1` top), so each runs counter-clockwise seen from
//! outside the block; they are ordered by the side's two in-plane indices,
//! the one of the lower axis (x before y before z) running fastest.

use serde::{Deserialize, Serialize};

use super::grid::Grid;
use super::volume::{Cell, Face, HEX8_FACES};
use crate::element::hex::CORNERS;

/// A structured block of hexahedra.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Block3d {
    /// The corner of smallest x, y and z (reference frame).
    pub origin: [f64; 3],
    /// The extents along x, y and z.
    pub size: [f64; 3],
    /// Cells along x.
    pub nx: usize,
    /// Cells along y.
    pub ny: usize,
    /// Cells along z.
    pub nz: usize,
}

/// A side of a 3D block.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Side3d {
    /// The smallest x.
    Left,
    /// The largest x.
    Right,
    /// The smallest y.
    Front,
    /// The largest y.
    Back,
    /// The smallest z.
    Bottom,
    /// The largest z.
    Top,
}

impl Side3d {
    /// All six, in declaration order.
    pub const ALL: [Side3d; 6] = [
        Side3d::Left,
        Side3d::Right,
        Side3d::Front,
        Side3d::Back,
        Side3d::Bottom,
        Side3d::Top,
    ];

    /// The side's name as written in scene files.
    pub fn name(self) -> &'static str {
        match self {
            Side3d::Left => "left",
            Side3d::Right => "right",
            Side3d::Front => "front",
            Side3d::Back => "back",
            Side3d::Bottom => "bottom",
            Side3d::Top => "top",
        }
    }

    /// The axis normal to it (0 x, 1 y, 2 z) and whether it is at that
    /// axis' largest coordinate.
    pub fn axis(self) -> (usize, bool) {
        match self {
            Side3d::Left => (0, false),
            Side3d::Right => (0, true),
            Side3d::Front => (1, false),
            Side3d::Back => (1, true),
            Side3d::Bottom => (2, false),
            Side3d::Top => (2, true),
        }
    }

    /// The local face of a [`Cell::Hex8`] ([`HEX8_FACES`]) that lies on it.
    fn local_face(self) -> usize {
        match self {
            Side3d::Bottom => 0,
            Side3d::Top => 1,
            Side3d::Front => 2,
            Side3d::Right => 3,
            Side3d::Back => 4,
            Side3d::Left => 5,
        }
    }
}

/// A block that cannot be generated.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Block3dError {
    /// Zero cells along an axis, or a size that is not positive and
    /// finite, or a non-finite origin.
    #[error(
        "a 3D block needs nx, ny, nz of at least 1, a positive finite size and a finite origin (nx = {nx}, ny = {ny}, nz = {nz}, size = {size:?}, origin = {origin:?})"
    )]
    Empty {
        /// Cells along x.
        nx: usize,
        /// Cells along y.
        ny: usize,
        /// Cells along z.
        nz: usize,
        /// The size.
        size: [f64; 3],
        /// The origin.
        origin: [f64; 3],
    },
    /// More nodes than a `usize` counts.
    #[error("a 3D block of {nx} x {ny} x {nz} cells has too many nodes to number")]
    TooLarge {
        /// Cells along x.
        nx: usize,
        /// Cells along y.
        ny: usize,
        /// Cells along z.
        nz: usize,
    },
}

impl Block3d {
    /// Checks that the block can be generated: at least one cell along
    /// every axis, a positive finite size, a finite origin, a node count
    /// that fits a `usize`.
    pub fn check(&self) -> Result<(), Block3dError> {
        let Block3d {
            origin,
            size,
            nx,
            ny,
            nz,
        } = *self;
        if nx == 0
            || ny == 0
            || nz == 0
            || !size.iter().all(|&s| s > 0.0 && s.is_finite())
            || !origin.iter().all(|v| v.is_finite())
        {
            return Err(Block3dError::Empty {
                nx,
                ny,
                nz,
                size,
                origin,
            });
        }
        let fits = [nx, ny, nz]
            .iter()
            .try_fold(1_usize, |n, &m| n.checked_mul(m.checked_add(1)?))
            .is_some_and(|n| n < usize::MAX / 8);
        if fits {
            Ok(())
        } else {
            Err(Block3dError::TooLarge { nx, ny, nz })
        }
    }

    /// The block's grid (cells `nx, ny, nz`).
    fn grid(&self) -> Grid<3> {
        Grid {
            origin: self.origin,
            size: self.size,
            cells: [self.nx, self.ny, self.nz],
        }
    }

    /// The body-local number of node `(i, j, k)`.
    pub fn node(&self, i: usize, j: usize, k: usize) -> usize {
        self.grid().node([i, j, k])
    }

    /// The nodes' reference coordinates, in body-local order (module docs).
    pub fn nodes(&self) -> Result<Vec<[f64; 3]>, Block3dError> {
        self.check()?;
        Ok(self.grid().nodes())
    }

    /// The cells, with body-local nodes, in body-local order (module docs).
    pub fn cells(&self) -> Result<Vec<Cell>, Block3dError> {
        self.check()?;
        Ok(self
            .grid()
            .cells(&CORNERS)
            .into_iter()
            .map(Cell::Hex8)
            .collect())
    }

    /// The quad4 faces of a side, with body-local nodes, counter-clockwise
    /// seen from outside the block, in the order of the module docs.
    pub fn side(&self, side: Side3d) -> Result<Vec<Face>, Block3dError> {
        self.check()?;
        let (axis, high) = side.axis();
        let n = [self.nx, self.ny, self.nz];
        let at = if high { n[axis] - 1 } else { 0 };
        // the two in-plane axes, the lower one fastest
        let (a, b) = match axis {
            0 => (1, 2),
            1 => (0, 2),
            _ => (0, 1),
        };
        let local = HEX8_FACES[side.local_face()];
        let mut faces = Vec::with_capacity(n[a] * n[b]);
        for q in 0..n[b] {
            for p in 0..n[a] {
                let mut ijk = [0; 3];
                ijk[axis] = at;
                ijk[a] = p;
                ijk[b] = q;
                let nodes = self.grid().cell(ijk, &CORNERS);
                faces.push(Face::Quad4(local.map(|k| nodes[k])));
            }
        }
        Ok(faces)
    }
}

impl super::Mesh<3> {
    /// Appends a structured block of hexahedra (see the module docs; the
    /// body's nodes and elements in the order of [`Block3d::nodes`] and
    /// [`Block3d::cells`], so that [`Block3d::side`]'s body-local nodes
    /// plus the body's first node are its mesh nodes). Returns the body's
    /// index.
    pub fn add_block3d(
        &mut self,
        name: &str,
        material: crate::material::Material,
        block: Block3d,
    ) -> Result<usize, super::MeshError> {
        let err = |error| super::MeshError::Block3d {
            body: name.to_owned(),
            error,
        };
        let nodes = block.nodes().map_err(err)?;
        let cells = block.cells().map_err(err)?;
        self.push_body(name, material, &nodes, &cells, None)
    }
}

#[cfg(test)]
mod tests {
    use std::collections::HashSet;

    use super::*;
    use crate::mesh::faces::BoundaryFaces;
    use crate::mesh::volume::dot;

    const BLOCK: Block3d = Block3d {
        origin: [1.0, -2.0, 0.5],
        size: [2.0, 3.0, 1.5],
        nx: 2,
        ny: 3,
        nz: 4,
    };

    /// Everything the block's geometry promises, for `block`.
    fn check_block(block: Block3d) {
        let Block3d {
            origin,
            size,
            nx,
            ny,
            nz,
        } = block;
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
            nodes[block.node(nx, ny, nz)],
            [
                origin[0] + size[0],
                origin[1] + size[1],
                origin[2] + size[2]
            ]
        );

        let mut all_sides = HashSet::new();
        for side in Side3d::ALL {
            let faces = block.side(side).unwrap();
            let (axis, high) = side.axis();
            let n = [nx, ny, nz];
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
        for side in Side3d::ALL {
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
        check_block(Block3d {
            nx: 1,
            ny: 1,
            nz: 1,
            ..BLOCK
        });
    }

    #[test]
    fn a_refined_block_keeps_its_shape() {
        let refined = Block3d {
            nx: 2 * BLOCK.nx,
            ny: 2 * BLOCK.ny,
            nz: 3 * BLOCK.nz,
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
        let block = Block3d {
            origin: [0.0; 3],
            size: [1.0; 3],
            nx: 2,
            ny: 1,
            nz: 1,
        };
        assert_eq!(
            block.cells().unwrap()[1],
            Cell::Hex8([1, 2, 5, 4, 7, 8, 11, 10])
        );
        // the bottom, seen from below: counter-clockwise there
        assert_eq!(
            block.side(Side3d::Bottom).unwrap(),
            vec![Face::Quad4([0, 3, 4, 1]), Face::Quad4([1, 4, 5, 2])]
        );
        assert_eq!(
            block.side(Side3d::Right).unwrap(),
            vec![Face::Quad4([2, 5, 11, 8])]
        );
    }

    #[test]
    fn empty_and_huge_blocks_are_errors() {
        for bad in [
            Block3d { nz: 0, ..BLOCK },
            Block3d {
                size: [1.0, 0.0, 1.0],
                ..BLOCK
            },
            Block3d {
                size: [1.0, f64::NAN, 1.0],
                ..BLOCK
            },
            Block3d {
                origin: [f64::INFINITY, 0.0, 0.0],
                ..BLOCK
            },
        ] {
            assert!(matches!(bad.nodes(), Err(Block3dError::Empty { .. })));
            assert!(bad.cells().is_err() && bad.side(Side3d::Top).is_err());
        }
        let huge = Block3d {
            nx: usize::MAX,
            ..BLOCK
        };
        assert!(matches!(huge.check(), Err(Block3dError::TooLarge { .. })));
        let huge = Block3d {
            nx: 1 << 22,
            ny: 1 << 22,
            nz: 1 << 22,
            ..BLOCK
        };
        assert!(matches!(huge.cells(), Err(Block3dError::TooLarge { .. })));
    }
}
