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

mod types;

pub use types::{ApproxType, EntityOrder, Formulation, OpCount, ParseNameError};

use nalgebra::{ArrayStorage, SMatrix, SVector};

#[allow(clippy::all, unused_parens, unused_variables, non_snake_case)]
mod generated {
    //! The kernels written by `build.rs` (see `OUT_DIR/kernels.rs`): the
    //! [`Formulation`] enum, the truncation table and one [`KernelSet`] per
    //! compiled formulation.
    use crate::{EntityOrder, OpCount};

    /// `(d, xi_s, xi) -> [r, dr/dxi]`: the projection residual.
    pub(crate) type ResidualFn = fn(&[f64; 8], f64, f64) -> [f64; 2];
    /// `(d, xi_s, xi_m) -> g`. `xi_m`: the converged projection on input
    /// (Newton formulations; ignored when the projection is in closed
    /// form), the projection used on output.
    pub(crate) type GapFn = fn(&[f64; 8], f64, &mut f64) -> f64;
    /// `(d, xi_s, xi_m, grad) -> g` (`xi_m` as for [`GapFn`]).
    pub(crate) type GradientFn = fn(&[f64; 8], f64, &mut f64, &mut [f64; 8]) -> f64;
    /// `(d, xi_s, xi_m, grad, hess) -> g` (`xi_m` as for [`GapFn`]).
    pub(crate) type HessianFn =
        fn(&[f64; 8], f64, &mut f64, &mut [f64; 8], &mut [[f64; 8]; 8]) -> f64;

    /// One approximation type's kernel. All take `d`, the coordinates
    /// relative to slave node 1 (`d[0] = d[1] = 0`, not read).
    #[derive(Clone, Copy)]
    pub(crate) enum Kernel {
        /// First-order only (Type 1).
        Gradient(GradientFn),
        /// With the second-order term.
        Hessian(HessianFn),
    }

    /// The generated kernels of one formulation.
    pub(crate) struct KernelSet {
        /// The residual is affine in `xi`: every kernel solves the
        /// projection itself (no Newton iteration needed).
        pub(crate) closed_form_projection: bool,
        pub(crate) residual: ResidualFn,
        pub(crate) gap: GapFn,
        pub(crate) kernels: [Kernel; 6],
        pub(crate) ops: [OpCount; 6],
        pub(crate) projection_ops: OpCount,
    }

    include!(concat!(env!("OUT_DIR"), "/kernels.rs"));
}

/// Why a kernel could not evaluate a configuration.
///
/// Every data-dependent failure of the kernels is one of these; a kernel
/// never returns NaN or infinity for input it accepted.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum KernelError {
    /// A coordinate or `xi_s` is NaN or infinite.
    #[error("non-finite input: coordinate {index} is {value}")]
    NonFinite {
        /// Index into `q` (0..8), or 8 for `xi_s`.
        index: usize,
        /// The offending value.
        value: f64,
    },
    /// A segment has (numerically) zero length.
    #[error("degenerate {segment} segment: length {length:e} is below {threshold:e}")]
    DegenerateSegment {
        /// Which segment.
        segment: Segment,
        /// Its length.
        length: f64,
        /// The smallest accepted length (relative to the configuration's size).
        threshold: f64,
    },
    /// The projection equation has no (finite) solution, e.g. for the
    /// slave-normal formulation when the master segment is perpendicular to
    /// the slave segment (`t_m . t_s = 0`).
    #[error(
        "no projection: the projection equation r(q, xi) = 0 has no finite solution (dr/dxi = {r_xi:e})"
    )]
    NoProjection {
        /// The derivative of the projection residual with respect to `xi`
        /// where the solve gave up.
        r_xi: f64,
    },
    /// The projection was found but lies absurdly far outside the master
    /// segment (`|xi_m|` above [`XI_M_LIMIT`]), where the gap and its
    /// derivatives lose all accuracy.
    #[error("projection too far from the master segment: xi_m = {xi_m:e}")]
    ProjectionOutOfReach {
        /// The projection coordinate.
        xi_m: f64,
    },
    /// The Newton iteration for the projection did not converge.
    #[error(
        "the projection did not converge in {iterations} Newton iterations (last |dxi| = {last_step:e})"
    )]
    ProjectionDiverged {
        /// Iterations performed.
        iterations: usize,
        /// The last Newton correction.
        last_step: f64,
    },
    /// This formulation was not compiled in (see the crate's features).
    #[error("formulation `{0}` was not compiled into this build of contact-kernels")]
    NotCompiled(Formulation),
}

/// The two segments of a contact pair.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Segment {
    /// The slave segment (nodes `q[0..4]`).
    Slave,
    /// The master segment (nodes `q[4..8]`).
    Master,
}

impl std::fmt::Display for Segment {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Segment::Slave => "slave",
            Segment::Master => "master",
        })
    }
}

/// `|xi_m|` beyond which a projection is rejected as out of reach.
pub const XI_M_LIMIT: f64 = 1e6;

