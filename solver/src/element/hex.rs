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
//! longest edge, [`MIN_RELATIVE_DET`] the triangle's floor): positive, and
//! not flat beyond rounding (a collapsed face leaves a `detJ0` of the
//! order of the rounding error, of either sign).

use super::kinematics::det;
use super::material::Material;
use super::solid::{SolidResponse, add_point, point_energy, point_stress};
use super::stress::Stress;
pub use super::tri::MIN_RELATIVE_DET;
use super::{ElementKind, InvalidElement, SolidElement};

/// The twelve edges, as pairs of nodes.
const EDGES: [[usize; 2]; 12] = [
    [0, 1],
    [1, 2],
    [2, 3],
    [3, 0],
    [4, 5],
    [5, 6],
    [6, 7],
    [7, 4],
    [0, 4],
    [1, 5],
    [2, 6],
    [3, 7],
];

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

/// The inverse of the 3x3 matrix `m` with determinant `det` (adjugate
/// over determinant).
fn inverse(m: &[[f64; 3]; 3], det: f64) -> [[f64; 3]; 3] {
    let c = |i: usize, j: usize| {
        let (i1, i2) = ((i + 1) % 3, (i + 2) % 3);
        let (j1, j2) = ((j + 1) % 3, (j + 2) % 3);
        m[i1][j1] * m[i2][j2] - m[i1][j2] * m[i2][j1]
    };
    // inv[i][j] = cofactor(j, i) / det
    std::array::from_fn(|i| std::array::from_fn(|j| c(j, i) / det))
}

/// `G_a = J0^-T dN_a/dxi` of the element with reference coordinates
/// `x_ref` at the parent gradients `dn`, with `detJ0`; `None` when `detJ0`
/// is not positive.
fn reference_gradients<const N: usize>(
    x_ref: &[[f64; 3]; N],
    dn: &[[f64; 3]; N],
) -> (f64, Option<[[f64; 3]; N]>) {
    // J[i][k] = sum_a X_a[i] dN_a/dxi_k
    let mut j = [[0.0; 3]; 3];
    for a in 0..N {
        for i in 0..3 {
            for k in 0..3 {
                j[i][k] += x_ref[a][i] * dn[a][k];
            }
        }
    }
    let d = det(&j);
    if !(d > 0.0) {
        return (d, None);
    }
    let inv = inverse(&j, d);
    // dN/dX = dN/dxi J^-1 (row vectors)
    let g = std::array::from_fn(|a| {
        std::array::from_fn(|c| dn[a][0] * inv[0][c] + dn[a][1] * inv[1][c] + dn[a][2] * inv[2][c])
    });
    (d, Some(g))
}

/// The reference-configuration geometry of one element at its Gauss points,
/// computed once per mesh.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HexGeometry {
    /// `G_a = dN_a/dX` per Gauss point and node.
    pub grads_ref: [[[f64; 3]; 8]; 8],
    /// `w detJ0` per Gauss point (the reference volume weight).
    pub weight_ref: [f64; 8],
}

impl HexGeometry {
    /// Geometry of the element with reference corner coordinates `x_ref`
    /// (Gmsh's order). Fails when a coordinate is not finite (`det_j0` NaN)
    /// or when `detJ0 <= MIN_RELATIVE_DET l_max^3` at a Gauss point
    /// (inverted, flat or badly distorted element; `det_j0` is the
    /// smallest).
    pub fn new(x_ref: &[[f64; 3]; 8]) -> Result<HexGeometry, InvalidElement> {
        if x_ref.iter().flatten().any(|v| !v.is_finite()) {
            return Err(InvalidElement { det_j0: f64::NAN });
        }
        let mut grads_ref = [[[0.0; 3]; 8]; 8];
        let mut weight_ref = [0.0; 8];
        let mut worst = f64::INFINITY;
        for (gp, p) in GAUSS_2X2X2.iter().enumerate() {
            let (d, g) = reference_gradients(x_ref, &parent_gradients(p));
            // the smallest, and NaN once one is NaN (an overflow)
            worst = if d.is_nan() || worst.is_nan() {
                f64::NAN
            } else {
                worst.min(d)
            };
            if let Some(g) = g {
                grads_ref[gp] = g;
                weight_ref[gp] = d;
            }
        }
        let l2_max = EDGES
            .iter()
            .map(|&[a, b]| {
                let e: [f64; 3] = std::array::from_fn(|i| x_ref[b][i] - x_ref[a][i]);
                e[0] * e[0] + e[1] * e[1] + e[2] * e[2]
            })
            .fold(0.0_f64, f64::max);
        if !(worst > MIN_RELATIVE_DET * l2_max * l2_max.sqrt()) {
            return Err(InvalidElement { det_j0: worst });
        }
        Ok(HexGeometry {
            grads_ref,
            weight_ref,
        })
    }

    /// The reference volume `sum w detJ0`.
    pub fn volume_ref(&self) -> f64 {
        self.weight_ref.iter().sum()
    }
}

/// Internal force, tangent stiffness and strain energy of one element
/// (`f_int` ordered `[u1x, u1y, u1z, u2x, ..., u8z]`, the 24x24 tangent).
pub type HexResponse = SolidResponse<24>;

/// Evaluates the element at displacements `u` (reference frame).
pub fn hex_response(geom: &HexGeometry, u: &[f64; 24], material: &Material) -> HexResponse {
    let d = material.d_matrix_3d();
    let mut out = SolidResponse::starting_at(0.0);
    for gp in 0..8 {
        add_point(
            &mut out,
            &geom.grads_ref[gp],
            geom.weight_ref[gp],
            u,
            &d,
            material,
        );
    }
    out.symmetrize();
    out
}

/// Strain energy only (cheaper than [`hex_response`]).
pub fn hex_energy(geom: &HexGeometry, u: &[f64; 24], material: &Material) -> f64 {
    let d = material.d_matrix_3d();
    (0..8)
        .map(|gp| point_energy(&geom.grads_ref[gp], geom.weight_ref[gp], u, &d, material))
        .sum()
}

/// Stresses at each Gauss point of the element.
pub fn hex_point_stresses(
    geom: &HexGeometry,
    u: &[f64; 24],
    material: &Material,
) -> [Stress<6>; 8] {
    let d = material.d_matrix_3d();
    std::array::from_fn(|gp| point_stress(&geom.grads_ref[gp], u, &d, material))
}

/// Stresses averaged over the Gauss points (equal weights).
pub fn hex_mean_stress(geom: &HexGeometry, u: &[f64; 24], material: &Material) -> Stress<6> {
    Stress::mean(&hex_point_stresses(geom, u, material))
}

impl SolidElement<3, 8, 24, 6> for HexGeometry {
    const KIND: ElementKind = ElementKind::Hex8;

    fn from_reference(x_ref: &[[f64; 3]; 8]) -> Result<Self, InvalidElement> {
        HexGeometry::new(x_ref)
    }

    fn measure_ref(&self) -> f64 {
        self.volume_ref()
    }

    fn response(&self, u: &[f64; 24], material: &Material) -> SolidResponse<24> {
        hex_response(self, u, material)
    }

    fn energy(&self, u: &[f64; 24], material: &Material) -> f64 {
        hex_energy(self, u, material)
    }

    fn point_stresses(&self, u: &[f64; 24], material: &Material) -> Vec<Stress<6>> {
        hex_point_stresses(self, u, material).to_vec()
    }

    fn mean_stress(&self, u: &[f64; 24], material: &Material) -> Stress<6> {
        hex_mean_stress(self, u, material)
    }
}
