//! Volume cells of a 3D mesh (the 8-node hexahedron and the 4-node
//! tetrahedron), their faces, and the checks on their reference geometry:
//! the data that 3D mesh generators and readers produce ([`super::block3d`],
//! [`super::gmsh::MshVolumeMesh`]) and that [`super::faces`] takes the
//! boundary of.
//!
//! Node order is Gmsh's (and VTK's) for both cells:
//!
//! * [`Cell::Hex8`]: nodes 0-3 the face `zeta = -1` and 4-7 the face
//!   `zeta = +1`, at the natural coordinates [`CORNERS`]
//!   (`(-1,-1,-1), (1,-1,-1), (1,1,-1), (-1,1,-1)`, then the same at
//!   `zeta = 1`); positive when `(x1 - x0) x (x3 - x0) . (x4 - x0) > 0` at
//!   every corner (see [`Cell::min_corner_jacobian`]);
//! * [`Cell::Tet4`]: positive when `(x1 - x0) x (x2 - x0) . (x3 - x0) > 0`.
//!
//! A [`Face`] is a quad4 or a tri3 whose nodes run counter-clockwise seen
//! from outside the cell it bounds, so that its normal `t_1 x t_2`
//! (`t_1 = dx/du`, `t_2 = dx/dv` in the conventions' face parametrisation)
//! points out. [`Cell::faces`] lists a cell's faces that way: the table
//! [`HEX8_FACES`] (six quad4s) or [`TET4_FACES`] (four tri3s).

use crate::element::geometry::min_det;
use crate::element::hex::CORNERS;
use crate::element::{ElementKind, FaceKind};

/// The hexahedron's faces as its local nodes, each counter-clockwise seen
/// from outside: `zeta = -1`, `zeta = +1`, `eta = -1`, `xi = +1`,
/// `eta = +1`, `xi = -1`.
pub const HEX8_FACES: [[usize; 4]; 6] = [
    [0, 3, 2, 1],
    [4, 5, 6, 7],
    [0, 1, 5, 4],
    [1, 2, 6, 5],
    [2, 3, 7, 6],
    [3, 0, 4, 7],
];

/// The tetrahedron's faces as its local nodes, each counter-clockwise seen
/// from outside: opposite node 3, 2, 0 and 1.
pub const TET4_FACES: [[usize; 3]; 4] = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]];

/// The connectivity of one volume cell, in Gmsh's node order (module
/// docs). `N` is the node index.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Cell<N = usize> {
    /// An 8-node hexahedron.
    Hex8([N; 8]),
    /// A 4-node tetrahedron.
    Tet4([N; 4]),
}

impl<N> From<Cell<N>> for crate::element::Element<N> {
    /// The solid element of a cell (the same nodes, in the same order).
    fn from(cell: Cell<N>) -> Self {
        match cell {
            Cell::Hex8(n) => crate::element::Element::Hex8(n),
            Cell::Tet4(n) => crate::element::Element::Tet4(n),
        }
    }
}

/// One face of a volume mesh: its nodes counter-clockwise seen from outside
/// the cell it bounds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Face<N = usize> {
    /// A 4-node quadrilateral face.
    Quad4([N; 4]),
    /// A 3-node triangular face.
    Tri3([N; 3]),
}

impl<N: Copy> Cell<N> {
    /// Its kind.
    pub fn kind(&self) -> ElementKind {
        match self {
            Cell::Hex8(_) => ElementKind::Hex8,
            Cell::Tet4(_) => ElementKind::Tet4,
        }
    }

    /// Its nodes, in Gmsh's order.
    pub fn nodes(&self) -> &[N] {
        match self {
            Cell::Hex8(n) => n,
            Cell::Tet4(n) => n,
        }
    }

    /// The same cell with every node mapped by `f`.
    pub fn map_nodes<M>(self, f: impl FnMut(N) -> M) -> Cell<M> {
        match self {
            Cell::Hex8(n) => Cell::Hex8(n.map(f)),
            Cell::Tet4(n) => Cell::Tet4(n.map(f)),
        }
    }

