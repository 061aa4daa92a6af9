//! 3D faces: validation of a face pair and the projection solve onto a
//! master face (the counterparts of `validate.rs` and `projection.rs` for
//! segments).
//!
//! ## Validation ([`relative_coordinates`])
//!
//! In this order: `q` has the set's coordinate count, every coordinate and
//! both components of `xi_s` are finite, the slave point lies on its face
//! (tri3: `u >= 0`, `v >= 0`, `u + v <= 1`; quad4: `[-1, 1]^2`, edges
//! included), and neither face is degenerate or folded:
//!
//! * **degenerate**: at a corner, `|t_1 x t_2|` (the tangents `dx/du`,
//!   `dx/dv` there; one value for a tri3) is not above
//!   [`crate::DEGENERATE_LENGTH`] times the face's size squared (the size:
//!   the largest coordinate difference between its first node and the
//!   others), [`KernelError::DegenerateFace`];
//! * **folded** (quad4): a corner's `t_1 x t_2` does not point the way of
//!   the face's mean normal `(x_3 - x_1) x (x_4 - x_2)` (their dot product
//!   is not positive), [`KernelError::FoldedFace`].
//!
//! Faces of two kinds in one pair (tri3 on quad4, quad4 on tri3) are
//! checked each by its own kind. The coordinates are then written relative
//! to the first point (slave node 1).
//!
//! ## Projection ([`solve`])
//!
//! On a quad4 master the residual is not affine in `xi`: Newton from
//! `(0, 0)`, at most [`FACE_ITERATIONS`] iterations, until `max|dxi| <=
//! 1e-12 (1 + max|xi|)`; [`KernelError::ProjectionOutOfReach`] once
//! `max|xi|` passes [`crate::XI_M_LIMIT`], [`KernelError::NoProjection`]
//! when `det A = 0` or the step is not finite (its `r_xi` field then holds
//! `det A`), [`KernelError::ProjectionDiverged`] otherwise. On a tri3
//! master the kernels solve it in closed form.

use crate::generated::FaceKernelSet;
use crate::validate::all_finite;
use crate::{DEGENERATE_LENGTH, KernelError, Segment, XI_M_LIMIT};

/// Newton iterations allowed for a face projection.
pub(crate) const FACE_ITERATIONS: usize = 20;

/// A Newton correction below this (relative to `1 + max|xi|`) ends the
/// face projection solve.
const FACE_TOLERANCE: f64 = 1e-12;

/// The dimension of every point of a face.
const DIM: usize = 3;

/// Validates `q` and `xi_s` (two values) for `set` and writes the
/// coordinates relative to the first point into `d` (`d.len() == q.len()`
/// is the caller's).
pub(crate) fn relative_coordinates(
    set: &FaceKernelSet,
    q: &[f64],
    xi_s: [f64; 2],
    d: &mut [f64],
) -> Result<(), KernelError> {
    if q.len() != set.coords {
        return Err(KernelError::CoordinateCount {
            expected: set.coords,
            found: q.len(),
        });
    }
    debug_assert_eq!(d.len(), q.len());
    if !(all_finite(q) && all_finite(&xi_s)) {
        let (index, value) = q
            .iter()
            .chain(&xi_s)
            .copied()
            .enumerate()
            .find(|(_, v)| !v.is_finite())
            .expect("one is not finite");
        return Err(KernelError::NonFinite { index, value });
    }
    let [u, v] = xi_s;
    let inside = if set.slave_nodes == 3 {
        u >= 0.0 && v >= 0.0 && u + v <= 1.0
    } else {
        u.abs() <= 1.0 && v.abs() <= 1.0
    };
    if !inside {
        return Err(KernelError::SlavePointOutside { u, v });
    }
    for (dp, qp) in d.chunks_exact_mut(DIM).zip(q.chunks_exact(DIM)) {
        for k in 0..DIM {
            dp[k] = qp[k] - q[k];
        }
    }
    let slave = &d[..set.slave_nodes * DIM];
    let master = &d[set.slave_nodes * DIM..];
    debug_assert_eq!(master.len(), set.master_nodes * DIM);
    check_face(Segment::Slave, slave)?;
    check_face(Segment::Master, master)
}

