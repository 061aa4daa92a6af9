//! The isoparametric reference geometry of every element, written once for
//! the quadrilateral, triangle, hexahedron and tetrahedron: the reference
//! gradients and weights at the integration points, the degeneracy test,
//! and the element's response summed over its points.
//!
//! An element of `N` nodes in `D` dimensions maps its parent element onto
//! the reference coordinates `X`; at each of its `P` integration points
//!
//! ```text
//! J0      = sum_a X_a (dN_a/dxi)^T        (reference Jacobian)
//! G_a     = dN_a/dX = J0^-T dN_a/dxi       (reference gradients)
//! weight  = w_p detJ0
//! ```
//!
//! Its kind ([`Shape`]) gives the parent gradients, the rule and the
//! weights. The bilinear and trilinear elements are integrated by Gauss
//! rules of unit weights (2x2, 2x2x2) and form `J0` as the sum above
//! ([`gauss_point`]); the linear triangle and tetrahedron have constant
//! gradients, one point of weight `1/2` or `1/6` (the parent simplex's
//! measure), and `J0`'s columns `X_{k+1} - X_1` ([`simplex_point`]), whose
//! rows of `J0^-1` are `G_2 .. G_{D+1}` and `G_1 = -(G_2 + .. + G_{D+1})`.
//!
//! An element is admissible when its coordinates are finite and
//! `detJ0 > MIN_RELATIVE_DET l^D` at every point ([`min_det`]; `l` the
//! longest edge of [`ElementKind::edges`]): positive, and not flat beyond
//! rounding (the rounding error of `detJ0` is about `2 eps l^D`, so a
//! collapsed element leaves a `detJ0` of that order, of either sign). The
//! mesh readers test their cells against the same floor.
//!
//! Over the points, `f_int`, `K` and `U` are the sums of
//! [`super::solid`]'s integrand in point order; the stresses are the
//! points', their mean [`Stress::mean`].

use std::fmt;
use std::marker::PhantomData;

use super::kinematics::{check_dims, det, displacement_gradient};
use super::material::Material;
use super::solid::{SolidResponse, add_point, point_energy, point_stress};
use super::stress::Stress;
use super::{ElementKind, InvalidElement, SolidElement};

/// The smallest admissible `detJ0 / l^D` (`l` the longest reference edge):
/// below it the element's measure is at the level of the rounding error
/// of `detJ0` (about `2 eps l^D`), i.e. its nodes are collinear (2D) or
/// coplanar (3D) as far as the arithmetic can tell. A triangle passes when
/// its smallest angle is above about `1e-14` rad.
pub const MIN_RELATIVE_DET: f64 = 16.0 * f64::EPSILON;

/// The floor `MIN_RELATIVE_DET l^D` of an element of kind `kind` with
/// node coordinates `x` (`l` its longest edge); `detJ0` must exceed it.
pub fn min_det<const D: usize>(kind: ElementKind, x: &[[f64; D]]) -> f64 {
    let l2_max = kind
        .edges()
        .iter()
        .map(|&[a, b]| {
            let mut l2 = 0.0;
            for i in 0..D {
                let e = x[b][i] - x[a][i];
                l2 += e * e;
            }
            l2
        })
        .fold(0.0_f64, f64::max);
    if D == 2 {
        MIN_RELATIVE_DET * l2_max
    } else {
        MIN_RELATIVE_DET * l2_max * l2_max.sqrt()
    }
}

/// One element kind's parent element: its integration rule and the map of
/// its parent onto the reference coordinates.
pub trait Shape<const D: usize, const N: usize, const P: usize>:
    Sized + Copy + PartialEq + fmt::Debug
{
    /// The kind (`KIND.node_count() == N`, `KIND.dim() == D`).
    const KIND: ElementKind;

    /// `detJ0` at integration point `p` of the element with reference
    /// coordinates `x_ref`, and its reference gradients `G_a` when `detJ0`
    /// is positive.
    fn point(x_ref: &[[f64; D]; N], p: usize) -> (f64, Option<[[f64; D]; N]>);

    /// The weight `w_p detJ0` of a point.
    fn weight(det_j0: f64) -> f64;
}