    /// Its faces, each counter-clockwise seen from outside ([`HEX8_FACES`],
    /// [`TET4_FACES`] in that order).
    pub fn faces(&self) -> Vec<Face<N>> {
        match self {
            Cell::Hex8(n) => HEX8_FACES
                .iter()
                .map(|f| Face::Quad4(f.map(|k| n[k])))
                .collect(),
            Cell::Tet4(n) => TET4_FACES
                .iter()
                .map(|f| Face::Tri3(f.map(|k| n[k])))
                .collect(),
        }
    }
}

impl Cell<[f64; 3]> {
    /// The smallest Jacobian determinant of the cell's map from its
    /// natural coordinates, over its corners (a hexahedron's trilinear
    /// map at each of its 8 nodes; a tetrahedron's constant
    /// `(x1 - x0) x (x2 - x0) . (x3 - x0)`), and the corner (local node)
    /// where it is reached. NaN for non-finite coordinates.
    pub fn min_corner_jacobian(&self) -> (f64, usize) {
        match self {
            Cell::Tet4(x) => (triple(sub(x[1], x[0]), sub(x[2], x[0]), sub(x[3], x[0])), 0),
            Cell::Hex8(x) => {
                let mut worst = (f64::INFINITY, 0);
                for (a, p) in CORNERS.iter().enumerate() {
                    // J[:, j] = sum_b x_b dN_b/dxi_j at the corner p
                    let mut columns = [[0.0; 3]; 3];
                    for (b, xb) in x.iter().enumerate() {
                        let q = CORNERS[b];
                        for (j, column) in columns.iter_mut().enumerate() {
                            let mut d = q[j] / 8.0;
                            for k in (0..3).filter(|&k| k != j) {
                                d *= 1.0 + q[k] * p[k];
                            }
                            for c in 0..3 {
                                column[c] += xb[c] * d;
                            }
                        }
                    }
                    let det = triple(columns[0], columns[1], columns[2]);
                    if det.is_nan() {
                        return (f64::NAN, a);
                    }
                    if det < worst.0 {
                        worst = (det, a);
                    }
                }
                worst
            }
        }
    }

    /// Whether the cell is positive: its smallest corner Jacobian (see
    /// [`Cell::min_corner_jacobian`]) exceeds the elements' degeneracy
    /// floor [`min_det`] (`MIN_RELATIVE_DET l^3`, `l` its longest edge; a
    /// hexahedron at that floor or below is inverted or degenerate at a
    /// corner, a tetrahedron flat or inverted). Cells of non-finite
    /// coordinates are not valid.
    pub fn is_valid(&self) -> bool {
        let (det, _) = self.min_corner_jacobian();
        det > min_det(self.kind(), self.nodes())
    }
}

impl<N: Copy> Face<N> {
    /// Its kind.
    pub fn kind(&self) -> FaceKind {
        match self {
            Face::Quad4(_) => FaceKind::Quad4,
            Face::Tri3(_) => FaceKind::Tri3,
        }
    }

    /// Its nodes, counter-clockwise seen from outside.
    pub fn nodes(&self) -> &[N] {
        match self {
            Face::Quad4(n) => n,
            Face::Tri3(n) => n,
        }
    }

    /// The same face with every node mapped by `f`.
    pub fn map_nodes<M>(self, f: impl FnMut(N) -> M) -> Face<M> {
        match self {
            Face::Quad4(n) => Face::Quad4(n.map(f)),
            Face::Tri3(n) => Face::Tri3(n.map(f)),
        }
    }
}

impl Face<[f64; 3]> {
    /// The unnormalised normal `t_1 x t_2` at the face's centre (tri3:
    /// `(x1 - x0) x (x2 - x0)`; quad4: the bilinear map's `dx/du x dx/dv`
    /// at `u = v = 0`, with `u` along nodes 0 -> 1 and `v` along 0 -> 3),
    /// pointing out of the cell for a face of [`Cell::faces`].
    pub fn normal(&self) -> [f64; 3] {
        match self {
            Face::Tri3(x) => cross(sub(x[1], x[0]), sub(x[2], x[0])),
            Face::Quad4(x) => {
                // dx/du = (x1 + x2 - x0 - x3)/4, dx/dv = (x2 + x3 - x0 - x1)/4
                let t1 = std::array::from_fn(|c| (x[1][c] + x[2][c] - x[0][c] - x[3][c]) / 4.0);
                let t2 = std::array::from_fn(|c| (x[2][c] + x[3][c] - x[0][c] - x[1][c]) / 4.0);
                cross(t1, t2)
            }
        }
    }

