//! The total-Lagrangian 3-node linear triangle (constant strain, T3) with
//! St Venant–Kirchhoff material: the triangular counterpart of [`quad`].
//!
//! Nodes are numbered counter-clockwise; the linear shape functions on the
//! parent triangle `xi, eta >= 0, xi + eta <= 1` are
//! `N_1 = 1 - xi - eta`, `N_2 = xi`, `N_3 = eta`.
//!
//! With reference coordinates `X` and displacements `u` (all in the reference
//! frame, unit thickness), the shape functions are linear, so their
//! reference gradients, the deformation gradient, the strain and the stress
//! are constant over the element:
//!
//! ```text
//! J0      = [X_2 - X_1, X_3 - X_1]           (reference Jacobian, columns)
//! A0      = detJ0 / 2                          (reference area)
//! G_a     = dN_a/dX = J0^-T dN_a/dxi           (constant):
//!           G_2 = [Y_3 - Y_1, X_1 - X_3]/detJ0,
//!           G_3 = [Y_1 - Y_2, X_2 - X_1]/detJ0,  G_1 = -(G_2 + G_3)
//! F       = I + sum_a u_a G_a^T                (deformation gradient)
//! E       = (F^T F - I)/2,  E_v = [E11, E22, 2 E12]
//! S_v     = D E_v                              (see `material`)
//! B       : dE_v/du, columns 2a+i:
//!           [F_i1 G_a1,  F_i2 G_a2,  F_i1 G_a2 + F_i2 G_a1]
//! f_int   = A0 B^T S_v
//! K       = A0 (B^T D B + (G_a . S G_b) I_2)
//! U       = A0 1/2 E_v . S_v
//! ```
//!
//! The integrand is constant, so one integration point (weight `A0`) is
//! exact. `K` is the exact derivative of `f_int` (the geometric term is the
//! derivative of `B^T` at fixed `S`), and `f_int` the exact gradient of `U`.
//! The operations per point are those of [`quad`] (one integrand,
//! [`super::solid`]), so a homogeneous deformation gives the triangle and
//! the quadrilateral the same stress.
//!
//! Invariant of a [`TriGeometry`]: finite reference coordinates and
//! `detJ0 > MIN_RELATIVE_DET * l_max^2` (`l_max` the longest edge,
//! [`super::geometry`]), i.e. counter-clockwise and not degenerate beyond
//! rounding. Failures are [`super::InvalidElement`] (`det_j0` is the
//! element's one `detJ0`, NaN for a non-finite coordinate).
//!
//! [`quad`]: super::quad

use super::ElementKind;
use super::geometry::{Geometry, Shape, simplex_point};

/// The 3-node triangle's parent triangle and one-point rule.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tri3;

impl Shape<2, 3, 1> for Tri3 {
    const KIND: ElementKind = ElementKind::Tri3;

    fn point(x_ref: &[[f64; 2]; 3], _: usize) -> (f64, Option<[[f64; 2]; 3]>) {
        simplex_point(x_ref)
    }

    /// `A0 = detJ0 / 2`.
    fn weight(det_j0: f64) -> f64 {
        det_j0 / 2.0
    }
}

