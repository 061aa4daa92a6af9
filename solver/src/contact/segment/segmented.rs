//! The integration rule on the slave segments: plain Gauss, or segmented
//! (Gauss on the pieces between the slave points whose projections reach a
//! master node).
//!
//! # Why segment
//!
//! Along a slave segment the contact integrand `lambda(xi_s) g'(xi_s)` is
//! smooth on the slave side (`lambda` and `N_a(xi_s)` are linear), but its
//! master part carries `N_m(xi_m(xi_s))`, and `xi_m(xi_s)` switches from
//! one master segment to the next where the projection crosses a master
//! node: the integrand has a kink there. A Gauss rule over the whole slave
//! segment integrates a kink with an error that falls only slowly with the
//! number of points, so non-matching meshes do not transmit a uniform
//! pressure uniformly (the contact patch test fails). Split at the kinks,
//! every piece's integrand is smooth (a polynomial of degree 2 at a flat
//! interface, where `lambda N_m` is the product of two linear functions),
//! and `n_g` Gauss points per piece integrate it exactly for `n_g >= 2`.
//!
//! # The split
//!
//! For a slave segment with reference end points `A` (`xi_s = -1`) and `B`
//! (`xi_s = +1`), `t_s = B - A`, `x_s(xi) = A + (1 + xi)/2 t_s`, and every
//! master segment `[M1, M2]` (`t_m = M2 - M1`) and each of its ends `E`
//! (`xi_m = -1` at `M1`, `+1` at `M2`), the split is the slave coordinate
//! whose projection onto that master segment lands on `E`, in the pair's
//! formulation (docs/conventions.md, "Geometry and sign conventions"):
//!
//! ```text
//! slave-normal   (E - x_s(xi)) . t_s = 0   (1 + xi)/2 = (E - A) . t_s / (t_s . t_s)
//! closest-point  (E - x_s(xi)) . t_m = 0   (1 + xi)/2 = (E - A) . t_m / (t_s . t_m)
//! ```
//!
//! With the slave normal the split does not depend on the master segment
//! (it is the foot of the master node on the slave segment); with the
//! closest point the two segments meeting at a node give two splits where
//! the master face bends (between them a slave point projects into both
//! segments or into neither), one where it is straight. Only splits
//! strictly inside the slave segment count, and a split within
//! [`SPLIT_TOL`] (parametric) of a slave node or of another split is
//! dropped ([`is_new_split`]), so no piece has zero length; a split that
//! is not finite (a master segment perpendicular to the slave segment, in
//! closest point) is dropped too. Each piece `[a, b]` then carries the
//! `n_g`-point Gauss rule mapped to it: `xi_s = (a + b)/2 + (b - a)/2 x`,
//! weight `w (b - a)/2` ([`segmented_rule`]).
//!
//! # When the split is computed, and its limits
//!
//! The split is computed once, in the **reference** configuration, when
//! the layout is built ([`super::ContactLayout::new`]): the integration
//! points, like every other part of the layout, never change during a
//! solve, so Types 1–6, the complete formulation, ties and reports all see
//! a fixed set of points. This is exact as long as the master nodes
//! project where they did in the reference configuration, e.g. the contact
//! patch test (`scenes/patch-test.toml`: both blocks stretch alike, the
//! interface does not slide). Where the faces slide or rotate relative to
//! each other, the kinks move away from the splits and segmented
//! integration loses its exactness: a master node that has slid by `delta`
//! (less than the distance from a piece's end to its first Gauss point)
//! gets the force `p (integral N_m - delta^2 / h)` instead of
//! `p integral N_m` under a uniform pressure `p` with 2 points per piece
//! (`h` its segments' length; the test
//! `reference_split_error_grows_with_the_slip_squared`), a relative error
//! of about `(delta / h)^2`: `1e-4` for a slip of a hundredth of a master
//! segment. For large slips the rule is a Gauss rule on
//! `n_g (1 + splits)` points without the patch-test guarantee. Recomputing the splits at converged
//! steps would follow the sliding but change the number of points (and
//! with them the pairings, Taylor coefficients and ties the solver keeps
//! per point); that is not done.
//!
//! Every master segment of the pair is considered, also one far away or
//! facing away: its splits cost points but do not make the rule wrong.
//!
//! Invariants: with [`crate::model::Integration::Gauss`] the points and weights are
//! those of the Gauss rule itself (bit for bit the rule before segmented
//! integration existed); the splits are sorted, strictly inside
//! `(-1, 1)` and at least [`SPLIT_TOL`] apart and away from `+-1`; the
//! weights of a segment's points add up to 2 (to rounding).

