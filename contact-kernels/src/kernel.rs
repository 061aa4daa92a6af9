//! The kernel handle: one (formulation, approximation type), evaluated into
//! buffers the caller owns.
//!
//! ```
//! use contact_kernels::{ApproxType, Formulation, GapOut, Kernel};
//!
//! let kernel = Kernel::new(Formulation::SlaveNormal, ApproxType::Type6)?;
//! let mut out = GapOut::new(&kernel); // allocate once, reuse for every point
//! let q = [0.0, 1.0, 2.0, 1.1, 2.1, 0.9, -0.1, 1.0];
//! kernel.eval(&q, 0.3, &mut out)?;
//! assert!((out.gap() - 0.129090446096668).abs() < 1e-12);
//! let hess = out.hess().expect("Type 6 has a Hessian");
//! assert!((hess[0] - 0.00046515059696).abs() < 1e-12);
//! # Ok::<(), contact_kernels::KernelError>(())
//! ```
//!
//! ## Invariants
//!
//! * [`Kernel::eval`] validates once ([`crate::validate`]), solves or
//!   checks the projection ([`crate::projection`]), runs the generated
//!   kernel and rejects non-finite outputs; on `Ok` every value in the
//!   [`GapOut`] is finite and belongs to this call.
//! * On `Err` the contents of the [`GapOut`] are unspecified.
//! * A [`GapOut`] holds `n` gradient entries and `n * n` Hessian entries
//!   (the full symmetric matrix, row-major — equal to column-major), plus
//!   `n` scratch values for the relative coordinates; it fits every kernel
//!   with `n` coordinates.
//!
//! A batched call (#9) fits beside [`Kernel::eval`]: the generated
//! functions and the validation already work on slices, so
//! `eval_batch(&self, qs: &[f64], xi_s: &[f64], out: &mut GapBatch)` is the
//! same steps over `qs.chunks_exact(n)` into structure-of-arrays buffers
//! (one status per point, as the solver treats failures per point).

use crate::generated::{self, KernelSet, kernel_set};
use crate::validate::{all_finite, relative_coordinates};
use crate::{ApproxType, Formulation, KernelError, OpCount, OutputKind, projection};

/// The generated kernel of one (formulation, approximation type).
#[derive(Clone, Copy)]
pub struct Kernel {
    formulation: Formulation,
    ty: ApproxType,
    set: &'static KernelSet,
    kernel: generated::Kernel,
}

impl std::fmt::Debug for Kernel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Kernel")
            .field("formulation", &self.formulation)
            .field("ty", &self.ty)
            .field("coords", &self.coords())
            .field("has_hessian", &self.has_hessian())
            .finish()
    }
}

/// The outputs of [`Kernel::eval`], in buffers sized once and reused.
#[derive(Debug, Clone, PartialEq)]
pub struct GapOut {
    gap: f64,
    xi_m: f64,
    has_hessian: bool,
    grad: Vec<f64>,
    hess: Vec<f64>,
    scratch: Vec<f64>,
}

impl GapOut {
    /// Buffers for `kernel` (and every other kernel with as many
    /// coordinates).
    pub fn new(kernel: &Kernel) -> GapOut {
        GapOut::with_coords(kernel.coords())
    }

    /// Buffers for kernels of `n` coordinates.
    pub fn with_coords(n: usize) -> GapOut {
        GapOut {
            gap: 0.0,
            xi_m: 0.0,
            has_hessian: false,
            grad: vec![0.0; n],
            hess: vec![0.0; n * n],
            scratch: vec![0.0; n],
        }
    }

    /// The coordinate count the buffers are sized for.
    pub fn coords(&self) -> usize {
        self.grad.len()
    }

    /// The gap `g = n . x_ms` (negative when penetrating).
    pub fn gap(&self) -> f64 {
        self.gap
    }

