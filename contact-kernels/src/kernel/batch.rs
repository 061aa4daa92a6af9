//! [`Kernel::eval_batch`](super::Kernel::eval_batch)'s evaluation, one
//! driver for every [`ParamKernel`] (segments, `P = 1`; faces, `P = 2`): the
//! points in groups of [`LANES`], one call of the lane kernel per group.
//!
//! Per group:
//!
//! 1. the points' coordinates are validated in lanes where the kernel can
//!    (segments: gathered into lanes, structure of arrays, and checked by
//!    `validate::relative_coordinates_lanes`, the scalar checks' decisions
//!    and the scalar relative coordinates; faces: nowhere). A point the
//!    lanes do not pass, or whose projection is not in closed form, is
//!    validated and its projection started by the scalar path's own
//!    functions ([`ParamKernel::relative_coordinates`],
//!    [`ParamKernel::start`]: Newton where the kernels do not solve it), so
//!    a point that fails there gets exactly
//!    [`Kernel::eval`](super::Kernel::eval)'s error. A failed point's lane
//!    (like the lanes past the end of a short last group) computes on zeros
//!    whose results are discarded;
//! 2. the lane kernel evaluates all lanes at once; lane `l` holds the
//!    scalar kernel's bits for point `l`;
//! 3. a lane is accepted when every component of its `xi_m` passes the
//!    projection check's tests and every output is finite (the scalar
//!    path's two checks). Any other lane is evaluated again by the scalar
//!    path, so a failing point reports exactly the error
//!    [`Kernel::eval`](super::Kernel::eval) reports (no projection, out of
//!    reach, non-finite output), never a second opinion;
//! 4. accepted lanes are scattered into the [`GapBatch`] (4 x 4 transposes
//!    when the whole group is accepted).
//!
//! The whole evaluation is compiled twice, like the lane kernels: for the
//! target's baseline and, on x86-64, for AVX2 (no FMA), and runs in the
//! copy of the kernel's [`Kernel::lane_isa`](super::Kernel::lane_isa). A
//! failed point is zeroed and carries its error ([`GapBatch::status`]).

use super::GapBatch;
use super::param_kernel::{ParamKernel, eval_point};
use crate::KernelError;
use crate::generated_lanes::LaneIsa;
use crate::lanes::{LANES, Lanes};
use crate::projection::XI_M_LIMIT;

/// The lane kernel's buffers: relative coordinates, gradient and Hessian
/// (full, row-major), `LANES` points each.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct LaneBuffers {
    pub(super) d: Vec<Lanes>,
    pub(super) grad: Vec<Lanes>,
    pub(super) hess: Vec<Lanes>,
}

impl LaneBuffers {
    /// Buffers for kernels of `n` coordinates.
    pub(super) fn new(n: usize) -> LaneBuffers {
        LaneBuffers {
            d: vec![Lanes::ZERO; n],
            grad: vec![Lanes::ZERO; n],
            hess: vec![Lanes::ZERO; n * n],
        }
    }
}

/// Evaluates every point of `xi_s` (`P` values each) into `out` (shapes
/// checked and `out` prepared by the caller); returns how many succeeded.
pub(super) fn eval_lanes<K: ParamKernel<P>, const P: usize>(
    k: &K,
    qs: &[f64],
    xi_s: &[f64],
    out: &mut GapBatch,
) -> usize {
    match k.lane_isa() {
        // SAFETY: `lane_isa` is AVX2 only when the CPU supports it
        // (`generated_lanes::select`).
        #[cfg(target_arch = "x86_64")]
        LaneIsa::Avx2 => unsafe { eval_all_avx2(k, qs, xi_s, out) },
        _ => eval_all::<K, P, false>(k, qs, xi_s, out),
    }
}

/// Point `p` through the scalar path (for its exact error); whether it
/// succeeded.
#[cold]
#[inline(never)]
fn eval_point_scalar<K: ParamKernel<P>, const P: usize>(
    k: &K,
    p: usize,
    qs: &[f64],
    xi_s: &[f64],
    out: &mut GapBatch,
) -> bool {
    let n = k.coords();
    let nn = if out.has_hessian { n * n } else { 0 };
    let q = &qs[p * n..(p + 1) * n];
    let grad = &mut out.grad[p * n..(p + 1) * n];
    let hess = &mut out.hess[p * nn..(p + 1) * nn];
    let xi = std::array::from_fn(|c| xi_s[P * p + c]);
    match eval_point(k, q, xi, &mut out.scratch, grad, hess) {
        Ok((gap, xi_m)) => {
            out.gap[p] = gap;
            out.xi_m[P * p..P * (p + 1)].copy_from_slice(&xi_m);
            out.status[p] = None;
            true
        }
        Err(e) => {
            out.fail(p, e);
            false
        }
    }
}

