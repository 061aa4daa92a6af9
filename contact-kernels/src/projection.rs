//! The projection: solving the formulation's `r(q, xi) = 0` for `xi_m`,
//! rejecting projections that do not exist or lie out of reach, and the
//! projection handle [`Projector`] (gap and `xi_m`, no derivatives).
//!
//! When the residual is affine in `xi` the generated kernels solve it in
//! closed form themselves ([`start`] returns `0`, ignored by them);
//! otherwise [`start`] runs Newton's method on the generated residual.
//! Either way [`check`] validates the `xi_m` a kernel used.

use crate::generated::{FaceKernelSet, KernelSet, face_kernel_set, kernel_set};
use crate::param::{Xi, XiArg};
use crate::validate::relative_coordinates;
use crate::{Formulation, KernelError, OutputKind, Projection, faces};

/// `|xi_m|` beyond which a projection is rejected as out of reach.
pub const XI_M_LIMIT: f64 = 1e6;

/// Newton iterations allowed for the projection.
const PROJECTION_ITERATIONS: usize = 20;

/// A Newton correction below this (relative to `1 + |xi|`) ends the
/// projection solve.
const PROJECTION_TOLERANCE: f64 = 1e-12;

/// Solves the formulation's projection equation `r(q, xi) = 0` by Newton's
/// method from `xi = 0` (one step for straight segments, where `r` is linear
/// in `xi`; a second step confirms convergence). `d`: relative coordinates.
pub(crate) fn solve(
    residual: impl Fn(&[f64], f64, f64) -> [f64; 2],
    d: &[f64],
    xi_s: f64,
) -> Result<f64, KernelError> {
    let mut xi = 0.0_f64;
    let mut last_step = f64::INFINITY;
    for _ in 0..PROJECTION_ITERATIONS {
        let [r, r_xi] = residual(d, xi_s, xi);
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

/// The projection a kernel starts from: `0` when the kernels solve it in
/// closed form, the Newton solution otherwise.
pub(crate) fn start(set: &KernelSet, d: &[f64], xi_s: f64) -> Result<f64, KernelError> {
    if set.closed_form_projection {
        Ok(0.0)
    } else {
        solve(set.residual, d, xi_s)
    }
}

/// Rejects a projection the kernel could not find (non-finite: the
/// residual's `dr/dxi` vanished) or that lies out of reach.
pub(crate) fn check(set: &KernelSet, d: &[f64], xi_s: f64, xi_m: f64) -> Result<(), KernelError> {
    check_with(set.residual, d, xi_s, xi_m)
}

/// [`check`] with the residual given as a function.
pub(crate) fn check_with(
    residual: impl Fn(&[f64], f64, f64) -> [f64; 2],
    d: &[f64],
    xi_s: f64,
    xi_m: f64,
) -> Result<(), KernelError> {
    if !xi_m.is_finite() {
        let [_, r_xi] = residual(d, xi_s, 0.0);
        return Err(KernelError::NoProjection { r_xi });
    }
    if xi_m.abs() > XI_M_LIMIT {
        return Err(KernelError::ProjectionOutOfReach { xi_m });
    }
    Ok(())
}

/// The projection kernel of one formulation: projects a slave point onto
/// the master segment and returns the gap and `xi_m` (no derivatives), as a
/// solver does to re-project and re-pair.
#[derive(Clone, Copy)]
pub struct Projector {
    formulation: Formulation,
    sets: Sets,
}

/// The kernels a projector runs: a segment or a face formulation's.
#[derive(Clone, Copy)]
enum Sets {
    Segments(&'static KernelSet),
    Faces(&'static FaceKernelSet),
}

impl std::fmt::Debug for Projector {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Projector")
            .field("formulation", &self.formulation)
            .field("coords", &self.coords())
            .finish()
    }
}

impl Projector {
    /// The projection kernel of `formulation`, or
    /// [`KernelError::NotCompiled`].
    pub fn new(formulation: Formulation) -> Result<Projector, KernelError> {
        if let Some(set) = face_kernel_set(formulation) {
            return Ok(Projector {
                formulation,
                sets: Sets::Faces(set),
            });
        }
        let set = kernel_set(formulation).ok_or(KernelError::NotCompiled(formulation))?;
        Ok(Projector {
            formulation,
            sets: Sets::Segments(set),
        })
    }

    /// The formulation.
    pub fn formulation(&self) -> Formulation {
        self.formulation
    }

    /// The coordinate count `n` every `q` must have.
    pub fn coords(&self) -> usize {
        match self.sets {
            Sets::Segments(s) => s.coords,
            Sets::Faces(f) => f.coords,
        }
    }

    /// The parametric dimension of the faces (1 for segments, 2 for
    /// faces): the length of `xi_s` and of [`Projection::xi_m_all`].
    pub fn param_dim(&self) -> usize {
        match self.sets {
            Sets::Segments(_) => 1,
            Sets::Faces(_) => 2,
        }
    }

    /// Projects the slave point `x_s(xi_s)` of configuration `q` (`n`
    /// coordinates) onto the master segment or face; `xi_s` has
    /// [`Projector::param_dim`] values ([`KernelError::ParamCount`]
    /// otherwise). `scratch` is the caller's buffer of `n` values for the
    /// relative coordinates (overwritten).
    pub fn project(
        &self,
        q: &[f64],
        xi_s: impl XiArg,
        scratch: &mut [f64],
    ) -> Result<Projection, KernelError> {
        if scratch.len() != self.coords() {
            return Err(KernelError::BufferSize {
                expected: self.coords(),
                found: scratch.len(),
            });
        }
        match (self.sets, xi_s.as_xi()) {
            (Sets::Segments(_), [x]) => self.project_into(q, *x, scratch),
            (Sets::Faces(set), [u, v]) => project_face(set, q, [*u, *v], scratch),
            (_, other) => Err(KernelError::ParamCount {
                expected: self.param_dim(),
                found: other.len(),
            }),
        }
    }

    /// [`Projector::project`] with `d.len() == n` checked by the caller.
    #[inline]
    pub(crate) fn project_into(
        &self,
        q: &[f64],
        xi_s: f64,
        d: &mut [f64],
    ) -> Result<Projection, KernelError> {
        let set = match self.sets {
            Sets::Segments(s) => s,
            Sets::Faces(_) => {
                return Err(KernelError::ParamCount {
                    expected: 2,
                    found: 1,
                });
            }
        };
        relative_coordinates(set, q, xi_s, d)?;
        let mut xi_m = start(set, d, xi_s)?;
        let gap = (set.gap)(d, xi_s, &mut xi_m);
        check(set, d, xi_s, xi_m)?;
        if !gap.is_finite() {
            return Err(KernelError::NonFiniteOutput {
                output: OutputKind::Gap,
                xi_m,
            });
        }
        Ok(Projection {
            gap,
            xi_m,
            xi: Xi::scalar(xi_m),
        })
    }
}

/// A face pair's projection (as [`Projector::project_into`] for segments):
/// validation, the projection, the gap kernel.
fn project_face(
    set: &FaceKernelSet,
    q: &[f64],
    xi_s: [f64; 2],
    d: &mut [f64],
) -> Result<Projection, KernelError> {
    faces::relative_coordinates(set, q, xi_s, d)?;
    let mut xi_m = faces::start(set, d, xi_s)?;
    let gap = (set.gap)(d, &xi_s, &mut xi_m);
    faces::check(set, d, xi_s, xi_m)?;
    if !gap.is_finite() {
        return Err(KernelError::NonFiniteOutput {
            output: OutputKind::Gap,
            xi_m: xi_m[0],
        });
    }
    Ok(Projection {
        gap,
        xi_m: xi_m[0],
        xi: Xi::pair(xi_m),
    })
}
