//! Segmented integration on 3D faces: a slave face (tri3 or quad4) clipped
//! against a master face projected onto it, the intersection triangulated
//! and given a Gauss rule in the slave face's parametric coordinates.
//!
//! # The slave plane
//!
//! The slave face's nodes `X_a` define a plane: through their centroid,
//! with unit normal `n = t_1 x t_2 / |..|` for a tri3 (`t_1 = X_2 - X_1`,
//! `t_2 = X_3 - X_1`) and `n = (X_3 - X_1) x (X_4 - X_2) / |..|` for a quad4
//! (the diagonals), i.e. the face's outward normal. In-plane axes are
//! `e_1 = (X_2 - X_1)` without its `n` component, normalised, and
//! `e_2 = n x e_1`, so a face whose nodes run counter-clockwise seen from
//! outside is counter-clockwise in `(e_1, e_2)`. A point `x` has plane
//! coordinates `p = ((x - c) . e_1, (x - c) . e_2)` (orthogonal projection).
//!
//! # Why the plane and not (u, v)
//!
//! Clipping happens in plane coordinates, not in the slave's parametric
//! coordinates: the projection of a straight master edge is a straight line
//! in the plane, but its image under the inverse of the bilinear quad4 map
//! is curved, so Sutherland–Hodgman in `(u, v)` would be exact only on
//! parallelograms. In the plane both faces are convex polygons and their
//! intersection is exact. Each piece's Gauss points are then mapped to
//! `(u, v)` by inverting the slave's map in the plane (linear on a tri3;
//! Newton on the bilinear quad4, which is one-to-one on a convex quad).
//! The weights are areas in the plane, so `sum w f(u, v)` over the pieces
//! of all master faces that tile the slave face is `int f dA` over the
//! slave face: the caller does **not** multiply by a Jacobian. On a planar
//! slave face this is its area element exactly; on a warped quad4 it is
//! the projected area, which differs from the curved surface's by the
//! square of the warp.
//!
//! # Clipping and triangulation
//!
//! Both polygons are checked convex (every corner turns the same way, up
//! to [`CLIP_TOL`]; a slave corner must turn strictly, since a straight
//! corner makes the quad4 map singular there) and oriented
//! counter-clockwise in the plane (a master
//! face, whose outward normal opposes the slave's, projects clockwise and
//! is reversed). The master polygon is clipped by each slave edge's
//! half-plane in turn (Sutherland–Hodgman): a vertex at signed distance
//! `s >= -CLIP_TOL h` from the edge's line is inside (`h` the slave's
//! diameter), an edge crossing the line is cut at `t = s_p / (s_p - s_q)`.
//! Shared edges and touching vertices therefore give polygons of zero area.
//! Consecutive vertices closer than `CLIP_TOL h` are merged; the polygon is
//! fanned from its first vertex into triangles, and every triangle (and
//! polygon) of area at most `CLIP_TOL A_s` (`A_s` the slave's plane area)
//! is dropped: no overlap, touching, edge-on masters and slivers give no
//! piece.
//!
//! # Gauss rules on a triangle
//!
//! [`TriangleRule`]: the centroid (degree 1), the interior three-point rule
//! at barycentric `(1/6, 1/6, 2/3)` and permutations (degree 2), and
//! Radon's seven-point rule (degree 5). A piece's point `p = sum_i b_i P_i`
//! has weight `w_q A_piece` (`sum_q w_q = 1`), so polynomials in the plane
//! coordinates up to the rule's degree integrate exactly over every piece,
//! hence over the slave face (and polynomials in `(u, v)` too when the
//! slave map is affine: a tri3 or a parallelogram quad4).

use thiserror::Error;

/// The one tolerance of the clipping, relative: distances up to
/// `CLIP_TOL h` count as zero (`h` the slave face's diameter) and pieces of
/// area up to `CLIP_TOL A_s` are dropped (`A_s` its area in the plane).
pub const CLIP_TOL: f64 = 1e-12;

