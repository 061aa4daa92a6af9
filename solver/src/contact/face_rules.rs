//! Gauss rules on slave faces: which points a face's `gauss_points = n`
//! means.
//!
//! - **Segment** (2D, `[-1, 1]`): `n` Gauss–Legendre points
//!   ([`super::gauss_legendre`]), `1 <= n <= 8`, weights summing to 2;
//!   degree `2n - 1`.
//! - **Quad4** (`[-1, 1]^2`): the `n x n` tensor Gauss–Legendre rule,
//!   `1 <= n <= 8`, weights summing to 4; every monomial `u^a v^b` with
//!   `a, b <= 2n - 1` exact (total degree `2n - 1`).
//! - **Tri3** (the unit triangle `u, v >= 0`, `u + v <= 1`): symmetric
//!   rules of 1, 3, 4, 6 or 7 points, weights summing to 1/2 (the
//!   triangle's area), [`TRI3_POINTS`]:
//!   - 1: the centroid, degree 1;
//!   - 3: the interior rule at `(1/6, 1/6)`, `(2/3, 1/6)`, `(1/6, 2/3)`,
//!     degree 2 (Strang and Fix, *An Analysis of the Finite Element
//!     Method*, 1973, table 4.1);
//!   - 4: Strang–Fix's degree-3 rule (centroid weight `-27/96`, points
//!     `(1/5, 1/5)`, `(3/5, 1/5)`, `(1/5, 3/5)` of weight `25/96`; the
//!     one rule here with a negative weight);
//!   - 6: Dunavant's degree-4 rule (D. A. Dunavant, "High degree efficient
//!     symmetrical Gaussian quadrature rules for the triangle", Int. J.
//!     Numer. Meth. Engng 21, 1985, rule 4), to the 15 digits published;
//!   - 7: Radon's degree-5 rule (Dunavant's rule 5), in closed form with
//!     `sqrt(15)`.
//!
//! Defaults ([`default_points`]): 2 on segments (as before), 2 x 2 on a
//! quad4, 3 on a tri3. A count without a rule is a [`RuleError`] naming
//! the counts there are. Every point lies inside its face.

use thiserror::Error;

use super::gauss_legendre;
use crate::element::FaceKind;

/// The largest `gauss_points` on segments and (per direction) on quad4.
pub const MAX_TENSOR_POINTS: usize = 8;

/// The tri3 rules' point counts.
pub const TRI3_POINTS: [usize; 5] = [1, 3, 4, 6, 7];

/// A `gauss_points` value with no rule on that kind of face.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[error(
    "no Gauss rule of {requested} points on a {kind}: available are {}",
    list(available)
)]
pub struct RuleError {
    /// The face kind.
    pub kind: FaceKind,
    /// The count asked for.
    pub requested: usize,
    /// The counts that have a rule.
    pub available: Vec<usize>,
}

fn list(counts: &[usize]) -> String {
    counts
        .iter()
        .map(|c| c.to_string())
        .collect::<Vec<_>>()
        .join(", ")
}

/// The default `gauss_points` of a face kind: 2 on segments, 2 (x 2) on a
/// quad4, 3 on a tri3.
pub fn default_points(kind: FaceKind) -> usize {
    match kind {
        FaceKind::Segment | FaceKind::Quad4 => 2,
        FaceKind::Tri3 => 3,
    }
}

/// The counts `gauss_points` may take on `kind`.
pub fn available(kind: FaceKind) -> Vec<usize> {
    match kind {
        FaceKind::Segment | FaceKind::Quad4 => (1..=MAX_TENSOR_POINTS).collect(),
        FaceKind::Tri3 => TRI3_POINTS.to_vec(),
    }
}

/// A rule's points (`[xi, 0]` on a segment, `[u, v]` on a face) and
/// weights, and the total degree it integrates exactly.
#[derive(Debug, Clone, PartialEq)]
pub struct FaceRule {
    /// Points and weights.
    pub points: Vec<([f64; 2], f64)>,
    /// Every polynomial of at most this total degree is integrated
    /// exactly (on a quad4, also every `u^a v^b` with `a, b` up to it).
    pub degree: usize,
}

