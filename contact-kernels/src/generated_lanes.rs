//! The lane kernels written by `build.rs` (`OUT_DIR/kernels_lanes.rs`, by
//! `codegen::emit::LanesEmitter` from the same instruction lists as the
//! scalar kernels) and the run-time types they are written against.
//!
//! Every lane kernel evaluates `LANES` (4) points at once: `d` holds the
//! relative coordinates as `n` [`Lanes`] values (coordinate `i` of every
//! point), `xi_s` and `xi_m` one value per point; it stores the gradient
//! into `grad` (`n` values) and, with a second-order term, the full
//! symmetric Hessian into `hess` (`n * n` values, row-major). Lane `l` of
//! every output is bit for bit what the scalar kernel gives point `l`.
//!
//! The kernels of 3D faces take `xi_s` and `xi_m` as two [`Lanes`] each
//! (`face_lane_set`, [`FaceLaneKernel`]). The slip's lane kernels of
//! segments (`slip_lane_set`, [`SlipLaneKernel`]) take the last converged
//! projection `xi_m0` after `xi_s` and return the slip's component; a face
//! slip's (`face_slip_lane_set`, [`FaceSlipLaneKernel`]) are one function
//! per component, compiled for AVX2 only (`codegen::emit::lanes`' module
//! docs say why).
//!
//! Each kernel's body is generic over its value type ([`LaneValue`]) and
//! exists twice: portable, over [`Lanes`], and on x86-64 compiled for AVX2
//! (no FMA) over `Avx4`, one 256-bit register per value, so that every
//! operation is one vector instruction however large the kernel. [`select`] picks the AVX2 copy when the CPU has it
//! (`is_x86_feature_detected!`), once, when a `Kernel` is made.

use crate::generated::Formulation;
#[cfg(target_arch = "x86_64")]
use crate::lanes::Avx4;
use crate::lanes::{LaneValue, Lanes};

/// `(d, xi_s, xi_m, grad) -> g` over lanes.
///
/// `unsafe`: the AVX2 copies may only run on a CPU with AVX2 ([`select`]
/// guarantees it); the portable ones are safe to call.
pub(crate) type LaneGradientFn = unsafe fn(&[Lanes], Lanes, &mut Lanes, &mut [Lanes]) -> Lanes;
/// `(d, xi_s, xi_m, grad, hess) -> g` over lanes (`hess` full); safety as
/// for [`LaneGradientFn`].
pub(crate) type LaneHessianFn =
    unsafe fn(&[Lanes], Lanes, &mut Lanes, &mut [Lanes], &mut [Lanes]) -> Lanes;

/// One approximation type's lane kernel.
#[derive(Clone, Copy)]
pub(crate) enum LaneKernel {
    /// First-order only (Type 1).
    Gradient(LaneGradientFn),
    /// With the second-order term.
    Hessian(LaneHessianFn),
}

/// `(d, xi_s, xi_m, grad) -> g` over lanes for faces: `xi_s` and the
/// in/out `xi_m` are two [`Lanes`] each (`u`, `v` of every point); safety
/// as for [`LaneGradientFn`].
pub(crate) type FaceLaneGradientFn =
    unsafe fn(&[Lanes], &[Lanes], &mut [Lanes], &mut [Lanes]) -> Lanes;
/// `(d, xi_s, xi_m, grad, hess) -> g` over lanes for faces; safety as for
/// [`LaneGradientFn`].
pub(crate) type FaceLaneHessianFn =
    unsafe fn(&[Lanes], &[Lanes], &mut [Lanes], &mut [Lanes], &mut [Lanes]) -> Lanes;

/// One approximation type's lane kernel for faces (made only by the face
/// formulations compiled in: none without the `faces` features).
#[derive(Clone, Copy)]
#[cfg_attr(not(feature = "faces"), allow(dead_code))]
pub(crate) enum FaceLaneKernel {
    /// First-order only (Type 1).
    Gradient(FaceLaneGradientFn),
    /// With the second-order term.
    Hessian(FaceLaneHessianFn),
}