    /// The master parametric coordinate of the projection.
    pub fn xi_m(&self) -> f64 {
        self.xi_m
    }

    /// `dg/dq` as the type keeps it (`n` entries).
    pub fn grad(&self) -> &[f64] {
        &self.grad
    }

    /// The symmetric `d2g/dq2` as the type keeps it (`n * n` entries,
    /// row-major); `None` after a kernel without second-order term (Type 1).
    pub fn hess(&self) -> Option<&[f64]> {
        self.has_hessian.then_some(&self.hess[..])
    }
}

impl Kernel {
    /// The kernel of `(formulation, ty)`, or [`KernelError::NotCompiled`].
    pub fn new(formulation: Formulation, ty: ApproxType) -> Result<Kernel, KernelError> {
        let set = kernel_set(formulation).ok_or(KernelError::NotCompiled(formulation))?;
        Ok(Kernel {
            formulation,
            ty,
            set,
            kernel: set.kernels[ty.index() - 1],
        })
    }

    /// The formulation.
    pub fn formulation(&self) -> Formulation {
        self.formulation
    }

    /// The approximation type.
    pub fn ty(&self) -> ApproxType {
        self.ty
    }

    /// The coordinate count `n` every `q` must have.
    pub fn coords(&self) -> usize {
        self.set.coords
    }

    /// Whether the kernel computes a second-order term.
    pub fn has_hessian(&self) -> bool {
        matches!(self.kernel, generated::Kernel::Hessian(_))
    }

    /// The generated kernel's operation count.
    pub fn op_count(&self) -> OpCount {
        self.set.ops[self.ty.index() - 1]
    }

    /// Evaluates the gap and its derivatives at configuration `q` (`n`
    /// coordinates, [`KernelError::CoordinateCount`] otherwise) and slave
    /// parameter `xi_s` into `out` (sized for `n` coordinates,
    /// [`KernelError::BufferSize`] otherwise).
    pub fn eval(&self, q: &[f64], xi_s: f64, out: &mut GapOut) -> Result<(), KernelError> {
        if out.coords() != self.coords() {
            return Err(KernelError::BufferSize {
                expected: self.coords(),
                found: out.coords(),
            });
        }
        let (gap, xi_m) =
            self.eval_into(q, xi_s, &mut out.scratch, &mut out.grad, &mut out.hess)?;
        out.gap = gap;
        out.xi_m = xi_m;
        out.has_hessian = self.has_hessian();
        Ok(())
    }

    /// The evaluation on raw buffers: `d` (scratch), `grad` of `n` and
    /// `hess` of `n * n` values (untouched without second-order term), sized
    /// by the caller. Returns `(gap, xi_m)`.
    #[inline]
    pub(crate) fn eval_into(
        &self,
        q: &[f64],
        xi_s: f64,
        d: &mut [f64],
        grad: &mut [f64],
        hess: &mut [f64],
    ) -> Result<(f64, f64), KernelError> {
        let set = self.set;
        relative_coordinates(set, q, xi_s, d)?;
        let mut xi_m = projection::start(set, d, xi_s)?;
        let (gap, finite) = match self.kernel {
            generated::Kernel::Gradient(k) => {
                let gap = k(d, xi_s, &mut xi_m, grad);
                (gap, all_finite(grad))
            }
            generated::Kernel::Hessian(k) => {
                let gap = k(d, xi_s, &mut xi_m, grad, hess);
                (gap, all_finite(grad) & all_finite(hess))
            }
        };
        projection::check(set, d, xi_s, xi_m)?;
        if !(finite && gap.is_finite()) {
            // Cold path: name the first non-finite output.
            let output = if !gap.is_finite() {
                OutputKind::Gap
            } else if !all_finite(grad) {
                OutputKind::Gradient
            } else {
                OutputKind::Hessian
            };
            return Err(KernelError::NonFiniteOutput { output, xi_m });
        }
        Ok((gap, xi_m))
    }
}
