//! The total-Lagrangian 4-node quadrilateral (Q4) with St Venant–Kirchhoff
//! material and 2x2 Gauss integration.
//!
//! Nodes are numbered counter-clockwise; the bilinear shape functions on the
//! parent square `(xi, eta) in [-1, 1]^2` are
//! `N_a = (1 + xi_a xi)(1 + eta_a eta)/4` with the corners
//! `(-1,-1), (1,-1), (1,1), (-1,1)`.
//!
//! With reference coordinates `X` and displacements `u` (all in the reference
//! frame, unit thickness), at each Gauss point
//!
//! ```text
//! J0      = sum_a X_a (dN_a/dxi)^T            (reference Jacobian)
//! G_a     = dN_a/dX = J0^-T dN_a/dxi           (reference gradients)
//! F       = I + sum_a u_a G_a^T                (deformation gradient)
//! E       = (F^T F - I)/2,  E_v = [E11, E22, 2 E12]
//! S_v     = D E_v                              (see `material`)
//! B       : dE_v/du, columns 2a+i:
//!           [F_i1 G_a1,  F_i2 G_a2,  F_i1 G_a2 + F_i2 G_a1]
//! f_int   = sum_gp w detJ0 B^T S_v
//! K       = sum_gp w detJ0 (B^T D B + (G_a . S G_b) I_2)
//! U       = sum_gp w detJ0 1/2 E_v . S_v
//! ```
//!
//! `K` is the exact derivative of `f_int` (the geometric term is the
//! derivative of `B^T` at fixed `S`), and `f_int` the exact gradient of `U`.
//! The point's sums are [`super::solid`]'s, shared with every element.

use super::material::Material;
use super::solid::{SolidResponse, add_point, point_energy, point_stress};
use super::stress::Stress;
use super::{ElementKind, InvalidElement, SolidElement};

/// The 2x2 Gauss points on the parent square (weights are all one).
pub const GAUSS_2X2: [[f64; 2]; 4] = {
    const G: f64 = 0.577_350_269_189_625_8; // 1/sqrt(3)
    [[-G, -G], [G, -G], [G, G], [-G, G]]
};

/// Parent coordinates of the four corners, counter-clockwise.
const CORNERS: [[f64; 2]; 4] = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];

/// `[dN_a/dxi, dN_a/deta]` at a parent point.
fn parent_gradients(xi: f64, eta: f64) -> [[f64; 2]; 4] {
    let mut out = [[0.0; 2]; 4];
    for (a, c) in CORNERS.iter().enumerate() {
        out[a] = [
            c[0] * (1.0 + c[1] * eta) / 4.0,
            c[1] * (1.0 + c[0] * xi) / 4.0,
        ];
    }
    out
}

/// The reference-configuration geometry of one element at its Gauss points,
/// computed once per mesh.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QuadGeometry {
    /// `G_a = dN_a/dX` per Gauss point and node.
    pub grads_ref: [[[f64; 2]; 4]; 4],
    /// `w detJ0` per Gauss point (the reference area weight).
    pub weight_ref: [f64; 4],
}

impl QuadGeometry {
    /// Geometry of the element with reference corner coordinates `x_ref`
    /// (counter-clockwise). Fails when `detJ0 <= 0` at a Gauss point
    /// (clockwise, degenerate or badly distorted element).
    pub fn new(x_ref: &[[f64; 2]; 4]) -> Result<QuadGeometry, InvalidElement> {
        let mut grads_ref = [[[0.0; 2]; 4]; 4];
        let mut weight_ref = [0.0; 4];
        let mut worst = f64::INFINITY;
        for (gp, p) in GAUSS_2X2.iter().enumerate() {
            let dn = parent_gradients(p[0], p[1]);
            // J[i][j] = sum_a X_a[i] dN_a/dxi_j
            let mut j = [[0.0; 2]; 2];
            for a in 0..4 {
                for i in 0..2 {
                    for k in 0..2 {
                        j[i][k] += x_ref[a][i] * dn[a][k];
                    }
                }
            }
            let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
            worst = worst.min(det);
            if !(det > 0.0) {
                continue;
            }
            // dN/dX = dN/dxi J^-1 (row vectors)
            let inv = [
                [j[1][1] / det, -j[0][1] / det],
                [-j[1][0] / det, j[0][0] / det],
            ];
            for a in 0..4 {
                grads_ref[gp][a] = [
                    dn[a][0] * inv[0][0] + dn[a][1] * inv[1][0],
                    dn[a][0] * inv[0][1] + dn[a][1] * inv[1][1],
                ];
            }
            weight_ref[gp] = det;
        }
        if !(worst > 0.0) {
            return Err(InvalidElement { det_j0: worst });
        }
        Ok(QuadGeometry {
            grads_ref,
            weight_ref,
        })
    }