/// `(d, xi_s, xi_m0, xi_m, grad0) -> s` over lanes: a segment pair's slip
/// (one component) with its gradient; safety as for [`LaneGradientFn`].
pub(crate) type SlipLaneGradientFn =
    unsafe fn(&[Lanes], Lanes, Lanes, &mut Lanes, &mut [Lanes]) -> Lanes;
/// `(d, xi_s, xi_m0, xi_m, grad0, hess0) -> s` over lanes (`hess0` full);
/// safety as for [`LaneGradientFn`].
pub(crate) type SlipLaneHessianFn =
    unsafe fn(&[Lanes], Lanes, Lanes, &mut Lanes, &mut [Lanes], &mut [Lanes]) -> Lanes;

/// One approximation type's slip lane kernel for segments.
#[derive(Clone, Copy)]
pub(crate) enum SlipLaneKernel {
    /// First-order only.
    Gradient(SlipLaneGradientFn),
    /// With the second-order term.
    Hessian(SlipLaneHessianFn),
}

/// `(d, xi_s, xi_m0, xi_m, grad) -> s_j` over lanes: one component of a
/// face pair's slip with its gradient (`xi_s`, `xi_m0` and the in/out
/// `xi_m` two [`Lanes`] each); safety as for [`LaneGradientFn`].
pub(crate) type FaceSlipLaneGradientFn =
    unsafe fn(&[Lanes], &[Lanes], &[Lanes], &mut [Lanes], &mut [Lanes]) -> Lanes;
/// `(d, xi_s, xi_m0, xi_m, grad, hess) -> s_j` over lanes (`hess` full);
/// safety as for [`LaneGradientFn`].
pub(crate) type FaceSlipLaneHessianFn =
    unsafe fn(&[Lanes], &[Lanes], &[Lanes], &mut [Lanes], &mut [Lanes], &mut [Lanes]) -> Lanes;

/// One approximation type's slip lane kernels for faces: one function per
/// component (`codegen::emit::lanes` says why), in component order,
/// compiled for AVX2 only (a `LaneSet<Option<FaceSlipLaneKernel>>` whose
/// portable entries are `None`).
#[derive(Clone, Copy)]
#[cfg_attr(not(feature = "faces"), allow(dead_code))]
pub(crate) enum FaceSlipLaneKernel {
    /// First-order only.
    Gradient([FaceSlipLaneGradientFn; 3]),
    /// With the second-order term.
    Hessian([FaceSlipLaneHessianFn; 3]),
}

/// The instruction set a lane kernel was compiled for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum LaneIsa {
    /// The target's baseline (on x86-64: SSE2, two lanes per instruction).
    Portable,
    /// AVX2 (x86-64): four lanes per instruction, no FMA.
    Avx2,
}

/// The lane kernels of one formulation, types 1..=6 ([`LaneKernel`]s of
/// segments, [`FaceLaneKernel`]s of faces, [`SlipLaneKernel`]s of a
/// segment slip, [`FaceSlipLaneKernel`]s of a face slip).
pub(crate) struct LaneSet<K = LaneKernel> {
    pub(crate) portable: [K; 6],
    #[cfg(target_arch = "x86_64")]
    pub(crate) avx2: [K; 6],
}

/// The lane kernel of type `ty` (1..=6) for the best instruction set this
/// CPU has, or the one asked for when it is [`LaneIsa::Portable`].
///
/// Invariant: an [`LaneIsa::Avx2`] kernel is returned only when the CPU
/// supports AVX2, so calling it is sound.
pub(crate) fn select<K: Copy>(set: &LaneSet<K>, ty: usize, isa: LaneIsa) -> (K, LaneIsa) {
    #[cfg(target_arch = "x86_64")]
    if isa == LaneIsa::Avx2 && std::is_x86_feature_detected!("avx2") {
        return (set.avx2[ty - 1], LaneIsa::Avx2);
    }
    let _ = isa;
    (set.portable[ty - 1], LaneIsa::Portable)
}

include!(concat!(env!("OUT_DIR"), "/kernels_lanes.rs"));