    /// The centroid of its nodes.
    pub fn centroid(&self) -> [f64; 3] {
        let x = self.nodes();
        let n = x.len() as f64;
        std::array::from_fn(|c| x.iter().map(|p| p[c]).sum::<f64>() / n)
    }
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `a x b`.
pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `a x b . c`.
fn triple(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    let n = cross(a, b);
    n[0] * c[0] + n[1] * c[1] + n[2] * c[2]
}

/// `a . b`.
pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The unit cube's hexahedron and a tetrahedron at the origin.
    fn unit_hex() -> Cell<[f64; 3]> {
        Cell::Hex8(CORNERS.map(|p| p.map(|v| (v + 1.0) / 2.0)))
    }

    fn unit_tet() -> Cell<[f64; 3]> {
        Cell::Tet4([
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ])
    }

    /// Every face of `cell` points away from the cell's centroid.
    fn faces_point_out(cell: &Cell<[f64; 3]>) {
        let x = cell.nodes();
        let centre: [f64; 3] =
            std::array::from_fn(|c| x.iter().map(|p| p[c]).sum::<f64>() / x.len() as f64);
        for face in cell.faces() {
            let out = sub(face.centroid(), centre);
            assert!(dot(face.normal(), out) > 0.0, "{face:?}");
        }
    }

    #[test]
    fn cell_faces_point_out() {
        faces_point_out(&unit_hex());
        faces_point_out(&unit_tet());
        // a sheared, stretched hexahedron
        let Cell::Hex8(x) = unit_hex() else {
            unreachable!()
        };
        let sheared = Cell::Hex8(x.map(|[a, b, c]| [3.0 * a + 0.5 * c, 2.0 * b + 0.3 * a, c]));
        faces_point_out(&sheared);
        assert!(sheared.is_valid());
    }

    #[test]
    fn jacobians_of_the_unit_cells() {
        // the unit cube maps [-1, 1]^3 with J = I/2
        let (det, _) = unit_hex().min_corner_jacobian();
        assert!((det - 0.125).abs() < 1e-15, "{det}");
        assert_eq!(unit_tet().min_corner_jacobian(), (1.0, 0));
        assert!(unit_hex().is_valid() && unit_tet().is_valid());
    }

    #[test]
    fn inverted_and_degenerate_cells_are_invalid() {
        let Cell::Tet4([a, b, c, d]) = unit_tet() else {
            unreachable!()
        };
        assert!(!Cell::Tet4([a, c, b, d]).is_valid());
        assert!(!Cell::Tet4([a, b, c, [0.5, 0.5, 0.0]]).is_valid());
        let Cell::Hex8(x) = unit_hex() else {
            unreachable!()
        };
        // bottom and top swapped: inverted everywhere
        let flipped = [x[4], x[5], x[6], x[7], x[0], x[1], x[2], x[3]];
        assert!(Cell::Hex8(flipped).min_corner_jacobian().0 < 0.0);
        assert!(!Cell::Hex8(flipped).is_valid());
        // one corner pushed through the opposite face: inverted at that
        // corner only
        let mut dented = x;
        dented[6] = [0.2, 0.2, 0.2];
        let (det, corner) = Cell::Hex8(dented).min_corner_jacobian();
        assert!(det < 0.0 && corner == 6, "{det} at {corner}");
        // a collapsed edge: zero Jacobian at its corners
        let mut collapsed = x;
        collapsed[1] = collapsed[0];
        assert!(!Cell::Hex8(collapsed).is_valid());
        let mut nan = x;
        nan[3][1] = f64::NAN;
        assert!(!Cell::Hex8(nan).is_valid());
    }
}
