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

use super::ElementKind;
use super::geometry::{Geometry, Shape, gauss_point};

/// The 2x2 Gauss points on the parent square (weights are all one).
pub const GAUSS_2X2: [[f64; 2]; 4] = {
    const G: f64 = 0.577_350_269_189_625_8; // 1/sqrt(3)
    [[-G, -G], [G, -G], [G, G], [-G, G]]
};

/// Parent coordinates of the four corners, counter-clockwise.
pub const CORNERS: [[f64; 2]; 4] = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];

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

/// The 4-node quadrilateral's parent square and 2x2 Gauss rule.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Quad4;

impl Shape<2, 4, 4> for Quad4 {
    const KIND: ElementKind = ElementKind::Quad4;

    fn point(x_ref: &[[f64; 2]; 4], p: usize) -> (f64, Option<[[f64; 2]; 4]>) {
        let [xi, eta] = GAUSS_2X2[p];
        gauss_point(x_ref, &parent_gradients(xi, eta))
    }

    fn weight(det_j0: f64) -> f64 {
        det_j0
    }
}

/// The reference geometry of one quadrilateral at its four Gauss points,
/// computed once per mesh.
pub type QuadGeometry = Geometry<Quad4, 2, 4, 8, 3, 4>;

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::element::SolidElement;
    use crate::element::material::Material;
    use crate::element::material::PlaneModel;
    use crate::testutil::Lcg;

    /// The 2D element tests' material.
    pub(in crate::element) const MAT: Material = Material {
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
        assert!((g.measure_ref() - 1.0).abs() < 1e-14);
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
        let r = g.response(&u, &MAT);
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
                let r = g.response(&u, &mat);
                let h = 1e-6;
                let scale = r.k.iter().flatten().fold(0.0_f64, |m, v| m.max(v.abs()));
                for p in 0..8 {
                    let mut up = u;
                    let mut um = u;
                    up[p] += h;
                    um[p] -= h;
                    let fd_e = (g.energy(&up, &mat) - g.energy(&um, &mat)) / (2.0 * h);
                    assert!(
                        (fd_e - r.f_int[p]).abs() < 1e-6 * scale.max(1.0),
                        "force {p}"
                    );
                    let rp = g.response(&up, &mat);
                    let rm = g.response(&um, &mat);
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
        for p in g.point_stresses(&u, &MAT) {
            for c in 0..3 {
                assert!((p.pk2[c] - s[c]).abs() < 1e-10 * s[c].abs().max(1.0));
            }
        }
    }
}