fn sub(a: &[f64], b: &[f64]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The degenerate and fold checks of one face (`p`: its nodes, 3 or 4
/// points of three coordinates).
fn check_face(face: Segment, p: &[f64]) -> Result<(), KernelError> {
    let node = |a: usize| &p[a * DIM..(a + 1) * DIM];
    let nodes = p.len() / DIM;
    let size = (1..nodes)
        .flat_map(|a| sub(node(a), node(0)))
        .fold(0.0_f64, |m, c| m.max(c.abs()));
    let threshold = DEGENERATE_LENGTH * size * size;
    // t_1 x t_2 at each corner (quad4: the tangents halved, as dx/du and
    // dx/dv are on [-1, 1]^2).
    let mut all = [[0.0; 3]; 4];
    let corners: &[[f64; 3]] = if nodes == 3 {
        all[0] = cross(sub(node(1), node(0)), sub(node(2), node(0)));
        &all[..1]
    } else {
        let h = |a: [f64; 3]| a.map(|c| 0.5 * c);
        let (e12, e43) = (h(sub(node(1), node(0))), h(sub(node(2), node(3))));
        let (e14, e23) = (h(sub(node(3), node(0))), h(sub(node(2), node(1))));
        all = [
            cross(e12, e14),
            cross(e12, e23),
            cross(e43, e23),
            cross(e43, e14),
        ];
        &all
    };
    for (corner, c) in corners.iter().enumerate() {
        let area2 = dot(*c, *c);
        // Written so that a NaN is also rejected.
        #[allow(clippy::neg_cmp_op_on_partial_ord)]
        if !(area2 > threshold * threshold) {
            return Err(KernelError::DegenerateFace {
                face,
                corner: corner as u8,
                area: area2.sqrt(),
                threshold,
            });
        }
    }
    if nodes == 4 {
        let mean = cross(sub(node(2), node(0)), sub(node(3), node(1)));
        for (corner, c) in corners.iter().enumerate() {
            #[allow(clippy::neg_cmp_op_on_partial_ord)]
            if !(dot(*c, mean) > 0.0) {
                return Err(KernelError::FoldedFace {
                    face,
                    corner: corner as u8,
                });
            }
        }
    }
    Ok(())
}

/// The projection a kernel starts from: `(0, 0)` when the kernels solve it
/// in closed form, Newton's solution otherwise (module docs).
pub(crate) fn start(
    set: &FaceKernelSet,
    d: &[f64],
    xi_s: [f64; 2],
) -> Result<[f64; 2], KernelError> {
    if set.closed_form_projection {
        Ok([0.0; 2])
    } else {
        solve(set, d, xi_s)
    }
}

/// Newton's method on the set's residual from `(0, 0)` (module docs).
pub(crate) fn solve(
    set: &FaceKernelSet,
    d: &[f64],
    xi_s: [f64; 2],
) -> Result<[f64; 2], KernelError> {
    let mut xi = [0.0_f64; 2];
    let mut last_step = f64::INFINITY;
    for _ in 0..FACE_ITERATIONS {
        let [r0, r1, a00, a01, a10, a11] = (set.residual)(d, &xi_s, &xi);
        let det = a00 * a11 - a01 * a10;
        let du = (a11 * r0 - a01 * r1) / det;
        let dv = (a00 * r1 - a10 * r0) / det;
        if det == 0.0 || !(du.is_finite() && dv.is_finite()) {
            return Err(KernelError::NoProjection { r_xi: det });
        }
        xi = [xi[0] - du, xi[1] - dv];
        let reach = xi[0].abs().max(xi[1].abs());
        if reach > XI_M_LIMIT {
            return Err(KernelError::ProjectionOutOfReach {
                xi_m: if xi[0].abs() >= xi[1].abs() {
                    xi[0]
                } else {
                    xi[1]
                },
            });
        }
        last_step = du.abs().max(dv.abs());
        if last_step <= FACE_TOLERANCE * (1.0 + reach) {
            return Ok(xi);
        }
    }
    Err(KernelError::ProjectionDiverged {
        iterations: FACE_ITERATIONS,
        last_step,
    })
}

/// Rejects a projection the kernel could not find (non-finite: `det A`
/// vanished) or that lies out of reach.
pub(crate) fn check(
    set: &FaceKernelSet,
    d: &[f64],
    xi_s: [f64; 2],
    xi_m: [f64; 2],
) -> Result<(), KernelError> {
    if !(xi_m[0].is_finite() && xi_m[1].is_finite()) {
        let [_, _, a00, a01, a10, a11] = (set.residual)(d, &xi_s, &[0.0; 2]);
        return Err(KernelError::NoProjection {
            r_xi: a00 * a11 - a01 * a10,
        });
    }
    for x in xi_m {
        if x.abs() > XI_M_LIMIT {
            return Err(KernelError::ProjectionOutOfReach { xi_m: x });
        }
    }
    Ok(())
}
