//! [`Lanes`]: one value of [`LANES`] points, the register type of the
//! generated lane kernels (`kernels_lanes.rs`, see `generated_lanes.rs`),
//! and [`LaneValue`], the operations those kernels are written against.
//!
//! Every operation acts lane by lane with exactly the IEEE operation the
//! scalar kernels use (`+`, `-`, `*`, `1 / x`, `-x`, `sqrt`, `powi`), so
//! lane `l` of a result is bit for bit the scalar result for point `l`;
//! nothing is fused (no FMA).
//!
//! Two value types implement [`LaneValue`], with one layout (four `f64`,
//! 32-byte aligned), so the kernels' buffers are shared:
//!
//! * [`Lanes`], portable: four independent scalar operations, which the
//!   compiler's SLP vectoriser turns into vector instructions where it can
//!   (SSE2: two per operation). In very large kernels (the 3D Hessians:
//!   ten thousand operations in one block) it gives up, and the code
//!   stays scalar;
//! * `Avx4` (x86-64), one AVX register: every operation is one 256-bit
//!   instruction whatever the kernel's size. It is used only inside
//!   functions compiled for AVX2 (the `_x4_avx2` entry points), which run
//!   only on a CPU that has it.

use std::ops::{Add, Mul, Neg, Sub};

/// Points per lane value.
pub(crate) const LANES: usize = 4;

/// `LANES` values of one register, one per point (aligned for 256-bit
/// loads and stores).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[repr(C, align(32))]
pub(crate) struct Lanes(pub(crate) [f64; LANES]);

/// The operations of a lane kernel's value type ([`Lanes`], `Avx4`):
/// the arithmetic operators lane by lane and the methods below, each the
/// scalar kernels' operation on every lane.
pub(crate) trait LaneValue:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Neg<Output = Self>
{
    /// Zero in every lane (a structurally zero output).
    const ZERO: Self;
    /// `c` in every lane.
    fn splat(c: f64) -> Self;
    /// `1 / x` lane by lane (the scalar kernels' `1.0 / x`).
    fn recip(self) -> Self;
    /// The square root lane by lane (correctly rounded, as `f64::sqrt`).
    fn sqrt(self) -> Self;
    /// `x^n` lane by lane, with `f64::powi` as the scalar kernels.
    #[allow(dead_code)] // emitted only for formulations with such powers
    fn powi(self, n: i32) -> Self;
}

impl LaneValue for Lanes {
    const ZERO: Lanes = Lanes::ZERO;
    #[inline(always)]
    fn splat(c: f64) -> Lanes {
        Lanes::splat(c)
    }
    #[inline(always)]
    fn recip(self) -> Lanes {
        Lanes::recip(self)
    }
    #[inline(always)]
    fn sqrt(self) -> Lanes {
        Lanes::sqrt(self)
    }
    #[inline(always)]
    fn powi(self, n: i32) -> Lanes {
        Lanes::powi(self, n)
    }
}

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

#[cfg(target_arch = "x86_64")]
pub(crate) use avx::Avx4;

/// [`Avx4`]: [`Lanes`] in one AVX register.
#[cfg(target_arch = "x86_64")]
mod avx {
    use super::{LANES, LaneValue, Lanes};
    use std::arch::x86_64::{
        __m256d, _mm256_add_pd, _mm256_div_pd, _mm256_mul_pd, _mm256_set1_pd, _mm256_sqrt_pd,
        _mm256_sub_pd, _mm256_xor_pd,
    };
    use std::ops::{Add, Mul, Neg, Sub};

    /// Four lanes in one 256-bit register, the same bits and layout as
    /// [`Lanes`] (`repr(transparent)` over `__m256d`: 32 bytes, 32-byte
    /// aligned), so the lane buffers are reinterpreted, not copied
    /// ([`Avx4::slice`], [`Avx4::slice_mut`]).
    ///
    /// Every operation is one AVX instruction with the scalar operation's
    /// IEEE rounding (`vaddpd`, `vsubpd`, `vmulpd`, `vdivpd`, `vsqrtpd`;
    /// negation flips the sign bit, as `-x` does). An `Avx4` may only be
    /// operated on in code compiled with AVX2 enabled, on a CPU that has it:
    /// the lane kernels' `_x4_avx2` entry points, which are `unsafe` for
    /// that reason and chosen only after `is_x86_feature_detected!`.
    #[derive(Clone, Copy)]
    #[repr(transparent)]
    pub(crate) struct Avx4(__m256d);

    const _: () = {
        assert!(size_of::<Avx4>() == size_of::<Lanes>());
        assert!(align_of::<Avx4>() == align_of::<Lanes>());
    };

    impl Avx4 {
        /// The lanes of `v`, bit for bit.
        #[inline(always)]
        pub(crate) fn from_lanes(v: Lanes) -> Avx4 {
            // SAFETY: both types are 32 bytes of four `f64`, every bit
            // pattern valid (the layout is asserted above).
            unsafe { std::mem::transmute::<Lanes, Avx4>(v) }
        }

        /// The lanes of `self`, bit for bit.
        #[inline(always)]
        pub(crate) fn to_lanes(self) -> Lanes {
            // SAFETY: as in `from_lanes`.
            unsafe { std::mem::transmute::<Avx4, Lanes>(self) }
        }