/// The rule `gauss_points = n` gives on `kind` (module docs).
pub fn face_rule(kind: FaceKind, n: usize) -> Result<FaceRule, RuleError> {
    let err = || RuleError {
        kind,
        requested: n,
        available: available(kind),
    };
    match kind {
        FaceKind::Segment | FaceKind::Quad4 if !(1..=MAX_TENSOR_POINTS).contains(&n) => Err(err()),
        FaceKind::Segment => Ok(FaceRule {
            points: gauss_legendre(n)
                .into_iter()
                .map(|(x, w)| ([x, 0.0], w))
                .collect(),
            degree: 2 * n - 1,
        }),
        FaceKind::Quad4 => {
            let line = gauss_legendre(n);
            let mut points = Vec::with_capacity(n * n);
            for &(v, wv) in &line {
                for &(u, wu) in &line {
                    points.push(([u, v], wu * wv));
                }
            }
            Ok(FaceRule {
                points,
                degree: 2 * n - 1,
            })
        }
        FaceKind::Tri3 => tri3_rule(n).ok_or_else(err),
    }
}

/// The three points `(a, a)`, `(1 - 2a, a)`, `(a, 1 - 2a)` of weight `w`.
fn orbit3(a: f64, w: f64) -> [([f64; 2], f64); 3] {
    let b = 1.0 - 2.0 * a;
    [([a, a], w), ([b, a], w), ([a, b], w)]
}

