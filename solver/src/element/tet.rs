//! The total-Lagrangian 4-node linear tetrahedron (constant strain, T4)
//! with St Venant–Kirchhoff material: the three-dimensional counterpart of
//! [`super::tri`].
//!
//! Nodes are in Gmsh's order; the linear shape functions on the parent
//! tetrahedron `xi, eta, zeta >= 0, xi + eta + zeta <= 1` are
//! `N_1 = 1 - xi - eta - zeta`, `N_2 = xi`, `N_3 = eta`, `N_4 = zeta`, so
//! the element is positive when node 4 lies on the side of the face
//! 1-2-3 that its counter-clockwise normal points to:
//!
//! ```text
//! J0      = [X_2 - X_1, X_3 - X_1, X_4 - X_1]    (reference Jacobian, columns)
//! V0      = detJ0 / 6                             (reference volume)
//! G_a     = dN_a/dX = J0^-T dN_a/dxi               (constant): G_{k+1} is
//!           row k of J0^-1 (k = 1, 2, 3), G_1 = -(G_2 + G_3 + G_4)
//! ```
//!
//! and the integrand of [`super::solid`] with the weight `V0` at one point:
//! the integrand is constant, so the rule is exact.
//!
//! Invariant of a [`TetGeometry`]: finite reference coordinates and
//! `detJ0 > MIN_RELATIVE_DET * l_max^3` (`l_max` the longest edge,
//! [`MIN_RELATIVE_DET`] the triangle's floor), i.e. positively oriented
//! and not flat beyond rounding.

use super::kinematics::det;
use super::material::Material;
use super::solid::{SolidResponse, add_point, point_energy, point_stress};
use super::stress::Stress;
pub use super::tri::MIN_RELATIVE_DET;
use super::{ElementKind, InvalidElement, SolidElement};

/// The reference-configuration geometry of one element, computed once per
/// mesh.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TetGeometry {
    /// `G_a = dN_a/dX` per node (constant over the element).
    pub grads_ref: [[f64; 3]; 4],
    /// The reference volume `V0 = detJ0 / 6` (the weight of the one
    /// integration point).
    pub weight_ref: f64,
}

impl TetGeometry {
    /// Geometry of the element with reference corner coordinates `x_ref`
    /// (Gmsh's order). Fails when a coordinate is not finite (`det_j0`
    /// NaN) or when `detJ0 <= MIN_RELATIVE_DET l_max^3` (inverted or flat
    /// element).
    pub fn new(x_ref: &[[f64; 3]; 4]) -> Result<TetGeometry, InvalidElement> {
        if x_ref.iter().flatten().any(|v| !v.is_finite()) {
            return Err(InvalidElement { det_j0: f64::NAN });
        }
        // J[i][k] = X_{k+2}[i] - X_1[i]
        let j: [[f64; 3]; 3] =
            std::array::from_fn(|i| std::array::from_fn(|k| x_ref[k + 1][i] - x_ref[0][i]));
        let d = det(&j);
        let mut l2_max = 0.0_f64;
        for a in 0..4 {
            for b in a + 1..4 {
                let e: [f64; 3] = std::array::from_fn(|i| x_ref[b][i] - x_ref[a][i]);
                l2_max = l2_max.max(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
            }
        }
        if !(d.is_finite() && d > MIN_RELATIVE_DET * l2_max * l2_max.sqrt()) {
            return Err(InvalidElement { det_j0: d });
        }
        // rows of J^-1 = cofactors of the columns over det
        let c = |r: usize, s: usize| {
            let (r1, r2) = ((r + 1) % 3, (r + 2) % 3);
            let (s1, s2) = ((s + 1) % 3, (s + 2) % 3);
            j[r1][s1] * j[r2][s2] - j[r1][s2] * j[r2][s1]
        };
        let row = |k: usize| -> [f64; 3] { std::array::from_fn(|i| c(i, k) / d) };
        let (g2, g3, g4) = (row(0), row(1), row(2));
        let g1 = std::array::from_fn(|i| -(g2[i] + g3[i] + g4[i]));
        Ok(TetGeometry {
            grads_ref: [g1, g2, g3, g4],
            weight_ref: d / 6.0,
        })
    }

    /// The reference volume `V0`.
    pub fn volume_ref(&self) -> f64 {
        self.weight_ref
    }
}

/// Internal force, tangent stiffness and strain energy of one element
/// (`f_int` ordered `[u1x, u1y, u1z, ..., u4z]`, the 12x12 tangent).
pub type TetResponse = SolidResponse<12>;

/// Evaluates the element at displacements `u` (reference frame).
pub fn tet_response(geom: &TetGeometry, u: &[f64; 12], material: &Material) -> TetResponse {
    let d = material.d_matrix_3d();
    let mut out = SolidResponse::starting_at(-0.0);
    add_point(&mut out, &geom.grads_ref, geom.weight_ref, u, &d, material);
    out.symmetrize();
    out
}

/// Strain energy only (cheaper than [`tet_response`]).
pub fn tet_energy(geom: &TetGeometry, u: &[f64; 12], material: &Material) -> f64 {
    let d = material.d_matrix_3d();
    point_energy(&geom.grads_ref, geom.weight_ref, u, &d, material)
}

/// Stresses at the element's one integration point.
pub fn tet_point_stresses(
    geom: &TetGeometry,
    u: &[f64; 12],
    material: &Material,
) -> [Stress<6>; 1] {
    let d = material.d_matrix_3d();
    [point_stress(&geom.grads_ref, u, &d, material)]
}

/// The element's stress (constant over it).
pub fn tet_mean_stress(geom: &TetGeometry, u: &[f64; 12], material: &Material) -> Stress<6> {
    let [s] = tet_point_stresses(geom, u, material);
    s
}

impl SolidElement<3, 4, 12, 6> for TetGeometry {
    const KIND: ElementKind = ElementKind::Tet4;

    fn from_reference(x_ref: &[[f64; 3]; 4]) -> Result<Self, InvalidElement> {
        TetGeometry::new(x_ref)
    }

    fn measure_ref(&self) -> f64 {
        self.volume_ref()
    }

    fn response(&self, u: &[f64; 12], material: &Material) -> SolidResponse<12> {
        tet_response(self, u, material)
    }

    fn energy(&self, u: &[f64; 12], material: &Material) -> f64 {
        tet_energy(self, u, material)
    }

    fn point_stresses(&self, u: &[f64; 12], material: &Material) -> Vec<Stress<6>> {
        tet_point_stresses(self, u, material).to_vec()
    }

    fn mean_stress(&self, u: &[f64; 12], material: &Material) -> Stress<6> {
        tet_mean_stress(self, u, material)
    }
}
