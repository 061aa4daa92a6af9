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
//! One function serves every element, so a homogeneous deformation gives
//! every element type the same bits.

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
/// displacements `u` (`2 N` values), for the material matrix `d`.
pub(crate) fn point_state<const N: usize>(
    grads: &[[f64; 2]; N],
    u: &[f64],
    d: &[[f64; 3]; 3],
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
    let f = [[1.0 + h[0][0], h[0][1]], [h[1][0], 1.0 + h[1][1]]];
    // E = (H + H^T + H^T H)/2, without the cancellation of F^T F - I
    let hh = |j: usize, k: usize| h[0][j] * h[0][k] + h[1][j] * h[1][k];
    let e_v = [
        h[0][0] + hh(0, 0) / 2.0,
        h[1][1] + hh(1, 1) / 2.0,
        h[0][1] + h[1][0] + hh(0, 1),
    ];
    let mut s_v = [0.0; 3];
    for r in 0..3 {
        s_v[r] = d[r][0] * e_v[0] + d[r][1] * e_v[1] + d[r][2] * e_v[2];
    }
    PointState { f, e_v, s_v }
}
