//! Kinematics and stress at one integration point of a total-Lagrangian
//! element in `D = 2` or `3` dimensions, shared by every element
//! ([`super::quad`], [`super::tri`], [`super::hex`], [`super::tet`]).
//!
//! With the reference gradients `G_a = dN_a/dX` of the element's `N` nodes
//! and their displacements `u` (`[u1x, u1y, (u1z,) u2x, ...]`):
//!
//! ```text
//! H   = sum_a u_a G_a^T                 (displacement gradient du/dX)
//! F   = I + H
//! E   = (H + H^T + H^T H)/2             (no cancellation of F^T F - I)
//! E_v = E in Voigt order with engineering shear (`VOIGT`):
//!       2D [E11, E22, 2 E12], 3D [E11, E22, E33, 2 E23, 2 E13, 2 E12]
//! S_v = D E_v                            (St Venant–Kirchhoff, see `material`)
//! ```
//!
//! With [`Kinematics::Small`] (linear elasticity) `F` is taken as `I` in
//! what the elements build from it (the strain-displacement matrix) and
//! `E = (H + H^T)/2`, so `S_v` is the Cauchy stress of linear elasticity
//! and the element drops its geometric stiffness.
//!
//! One function serves every element of a dimension, so the same `F`
//! gives every element type the same stress bits (a homogeneous
//! deformation gives each element its `F` up to the rounding of its
//! reference gradients: exact for a triangle or tetrahedron with dyadic
//! coordinates, not at the quadrilateral's and hexahedron's Gauss points,
//! `1/sqrt 3` being irrational). Every sum starts
//! from its first term and runs in index order, so in 2D the operations
//! are exactly those of the two-dimensional formulas written out.

use super::material::Kinematics;

/// The tensor index pairs `(i, j)` of the Voigt components in `D = 2`
/// dimensions: `[11, 22, 12]`.
pub const VOIGT_2D: [(usize, usize); 3] = [(0, 0), (1, 1), (0, 1)];

/// The tensor index pairs `(i, j)` of the Voigt components in `D = 3`
/// dimensions: `[11, 22, 33, 23, 13, 12]`.
pub const VOIGT_3D: [(usize, usize); 6] = [(0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1)];

/// The Voigt index pairs for `V` components (3 in 2D, 6 in 3D).
pub(crate) const fn voigt<const V: usize>() -> [(usize, usize); V] {
    let mut out = [(0, 0); V];
    let mut r = 0;
    while r < V {
        out[r] = if V == 3 { VOIGT_2D[r] } else { VOIGT_3D[r] };
        r += 1;
    }
    out
}

/// Compile-time check that `D` is 2 or 3, `V` its number of Voigt
/// components and, when given, `M = D N`.
pub(crate) const fn check_dims<const D: usize, const V: usize>(n: usize, m: usize) {
    assert!(
        (D == 2 && V == 3) || (D == 3 && V == 6),
        "D must be 2 or 3 and V = D(D+1)/2"
    );
    assert!(m == D * n, "an element of N nodes has D N dofs");
}

/// The symmetric `D x D` tensor of the Voigt vector `v` (stress
/// components, no engineering factor).
pub(crate) fn tensor<const D: usize, const V: usize>(v: &[f64; V]) -> [[f64; D]; D] {
    let pairs = voigt::<V>();
    let mut t = [[0.0; D]; D];
    for (r, &(i, j)) in pairs.iter().enumerate() {
        t[i][j] = v[r];
        t[j][i] = v[r];
    }
    t
}

/// The determinant of a `2 x 2` or `3 x 3` matrix.
pub(crate) fn det<const D: usize>(m: &[[f64; D]; D]) -> f64 {
    const { assert!(D == 2 || D == 3, "D must be 2 or 3") };
    if D == 2 {
        m[0][0] * m[1][1] - m[0][1] * m[1][0]
    } else {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    }
}

/// The displacement gradient `H = du/dX = sum_a u_a G_a^T` at a point
/// with reference gradients `grads` of `N` nodes and displacements `u`
/// (`D N` values), summed node by node from zero.
pub(crate) fn displacement_gradient<const D: usize, const N: usize>(
    grads: &[[f64; D]; N],
    u: &[f64],
) -> [[f64; D]; D] {
    let u = &u[..D * N];
    let mut h = [[0.0; D]; D];
    for a in 0..N {
        for i in 0..D {
            for j in 0..D {
                h[i][j] += u[D * a + i] * grads[a][j];
            }
        }
    }
    h
}

