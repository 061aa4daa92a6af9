//! The boundary faces of a volume mesh: the faces of its cells
//! ([`Cell::faces`]) that belong to exactly one cell, each oriented
//! outward by that cell (counter-clockwise seen from outside). A face is
//! identified by its set of nodes, so two cells share a face when they
//! share all of its nodes, whatever order each lists them in; a face of
//! two or more cells is interior.
//!
//! [`BoundaryFaces`] holds them, in cell order then each cell's face order
//! ([`super::volume::HEX8_FACES`], [`super::volume::TET4_FACES`]), and
//! answers which cell owns a face given its nodes in any order
//! ([`BoundaryFaces::find`]): how the Gmsh reader orients a physical
//! surface's elements, and how contact surfaces are found on a volume body.

use std::collections::HashMap;

use super::volume::{Cell, Face};

/// One boundary face: the cell that owns it, which of that cell's faces it
/// is, and its nodes oriented outward.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BoundaryFace {
    /// The owning cell (index into the cells the faces were taken from).
    pub cell: usize,
    /// Its local face number (into [`Cell::faces`]).
    pub local: usize,
    /// The face, counter-clockwise seen from outside the cell.
    pub face: Face,
}

/// How a set of nodes relates to the faces of a mesh's cells
/// ([`BoundaryFaces::find`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FaceLookup<'a> {
    /// A boundary face, owned by one cell.
    Boundary(&'a BoundaryFace),
    /// A face of `cells` cells (two or more): interior.
    Interior {
        /// How many cells have it.
        cells: usize,
    },
    /// No cell has a face with these nodes.
    Missing,
}

/// The boundary faces of a set of cells (module docs).
#[derive(Debug, Clone, Default)]
pub struct BoundaryFaces {
    faces: Vec<BoundaryFace>,
    /// Every face's sorted nodes -> (cells that have it, the boundary
    /// face's index in `faces` when there is exactly one).
    index: HashMap<Vec<usize>, (usize, Option<usize>)>,
}

impl BoundaryFaces {
    /// The boundary faces of `cells`.
    pub fn of(cells: &[Cell]) -> BoundaryFaces {
        // (cells that have it, the first of them and its local face)
        let mut seen: HashMap<Vec<usize>, (usize, usize, usize)> = HashMap::new();
        let mut order: Vec<Vec<usize>> = Vec::new();
        for (c, cell) in cells.iter().enumerate() {
            for (local, face) in cell.faces().iter().enumerate() {
                let key = sorted(face.nodes());
                match seen.get_mut(&key) {
                    Some(entry) => entry.0 += 1,
                    None => {
                        seen.insert(key.clone(), (1, c, local));
                        order.push(key);
                    }
                }
            }
        }
        let mut faces = Vec::new();
        let mut index = HashMap::with_capacity(order.len());
        for key in order {
            let (count, cell, local) = seen[&key];
            let at = (count == 1).then(|| {
                faces.push(BoundaryFace {
                    cell,
                    local,
                    face: cells[cell].faces()[local],
                });
                faces.len() - 1
            });
            index.insert(key, (count, at));
        }
        BoundaryFaces { faces, index }
    }

    /// The boundary faces, in the order of their cells, then of each
    /// cell's faces.
    pub fn faces(&self) -> &[BoundaryFace] {
        &self.faces
    }

    /// Their number.
    pub fn len(&self) -> usize {
        self.faces.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.faces.is_empty()
    }

    /// The face whose nodes are `nodes`, in any order.
    pub fn find(&self, nodes: &[usize]) -> FaceLookup<'_> {
        match self.index.get(&sorted(nodes)) {
            Some(&(_, Some(at))) => FaceLookup::Boundary(&self.faces[at]),
            Some(&(cells, None)) => FaceLookup::Interior { cells },
            None => FaceLookup::Missing,
        }
    }
}