/// A segment shorter than this times the configuration's size is degenerate.
pub const DEGENERATE_LENGTH: f64 = 1e-10;

/// Gap and projection coordinate only (the projection kernel).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Projection {
    /// The gap `g = n . x_ms` (negative when penetrating).
    pub gap: f64,
    /// The master parametric coordinate of the projection (inside the
    /// segment when in `[-1, 1]`).
    pub xi_m: f64,
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
    pub grad: SVector<f64, 8>,
    /// The symmetric `d2g/dq2` as the type keeps it; `None` for Type 1,
    /// which has no second-order term.
    pub hess: Option<SMatrix<f64, 8, 8>>,
}

/// The input, validated and shifted to coordinates relative to slave node 1
/// (all kernels depend on coordinate differences only, so this keeps their
/// accuracy far from the origin).
struct Local {
    d: [f64; 8],
}

/// The one place where degenerate input is detected.
fn validate(q: &[f64; 8], xi_s: f64) -> Result<Local, KernelError> {
    if !(all_finite(q) && xi_s.is_finite()) {
        // Cold path: name the first offending input.
        let (index, value) = q
            .iter()
            .chain(std::iter::once(&xi_s))
            .copied()
            .enumerate()
            .find(|(_, v)| !v.is_finite())
            .expect("one is not finite");
        return Err(KernelError::NonFinite { index, value });
    }
    let mut d = [0.0; 8];
    for i in 0..4 {
        d[2 * i] = q[2 * i] - q[0];
        d[2 * i + 1] = q[2 * i + 1] - q[1];
    }
    let size = d.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let threshold = DEGENERATE_LENGTH * size;
    for (segment, a) in [(Segment::Slave, 0), (Segment::Master, 4)] {
        // Squared lengths: no hypot in the hot path. (Configurations with
        // coordinates below ~1e-150 underflow here and are reported as
        // degenerate.)
        let (dx, dy) = (d[a + 2] - d[a], d[a + 3] - d[a + 1]);
        let length2 = dx * dx + dy * dy;
        // Written so that a NaN length is also rejected.
        #[allow(clippy::neg_cmp_op_on_partial_ord)]
        if !(length2 > threshold * threshold) {
            let length = length2.sqrt();
            return Err(KernelError::DegenerateSegment {
                segment,
                length,
                threshold,
            });
        }
    }
    Ok(Local { d })
}

/// Newton iterations allowed for the projection.
const PROJECTION_ITERATIONS: usize = 20;

/// A Newton correction below this (relative to `1 + |xi|`) ends the
/// projection solve.
const PROJECTION_TOLERANCE: f64 = 1e-12;

/// Solves the formulation's projection equation `r(q, xi) = 0` by Newton's
/// method from `xi = 0` (one step for straight segments, where `r` is linear
/// in `xi`; a second step confirms convergence).
fn solve_projection(
    residual: fn(&[f64; 8], f64, f64) -> [f64; 2],
    local: &Local,
    xi_s: f64,
) -> Result<f64, KernelError> {
    let mut xi = 0.0_f64;
    let mut last_step = f64::INFINITY;
    for _ in 0..PROJECTION_ITERATIONS {
        let [r, r_xi] = residual(&local.d, xi_s, xi);
        let step = r / r_xi;
        if !step.is_finite() {
            return Err(KernelError::NoProjection { r_xi });
        }
        xi -= step;
        if xi.abs() > XI_M_LIMIT {
            return Err(KernelError::ProjectionOutOfReach { xi_m: xi });
        }
        last_step = step.abs();
        if last_step <= PROJECTION_TOLERANCE * (1.0 + xi.abs()) {
            return Ok(xi);
        }
    }
    Err(KernelError::ProjectionDiverged {
        iterations: PROJECTION_ITERATIONS,
        last_step,
    })
}

/// Projects the slave point `x_s(xi_s)` onto the master segment and returns
/// the gap and `xi_m` (no derivatives): the kernel a solver calls to
/// re-project and re-pair.
pub fn project(
    formulation: Formulation,
    q: &[f64; 8],
    xi_s: f64,
) -> Result<Projection, KernelError> {
    let set = generated::kernel_set(formulation).ok_or(KernelError::NotCompiled(formulation))?;
    let local = validate(q, xi_s)?;
    let mut xi_m = start_projection(set, &local, xi_s)?;
    let gap = (set.gap)(&local.d, xi_s, &mut xi_m);
    check_projection(set, &local, xi_s, xi_m)?;
    finite_or_no_projection(gap)?;
    Ok(Projection { gap, xi_m })
}

/// The projection a kernel starts from: `0` when the kernels solve it in
/// closed form, the Newton solution otherwise.
fn start_projection(
    set: &generated::KernelSet,
    local: &Local,
    xi_s: f64,
) -> Result<f64, KernelError> {
    if set.closed_form_projection {
        Ok(0.0)
    } else {
        solve_projection(set.residual, local, xi_s)
    }
}

