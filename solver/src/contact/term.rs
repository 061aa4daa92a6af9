//! What the assembly, the active set and the frozen Taylor expansion need
//! of a contact integration point and of its evaluation, in any dimension.
//!
//! A point contributes `w J0 lambda(xi_s) g` to the potential, with
//! `lambda(xi_s) = sum_a N_a(xi_s) l_a` over the multipliers at its slave
//! face's nodes ([`WeightedPoint`]: `w J0` and the pairs `(l_a, N_a)`). Its
//! evaluation gives `g`, `g'` and `g''` on the `N` coordinates of the
//! point's slave and master nodes, each coordinate with its degree of
//! freedom ([`GapTerm`]). 2D segments ([`super::ContactPoint`],
//! [`super::PointEval`]: two slave multipliers, `N = 8`) and 3D faces
//! ([`super::FacePoint`], [`super::FaceEval`]: three or four slave
//! multipliers, `N = 24` with the coordinates a pair of smaller faces does
//! not have as padding) implement both, so that one assembly, one active
//! set and one expansion serve both dimensions.
//!
//! Invariants: `multiplier_shape` lists `count <= MAX_POINT_MULTIPLIERS`
//! entries, in the slave face's node order; a padding coordinate has no
//! dof and exactly zero gradient and Hessian entries; sums over the
//! multipliers start with the first term (so two-node segments sum
//! exactly as `N_1 l_1 + N_2 l_2`).

use nalgebra::{SMatrix, SVector};

use crate::ids::{DofId, MultiplierIndex};

/// The most multipliers one point's slave face carries (a quad4's four
/// nodes).
pub const MAX_POINT_MULTIPLIERS: usize = 4;

/// The coordinates of the largest 3D face pair (a quad4 on a quad4: 8
/// nodes of 3): the size of a [`super::FaceEval`]'s gradient and Hessian.
pub const FACE_COORDS: usize = 24;

/// A point's slave face multipliers `l_a` with their shape values
/// `N_a(xi_s)`: `count` entries (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MultiplierShape {
    /// The multipliers at the slave face's nodes, in node order.
    pub multipliers: [MultiplierIndex; MAX_POINT_MULTIPLIERS],
    /// `N_a(xi_s)`, in the same order.
    pub shape: [f64; MAX_POINT_MULTIPLIERS],
    /// How many entries are used.
    pub count: usize,
}

impl MultiplierShape {
    /// `lambda(xi_s) = sum_a N_a l_a` (summed from the first entry).
    pub fn lambda(&self, lambda: &[f64]) -> f64 {
        let mut lam = self.shape[0] * lambda[self.multipliers[0].index()];
        for a in 1..self.count {
            lam += self.shape[a] * lambda[self.multipliers[a].index()];
        }
        lam
    }

    /// The used `(l_a, N_a)` pairs.
    pub fn iter(&self) -> impl Iterator<Item = (MultiplierIndex, f64)> + '_ {
        (0..self.count).map(|a| (self.multipliers[a], self.shape[a]))
    }
}

/// The slip of one point and its derivatives on the evaluation's `N`
/// coordinates (2D: one component, along the tangent of
/// docs/conventions.md, "The slip"; [`super::friction`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlipTerm<const N: usize> {
    /// The slip `s` since the last converged state.
    pub slip: f64,
    /// `ds/du` on the `N` coordinates.
    pub grad: SVector<f64, N>,
    /// `d2s/du2`, `None` when the kernel's type has none.
    pub hess: Option<SMatrix<f64, N, N>>,
}

