//! The one validation point: raw input in, validated relative coordinates
//! or a [`KernelError`] out.
//!
//! [`relative_coordinates`] checks, in this order, that `q` has the kernel
//! set's coordinate count, that every coordinate and `xi_s` is finite, and
//! that neither segment is degenerate; it writes the coordinates relative to
//! the first point (slave node 1) into the caller's buffer. All kernels
//! depend on coordinate differences only, so this keeps their accuracy far
//! from the origin.
//!
//! ## Segment layout
//!
//! The points are a slave segment's nodes followed by a master segment's
//! nodes, equally many each: two and two for straight segments, three and
//! three for quadratic segments (Gmsh line3 order: the end nodes, then the
//! mid node). A segment is degenerate when the chord between its end nodes
//! (its first and second node) is shorter than [`DEGENERATE_LENGTH`] times
//! the configuration's size (the largest relative coordinate).
//!
//! A 3-node segment `x(xi) = N1 a + N2 b + N3 m` (ends `a`, `b`, mid node
//! `m`) has the tangent `t(xi) = (b - a) / 2 + xi (a + b - 2 m)`. It is
//! **folded** when `t . (b - a)` is not positive on all of `[-1, 1]`: the
//! mid node's offset along the chord from the chord's midpoint,
//! `s = (m - (a + b) / 2) . (b - a) / |b - a|^2`, reaches a quarter of the
//! chord (`|s| >= 1/4`: at the quarter point the tangent vanishes at an end,
//! beyond it the segment runs backwards). [`KernelError::FoldedSegment`]
//! rejects `1 - 4 |s| <= `[`DEGENERATE_LENGTH`] (the smallest end tangent's
//! chord component relative to the midpoint's), so an accepted 3-node
//! segment has a tangent that never vanishes.

use crate::generated::KernelSet;
use crate::lanes::{LANES, Lanes};
use crate::{KernelError, Segment};

/// A segment shorter than this times the configuration's size is degenerate.
pub const DEGENERATE_LENGTH: f64 = 1e-10;

/// The dimension of every point: the formulation language's values are
/// 2-vectors (`KernelSet::dim` records it). A constant, so that the loops
/// below unroll when the coordinate count is known at the call site.
const DIM: usize = 2;

/// Validates `q` and `xi_s` for `set` and writes the coordinates relative
/// to the first point into `d` (`d.len() == q.len()` is the caller's).
#[inline]
pub(crate) fn relative_coordinates(
    set: &KernelSet,
    q: &[f64],
    xi_s: f64,
    d: &mut [f64],
) -> Result<(), KernelError> {
    debug_assert_eq!(set.dim, DIM);
    relative_coordinates_n(set.coords, q, xi_s, d)
}