    /// The reference area `sum w detJ0`.
    pub fn area_ref(&self) -> f64 {
        self.weight_ref.iter().sum()
    }
}

/// Internal force, tangent stiffness and strain energy of one element
/// (`f_int` ordered `[u1x, u1y, u2x, ..., u4y]`, the 8x8 tangent).
pub type QuadResponse = SolidResponse<8>;

/// Evaluates the element at displacements `u` (reference frame).
pub fn quad_response(geom: &QuadGeometry, u: &[f64; 8], material: &Material) -> QuadResponse {
    let d = material.d_matrix();
    let mut out = SolidResponse::starting_at(0.0);
    for gp in 0..4 {
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

/// Strain energy only (cheaper than [`quad_response`]).
pub fn quad_energy(geom: &QuadGeometry, u: &[f64; 8], material: &Material) -> f64 {
    let d = material.d_matrix();
    (0..4)
        .map(|gp| point_energy(&geom.grads_ref[gp], geom.weight_ref[gp], u, &d, material))
        .sum()
}

/// Stresses at each Gauss point of the element.
pub fn quad_point_stresses(geom: &QuadGeometry, u: &[f64; 8], material: &Material) -> [Stress; 4] {
    let d = material.d_matrix();
    std::array::from_fn(|gp| point_stress(&geom.grads_ref[gp], u, &d, material))
}

/// Stresses averaged over the Gauss points (equal weights).
pub fn quad_mean_stress(geom: &QuadGeometry, u: &[f64; 8], material: &Material) -> Stress {
    Stress::mean(&quad_point_stresses(geom, u, material))
}

impl SolidElement<2, 4, 8, 3> for QuadGeometry {
    const KIND: ElementKind = ElementKind::Quad4;

    fn from_reference(x_ref: &[[f64; 2]; 4]) -> Result<Self, InvalidElement> {
        QuadGeometry::new(x_ref)
    }

    fn measure_ref(&self) -> f64 {
        self.area_ref()
    }

    fn response(&self, u: &[f64; 8], material: &Material) -> SolidResponse<8> {
        quad_response(self, u, material)
    }

    fn energy(&self, u: &[f64; 8], material: &Material) -> f64 {
        quad_energy(self, u, material)
    }

    fn point_stresses(&self, u: &[f64; 8], material: &Material) -> Vec<Stress<3>> {
        quad_point_stresses(self, u, material).to_vec()
    }

    fn mean_stress(&self, u: &[f64; 8], material: &Material) -> Stress<3> {
        quad_mean_stress(self, u, material)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::material::PlaneModel;
    use crate::testutil::Lcg;

    const MAT: Material = Material {
        young: 1000.0,
        poisson: 0.3,
        model: PlaneModel::PlaneStress,
        kinematics: crate::element::material::Kinematics::Finite,
    };

    fn distorted() -> [[f64; 2]; 4] {
        [[0.1, -0.05], [1.2, 0.1], [1.0, 0.7], [-0.1, 0.55]]
    }

    #[test]
    fn area_and_partition_of_unity() {
        let g = QuadGeometry::new(&[[0.0, 0.0], [2.0, 0.0], [2.0, 0.5], [0.0, 0.5]]).unwrap();
        assert!((g.area_ref() - 1.0).abs() < 1e-14);
        for gp in 0..4 {
            for dir in 0..2 {
                let s: f64 = (0..4).map(|a| g.grads_ref[gp][a][dir]).sum();
                assert!(s.abs() < 1e-14);
            }
        }
        assert!(QuadGeometry::new(&[[0.0, 0.0], [0.0, 1.0], [1.0, 1.0], [1.0, 0.0]]).is_err());
    }

    /// Rigid motions (large rotation plus translation) carry no strain, no
    /// energy and no internal force.
    #[test]
    fn rigid_rotation_is_stress_free() {
        let x = distorted();
        let g = QuadGeometry::new(&x).unwrap();
        let (c, s) = (0.7_f64.cos(), 0.7_f64.sin());
        let mut u = [0.0; 8];
        for a in 0..4 {
            u[2 * a] = c * x[a][0] - s * x[a][1] + 0.3 - x[a][0];
            u[2 * a + 1] = s * x[a][0] + c * x[a][1] - 1.1 - x[a][1];
        }
        let r = quad_response(&g, &u, &MAT);
        assert!(r.energy.abs() < 1e-12);
        assert!(r.f_int.iter().all(|f| f.abs() < 1e-10));
    }

    /// The internal force is the gradient of the energy and the tangent the
    /// derivative of the internal force (central differences, h = 1e-6,
    /// relative tolerance 1e-6), at random deformed states.
    #[test]
    fn tangent_and_force_match_finite_differences() {
        let mut rng = Lcg::new(7);
        let x = distorted();
        let g = QuadGeometry::new(&x).unwrap();
        for model in [PlaneModel::PlaneStress, PlaneModel::PlaneStrain] {
            let mat = Material { model, ..MAT };
            for _ in 0..5 {
                let u: [f64; 8] = std::array::from_fn(|_| rng.uniform(-0.2, 0.2));
                let r = quad_response(&g, &u, &mat);
                let h = 1e-6;
                let scale = r.k.iter().flatten().fold(0.0_f64, |m, v| m.max(v.abs()));
                for p in 0..8 {
                    let mut up = u;
                    let mut um = u;
                    up[p] += h;
                    um[p] -= h;
                    let fd_e =
                        (quad_energy(&g, &up, &mat) - quad_energy(&g, &um, &mat)) / (2.0 * h);
                    assert!(
                        (fd_e - r.f_int[p]).abs() < 1e-6 * scale.max(1.0),
                        "force {p}"
                    );
                    let rp = quad_response(&g, &up, &mat);
                    let rm = quad_response(&g, &um, &mat);
                    for q in 0..8 {
                        let fd = (rp.f_int[q] - rm.f_int[q]) / (2.0 * h);
                        assert!(
                            (fd - r.k[q][p]).abs() < 1e-6 * scale,
                            "K[{q}][{p}]: {fd} vs {}",
                            r.k[q][p]
                        );
                    }
                }
            }
        }
    }

    /// A homogeneous deformation gives the same stress at every Gauss point,
    /// equal to `D E_v` of the prescribed deformation gradient.
    #[test]
    fn homogeneous_deformation_gives_constant_stress() {
        let x = distorted();
        let g = QuadGeometry::new(&x).unwrap();
        let h = [[0.1, 0.05], [-0.03, 0.2]];
        let mut u = [0.0; 8];
        for a in 0..4 {
            for i in 0..2 {
                u[2 * a + i] = h[i][0] * x[a][0] + h[i][1] * x[a][1];
            }
        }
        let f = [[1.1, 0.05], [-0.03, 1.2]];
        let e = [
            (f[0][0] * f[0][0] + f[1][0] * f[1][0] - 1.0) / 2.0,
            (f[0][1] * f[0][1] + f[1][1] * f[1][1] - 1.0) / 2.0,
            f[0][0] * f[0][1] + f[1][0] * f[1][1],
        ];
        let d = MAT.d_matrix();
        let s: [f64; 3] = std::array::from_fn(|r| d[r][0] * e[0] + d[r][1] * e[1] + d[r][2] * e[2]);
        for p in quad_point_stresses(&g, &u, &MAT) {
            for c in 0..3 {
                assert!((p.pk2[c] - s[c]).abs() < 1e-10 * s[c].abs().max(1.0));
            }
        }
    }
}
