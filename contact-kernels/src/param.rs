//! Parametric coordinates: how a caller passes the slave point `xi_s` and
//! how the handles report the projection `xi_m`.
//!
//! A segment (2D) has one parametric coordinate, a face (3D: tri3, quad4)
//! two, `(u, v)`: [`crate::Kernel::param_dim`]. Every handle takes `xi_s`
//! through [`XiArg`], implemented for `f64` (a segment's `xi_s`, as every
//! 2D call writes it), `[f64; N]`, `&[f64; N]`, `&[f64]`, `Vec<f64>` and
//! `&Vec<f64>`, so `kernel.eval(&q, 0.3, &mut out)` and
//! `kernel.eval(&q, [0.2, -0.1], &mut out)` are the same call. A length
//! other than the kernel's parametric dimension is
//! [`crate::KernelError::ParamCount`], never a panic.
//!
//! The projection is reported as a slice of the same length
//! ([`crate::GapOut::xi_m_all`], [`crate::Projection::xi_m_all`],
//! [`crate::GapBatch::xi_m`]); `xi_m()` (a plain `f64`) is its first
//! component: for a segment, the projection itself.

/// The largest parametric dimension of a face (2: `(u, v)`).
pub const MAX_PARAM_DIM: usize = 2;

/// A slave point's parametric coordinates, as the handles take them: a
/// scalar for a segment, two values for a face.
pub trait XiArg {
    /// The coordinates as a slice (one entry for a scalar).
    fn as_xi(&self) -> &[f64];
}

impl XiArg for f64 {
    #[inline(always)]
    fn as_xi(&self) -> &[f64] {
        std::slice::from_ref(self)
    }
}

impl<const N: usize> XiArg for [f64; N] {
    #[inline(always)]
    fn as_xi(&self) -> &[f64] {
        self
    }
}

impl<const N: usize> XiArg for &[f64; N] {
    #[inline(always)]
    fn as_xi(&self) -> &[f64] {
        &self[..]
    }
}

impl XiArg for &[f64] {
    #[inline(always)]
    fn as_xi(&self) -> &[f64] {
        self
    }
}

impl XiArg for Vec<f64> {
    #[inline(always)]
    fn as_xi(&self) -> &[f64] {
        self
    }
}

impl XiArg for &Vec<f64> {
    #[inline(always)]
    fn as_xi(&self) -> &[f64] {
        self
    }
}

/// Up to [`MAX_PARAM_DIM`] parametric coordinates by value (the storage
/// behind the `xi_m` slices the handles return).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Xi {
    v: [f64; MAX_PARAM_DIM],
    len: usize,
}

impl Xi {
    /// One coordinate (a segment's).
    #[inline(always)]
    pub(crate) fn scalar(x: f64) -> Xi {
        Xi {
            v: [x, 0.0],
            len: 1,
        }
    }

    /// Two coordinates (a face's `(u, v)`).
    #[inline(always)]
    pub(crate) fn pair(x: [f64; 2]) -> Xi {
        Xi { v: x, len: 2 }
    }

    /// The coordinates, `len` of them.
    #[inline(always)]
    pub(crate) fn as_slice(&self) -> &[f64] {
        &self.v[..self.len]
    }

    /// The first coordinate.
    #[inline(always)]
    pub(crate) fn first(&self) -> f64 {
        self.v[0]
    }
}