fn sorted(nodes: &[usize]) -> Vec<usize> {
    let mut key = nodes.to_vec();
    key.sort_unstable();
    key
}

/// `face` (outward) rotated to start at node `first`, if it has it; else
/// as it is. A surface element read from a file keeps its first node, and
/// its own order when that is already outward.
pub fn starting_at(face: Face, first: usize) -> Face {
    fn rotate<const K: usize>(mut n: [usize; K], first: usize) -> [usize; K] {
        if let Some(at) = n.iter().position(|&v| v == first) {
            n.rotate_left(at);
        }
        n
    }
    match face {
        Face::Quad4(n) => Face::Quad4(rotate(n, first)),
        Face::Tri3(n) => Face::Tri3(rotate(n, first)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::volume::dot;

    /// A cube `[0, 1]^3` cut into six tetrahedra around its diagonal 0-6
    /// (Kuhn's triangulation), nodes numbered as a hexahedron's.
    fn kuhn_cube() -> (Vec<[f64; 3]>, Vec<Cell>) {
        let nodes = crate::element::hex::CORNERS
            .map(|p| p.map(|v| (v + 1.0) / 2.0))
            .to_vec();
        let cells = crate::element::hex::KUHN_TETS
            .iter()
            .map(|&t| {
                let cell = Cell::Tet4(t);
                // orient positively
                if cell.map_nodes(|n| nodes[n]).is_valid() {
                    cell
                } else {
                    Cell::Tet4([t[0], t[2], t[1], t[3]])
                }
            })
            .collect();
        (nodes, cells)
    }

    #[test]
    fn a_tetrahedral_cube_has_twelve_outward_triangles() {
        let (nodes, cells) = kuhn_cube();
        assert!(cells.iter().all(|c| c.map_nodes(|n| nodes[n]).is_valid()));
        let boundary = BoundaryFaces::of(&cells);
        assert_eq!(boundary.len(), 12);
        let centre = [0.5; 3];
        for f in boundary.faces() {
            let x = f.face.map_nodes(|n| nodes[n]);
            let c = x.centroid();
            let out = [c[0] - centre[0], c[1] - centre[1], c[2] - centre[2]];
            assert!(dot(x.normal(), out) > 0.0, "{f:?}");
            // on the cube's surface
            assert!(
                c.iter()
                    .any(|&v| v.abs() < 1e-12 || (v - 1.0).abs() < 1e-12)
            );
        }
        // 24 face slots: 12 on the boundary, 6 interior faces of two each
        assert_eq!(
            boundary.find(&[6, 0, 2]),
            FaceLookup::Interior { cells: 2 },
            "the face 0-2-6 is between two tetrahedra"
        );
        assert_eq!(boundary.find(&[0, 1, 4]), FaceLookup::Missing);
        let FaceLookup::Boundary(f) = boundary.find(&[1, 2, 0]) else {
            panic!("the bottom triangle 0-1-2 is a boundary face")
        };
        assert_eq!(f.cell, 0);
        // seen from below (outside) 0-2-1 is counter-clockwise
        assert_eq!(starting_at(f.face, 0), Face::Tri3([0, 2, 1]));
    }

    #[test]
    fn a_single_cell_is_all_boundary() {
        let cell = Cell::Hex8([0, 1, 2, 3, 4, 5, 6, 7]);
        let boundary = BoundaryFaces::of(&[cell]);
        assert_eq!(boundary.len(), 6);
        assert_eq!(
            boundary.faces().iter().map(|f| f.face).collect::<Vec<_>>(),
            cell.faces()
        );
        assert!(BoundaryFaces::of(&[]).is_empty());
    }

    #[test]
    fn rotation_keeps_the_cycle() {
        let face = Face::Quad4([3, 0, 4, 7]);
        assert_eq!(starting_at(face, 4), Face::Quad4([4, 7, 3, 0]));
        assert_eq!(starting_at(face, 9), face);
    }
}
