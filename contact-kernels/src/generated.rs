//! The kernels written by `build.rs` (see `OUT_DIR/kernels.rs`): the
//! [`Formulation`] enum, the truncation table and one [`KernelSet`] per
//! compiled formulation, with the run-time types they are written against.
//!
//! Every generated function takes `d`, the coordinates relative to the
//! first point (slave node 1: `d[0..dim]` are zero and not read), as a slice
//! of exactly `KernelSet::coords` values, and stores into `grad` (`coords`
//! values) and `hess` (`coords * coords`, the full symmetric matrix,
//! row-major). The callers in this crate guarantee these lengths (the
//! functions reslice on entry and would panic otherwise).

use crate::{EntityOrder, OpCount};

/// `(d, xi_s, xi) -> [r, dr/dxi]`: the projection residual.
pub(crate) type ResidualFn = fn(&[f64], f64, f64) -> [f64; 2];
/// `(d, xi_s, xi_m) -> g`. `xi_m`: the converged projection on input
/// (Newton formulations; ignored when the projection is in closed form),
/// the projection used on output.
pub(crate) type GapFn = fn(&[f64], f64, &mut f64) -> f64;
/// `(d, xi_s, xi_m, grad) -> g` (`xi_m` as for [`GapFn`]).
pub(crate) type GradientFn = fn(&[f64], f64, &mut f64, &mut [f64]) -> f64;
/// `(d, xi_s, xi_m, grad, hess) -> g` (`xi_m` as for [`GapFn`]).
pub(crate) type HessianFn = fn(&[f64], f64, &mut f64, &mut [f64], &mut [f64]) -> f64;

/// One approximation type's kernel.
#[derive(Clone, Copy)]
pub(crate) enum Kernel {
    /// First-order only (Type 1).
    Gradient(GradientFn),
    /// With the second-order term.
    Hessian(HessianFn),
}

/// `(d, xi_s, xi_m0, xi_m, grad) -> s`: the slip of a segment pair
/// (`xi_m` as for [`GapFn`], `xi_m0` the last converged projection).
pub(crate) type SlipGradientFn = fn(&[f64], f64, f64, &mut f64, &mut [f64]) -> f64;
/// `(d, xi_s, xi_m0, xi_m, grad, hess) -> s`.
pub(crate) type SlipHessianFn = fn(&[f64], f64, f64, &mut f64, &mut [f64], &mut [f64]) -> f64;

/// One approximation type's slip kernel (segments: one component).
#[derive(Clone, Copy)]
pub(crate) enum SlipKernel {
    /// First-order only.
    Gradient(SlipGradientFn),
    /// With the second-order term.
    Hessian(SlipHessianFn),
}

/// `(d, xi_s, xi_m0, xi_m, grad0, grad1, grad2) -> [s0, s1, s2]`: the slip
/// of a face pair, its three global components.
pub(crate) type FaceSlipGradientFn =
    fn(&[f64], &[f64], &[f64], &mut [f64], &mut [f64], &mut [f64], &mut [f64]) -> [f64; 3];
/// `(d, xi_s, xi_m0, xi_m, grad0, grad1, grad2, hess0, hess1, hess2) -> [s0, s1, s2]`.
pub(crate) type FaceSlipHessianFn = fn(
    &[f64],
    &[f64],
    &[f64],
    &mut [f64],
    &mut [f64],
    &mut [f64],
    &mut [f64],
    &mut [f64],
    &mut [f64],
    &mut [f64],
) -> [f64; 3];

/// One approximation type's slip kernel for faces (three components).
#[derive(Clone, Copy)]
#[cfg_attr(not(feature = "faces"), allow(dead_code))]
pub(crate) enum FaceSlipKernel {
    /// First-order only.
    Gradient(FaceSlipGradientFn),
    /// With the second-order term.
    Hessian(FaceSlipHessianFn),
}

/// A formulation's slip kernels, types 1..=6, and their costs.
pub(crate) struct SlipSet<K> {
    pub(crate) kernels: [K; 6],
    pub(crate) ops: [OpCount; 6],
}

/// The generated kernels of one formulation.
pub(crate) struct KernelSet {
    /// The dimension of every point.
    pub(crate) dim: usize,
    /// The coordinate count `n` (points times `dim`).
    pub(crate) coords: usize,
    /// The residual is affine in `xi`: every kernel solves the
    /// projection itself (no Newton iteration needed).
    pub(crate) closed_form_projection: bool,
    pub(crate) residual: ResidualFn,
    pub(crate) gap: GapFn,
    pub(crate) kernels: [Kernel; 6],
    pub(crate) ops: [OpCount; 6],
    pub(crate) projection_ops: OpCount,
    /// The slip's kernels, if the formulation defines a slip.
    pub(crate) slip: Option<SlipSet<SlipKernel>>,
}

/// `(d, xi, out)`: a face projection's residuals and their Jacobian at
/// `xi = (u, v)`, `[r_0, r_1, A_00, A_01, A_10, A_11]`, `A_ac = dr_a/dxi_c`.
pub(crate) type FaceResidualFn = fn(&[f64], &[f64], &[f64]) -> [f64; 6];
/// `(d, xi_s, xi_m) -> g` for faces: `xi_s` and `xi_m` have two values
/// (`xi_m` in/out as for [`GapFn`]).
pub(crate) type FaceGapFn = fn(&[f64], &[f64], &mut [f64]) -> f64;
/// `(d, xi_s, xi_m, grad) -> g` for faces.
pub(crate) type FaceGradientFn = fn(&[f64], &[f64], &mut [f64], &mut [f64]) -> f64;
/// `(d, xi_s, xi_m, grad, hess) -> g` for faces.
pub(crate) type FaceHessianFn = fn(&[f64], &[f64], &mut [f64], &mut [f64], &mut [f64]) -> f64;

/// One approximation type's kernel for faces (made only by the face
/// formulations compiled in: none without the `faces` features).
#[derive(Clone, Copy)]
#[cfg_attr(not(feature = "faces"), allow(dead_code))]
pub(crate) enum FaceKernel {
    /// First-order only (Type 1).
    Gradient(FaceGradientFn),
    /// With the second-order term.
    Hessian(FaceHessianFn),
}

/// The generated kernels of one formulation of 3D faces (points of three
/// coordinates; `xi_s`, `xi_m` of two).
pub(crate) struct FaceKernelSet {
    /// The coordinate count `n` (3 times the points).
    pub(crate) coords: usize,
    /// Nodes of the slave face (3: tri3, 4: quad4), the first points.
    pub(crate) slave_nodes: usize,
    /// Nodes of the master face, the points after the slave's.
    pub(crate) master_nodes: usize,
    /// The residual is affine in `xi` (a tri3 master): every kernel solves
    /// the projection itself.
    pub(crate) closed_form_projection: bool,
    pub(crate) residual: FaceResidualFn,
    pub(crate) gap: FaceGapFn,
    pub(crate) kernels: [FaceKernel; 6],
    pub(crate) ops: [OpCount; 6],
    pub(crate) projection_ops: OpCount,
    /// The slip's kernels, if the formulation defines a slip.
    pub(crate) slip: Option<SlipSet<FaceSlipKernel>>,
}

include!(concat!(env!("OUT_DIR"), "/kernels.rs"));
