//! Kernels given at run time: a formulation that is not compiled in (a
//! user's formulation file, run by an interpreter of its generated
//! programs) evaluated through exactly the steps of [`Kernel::eval`]:
//! the validation of `validate.rs` (coordinate count, finite input,
//! degenerate and folded segments, relative coordinates), the projection
//! of `projection.rs` (closed form in the kernel, or Newton's method on the
//! residual from `xi = 0`; out-of-reach and non-finite projections
//! refused) and the rejection of non-finite outputs.
//!
//! [`Kernel::eval`]: crate::Kernel::eval

use crate::validate::{all_finite, relative_coordinates_n};
use crate::{ApproxType, GapOut, KernelError, OutputKind, projection};

/// A formulation's kernels supplied at run time, with the generated
/// kernels' calling convention (relative coordinates `d`).
pub trait RuntimeKernels {
    /// The coordinate count `n` (8 for two-node segment pairs, 12 for
    /// 3-node ones).
    fn coords(&self) -> usize;
    /// Whether the kernels solve the projection in closed form (then the
    /// `xi_m` they receive is ignored and they write the one they used).
    fn closed_form_projection(&self) -> bool;
    /// `[r, dr/dxi]` of the projection at `xi`.
    fn residual(&self, d: &[f64], xi_s: f64, xi: f64) -> [f64; 2];
    /// Whether type `ty` has a second-order term.
    fn has_hessian(&self, ty: ApproxType) -> bool;
    /// Runs type `ty`: returns the gap, writes `grad` (`n`) and, for a type
    /// with a Hessian, `hess` (`n * n`, full and symmetric); `xi_m` is the
    /// converged projection on input and the one used on output.
    fn eval(
        &self,
        ty: ApproxType,
        d: &[f64],
        xi_s: f64,
        xi_m: &mut f64,
        grad: &mut [f64],
        hess: &mut [f64],
    ) -> f64;
}

/// Evaluates type `ty` of `kernels` at `q` and `xi_s` into `out` as
/// [`crate::Kernel::eval`] evaluates a compiled formulation: the same
/// checks in the same order, the same errors.
pub fn eval_runtime(
    kernels: &dyn RuntimeKernels,
    ty: ApproxType,
    q: &[f64],
    xi_s: f64,
    out: &mut GapOut,
) -> Result<(), KernelError> {
    let n = kernels.coords();
    if out.coords() != n {
        return Err(KernelError::BufferSize {
            expected: n,
            found: out.coords(),
        });
    }
    relative_coordinates_n(n, q, xi_s, &mut out.scratch)?;
    let d = &out.scratch;
    let residual = |d: &[f64], xi_s: f64, xi: f64| kernels.residual(d, xi_s, xi);
    let mut xi_m = if kernels.closed_form_projection() {
        0.0
    } else {
        projection::solve(residual, d, xi_s)?
    };
    let has_hessian = kernels.has_hessian(ty);
    let gap = kernels.eval(ty, d, xi_s, &mut xi_m, &mut out.grad, &mut out.hess);
    projection::check_with(residual, d, xi_s, xi_m)?;
    let finite_hess = !has_hessian || all_finite(&out.hess);
    if !(gap.is_finite() && all_finite(&out.grad) && finite_hess) {
        let output = if !gap.is_finite() {
            OutputKind::Gap
        } else if !all_finite(&out.grad) {
            OutputKind::Gradient
        } else {
            OutputKind::Hessian
        };
        return Err(KernelError::NonFiniteOutput { output, xi_m });
    }
    out.gap = gap;
    out.xi_m = crate::param::Xi::scalar(xi_m);
    out.has_hessian = has_hessian;
    Ok(())
}