/// The inverse of the `D x D` matrix `m` of determinant `det` (adjugate
/// over determinant).
fn inverse<const D: usize>(m: &[[f64; D]; D], det: f64) -> [[f64; D]; D] {
    const { assert!(D == 2 || D == 3, "D must be 2 or 3") };
    let mut inv = [[0.0; D]; D];
    if D == 2 {
        inv[0][0] = m[1][1] / det;
        inv[0][1] = -m[0][1] / det;
        inv[1][0] = -m[1][0] / det;
        inv[1][1] = m[0][0] / det;
    } else {
        let c = |i: usize, j: usize| {
            let (i1, i2) = ((i + 1) % 3, (i + 2) % 3);
            let (j1, j2) = ((j + 1) % 3, (j + 2) % 3);
            m[i1][j1] * m[i2][j2] - m[i1][j2] * m[i2][j1]
        };
        // inv[i][j] = cofactor(j, i) / det
        for (i, row) in inv.iter_mut().enumerate() {
            for (j, v) in row.iter_mut().enumerate() {
                *v = c(j, i) / det;
            }
        }
    }
    inv
}

/// `detJ0` and `G_a = J0^-T dN_a/dxi` at a point of the parent gradients
/// `dn`, `J0 = sum_a X_a dn_a^T` (`None` when `detJ0` is not positive).
pub(crate) fn gauss_point<const D: usize, const N: usize>(
    x_ref: &[[f64; D]; N],
    dn: &[[f64; D]; N],
) -> (f64, Option<[[f64; D]; N]>) {
    let mut j = [[0.0; D]; D];
    for a in 0..N {
        for i in 0..D {
            for k in 0..D {
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
        std::array::from_fn(|c| {
            let mut v = dn[a][0] * inv[0][c];
            for k in 1..D {
                v += dn[a][k] * inv[k][c];
            }
            v
        })
    });
    (d, Some(g))
}

/// `detJ0` and the constant `G_a` of a linear simplex (`N = D + 1`):
/// `J0`'s columns are `X_{k+1} - X_1`, `G_{k+1}` row `k` of `J0^-1` and
/// `G_1 = -(G_2 + .. + G_N)` (`None` when `detJ0` is not positive).
pub(crate) fn simplex_point<const D: usize, const N: usize>(
    x_ref: &[[f64; D]; N],
) -> (f64, Option<[[f64; D]; N]>) {
    const { assert!(N == D + 1, "a linear simplex has D + 1 nodes") };
    // J[i][k] = X_{k+2}[i] - X_1[i]
    let j: [[f64; D]; D] =
        std::array::from_fn(|i| std::array::from_fn(|k| x_ref[k + 1][i] - x_ref[0][i]));
    let d = det(&j);
    if !(d > 0.0) {
        return (d, None);
    }
    let inv = inverse(&j, d);
    let mut g = [[0.0; D]; N];
    g[1..].copy_from_slice(&inv);
    for i in 0..D {
        let mut s = g[1][i];
        for row in &g[2..] {
            s += row[i];
        }
        g[0][i] = -s;
    }
    (d, Some(g))
}

/// The reference geometry of one element of shape `S` (`D` dimensions,
/// `N` nodes, `M = D N` dofs, `V` Voigt components, `P` integration
/// points), computed once per mesh.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Geometry<
    S,
    const D: usize,
    const N: usize,
    const M: usize,
    const V: usize,
    const P: usize,
> {
    /// `G_a = dN_a/dX` per integration point and node.
    pub grads_ref: [[[f64; D]; N]; P],
    /// `w_p detJ0` per integration point (the reference measure's weight).
    pub weight_ref: [f64; P],
    shape: PhantomData<S>,
}

impl<S, const D: usize, const N: usize, const M: usize, const V: usize, const P: usize>
    Geometry<S, D, N, M, V, P>
where
    S: Shape<D, N, P>,
{
    /// Geometry of the element with reference node coordinates `x_ref`
    /// (counter-clockwise in 2D, Gmsh's order in 3D). Fails when a
    /// coordinate is not finite (`det_j0` NaN) or when `detJ0 <= min_det`
    /// at a point (inverted, degenerate or badly distorted element;
    /// `det_j0` the smallest, NaN once one overflows).
    pub fn new(x_ref: &[[f64; D]; N]) -> Result<Self, InvalidElement> {
        const { check_dims::<D, V>(N, M) };
        if x_ref.iter().flatten().any(|v| !v.is_finite()) {
            return Err(InvalidElement { det_j0: f64::NAN });
        }
        let mut grads_ref = [[[0.0; D]; N]; P];
        let mut weight_ref = [0.0; P];
        let mut worst = f64::INFINITY;
        for p in 0..P {
            let (d, g) = S::point(x_ref, p);
            worst = if d.is_nan() || worst.is_nan() {
                f64::NAN
            } else {
                worst.min(d)
            };
            if let Some(g) = g {
                grads_ref[p] = g;
                weight_ref[p] = S::weight(d);
            }
        }
        if !(worst.is_finite() && worst > min_det(S::KIND, x_ref)) {
            return Err(InvalidElement { det_j0: worst });
        }
        Ok(Geometry {
            grads_ref,
            weight_ref,
            shape: PhantomData,
        })
    }
}

impl<S, const D: usize, const N: usize, const M: usize, const V: usize, const P: usize>
    SolidElement<D, N, M, V> for Geometry<S, D, N, M, V, P>
where
    S: Shape<D, N, P>,
{
    const KIND: ElementKind = S::KIND;

    fn from_reference(x_ref: &[[f64; D]; N]) -> Result<Self, InvalidElement> {
        Self::new(x_ref)
    }

    /// `sum_p w_p detJ0` (one point: its weight).
    fn measure_ref(&self) -> f64 {
        match self.weight_ref.as_slice() {
            [w] => *w,
            w => w.iter().sum(),
        }
    }

    /// The sums start at `0.0` for a rule of several points, at `-0.0`
    /// for one point (`-0.0 + x` is `x` to the bit: the point's values).
    fn response(&self, u: &[f64; M], material: &Material) -> SolidResponse<M> {
        let d = material.elasticity::<V>();
        let mut out = SolidResponse::starting_at(if P == 1 { -0.0 } else { 0.0 });
        for p in 0..P {
            add_point(
                &mut out,
                &self.grads_ref[p],
                self.weight_ref[p],
                u,
                &d,
                material,
            );
        }
        out.symmetrize();
        out
    }

    fn energy(&self, u: &[f64; M], material: &Material) -> f64 {
        let d = material.elasticity::<V>();
        let e = |p: usize| point_energy(&self.grads_ref[p], self.weight_ref[p], u, &d, material);
        if P == 1 { e(0) } else { (0..P).map(&e).sum() }
    }

    fn point_stresses(&self, u: &[f64; M], material: &Material) -> Vec<Stress<V>> {
        let d = material.elasticity::<V>();
        (0..P)
            .map(|p| point_stress(&self.grads_ref[p], u, &d, material))
            .collect()
    }

    fn mean_stress(&self, u: &[f64; M], material: &Material) -> Stress<V> {
        Stress::mean(&self.point_stresses(u, material))
    }

    /// `det(I + H)` at each point ([`displacement_gradient`]), the
    /// smallest (NaN as soon as one is NaN).
    fn min_det_f(&self, u: &[f64; M]) -> f64 {
        let mut worst = f64::INFINITY;
        for grads in &self.grads_ref {
            let mut f = displacement_gradient(grads, u);
            for (i, row) in f.iter_mut().enumerate() {
                row[i] += 1.0;
            }
            let d = det(&f);
            if d.is_nan() {
                return f64::NAN;
            }
            worst = worst.min(d);
        }
        worst
    }
}
