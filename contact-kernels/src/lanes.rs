//! [`Lanes`]: one value of [`LANES`] points, the register type of the
//! generated lane kernels (`kernels_lanes.rs`, see `generated_lanes.rs`).
//!
//! Every operation acts lane by lane with exactly the IEEE operation the
//! scalar kernels use (`+`, `-`, `*`, `1 / x`, `-x`, `sqrt`, `powi`), so
//! lane `l` of a result is bit for bit the scalar result for point `l`.
//! The operators are written as four independent scalar operations, which
//! the compiler turns into one vector instruction (SSE2: two, AVX2: one
//! 256-bit instruction); nothing is fused (no FMA).

use std::ops::{Add, Mul, Neg, Sub};

/// Points per lane value.
pub(crate) const LANES: usize = 4;

/// `LANES` values of one register, one per point (aligned for 256-bit
/// loads and stores).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[repr(C, align(32))]
pub(crate) struct Lanes(pub(crate) [f64; LANES]);

impl Lanes {
    /// Zero in every lane (a structurally zero output).
    pub(crate) const ZERO: Lanes = Lanes([0.0; LANES]);

    /// `c` in every lane.
    #[inline(always)]
    pub(crate) const fn splat(c: f64) -> Lanes {
        Lanes([c; LANES])
    }

    /// `1 / x` lane by lane (the scalar kernels' `1.0 / x`).
    #[inline(always)]
    pub(crate) fn recip(self) -> Lanes {
        let [a, b, c, d] = self.0;
        Lanes([1.0 / a, 1.0 / b, 1.0 / c, 1.0 / d])
    }

    /// The square root lane by lane (correctly rounded, as `f64::sqrt`).
    #[inline(always)]
    pub(crate) fn sqrt(self) -> Lanes {
        let [a, b, c, d] = self.0;
        Lanes([a.sqrt(), b.sqrt(), c.sqrt(), d.sqrt()])
    }

    /// `|x|` lane by lane (exact: the sign bit cleared).
    #[inline(always)]
    pub(crate) fn abs(self) -> Lanes {
        let [a, b, c, d] = self.0;
        Lanes([a.abs(), b.abs(), c.abs(), d.abs()])
    }

    /// The larger of `self` and `o` lane by lane, for finite values (equal
    /// to `f64::max` there; with a NaN the result is unspecified).
    #[inline(always)]
    pub(crate) fn max_finite(self, o: Lanes) -> Lanes {
        let ([a, b, c, d], [e, f, g, h]) = (self.0, o.0);
        let m = |x: f64, y: f64| if y > x { y } else { x };
        Lanes([m(a, e), m(b, f), m(c, g), m(d, h)])
    }

    /// `x^n` lane by lane, with `f64::powi` as the scalar kernels.
    #[inline(always)]
    #[allow(dead_code)] // emitted only for formulations with such powers
    pub(crate) fn powi(self, n: i32) -> Lanes {
        let [a, b, c, d] = self.0;
        Lanes([a.powi(n), b.powi(n), c.powi(n), d.powi(n)])
    }
}

impl Add for Lanes {
    type Output = Lanes;
    #[inline(always)]
    fn add(self, o: Lanes) -> Lanes {
        let ([a, b, c, d], [e, f, g, h]) = (self.0, o.0);
        Lanes([a + e, b + f, c + g, d + h])
    }
}

impl Sub for Lanes {
    type Output = Lanes;
    #[inline(always)]
    fn sub(self, o: Lanes) -> Lanes {
        let ([a, b, c, d], [e, f, g, h]) = (self.0, o.0);
        Lanes([a - e, b - f, c - g, d - h])
    }
}

impl Mul for Lanes {
    type Output = Lanes;
    #[inline(always)]
    fn mul(self, o: Lanes) -> Lanes {
        let ([a, b, c, d], [e, f, g, h]) = (self.0, o.0);
        Lanes([a * e, b * f, c * g, d * h])
    }
}

impl Neg for Lanes {
    type Output = Lanes;
    #[inline(always)]
    fn neg(self) -> Lanes {
        let [a, b, c, d] = self.0;
        Lanes([-a, -b, -c, -d])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_operation_is_the_scalar_one_per_lane() {
        let x = Lanes([2.0, 1e-300, -3.5, 7.25]);
        let y = Lanes([0.1, 3.0, 1e300, -0.3]);
        for l in 0..LANES {
            let (a, b) = (x.0[l], y.0[l]);
            assert_eq!((x + y).0[l].to_bits(), (a + b).to_bits());
            assert_eq!((x - y).0[l].to_bits(), (a - b).to_bits());
            assert_eq!((x * y).0[l].to_bits(), (a * b).to_bits());
            assert_eq!((-x).0[l].to_bits(), (-a).to_bits());
            assert_eq!(x.recip().0[l].to_bits(), (1.0 / a).to_bits());
            assert_eq!(y.sqrt().0[l].to_bits(), b.sqrt().to_bits());
            assert_eq!(x.powi(3).0[l].to_bits(), a.powi(3).to_bits());
            assert_eq!((-x).abs().0[l].to_bits(), a.abs().to_bits());
            assert_eq!(x.max_finite(y).0[l].to_bits(), a.max(b).to_bits());
        }
        assert_eq!(Lanes::splat(0.5).0, [0.5; LANES]);
    }
}