/// A point's slip as the friction sees it ([`super::friction`]): its
/// components `s_c` with their derivatives, and the tangential directions
/// of its slave nodes' multipliers in those components (the multiplier
/// `t_ak` of node `a` acts along `d_ak`, the point's slip along it is
/// `d_ak . s`). 2D ([`SlipTerm`]): one component, along the tangent, every
/// direction `[1]`; 3D ([`super::FaceSlip`]): the three global components
/// and each node's two tangents.
pub trait PointSlip<const N: usize>: Clone + std::fmt::Debug {
    /// The number of components (1 or 3).
    fn components(&self) -> usize;
    /// Component `c`'s value.
    fn value(&self, c: usize) -> f64;
    /// Component `c`'s gradient.
    fn grad(&self, c: usize) -> &SVector<f64, N>;
    /// Component `c`'s Hessian, `None` when the kernel's type has none.
    fn hess(&self, c: usize) -> Option<&SMatrix<f64, N, N>>;
    /// Direction `k` of the multipliers of the slave node at entry `j` of
    /// the point's [`MultiplierShape`], in the components (the unused ones
    /// zero).
    fn direction(&self, j: usize, k: usize) -> [f64; 3];
    /// The second-order expansion by the displacement increment `d` of the
    /// coordinates (each component as the gap is, [`super::Taylor`]).
    fn expanded(&self, d: &SVector<f64, N>) -> Self;
}

impl<const N: usize> PointSlip<N> for SlipTerm<N> {
    fn components(&self) -> usize {
        1
    }

    fn value(&self, _c: usize) -> f64 {
        self.slip
    }

    fn grad(&self, _c: usize) -> &SVector<f64, N> {
        &self.grad
    }

    fn hess(&self, _c: usize) -> Option<&SMatrix<f64, N, N>> {
        self.hess.as_ref()
    }

    fn direction(&self, _j: usize, _k: usize) -> [f64; 3] {
        [1.0, 0.0, 0.0]
    }

    fn expanded(&self, d: &SVector<f64, N>) -> SlipTerm<N> {
        let (slip, grad) = expand_value(self.slip, &self.grad, self.hess.as_ref(), d);
        SlipTerm {
            slip,
            grad,
            hess: self.hess,
        }
    }
}

/// `f0 + f'0 . d + 1/2 d . f''0 d` and its gradient `f'0 + f''0 d`.
pub fn expand_value<const N: usize>(
    f0: f64,
    grad: &SVector<f64, N>,
    hess: Option<&SMatrix<f64, N, N>>,
    d: &SVector<f64, N>,
) -> (f64, SVector<f64, N>) {
    match hess {
        Some(h) => {
            let hd = h * d;
            (f0 + grad.dot(d) + 0.5 * d.dot(&hd), grad + hd)
        }
        None => (f0 + grad.dot(d), *grad),
    }
}

/// An integration point as the assembly and the active set see it.
pub trait WeightedPoint {
    /// `w J0`: the rule's weight times the slave face's reference Jacobian.
    fn weight_ref(&self) -> f64;
    /// The multipliers of the point's slave face and their shape values
    /// at the point.
    fn multiplier_shape(&self) -> MultiplierShape;
}

/// A point's evaluation on `N` coordinates as the assembly and the Taylor
/// expansion see it.
pub trait GapTerm<const N: usize>: Clone {
    /// The point's slip ([`PointSlip`]).
    type Slip: PointSlip<N>;
    /// The gap (exact or Taylor-approximated).
    fn gap(&self) -> f64;
    /// `dg/du` on the `N` coordinates.
    fn grad(&self) -> &SVector<f64, N>;
    /// `d2g/du2`, `None` when the type has none (Type 1).
    fn hess(&self) -> Option<&SMatrix<f64, N, N>>;
    /// The degree of freedom of coordinate `k`; `None` for a padding slot.
    fn dof(&self, k: usize) -> Option<DofId>;
    /// The same evaluation with gap `gap`, gradient `grad` and slip `slip`
    /// (the Hessians kept): the Taylor expansion's value at another
    /// displacement.
    fn with_values(&self, gap: f64, grad: SVector<f64, N>, slip: Option<Self::Slip>) -> Self;
    /// The point's slip, when its pair has friction and the slip was
    /// evaluated (default: none; [`super::friction`]).
    fn slip(&self) -> Option<&Self::Slip> {
        None
    }
}
