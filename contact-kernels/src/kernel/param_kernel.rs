//! The two kinds of kernel over their parametric dimension `P`
//! ([`ParamKernel`]): [`Segments`] (`P = 1`, `xi_s` one value) and
//! [`Faces`] (`P = 2`, `xi_s = (u, v)`), and the evaluation of one point
//! both share ([`eval_point`]): validation, the projection's start, the
//! scalar kernel, the projection's check and the finiteness of the
//! outputs, in that order. The batch driver (`batch.rs`) runs over the same
//! trait.

use super::{Faces, Segments};
use crate::generated::{self, FaceKernel};
use crate::generated_lanes::{
    FaceLaneKernel, FaceSlipLaneKernel, LaneIsa, LaneKernel, SlipLaneKernel,
};
use crate::lanes::{LANES, Lanes};
use crate::validate::{all_finite, relative_coordinates, relative_coordinates_lanes};
use crate::{KernelError, OutputKind, faces, projection};

/// A kernel whose slave and master points have `P` parametric coordinates:
/// the steps of the scalar path and the lane kernel's call.
pub(crate) trait ParamKernel<const P: usize> {
    /// The coordinate count `n`.
    fn coords(&self) -> usize;

    /// The instruction set of the lane kernel.
    fn lane_isa(&self) -> LaneIsa;

    /// The scalar validation: the relative coordinates of `q` into `d`, or
    /// the error of the first check that fails.
    fn relative_coordinates(
        &self,
        q: &[f64],
        xi_s: [f64; P],
        d: &mut [f64],
    ) -> Result<(), KernelError>;

    /// The projection the kernel starts from (solved by Newton where the
    /// kernels do not solve it in closed form).
    fn start(&self, d: &[f64], xi_s: [f64; P]) -> Result<[f64; P], KernelError>;

    /// Rejects a projection the kernel could not find or that lies out of
    /// reach.
    fn check(&self, d: &[f64], xi_s: [f64; P], xi_m: [f64; P]) -> Result<(), KernelError>;

    /// The scalar kernel: the gap, `grad`, and `hess` when the kernel has a
    /// second-order term (the second value: whether it has).
    fn run(
        &self,
        d: &[f64],
        xi_s: [f64; P],
        xi_m: &mut [f64; P],
        grad: &mut [f64],
        hess: &mut [f64],
    ) -> (f64, bool);

    /// The slip kernel (if the formulation has a slip): its components
    /// into `slip`, `grad` (`c n`: component after component) and `hess`
    /// (`c n n`, when the kernel has a second-order term: the second value).
    /// `None` without a slip.
    fn run_slip(
        &self,
        d: &[f64],
        xi_s: [f64; P],
        xi_m0: [f64; P],
        xi_m: &mut [f64; P],
        out: SlipBuffers<'_>,
    ) -> Option<bool>;

    /// The lane validation of a group whose coordinates `d` holds (a lane
    /// the lanes cannot decide alone is `false`: the scalar path validates
    /// it again), and whether the projection of a passing lane must still
    /// be started per point. `AVX2`: the caller runs with AVX2 enabled.
    fn validate_lanes<const AVX2: bool>(
        &self,
        qs: &[f64],
        d: &mut [Lanes],
        xi_s: &[Lanes; P],
    ) -> ([bool; LANES], bool);

    /// The lane kernel over the lane buffers; returns the gap and whether
    /// the kernel has a second-order term.
    ///
    /// # Safety
    /// An AVX2 lane kernel may run only on a CPU with AVX2
    /// (`generated_lanes::select` guarantees it); the buffers have the
    /// lengths the kernels reslice to (`n`, `n * n`).
    unsafe fn run_lanes(
        &self,
        d: &[Lanes],
        xi_s: &[Lanes; P],
        xi_m: &mut [Lanes; P],
        grad: &mut [Lanes],
        hess: &mut [Lanes],
    ) -> (Lanes, bool);

    /// The slip's lane kernels over the lane buffers: its components into
    /// `slip` (`c` values), their gradients into `grad` (`c n`) and Hessians
    /// into `hess` (`c n n`), component after component; returns whether it
    /// has a second-order term, `None` without a slip lane kernel.
    ///
    /// # Safety
    /// As [`ParamKernel::run_lanes`] (the buffers: `c`, `c n` and `c n n`).
    unsafe fn run_slip_lanes(
        &self,
        d: &[Lanes],
        xi_s: &[Lanes; P],
        xi_m0: &[Lanes; P],
        xi_m: &mut [Lanes; P],
        out: SlipLaneBuffers<'_>,
    ) -> Option<bool>;