/// The tri3 rule of `n` points, weights summing to 1/2 (`None`: no
/// rule of `n` points).
pub(crate) fn tri3_rule(n: usize) -> Option<FaceRule> {
    let third = 1.0 / 3.0;
    let (points, degree) = match n {
        1 => (vec![([third, third], 0.5)], 1),
        3 => {
            let (a, b) = (1.0 / 6.0, 2.0 / 3.0);
            let w = 1.0 / 6.0;
            (vec![([a, a], w), ([b, a], w), ([a, b], w)], 2)
        }
        4 => {
            let mut p = vec![([third, third], -27.0 / 96.0)];
            p.extend(orbit3(0.2, 25.0 / 96.0));
            (p, 3)
        }
        6 => {
            // Dunavant (1985), rule 4: weights for unit area, halved here.
            let mut p = Vec::with_capacity(6);
            p.extend(orbit3(0.445_948_490_915_965, 0.223_381_589_678_011 / 2.0));
            p.extend(orbit3(0.091_576_213_509_771, 0.109_951_743_655_322 / 2.0));
            (p, 4)
        }
        7 => {
            let s = 15f64.sqrt();
            let (a, b) = ((6.0 - s) / 21.0, (6.0 + s) / 21.0);
            let (wa, wb) = ((155.0 - s) / 1200.0 / 2.0, (155.0 + s) / 1200.0 / 2.0);
            let mut p = vec![([third, third], 9.0 / 40.0 / 2.0)];
            p.extend([
                ([a, a], wa),
                ([1.0 - 2.0 * a, a], wa),
                ([a, 1.0 - 2.0 * a], wa),
                ([b, b], wb),
                ([1.0 - 2.0 * b, b], wb),
                ([b, 1.0 - 2.0 * b], wb),
            ]);
            (p, 5)
        }
        _ => return None,
    };
    Some(FaceRule { points, degree })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn factorial(k: usize) -> f64 {
        (1..=k).map(|i| i as f64).product()
    }

    /// `integral u^a v^b` over the unit triangle: `a! b! / (a + b + 2)!`.
    fn triangle_monomial(a: usize, b: usize) -> f64 {
        factorial(a) * factorial(b) / factorial(a + b + 2)
    }

    /// `integral x^a` over `[-1, 1]`.
    fn line_monomial(a: usize) -> f64 {
        if a % 2 == 1 {
            0.0
        } else {
            2.0 / (a as f64 + 1.0)
        }
    }

    fn integrate(rule: &FaceRule, a: usize, b: usize) -> f64 {
        rule.points
            .iter()
            .map(|([u, v], w)| w * u.powi(a as i32) * v.powi(b as i32))
            .sum()
    }

    #[test]
    fn tri3_rules_integrate_their_degree_exactly_inside_the_triangle() {
        let mut degrees = Vec::new();
        for n in TRI3_POINTS {
            let rule = face_rule(FaceKind::Tri3, n).unwrap();
            assert_eq!(rule.points.len(), n);
            let total: f64 = rule.points.iter().map(|(_, w)| w).sum();
            assert!((total - 0.5).abs() < 1e-15, "{n}: {total}");
            for ([u, v], _) in &rule.points {
                assert!(*u > 0.0 && *v > 0.0 && u + v < 1.0, "{n}: ({u}, {v})");
            }
            for a in 0..=rule.degree {
                for b in 0..=rule.degree - a {
                    let (got, exact) = (integrate(&rule, a, b), triangle_monomial(a, b));
                    assert!(
                        (got - exact).abs() < 1e-14,
                        "{n} u^{a} v^{b}: {got} vs {exact}"
                    );
                }
            }
            // the stated degree is the rule's: one degree more is not exact
            let d = rule.degree + 1;
            let worst = (0..=d)
                .map(|a| (integrate(&rule, a, d - a) - triangle_monomial(a, d - a)).abs())
                .fold(0.0, f64::max);
            assert!(worst > 1e-6, "{n}: degree {d} exact too ({worst})");
            degrees.push(rule.degree);
        }
        assert_eq!(degrees, [1, 2, 3, 4, 5]);
        let three = face_rule(FaceKind::Tri3, 3).unwrap();
        let expected = [
            [1.0 / 6.0, 1.0 / 6.0],
            [2.0 / 3.0, 1.0 / 6.0],
            [1.0 / 6.0, 2.0 / 3.0],
        ];
        for (p, e) in three.points.iter().zip(expected) {
            assert_eq!(p.0, e);
        }
    }

    #[test]
    fn quad4_and_segment_rules_integrate_their_degree_exactly() {
        for n in 1..=MAX_TENSOR_POINTS {
            let quad = face_rule(FaceKind::Quad4, n).unwrap();
            assert_eq!(quad.points.len(), n * n);
            let total: f64 = quad.points.iter().map(|(_, w)| w).sum();
            assert!((total - 4.0).abs() < 1e-14, "{n}: {total}");
            for ([u, v], _) in &quad.points {
                assert!(u.abs() < 1.0 && v.abs() < 1.0);
            }
            for a in 0..=quad.degree {
                for b in 0..=quad.degree {
                    let got = integrate(&quad, a, b);
                    let exact = line_monomial(a) * line_monomial(b);
                    assert!(
                        (got - exact).abs() < 1e-14,
                        "{n} u^{a} v^{b}: {got} vs {exact}"
                    );
                }
            }
            let segment = face_rule(FaceKind::Segment, n).unwrap();
            assert_eq!(segment.points.len(), n);
            for a in 0..=segment.degree {
                let got = integrate(&segment, a, 0);
                assert!((got - line_monomial(a)).abs() < 1e-14, "{n} x^{a}: {got}");
            }
            // the segment rule is the contact element's, bit for bit
            let legendre = gauss_legendre(n);
            for (p, (x, w)) in segment.points.iter().zip(legendre) {
                assert_eq!(*p, ([x, 0.0], w));
            }
        }
    }

    #[test]
    fn defaults_and_missing_rules() {
        assert_eq!(default_points(FaceKind::Segment), 2);
        assert_eq!(default_points(FaceKind::Quad4), 2);
        assert_eq!(default_points(FaceKind::Tri3), 3);
        for kind in [FaceKind::Segment, FaceKind::Quad4, FaceKind::Tri3] {
            assert!(face_rule(kind, default_points(kind)).is_ok());
        }
        let err = face_rule(FaceKind::Tri3, 5).unwrap_err();
        assert_eq!(err.available, vec![1, 3, 4, 6, 7]);
        assert_eq!(
            err.to_string(),
            "no Gauss rule of 5 points on a tri3: available are 1, 3, 4, 6, 7"
        );
        for n in [0, 2, 8] {
            assert!(face_rule(FaceKind::Tri3, n).is_err(), "{n}");
        }
        for kind in [FaceKind::Segment, FaceKind::Quad4] {
            for n in [0, 9] {
                let err = face_rule(kind, n).unwrap_err();
                assert_eq!(err.available, (1..=8).collect::<Vec<_>>());
                assert!(err.to_string().contains(&format!("{n} points on a {kind}")));
            }
        }
    }
}
