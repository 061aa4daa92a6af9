//! The total-Lagrangian 8-node hexahedron (H8) with St Venant–Kirchhoff
//! material and 2x2x2 Gauss integration: the three-dimensional counterpart
//! of [`super::quad`].
//!
//! Nodes are in Gmsh's order: the face `zeta = -1` counter-clockwise seen
//! from `+zeta` (nodes 1-4), then the face `zeta = +1` in the same order
//! (nodes 5-8), i.e. the parent corners
//! `(-1,-1,-1), (1,-1,-1), (1,1,-1), (-1,1,-1), (-1,-1,1), (1,-1,1),
//! (1,1,1), (-1,1,1)`; the trilinear shape functions on the parent cube
//! `[-1, 1]^3` are `N_a = (1 + xi_a xi)(1 + eta_a eta)(1 + zeta_a zeta)/8`.
//!
//! With reference coordinates `X` and displacements `u` (reference frame),
//! at each Gauss point `J0 = sum_a X_a (dN_a/dxi)^T`, `G_a = J0^-T dN_a/dxi`
//! and the integrand of [`super::solid`] with weight `detJ0` (the eight
//! Gauss weights are one): `F = I + sum_a u_a G_a^T`, the Green–Lagrange
//! strain in 3D Voigt order `[E11, E22, E33, 2 E23, 2 E13, 2 E12]`,
//! `S_v = D E_v` with the 6x6 `D` of [`super::material`].
//!
//! Invariant of a [`HexGeometry`]: finite reference coordinates and
//! `detJ0 > MIN_RELATIVE_DET * l_max^3` at every Gauss point (`l_max` the
//! longest edge, [`super::geometry`]'s floor): positive, and
//! not flat beyond rounding (a collapsed face leaves a `detJ0` of the
//! order of the rounding error, of either sign).

use super::ElementKind;
use super::geometry::{Geometry, Shape, gauss_point};

/// Parent coordinates of the eight corners, in Gmsh's node order.
pub const CORNERS: [[f64; 3]; 8] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
];

/// Kuhn's split of the hexahedron into six tetrahedra around its diagonal
/// from node 0 to node 6, as local nodes (each positive for a cube in
/// Gmsh's order; on a general hexahedron test each one's orientation).
pub const KUHN_TETS: [[usize; 4]; 6] = [
    [0, 1, 2, 6],
    [0, 2, 3, 6],
    [0, 3, 7, 6],
    [0, 7, 4, 6],
    [0, 4, 5, 6],
    [0, 5, 1, 6],
];

/// The 2x2x2 Gauss points on the parent cube, `(+-1/sqrt 3)` times the
/// corners in node order (weights are all one).
pub const GAUSS_2X2X2: [[f64; 3]; 8] = {
    const G: f64 = 0.577_350_269_189_625_8; // 1/sqrt(3)
    let mut p = [[0.0; 3]; 8];
    let mut a = 0;
    while a < 8 {
        p[a] = [G * CORNERS[a][0], G * CORNERS[a][1], G * CORNERS[a][2]];
        a += 1;
    }
    p
};

/// `[dN_a/dxi, dN_a/deta, dN_a/dzeta]` at a parent point.
fn parent_gradients(p: &[f64; 3]) -> [[f64; 3]; 8] {
    CORNERS.map(|c| {
        let s = [1.0 + c[0] * p[0], 1.0 + c[1] * p[1], 1.0 + c[2] * p[2]];
        [
            c[0] * s[1] * s[2] / 8.0,
            c[1] * s[0] * s[2] / 8.0,
            c[2] * s[0] * s[1] / 8.0,
        ]
    })
}

/// The 8-node hexahedron's parent cube and 2x2x2 Gauss rule.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hex8;

impl Shape<3, 8, 8> for Hex8 {
    const KIND: ElementKind = ElementKind::Hex8;

    fn point(x_ref: &[[f64; 3]; 8], p: usize) -> (f64, Option<[[f64; 3]; 8]>) {
        gauss_point(x_ref, &parent_gradients(&GAUSS_2X2X2[p]))
    }

    fn weight(det_j0: f64) -> f64 {
        det_j0
    }
}

/// The reference geometry of one hexahedron at its eight Gauss points,
/// computed once per mesh.
pub type HexGeometry = Geometry<Hex8, 3, 8, 24, 6, 8>;