    /// Whether [`ParamKernel::run_slip_lanes`] has a kernel to run.
    fn has_slip_lanes(&self) -> bool;
}

/// The evaluation of one point on raw buffers: `d` (scratch), `grad` of `n`
/// and `hess` of `n * n` values (untouched without second-order term), sized
/// by the caller. Returns `(gap, xi_m)`.
#[inline]
pub(crate) fn eval_point<K: ParamKernel<P>, const P: usize>(
    k: &K,
    q: &[f64],
    xi_s: [f64; P],
    d: &mut [f64],
    grad: &mut [f64],
    hess: &mut [f64],
) -> Result<(f64, [f64; P]), KernelError> {
    k.relative_coordinates(q, xi_s, d)?;
    let mut xi_m = k.start(d, xi_s)?;
    let (gap, hessian) = k.run(d, xi_s, &mut xi_m, grad, hess);
    let finite = if hessian {
        all_finite(grad) & all_finite(hess)
    } else {
        all_finite(grad)
    };
    k.check(d, xi_s, xi_m)?;
    if !(finite && gap.is_finite()) {
        return Err(non_finite(&[gap], OutputKind::Gap, grad, xi_m[0]));
    }
    Ok((gap, xi_m))
}

/// Where a slip kernel writes: its components, gradients (`c n`) and
/// Hessians (`c n n`), each component's run after the previous one's.
pub(crate) struct SlipBuffers<'a> {
    pub(crate) slip: &'a mut [f64; 3],
    pub(crate) grad: &'a mut [f64],
    pub(crate) hess: &'a mut [f64],
}

/// Where the slip's lane kernels write: [`SlipBuffers`] over lanes.
pub(crate) struct SlipLaneBuffers<'a> {
    pub(crate) slip: &'a mut [Lanes],
    pub(crate) grad: &'a mut [Lanes],
    pub(crate) hess: &'a mut [Lanes],
}

/// The slip of one point: the steps of [`eval_point`] (validation,
/// projection start, kernel, projection check, finite outputs) with the
/// slip kernel, `xi_m0` checked finite first (its component `k` reported as
/// index `n + P + k`). Returns `(xi_m, has_hessian)`. The formulation has
/// a slip (the caller's guarantee; [`ParamKernel::run_slip`] returns
/// `None` otherwise, and this panics).
pub(crate) fn slip_point<K: ParamKernel<P>, const P: usize>(
    k: &K,
    q: &[f64],
    xi_s: [f64; P],
    xi_m0: [f64; P],
    d: &mut [f64],
    out: SlipBuffers<'_>,
    components: usize,
) -> Result<([f64; P], bool), KernelError> {
    let mut xi_m = slip_start(k, q, xi_s, xi_m0, d)?;
    let SlipBuffers { slip, grad, hess } = out;
    let hessian = k
        .run_slip(
            d,
            xi_s,
            xi_m0,
            &mut xi_m,
            SlipBuffers {
                slip: &mut *slip,
                grad: &mut *grad,
                hess: &mut *hess,
            },
        )
        .expect("the caller checked that the formulation has a slip");
    k.check(d, xi_s, xi_m)?;
    let n = k.coords();
    let slip = &slip[..components];
    let grad = &grad[..components * n];
    let finite = all_finite(grad) && (!hessian || all_finite(&hess[..components * n * n]));
    if !(finite && all_finite(slip)) {
        return Err(non_finite(slip, OutputKind::Slip, grad, xi_m[0]));
    }
    Ok((xi_m, hessian))
}

/// The steps of a slip's evaluation before its kernel, in
/// [`slip_point`]'s order: the validation (the relative coordinates of `q`
/// into `d`), `xi_m0` finite (its component `k` reported as index
/// `n + P + k`) and the projection's start, which it returns. The one
/// place a slip point is refused before its kernel runs (the batch's too).
#[inline]
pub(crate) fn slip_start<K: ParamKernel<P>, const P: usize>(
    k: &K,
    q: &[f64],
    xi_s: [f64; P],
    xi_m0: [f64; P],
    d: &mut [f64],
) -> Result<[f64; P], KernelError> {
    k.relative_coordinates(q, xi_s, d)?;
    if let Some(c) = xi_m0.iter().position(|x| !x.is_finite()) {
        return Err(KernelError::NonFinite {
            index: q.len() + P + c,
            value: xi_m0[c],
        });
    }
    k.start(d, xi_s)
}

/// The error of a kernel output that is not finite: the first non-finite
/// one, in the order value (`kind`: the gap or the slip), gradient,
/// Hessian (cold path).
#[cold]
fn non_finite(value: &[f64], kind: OutputKind, grad: &[f64], xi_m: f64) -> KernelError {
    let output = if !all_finite(value) {
        kind
    } else if !all_finite(grad) {
        OutputKind::Gradient
    } else {
        OutputKind::Hessian
    };
    KernelError::NonFiniteOutput { output, xi_m }
}

