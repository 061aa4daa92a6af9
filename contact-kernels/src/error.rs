//! Why a kernel could not evaluate a configuration.
//!
//! Every data-dependent failure of the kernels is a [`KernelError`]; a
//! kernel never returns NaN or infinity for input it accepted. Every field
//! of an error is a value the kernel actually computed or received.

use crate::Formulation;

/// The message of [`KernelError::DegenerateSegment`]: a segment shorter
/// than the threshold, or a configuration outside the range where the
/// squared lengths of the check are representable (they overflow beyond
/// coordinate differences of about 1e154 and underflow below about
/// 1e-154), said as such.
fn degenerate_message(segment: Segment, length: f64, threshold: f64) -> String {
    let size = threshold / crate::DEGENERATE_LENGTH;
    if !length.is_finite() {
        format!(
            "{segment} segment out of range: the square of its length overflows (the \
             configuration spans {size:e}; the kernels need coordinate differences below about \
             1e150: scale the coordinates)"
        )
    } else if threshold == 0.0 {
        format!(
            "degenerate {segment} segment: length {length:e}, and the whole configuration spans \
             zero or a subnormal distance (every point coincides, or coordinate differences \
             are below about 1e-300)"
        )
    } else if size < 1e-150 {
        format!(
            "{segment} segment out of range: the configuration spans only {size:e} (the \
             kernels need coordinate differences above about 1e-150, where their squares do \
             not underflow: scale the coordinates)"
        )
    } else {
        format!("degenerate {segment} segment: length {length:e} is below {threshold:e}")
    }
}

