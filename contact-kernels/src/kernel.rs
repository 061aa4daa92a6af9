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
//! ## Parametric coordinates
//!
//! `xi_s` is passed as any [`XiArg`] (`f64`, `[f64; N]`, `&[f64]`, ...) of
//! the kernel's parametric dimension [`Kernel::param_dim`] (1 for
//! segments, 2 for faces); another length is
//! [`KernelError::ParamCount`]. The projection comes back as a slice of the
//! same length ([`GapOut::xi_m_all`]); [`GapOut::xi_m`] is its first
//! component (for a segment, the projection). See [`crate::param`].
//!
//! [`Kernel::eval_batch`] runs the same steps over many points into a
//! [`GapBatch`] (structure of arrays: all gaps, then all gradients, then all
//! Hessians), with one status per point: a point that fails (degenerate
//! segment, no projection) does not stop the others, as the solver treats
//! failures per point. A failed point's entries are zero and its accessors
//! return its error, never stale or NaN values. It evaluates 4 points per
//! call of the lane kernels (`batch.rs`, one driver for segments and
//! faces over their parametric dimension, `param_kernel.rs`; AVX2 when the
//! CPU has it), with the same results and errors as [`Kernel::eval`] point
//! by point.

use crate::generated::{self, KernelSet, face_kernel_set, kernel_set};
use crate::generated_lanes::{
    self, FaceLaneKernel, FaceSlipLaneKernel, LaneIsa, LaneKernel, LaneSet, SlipLaneKernel,
    face_lane_set, face_slip_lane_set, lane_set, slip_lane_set,
};
use crate::param::{Xi, XiArg};
use crate::{ApproxType, Formulation, KernelError, OpCount};
use param_kernel::eval_point;

/// The generated kernel of one (formulation, approximation type).
#[derive(Clone, Copy)]
pub struct Kernel {
    formulation: Formulation,
    ty: ApproxType,
    imp: Imp,
}

/// A kernel of segments (2D, with lane kernels for the batch) or of faces
/// (3D).
#[derive(Clone, Copy)]
enum Imp {
    Segments(Segments),
    Faces(Faces),
}

/// A segment kernel: its set, the scalar kernel and the lane kernel, and
/// the slip's (when the formulation has one).
#[derive(Clone, Copy)]
pub(crate) struct Segments {
    set: &'static KernelSet,
    kernel: generated::Kernel,
    slip: Option<generated::SlipKernel>,
    lane_set: &'static LaneSet,
    lanes: LaneKernel,
    slip_lane_set: Option<&'static LaneSet<SlipLaneKernel>>,
    slip_lanes: Option<SlipLaneKernel>,
    lane_isa: LaneIsa,
}

/// A face kernel: its set, the scalar kernel and the lane kernel, and the
/// slip's (when the formulation has one; one lane function per component,
/// compiled for AVX2 only: `None` on the portable build).
#[derive(Clone, Copy)]
pub(crate) struct Faces {
    set: &'static generated::FaceKernelSet,
    kernel: generated::FaceKernel,
    slip: Option<generated::FaceSlipKernel>,
    lane_set: &'static LaneSet<FaceLaneKernel>,
    lanes: FaceLaneKernel,
    slip_lane_set: Option<&'static LaneSet<Option<FaceSlipLaneKernel>>>,
    slip_lanes: Option<FaceSlipLaneKernel>,
    lane_isa: LaneIsa,
}

/// The slip lane kernel of type `ty` in `set`, for the instruction set
/// [`generated_lanes::select`] chooses (the gap's lane kernel's: both
/// follow the same rule).
fn select_slip<K: Copy>(set: Option<&LaneSet<K>>, ty: usize, isa: LaneIsa) -> Option<K> {
    set.map(|s| generated_lanes::select(s, ty, isa).0)
}

mod batch;
mod param_kernel;
mod slip;
mod slip_batch;

