//! Consistent nodal forces of a uniform traction on a 3D face.
//!
//! A dead traction `t` (force per unit reference area, the same at every
//! point of a face) loads node `a` of the face with
//!
//! ```text
//! f_a = t * w_a,   w_a = integral over the face of N_a dA
//! ```
//!
//! where `N_a` is the face's shape function of node `a` and `dA` the
//! reference area element. [`nodal_areas`] gives the weights `w_a`:
//!
//! * a tri3 (linear, constant Jacobian) exactly: `w_a = A / 3`, `A` its
//!   area `|(x1 - x0) x (x2 - x0)| / 2`;
//! * a quad4 (bilinear, Gmsh's corners `(-1,-1), (1,-1), (1,1), (-1,1)`)
//!   with 2 x 2 Gauss points (`u, v = +-1/sqrt 3`, weights 1), `dA =
//!   |dx/du x dx/dv| du dv`: exact for a planar face, whose `|dx/du x
//!   dx/dv|` is linear in `u` and `v`; a warped face's area element is not
//!   a polynomial and the rule approximates it.
//!
//! The weights add up to the face's area (the rule's area for a warped
//! quad4), so the nodal forces add up to `t` times it.

use crate::element::FaceKind;
use crate::mesh::face_shape::FaceShape;
use crate::mesh::volume::{Face, cross};

/// `1/sqrt(3)`: the 2-point Gauss abscissa.
const GAUSS: f64 = 0.577_350_269_189_625_8;

/// The weights `w_a = integral of N_a dA` of the face's nodes (module
/// docs), node by node: the consistent nodal forces of a uniform traction
/// `t` are `t w_a`.
pub fn nodal_areas(face: &Face<[f64; 3]>) -> Face<f64> {
    match face {
        Face::Tri3(x) => {
            let area = norm(cross(sub(x[1], x[0]), sub(x[2], x[0]))) / 2.0;
            Face::Tri3([area / 3.0; 3])
        }
        Face::Quad4(_) => {
            let mut w = [0.0; 4];
            for u in [-GAUSS, GAUSS] {
                for v in [-GAUSS, GAUSS] {
                    let da = face.area_element([u, v]);
                    let shape = FaceShape::at(FaceKind::Quad4, [u, v]);
                    for (wa, na) in w.iter_mut().zip(shape.n) {
                        *wa += na * da;
                    }
                }
            }
            Face::Quad4(w)
        }
    }
}

