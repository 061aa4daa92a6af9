//! [`Slip::eval_batch`]: the slip of many points into a [`SlipBatch`]
//! (structure of arrays), four points per call of the slip's lane kernels
//! (a segment's one component; a face's three, one lane function each),
//! with the results and errors of [`Slip::eval`] point by point.
//!
//! Per group of [`LANES`] points:
//!
//! 1. segments: the points' coordinates are gathered into lanes and
//!    validated there (the gap batch's lane checks,
//!    `ParamKernel::validate_lanes`); a lane that passes, whose `xi_m0` is
//!    finite and whose projection is in closed form is ready. Faces have no
//!    lane validation (as the gap's batch). Any other point goes through the scalar path's
//!    steps before the kernel ([`slip_start`]: validation, `xi_m0` finite,
//!    the projection's start), so a point refused there carries exactly
//!    [`Slip::eval`]'s error. A refused point's lane, like the lanes past
//!    the end of a short last group, computes on zeros whose results are
//!    discarded;
//! 2. the slip's lane kernels evaluate the group (AVX2 where the CPU has
//!    it, [`Kernel::lane_isa`](super::Kernel::lane_isa)): lane `l` of every
//!    output holds the bits the scalar slip kernel gives point `l`;
//! 3. a lane is accepted when every component of its `xi_m` passes the
//!    projection check's tests and every output is finite (the scalar
//!    path's two checks after the kernel). Any other lane is evaluated
//!    again by the scalar path ([`slip_point`]), so a failing point
//!    reports exactly the error [`Slip::eval`] reports, never a second
//!    opinion. A failed point's entries are zero.
//!
//! The results are scattered lane by lane (no transposes, unlike the
//! gap's batch).

use super::batch::accepted;
use super::param_kernel::{ParamKernel, SlipBuffers, SlipLaneBuffers, slip_point, slip_start};
use super::{Imp, slip::Slip};
use crate::KernelError;
use crate::lanes::{LANES, Lanes};

/// Outputs of [`Slip::eval_batch`] for `len` points, structure of arrays
/// (`c` components, `n` coordinates, `k` parametric coordinates): point
/// `p`'s slip is `slips()[p c..(p + 1) c]`, its projection
/// `xi_m(p)` (`k` values), component `j`'s gradient `grad(p, j)` (`n`
/// values) and Hessian `hess(p, j)` (`n n`, row-major, full). Reuse one
/// batch for every call: it grows to the largest batch and never shrinks.
#[derive(Debug, Clone, PartialEq)]
pub struct SlipBatch {
    components: usize,
    coords: usize,
    param_dim: usize,
    len: usize,
    has_hessian: bool,
    slip: Vec<f64>,
    xi_m: Vec<f64>,
    grad: Vec<f64>,
    hess: Vec<f64>,
    status: Vec<Option<KernelError>>,
    scratch: Vec<f64>,
    lanes: LaneBuffers,
}

/// The slip lane kernels' buffers, `LANES` points each: the relative
/// coordinates (`n`), the components (`c`), their gradients (`c n`) and
/// Hessians (`c n n`), component after component.
#[derive(Debug, Clone, PartialEq)]
struct LaneBuffers {
    d: Vec<Lanes>,
    slip: Vec<Lanes>,
    grad: Vec<Lanes>,
    hess: Vec<Lanes>,
}

impl SlipBatch {
    /// An empty batch for `slip`'s sizes.
    pub fn new(slip: &Slip) -> SlipBatch {
        let (c, n) = (slip.components(), slip.kernel().coords());
        SlipBatch {
            components: c,
            coords: n,
            param_dim: slip.kernel().param_dim(),
            len: 0,
            has_hessian: false,
            slip: Vec::new(),
            xi_m: Vec::new(),
            grad: Vec::new(),
            hess: Vec::new(),
            status: Vec::new(),
            scratch: vec![0.0; n],
            lanes: LaneBuffers {
                d: vec![Lanes::ZERO; n],
                slip: vec![Lanes::ZERO; c],
                grad: vec![Lanes::ZERO; c * n],
                hess: vec![Lanes::ZERO; c * n * n],
            },
        }
    }

