//! The slip handle: the tangential slip of one (formulation, approximation
//! type) and its kept derivatives, evaluated into buffers the caller owns.
//!
//! The slip (docs/conventions.md, "The slip") is the motion of the master
//! point the slave point faces since the last converged state, where it
//! faced `xi_m0`: `s_m = x_m(xi_m) - x_m(xi_m0)` with the current master
//! coordinates, in the tangent plane of the formulation's normal `n`. A
//! segment pair has one component (along `(-n.y, n.x)`), a face pair three
//! (the global components of `s_m - (n . s_m) n`). Its first and second
//! derivatives are truncated by the type as the gap's are (`s_m` takes the
//! `x_ms` column of the truncation table).
//!
//! ```
//! use contact_kernels::{ApproxType, Formulation, Kernel, SlipOut};
//!
//! let kernel = Kernel::new(Formulation::SlaveNormal, ApproxType::Type6)?;
//! let slip = kernel.slip().expect("slave-normal defines a slip");
//! let mut out = SlipOut::new(&slip);
//! let q = [0.0, 1.0, 2.0, 1.1, 2.1, 0.9, -0.1, 1.0];
//! // At the projection itself the master point has not moved.
//! let xi_m = -0.278587699316629;
//! slip.eval(&q, 0.3, xi_m, &mut out)?;
//! assert!(out.slip()[0].abs() < 1e-12);
//! assert_eq!(out.grad(0).len(), 8);
//! # Ok::<(), contact_kernels::KernelError>(())
//! ```
//!
//! ## Invariants
//!
//! * [`Slip::eval`] runs [`crate::Kernel::eval`]'s steps in its order
//!   (validation, projection start, kernel, projection check, finite
//!   outputs), `xi_m0` checked finite after `q` and `xi_s` (its component
//!   `k` reported as [`KernelError::NonFinite`] at index `n + P + k`, `P`
//!   the parametric dimension); on `Ok` every value in the [`SlipOut`] is
//!   finite and belongs to this call; on `Err` its contents are
//!   unspecified.

use super::param_kernel::{SlipBuffers, slip_point};
use super::{Imp, Kernel, param};
use crate::generated;
use crate::param::{Xi, XiArg};
use crate::{KernelError, OpCount};

/// The slip kernel of one (formulation, approximation type): made by
/// [`Kernel::slip`] when the formulation defines a slip.
#[derive(Debug, Clone, Copy)]
pub struct Slip {
    kernel: Kernel,
}

/// The outputs of [`Slip::eval`], in buffers sized once and reused.
#[derive(Debug, Clone, PartialEq)]
pub struct SlipOut {
    components: usize,
    coords: usize,
    slip: [f64; 3],
    xi_m: Xi,
    has_hessian: bool,
    grad: Vec<f64>,
    hess: Vec<f64>,
    scratch: Vec<f64>,
}

impl SlipOut {
    /// Buffers for `slip` (and every slip kernel with as many coordinates
    /// and components).
    pub fn new(slip: &Slip) -> SlipOut {
        let (c, n) = (slip.components(), slip.kernel.coords());
        SlipOut {
            components: c,
            coords: n,
            slip: [0.0; 3],
            xi_m: Xi::scalar(0.0),
            has_hessian: false,
            grad: vec![0.0; c * n],
            hess: vec![0.0; c * n * n],
            scratch: vec![0.0; n],
        }
    }

    /// The slip's components: one for a segment pair (along the tangent),
    /// three for a face pair (global `x`, `y`, `z`).
    pub fn slip(&self) -> &[f64] {
        &self.slip[..self.components]
    }

    /// The projection the slip was evaluated at ([`Kernel::param_dim`]
    /// values).
    pub fn xi_m_all(&self) -> &[f64] {
        self.xi_m.as_slice()
    }

    /// Component `c`'s gradient as the type keeps it (`n` entries).
    ///
    /// # Panics
    /// If `c` is not below the component count.
    pub fn grad(&self, c: usize) -> &[f64] {
        assert!(
            c < self.components,
            "the slip has {} components",
            self.components
        );
        &self.grad[c * self.coords..(c + 1) * self.coords]
    }