use contact_kernels::Formulation;

/// Splits closer than this (in the slave segment's parametric coordinate,
/// on `[-1, 1]`) to a slave node or to each other are one: a master node
/// that projects onto a slave node, or within this of it, does not create
/// a piece (the integrand's kink then sits at the piece's end, where the
/// rule's error is of the order of the distance squared).
pub const SPLIT_TOL: f64 = 1e-9;

/// Whether `xi` is a split of its own: finite, strictly inside the
/// segment by more than [`SPLIT_TOL`], and more than [`SPLIT_TOL`] away
/// from every split in `splits`.
pub fn is_new_split(xi: f64, splits: &[f64]) -> bool {
    xi > -1.0 + SPLIT_TOL
        && xi < 1.0 - SPLIT_TOL
        && splits.iter().all(|s| (s - xi).abs() > SPLIT_TOL)
}

/// The slave coordinate whose projection onto the master segment `master`
/// (`[M1, M2]`) lands on its end `end` (0: `M1`, `xi_m = -1`; 1: `M2`,
/// `xi_m = +1`), for the slave segment `slave` (`[A, B]`) and the
/// projection of `formulation` (module docs, "The split"). Not finite when
/// no slave point projects there (closest point, perpendicular segments).
pub fn slave_coordinate_of_master_end(
    formulation: Formulation,
    slave: [[f64; 2]; 2],
    master: [[f64; 2]; 2],
    end: usize,
) -> f64 {
    let [a, b] = slave;
    let t_s = [b[0] - a[0], b[1] - a[1]];
    let e = master[end];
    let ea = [e[0] - a[0], e[1] - a[1]];
    let dir = match formulation {
        // quadratic-slave-normal on a straight segment (the scene refuses
        // it; its mid nodes would sit at the chord midpoints) is slave-normal.
        Formulation::SlaveNormal | Formulation::QuadraticSlaveNormal => t_s,
        Formulation::ClosestPoint => [master[1][0] - master[0][0], master[1][1] - master[0][1]],
        // Faces (3D) are refused before any pairing (the scene and the run
        // take 8-coordinate formulations only): no split.
        Formulation::Tri3SlaveNormal
        | Formulation::Tri3ClosestPoint
        | Formulation::Quad4SlaveNormal
        | Formulation::Quad4ClosestPoint
        | Formulation::Tri3Quad4SlaveNormal
        | Formulation::Tri3Quad4ClosestPoint
        | Formulation::Quad4Tri3SlaveNormal
        | Formulation::Quad4Tri3ClosestPoint => return f64::NAN,
    };
    let frac = (ea[0] * dir[0] + ea[1] * dir[1]) / (t_s[0] * dir[0] + t_s[1] * dir[1]);
    2.0 * frac - 1.0
}

/// The splits of the slave segment `slave` by the master segments
/// `masters` (reference coordinates), sorted (module docs, "The split").
pub fn split_coordinates(
    formulation: Formulation,
    slave: [[f64; 2]; 2],
    masters: &[[[f64; 2]; 2]],
) -> Vec<f64> {
    let mut splits = Vec::new();
    for &m in masters {
        for end in 0..2 {
            let xi = slave_coordinate_of_master_end(formulation, slave, m, end);
            if is_new_split(xi, &splits) {
                splits.push(xi);
            }
        }
    }
    splits.sort_by(f64::total_cmp);
    splits
}

