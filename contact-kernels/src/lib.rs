//! Generated gap, gradient and Hessian kernels for 2D segment-to-segment
//! contact.
//!
//! Every kernel takes the **current coordinates** of a slave segment and a
//! master segment,
//!
//! ```text
//! q = [xs1, ys1, xs2, ys2, xm1, ym1, xm2, ym2]
//! ```
//!
//! (two-node straight segments; the `quadratic-slave-normal` formulation,
//! behind the crate feature of that name, takes 3-node quadratic segments,
//! `q = [xs1, ys1, xs2, ys2, xs3, ys3, xm1, ym1, xm2, ym2, xm3, ym3]`, end
//! nodes first and the mid node last as Gmsh's line3: the coordinate count
//! is the formulation's, [`Kernel::coords`])
//!
//! and the slave integration point's parametric coordinate `xi_s` in
//! `[-1, 1]`, projects the slave point onto the master segment (the
//! projection coordinate `xi_m` is an implicit function `r(q, xi) = 0` of
//! the formulation) and returns the gap `g = n . x_ms` with its derivatives
//! with respect to `q` as the chosen [`ApproxType`] keeps them:
//!
//! * `g > 0`: the bodies are apart; `g < 0`: they penetrate.
//! * `x_ms = x_m(xi_m) - x_s` points from the slave point to its projection.
//! * Segments run counter-clockwise around their own body; the outward
//!   normal of a segment with tangent `t` is `(t.y, -t.x) / |t|`.
//!
//! The kernels are generated at build time by `gapsim-codegen` from the
//! formulation files in `formulations/`; each approximation type computes
//! only the derivative terms it keeps (Type 1 has no Hessian at all).
//!
//! Two ways in:
//!
//! * the handles [`Kernel`] (one per formulation and type) and
//!   [`Projector`] take `q` as a slice of the formulation's coordinate count
//!   and write into buffers the caller owns ([`GapOut`]), for hot loops;
//! * [`evaluate`] and [`project`] take the straight segment pair's
//!   `[f64; 8]` and return values ([`GapDerivatives`] with nalgebra
//!   vectors), built on the handles with bit-identical results.
//!
//! ## 3D faces
//!
//! The face formulations (`tri3-slave-normal`, `quad4-closest-point`,
//! `tri3-quad4-slave-normal`, ...: tri3 and quad4 faces, every pair of kinds,
//! both readings; the crate feature `faces`, on by default) take the slave
//! face's nodes then the master face's, `(x, y, z)` each, and the slave point
//! `xi_s = (u, v)`; they report `xi_m = (u, v)` (docs/conventions.md, "3D
//! faces"):
//!
//! ```
//! use contact_kernels::{ApproxType, Formulation, GapOut, Kernel};
//!
//! let k = Kernel::new(Formulation::Tri3SlaveNormal, ApproxType::Type6)?;
//! let q = [
//!     0.0, 0.0, 1.0, 0.1, 1.0, 1.05, 1.0, 0.1, 0.95, // slave tri3
//!     -0.3, -0.2, 0.8, 1.4, 0.1, 0.85, 0.2, 1.5, 0.75, // master tri3
//! ];
//! let mut out = GapOut::new(&k);
//! k.eval(&q, [0.3, 0.25], &mut out)?;
//! assert!((out.gap() - 0.203900706766229).abs() < 1e-14);
//! assert!((out.xi_m_all()[1] - 0.270469354510283).abs() < 1e-14);
//! # Ok::<(), contact_kernels::KernelError>(())
//! ```
//!
//! Parametric coordinates: the handles take `xi_s` as any [`XiArg`] of
//! [`Kernel::param_dim`] values (`0.3` for a segment, `[0.2, -0.1]` for a
//! face) and report `xi_m` as a slice of as many ([`GapOut::xi_m_all`]);
//! see [`param`].
//!
//! Modules: `validate` (the one validation point), `param` (parametric
//! coordinates, [`XiArg`]), `projection` (the
//! projection solve and [`Projector`]), `kernel` ([`Kernel`], [`GapOut`]),
//! `runtime` ([`eval_runtime`]: kernels given at run time, e.g. a user's
//! formulation file interpreted, through the same checks),
//! `error` ([`KernelError`]), `types` (formulations, types, op counts),
//! `generated` (the build script's output), `lanes` (the SIMD value type)
//! and `generated_lanes` (the same kernels over 4 points at a time, for
//! [`Kernel::eval_batch`]).
//!
//! ```
//! use contact_kernels::{evaluate, ApproxType, Formulation};
//!
//! let q = [0.0, 1.0, 2.0, 1.1, 2.1, 0.9, -0.1, 1.0];
//! let out = evaluate(Formulation::SlaveNormal, ApproxType::Type6, &q, 0.3)?;
//! assert!((out.gap - 0.129090446096668).abs() < 1e-12);
//! assert!((out.xi_m + 0.278587699316629).abs() < 1e-12);
//! let hess = out.hess.expect("Type 6 has a Hessian");
//! assert!((hess[(0, 0)] - 0.00046515059696).abs() < 1e-12);
//! # Ok::<(), contact_kernels::KernelError>(())
//! ```
#![warn(missing_docs)]

mod error;
mod faces;
#[allow(clippy::all, unused_parens, unused_variables, non_snake_case)]
mod generated;
#[allow(clippy::all, unused_parens, unused_variables, non_snake_case)]
mod generated_lanes;
mod kernel;
mod lanes;
pub mod param;
mod projection;
mod runtime;
mod types;
mod validate;

