//! The shape functions of the tri3 and quad4 faces (docs/conventions.md,
//! "3D faces") and the point and tangents they interpolate.
//!
//! - tri3 on the unit triangle `u, v >= 0`, `u + v <= 1`:
//!   `N = (1 - u - v, u, v)`;
//! - quad4 on `[-1, 1]^2`, nodes at `(-1,-1), (1,-1), (1,1), (-1,1)`
//!   (Gmsh's order): `N_a = (1 + u u_a)(1 + v v_a) / 4`.
//!
//! The point is `x(u, v) = sum_a N_a x_a`, the tangents `t_1 = dx/du`,
//! `t_2 = dx/dv`, and the outward normal of a face whose nodes run
//! counter-clockwise seen from outside is along `t_1 x t_2`.
//!
//! Invariant: entries beyond the face's node count are zero.

use super::volume::Face;
use crate::element::FaceKind;

/// The quad4's reference corners, in Gmsh's node order.
pub const QUAD4_CORNERS: [[f64; 2]; 4] = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];

/// The shape functions of one face kind at one point and their
/// derivatives (module docs); `count` entries used.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FaceShape {
    /// `N_a(u, v)`.
    pub n: [f64; 4],
    /// `dN_a/du`.
    pub du: [f64; 4],
    /// `dN_a/dv`.
    pub dv: [f64; 4],
    /// The face's node count (3 or 4).
    pub count: usize,
}

impl FaceShape {
    /// The shape functions of `kind` at `xi = (u, v)` (a segment's at `u`).
    pub fn at(kind: FaceKind, [u, v]: [f64; 2]) -> FaceShape {
        match kind {
            FaceKind::Segment => FaceShape {
                n: [(1.0 - u) / 2.0, (1.0 + u) / 2.0, 0.0, 0.0],
                du: [-0.5, 0.5, 0.0, 0.0],
                dv: [0.0; 4],
                count: 2,
            },
            FaceKind::Tri3 => FaceShape {
                n: [1.0 - u - v, u, v, 0.0],
                du: [-1.0, 1.0, 0.0, 0.0],
                dv: [-1.0, 0.0, 1.0, 0.0],
                count: 3,
            },
            FaceKind::Quad4 => {
                let mut s = FaceShape {
                    n: [0.0; 4],
                    du: [0.0; 4],
                    dv: [0.0; 4],
                    count: 4,
                };
                for (a, [ua, va]) in QUAD4_CORNERS.iter().enumerate() {
                    s.n[a] = (1.0 + ua * u) * (1.0 + va * v) / 4.0;
                    s.du[a] = ua * (1.0 + va * v) / 4.0;
                    s.dv[a] = va * (1.0 + ua * u) / 4.0;
                }
                s
            }
        }
    }
}

impl Face<[f64; 3]> {
    /// The point `x(u, v)` and the tangents `t_1 = dx/du`, `t_2 = dx/dv` at
    /// `xi = (u, v)` (module docs), each summed in node order.
    pub fn point_and_tangents(&self, xi: [f64; 2]) -> [[f64; 3]; 3] {
        let s = FaceShape::at(self.kind(), xi);
        let mut out = [[0.0; 3]; 3];
        for (a, x) in self.nodes().iter().enumerate() {
            for c in 0..3 {
                out[0][c] += s.n[a] * x[c];
                out[1][c] += s.du[a] * x[c];
                out[2][c] += s.dv[a] * x[c];
            }
        }
        out
    }