        /// `v` viewed as `Avx4` values (same layout, no copy).
        #[inline(always)]
        pub(crate) fn slice(v: &[Lanes]) -> &[Avx4] {
            // SAFETY: same size and alignment (asserted above), every bit
            // pattern valid in both; the length is kept.
            unsafe { std::slice::from_raw_parts(v.as_ptr().cast::<Avx4>(), v.len()) }
        }

        /// `v` viewed as `Avx4` values, mutably (same layout, no copy).
        #[inline(always)]
        pub(crate) fn slice_mut(v: &mut [Lanes]) -> &mut [Avx4] {
            // SAFETY: as in `slice`; the borrow of `v` is carried over.
            unsafe { std::slice::from_raw_parts_mut(v.as_mut_ptr().cast::<Avx4>(), v.len()) }
        }

        /// `v` viewed as one `Avx4` value, mutably.
        #[inline(always)]
        pub(crate) fn one_mut(v: &mut Lanes) -> &mut Avx4 {
            &mut Avx4::slice_mut(std::slice::from_mut(v))[0]
        }
    }

    // SAFETY (every `unsafe` block below): the AVX intrinsics are sound in
    // code compiled for AVX2 on a CPU that has it, the only place an
    // `Avx4` is operated on (see the type's documentation). These
    // functions are always inlined into such code.
    impl LaneValue for Avx4 {
        // SAFETY: four `f64` zeros, all bits zero.
        const ZERO: Avx4 = unsafe { std::mem::transmute::<[f64; LANES], Avx4>([0.0; LANES]) };
        #[inline(always)]
        fn splat(c: f64) -> Avx4 {
            Avx4(unsafe { _mm256_set1_pd(c) })
        }
        #[inline(always)]
        fn recip(self) -> Avx4 {
            Avx4(unsafe { _mm256_div_pd(_mm256_set1_pd(1.0), self.0) })
        }
        #[inline(always)]
        fn sqrt(self) -> Avx4 {
            Avx4(unsafe { _mm256_sqrt_pd(self.0) })
        }
        #[inline(always)]
        fn powi(self, n: i32) -> Avx4 {
            Avx4::from_lanes(self.to_lanes().powi(n))
        }
    }

    impl Add for Avx4 {
        type Output = Avx4;
        #[inline(always)]
        fn add(self, o: Avx4) -> Avx4 {
            Avx4(unsafe { _mm256_add_pd(self.0, o.0) })
        }
    }

    impl Sub for Avx4 {
        type Output = Avx4;
        #[inline(always)]
        fn sub(self, o: Avx4) -> Avx4 {
            Avx4(unsafe { _mm256_sub_pd(self.0, o.0) })
        }
    }

    impl Mul for Avx4 {
        type Output = Avx4;
        #[inline(always)]
        fn mul(self, o: Avx4) -> Avx4 {
            Avx4(unsafe { _mm256_mul_pd(self.0, o.0) })
        }
    }

    impl Neg for Avx4 {
        type Output = Avx4;
        #[inline(always)]
        fn neg(self) -> Avx4 {
            // `-x` flips the sign bit and nothing else (also of zeros and
            // NaNs), as the scalar negation does.
            Avx4(unsafe { _mm256_xor_pd(self.0, _mm256_set1_pd(-0.0)) })
        }
    }
}

/// (Run by tests/lanes.rs, which compiles this file on its own: the
/// library has no unit-test target, see Cargo.toml.)
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

    /// `Avx4` gives every lane the scalar operation's bits, in a function
    /// compiled for AVX2 (skipped on a CPU without it).
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn avx4_is_the_scalar_operation_per_lane() {
        if !std::is_x86_feature_detected!("avx2") {
            return;
        }
        #[target_feature(enable = "avx2")]
        fn all(x: Lanes, y: Lanes) -> [Lanes; 9] {
            let (a, b) = (Avx4::from_lanes(x), Avx4::from_lanes(y));
            [
                (a + b).to_lanes(),
                (a - b).to_lanes(),
                (a * b).to_lanes(),
                (-a).to_lanes(),
                a.recip().to_lanes(),
                b.sqrt().to_lanes(),
                a.powi(3).to_lanes(),
                <Avx4 as LaneValue>::splat(0.5).to_lanes(),
                <Avx4 as LaneValue>::ZERO.to_lanes(),
            ]
        }
        let x = Lanes([2.0, 1e-300, -3.5, 0.0]);
        let y = Lanes([0.1, 3.0, 1e300, -0.3]);
        // SAFETY: the CPU has AVX2 (checked above).
        let r = unsafe { all(x, y) };
        for l in 0..LANES {
            let (a, b) = (x.0[l], y.0[l]);
            let want = [
                a + b,
                a - b,
                a * b,
                -a,
                1.0 / a,
                b.sqrt(),
                a.powi(3),
                0.5,
                0.0,
            ];
            for (got, want) in r.iter().zip(want) {
                assert_eq!(got.0[l].to_bits(), want.to_bits(), "lane {l}");
            }
        }
    }
}