/// Rejects a projection the kernel could not find (non-finite: the
/// residual's `dr/dxi` vanished) or that lies out of reach.
fn check_projection(
    set: &generated::KernelSet,
    local: &Local,
    xi_s: f64,
    xi_m: f64,
) -> Result<(), KernelError> {
    if !xi_m.is_finite() {
        let [_, r_xi] = (set.residual)(&local.d, xi_s, 0.0);
        return Err(KernelError::NoProjection { r_xi });
    }
    if xi_m.abs() > XI_M_LIMIT {
        return Err(KernelError::ProjectionOutOfReach { xi_m });
    }
    Ok(())
}

/// Evaluates the gap and its derivatives as approximation type `ty` keeps
/// them (Type 6: the exact gradient and Hessian).
pub fn evaluate(
    formulation: Formulation,
    ty: ApproxType,
    q: &[f64; 8],
    xi_s: f64,
) -> Result<GapDerivatives, KernelError> {
    let set = generated::kernel_set(formulation).ok_or(KernelError::NotCompiled(formulation))?;
    let local = validate(q, xi_s)?;
    let mut xi_m = start_projection(set, &local, xi_s)?;
    let mut grad = [0.0; 8];
    // Symmetric, so the kernel's row-major writes are also nalgebra's
    // column-major storage.
    let mut hess = [[0.0; 8]; 8];
    let (gap, finite, has_hessian) = match set.kernels[ty.index() - 1] {
        generated::Kernel::Gradient(k) => {
            let gap = k(&local.d, xi_s, &mut xi_m, &mut grad);
            (gap, all_finite(&grad), false)
        }
        generated::Kernel::Hessian(k) => {
            let gap = k(&local.d, xi_s, &mut xi_m, &mut grad, &mut hess);
            (
                gap,
                all_finite(&grad) & all_finite(hess.as_flattened()),
                true,
            )
        }
    };
    check_projection(set, &local, xi_s, xi_m)?;
    if !(finite && gap.is_finite()) {
        return Err(KernelError::NoProjection { r_xi: 0.0 });
    }
    Ok(GapDerivatives {
        gap,
        xi_m,
        grad: SVector::from_array_storage(ArrayStorage([grad])),
        hess: has_hessian.then(|| SMatrix::from_array_storage(ArrayStorage(hess))),
    })
}

/// Whether every value is finite, with integer operations that vectorise:
/// a value is NaN or infinite exactly when its exponent bits are all ones,
/// i.e. when adding one to the exponent field carries into the sign bit.
fn all_finite(v: &[f64]) -> bool {
    const EXPONENT: u64 = 0x7ff0_0000_0000_0000;
    const EXPONENT_ONE: u64 = 0x0010_0000_0000_0000;
    v.iter().fold(0u64, |acc, x| {
        acc | ((x.to_bits() & EXPONENT) + EXPONENT_ONE)
    }) >> 63
        == 0
}

/// A non-finite output can only come from an (almost) singular projection.
fn finite_or_no_projection(v: f64) -> Result<(), KernelError> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(KernelError::NoProjection { r_xi: 0.0 })
    }
}

/// The generated kernel's operation count for `(formulation, ty)`, or the
/// projection kernel's (one residual evaluation plus the gap) when `ty` is
/// `None`. `None` when the formulation was not compiled in.
pub fn op_count(formulation: Formulation, ty: Option<ApproxType>) -> Option<OpCount> {
    let set = generated::kernel_set(formulation)?;
    Some(match ty {
        Some(t) => set.ops[t.index() - 1],
        None => set.projection_ops,
    })
}

/// The formulations compiled into this build.
pub fn compiled_formulations() -> Vec<Formulation> {
    Formulation::ALL
        .into_iter()
        .filter(|f| generated::kernel_set(*f).is_some())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A residual that is not affine in `xi` (`r = xi^3 + xi - d[2]`), as a
    /// curved-segment formulation would have: the Newton path must converge.
    fn cubic(d: &[f64; 8], _xi_s: f64, xi: f64) -> [f64; 2] {
        [xi * xi * xi + xi - d[2], 3.0 * xi * xi + 1.0]
    }

    /// `r = xi^2 + 1`: no real root.
    fn no_root(_d: &[f64; 8], _xi_s: f64, xi: f64) -> [f64; 2] {
        [xi * xi + 1.0, 2.0 * xi]
    }

    #[test]
    fn newton_projection_converges_for_a_nonlinear_residual() {
        let local = Local {
            d: [0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        };
        let xi = solve_projection(cubic, &local, 0.0).unwrap();
        // xi = 1 solves xi^3 + xi = 2; Newton's tolerance is 1e-12.
        assert!((xi - 1.0).abs() < 1e-12, "{xi}");
    }

    #[test]
    fn newton_projection_reports_failure() {
        let local = Local { d: [0.0; 8] };
        match solve_projection(no_root, &local, 0.0) {
            Err(
                KernelError::NoProjection { .. }
                | KernelError::ProjectionDiverged { .. }
                | KernelError::ProjectionOutOfReach { .. },
            ) => {}
            other => panic!("expected a projection failure, got {other:?}"),
        }
    }
}