/// [`relative_coordinates`] for kernels of `coords` coordinates (segment
/// pairs of two-dimensional points) given at run time
/// ([`crate::runtime`]).
#[inline]
pub(crate) fn relative_coordinates_n(
    coords: usize,
    q: &[f64],
    xi_s: f64,
    d: &mut [f64],
) -> Result<(), KernelError> {
    if q.len() != coords {
        return Err(KernelError::CoordinateCount {
            expected: coords,
            found: q.len(),
        });
    }
    debug_assert_eq!(d.len(), q.len());
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
    for (dp, qp) in d.chunks_exact_mut(DIM).zip(q.chunks_exact(DIM)) {
        for k in 0..DIM {
            dp[k] = qp[k] - q[k];
        }
    }
    let size = d.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let threshold = DEGENERATE_LENGTH * size;
    let points = q.len() / DIM;
    let half = points / 2;
    // The end nodes: the first two of each segment (for two-node segments
    // the first and last).
    for (segment, first, last) in [(Segment::Slave, 0, 1), (Segment::Master, half, half + 1)] {
        // Squared lengths: no hypot in the hot path. (Configurations with
        // coordinates below ~1e-150 underflow here and are reported as
        // degenerate.)
        let (a, b) = (first * DIM, last * DIM);
        let mut length2 = 0.0;
        for k in 0..DIM {
            let c = d[b + k] - d[a + k];
            length2 += c * c;
        }
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
    if half == 3 {
        for (segment, first) in [(Segment::Slave, 0), (Segment::Master, half)] {
            check_fold(segment, &d[first * DIM..(first + 3) * DIM])?;
        }
    }
    Ok(())
}

/// Rejects a folded 3-node segment (module docs): `p` holds its end nodes
/// and its mid node, relative coordinates, after the chord check (the chord
/// is not zero).
#[inline]
fn check_fold(segment: Segment, p: &[f64]) -> Result<(), KernelError> {
    let mut chord2 = 0.0;
    let mut along = 0.0;
    for k in 0..DIM {
        let c = p[DIM + k] - p[k];
        chord2 += c * c;
        // a + b - 2 m: the tangent's rate of change along the segment.
        along += (p[k] + p[DIM + k] - 2.0 * p[2 * DIM + k]) * c;
    }
    // t(+-1) . (b - a) = chord2 / 2 +- along must stay positive, with
    // margin: chord2 / 2 - |along| > DEGENERATE_LENGTH * chord2 / 2.
    let half_chord2 = 0.5 * chord2;
    // Written so that a NaN is also rejected.
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    if !(half_chord2 - along.abs() > DEGENERATE_LENGTH * half_chord2) {
        return Err(KernelError::FoldedSegment {
            segment,
            mid_offset: -along / (2.0 * chord2),
        });
    }
    Ok(())
}

/// [`relative_coordinates`]' checks and arithmetic for [`LANES`] points at
/// once (the batch): `d` holds on entry coordinate `i` of every point in
/// `d[i]` (`n` values; the coordinate count is the caller's) and receives
/// the relative coordinates, bit for bit the scalar ones; `xi_s` holds the
/// points' slave parameters. Returns, per lane, whether the point passed
/// every check.
///
/// A point that did not pass is to be validated again by
/// [`relative_coordinates`], which decides and names its error: this test
/// may reject a valid point (its finiteness test is that the sum of the
/// inputs is finite, which overflows for inputs near `f64::MAX`) but never
/// accepts one the scalar checks reject (a NaN or infinite input makes the
/// sum non-finite; the segment tests are the scalar comparisons).
#[inline(always)]
pub(crate) fn relative_coordinates_lanes(d: &mut [Lanes], xi_s: Lanes) -> [bool; LANES] {
    let sum = d.iter().fold(xi_s, |s, v| s + *v);
    let origin: [Lanes; DIM] = std::array::from_fn(|k| d[k]);
    for dp in d.chunks_exact_mut(DIM) {
        for k in 0..DIM {
            dp[k] = dp[k] - origin[k];
        }
    }
    // The scalar fold of `max(|v|)`: the same value for finite input (the
    // only input that can pass).
    let size = d.iter().fold(Lanes::ZERO, |m, v| m.max_finite(v.abs()));
    let threshold = Lanes::splat(DEGENERATE_LENGTH) * size;
    let threshold2 = threshold * threshold;
    let points = d.len() / DIM;
    let half = points / 2;
    let mut pass = sum.0.map(f64::is_finite);
    for (first, last) in [(0, half - 1), (half, points - 1)] {
        let (a, b) = (first * DIM, last * DIM);
        let mut length2 = Lanes::ZERO;
        for k in 0..DIM {
            let c = d[b + k] - d[a + k];
            length2 = length2 + c * c;
        }
        for ((pass, length2), threshold2) in pass.iter_mut().zip(length2.0).zip(threshold2.0) {
            // As in the scalar check: a NaN length fails too.
            *pass &= length2 > threshold2;
        }
    }
    pass
}

/// Whether every value is finite, with integer operations that vectorise:
/// a value is NaN or infinite exactly when its exponent bits are all ones,
/// i.e. when adding one to the exponent field carries into the sign bit.
#[inline]
pub(crate) fn all_finite(v: &[f64]) -> bool {
    const EXPONENT: u64 = 0x7ff0_0000_0000_0000;
    const EXPONENT_ONE: u64 = 0x0010_0000_0000_0000;
    v.iter().fold(0u64, |acc, x| {
        acc | ((x.to_bits() & EXPONENT) + EXPONENT_ONE)
    }) >> 63
        == 0
}
