//! Kinematics and stress at one integration point of a total-Lagrangian
//! element, shared by the Q4 ([`crate::quad`]) and the triangle
//! ([`crate::tri`]).
//!
//! With the reference gradients `G_a = dN_a/dX` of the element's `N` nodes
//! and their displacements `u` (`[u1x, u1y, u2x, ...]`):
//!
//! ```text
//! H   = sum_a u_a G_a^T                 (displacement gradient du/dX)
//! F   = I + H
//! E_v = [E11, E22, 2 E12],  E = (H + H^T + H^T H)/2   (no cancellation of F^T F - I)
//! S_v = D E_v                            (St Venant–Kirchhoff, see `material`)
//! ```
//!
//! With [`Kinematics::Small`] (linear elasticity) `F` is taken as `I` in
//! what the elements build from it (the strain-displacement matrix) and
//! `E_v = [H11, H22, H12 + H21]`, so `S_v` is the Cauchy stress of linear
//! elasticity and the element drops its geometric stiffness.
//!
//! One function serves every element, so a homogeneous deformation gives
//! every element type the same bits.

use crate::material::Kinematics;

/// Deformation gradient, strain and stress at one point.
pub(crate) struct PointState {
    /// `F = I + H`.
    pub(crate) f: [[f64; 2]; 2],
    /// Green–Lagrange strain, Voigt with engineering shear.
    pub(crate) e_v: [f64; 3],
    /// Second Piola–Kirchhoff stress `D E_v`.
    pub(crate) s_v: [f64; 3],
}

/// The state at a point with reference gradients `grads` of `N` nodes and
/// displacements `u` (`2 N` values), for the material matrix `d` and the
/// strain measure `kinematics`.
pub(crate) fn point_state<const N: usize>(
    grads: &[[f64; 2]; N],
    u: &[f64],
    d: &[[f64; 3]; 3],
    kinematics: Kinematics,
) -> PointState {
    let u = &u[..2 * N];
    // displacement gradient H = du/dX; F = I + H
    let mut h = [[0.0; 2]; 2];
    for a in 0..N {
        for i in 0..2 {
            for j in 0..2 {
                h[i][j] += u[2 * a + i] * grads[a][j];
            }
        }
    }
    if kinematics == Kinematics::Small {
        let e_v = [h[0][0], h[1][1], h[0][1] + h[1][0]];
        return PointState {
            f: [[1.0, 0.0], [0.0, 1.0]],
            e_v,
            s_v: stress(d, &e_v),
        };
    }
    let f = [[1.0 + h[0][0], h[0][1]], [h[1][0], 1.0 + h[1][1]]];
    // E = (H + H^T + H^T H)/2, without the cancellation of F^T F - I
    let hh = |j: usize, k: usize| h[0][j] * h[0][k] + h[1][j] * h[1][k];
    let e_v = [
        h[0][0] + hh(0, 0) / 2.0,
        h[1][1] + hh(1, 1) / 2.0,
        h[0][1] + h[1][0] + hh(0, 1),
    ];
    PointState {
        f,
        e_v,
        s_v: stress(d, &e_v),
    }
}

/// `S_v = D E_v`.
fn stress(d: &[[f64; 3]; 3], e_v: &[f64; 3]) -> [f64; 3] {
    let mut s_v = [0.0; 3];
    for r in 0..3 {
        s_v[r] = d[r][0] * e_v[0] + d[r][1] * e_v[1] + d[r][2] * e_v[2];
    }
    s_v
}

#[cfg(test)]
mod tests {
    use crate::material::{Kinematics, Material, PlaneModel};
    use crate::quad::{QuadGeometry, quad_energy, quad_response};
    use crate::testutil::Lcg;
    use crate::tri::{TriGeometry, tri_energy, tri_response};

    const SMALL: Material = Material {
        young: 200.0,
        poisson: 0.3,
        model: PlaneModel::PlaneStrain,
        kinematics: Kinematics::Small,
    };

    const QUAD: [[f64; 2]; 4] = [[0.0, 0.0], [1.2, 0.1], [1.0, 0.9], [-0.1, 0.8]];
    const TRI: [[f64; 2]; 3] = [[0.0, 0.0], [1.1, 0.2], [0.3, 0.9]];