    /// Component `c`'s symmetric Hessian as the type keeps it (`n * n`
    /// entries, row-major); `None` after a kernel without second-order
    /// term.
    ///
    /// # Panics
    /// If `c` is not below the component count.
    pub fn hess(&self, c: usize) -> Option<&[f64]> {
        assert!(
            c < self.components,
            "the slip has {} components",
            self.components
        );
        let nn = self.coords * self.coords;
        self.has_hessian.then(|| &self.hess[c * nn..(c + 1) * nn])
    }
}

impl Kernel {
    /// The slip kernel of this (formulation, type), or `None` when the
    /// formulation defines no slip.
    pub fn slip(&self) -> Option<Slip> {
        let has = match &self.imp {
            Imp::Segments(s) => s.slip.is_some(),
            Imp::Faces(f) => f.slip.is_some(),
        };
        has.then_some(Slip { kernel: *self })
    }
}

impl Slip {
    /// The gap kernel of the same (formulation, type).
    pub fn kernel(&self) -> &Kernel {
        &self.kernel
    }

    /// The slip's components: 1 for segments, 3 for faces.
    pub fn components(&self) -> usize {
        match self.kernel.imp {
            Imp::Segments(_) => 1,
            Imp::Faces(_) => 3,
        }
    }

    /// Whether the slip kernel computes a second-order term.
    pub fn has_hessian(&self) -> bool {
        match &self.kernel.imp {
            Imp::Segments(s) => matches!(s.slip, Some(generated::SlipKernel::Hessian(_))),
            Imp::Faces(f) => matches!(f.slip, Some(generated::FaceSlipKernel::Hessian(_))),
        }
    }

    /// The generated slip kernel's operation count.
    pub fn op_count(&self) -> OpCount {
        let t = self.kernel.ty().index() - 1;
        let ops = match &self.kernel.imp {
            Imp::Segments(s) => s.set.slip.as_ref().map(|s| s.ops[t]),
            Imp::Faces(f) => f.set.slip.as_ref().map(|s| s.ops[t]),
        };
        ops.expect("a Slip exists only for a formulation with a slip")
    }

    /// Evaluates the slip and its derivatives at configuration `q`, slave
    /// point `xi_s` and last converged projection `xi_m0` (both
    /// [`Kernel::param_dim`] values) into `out` (made for this slip's sizes,
    /// [`KernelError::BufferSize`] otherwise). The errors are
    /// [`Kernel::eval`]'s, and a non-finite `xi_m0`.
    pub fn eval(
        &self,
        q: &[f64],
        xi_s: impl XiArg,
        xi_m0: impl XiArg,
        out: &mut SlipOut,
    ) -> Result<(), KernelError> {
        let (c, n) = (self.components(), self.kernel.coords());
        if out.coords != n || out.components != c {
            return Err(KernelError::BufferSize {
                expected: n,
                found: out.coords,
            });
        }
        let SlipOut {
            slip,
            grad,
            hess,
            scratch,
            ..
        } = out;
        let buffers = SlipBuffers { slip, grad, hess };
        let (xi_m, hessian) = match &self.kernel.imp {
            Imp::Segments(s) => {
                let (xi_s, xi_m0) = (param(xi_s.as_xi())?, param(xi_m0.as_xi())?);
                slip_point(s, q, xi_s, xi_m0, scratch, buffers, c)
                    .map(|([x], h)| (Xi::scalar(x), h))?
            }
            Imp::Faces(f) => {
                let (xi_s, xi_m0) = (param(xi_s.as_xi())?, param(xi_m0.as_xi())?);
                slip_point(f, q, xi_s, xi_m0, scratch, buffers, c).map(|(x, h)| (Xi::pair(x), h))?
            }
        };
        out.xi_m = xi_m;
        out.has_hessian = hessian;
        Ok(())
    }
}