/// The rule `rule` (points and weights on `[-1, 1]`) mapped onto each
/// piece between consecutive `splits` (sorted, inside `(-1, 1)`), piece by
/// piece from `xi = -1`: points `(a + b)/2 + (b - a)/2 x` with weights
/// `w (b - a)/2`.
pub fn segmented_rule(rule: &[(f64, f64)], splits: &[f64]) -> Vec<(f64, f64)> {
    let ends: Vec<f64> = std::iter::once(-1.0)
        .chain(splits.iter().copied())
        .chain(std::iter::once(1.0))
        .collect();
    ends.windows(2)
        .flat_map(|piece| {
            let (mid, half) = ((piece[0] + piece[1]) / 2.0, (piece[1] - piece[0]) / 2.0);
            rule.iter().map(move |&(x, w)| (mid + half * x, w * half))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::gauss_legendre;

    const FORMULATIONS: [Formulation; 2] = [Formulation::SlaveNormal, Formulation::ClosestPoint];

    /// Non-matching flat faces: a slave segment from `x = 0.45` to `0.25`
    /// (the bottom of an upper body, counter-clockwise) and master nodes
    /// every `1/7`: the splits are the two master nodes inside it, for both
    /// formulations.
    #[test]
    fn flat_faces_split_at_the_master_nodes() {
        let slave = [[0.45, 0.5], [0.25, 0.5]];
        let masters: Vec<[[f64; 2]; 2]> = (0..7)
            .map(|i| [[i as f64 / 7.0, 0.5], [(i + 1) as f64 / 7.0, 0.5]])
            .collect();
        for f in FORMULATIONS {
            let s = split_coordinates(f, slave, &masters);
            // x = 0.45 - 0.1 (1 + xi): nodes 2/7 and 3/7 lie inside
            let expect: Vec<f64> = [3.0 / 7.0, 2.0 / 7.0]
                .iter()
                .map(|x| (0.45 - x) / 0.1 - 1.0)
                .collect();
            assert_eq!(s.len(), 2, "{f:?}: {s:?}");
            for (a, b) in s.iter().zip(&expect) {
                assert!((a - b).abs() < 1e-14, "{f:?}: {s:?} vs {expect:?}");
            }
        }
    }

    /// The split is where the formulation's own projection (the kernels')
    /// lands on the master segment's end: `xi_m = -1` or `+1`.
    #[test]
    fn splits_agree_with_the_kernels_projection() {
        let slave = [[1.3, 0.1], [-0.2, 0.25]];
        let masters = [
            [[1.6, -0.1], [0.9, 0.08]],
            [[0.9, 0.08], [0.35, -0.05]],
            [[0.35, -0.05], [-0.5, 0.02]],
        ];
        for f in FORMULATIONS {
            let mut checked = 0;
            for m in masters {
                for end in 0..2 {
                    let xi = slave_coordinate_of_master_end(f, slave, m, end);
                    if !(xi.abs() < 1.0) {
                        continue;
                    }
                    let q = [
                        slave[0][0],
                        slave[0][1],
                        slave[1][0],
                        slave[1][1],
                        m[0][0],
                        m[0][1],
                        m[1][0],
                        m[1][1],
                    ];
                    let p = contact_kernels::project(f, &q, xi).unwrap();
                    let target = [-1.0, 1.0][end];
                    assert!(
                        (p.xi_m - target).abs() < 1e-12,
                        "{f:?}: {} vs {target}",
                        p.xi_m
                    );
                    checked += 1;
                }
            }
            assert!(checked >= 4, "{f:?}: {checked}");
            // with a bent master face, closest point splits twice per
            // interior node, slave normal once
            let n = split_coordinates(f, slave, &masters).len();
            assert_eq!(
                n,
                if f == Formulation::SlaveNormal { 2 } else { 4 },
                "{f:?}"
            );
        }
    }

    /// A master node on a slave node, or within the tolerance of one or of
    /// another split, makes no piece; nothing non-finite does either.
    #[test]
    fn near_duplicate_splits_make_no_piece() {
        let slave = [[0.0, 0.0], [1.0, 0.0]];
        let tiny = 0.1 * SPLIT_TOL;
        let masters = [
            [[1.0 + tiny, 0.0], [0.5, 0.0]],
            [[0.5, 0.0], [0.5 - tiny, 0.0]],
            [[0.5 - tiny, 0.0], [-tiny, 0.0]],
        ];
        for f in FORMULATIONS {
            assert_eq!(split_coordinates(f, slave, &masters), [0.0], "{f:?}");
        }
        assert!(!is_new_split(f64::NAN, &[]));
        assert!(!is_new_split(f64::INFINITY, &[]));
        assert!(!is_new_split(1.0 - tiny, &[]));
        assert!(is_new_split(0.5, &[0.5 + 2.0 * SPLIT_TOL]));
        // a master segment perpendicular to the slave: no closest-point split
        let perpendicular = [[[0.3, 0.0], [0.3, 1.0]]];
        assert!(split_coordinates(Formulation::ClosestPoint, slave, &perpendicular).is_empty());
        let rule = gauss_legendre(3);
        let points = segmented_rule(&rule, &[-1.0 + 2.0 * SPLIT_TOL, 0.0]);
        assert!(points.iter().all(|&(x, w)| x.abs() < 1.0 && w > 0.0));
    }

    /// Without splits the rule is the Gauss rule itself; with splits it
    /// integrates a function with kinks at the splits exactly (a
    /// piecewise polynomial of degree `2 n - 1`), and its weights add up
    /// to 2.
    #[test]
    fn segmented_rule_integrates_kinked_polynomials_exactly() {
        for n in 1..=8 {
            let rule = gauss_legendre(n);
            assert_eq!(segmented_rule(&rule, &[]), rule);
            let splits = [-0.37, 0.2, 0.81];
            let seg = segmented_rule(&rule, &splits);
            assert_eq!(seg.len(), 4 * n);
            let total: f64 = seg.iter().map(|p| p.1).sum();
            assert!((total - 2.0).abs() < 1e-14);
            // kinks at all three splits, degree 2n - 1 between them
            let k = 2 * n as i32 - 1;
            let f = |x: f64| {
                (x - 0.2).abs().powi(k) + (x + 0.37).max(0.0).powi(k) + (0.81 - x).max(0.0).powi(k)
            };
            let up = |v: f64| v.powi(k + 1) / (k + 1) as f64;
            let exact = up(0.8) + up(1.2) + up(1.37) + up(1.81);
            let q: f64 = seg.iter().map(|&(x, w)| w * f(x)).sum();
            assert!(
                (q - exact).abs() < 1e-12 * exact.abs(),
                "n={n}: {q} vs {exact}"
            );
        }
    }

    /// The limit of a split fixed in the reference configuration: when the
    /// master node slides by `delta` from where it projected, the kink of
    /// its shape function `N_m` (slope jump `2/h`, `h` the master segment
    /// length) sits `delta` inside a piece, and the 2-point rule misses
    /// `integral N_m` by exactly `delta^2 / h` (while `delta` is smaller
    /// than the distance from the piece's end to its first Gauss point):
    /// relative to the node's share of the pressure, about `(delta / h)^2`.
    #[test]
    fn reference_split_error_grows_with_the_slip_squared() {
        let (node, h) = (0.3, 0.8);
        let slave = [[0.0, 0.0], [1.0, 0.0]];
        let masters = [
            [[node + h, 0.0], [node, 0.0]],
            [[node, 0.0], [node - h, 0.0]],
        ];
        let hat = |x: f64, c: f64| (1.0 - (x - c).abs() / h).max(0.0);
        // integral over x in [0, 1] of the hat at c (its support covers it)
        let exact = |c: f64| c - c * c / (2.0 * h) + (1.0 - c) - (1.0 - c).powi(2) / (2.0 * h);
        for f in FORMULATIONS {
            let points = segmented_rule(&gauss_legendre(2), &split_coordinates(f, slave, &masters));
            let quad = |c: f64| -> f64 {
                points
                    .iter()
                    .map(|&(xi, w)| w / 2.0 * hat((1.0 + xi) / 2.0, c))
                    .sum()
            };
            assert!((quad(node) - exact(node)).abs() < 1e-15, "{f:?}");
            for delta in [-1e-2, -1e-3, 1e-3, 1e-2] {
                let error = (quad(node + delta) - exact(node + delta)).abs();
                let expect = delta * delta / h;
                assert!(
                    (error - expect).abs() < 1e-12,
                    "{f:?} {delta}: {error} vs {expect}"
                );
            }
        }
    }
}