    /// Central-difference check of `f = dW/du` and `K = df/du` (h = 1e-6,
    /// relative 1e-6) for one element given as energy and response.
    fn check_derivatives<const M: usize>(
        u: [f64; M],
        energy: impl Fn(&[f64; M]) -> f64,
        response: impl Fn(&[f64; M]) -> ([f64; M], [[f64; M]; M]),
    ) {
        let (f, k) = response(&u);
        let scale = k.iter().flatten().fold(1.0_f64, |m, v| m.max(v.abs()));
        let h = 1e-6;
        for p in 0..M {
            let (mut up, mut um) = (u, u);
            up[p] += h;
            um[p] -= h;
            let fd_e = (energy(&up) - energy(&um)) / (2.0 * h);
            assert!((fd_e - f[p]).abs() < 1e-6 * scale, "force {p}");
            let (fp, _) = response(&up);
            let (fm, _) = response(&um);
            for q in 0..M {
                let fd = (fp[q] - fm[q]) / (2.0 * h);
                assert!((fd - k[q][p]).abs() < 1e-6 * scale, "K[{q}][{p}]");
            }
        }
    }

    /// With small kinematics the Q4 and the triangle are linear: the force
    /// is the energy's gradient, the tangent the force's derivative and
    /// independent of the displacement, and `f = K u`.
    #[test]
    fn small_strain_elements_are_linear_and_consistent() {
        let mut rng = Lcg::new(11);
        let qg = QuadGeometry::new(&QUAD).unwrap();
        let tg = TriGeometry::new(&TRI).unwrap();
        for _ in 0..3 {
            let u: [f64; 8] = std::array::from_fn(|_| rng.uniform(-0.2, 0.2));
            check_derivatives(
                u,
                |u| quad_energy(&qg, u, &SMALL),
                |u| {
                    let r = quad_response(&qg, u, &SMALL);
                    (r.f_int, r.k)
                },
            );
            let r = quad_response(&qg, &u, &SMALL);
            let r0 = quad_response(&qg, &[0.0; 8], &SMALL);
            assert_eq!(r.k, r0.k, "the Q4 tangent depends on u");
            for p in 0..8 {
                let ku: f64 = (0..8).map(|q| r.k[p][q] * u[q]).sum();
                assert!((ku - r.f_int[p]).abs() < 1e-10 * r.f_int[p].abs().max(1.0));
            }

            let u: [f64; 6] = std::array::from_fn(|_| rng.uniform(-0.2, 0.2));
            check_derivatives(
                u,
                |u| tri_energy(&tg, u, &SMALL),
                |u| {
                    let r = tri_response(&tg, u, &SMALL);
                    (r.f_int, r.k)
                },
            );
            let r = tri_response(&tg, &u, &SMALL);
            let r0 = tri_response(&tg, &[0.0; 6], &SMALL);
            assert_eq!(r.k, r0.k, "the triangle tangent depends on u");
        }
    }

    /// At the reference state both kinematics have the same tangent, and
    /// for a displacement of size `s` their forces differ by `O(s^2)`.
    #[test]
    fn small_and_finite_agree_to_first_order() {
        let finite = Material {
            kinematics: Kinematics::Finite,
            ..SMALL
        };
        let qg = QuadGeometry::new(&QUAD).unwrap();
        let k_small = quad_response(&qg, &[0.0; 8], &SMALL).k;
        let k_finite = quad_response(&qg, &[0.0; 8], &finite).k;
        assert_eq!(k_small, k_finite);
        let dir: [f64; 8] = [0.3, -0.1, 0.2, 0.4, -0.2, 0.1, 0.05, -0.3];
        let diff = |s: f64| {
            let u = dir.map(|d| s * d);
            let a = quad_response(&qg, &u, &SMALL).f_int;
            let b = quad_response(&qg, &u, &finite).f_int;
            a.iter()
                .zip(&b)
                .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()))
        };
        let ratio = diff(1e-3) / diff(5e-4);
        assert!(
            (ratio - 4.0).abs() < 0.05,
            "difference ratio {ratio}, expected 4"
        );
    }

    /// Small kinematics is not rotation invariant: a rigid rotation strains
    /// it (the documented limit of linear elasticity).
    #[test]
    fn small_strain_is_not_rotation_invariant() {
        let tg = TriGeometry::new(&TRI).unwrap();
        let (c, s) = (0.3_f64.cos(), 0.3_f64.sin());
        let mut u = [0.0; 6];
        for a in 0..3 {
            u[2 * a] = c * TRI[a][0] - s * TRI[a][1] - TRI[a][0];
            u[2 * a + 1] = s * TRI[a][0] + c * TRI[a][1] - TRI[a][1];
        }
        assert!(tri_energy(&tg, &u, &SMALL) > 1e-3);
        let finite = Material {
            kinematics: Kinematics::Finite,
            ..SMALL
        };
        assert!(tri_energy(&tg, &u, &finite).abs() < 1e-12);
    }
}