impl ParamKernel<1> for Segments {
    #[inline(always)]
    fn coords(&self) -> usize {
        self.set.coords
    }

    #[inline(always)]
    fn lane_isa(&self) -> LaneIsa {
        self.lane_isa
    }

    #[inline(always)]
    fn relative_coordinates(
        &self,
        q: &[f64],
        [xi_s]: [f64; 1],
        d: &mut [f64],
    ) -> Result<(), KernelError> {
        relative_coordinates(self.set, q, xi_s, d)
    }

    #[inline(always)]
    fn start(&self, d: &[f64], [xi_s]: [f64; 1]) -> Result<[f64; 1], KernelError> {
        projection::start(self.set, d, xi_s).map(|xi_m| [xi_m])
    }

    #[inline(always)]
    fn check(&self, d: &[f64], [xi_s]: [f64; 1], [xi_m]: [f64; 1]) -> Result<(), KernelError> {
        projection::check(self.set, d, xi_s, xi_m)
    }

    #[inline(always)]
    fn run(
        &self,
        d: &[f64],
        [xi_s]: [f64; 1],
        [xi_m]: &mut [f64; 1],
        grad: &mut [f64],
        hess: &mut [f64],
    ) -> (f64, bool) {
        match self.kernel {
            generated::Kernel::Gradient(k) => (k(d, xi_s, xi_m, grad), false),
            generated::Kernel::Hessian(k) => (k(d, xi_s, xi_m, grad, hess), true),
        }
    }

    fn run_slip(
        &self,
        d: &[f64],
        [xi_s]: [f64; 1],
        [xi_m0]: [f64; 1],
        [xi_m]: &mut [f64; 1],
        out: SlipBuffers<'_>,
    ) -> Option<bool> {
        Some(match self.slip? {
            generated::SlipKernel::Gradient(k) => {
                out.slip[0] = k(d, xi_s, xi_m0, xi_m, out.grad);
                false
            }
            generated::SlipKernel::Hessian(k) => {
                out.slip[0] = k(d, xi_s, xi_m0, xi_m, out.grad, out.hess);
                true
            }
        })
    }

    #[inline(always)]
    fn validate_lanes<const AVX2: bool>(
        &self,
        qs: &[f64],
        d: &mut [Lanes],
        [xi_s]: &[Lanes; 1],
    ) -> ([bool; LANES], bool) {
        super::batch::gather::<AVX2>(qs, d);
        (
            relative_coordinates_lanes(d, *xi_s),
            !self.set.closed_form_projection,
        )
    }

    #[inline(always)]
    unsafe fn run_lanes(
        &self,
        d: &[Lanes],
        [xi_s]: &[Lanes; 1],
        [xi_m]: &mut [Lanes; 1],
        grad: &mut [Lanes],
        hess: &mut [Lanes],
    ) -> (Lanes, bool) {
        // SAFETY: the caller's (the trait's contract).
        unsafe {
            match self.lanes {
                LaneKernel::Gradient(f) => (f(d, *xi_s, xi_m, grad), false),
                LaneKernel::Hessian(f) => (f(d, *xi_s, xi_m, grad, hess), true),
            }
        }
    }

    #[inline(always)]
    unsafe fn run_slip_lanes(
        &self,
        d: &[Lanes],
        [xi_s]: &[Lanes; 1],
        [xi_m0]: &[Lanes; 1],
        [xi_m]: &mut [Lanes; 1],
        out: SlipLaneBuffers<'_>,
    ) -> Option<bool> {
        let SlipLaneBuffers { slip, grad, hess } = out;
        // SAFETY: the caller's (the trait's contract).
        unsafe {
            Some(match self.slip_lanes? {
                SlipLaneKernel::Gradient(f) => {
                    slip[0] = f(d, *xi_s, *xi_m0, xi_m, grad);
                    false
                }
                SlipLaneKernel::Hessian(f) => {
                    slip[0] = f(d, *xi_s, *xi_m0, xi_m, grad, hess);
                    true
                }
            })
        }
    }

    #[inline(always)]
    fn has_slip_lanes(&self) -> bool {
        self.slip_lanes.is_some()
    }
}

impl ParamKernel<2> for Faces {
    #[inline(always)]
    fn coords(&self) -> usize {
        self.set.coords
    }

    #[inline(always)]
    fn lane_isa(&self) -> LaneIsa {
        self.lane_isa
    }