/// [`eval_all`] compiled for AVX2.
///
/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn eval_all_avx2<K: ParamKernel<P>, const P: usize>(
    k: &K,
    qs: &[f64],
    xi_s: &[f64],
    out: &mut GapBatch,
) -> usize {
    eval_all::<K, P, true>(k, qs, xi_s, out)
}

/// Every group; returns how many points succeeded. `AVX2`: the caller runs
/// with AVX2 enabled (the gather and scatter use its shuffles).
#[inline(always)]
fn eval_all<K: ParamKernel<P>, const P: usize, const AVX2: bool>(
    k: &K,
    qs: &[f64],
    xi_s: &[f64],
    out: &mut GapBatch,
) -> usize {
    let points = xi_s.len() / P;
    let mut ok = 0;
    let mut first = 0;
    while first < points {
        let count = LANES.min(points - first);
        ok += eval_group::<K, P, AVX2>(k, first, count, qs, xi_s, out);
        first += LANES;
    }
    ok
}

/// Points `first..first + count` (`count <= LANES`); returns how many
/// succeeded.
#[inline(always)]
fn eval_group<K: ParamKernel<P>, const P: usize, const AVX2: bool>(
    k: &K,
    first: usize,
    count: usize,
    qs: &[f64],
    xi_s: &[f64],
    out: &mut GapBatch,
) -> usize {
    let n = k.coords();
    let mut xi_s_l = [Lanes::ZERO; P];
    for l in 0..count {
        for (c, x) in xi_s_l.iter_mut().enumerate() {
            x.0[l] = xi_s[P * (first + l) + c];
        }
    }
    let (mut valid, start_all) = k.validate_lanes::<AVX2>(
        &qs[first * n..(first + count) * n],
        &mut out.lanes.d,
        &xi_s_l,
    );
    valid[count..].fill(false);
    let mut xi_m_l = [Lanes::ZERO; P];
    for (l, valid) in valid.iter_mut().enumerate() {
        if !*valid || start_all {
            let started = (l < count).then(|| start_lane(k, first + l, l, qs, xi_s, out));
            match started {
                Some(Ok(xi_m)) => {
                    for (x, v) in xi_m_l.iter_mut().zip(xi_m) {
                        x.0[l] = v;
                    }
                    *valid = true;
                }
                Some(Err(e)) => {
                    out.fail(first + l, e);
                    *valid = false;
                }
                None => {}
            }
            if !*valid {
                for dl in &mut out.lanes.d {
                    dl.0[l] = 0.0;
                }
            }
        }
    }
    if !valid.contains(&true) {
        return 0;
    }
    let buf = &mut out.lanes;
    // SAFETY: `generated_lanes::select` returns an AVX2 kernel only when
    // the CPU supports AVX2; the buffers have the lengths the kernels
    // reslice to (`n`, `n * n`).
    let (gap_l, hessian) =
        unsafe { k.run_lanes(&buf.d, &xi_s_l, &mut xi_m_l, &mut buf.grad, &mut buf.hess) };
    // The lane's outputs are all finite when their sum is (a NaN or an
    // infinity makes it non-finite; an overflowing sum of finite values
    // only sends the point through the scalar path, which decides).
    if count == LANES && !valid.contains(&false) {
        // The common case: scatter first (summing on the way), then send
        // any lane that fails a check through the scalar path, which
        // rewrites or zeroes all of its point's entries.
        let sum = out.accept_all::<P, AVX2>(first, gap_l, &xi_m_l, hessian);
        let mut ok = 0;
        for l in 0..LANES {
            if accepted(sum, &xi_m_l, l) {
                ok += 1;
            } else {
                ok += usize::from(eval_point_scalar(k, first + l, qs, xi_s, out));
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
        if accepted(sum, &xi_m_l, l) {
            out.accept(p, l, gap_l.0[l], xi_m_l.map(|x| x.0[l]), hessian);
            ok += 1;
        } else {
            ok += usize::from(eval_point_scalar(k, p, qs, xi_s, out));
        }
    }
    ok
}

/// Lane `l` (point `p`) when the lanes cannot decide alone: the scalar
/// validation for a lane that failed the lane checks (its error, or its
/// relative coordinates, which go into the lane), then the projection's
/// start.
#[cold]
#[inline(never)]
fn start_lane<K: ParamKernel<P>, const P: usize>(
    k: &K,
    p: usize,
    l: usize,
    qs: &[f64],
    xi_s: &[f64],
    out: &mut GapBatch,
) -> Result<[f64; P], KernelError> {
    let n = k.coords();
    let xi = std::array::from_fn(|c| xi_s[P * p + c]);
    let d = &mut out.scratch;
    k.relative_coordinates(&qs[p * n..(p + 1) * n], xi, d)?;
    for (dl, &v) in out.lanes.d.iter_mut().zip(d.iter()) {
        dl.0[l] = v;
    }
    k.start(d, xi)
}

/// Whether lane `l` passes the scalar path's checks: every output finite
/// (`sum`, the sum of its outputs, is finite) and the projection check's
/// tests on every component of `xi_m` (written so that NaN fails them).
#[inline(always)]
pub(super) fn accepted<const P: usize>(sum: Lanes, xi_m: &[Lanes; P], l: usize) -> bool {
    sum.0[l].is_finite() && xi_m.iter().all(|x| x.0[l].abs() <= XI_M_LIMIT)
}

/// `qs` (up to `LANES` points of `d.len()` coordinates each, point-major)
/// into lanes: `d[i].0[l] = qs[l n + i]`; lanes past the points are zero.
/// With `AVX2` (which the caller must have enabled), a full group goes
/// through 4 x 4 transposes in registers.
#[inline(always)]
pub(super) fn gather<const AVX2: bool>(qs: &[f64], d: &mut [Lanes]) {
    let n = d.len();
    #[cfg(target_arch = "x86_64")]
    if AVX2 && qs.len() == LANES * n {
        // SAFETY: `AVX2` is true only in `eval_all_avx2`, which runs on a
        // CPU with AVX2.
        unsafe { gather_avx2(qs, d) };
        return;
    }
    if qs.len() == LANES * n {
        let (q0, rest) = qs.split_at(n);
        let (q1, rest) = rest.split_at(n);
        let (q2, q3) = rest.split_at(n);
        for (i, dl) in d.iter_mut().enumerate() {
            *dl = Lanes([q0[i], q1[i], q2[i], q3[i]]);
        }
    } else {
        for (i, dl) in d.iter_mut().enumerate() {
            *dl = Lanes(std::array::from_fn(|l| {
                qs.get(l * n + i).copied().unwrap_or(0.0)
            }));
        }
    }
}

/// Lanes into `LANES` consecutive rows of `src.len()` values each:
/// `rows[l len + i] = src[i].0[l]`, four entries at a time (a 4 x 4
/// transpose per block; with `AVX2`, which the caller must have enabled, in
/// four shuffles and four 256-bit stores).
#[inline(always)]
fn scatter<const AVX2: bool>(src: &[Lanes], rows: &mut [f64], sum: Lanes) -> Lanes {
    #[cfg(target_arch = "x86_64")]
    if AVX2 {
        // SAFETY: `AVX2` is true only in `eval_all_avx2`, which runs on a
        // CPU with AVX2.
        return unsafe { scatter_avx2(src, rows, sum) };
    }
    let len = src.len();
    let (r0, rest) = rows.split_at_mut(len);
    let (r1, rest) = rest.split_at_mut(len);
    let (r2, r3) = rest.split_at_mut(len);
    let blocks = len / 4 * 4;
    for b in (0..blocks).step_by(4) {
        let [a, bb, c, d] = [src[b].0, src[b + 1].0, src[b + 2].0, src[b + 3].0];
        r0[b..b + 4].copy_from_slice(&[a[0], bb[0], c[0], d[0]]);
        r1[b..b + 4].copy_from_slice(&[a[1], bb[1], c[1], d[1]]);
        r2[b..b + 4].copy_from_slice(&[a[2], bb[2], c[2], d[2]]);
        r3[b..b + 4].copy_from_slice(&[a[3], bb[3], c[3], d[3]]);
    }
    for i in blocks..len {
        let v = src[i].0;
        (r0[i], r1[i], r2[i], r3[i]) = (v[0], v[1], v[2], v[3]);
    }
    src.iter().fold(sum, |s, v| s + *v)
}

/// The 4 x 4 transpose of the rows `a`, `e`, `c`, `d`: the columns.
///
/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
unsafe fn transpose4(
    a: std::arch::x86_64::__m256d,
    e: std::arch::x86_64::__m256d,
    c: std::arch::x86_64::__m256d,
    d: std::arch::x86_64::__m256d,
) -> [std::arch::x86_64::__m256d; 4] {
    use std::arch::x86_64::{_mm256_permute2f128_pd, _mm256_unpackhi_pd, _mm256_unpacklo_pd};
    let ae_even = _mm256_unpacklo_pd(a, e); // a0 e0 a2 e2
    let ae_odd = _mm256_unpackhi_pd(a, e); // a1 e1 a3 e3
    let cd_even = _mm256_unpacklo_pd(c, d); // c0 d0 c2 d2
    let cd_odd = _mm256_unpackhi_pd(c, d); // c1 d1 c3 d3
    [
        _mm256_permute2f128_pd(ae_even, cd_even, 0x20),
        _mm256_permute2f128_pd(ae_odd, cd_odd, 0x20),
        _mm256_permute2f128_pd(ae_even, cd_even, 0x31),
        _mm256_permute2f128_pd(ae_odd, cd_odd, 0x31),
    ]
}

/// [`gather`] of a full group with AVX2 shuffles.
///
/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
unsafe fn gather_avx2(qs: &[f64], d: &mut [Lanes]) {
    use std::arch::x86_64::{_mm256_loadu_pd, _mm256_store_pd};
    let n = d.len();
    assert_eq!(qs.len(), LANES * n, "LANES points of d.len() coordinates");
    let blocks = n / 4 * 4;
    for b in (0..blocks).step_by(4) {
        // SAFETY: the loads read qs[l n + b..l n + b + 4] for l < 4, inside
        // `qs` (asserted); `Lanes` is 32-byte aligned.
        unsafe {
            let base = qs.as_ptr().add(b);
            let rows = [0, 1, 2, 3].map(|l| _mm256_loadu_pd(base.add(l * n)));
            let columns = transpose4(rows[0], rows[1], rows[2], rows[3]);
            for (k, column) in columns.into_iter().enumerate() {
                _mm256_store_pd(d[b + k].0.as_mut_ptr(), column);
            }
        }
    }
    for (i, dl) in d.iter_mut().enumerate().skip(blocks) {
        *dl = Lanes([qs[i], qs[n + i], qs[2 * n + i], qs[3 * n + i]]);
    }
}

/// [`scatter`] with AVX2 shuffles.
///
/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
unsafe fn scatter_avx2(src: &[Lanes], rows: &mut [f64], sum: Lanes) -> Lanes {
    use std::arch::x86_64::{_mm256_add_pd, _mm256_load_pd, _mm256_store_pd, _mm256_storeu_pd};
    let len = src.len();
    assert_eq!(rows.len(), LANES * len, "LANES rows of src.len() values");
    let blocks = len / 4 * 4;
    // Four partial sums (of blocks' first, second, third and fourth rows),
    // added at the end: independent chains.
    let mut sums = [sum, Lanes::ZERO, Lanes::ZERO, Lanes::ZERO];
    for b in (0..blocks).step_by(4) {
        // SAFETY: `Lanes` is 32-byte aligned; the stores write
        // rows[l len + b..l len + b + 4] for l < 4, inside `rows` (asserted).
        unsafe {
            let columns = [0, 1, 2, 3].map(|k| _mm256_load_pd(src[b + k].0.as_ptr()));
            for (s, v) in sums.iter_mut().zip(columns) {
                _mm256_store_pd(
                    s.0.as_mut_ptr(),
                    _mm256_add_pd(_mm256_load_pd(s.0.as_ptr()), v),
                );
            }
            let transposed = transpose4(columns[0], columns[1], columns[2], columns[3]);
            let base = rows.as_mut_ptr().add(b);
            for (l, row) in transposed.into_iter().enumerate() {
                _mm256_storeu_pd(base.add(l * len), row);
            }
        }
    }
    for i in blocks..len {
        for l in 0..LANES {
            rows[l * len + i] = src[i].0[l];
        }
        sums[0] = sums[0] + src[i];
    }
    (sums[0] + sums[1]) + (sums[2] + sums[3])
}

impl GapBatch {
    /// Point `p` failed with `e`: zero entries, the error as its status.
    pub(super) fn fail(&mut self, p: usize, e: KernelError) {
        let (n, k) = (self.coords, self.param_dim);
        self.gap[p] = 0.0;
        self.xi_m[p * k..(p + 1) * k].fill(0.0);
        self.grad[p * n..(p + 1) * n].fill(0.0);
        if self.has_hessian {
            self.hess[p * n * n..(p + 1) * n * n].fill(0.0);
        }
        self.status[p] = Some(e);
    }

    /// Point `p` takes lane `l` of the lane buffers.
    #[inline(always)]
    fn accept<const P: usize>(
        &mut self,
        p: usize,
        l: usize,
        gap: f64,
        xi_m: [f64; P],
        hessian: bool,
    ) {
        let n = self.coords;
        self.gap[p] = gap;
        self.xi_m[P * p..P * (p + 1)].copy_from_slice(&xi_m);
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

    /// Points `first..first + LANES` take the lane buffers; returns the sum
    /// of each lane's outputs (gap, gradient, Hessian).
    #[inline(always)]
    fn accept_all<const P: usize, const AVX2: bool>(
        &mut self,
        first: usize,
        gap: Lanes,
        xi_m: &[Lanes; P],
        hessian: bool,
    ) -> Lanes {
        let (n, range) = (self.coords, first..first + LANES);
        self.gap[range.clone()].copy_from_slice(&gap.0);
        if P == 1 {
            self.xi_m[range.clone()].copy_from_slice(&xi_m[0].0);
        } else {
            for l in 0..LANES {
                for (c, x) in xi_m.iter().enumerate() {
                    self.xi_m[P * (first + l) + c] = x.0[l];
                }
            }
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