/// The reference geometry of one triangle (constant gradients, the weight
/// `A0`), computed once per mesh.
pub type TriGeometry = Geometry<Tri3, 2, 3, 6, 3, 1>;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::SolidElement;
    use crate::element::material::{Material, PlaneModel};
    use crate::element::quad::QuadGeometry;
    use crate::element::quad::tests::MAT;
    use crate::testutil::Lcg;

    fn skewed() -> [[f64; 2]; 3] {
        [[0.1, -0.05], [1.2, 0.1], [0.3, 0.7]]
    }

    /// A random counter-clockwise triangle that is not too flat.
    fn random_triangle(rng: &mut Lcg) -> [[f64; 2]; 3] {
        loop {
            let x: [[f64; 2]; 3] =
                std::array::from_fn(|_| [rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)]);
            let det = (x[1][0] - x[0][0]) * (x[2][1] - x[0][1])
                - (x[2][0] - x[0][0]) * (x[1][1] - x[0][1]);
            if det > 0.2 {
                return x;
            }
        }
    }

    /// Nodal displacements of the map `x = R (I + H) X + c`.
    fn mapped(x: &[[f64; 2]; 3], h: [[f64; 2]; 2], angle: f64, c: [f64; 2]) -> [f64; 6] {
        let (cs, sn) = (angle.cos(), angle.sin());
        let mut u = [0.0; 6];
        for a in 0..3 {
            let y = [
                x[a][0] + h[0][0] * x[a][0] + h[0][1] * x[a][1],
                x[a][1] + h[1][0] * x[a][0] + h[1][1] * x[a][1],
            ];
            u[2 * a] = cs * y[0] - sn * y[1] + c[0] - x[a][0];
            u[2 * a + 1] = sn * y[0] + cs * y[1] + c[1] - x[a][1];
        }
        u
    }

    fn max_abs(v: impl IntoIterator<Item = f64>) -> f64 {
        v.into_iter().fold(0.0_f64, |m, x| m.max(x.abs()))
    }

    #[test]
    fn area_and_partition_of_unity() {
        let g = TriGeometry::new(&[[0.0, 0.0], [2.0, 0.0], [0.5, 0.5]]).unwrap();
        assert!((g.measure_ref() - 0.5).abs() < 1e-15);
        for dir in 0..2 {
            let s: f64 = (0..3).map(|a| g.grads_ref[0][a][dir]).sum();
            assert!(s.abs() < 1e-15);
        }
        // G_a . (X_b - X_c) reproduces the identity: sum_a X_a G_a^T = I.
        let x = skewed();
        let g = TriGeometry::new(&x).unwrap();
        for i in 0..2 {
            for j in 0..2 {
                let v: f64 = (0..3).map(|a| x[a][i] * g.grads_ref[0][a][j]).sum();
                let id = if i == j { 1.0 } else { 0.0 };
                assert!((v - id).abs() < 1e-14, "[{i}][{j}] = {v}");
            }
        }
    }

    /// Clockwise, degenerate (collinear or coincident nodes, also collinear
    /// up to rounding) and non-finite elements are rejected with the
    /// quadrilateral's error.
    #[test]
    fn invalid_elements_are_rejected() {
        let x = skewed();
        let cw = [x[0], x[2], x[1]];
        let err = TriGeometry::new(&cw).unwrap_err();
        assert!(err.det_j0 < 0.0);
        let collinear = [[0.0, 0.0], [1.0, 1.0], [3.0, 3.0]];
        assert_eq!(TriGeometry::new(&collinear).unwrap_err().det_j0, 0.0);
        let coincident = [[0.5, 0.5], [0.5, 0.5], [1.0, 0.0]];
        assert!(TriGeometry::new(&coincident).is_err());
        let point = [[0.5, 0.5]; 3];
        assert!(TriGeometry::new(&point).is_err());
        // Collinear in exact arithmetic, with coordinates that are not
        // representable: whatever the sign of the computed detJ0, rejected.
        let mut rng = Lcg::new(3);
        for _ in 0..200 {
            let p = [rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)];
            let d = [rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)];
            let (s, t) = (rng.uniform(0.1, 0.9), rng.uniform(1.1, 2.0));
            let near = [
                p,
                [p[0] + s * d[0], p[1] + s * d[1]],
                [p[0] + t * d[0], p[1] + t * d[1]],
            ];
            assert!(TriGeometry::new(&near).is_err(), "{near:?}");
            assert!(TriGeometry::new(&[near[0], near[2], near[1]]).is_err());
        }
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            for a in 0..3 {
                for i in 0..2 {
                    let mut y = x;
                    y[a][i] = bad;
                    let err = TriGeometry::new(&y).unwrap_err();
                    assert!(err.det_j0.is_nan(), "{y:?}");
                }
            }
        }
        // A thin but honest triangle passes.
        assert!(TriGeometry::new(&[[0.0, 0.0], [1.0, 0.0], [0.5, 1e-9]]).is_ok());
    }

    /// Rigid motions (translation, and a large rotation plus translation)
    /// carry no strain, no energy and no internal force.
    #[test]
    fn rigid_motion_is_stress_free() {
        let x = skewed();
        let g = TriGeometry::new(&x).unwrap();
        let zero = [[0.0; 2]; 2];
        for (angle, c) in [(0.0, [0.3, -1.1]), (0.7, [0.3, -1.1]), (2.5, [0.0, 0.0])] {
            let u = mapped(&x, zero, angle, c);
            let r = g.response(&u, &MAT);
            assert!(r.energy.abs() < 1e-12, "{angle}: U = {}", r.energy);
            assert!(max_abs(r.f_int) < 1e-10, "{angle}: {:?}", r.f_int);
            let s = g.mean_stress(&u, &MAT);
            assert!(max_abs(s.pk2.into_iter().chain(s.cauchy)) < 1e-10);
        }
    }

    /// The internal force is the gradient of the energy and the tangent the
    /// derivative of the internal force (central differences, h = 1e-6,
    /// relative tolerance 1e-6), at random deformed states of random
    /// triangles; the tangent is symmetric.
    #[test]
    fn tangent_and_force_match_finite_differences() {
        let mut rng = Lcg::new(7);
        for model in [PlaneModel::PlaneStress, PlaneModel::PlaneStrain] {
            let mat = Material { model, ..MAT };
            for _ in 0..5 {
                let g = TriGeometry::new(&random_triangle(&mut rng)).unwrap();
                let u: [f64; 6] = std::array::from_fn(|_| rng.uniform(-0.2, 0.2));
                let r = g.response(&u, &mat);
                let h = 1e-6;
                let scale = max_abs(r.k.into_iter().flatten());
                for p in 0..6 {
                    let mut up = u;
                    let mut um = u;
                    up[p] += h;
                    um[p] -= h;
                    let fd_e = (g.energy(&up, &mat) - g.energy(&um, &mat)) / (2.0 * h);
                    assert!(
                        (fd_e - r.f_int[p]).abs() < 1e-6 * scale.max(1.0),
                        "force {p}: {fd_e} vs {}",
                        r.f_int[p]
                    );
                    let rp = g.response(&up, &mat);
                    let rm = g.response(&um, &mat);
                    for q in 0..6 {
                        let fd = (rp.f_int[q] - rm.f_int[q]) / (2.0 * h);
                        assert!(
                            (fd - r.k[q][p]).abs() < 1e-6 * scale,
                            "K[{q}][{p}]: {fd} vs {}",
                            r.k[q][p]
                        );
                        assert_eq!(r.k[p][q], r.k[q][p]);
                    }
                }
                assert_eq!(r.energy, g.energy(&u, &mat));
            }
        }
    }

    /// A homogeneous deformation gives `S_v = D E_v` of the prescribed
    /// deformation gradient, the Cauchy stress `F S F^T / det F`, the energy
    /// `A0/2 E_v . S_v`, and nodal forces `A0 F S G_a`.
    #[test]
    fn homogeneous_deformation_gives_analytic_stress() {
        let x = skewed();
        let g = TriGeometry::new(&x).unwrap();
        let hm = [[0.1, 0.05], [-0.03, 0.2]];
        let u = mapped(&x, hm, 0.0, [0.0, 0.0]);
        let f = [[1.1, 0.05], [-0.03, 1.2]];
        let e = [
            (f[0][0] * f[0][0] + f[1][0] * f[1][0] - 1.0) / 2.0,
            (f[0][1] * f[0][1] + f[1][1] * f[1][1] - 1.0) / 2.0,
            f[0][0] * f[0][1] + f[1][0] * f[1][1],
        ];
        for model in [PlaneModel::PlaneStress, PlaneModel::PlaneStrain] {
            let mat = Material { model, ..MAT };
            let d = mat.d_matrix();
            let s: [f64; 3] =
                std::array::from_fn(|r| d[r][0] * e[0] + d[r][1] * e[1] + d[r][2] * e[2]);
            let sm = [[s[0], s[2]], [s[2], s[1]]];
            let fs = |i: usize, j: usize| f[i][0] * sm[0][j] + f[i][1] * sm[1][j];
            let det_f = f[0][0] * f[1][1] - f[0][1] * f[1][0];
            let sigma = |i: usize, j: usize| (fs(i, 0) * f[j][0] + fs(i, 1) * f[j][1]) / det_f;
            let cauchy = [sigma(0, 0), sigma(1, 1), sigma(0, 1)];
            let tol = 1e-12 * s[0].abs().max(s[1].abs());
            let st = g.mean_stress(&u, &mat);
            for c in 0..3 {
                assert!((st.pk2[c] - s[c]).abs() < tol, "S[{c}]");
                assert!((st.cauchy[c] - cauchy[c]).abs() < tol, "sigma[{c}]");
            }
            assert!((st.green[0] - e[0]).abs() < 1e-14);
            assert!((st.green[1] - e[1]).abs() < 1e-14);
            assert!((st.green[2] - e[2] / 2.0).abs() < 1e-14);
            let r = g.response(&u, &mat);
            let energy = g.measure_ref() / 2.0 * (e[0] * s[0] + e[1] * s[1] + e[2] * s[2]);
            assert!((r.energy - energy).abs() < 1e-12 * energy);
            for a in 0..3 {
                for i in 0..2 {
                    let ga = g.grads_ref[0][a];
                    let fa = g.measure_ref() * (fs(i, 0) * ga[0] + fs(i, 1) * ga[1]);
                    assert!((r.f_int[2 * a + i] - fa).abs() < tol, "f[{a}][{i}]");
                }
            }
        }
    }

    /// Two triangles forming a square match a Q4 on the same square under
    /// homogeneous deformations (a uniform stretch, then a general one with
    /// a rotation): the same energy to 1e-12 relative, and the same
    /// assembled nodal forces (both are `F S` times the boundary integral of
    /// the same linear edge traces).
    #[test]
    fn two_triangles_match_a_quad_under_homogeneous_deformation() {
        let side = 1.5;
        let sq = [[0.0, 0.0], [side, 0.0], [side, side], [0.0, side]];
        let q = QuadGeometry::new(&sq).unwrap();
        let splits = [[[0, 1, 2], [0, 2, 3]], [[0, 1, 3], [1, 2, 3]]];
        for model in [PlaneModel::PlaneStress, PlaneModel::PlaneStrain] {
            let mat = Material { model, ..MAT };
            for (hm, angle) in [
                ([[0.2, 0.0], [0.0, 0.0]], 0.0),
                ([[0.1, 0.05], [-0.03, 0.2]], 0.9),
            ] {
                let mut uq = [0.0; 8];
                for a in 0..4 {
                    let (cs, sn) = (f64::cos(angle), f64::sin(angle));
                    let x = sq[a];
                    let y = [
                        x[0] + hm[0][0] * x[0] + hm[0][1] * x[1],
                        x[1] + hm[1][0] * x[0] + hm[1][1] * x[1],
                    ];
                    uq[2 * a] = cs * y[0] - sn * y[1] + 0.4 - x[0];
                    uq[2 * a + 1] = sn * y[0] + cs * y[1] - 0.2 - x[1];
                }
                let rq = q.response(&uq, &mat);
                assert!((rq.energy - q.energy(&uq, &mat)).abs() < 1e-12 * rq.energy);
                for split in splits {
                    let mut energy = 0.0;
                    let mut f = [0.0; 8];
                    for tri in split {
                        let g = TriGeometry::new(&tri.map(|n| sq[n])).unwrap();
                        let u: [f64; 6] = std::array::from_fn(|p| uq[2 * tri[p / 2] + p % 2]);
                        let r = g.response(&u, &mat);
                        energy += r.energy;
                        for p in 0..6 {
                            f[2 * tri[p / 2] + p % 2] += r.f_int[p];
                        }
                    }
                    assert!(
                        (energy - rq.energy).abs() < 1e-12 * rq.energy,
                        "{energy} vs {}",
                        rq.energy
                    );
                    let scale = max_abs(rq.f_int);
                    for p in 0..8 {
                        assert!((f[p] - rq.f_int[p]).abs() < 1e-12 * scale, "f[{p}]");
                    }
                }
            }
        }
    }

    /// Element-level patch test on the MacNeal–Harder patch with every
    /// quadrilateral split into two triangles: under a homogeneous
    /// deformation the assembled internal force vanishes at the interior
    /// nodes and every element has the same stress.
    #[test]
    fn patch_of_triangles_is_in_equilibrium_under_homogeneous_deformation() {
        let nodes = crate::element::tests::mixed::NODES;
        let quads = crate::element::tests::mixed::QUADS;
        let tris: Vec<[usize; 3]> = quads
            .iter()
            .flat_map(|&[a, b, c, d]| [[a, b, c], [a, c, d]])
            .collect();
        let hm = [[0.08, 0.03], [-0.02, 0.05]];
        let mut f = [0.0; 16];
        let mut stresses = Vec::new();
        for tri in &tris {
            let x = tri.map(|n| nodes[n]);
            let g = TriGeometry::new(&x).unwrap();
            let u = mapped(&x, hm, 0.4, [0.01, -0.02]);
            let r = g.response(&u, &MAT);
            for p in 0..6 {
                f[2 * tri[p / 2] + p % 2] += r.f_int[p];
            }
            stresses.push(g.mean_stress(&u, &MAT));
        }
        let scale = max_abs(f);
        assert!(scale > 1.0);
        for p in 8..16 {
            assert!(f[p].abs() < 1e-12 * scale, "f[{p}] = {}", f[p]);
        }
        let s0 = stresses[0];
        for s in &stresses {
            for c in 0..3 {
                assert!((s.pk2[c] - s0.pk2[c]).abs() < 1e-10 * s0.pk2[0].abs());
                assert!((s.cauchy[c] - s0.cauchy[c]).abs() < 1e-10 * s0.cauchy[0].abs());
            }
        }
    }

    /// Objectivity: a rigid rotation (and translation) superposed on a
    /// deformed state changes neither the energy, nor the PK2 stress, and
    /// rotates the Cauchy stress and the internal force.
    #[test]
    fn superposed_rotation_leaves_energy_unchanged() {
        let mut rng = Lcg::new(19);
        for model in [PlaneModel::PlaneStress, PlaneModel::PlaneStrain] {
            let mat = Material { model, ..MAT };
            for _ in 0..5 {
                let x = random_triangle(&mut rng);
                let g = TriGeometry::new(&x).unwrap();
                let u: [f64; 6] = std::array::from_fn(|_| rng.uniform(-0.2, 0.2));
                let angle = rng.uniform(-3.0, 3.0);
                let c = [rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)];
                let (cs, sn) = (angle.cos(), angle.sin());
                let rot = |v: [f64; 2]| [cs * v[0] - sn * v[1], sn * v[0] + cs * v[1]];
                let mut ur = [0.0; 6];
                for a in 0..3 {
                    let y = rot([x[a][0] + u[2 * a], x[a][1] + u[2 * a + 1]]);
                    ur[2 * a] = y[0] + c[0] - x[a][0];
                    ur[2 * a + 1] = y[1] + c[1] - x[a][1];
                }
                let r = g.response(&u, &mat);
                let rr = g.response(&ur, &mat);
                assert!((r.energy - rr.energy).abs() < 1e-12 * r.energy.max(1.0));
                let scale = max_abs(r.f_int);
                for a in 0..3 {
                    let fa = rot([r.f_int[2 * a], r.f_int[2 * a + 1]]);
                    for i in 0..2 {
                        assert!((rr.f_int[2 * a + i] - fa[i]).abs() < 1e-11 * scale);
                    }
                }
                let s = g.mean_stress(&u, &mat);
                let sr = g.mean_stress(&ur, &mat);
                let smax = max_abs(s.pk2);
                for k in 0..3 {
                    assert!((s.pk2[k] - sr.pk2[k]).abs() < 1e-11 * smax);
                }
                // sigma_r = R sigma R^T
                let sig = [[s.cauchy[0], s.cauchy[2]], [s.cauchy[2], s.cauchy[1]]];
                let col0 = rot([sig[0][0], sig[1][0]]);
                let col1 = rot([sig[0][1], sig[1][1]]);
                let rs = [[col0[0], col1[0]], [col0[1], col1[1]]];
                let rsrt = [rot(rs[0]), rot(rs[1])];
                let cmax = max_abs(s.cauchy);
                assert!((sr.cauchy[0] - rsrt[0][0]).abs() < 1e-11 * cmax);
                assert!((sr.cauchy[1] - rsrt[1][1]).abs() < 1e-11 * cmax);
                assert!((sr.cauchy[2] - rsrt[0][1]).abs() < 1e-11 * cmax);
            }
        }
    }
}
