//! The frozen Taylor expansion of Types 1–6 (see [`super`], "Types 1–6:
//! Taylor coefficients frozen per load step").
//!
//! The expansion point `u0` is the step start, except for a point that
//! crossed a master node in the step: in the repeated step (see
//! [`crate::newton`], "Re-pairing at the step end") its expansion is that
//! of its new segment taken at an earlier attempt's converged end.
//!
//! Invariant: the expansion is exact for the approximated problem: its
//! gradient is the derivative of its gap and its Hessian that of its
//! gradient, so Newton's tangent is exact within a step.

use nalgebra::SVector;

use super::term::{GapTerm, PointSlip, expand_value};

/// Frozen Taylor coefficients of one integration point for one load step,
/// on the `N` coordinates of its evaluation `E` (a 2D
/// [`super::PointEval`] with `N = 8`, a 3D [`super::FaceEval`] with
/// `N = 24`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Taylor<E, const N: usize> {
    /// The kernel output at the expansion point (the step start, or for a
    /// re-paired point an earlier attempt's end).
    pub at_start: E,
    /// The nodal displacements `u0` of `at_start`'s coordinates at the
    /// expansion point (zero on padding coordinates).
    pub u0: SVector<f64, N>,
}

/// The displacements of `e`'s coordinates in the global vector `u` (zero
/// on padding coordinates).
fn local<E: GapTerm<N>, const N: usize>(e: &E, u: &[f64]) -> SVector<f64, N> {
    SVector::<f64, N>::from_fn(|k, _| e.dof(k).map_or(0.0, |d| u[d.index()]))
}

impl<E: GapTerm<N>, const N: usize> Taylor<E, N> {
    /// The expansion of `at`, the kernel output at the displacements `u`
    /// (global vector): `u0` is `u` at `at`'s coordinates.
    pub fn at(at: E, u: &[f64]) -> Taylor<E, N> {
        Taylor {
            u0: local(&at, u),
            at_start: at,
        }
    }

    /// The second-order expansion at displacements `u` (global vector):
    /// the gap's and, when the point has one, the slip's (the same
    /// expansion of its own coefficients, [`crate::contact::friction`]).
    pub fn expand(&self, u: &[f64]) -> E {
        let s = &self.at_start;
        let d = local(s, u) - self.u0;
        let (gap, grad) = expand_value(s.gap(), s.grad(), s.hess(), &d);
        s.with_values(gap, grad, s.slip().map(|st| st.expanded(&d)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::{PointEval, SegmentTaylor};
    use crate::ids::MasterSegmentIndex;
    use nalgebra::SMatrix;

    #[test]
    fn taylor_expansion_is_quadratic_with_exact_gradient() {
        let h = SMatrix::<f64, 8, 8>::from_fn(|i, j| 0.1 * ((i + j) as f64).sin());
        let h = (h + h.transpose()) * 0.5;
        let at_start = PointEval {
            master: MasterSegmentIndex::new(0),
            nodes: [0, 1, 2, 3].map(crate::ids::NodeId::new),
            gap: 0.2,
            xi_m: 0.1,
            grad: SVector::<f64, 8>::from_fn(|i, _| i as f64 * 0.1 - 0.3),
            hess: Some(h),
            slip: None,
        };
        let u0 = SVector::<f64, 8>::from_fn(|i, _| 0.01 * i as f64);
        let t: SegmentTaylor = Taylor { at_start, u0 };
        let u: Vec<f64> = (0..8)
            .map(|i| 0.01 * i as f64 + 0.02 * (i as f64).cos())
            .collect();
        let e = t.expand(&u);
        let step = 1e-6;
        for k in 0..8 {
            let mut up = u.clone();
            let mut um = u.clone();
            up[k] += step;
            um[k] -= step;
            let fd = (t.expand(&up).gap - t.expand(&um).gap) / (2.0 * step);
            assert!((fd - e.grad[k]).abs() < 1e-9);
        }
        let at0 = t.expand(&u0.iter().copied().collect::<Vec<_>>());
        assert_eq!(at0.gap, 0.2);
    }
}