/// The consistent nodal forces `t w_a` of the uniform traction `t` on
/// `face`, node by node ([`nodal_areas`]).
pub fn nodal_forces(face: &Face<[f64; 3]>, t: [f64; 3]) -> Face<[f64; 3]> {
    nodal_areas(face).map_nodes(|w| t.map(|tc| tc * w))
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn norm(a: [f64; 3]) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A rotation about the axis (1, 2, 2)/3 by 0.7 rad, then a shift:
    /// weights do not depend on where a face is or how it is turned.
    fn place(p: [f64; 3]) -> [f64; 3] {
        let k = [1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0];
        let (s, c) = 0.7_f64.sin_cos();
        let kxp = cross(k, p);
        let kp = k[0] * p[0] + k[1] * p[1] + k[2] * p[2];
        std::array::from_fn(|i| p[i] * c + kxp[i] * s + k[i] * kp * (1.0 - c) + [0.5, -1.5, 2.0][i])
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-13 * (1.0 + b.abs())
    }

    /// The area of a planar quad: half the cross product of its diagonals.
    fn quad_area(x: &[[f64; 3]; 4]) -> f64 {
        norm(cross(sub(x[2], x[0]), sub(x[3], x[1]))) / 2.0
    }

    #[test]
    fn forces_add_up_to_traction_times_area() {
        let t = [0.3, -1.25, 2.0];
        let quads = [
            [
                [0.0, 0.0, 0.0],
                [2.0, 0.0, 0.0],
                [2.0, 1.0, 0.0],
                [0.0, 1.0, 0.0],
            ],
            [
                [0.0, 0.0, 0.0],
                [3.0, 0.0, 0.0],
                [2.0, 1.5, 0.0],
                [0.5, 1.0, 0.0],
            ],
            [
                [0.0, 0.0, 0.0],
                [1.0, 0.2, 0.0],
                [1.3, 1.1, 0.0],
                [-0.2, 0.9, 0.0],
            ],
        ];
        for q in quads {
            let q = q.map(place);
            let area = quad_area(&q);
            let f = nodal_forces(&Face::Quad4(q), t);
            for c in 0..3 {
                let sum: f64 = f.nodes().iter().map(|fa| fa[c]).sum();
                assert!(close(sum, t[c] * area), "{sum} vs {}", t[c] * area);
            }
        }
        let tri = [[0.0, 0.0, 0.0], [2.0, 0.5, 0.0], [0.4, 1.5, 0.0]].map(place);
        let area = 0.5 * (2.0 * 1.5 - 0.5 * 0.4);
        let w = nodal_areas(&Face::Tri3(tri));
        for &wa in w.nodes() {
            assert!(close(wa, area / 3.0), "{wa}");
        }
    }

    /// A planar quad's weights against the exact integral: with the area
    /// element `J = J0 + J1 u + J2 v` (planar), `w_a = J0 + (J1 u_a + J2
    /// v_a) / 3`; `J0`, `J1`, `J2` from the corners' 2D coordinates.
    #[test]
    fn planar_quad_weights_are_exact() {
        let p = [[0.0, 0.0], [3.0, 0.0], [2.0, 1.5], [0.5, 1.0]];
        // x(u, v) = a0 + a1 u + a2 v + a3 u v (each component)
        let coef = |c: usize| {
            let x = p.map(|q| q[c]);
            [
                (x[0] + x[1] + x[2] + x[3]) / 4.0,
                (-x[0] + x[1] + x[2] - x[3]) / 4.0,
                (-x[0] - x[1] + x[2] + x[3]) / 4.0,
                (x[0] - x[1] + x[2] - x[3]) / 4.0,
            ]
        };
        let (x, y) = (coef(0), coef(1));
        // J = (x1 + x3 v)(y2 + y3 u) - (x2 + x3 u)(y1 + y3 v)
        let j0 = x[1] * y[2] - x[2] * y[1];
        let j1 = x[1] * y[3] - x[3] * y[1];
        let j2 = x[3] * y[2] - x[2] * y[3];
        let face = Face::Quad4(p.map(|q| place([q[0], q[1], 0.0])));
        let w = nodal_areas(&face);
        for (a, [ua, va]) in crate::mesh::face_shape::QUAD4_CORNERS.iter().enumerate() {
            let exact = j0 + (j1 * ua + j2 * va) / 3.0;
            assert!(
                close(w.nodes()[a], exact),
                "node {a}: {} vs {exact}",
                w.nodes()[a]
            );
        }
        // an unequal split: the corner at the long edges gets the most
        assert!(w.nodes()[1] > w.nodes()[3]);
    }

    /// A uniform traction on a patch of `n x m` equal squares of side `h`:
    /// a corner node gets `t h^2 / 4`, an edge node `t h^2 / 2`, an
    /// interior node `t h^2`.
    #[test]
    fn uniform_traction_on_a_patch_gives_corner_edge_interior_weights() {
        let (n, m, h) = (3, 2, 0.5);
        let t = [0.0, 0.0, -4.0];
        let node = |i: usize, j: usize| j * (n + 1) + i;
        let mut f = vec![[0.0; 3]; (n + 1) * (m + 1)];
        for j in 0..m {
            for i in 0..n {
                let ids = [
                    node(i, j),
                    node(i + 1, j),
                    node(i + 1, j + 1),
                    node(i, j + 1),
                ];
                let x = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)]
                    .map(|(a, b)| place([a as f64 * h, b as f64 * h, 0.0]));
                let fe = nodal_forces(&Face::Quad4(x), t);
                for (k, fa) in ids.iter().zip(fe.nodes()) {
                    for c in 0..3 {
                        f[*k][c] += fa[c];
                    }
                }
            }
        }
        for j in 0..=m {
            for i in 0..=n {
                let on_edge = [i == 0 || i == n, j == 0 || j == m];
                let share = match on_edge {
                    [true, true] => 0.25,
                    [true, false] | [false, true] => 0.5,
                    [false, false] => 1.0,
                };
                for c in 0..3 {
                    let want = t[c] * h * h * share;
                    assert!(
                        close(f[node(i, j)][c], want),
                        "({i}, {j}) {c}: {:?}",
                        f[node(i, j)]
                    );
                }
            }
        }
        // tri3: a square split into two triangles gives its nodes A/3 per
        // triangle
        let sq = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ]
        .map(place);
        let a = nodal_areas(&Face::Tri3([sq[0], sq[1], sq[2]]));
        let b = nodal_areas(&Face::Tri3([sq[0], sq[2], sq[3]]));
        let corner0 = a.nodes()[0] + b.nodes()[0];
        assert!(close(corner0, 1.0 / 3.0), "{corner0}");
        assert!(close(a.nodes()[1], 1.0 / 6.0));
    }
}