/// Deformation gradient, strain and stress at one point.
pub(crate) struct PointState<const D: usize, const V: usize> {
    /// `F = I + H` (`I` with small kinematics).
    pub(crate) f: [[f64; D]; D],
    /// The strain, Voigt with engineering shear.
    pub(crate) e_v: [f64; V],
    /// The stress `D E_v` (second Piola–Kirchhoff; Cauchy with small
    /// kinematics).
    pub(crate) s_v: [f64; V],
}

/// The state at a point with reference gradients `grads` of `N` nodes and
/// displacements `u` (`D N` values), for the material matrix `d` and the
/// strain measure `kinematics`.
pub(crate) fn point_state<const D: usize, const V: usize, const N: usize>(
    grads: &[[f64; D]; N],
    u: &[f64],
    d: &[[f64; V]; V],
    kinematics: Kinematics,
) -> PointState<D, V> {
    const { check_dims::<D, V>(N, D * N) };
    let pairs = voigt::<V>();
    // F = I + H
    let h = displacement_gradient(grads, u);
    if kinematics == Kinematics::Small {
        let e_v = pairs.map(|(i, j)| if i == j { h[i][i] } else { h[i][j] + h[j][i] });
        let f = std::array::from_fn(|i| std::array::from_fn(|j| if i == j { 1.0 } else { 0.0 }));
        return PointState {
            f,
            e_v,
            s_v: stress(d, &e_v),
        };
    }
    let f = std::array::from_fn(|i| {
        std::array::from_fn(|j| if i == j { 1.0 + h[i][j] } else { h[i][j] })
    });
    // E = (H + H^T + H^T H)/2, without the cancellation of F^T F - I
    let hh = |j: usize, k: usize| {
        let mut s = h[0][j] * h[0][k];
        for i in 1..D {
            s += h[i][j] * h[i][k];
        }
        s
    };
    let e_v = pairs.map(|(i, j)| {
        if i == j {
            h[i][i] + hh(i, i) / 2.0
        } else {
            h[i][j] + h[j][i] + hh(i, j)
        }
    });
    PointState {
        f,
        e_v,
        s_v: stress(d, &e_v),
    }
}

/// `S_v = D E_v`.
fn stress<const V: usize>(d: &[[f64; V]; V], e_v: &[f64; V]) -> [f64; V] {
    std::array::from_fn(|r| dot(&d[r], e_v))
}

/// `a . b`, summed in index order from the first term.
pub(crate) fn dot<const V: usize>(a: &[f64; V], b: &[f64; V]) -> f64 {
    let mut s = a[0] * b[0];
    for t in 1..V {
        s += a[t] * b[t];
    }
    s
}

#[cfg(test)]
mod tests {
    use crate::element::SolidElement;
    use crate::element::material::{Kinematics, Material, PlaneModel};
    use crate::element::quad::QuadGeometry;
    use crate::element::tri::TriGeometry;
    use crate::testutil::Lcg;

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
                |u| qg.energy(u, &SMALL),
                |u| {
                    let r = qg.response(u, &SMALL);
                    (r.f_int, r.k)
                },
            );
            let r = qg.response(&u, &SMALL);
            let r0 = qg.response(&[0.0; 8], &SMALL);
            assert_eq!(r.k, r0.k, "the Q4 tangent depends on u");
            for p in 0..8 {
                let ku: f64 = (0..8).map(|q| r.k[p][q] * u[q]).sum();
                assert!((ku - r.f_int[p]).abs() < 1e-10 * r.f_int[p].abs().max(1.0));
            }

            let u: [f64; 6] = std::array::from_fn(|_| rng.uniform(-0.2, 0.2));
            check_derivatives(
                u,
                |u| tg.energy(u, &SMALL),
                |u| {
                    let r = tg.response(u, &SMALL);
                    (r.f_int, r.k)
                },
            );
            let r = tg.response(&u, &SMALL);
            let r0 = tg.response(&[0.0; 6], &SMALL);
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
        let k_small = qg.response(&[0.0; 8], &SMALL).k;
        let k_finite = qg.response(&[0.0; 8], &finite).k;
        assert_eq!(k_small, k_finite);
        let dir: [f64; 8] = [0.3, -0.1, 0.2, 0.4, -0.2, 0.1, 0.05, -0.3];
        let diff = |s: f64| {
            let u = dir.map(|d| s * d);
            let a = qg.response(&u, &SMALL).f_int;
            let b = qg.response(&u, &finite).f_int;
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
        assert!(tg.energy(&u, &SMALL) > 1e-3);
        let finite = Material {
            kinematics: Kinematics::Finite,
            ..SMALL
        };
        assert!(tg.energy(&u, &finite).abs() < 1e-12);
    }
}