    #[inline(always)]
    fn relative_coordinates(
        &self,
        q: &[f64],
        xi_s: [f64; 2],
        d: &mut [f64],
    ) -> Result<(), KernelError> {
        faces::relative_coordinates(self.set, q, xi_s, d)
    }

    #[inline(always)]
    fn start(&self, d: &[f64], xi_s: [f64; 2]) -> Result<[f64; 2], KernelError> {
        faces::start(self.set, d, xi_s)
    }

    #[inline(always)]
    fn check(&self, d: &[f64], xi_s: [f64; 2], xi_m: [f64; 2]) -> Result<(), KernelError> {
        faces::check(self.set, d, xi_s, xi_m)
    }

    #[inline(always)]
    fn run(
        &self,
        d: &[f64],
        xi_s: [f64; 2],
        xi_m: &mut [f64; 2],
        grad: &mut [f64],
        hess: &mut [f64],
    ) -> (f64, bool) {
        match self.kernel {
            FaceKernel::Gradient(k) => (k(d, &xi_s, xi_m, grad), false),
            FaceKernel::Hessian(k) => (k(d, &xi_s, xi_m, grad, hess), true),
        }
    }

    fn run_slip(
        &self,
        d: &[f64],
        xi_s: [f64; 2],
        xi_m0: [f64; 2],
        xi_m: &mut [f64; 2],
        out: SlipBuffers<'_>,
    ) -> Option<bool> {
        let n = self.set.coords;
        let (g0, rest) = out.grad.split_at_mut(n);
        let (g1, g2) = rest.split_at_mut(n);
        Some(match self.slip? {
            generated::FaceSlipKernel::Gradient(k) => {
                *out.slip = k(d, &xi_s, &xi_m0, xi_m, g0, g1, g2);
                false
            }
            generated::FaceSlipKernel::Hessian(k) => {
                let (h0, rest) = out.hess.split_at_mut(n * n);
                let (h1, h2) = rest.split_at_mut(n * n);
                *out.slip = k(d, &xi_s, &xi_m0, xi_m, g0, g1, g2, h0, h1, h2);
                true
            }
        })
    }

    /// Faces have no lane validation: every point is validated, and its
    /// projection started, by the scalar path.
    #[inline(always)]
    fn validate_lanes<const AVX2: bool>(
        &self,
        _qs: &[f64],
        _d: &mut [Lanes],
        _xi_s: &[Lanes; 2],
    ) -> ([bool; LANES], bool) {
        ([false; LANES], true)
    }

    #[inline(always)]
    unsafe fn run_lanes(
        &self,
        d: &[Lanes],
        xi_s: &[Lanes; 2],
        xi_m: &mut [Lanes; 2],
        grad: &mut [Lanes],
        hess: &mut [Lanes],
    ) -> (Lanes, bool) {
        // SAFETY: the caller's (the trait's contract).
        unsafe {
            match self.lanes {
                FaceLaneKernel::Gradient(f) => (f(d, xi_s, xi_m, grad), false),
                FaceLaneKernel::Hessian(f) => (f(d, xi_s, xi_m, grad, hess), true),
            }
        }
    }

    /// One lane function per component, each into its runs of the
    /// buffers. A component whose projection is in closed form writes the
    /// same `xi_m` every time; otherwise each reads the converged one.
    #[inline(always)]
    unsafe fn run_slip_lanes(
        &self,
        d: &[Lanes],
        xi_s: &[Lanes; 2],
        xi_m0: &[Lanes; 2],
        xi_m: &mut [Lanes; 2],
        out: SlipLaneBuffers<'_>,
    ) -> Option<bool> {
        let n = self.set.coords;
        let SlipLaneBuffers { slip, grad, hess } = out;
        // SAFETY: the caller's (the trait's contract).
        unsafe {
            Some(match self.slip_lanes? {
                FaceSlipLaneKernel::Gradient(fs) => {
                    for (j, f) in fs.iter().enumerate() {
                        slip[j] = f(d, xi_s, xi_m0, xi_m, &mut grad[j * n..(j + 1) * n]);
                    }
                    false
                }
                FaceSlipLaneKernel::Hessian(fs) => {
                    let nn = n * n;
                    for (j, f) in fs.iter().enumerate() {
                        slip[j] = f(
                            d,
                            xi_s,
                            xi_m0,
                            xi_m,
                            &mut grad[j * n..(j + 1) * n],
                            &mut hess[j * nn..(j + 1) * nn],
                        );
                    }
                    true
                }
            })
        }
    }

    #[inline(always)]
    fn has_slip_lanes(&self) -> bool {
        self.slip_lanes.is_some()
    }
}