    /// Points of the last call.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether the last call had no point.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Coordinates per point.
    pub fn coords(&self) -> usize {
        self.coords
    }

    /// The slip's components per point (1 for segments, 3 for faces).
    pub fn components(&self) -> usize {
        self.components
    }

    /// Point `p`'s outcome.
    pub fn status(&self, p: usize) -> Result<(), &KernelError> {
        match &self.status[..self.len][p] {
            None => Ok(()),
            Some(e) => Err(e),
        }
    }

    /// Point `p`'s slip components.
    pub fn slip(&self, p: usize) -> Result<&[f64], &KernelError> {
        let c = self.components;
        self.status(p).map(|()| &self.slip[p * c..(p + 1) * c])
    }

    /// Point `p`'s projection (the kernel's parametric dimension of values).
    pub fn xi_m(&self, p: usize) -> Result<&[f64], &KernelError> {
        let k = self.param_dim;
        self.status(p).map(|()| &self.xi_m[p * k..(p + 1) * k])
    }

    /// Component `j`'s gradient at point `p` (`n` values).
    ///
    /// # Panics
    /// If `j` is not below the component count.
    pub fn grad(&self, p: usize, j: usize) -> Result<&[f64], &KernelError> {
        assert!(
            j < self.components,
            "the slip has {} components",
            self.components
        );
        let (c, n) = (self.components, self.coords);
        let at = (p * c + j) * n;
        self.status(p).map(|()| &self.grad[at..at + n])
    }

    /// Component `j`'s Hessian at point `p` (`n n` values, row-major);
    /// `None` for a type without second-order term.
    ///
    /// # Panics
    /// If `j` is not below the component count.
    pub fn hess(&self, p: usize, j: usize) -> Result<Option<&[f64]>, &KernelError> {
        assert!(
            j < self.components,
            "the slip has {} components",
            self.components
        );
        let (c, nn) = (self.components, self.coords * self.coords);
        let at = (p * c + j) * nn;
        self.status(p)
            .map(|()| self.has_hessian.then(|| &self.hess[at..at + nn]))
    }

    /// All slips, point after point (zero at failed points).
    pub fn slips(&self) -> &[f64] {
        &self.slip[..self.len * self.components]
    }

    /// Sizes the buffers for `len` points of a kernel with or without a
    /// Hessian.
    fn prepare(&mut self, len: usize, has_hessian: bool) {
        let (c, n) = (self.components, self.coords);
        self.len = len;
        self.has_hessian = has_hessian;
        if self.status.len() < len {
            self.slip.resize(len * c, 0.0);
            self.xi_m.resize(len * self.param_dim, 0.0);
            self.grad.resize(len * c * n, 0.0);
            self.status.resize(len, None);
        }
        if has_hessian && self.hess.len() < len * c * n * n {
            self.hess.resize(len * c * n * n, 0.0);
        }
    }

    /// The entries of point `p`: its slip, gradients and Hessians (empty
    /// without a Hessian).
    fn point_buffers(&mut self, p: usize) -> (&mut [f64], &mut [f64], &mut [f64]) {
        let (c, n) = (self.components, self.coords);
        let nn = if self.has_hessian { n * n } else { 0 };
        (
            &mut self.slip[p * c..(p + 1) * c],
            &mut self.grad[p * c * n..(p + 1) * c * n],
            &mut self.hess[p * c * nn..(p + 1) * c * nn],
        )
    }

    /// Point `p` failed with `e`: zero entries, the error as its status.
    fn fail(&mut self, p: usize, e: KernelError) {
        let k = self.param_dim;
        self.xi_m[p * k..(p + 1) * k].fill(0.0);
        let (slip, grad, hess) = self.point_buffers(p);
        slip.fill(0.0);
        grad.fill(0.0);
        hess.fill(0.0);
        self.status[p] = Some(e);
    }

