//! [`Kernel::eval_batch`](super::Kernel::eval_batch) for 3D faces: the
//! points in groups of [`LANES`], one call of the face lane kernel per
//! group.
//!
//! Per group:
//!
//! 1. each point is validated and its projection started by the scalar
//!    path's own functions (`faces::relative_coordinates`, `faces::start`:
//!    Newton on a quad4 master), so a point that fails there gets exactly
//!    [`Kernel::eval`](super::Kernel::eval)'s error; its relative
//!    coordinates, `xi_s` and starting `xi_m` go into its lane. A failed
//!    point's lane (like the lanes past the end of a short last group)
//!    computes on zeros whose results are discarded;
//! 2. the lane kernel evaluates all lanes at once; lane `l` holds the
//!    scalar kernel's bits for point `l`;
//! 3. a lane is accepted when both components of its `xi_m` pass
//!    `faces::check`'s tests and every output is finite (the scalar path's
//!    checks). Any other lane is evaluated again by the scalar path, which
//!    names its error;
//! 4. accepted lanes are scattered into the [`GapBatch`] (4 x 4 transposes,
//!    with AVX2 shuffles in the AVX2 build, when the whole group is valid).
//!
//! Compiled twice like the segments' batch: for the target's baseline and,
//! on x86-64, for AVX2 (no FMA).

use super::batch::scatter;
use super::{Faces, GapBatch};
use crate::faces;
use crate::generated_lanes::{FaceLaneKernel, LaneIsa};
use crate::lanes::{LANES, Lanes};
use crate::projection::XI_M_LIMIT;

impl Faces {
    /// Evaluates every point of `xi_s` (two values each) into `out`
    /// (shapes checked and `out` prepared by the caller); returns how many
    /// succeeded.
    pub(super) fn eval_lanes(&self, qs: &[f64], xi_s: &[f64], out: &mut GapBatch) -> usize {
        match self.lane_isa {
            // SAFETY: `lane_isa` is AVX2 only when the CPU supports it
            // (`generated_lanes::select`).
            #[cfg(target_arch = "x86_64")]
            LaneIsa::Avx2 => unsafe { eval_all_avx2(self, qs, xi_s, out) },
            _ => eval_all::<false>(self, qs, xi_s, out),
        }
    }

    /// Point `p` through the scalar path (for its exact error); whether it
    /// succeeded.
    #[cold]
    #[inline(never)]
    fn eval_point_scalar(&self, p: usize, qs: &[f64], xi_s: &[f64], out: &mut GapBatch) -> bool {
        let n = self.set.coords;
        let nn = if out.has_hessian { n * n } else { 0 };
        let q = &qs[p * n..(p + 1) * n];
        let grad = &mut out.grad[p * n..(p + 1) * n];
        let hess = &mut out.hess[p * nn..(p + 1) * nn];
        let xi = [xi_s[2 * p], xi_s[2 * p + 1]];
        match self.eval_into(q, xi, &mut out.scratch, grad, hess) {
            Ok((gap, xi_m)) => {
                out.gap[p] = gap;
                out.xi_m[2 * p..2 * p + 2].copy_from_slice(&xi_m);
                out.status[p] = None;
                true
            }
            Err(e) => {
                out.fail(p, e);
                false
            }
        }
    }
}

/// [`eval_all`] compiled for AVX2.
///
/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn eval_all_avx2(k: &Faces, qs: &[f64], xi_s: &[f64], out: &mut GapBatch) -> usize {
    eval_all::<true>(k, qs, xi_s, out)
}

/// Every group; returns how many points succeeded.
#[inline(always)]
fn eval_all<const AVX2: bool>(k: &Faces, qs: &[f64], xi_s: &[f64], out: &mut GapBatch) -> usize {
    let points = xi_s.len() / 2;
    let mut ok = 0;
    let mut first = 0;
    while first < points {
        let count = LANES.min(points - first);
        ok += eval_group::<AVX2>(k, first, count, qs, xi_s, out);
        first += LANES;
    }
    ok
}