    /// `|t_1 x t_2|` at `xi`: the area element `dA = |t_1 x t_2| du dv`.
    pub fn area_element(&self, xi: [f64; 2]) -> f64 {
        let [_, t1, t2] = self.point_and_tangents(xi);
        let n = super::volume::cross(t1, t2);
        (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt()
    }

    /// The face's size: the square root of its area as the one-point rule
    /// at its centre gives it (exact for a flat tri3 and a parallelogram).
    pub fn size(&self) -> f64 {
        match self {
            Face::Tri3(_) => (self.area_element([1.0 / 3.0, 1.0 / 3.0]) / 2.0).sqrt(),
            Face::Quad4(_) => (4.0 * self.area_element([0.0, 0.0])).sqrt(),
        }
    }

    /// `t_1 x t_2` at `xi` (unnormalised; outward for a face of its body).
    pub fn normal_at(&self, xi: [f64; 2]) -> [f64; 3] {
        let [_, t1, t2] = self.point_and_tangents(xi);
        super::volume::cross(t1, t2)
    }
}

/// Whether `xi` lies on a face of `kind`, within `tol` of its boundary:
/// tri3 `u, v >= -tol`, `u + v <= 1 + tol`; quad4 `|u|, |v| <= 1 + tol`;
/// a segment `|u| <= 1 + tol`.
pub fn inside(kind: FaceKind, [u, v]: [f64; 2], tol: f64) -> bool {
    match kind {
        FaceKind::Segment => u.abs() <= 1.0 + tol,
        FaceKind::Tri3 => u >= -tol && v >= -tol && u + v <= 1.0 + tol,
        FaceKind::Quad4 => u.abs() <= 1.0 + tol && v.abs() <= 1.0 + tol,
    }
}

/// How far `xi` lies from the centre of a face of `kind`, 1 on its
/// boundary (the reach of a projection, [`crate::contact::ContactSpace`]):
/// quad4 `max(|u|, |v|)`, tri3 `1 + max(-u, -v, u + v - 1)`, a segment
/// `|u|`; a point is
/// [`inside`] with tolerance `tol` exactly when its reach is at most
/// `1 + tol` (up to rounding).
pub fn reach(kind: FaceKind, [u, v]: [f64; 2]) -> f64 {
    match kind {
        FaceKind::Segment => u.abs(),
        FaceKind::Tri3 => 1.0 + (-u).max(-v).max(u + v - 1.0),
        FaceKind::Quad4 => u.abs().max(v.abs()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shape_functions_are_a_partition_of_unity_and_interpolate_the_nodes() {
        for kind in [FaceKind::Segment, FaceKind::Tri3, FaceKind::Quad4] {
            let corners: Vec<[f64; 2]> = match kind {
                FaceKind::Segment => vec![[-1.0, 0.0], [1.0, 0.0]],
                FaceKind::Tri3 => vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
                FaceKind::Quad4 => QUAD4_CORNERS.to_vec(),
            };
            for (b, &c) in corners.iter().enumerate() {
                let s = FaceShape::at(kind, c);
                for a in 0..s.count {
                    assert_eq!(s.n[a], if a == b { 1.0 } else { 0.0 });
                }
            }
            let s = FaceShape::at(kind, [0.21, -0.13_f64.max(0.0) + 0.3]);
            assert!((s.n.iter().sum::<f64>() - 1.0).abs() < 1e-15);
            assert!(s.du.iter().sum::<f64>().abs() < 1e-15);
            assert!(s.dv.iter().sum::<f64>().abs() < 1e-15);
            // derivatives against central differences
            let (xi, h) = ([0.2, 0.3], 1e-6);
            let (p, m) = (
                FaceShape::at(kind, [xi[0] + h, xi[1]]),
                FaceShape::at(kind, [xi[0] - h, xi[1]]),
            );
            let s = FaceShape::at(kind, xi);
            for a in 0..s.count {
                assert!(((p.n[a] - m.n[a]) / (2.0 * h) - s.du[a]).abs() < 1e-9);
            }
        }
    }

    #[test]
    fn a_unit_square_has_area_element_a_quarter_and_normal_up() {
        let q = Face::Quad4([
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ]);
        assert_eq!(q.area_element([0.3, -0.7]), 0.25);
        assert_eq!(q.normal_at([0.0, 0.0]), [0.0, 0.0, 0.25]);
        let t = Face::Tri3([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
        assert_eq!(t.area_element([0.2, 0.2]), 1.0);
        assert!(inside(FaceKind::Tri3, [0.5, 0.5], 0.0));
        assert!(!inside(FaceKind::Tri3, [0.5, 0.6], 1e-9));
        assert!(!inside(FaceKind::Quad4, [1.0 + 1e-6, 0.0], 1e-9));
    }
}