/// Which face of the pair an error is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// The slave face.
    Slave,
    /// The master face.
    Master,
}

impl std::fmt::Display for Role {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Role::Slave => "slave",
            Role::Master => "master",
        })
    }
}

/// Bad input to the clipping.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ClipError {
    /// A face that is neither a tri3 nor a quad4.
    #[error("{role} face has {count} nodes (3 or 4 expected)")]
    NodeCount {
        /// The face.
        role: Role,
        /// Its number of nodes.
        count: usize,
    },
    /// A node with a non-finite coordinate.
    #[error("{role} face node {node} is not finite")]
    NonFinite {
        /// The face.
        role: Role,
        /// The node's position in the face.
        node: usize,
    },
    /// A slave face of (near) zero area: it has no plane.
    #[error("slave face has no area ({area:e})")]
    DegenerateSlave {
        /// Half the norm of the face's normal vector.
        area: f64,
    },
    /// A face whose polygon in the slave plane is not convex (folded or
    /// self-intersecting); `corner` is a corner turning against another
    /// (the later of the first two that disagree), or on a slave face the
    /// first corner that does not turn counter-clockwise.
    #[error("{role} face is not convex in the slave plane (corner {corner})")]
    NotConvex {
        /// The face.
        role: Role,
        /// The corner's position in the face.
        corner: usize,
    },
    /// The quad4 map could not be inverted at a point (in plane
    /// coordinates).
    #[error("no parametric coordinates for plane point ({}, {})", point[0], point[1])]
    NoInverse {
        /// The point in plane coordinates.
        point: [f64; 2],
    },
}

/// A Gauss rule on a triangle.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TriangleRule {
    /// The centroid: degree 1.
    Centroid,
    /// Barycentric `(1/6, 1/6, 2/3)` and permutations: degree 2.
    Three,
    /// Radon's seven-point rule: degree 5.
    Seven,
}

impl TriangleRule {
    /// The largest total degree integrated exactly.
    pub fn degree(self) -> usize {
        match self {
            TriangleRule::Centroid => 1,
            TriangleRule::Three => 2,
            TriangleRule::Seven => 5,
        }
    }

    /// Points as barycentric coordinates of the 2nd and 3rd vertex
    /// `(b_2, b_3)`, with weights summing to 1: the tri3 rules of
    /// `face_rules.rs` (there on the unit triangle, weights summing to its
    /// area 1/2; doubled here, exactly).
    pub fn points(self) -> Vec<([f64; 2], f64)> {
        let n = match self {
            TriangleRule::Centroid => 1,
            TriangleRule::Three => 3,
            TriangleRule::Seven => 7,
        };
        crate::contact::face_rules::tri3_rule(n)
            .expect("face_rules has the tri3 rules of 1, 3 and 7 points")
            .points
            .into_iter()
            .map(|(p, w)| (p, 2.0 * w))
            .collect()
    }
}

/// One triangle of a slave face's intersection with a master face, in
/// plane coordinates, counter-clockwise.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Piece {
    /// The corners in plane coordinates.
    pub vertices: [[f64; 2]; 3],
    /// The area (positive).
    pub area: f64,
}

/// An integration point on the slave face.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClipPoint {
    /// Slave parametric coordinates (unit triangle on a tri3, `[-1, 1]^2`
    /// on a quad4).
    pub uv: [f64; 2],
    /// The point's share of the area in the slave plane.
    pub weight: f64,
}

type V3 = [f64; 3];
type V2 = [f64; 2];