/// Points `first..first + count` (`count <= LANES`); returns how many
/// succeeded.
#[inline(always)]
fn eval_group<const AVX2: bool>(
    k: &Faces,
    first: usize,
    count: usize,
    qs: &[f64],
    xi_s: &[f64],
    out: &mut GapBatch,
) -> usize {
    let set = k.set;
    let n = set.coords;
    let mut xi_s_l = [Lanes::ZERO; 2];
    let mut xi_m_l = [Lanes::ZERO; 2];
    let mut valid = [false; LANES];
    for (l, valid) in valid.iter_mut().enumerate() {
        if l < count {
            let p = first + l;
            let xi = [xi_s[2 * p], xi_s[2 * p + 1]];
            let d = &mut out.scratch;
            let started = faces::relative_coordinates(set, &qs[p * n..(p + 1) * n], xi, d)
                .and_then(|()| faces::start(set, d, xi));
            match started {
                Ok(xi_m) => {
                    for (dl, &v) in out.lanes.d.iter_mut().zip(d.iter()) {
                        dl.0[l] = v;
                    }
                    for c in 0..2 {
                        xi_s_l[c].0[l] = xi[c];
                        xi_m_l[c].0[l] = xi_m[c];
                    }
                    *valid = true;
                    continue;
                }
                Err(e) => out.fail(p, e),
            }
        }
        for dl in &mut out.lanes.d {
            dl.0[l] = 0.0;
        }
    }
    if !valid.contains(&true) {
        return 0;
    }
    let buf = &mut out.lanes;
    // SAFETY: `generated_lanes::select` returns an AVX2 kernel only when
    // the CPU supports AVX2; the buffers have the lengths the kernels
    // reslice to (`n`, `n * n`, two for `xi_s` and `xi_m`).
    let (gap_l, hessian) = unsafe {
        match k.lanes {
            FaceLaneKernel::Gradient(f) => (f(&buf.d, &xi_s_l, &mut xi_m_l, &mut buf.grad), false),
            FaceLaneKernel::Hessian(f) => (
                f(&buf.d, &xi_s_l, &mut xi_m_l, &mut buf.grad, &mut buf.hess),
                true,
            ),
        }
    };
    // The lane's outputs are all finite when their sum is (a NaN or an
    // infinity makes it non-finite; an overflowing sum of finite values
    // only sends the point through the scalar path, which decides).
    if count == LANES && !valid.contains(&false) {
        // The common case: scatter first (summing on the way), then send
        // any lane that fails a check through the scalar path, which
        // rewrites or zeroes all of its point's entries.
        let sum = out.accept_all_faces::<AVX2>(first, gap_l, xi_m_l, hessian);
        let mut ok = 0;
        for l in 0..LANES {
            if accepted(sum, xi_m_l, l) {
                ok += 1;
            } else {
                ok += usize::from(k.eval_point_scalar(first + l, qs, xi_s, out));
            }
        }
        return ok;
    }
    let buf = &out.lanes;
    let mut sum = buf.grad.iter().fold(gap_l, |s, v| s + *v);
    if hessian {
        sum = buf.hess.iter().fold(sum, |s, v| s + *v);
    }
    let mut ok = 0;
    for l in (0..count).filter(|&l| valid[l]) {
        let p = first + l;
        if accepted(sum, xi_m_l, l) {
            out.accept_face(p, l, gap_l.0[l], [xi_m_l[0].0[l], xi_m_l[1].0[l]], hessian);
            ok += 1;
        } else {
            ok += usize::from(k.eval_point_scalar(p, qs, xi_s, out));
        }
    }
    ok
}

/// Whether lane `l` passes the scalar path's checks: every output finite
/// (`sum`, the sum of its outputs, is finite) and `faces::check`'s tests
/// on both components of `xi_m` (written so that NaN fails them).
#[inline(always)]
fn accepted(sum: Lanes, xi_m: [Lanes; 2], l: usize) -> bool {
    sum.0[l].is_finite() && xi_m[0].0[l].abs() <= XI_M_LIMIT && xi_m[1].0[l].abs() <= XI_M_LIMIT
}

impl GapBatch {
    /// Point `p` takes lane `l` of the lane buffers (a face: `xi_m` of two
    /// values).
    #[inline(always)]
    fn accept_face(&mut self, p: usize, l: usize, gap: f64, xi_m: [f64; 2], hessian: bool) {
        let n = self.coords;
        self.gap[p] = gap;
        self.xi_m[2 * p..2 * p + 2].copy_from_slice(&xi_m);
        self.status[p] = None;
        for (g, v) in self.grad[p * n..(p + 1) * n]
            .iter_mut()
            .zip(&self.lanes.grad)
        {
            *g = v.0[l];
        }
        if hessian {
            for (h, v) in self.hess[p * n * n..(p + 1) * n * n]
                .iter_mut()
                .zip(&self.lanes.hess)
            {
                *h = v.0[l];
            }
        }
    }

    /// Points `first..first + LANES` of faces take the lane buffers;
    /// returns the sum of each lane's outputs (gap, gradient, Hessian).
    #[inline(always)]
    fn accept_all_faces<const AVX2: bool>(
        &mut self,
        first: usize,
        gap: Lanes,
        xi_m: [Lanes; 2],
        hessian: bool,
    ) -> Lanes {
        let (n, range) = (self.coords, first..first + LANES);
        self.gap[range.clone()].copy_from_slice(&gap.0);
        for l in 0..LANES {
            let p = first + l;
            self.xi_m[2 * p] = xi_m[0].0[l];
            self.xi_m[2 * p + 1] = xi_m[1].0[l];
        }
        self.status[range].fill(None);
        let grad = &mut self.grad[first * n..(first + LANES) * n];
        let sum = scatter::<AVX2>(&self.lanes.grad, grad, gap);
        if !hessian {
            return sum;
        }
        let nn = n * n;
        scatter::<AVX2>(
            &self.lanes.hess,
            &mut self.hess[first * nn..(first + LANES) * nn],
            sum,
        )
    }
}