pub use slip::{Slip, SlipOut};
pub use slip_batch::SlipBatch;

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
    pub(crate) gap: f64,
    pub(crate) xi_m: Xi,
    pub(crate) has_hessian: bool,
    pub(crate) grad: Vec<f64>,
    pub(crate) hess: Vec<f64>,
    pub(crate) scratch: Vec<f64>,
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
            xi_m: Xi::scalar(0.0),
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

    /// The master parametric coordinate of the projection: for a segment
    /// the projection, for a face its first component `u` (all of it:
    /// [`GapOut::xi_m_all`]).
    pub fn xi_m(&self) -> f64 {
        self.xi_m.first()
    }

    /// The master parametric coordinates of the projection
    /// ([`Kernel::param_dim`] of them: `[xi_m]` for a segment, `[u, v]` for
    /// a face).
    pub fn xi_m_all(&self) -> &[f64] {
        self.xi_m.as_slice()
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

/// Outputs of [`Kernel::eval_batch`] for `len` points, structure of
/// arrays: point `p`'s gap is `gaps()[p]`, its projection
/// `xi_ms()[p k..(p + 1) k]` (`k` = [`Kernel::param_dim`]), its gradient
/// `grads()[p n..(p + 1) n]`, its Hessian `hessians()[p n n..(p + 1) n n]`
/// (row-major, full), `n` the kernel's coordinate count. Reuse one batch
/// for every call: it grows to the largest batch and never shrinks.
#[derive(Debug, Clone, PartialEq)]
pub struct GapBatch {
    coords: usize,
    param_dim: usize,
    len: usize,
    has_hessian: bool,
    gap: Vec<f64>,
    xi_m: Vec<f64>,
    grad: Vec<f64>,
    hess: Vec<f64>,
    status: Vec<Option<KernelError>>,
    scratch: Vec<f64>,
    lanes: batch::LaneBuffers,
}

impl GapBatch {
    /// An empty batch for `kernel`'s coordinate count.
    pub fn new(kernel: &Kernel) -> GapBatch {
        GapBatch {
            coords: kernel.coords(),
            param_dim: kernel.param_dim(),
            len: 0,
            has_hessian: false,
            gap: Vec::new(),
            xi_m: Vec::new(),
            grad: Vec::new(),
            hess: Vec::new(),
            status: Vec::new(),
            scratch: vec![0.0; kernel.coords()],
            lanes: batch::LaneBuffers::new(kernel.coords()),
        }
    }

    /// Points of the last call.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether the last call had no point.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Coordinates per point.
    pub fn coords(&self) -> usize {
        self.coords
    }

    /// Point `p`'s outcome.
    pub fn status(&self, p: usize) -> Result<(), &KernelError> {
        match &self.status[..self.len][p] {
            None => Ok(()),
            Some(e) => Err(e),
        }
    }

    /// Point `p`'s gap and `xi_m` (for a face: its first component; all
    /// of it: [`GapBatch::xi_m`]).
    pub fn gap(&self, p: usize) -> Result<(f64, f64), &KernelError> {
        let k = self.param_dim;
        self.status(p).map(|()| (self.gap[p], self.xi_m[p * k]))
    }

    /// Point `p`'s projection ([`Kernel::param_dim`] values).
    pub fn xi_m(&self, p: usize) -> Result<&[f64], &KernelError> {
        let k = self.param_dim;
        self.status(p).map(|()| &self.xi_m[p * k..(p + 1) * k])
    }

    /// All projections, point after point ([`Kernel::param_dim`] values
    /// each; zero at failed points).
    pub fn xi_ms(&self) -> &[f64] {
        &self.xi_m[..self.len * self.param_dim]
    }

    /// Point `p`'s gradient.
    pub fn grad(&self, p: usize) -> Result<&[f64], &KernelError> {
        let n = self.coords;
        self.status(p).map(|()| &self.grad[p * n..(p + 1) * n])
    }

    /// Point `p`'s Hessian (`None` for a gradient-only type).
    pub fn hess(&self, p: usize) -> Result<Option<&[f64]>, &KernelError> {
        let nn = self.coords * self.coords;
        self.status(p)
            .map(|()| self.has_hessian.then(|| &self.hess[p * nn..(p + 1) * nn]))
    }

    /// All gaps (zero at failed points).
    pub fn gaps(&self) -> &[f64] {
        &self.gap[..self.len]
    }

    /// All gradients, point after point (zero at failed points).
    pub fn grads(&self) -> &[f64] {
        &self.grad[..self.len * self.coords]
    }

    /// All Hessians, point after point (`None` for a gradient-only type).
    pub fn hessians(&self) -> Option<&[f64]> {
        let nn = self.coords * self.coords;
        self.has_hessian.then(|| &self.hess[..self.len * nn])
    }

    /// Sizes the buffers for `len` points of a kernel with or without a
    /// Hessian.
    fn prepare(&mut self, len: usize, has_hessian: bool) {
        let n = self.coords;
        self.len = len;
        self.has_hessian = has_hessian;
        if self.gap.len() < len {
            self.gap.resize(len, 0.0);
            self.xi_m.resize(len * self.param_dim, 0.0);
            self.grad.resize(len * n, 0.0);
            self.status.resize(len, None);
        }
        if has_hessian && self.hess.len() < len * n * n {
            self.hess.resize(len * n * n, 0.0);
        }
    }
}

impl Kernel {
    /// The kernel of `(formulation, ty)`, or [`KernelError::NotCompiled`].
    pub fn new(formulation: Formulation, ty: ApproxType) -> Result<Kernel, KernelError> {
        if let Some(set) = face_kernel_set(formulation) {
            let lane_set =
                face_lane_set(formulation).ok_or(KernelError::NotCompiled(formulation))?;
            let (lanes, lane_isa) = generated_lanes::select(lane_set, ty.index(), LaneIsa::Avx2);
            let slip_lane_set = face_slip_lane_set(formulation);
            return Ok(Kernel {
                formulation,
                ty,
                imp: Imp::Faces(Faces {
                    set,
                    kernel: set.kernels[ty.index() - 1],
                    slip: set.slip.as_ref().map(|s| s.kernels[ty.index() - 1]),
                    lane_set,
                    lanes,
                    slip_lane_set,
                    slip_lanes: select_slip(slip_lane_set, ty.index(), LaneIsa::Avx2).flatten(),
                    lane_isa,
                }),
            });
        }
        let set = kernel_set(formulation).ok_or(KernelError::NotCompiled(formulation))?;
        let lane_set = lane_set(formulation).ok_or(KernelError::NotCompiled(formulation))?;
        let (lanes, lane_isa) = generated_lanes::select(lane_set, ty.index(), LaneIsa::Avx2);
        let slip_lane_set = slip_lane_set(formulation);
        Ok(Kernel {
            formulation,
            ty,
            imp: Imp::Segments(Segments {
                set,
                kernel: set.kernels[ty.index() - 1],
                slip: set.slip.as_ref().map(|s| s.kernels[ty.index() - 1]),
                lane_set,
                lanes,
                slip_lane_set,
                slip_lanes: select_slip(slip_lane_set, ty.index(), LaneIsa::Avx2),
                lane_isa,
            }),
        })
    }

    /// The instruction set of the lane kernel [`Kernel::eval_batch`] runs:
    /// AVX2 when the CPU has it, unless [`Kernel::with_lane_isa`] chose
    /// the portable one.
    pub fn lane_isa(&self) -> LaneIsa {
        match &self.imp {
            Imp::Segments(s) => s.lane_isa,
            Imp::Faces(f) => f.lane_isa,
        }
    }

    /// This kernel with [`Kernel::eval_batch`] running the lane kernel
    /// compiled for `isa` (the portable one when `isa` is AVX2 and the CPU
    /// lacks it). Results do not depend on the choice.
    pub fn with_lane_isa(self, isa: LaneIsa) -> Kernel {
        match self.imp {
            Imp::Segments(s) => {
                let (lanes, lane_isa) = generated_lanes::select(s.lane_set, self.ty.index(), isa);
                Kernel {
                    imp: Imp::Segments(Segments {
                        lanes,
                        slip_lanes: select_slip(s.slip_lane_set, self.ty.index(), isa),
                        lane_isa,
                        ..s
                    }),
                    ..self
                }
            }
            Imp::Faces(f) => {
                let (lanes, lane_isa) = generated_lanes::select(f.lane_set, self.ty.index(), isa);
                Kernel {
                    imp: Imp::Faces(Faces {
                        lanes,
                        slip_lanes: select_slip(f.slip_lane_set, self.ty.index(), isa).flatten(),
                        lane_isa,
                        ..f
                    }),
                    ..self
                }
            }
        }
    }

    /// Whether [`Slip::eval_batch`] of this kernel's slip runs lane
    /// kernels, four points at a time, at this kernel's [`LaneIsa`]
    /// (`false`: it evaluates point by point, or the formulation has no
    /// slip). Faces have slip lane kernels only for AVX2.
    pub fn has_slip_lanes(&self) -> bool {
        match &self.imp {
            Imp::Segments(s) => s.slip_lanes.is_some(),
            Imp::Faces(f) => f.slip_lanes.is_some(),
        }
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
        match &self.imp {
            Imp::Segments(s) => s.set.coords,
            Imp::Faces(f) => f.set.coords,
        }
    }

    /// The parametric dimension of the faces: how many values `xi_s` has
    /// and `xi_m` reports (1 for segments, 2 for tri3 and quad4 faces).
    pub fn param_dim(&self) -> usize {
        match &self.imp {
            Imp::Segments(_) => 1,
            Imp::Faces(_) => 2,
        }
    }

    /// Whether the kernel computes a second-order term.
    pub fn has_hessian(&self) -> bool {
        match &self.imp {
            Imp::Segments(s) => s.has_hessian(),
            Imp::Faces(f) => matches!(f.kernel, generated::FaceKernel::Hessian(_)),
        }
    }

    /// The generated kernel's operation count.
    pub fn op_count(&self) -> OpCount {
        let ops = match &self.imp {
            Imp::Segments(s) => &s.set.ops,
            Imp::Faces(f) => &f.set.ops,
        };
        ops[self.ty.index() - 1]
    }

    /// Evaluates the gap and its derivatives at configuration `q` (`n`
    /// coordinates, [`KernelError::CoordinateCount`] otherwise) and slave
    /// point `xi_s` ([`Kernel::param_dim`] values: `0.3` for a segment,
    /// `[0.2, -0.1]` for a face; [`KernelError::ParamCount`] otherwise) into
    /// `out` (sized for `n` coordinates, [`KernelError::BufferSize`]
    /// otherwise).
    pub fn eval(&self, q: &[f64], xi_s: impl XiArg, out: &mut GapOut) -> Result<(), KernelError> {
        if out.coords() != self.coords() {
            return Err(KernelError::BufferSize {
                expected: self.coords(),
                found: out.coords(),
            });
        }
        match &self.imp {
            Imp::Segments(s) => {
                let xi_s = param(xi_s.as_xi())?;
                let (gap, [xi_m]) =
                    eval_point(s, q, xi_s, &mut out.scratch, &mut out.grad, &mut out.hess)?;
                out.gap = gap;
                out.xi_m = Xi::scalar(xi_m);
            }
            Imp::Faces(f) => {
                let xi_s = param(xi_s.as_xi())?;
                let (gap, xi_m) =
                    eval_point(f, q, xi_s, &mut out.scratch, &mut out.grad, &mut out.hess)?;
                out.gap = gap;
                out.xi_m = Xi::pair(xi_m);
            }
        }
        out.has_hessian = self.has_hessian();
        Ok(())
    }

    /// Evaluates the points `p = 0..xi_s.len() / k` (`k` =
    /// [`Kernel::param_dim`]), point `p` with the coordinates
    /// `qs[p n..(p + 1) n]` and the slave point `xi_s[p k..(p + 1) k]`, into
    /// `out`; returns how many succeeded. Each point gives the bits
    /// [`Kernel::eval`] gives it (and its error), though 4 points are
    /// evaluated per call of the lane kernel ([`Kernel::lane_isa`]).
    /// Fails only when the shapes disagree: `xi_s.len()`
    /// is not a multiple of `k` ([`KernelError::ParamCount`]), `qs.len()`
    /// is not `n` times the point count ([`KernelError::CoordinateCount`])
    /// or `out` was made for another kernel's sizes
    /// ([`KernelError::BufferSize`]).
    pub fn eval_batch(
        &self,
        qs: &[f64],
        xi_s: &[f64],
        out: &mut GapBatch,
    ) -> Result<usize, KernelError> {
        let n = self.coords();
        if out.coords != n || out.param_dim != self.param_dim() {
            return Err(KernelError::BufferSize {
                expected: n,
                found: out.coords,
            });
        }
        if !xi_s.len().is_multiple_of(self.param_dim()) {
            return Err(KernelError::ParamCount {
                expected: self.param_dim(),
                found: xi_s.len(),
            });
        }
        let points = xi_s.len() / self.param_dim();
        if qs.len() != n * points {
            return Err(KernelError::CoordinateCount {
                expected: n * points,
                found: qs.len(),
            });
        }
        out.prepare(points, self.has_hessian());
        Ok(match &self.imp {
            Imp::Segments(s) => batch::eval_lanes(s, qs, xi_s, out),
            Imp::Faces(f) => batch::eval_lanes(f, qs, xi_s, out),
        })
    }

    /// [`eval_point`] for a segment kernel (the value API's path);
    /// a face kernel reports [`KernelError::ParamCount`] (it takes two).
    #[inline]
    pub(crate) fn eval_into(
        &self,
        q: &[f64],
        xi_s: f64,
        d: &mut [f64],
        grad: &mut [f64],
        hess: &mut [f64],
    ) -> Result<(f64, f64), KernelError> {
        match &self.imp {
            Imp::Segments(s) => eval_point(s, q, [xi_s], d, grad, hess).map(|(g, [x])| (g, x)),
            Imp::Faces(_) => Err(KernelError::ParamCount {
                expected: 2,
                found: 1,
            }),
        }
    }
}

impl Segments {
    /// Whether the kernel computes a second-order term.
    #[inline(always)]
    pub(crate) fn has_hessian(&self) -> bool {
        matches!(self.kernel, generated::Kernel::Hessian(_))
    }
}

/// `xi_s` checked against the parametric dimension `P`.
#[inline(always)]
fn param<const P: usize>(xi_s: &[f64]) -> Result<[f64; P], KernelError> {
    xi_s.try_into().map_err(|_| KernelError::ParamCount {
        expected: P,
        found: xi_s.len(),
    })
}
