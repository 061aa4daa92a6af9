//! Hyper-dual numbers over double-doubles: `a + b e1 + c e2 + d e1 e2`
//! with `e1^2 = e2^2 = 0`. Seeding coordinate `j` in `e1` and `k` in `e2`,
//! a function's `(re, e1, e2, e12)` parts are `f`, `df/dq_j`, `df/dq_k` and
//! `d2f/dq_j dq_k`, exactly (no truncation error), in double-double
//! precision: the reference of the stability sweep.

use std::ops::{Add, Div, Mul, Neg, Sub};

use super::dd::Dd;

/// A hyper-dual number over [`Dd`].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Hd {
    /// Value.
    pub re: Dd,
    /// First direction.
    pub e1: Dd,
    /// Second direction.
    pub e2: Dd,
    /// Mixed second derivative.
    pub e12: Dd,
}

impl Hd {
    /// A constant.
    pub fn constant(x: f64) -> Hd {
        Hd {
            re: Dd::from_f64(x),
            ..Hd::default()
        }
    }

    /// A variable seeded in the directions `e1` and/or `e2`.
    pub fn variable(x: f64, in_e1: bool, in_e2: bool) -> Hd {
        let one = Dd::from_f64(1.0);
        let zero = Dd::default();
        Hd {
            re: Dd::from_f64(x),
            e1: if in_e1 { one } else { zero },
            e2: if in_e2 { one } else { zero },
            e12: zero,
        }
    }

    /// `1 / self`.
    pub fn recip(self) -> Hd {
        let one = Dd::from_f64(1.0);
        let r = one / self.re;
        let r2 = r * r;
        let two = Dd::from_f64(2.0);
        Hd {
            re: r,
            e1: -(self.e1 * r2),
            e2: -(self.e2 * r2),
            e12: two * self.e1 * self.e2 * r2 * r - self.e12 * r2,
        }
    }

    /// The square root.
    pub fn sqrt(self) -> Hd {
        let s = self.re.sqrt();
        let half = Dd::from_f64(0.5);
        let d = half / s; // d sqrt / dx
        let dd = -(d / (Dd::from_f64(2.0) * self.re)); // d2 sqrt / dx2
        Hd {
            re: s,
            e1: self.e1 * d,
            e2: self.e2 * d,
            e12: self.e12 * d + self.e1 * self.e2 * dd,
        }
    }
}

impl Add for Hd {
    type Output = Hd;
    fn add(self, b: Hd) -> Hd {
        Hd {
            re: self.re + b.re,
            e1: self.e1 + b.e1,
            e2: self.e2 + b.e2,
            e12: self.e12 + b.e12,
        }
    }
}

impl Sub for Hd {
    type Output = Hd;
    fn sub(self, b: Hd) -> Hd {
        self + (-b)
    }
}

impl Neg for Hd {
    type Output = Hd;
    fn neg(self) -> Hd {
        Hd {
            re: -self.re,
            e1: -self.e1,
            e2: -self.e2,
            e12: -self.e12,
        }
    }
}

impl Mul for Hd {
    type Output = Hd;
    fn mul(self, b: Hd) -> Hd {
        Hd {
            re: self.re * b.re,
            e1: self.re * b.e1 + self.e1 * b.re,
            e2: self.re * b.e2 + self.e2 * b.re,
            e12: self.re * b.e12 + self.e1 * b.e2 + self.e2 * b.e1 + self.e12 * b.re,
        }
    }
}

impl Div for Hd {
    type Output = Hd;
    #[allow(clippy::suspicious_arithmetic_impl)]
    fn div(self, b: Hd) -> Hd {
        self * b.recip()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `f(x, y) = sqrt(x) / y` at (2, 3): every part against its formula.
    #[test]
    fn hyper_dual_parts_are_the_derivatives() {
        let x = Hd::variable(2.0, true, false);
        let y = Hd::variable(3.0, false, true);
        let f = x.sqrt() / y;
        let s2 = 2f64.sqrt();
        assert!((f.re.to_f64() - s2 / 3.0).abs() < 1e-15);
        assert!((f.e1.to_f64() - 1.0 / (2.0 * s2 * 3.0)).abs() < 1e-15);
        assert!((f.e2.to_f64() + s2 / 9.0).abs() < 1e-15);
        assert!((f.e12.to_f64() + 1.0 / (2.0 * s2 * 9.0)).abs() < 1e-15);
        let xx = Hd::variable(2.0, true, true);
        let g = xx.sqrt();
        // d2 sqrt(x)/dx2 = -x^(-3/2) / 4
        assert!((g.e12.to_f64() + 2f64.powf(-1.5) / 4.0).abs() < 1e-15);
    }
}