pub use error::{KernelError, OutputKind, Segment};
pub use generated_lanes::LaneIsa;
pub use kernel::{GapBatch, GapOut, Kernel, Slip, SlipBatch, SlipOut};
pub use param::{MAX_PARAM_DIM, XiArg};
pub use projection::{Projector, XI_M_LIMIT};
pub use runtime::{RuntimeKernels, eval_runtime};
pub use types::{ApproxType, EntityOrder, Formulation, OpCount, ParseNameError};
pub use validate::DEGENERATE_LENGTH;

use nalgebra::{ArrayStorage, SMatrix, SVector};

/// The coordinate count of the straight segment-pair API ([`evaluate`],
/// [`project`], [`GapDerivatives`]): two 2D two-node segments.
pub const PAIR_COORDS: usize = 8;

/// Gap and projection coordinate only (the projection kernel).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Projection {
    /// The gap `g = n . x_ms` (negative when penetrating).
    pub gap: f64,
    /// The master parametric coordinate of the projection (inside the
    /// segment when in `[-1, 1]`); for a face its first component `u`
    /// (all of it: [`Projection::xi_m_all`]).
    pub xi_m: f64,
    xi: param::Xi,
}

impl Projection {
    /// The master parametric coordinates of the projection (one for a
    /// segment, `[u, v]` for a face).
    pub fn xi_m_all(&self) -> &[f64] {
        self.xi.as_slice()
    }
}

/// The gap and its derivatives with respect to `q` as one approximation
/// type keeps them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GapDerivatives {
    /// The gap `g = n . x_ms` (negative when penetrating).
    pub gap: f64,
    /// The master parametric coordinate of the projection.
    pub xi_m: f64,
    /// `dg/dq` as the type keeps it.
    pub grad: SVector<f64, PAIR_COORDS>,
    /// The symmetric `d2g/dq2` as the type keeps it; `None` for Type 1,
    /// which has no second-order term.
    pub hess: Option<SMatrix<f64, PAIR_COORDS, PAIR_COORDS>>,
}

/// Projects the slave point `x_s(xi_s)` onto the master segment and returns
/// the gap and `xi_m` (no derivatives): the kernel a solver calls to
/// re-project and re-pair. (The [`Projector`] handle, on a stack buffer.)
pub fn project(
    formulation: Formulation,
    q: &[f64; PAIR_COORDS],
    xi_s: f64,
) -> Result<Projection, KernelError> {
    let projector = Projector::new(formulation)?;
    let mut d = [0.0; PAIR_COORDS];
    projector.project_into(q, xi_s, &mut d)
}

/// Evaluates the gap and its derivatives as approximation type `ty` keeps
/// them (Type 6: the exact gradient and Hessian). (The [`Kernel`] handle,
/// on stack buffers, returned as nalgebra values.) For the formulations of
/// two-node pairs ([`pair_formulations`]); any other gives
/// [`KernelError::CoordinateCount`] (use [`Kernel`]).
pub fn evaluate(
    formulation: Formulation,
    ty: ApproxType,
    q: &[f64; PAIR_COORDS],
    xi_s: f64,
) -> Result<GapDerivatives, KernelError> {
    let kernel = Kernel::new(formulation, ty)?;
    let mut d = [0.0; PAIR_COORDS];
    let mut grad = [0.0; PAIR_COORDS];
    // Symmetric, so the kernel's row-major writes are also nalgebra's
    // column-major storage.
    let mut hess = [[0.0; PAIR_COORDS]; PAIR_COORDS];
    let (gap, xi_m) = kernel.eval_into(q, xi_s, &mut d, &mut grad, hess.as_flattened_mut())?;
    Ok(GapDerivatives {
        gap,
        xi_m,
        grad: SVector::from_array_storage(ArrayStorage([grad])),
        hess: kernel
            .has_hessian()
            .then(|| SMatrix::from_array_storage(ArrayStorage(hess))),
    })
}

/// The generated kernel's operation count for `(formulation, ty)`, or the
/// projection kernel's (one residual evaluation plus the gap) when `ty` is
/// `None`. `None` when the formulation was not compiled in.
pub fn op_count(formulation: Formulation, ty: Option<ApproxType>) -> Option<OpCount> {
    let (ops, projection_ops) = match generated::face_kernel_set(formulation) {
        Some(f) => (&f.ops, f.projection_ops),
        None => {
            let set = generated::kernel_set(formulation)?;
            (&set.ops, set.projection_ops)
        }
    };
    Some(match ty {
        Some(t) => ops[t.index() - 1],
        None => projection_ops,
    })
}

/// The formulations compiled into this build.
pub fn compiled_formulations() -> Vec<Formulation> {
    Formulation::ALL
        .into_iter()
        .filter(|f| f.coords().is_some())
        .collect()
}

/// The compiled formulations of two-node segment pairs ([`PAIR_COORDS`]
/// coordinates): those [`evaluate`], [`project`] and a solver meshing
/// straight segments can use. (The others, e.g. `quadratic-slave-normal`
/// with 12 coordinates, serve [`Kernel`] and [`Projector`] only.)
pub fn pair_formulations() -> Vec<Formulation> {
    compiled_formulations()
        .into_iter()
        .filter(|f| f.coords() == Some(PAIR_COORDS))
        .collect()
}