/// Why a kernel could not evaluate a configuration.
///
/// Every data-dependent failure of the kernels is one of these; a kernel
/// never returns NaN or infinity for input it accepted.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum KernelError {
    /// A coordinate, `xi_s` or `xi_m0` is NaN or infinite.
    #[error("non-finite input: coordinate {index} is {value}")]
    NonFinite {
        /// Index into `q` (`0..n`), or `n + k` (`q.len()`: 8 for two-node
        /// and 12 for three-node segment pairs) for component `k` of `xi_s`,
        /// `n + P + k` for component `k` of the last converged projection
        /// `xi_m0` ([`crate::Slip::eval`]; `P` the parametric dimension).
        index: usize,
        /// The offending value.
        value: f64,
    },
    /// A segment has (numerically) zero length.
    #[error("{}", degenerate_message(*segment, *length, *threshold))]
    DegenerateSegment {
        /// Which segment.
        segment: Segment,
        /// Its length.
        length: f64,
        /// The smallest accepted length (relative to the configuration's size).
        threshold: f64,
    },
    /// A 3-node segment's mid node folds it: its offset along the chord
    /// from the chord's midpoint reaches a quarter of the chord, where the
    /// segment's tangent vanishes (see the crate's `validate` module docs).
    #[error(
        "folded {segment} segment: its mid node lies {mid_offset} chord lengths from the chord's midpoint along the chord (accepted: strictly within 1/4)"
    )]
    FoldedSegment {
        /// Which segment.
        segment: Segment,
        /// The mid node's offset along the chord from the chord's midpoint,
        /// in chord lengths (`|mid_offset| < 1/4` is accepted).
        mid_offset: f64,
    },
    /// A face's normal (nearly) vanishes: at a corner, `|t_1 x t_2|` is not
    /// above [`crate::DEGENERATE_LENGTH`] times the face's size squared
    /// (see the crate's `faces` module docs).
    #[error(
        "degenerate {face} face: |t1 x t2| = {area:e} at corner {corner} is not above {threshold:e}"
    )]
    DegenerateFace {
        /// Which face.
        face: Segment,
        /// The corner (node index within the face; 0 for a tri3). (A `u8`
        /// keeps `KernelError` at its 2D size.)
        corner: u8,
        /// `|t_1 x t_2|` there.
        area: f64,
        /// The smallest accepted value (relative to the face's size).
        threshold: f64,
    },
    /// A quad4 face folds: at a corner, `t_1 x t_2` does not point the way
    /// of the face's mean normal `(x_3 - x_1) x (x_4 - x_2)`.
    #[error(
        "folded {face} face: the normal at corner {corner} points against the face's mean normal"
    )]
    FoldedFace {
        /// Which face.
        face: Segment,
        /// The corner (node index within the face).
        corner: u8,
    },
    /// The slave point lies outside its face (tri3: `u, v >= 0`, `u + v <=
    /// 1`; quad4: `[-1, 1]^2`).
    #[error("slave point (u, v) = ({u}, {v}) lies outside its face")]
    SlavePointOutside {
        /// `xi_s[0]`.
        u: f64,
        /// `xi_s[1]`.
        v: f64,
    },
    /// The projection equation has no (finite) solution, e.g. for the
    /// slave-normal formulation when the master segment is perpendicular to
    /// the slave segment (`t_m . t_s = 0`).
    #[error(
        "no projection: the projection equation r(q, xi) = 0 has no finite solution (dr/dxi = {r_xi:e})"
    )]
    NoProjection {
        /// The derivative of the projection residual with respect to `xi`
        /// where the solve gave up (for a face: `det A`, the determinant of
        /// the residuals' Jacobian in `(u, v)`).
        r_xi: f64,
    },
    /// The projection was found but lies absurdly far outside the master
    /// segment (`|xi_m|` above [`crate::XI_M_LIMIT`]), where the gap and its
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
    /// The projection was accepted (finite, within reach) but an output of
    /// the kernel is NaN or infinite: the configuration's derivatives
    /// overflow, or the projection is too close to singular for them.
    #[error(
        "non-finite {output} for a configuration whose projection was accepted (xi_m = {xi_m:e})"
    )]
    NonFiniteOutput {
        /// The first non-finite output, in the order gap, gradient, Hessian.
        output: OutputKind,
        /// The projection coordinate the kernel used.
        xi_m: f64,
    },
    /// The coordinate slice does not have the kernel's coordinate count.
    #[error("expected {expected} coordinates, got {found}")]
    CoordinateCount {
        /// The kernel's coordinate count.
        expected: usize,
        /// `q.len()`.
        found: usize,
    },
    /// A caller's output or scratch buffer was sized for another
    /// coordinate count (see [`crate::GapOut::new`]).
    #[error("buffer sized for {found} coordinates, the kernel has {expected}")]
    BufferSize {
        /// The kernel's coordinate count.
        expected: usize,
        /// The coordinate count the buffer was sized for.
        found: usize,
    },
    /// `xi_s` does not have the kernel's parametric dimension (one value
    /// for a segment, two for a face: [`crate::Kernel::param_dim`]).
    #[error("expected {expected} slave parametric coordinate(s), got {found}")]
    ParamCount {
        /// The kernel's parametric dimension.
        expected: usize,
        /// The length of the `xi_s` given (for a batch: values per point
        /// do not divide, `found` is the total).
        found: usize,
    },
    /// This formulation was not compiled in (see the crate's features).
    #[error("formulation `{0}` was not compiled into this build of contact-kernels")]
    NotCompiled(Formulation),
}

/// The two segments (or faces) of a contact pair.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Segment {
    /// The slave segment (the first half of the points: `q[0..4]` for
    /// two-node segments, `q[0..6]` for three-node segments).
    Slave,
    /// The master segment (the second half: `q[4..8]`, or `q[6..12]`).
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

/// A kernel output, as named by [`KernelError::NonFiniteOutput`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OutputKind {
    /// The gap.
    Gap,
    /// The gradient.
    Gradient,
    /// The Hessian.
    Hessian,
    /// The slip ([`crate::Slip::eval`]; its gradient and Hessian are
    /// reported as [`OutputKind::Gradient`] and [`OutputKind::Hessian`]).
    Slip,
}

impl std::fmt::Display for OutputKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            OutputKind::Gap => "gap",
            OutputKind::Gradient => "gradient",
            OutputKind::Hessian => "Hessian",
            OutputKind::Slip => "slip",
        })
    }
}