    /// Point `p` takes lane `l` of the lane buffers.
    fn accept<const P: usize>(&mut self, p: usize, l: usize, xi_m: &[Lanes; P]) {
        let (c, n) = (self.components, self.coords);
        let nn = if self.has_hessian { n * n } else { 0 };
        for (c, x) in xi_m.iter().enumerate() {
            self.xi_m[P * p + c] = x.0[l];
        }
        self.status[p] = None;
        for (s, v) in self.slip[p * c..(p + 1) * c]
            .iter_mut()
            .zip(&self.lanes.slip)
        {
            *s = v.0[l];
        }
        for (g, v) in self.grad[p * c * n..(p + 1) * c * n]
            .iter_mut()
            .zip(&self.lanes.grad)
        {
            *g = v.0[l];
        }
        for (h, v) in self.hess[p * c * nn..(p + 1) * c * nn]
            .iter_mut()
            .zip(&self.lanes.hess)
        {
            *h = v.0[l];
        }
    }
}

impl Slip {
    /// Evaluates the slip at the points `p = 0..xi_s.len() / k` (`k` =
    /// [`Kernel::param_dim`](super::Kernel::param_dim)): point `p` with the
    /// coordinates `qs[p n..(p + 1) n]`, the slave point
    /// `xi_s[p k..(p + 1) k]` and the last converged projection
    /// `xi_m0[p k..(p + 1) k]`, into `out`; returns how many succeeded.
    /// Each point gives the bits [`Slip::eval`] gives it (and its error),
    /// though 4 points are evaluated per call of the slip's lane kernel.
    /// Fails only when the shapes disagree: `xi_s.len()` is not a multiple
    /// of `k` or `xi_m0` is not as long ([`KernelError::ParamCount`]),
    /// `qs.len()` is not `n` times the point count
    /// ([`KernelError::CoordinateCount`]) or `out` was made for another
    /// slip's sizes ([`KernelError::BufferSize`]).
    pub fn eval_batch(
        &self,
        qs: &[f64],
        xi_s: &[f64],
        xi_m0: &[f64],
        out: &mut SlipBatch,
    ) -> Result<usize, KernelError> {
        let kernel = self.kernel();
        let (n, k) = (kernel.coords(), kernel.param_dim());
        if out.coords != n || out.param_dim != k || out.components != self.components() {
            return Err(KernelError::BufferSize {
                expected: n,
                found: out.coords,
            });
        }
        if !xi_s.len().is_multiple_of(k) {
            return Err(KernelError::ParamCount {
                expected: k,
                found: xi_s.len(),
            });
        }
        if xi_m0.len() != xi_s.len() {
            return Err(KernelError::ParamCount {
                expected: xi_s.len(),
                found: xi_m0.len(),
            });
        }
        let points = xi_s.len() / k;
        if qs.len() != n * points {
            return Err(KernelError::CoordinateCount {
                expected: n * points,
                found: qs.len(),
            });
        }
        out.prepare(points, self.has_hessian());
        let args = Points { qs, xi_s, xi_m0 };
        Ok(match &kernel.imp {
            Imp::Segments(s) => eval_all(s, &args, out),
            Imp::Faces(f) => eval_all(f, &args, out),
        })
    }
}

/// The points of one call: coordinates, slave points, last converged
/// projections.
struct Points<'a> {
    qs: &'a [f64],
    xi_s: &'a [f64],
    xi_m0: &'a [f64],
}

impl Points<'_> {
    /// Point `p`'s coordinates (`n`), `xi_s` and `xi_m0`.
    fn point<const P: usize>(&self, p: usize, n: usize) -> (&[f64], [f64; P], [f64; P]) {
        (
            &self.qs[p * n..(p + 1) * n],
            std::array::from_fn(|c| self.xi_s[P * p + c]),
            std::array::from_fn(|c| self.xi_m0[P * p + c]),
        )
    }
}

/// Every group (every point alone without a slip lane kernel: a
/// formulation compiled without its slip's lanes); returns how many points
/// succeeded.
fn eval_all<K: ParamKernel<P>, const P: usize>(k: &K, args: &Points, out: &mut SlipBatch) -> usize {
    let points = args.xi_s.len() / P;
    if !k.has_slip_lanes() {
        return (0..points)
            .map(|p| usize::from(eval_point_scalar(k, p, args, out)))
            .sum();
    }
    (0..points)
        .step_by(LANES)
        .map(|first| eval_group(k, first, LANES.min(points - first), args, out))
        .sum()
}