fn sub3(a: &V3, b: &V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot3(a: &V3, b: &V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross3(a: &V3, b: &V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn scale3(a: &V3, s: f64) -> V3 {
    [a[0] * s, a[1] * s, a[2] * s]
}
fn sub2(a: &V2, b: &V2) -> V2 {
    [a[0] - b[0], a[1] - b[1]]
}
fn cross2(a: &V2, b: &V2) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}
fn norm2(a: &V2) -> f64 {
    a[0].hypot(a[1])
}

/// Twice the signed area (shoelace).
fn signed_area(poly: &[V2]) -> f64 {
    let n = poly.len();
    0.5 * (0..n)
        .map(|i| cross2(&poly[i], &poly[(i + 1) % n]))
        .sum::<f64>()
}

fn check_nodes(role: Role, nodes: &[V3]) -> Result<(), ClipError> {
    if !(3..=4).contains(&nodes.len()) {
        return Err(ClipError::NodeCount {
            role,
            count: nodes.len(),
        });
    }
    for (node, x) in nodes.iter().enumerate() {
        if x.iter().any(|c| !c.is_finite()) {
            return Err(ClipError::NonFinite { role, node });
        }
    }
    Ok(())
}

/// Orients a convex polygon counter-clockwise, or refuses it. Corners
/// whose turn (sine of the angle between the edges) is within `CLIP_TOL`
/// of zero count as straight.
fn convex_ccw(role: Role, mut poly: Vec<V2>) -> Result<Vec<V2>, ClipError> {
    let n = poly.len();
    let turn = |i: usize| {
        let e0 = sub2(&poly[i], &poly[(i + n - 1) % n]);
        let e1 = sub2(&poly[(i + 1) % n], &poly[i]);
        let l = norm2(&e0) * norm2(&e1);
        if l == 0.0 { 0.0 } else { cross2(&e0, &e1) / l }
    };
    let turns: Vec<f64> = (0..n).map(turn).collect();
    if let Some(corner) = turns.iter().position(|&t| t < -CLIP_TOL) {
        // Not counter-clockwise: clockwise convex, or not convex.
        if let Some(c) = turns.iter().position(|&t| t > CLIP_TOL) {
            return Err(ClipError::NotConvex {
                role,
                corner: corner.max(c),
            });
        }
        poly.reverse();
    }
    Ok(poly)
}

/// A slave face with its plane, ready to clip master faces against.
#[derive(Debug, Clone)]
pub struct SlaveFace {
    /// The nodes' plane coordinates, counter-clockwise (3 or 4).
    corners: Vec<V2>,
    centroid: V3,
    e1: V3,
    e2: V3,
    /// Diameter (largest corner distance) in the plane.
    diameter: f64,
    area: f64,
}

impl SlaveFace {
    /// The slave face of nodes `nodes` (3: tri3, 4: quad4; counter-clockwise
    /// seen from outside its body).
    pub fn new(nodes: &[V3]) -> Result<Self, ClipError> {
        check_nodes(Role::Slave, nodes)?;
        let n = nodes.len();
        let normal = if n == 3 {
            cross3(&sub3(&nodes[1], &nodes[0]), &sub3(&nodes[2], &nodes[0]))
        } else {
            cross3(&sub3(&nodes[2], &nodes[0]), &sub3(&nodes[3], &nodes[1]))
        };
        let size = nodes
            .iter()
            .flat_map(|a| {
                nodes
                    .iter()
                    .map(move |b| dot3(&sub3(a, b), &sub3(a, b)).sqrt())
            })
            .fold(0.0, f64::max);
        let nn = dot3(&normal, &normal).sqrt();
        // |normal| is twice the area of a tri3, the diagonals' cross product
        // is twice a planar quad's area.
        if !(nn > 2.0 * CLIP_TOL * size * size) {
            return Err(ClipError::DegenerateSlave { area: 0.5 * nn });
        }
        let normal = scale3(&normal, 1.0 / nn);
        let mut centroid = [0.0; 3];
        for x in nodes {
            for k in 0..3 {
                centroid[k] += x[k] / n as f64;
            }
        }
        let t = sub3(&nodes[1], &nodes[0]);
        let t = sub3(&t, &scale3(&normal, dot3(&t, &normal)));
        let lt = dot3(&t, &t).sqrt();
        if !(lt > CLIP_TOL * size) {
            return Err(ClipError::DegenerateSlave { area: 0.5 * nn });
        }
        let e1 = scale3(&t, 1.0 / lt);
        let e2 = cross3(&normal, &e1);
        let mut face = SlaveFace {
            corners: Vec::new(),
            centroid,
            e1,
            e2,
            diameter: 0.0,
            area: 0.0,
        };
        let corners: Vec<V2> = nodes.iter().map(|x| face.to_plane(x)).collect();
        if let Some(corner) = (0..n).position(|i| {
            let e0 = sub2(&corners[i], &corners[(i + n - 1) % n]);
            let e1 = sub2(&corners[(i + 1) % n], &corners[i]);
            cross2(&e0, &e1) <= CLIP_TOL * norm2(&e0) * norm2(&e1)
        }) {
            return Err(ClipError::NotConvex {
                role: Role::Slave,
                corner,
            });
        }
        face.area = signed_area(&corners);
        face.diameter = corners
            .iter()
            .flat_map(|a| corners.iter().map(move |b| norm2(&sub2(a, b))))
            .fold(0.0, f64::max);
        face.corners = corners;
        Ok(face)
    }

    /// The face's area in its plane.
    pub fn area(&self) -> f64 {
        self.area
    }

    /// The plane coordinates of a point (orthogonal projection).
    pub fn to_plane(&self, x: &V3) -> V2 {
        let d = sub3(x, &self.centroid);
        [dot3(&d, &self.e1), dot3(&d, &self.e2)]
    }

    /// The plane point of parametric coordinates `uv` (the slave map).
    pub fn plane_point(&self, uv: V2) -> V2 {
        let (n, _, _) = self.shape(uv);
        let mut p = [0.0; 2];
        for (na, c) in n.iter().zip(&self.corners) {
            p[0] += na * c[0];
            p[1] += na * c[1];
        }
        p
    }

    /// Shape functions and their u, v derivatives at `uv`.
    fn shape(&self, [u, v]: V2) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        if self.corners.len() == 3 {
            (
                vec![1.0 - u - v, u, v],
                vec![-1.0, 1.0, 0.0],
                vec![-1.0, 0.0, 1.0],
            )
        } else {
            let (ua, va) = ([-1.0, 1.0, 1.0, -1.0], [-1.0, -1.0, 1.0, 1.0]);
            (
                (0..4)
                    .map(|a| 0.25 * (1.0 + u * ua[a]) * (1.0 + v * va[a]))
                    .collect(),
                (0..4).map(|a| 0.25 * ua[a] * (1.0 + v * va[a])).collect(),
                (0..4).map(|a| 0.25 * (1.0 + u * ua[a]) * va[a]).collect(),
            )
        }
    }

    /// The parametric coordinates of a plane point of the face (Newton on
    /// the slave map, exact in one step on a tri3), kept in the face: a
    /// point outside it by rounding is moved onto its boundary.
    pub fn parametric(&self, p: V2) -> Result<V2, ClipError> {
        let mut uv = if self.corners.len() == 3 {
            [1.0 / 3.0; 2]
        } else {
            [0.0; 2]
        };
        for _ in 0..50 {
            let x = self.plane_point(uv);
            let r = sub2(&p, &x);
            let (_, du, dv) = self.shape(uv);
            let (mut a, mut b) = ([0.0; 2], [0.0; 2]);
            for (k, c) in self.corners.iter().enumerate() {
                a[0] += du[k] * c[0];
                a[1] += du[k] * c[1];
                b[0] += dv[k] * c[0];
                b[1] += dv[k] * c[1];
            }
            let det = cross2(&a, &b);
            if !(det.abs() > 0.0) {
                return Err(ClipError::NoInverse { point: p });
            }
            let step = [cross2(&r, &b) / det, cross2(&a, &r) / det];
            uv = [uv[0] + step[0], uv[1] + step[1]];
            if !(uv[0].is_finite() && uv[1].is_finite()) {
                return Err(ClipError::NoInverse { point: p });
            }
            if norm2(&step) <= 1e-15 {
                break;
            }
        }
        if norm2(&sub2(&p, &self.plane_point(uv))) > 1e3 * CLIP_TOL * self.diameter {
            return Err(ClipError::NoInverse { point: p });
        }
        if self.corners.len() == 3 {
            let (u, v) = (uv[0].max(0.0), uv[1].max(0.0));
            let s = u + v;
            Ok(if s > 1.0 { [u / s, v / s] } else { [u, v] })
        } else {
            Ok([uv[0].clamp(-1.0, 1.0), uv[1].clamp(-1.0, 1.0)])
        }
    }

    /// The triangles of this face's intersection with the master face of
    /// nodes `master` projected onto the slave plane (empty without
    /// overlap).
    pub fn clip(&self, master: &[V3]) -> Result<Vec<Piece>, ClipError> {
        check_nodes(Role::Master, master)?;
        let projected = master.iter().map(|x| self.to_plane(x)).collect();
        let mut poly = convex_ccw(Role::Master, projected)?;
        let len_tol = CLIP_TOL * self.diameter;
        let area_tol = CLIP_TOL * self.area;
        if signed_area(&poly) <= area_tol {
            return Ok(Vec::new());
        }
        let n = self.corners.len();
        for i in 0..n {
            let a = self.corners[i];
            let edge = sub2(&self.corners[(i + 1) % n], &a);
            let le = norm2(&edge);
            let dist = |p: &V2| cross2(&edge, &sub2(p, &a)) / le;
            let mut out = Vec::with_capacity(poly.len() + 1);
            for j in 0..poly.len() {
                let p = poly[j];
                let q = poly[(j + 1) % poly.len()];
                let (sp, sq) = (dist(&p), dist(&q));
                let (p_in, q_in) = (sp >= -len_tol, sq >= -len_tol);
                if p_in {
                    out.push(p);
                }
                if p_in != q_in {
                    let t = sp / (sp - sq);
                    out.push([p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])]);
                }
            }
            poly = out;
            if poly.len() < 3 {
                return Ok(Vec::new());
            }
        }
        // Merge coincident neighbours.
        let mut merged: Vec<V2> = Vec::with_capacity(poly.len());
        for p in poly {
            if merged.last().is_none_or(|q| norm2(&sub2(&p, q)) > len_tol) {
                merged.push(p);
            }
        }
        while merged.len() > 1 && norm2(&sub2(&merged[0], &merged[merged.len() - 1])) <= len_tol {
            merged.pop();
        }
        if merged.len() < 3 || signed_area(&merged) <= area_tol {
            return Ok(Vec::new());
        }
        let p0 = merged[0];
        Ok(merged
            .windows(2)
            .skip(1)
            .map(|w| {
                let vertices = [p0, w[0], w[1]];
                Piece {
                    vertices,
                    area: signed_area(&vertices),
                }
            })
            .filter(|piece| piece.area > area_tol)
            .collect())
    }

    /// The integration points of this face's intersection with `master`:
    /// `rule` on every piece, mapped to the slave's `(u, v)`, weights in
    /// plane area.
    pub fn integration_points(
        &self,
        master: &[V3],
        rule: TriangleRule,
    ) -> Result<Vec<ClipPoint>, ClipError> {
        let points = rule.points();
        let mut out = Vec::new();
        for piece in self.clip(master)? {
            let [p1, p2, p3] = piece.vertices;
            for &([b2, b3], w) in &points {
                let b1 = 1.0 - b2 - b3;
                let p = [
                    b1 * p1[0] + b2 * p2[0] + b3 * p3[0],
                    b1 * p1[1] + b2 * p2[1] + b3 * p3[1],
                ];
                out.push(ClipPoint {
                    uv: self.parametric(p)?,
                    weight: w * piece.area,
                });
            }
        }
        Ok(out)
    }
}

#[cfg(test)]
#[path = "clip_tests.rs"]
mod tests;
