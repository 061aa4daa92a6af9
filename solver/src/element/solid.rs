//! The integrand of every total-Lagrangian solid element, written once for
//! `D = 2` and `3` dimensions: one integration point's contribution to the
//! internal force, the tangent (`B^T D B` and the geometric stiffness) and
//! the strain energy, and its stresses. An element supplies its reference
//! gradients and weights per point ([`super::quad`], [`super::tri`],
//! [`super::hex`], [`super::tet`]).
//!
//! At a point with reference gradients `G_a`, weight `w = w_gp detJ0` and
//! the state of [`super::kinematics`]:
//!
//! ```text
//! B       : dE_v/du, column D a + i, row r of the Voigt pair (j, k):
//!           F_ij G_aj                  (j = k)
//!           F_ij G_ak + F_ik G_aj      (j != k)
//! f_int  += w B^T S_v
//! K      += w (B^T D B + (G_a . S G_b) I_D)     (no geometric term with
//!                                                small kinematics)
//! U      += w 1/2 E_v . S_v
//! ```
//!
//! `K` is the exact derivative of `f_int` (the geometric term is the
//! derivative of `B^T` at fixed `S`), and `f_int` the exact gradient of `U`.
//! Only the upper triangle of `K` is summed; `SolidResponse::symmetrize`
//! mirrors it once every point is in.

use super::kinematics::{PointState, check_dims, det, dot, point_state, tensor, voigt};
use super::material::Material;
use super::stress::Stress;

/// Internal force, tangent stiffness and strain energy of one element of
/// `M` dofs (ordered `[u1x, u1y, (u1z,) u2x, ...]`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolidResponse<const M: usize> {
    /// `f_int`.
    pub f_int: [f64; M],
    /// The symmetric tangent `d f_int / d u`.
    pub k: [[f64; M]; M],
    /// The strain energy `U`.
    pub energy: f64,
}

impl<const M: usize> SolidResponse<M> {
    /// Every sum starting at `start`: `0.0` for a rule of several points
    /// (the Q4's sums as they were written), `-0.0` for a one-point rule
    /// (`-0.0 + x` is `x` to the bit, so its sums are the point's values,
    /// as the triangle assigned them).
    pub(crate) fn starting_at(start: f64) -> SolidResponse<M> {
        SolidResponse {
            f_int: [start; M],
            k: [[start; M]; M],
            energy: start,
        }
    }

    /// Copies the upper triangle of `k` onto the lower one.
    pub(crate) fn symmetrize(&mut self) {
        for p in 0..M {
            for q in 0..p {
                self.k[p][q] = self.k[q][p];
            }
        }
    }
}

/// Adds the point with reference gradients `g` (`N` nodes) and weight `w`
/// at displacements `u` to `out` (the upper triangle of `k`).
pub(crate) fn add_point<const D: usize, const V: usize, const N: usize, const M: usize>(
    out: &mut SolidResponse<M>,
    g: &[[f64; D]; N],
    w: f64,
    u: &[f64; M],
    d: &[[f64; V]; V],
    material: &Material,
) {
    const { check_dims::<D, V>(N, M) };
    let pairs = voigt::<V>();
    let PointState { f, e_v, s_v } = point_state(g, u, d, material.kinematics);
    let mut b = [[0.0; M]; V];
    for a in 0..N {
        for i in 0..D {
            for (r, &(j, k)) in pairs.iter().enumerate() {
                b[r][D * a + i] = if j == k {
                    f[i][j] * g[a][j]
                } else {
                    f[i][j] * g[a][k] + f[i][k] * g[a][j]
                };
            }
        }
    }
    out.energy += w * 0.5 * dot(&e_v, &s_v);
    // D B (V x M)
    let mut db = [[0.0; M]; V];
    for r in 0..V {
        for c in 0..M {
            let mut v = d[r][0] * b[0][c];
            for t in 1..V {
                v += d[r][t] * b[t][c];
            }
            db[r][c] = v;
        }
    }
    for p in 0..M {
        let mut fp = b[0][p] * s_v[0];
        for t in 1..V {
            fp += b[t][p] * s_v[t];
        }
        out.f_int[p] += w * fp;
        for q in p..M {
            let mut v = b[0][p] * db[0][q];
            for t in 1..V {
                v += b[t][p] * db[t][q];
            }
            out.k[p][q] += w * v;
        }
    }
    if material.kinematics.geometric_stiffness() {
        let s = tensor::<D, V>(&s_v);
        for a in 0..N {
            for bn in a..N {
                let sg: [f64; D] = std::array::from_fn(|i| {
                    let mut v = s[i][0] * g[bn][0];
                    for j in 1..D {
                        v += s[i][j] * g[bn][j];
                    }
                    v
                });
                let mut gsg = g[a][0] * sg[0];
                for i in 1..D {
                    gsg += g[a][i] * sg[i];
                }
                let geo = w * gsg;
                for i in 0..D {
                    out.k[D * a + i][D * bn + i] += geo;
                }
            }
        }
    }
}

/// The strain energy `w 1/2 E_v . S_v` of one point.
pub(crate) fn point_energy<const D: usize, const V: usize, const N: usize>(
    g: &[[f64; D]; N],
    w: f64,
    u: &[f64],
    d: &[[f64; V]; V],
    material: &Material,
) -> f64 {
    let s = point_state(g, u, d, material.kinematics);
    w * 0.5 * dot(&s.e_v, &s.s_v)
}

/// The stresses at one point: `S_v`, the Cauchy stress
/// `F S F^T / det F` and the strain with tensor shear.
pub(crate) fn point_stress<const D: usize, const V: usize, const N: usize>(
    g: &[[f64; D]; N],
    u: &[f64],
    d: &[[f64; V]; V],
    material: &Material,
) -> Stress<V> {
    let pairs = voigt::<V>();
    let PointState { f, e_v, s_v } = point_state(g, u, d, material.kinematics);
    let s = tensor::<D, V>(&s_v);
    let det_f = det(&f);
    let mut sigma = [[0.0; D]; D];
    for i in 0..D {
        for j in 0..D {
            let mut v = 0.0;
            for k in 0..D {
                for l in 0..D {
                    v += f[i][k] * s[k][l] * f[j][l];
                }
            }
            sigma[i][j] = v / det_f;
        }
    }
    Stress {
        pk2: s_v,
        cauchy: pairs.map(|(i, j)| sigma[i][j]),
        green: std::array::from_fn(|r| {
            let (i, j) = pairs[r];
            if i == j { e_v[r] } else { e_v[r] / 2.0 }
        }),
    }
}