/// Points `first..first + count` (`count <= LANES`); returns how many
/// succeeded.
fn eval_group<K: ParamKernel<P>, const P: usize>(
    k: &K,
    first: usize,
    count: usize,
    args: &Points,
    out: &mut SlipBatch,
) -> usize {
    let n = k.coords();
    let mut xi_s_l = [Lanes::ZERO; P];
    let mut xi_m0_l = [Lanes::ZERO; P];
    let mut xi_m_l = [Lanes::ZERO; P];
    for l in 0..count {
        for c in 0..P {
            xi_s_l[c].0[l] = args.xi_s[P * (first + l) + c];
            xi_m0_l[c].0[l] = args.xi_m0[P * (first + l) + c];
        }
    }
    let (mut valid, start_all) = k.validate_lanes::<false>(
        &args.qs[first * n..(first + count) * n],
        &mut out.lanes.d,
        &xi_s_l,
    );
    valid[count..].fill(false);
    for (l, valid) in valid.iter_mut().enumerate().take(count) {
        let p = first + l;
        let (q, xi_s, xi_m0) = args.point::<P>(p, n);
        // validated in lanes, `xi_m0` finite, the projection in closed
        // form (it starts at zero): ready
        if *valid && !start_all && xi_m0.iter().all(|x| x.is_finite()) {
            continue;
        }
        *valid = false;
        match slip_start(k, q, xi_s, xi_m0, &mut out.scratch) {
            Ok(xi_m) => {
                for c in 0..P {
                    xi_m_l[c].0[l] = xi_m[c];
                }
                for (dl, &v) in out.lanes.d.iter_mut().zip(&out.scratch) {
                    dl.0[l] = v;
                }
                *valid = true;
            }
            Err(e) => out.fail(p, e),
        }
    }
    // the lanes of failed points and past the end compute on zeros
    for l in (0..LANES).filter(|&l| !valid[l]) {
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
    // reslice to (`n`, then `c`, `c n`, `c n n`).
    let hessian = unsafe {
        k.run_slip_lanes(
            &buf.d,
            &xi_s_l,
            &xi_m0_l,
            &mut xi_m_l,
            SlipLaneBuffers {
                slip: &mut buf.slip,
                grad: &mut buf.grad,
                hess: &mut buf.hess,
            },
        )
    }
    .expect("eval_all checked that the slip has lane kernels");
    // The lane's outputs are all finite when their sum is (a NaN or an
    // infinity makes it non-finite; an overflowing sum of finite values
    // only sends the point through the scalar path, which decides).
    let mut sum = buf
        .slip
        .iter()
        .chain(&buf.grad)
        .fold(Lanes::ZERO, |s, v| s + *v);
    if hessian {
        sum = buf.hess.iter().fold(sum, |s, v| s + *v);
    }
    let mut ok = 0;
    for l in (0..count).filter(|&l| valid[l]) {
        let p = first + l;
        if accepted(sum, &xi_m_l, l) {
            out.accept(p, l, &xi_m_l);
            ok += 1;
        } else {
            ok += usize::from(eval_point_scalar(k, p, args, out));
        }
    }
    ok
}

/// Point `p` through the scalar path (for its exact error); whether it
/// succeeded.
#[cold]
#[inline(never)]
fn eval_point_scalar<K: ParamKernel<P>, const P: usize>(
    k: &K,
    p: usize,
    args: &Points,
    out: &mut SlipBatch,
) -> bool {
    let (n, c) = (k.coords(), out.components);
    let (q, xi_s, xi_m0) = args.point::<P>(p, n);
    let mut slip = [0.0; 3];
    let mut scratch = std::mem::take(&mut out.scratch);
    let (s, grad, hess) = out.point_buffers(p);
    let result = slip_point(
        k,
        q,
        xi_s,
        xi_m0,
        &mut scratch,
        SlipBuffers {
            slip: &mut slip,
            grad,
            hess,
        },
        c,
    );
    s.copy_from_slice(&slip[..c]);
    out.scratch = scratch;
    match result {
        Ok((xi_m, _)) => {
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
