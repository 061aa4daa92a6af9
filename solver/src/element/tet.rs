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
//! [`super::geometry`]'s floor), i.e. positively oriented and not flat
//! beyond rounding.

use super::ElementKind;
use super::geometry::{Geometry, Shape, simplex_point};

/// The 4-node tetrahedron's parent tetrahedron and one-point rule.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tet4;

impl Shape<3, 4, 1> for Tet4 {
    const KIND: ElementKind = ElementKind::Tet4;

    fn point(x_ref: &[[f64; 3]; 4], _: usize) -> (f64, Option<[[f64; 3]; 4]>) {
        simplex_point(x_ref)
    }

    /// `V0 = detJ0 / 6`.
    fn weight(det_j0: f64) -> f64 {
        det_j0 / 6.0
    }
}

/// The reference geometry of one tetrahedron (constant gradients, the
/// weight `V0`), computed once per mesh.
pub type TetGeometry = Geometry<Tet4, 3, 4, 12, 6, 1>;
