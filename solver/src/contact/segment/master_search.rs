//! The search over every master segment through the spatial index
//! ([`super::face_index`]): which segment a slave point projects into with
//! the smallest `|g|`, the same segment (and the same one on a tie) as
//! trying every segment in order, at `O(log n + k)` per point instead of
//! `O(n)`.
//!
//! # What the full scan chooses
//!
//! The scan of `search.rs` (and of the nodal contact table,
//! `nodal.rs`) tries master segments `0, 1, ..., n - 1`, keeps those
//! the point projects into (`|xi_m| <= 1 + `[`XI_INSIDE_TOL`]) and replaces
//! its choice only on a strictly smaller `|g|`: it chooses the segment with
//! the smallest `|g|`, the smallest index among equal `|g|`. It returns a
//! kernel error instead when any segment gives a slave-side one
//! (`super::slave_side`).
//!
//! # Why the candidates hold that choice
//!
//! For the formulations whose gap is a distance ([`gap_is_distance`]:
//! `slave-normal` and `closest-point`), the projection `x_m = x_m(xi_m)`
//! satisfies `x_m - x_s = g n` with a unit normal `n`: the gap vector runs
//! along the slave normal (`slave-normal`: `(x_m - x_s) . t_s = 0` and
//! `n = perp(t_s) / |t_s|`) or along the master normal (`closest-point`).
//! So `|g| = |x_m - x_s|`, and where the point projects into segment `f`
//! (`|xi_m| <= 1 + XI_INSIDE_TOL`), `x_m` lies on `f` or on its extension by
//! at most `XI_INSIDE_TOL L_f / 2` beyond an end (`L_f` its length): inside
//! `f`'s box inflated by `margin_f = (XI_INSIDE_TOL + XI_SLACK) L_f / 2`
//! (an extension of length `e` moves each coordinate by at most `e`). Hence
//!
//! ```text
//! dist(x_s, B_f) <= |x_m - x_s| = |g_f|.
//! ```
//!
//! The index answers every segment with `dist(x_s, B_f) <= r`, in
//! ascending order. Trying those at `r = r0` (the longest master segment)
//! gives the best candidate `g*` (smallest `|g|`, then smallest index); if
//! `need = |g*| + slack(|g*|) <= r`, every segment with `|g_f| <= |g*|`
//! has `dist(x_s, B_f) <= need <= r` and was tried, so the candidates'
//! choice is the scan's. Otherwise the query is repeated at `r = need`
//! (the segments already tried are not tried again); the best can only
//! improve, so this second query settles it. When no candidate is found
//! at `r0`, or a candidate gives a slave-side error, the caller runs the
//! full scan ([`MasterIndex::nearest_inside`] returns `None`): a point
//! that projects into no segment costs what it costs today.
//!
//! # Rounding
//!
//! The kernel's `xi_m` and `g` are rounded values of the exact ones. The
//! bound above holds for them when `xi_m` is within [`XI_SLACK`] of the
//! exact projection (the box margin) and `|g|` within
//! `slack(|g|) = DISTANCE_SLACK (|g| + S)` of the exact distance, with `S`
//! the largest coordinate magnitude of the slave segment and of the master
//! boxes (the kernels work in coordinates relative to a slave node, so
//! their rounding is relative to `S`). These are about `1e10` and `1e7`
//! times the double precision's unit: only a projection conditioned beyond
//! that (a master segment within about `1e-7` rad of the slave normal's
//! perpendicular) could escape them.
//!
//! # Kernel errors
//!
//! The scan reports a slave-side error if any master segment gives one.
//! The index is used only where none can: both slave nodes and `xi_s`
//! finite, every master node finite (else no index is built), a compiled
//! two-node formulation, and a slave segment longer than twice the
//! kernels' degenerate threshold ([`DEGENERATE_LENGTH`] times the
//! configuration's size) for the largest size any master segment can give
//! (the distance from the slave's first node to the master boxes' union).
//! Otherwise `nearest_inside` returns `None` and the caller scans.
//!
//! # When
//!
//! Pairs with fewer than [`INDEX_MIN_SEGMENTS`] master segments are
//! scanned: the index costs `O(n log n)` to build for each configuration,
//! more than a few scans of a short master face.

use contact_kernels::{DEGENERATE_LENGTH, Formulation, PAIR_COORDS};

use crate::contact::XI_INSIDE_TOL;
use crate::contact::face_index::{Aabb, FaceIndex, QueryStats};

/// Pairs with fewer master segments are scanned (module docs, "When").
pub const INDEX_MIN_SEGMENTS: usize = 64;

/// The rounding allowed in a kernel's `xi_m` (module docs, "Rounding").
pub const XI_SLACK: f64 = 1e-6;

/// The rounding allowed in a kernel's `|g|`, relative to `|g|` plus the
/// coordinates' magnitude (module docs, "Rounding").
pub const DISTANCE_SLACK: f64 = 1e-9;

/// Whether `formulation`'s gap is the distance from the slave point to its
/// projection (module docs): the index may then choose for the scan.
pub fn gap_is_distance(formulation: Formulation) -> bool {
    matches!(
        formulation,
        Formulation::SlaveNormal | Formulation::ClosestPoint
    ) && formulation.coords() == Some(PAIR_COORDS)
}

/// What trying one master segment found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Tried<T> {
    /// The point projects into the segment (as the scan tests it), with
    /// `abs_gap = |g|` and the caller's result.
    Inside {
        /// `|g|` on this segment.
        abs_gap: f64,
        /// What the caller keeps of the projection.
        value: T,
    },
    /// Not this segment (not facing, outside, a master-side kernel error).
    Elsewhere,
    /// A slave-side kernel error: only the full scan reports it as the
    /// scan does.
    Unsure,
}

/// The index over one pair's master segments in one configuration.
#[derive(Debug, Clone)]
pub struct MasterIndex {
    index: FaceIndex<2>,
    /// The union of the segments' boxes.
    bounds: Aabb<2>,
    /// The first query's radius: the longest segment.
    radius: f64,
}

impl MasterIndex {
    /// The index over `segments` (their nodes' current coordinates);
    /// `None` when there is none or a coordinate is not finite (the scan
    /// then reports what it reports today).
    pub fn build(segments: &[[[f64; 2]; 2]]) -> Option<MasterIndex> {
        let mut radius: f64 = 0.0;
        let mut boxes = Vec::with_capacity(segments.len());
        for (f, [a, b]) in segments.iter().enumerate() {
            let length = (b[0] - a[0]).hypot(b[1] - a[1]);
            radius = radius.max(length);
            let margin = (XI_INSIDE_TOL + XI_SLACK) * length / 2.0;
            boxes.push(Aabb::around(f, &[*a, *b], margin).ok()?);
        }
        if !radius.is_finite() {
            return None;
        }
        let bounds = boxes.iter().copied().reduce(|u, b| Aabb {
            min: [u.min[0].min(b.min[0]), u.min[1].min(b.min[1])],
            max: [u.max[0].max(b.max[0]), u.max[1].max(b.max[1])],
        })?;
        Some(MasterIndex {
            index: FaceIndex::build(boxes).ok()?,
            bounds,
            radius,
        })
    }

    /// The number of segments.
    pub fn len(&self) -> usize {
        self.index.len()
    }

    /// Whether the index holds no segment (never: [`Self::build`] refuses).
    pub fn is_empty(&self) -> bool {
        self.index.is_empty()
    }

    /// The segment the slave point `x_s(xi_s)` of slave segment `slave`
    /// projects into with the smallest `|g|` (the smallest index on a
    /// tie) and `try_segment`'s value there, exactly as the full scan
    /// chooses; `None` when the index cannot decide (module docs) and the
    /// caller must scan. `try_segment(f)` tries segment `f` as the scan
    /// does; `stats` adds the index's work.
    pub fn nearest_inside<T>(
        &self,
        slave: [[f64; 2]; 2],
        xi_s: f64,
        stats: &mut QueryStats,
        mut try_segment: impl FnMut(usize) -> Tried<T>,
    ) -> Option<(usize, T)> {
        let [a, b] = slave;
        if !(xi_s.is_finite() && a.iter().chain(&b).all(|v| v.is_finite())) {
            return None;
        }
        // The largest coordinate difference to the slave's first node any
        // master segment can give (the kernels' "size"), and the slave's
        // squared length as the kernels compute it.
        let mut size: f64 = (b[0] - a[0]).abs().max((b[1] - a[1]).abs());
        let mut scale: f64 = 0.0;
        for k in 0..2 {
            for c in [self.bounds.min[k], self.bounds.max[k]] {
                size = size.max((c - a[k]).abs());
                scale = scale.max(c.abs());
            }
            scale = scale.max(a[k].abs()).max(b[k].abs());
        }
        let length2 = (b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2);
        let threshold = 2.0 * DEGENERATE_LENGTH * size;
        #[allow(clippy::neg_cmp_op_on_partial_ord)]
        if !(length2 > threshold * threshold) {
            return None;
        }
        let (n1, n2) = ((1.0 - xi_s) / 2.0, (1.0 + xi_s) / 2.0);
        let x_s = [n1 * a[0] + n2 * b[0], n1 * a[1] + n2 * b[1]];
        let slack = |g: f64| DISTANCE_SLACK * (g + scale);

        let mut radius = self.radius;
        let mut tried: Vec<usize> = Vec::new();
        let mut best: Option<(f64, usize, T)> = None;
        loop {
            let found = self.index.query_point_counted(&x_s, radius, stats).ok()?;
            // `tried` is ascending and a subset of `found` (a larger ball).
            let mut old = tried.iter().peekable();
            for &f in &found {
                if old.next_if_eq(&&f).is_some() {
                    continue;
                }
                match try_segment(f) {
                    Tried::Inside { abs_gap, value } => {
                        if best
                            .as_ref()
                            .is_none_or(|(g, m, _)| abs_gap < *g || (abs_gap == *g && f < *m))
                        {
                            best = Some((abs_gap, f, value));
                        }
                    }
                    Tried::Elsewhere => {}
                    Tried::Unsure => return None,
                }
            }
            tried = found;
            let need = {
                let (g, _, _) = best.as_ref()?;
                g + slack(*g)
            };
            if need <= radius {
                return best.map(|(_, m, value)| (m, value));
            }
            radius = need;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testutil::Lcg;

    #[test]
    fn only_the_distance_formulations_use_the_index() {
        for f in Formulation::ALL {
            let expected = matches!(f, Formulation::SlaveNormal | Formulation::ClosestPoint)
                && contact_kernels::pair_formulations().contains(&f);
            assert_eq!(gap_is_distance(f), expected, "{f}");
        }
        assert!(gap_is_distance(Formulation::SlaveNormal));
        assert!(gap_is_distance(Formulation::ClosestPoint));
    }

    #[test]
    fn no_index_without_segments_or_with_a_non_finite_node() {
        assert!(MasterIndex::build(&[]).is_none());
        assert!(MasterIndex::build(&[[[0.0, 0.0], [f64::NAN, 0.0]]]).is_none());
        assert!(MasterIndex::build(&[[[0.0, 0.0], [f64::INFINITY, 0.0]]]).is_none());
        let index = MasterIndex::build(&[[[0.0, 0.0], [1.0, 0.0]]]).unwrap();
        assert_eq!(index.len(), 1);
        assert!(!index.is_empty());
    }

    /// What the index declines: non-finite slave input, a slave segment the
    /// kernels may call degenerate for some master segment, a candidate's
    /// slave-side error, a point that projects into no candidate.
    #[test]
    fn the_index_declines_what_only_the_scan_can_answer() {
        let index =
            MasterIndex::build(&[[[0.0, 0.0], [1.0, 0.0]], [[1.0, 0.0], [2.0, 0.0]]]).unwrap();
        let inside = |_: usize| Tried::Inside {
            abs_gap: 0.0,
            value: (),
        };
        let slave = [[1.0, 0.0], [0.0, 0.0]];
        let mut stats = QueryStats::default();
        assert_eq!(
            index.nearest_inside(slave, 0.0, &mut stats, inside),
            Some((0, ()))
        );
        assert!(stats.nodes_visited > 0);
        for bad in [
            [[f64::NAN, 0.0], [0.0, 0.0]],
            [[1.0, 0.0], [f64::INFINITY, 0.0]],
        ] {
            assert_eq!(index.nearest_inside(bad, 0.0, &mut stats, inside), None);
        }
        assert_eq!(
            index.nearest_inside(slave, f64::NAN, &mut stats, inside),
            None
        );
        // 1e-12 long at distance ~1e3 from the master: degenerate for the
        // kernels (threshold 1e-7) on some segment.
        let tiny = [[1000.0, 0.0], [1000.0 - 1e-12, 0.0]];
        assert_eq!(index.nearest_inside(tiny, 0.0, &mut stats, inside), None);
        let unsure = |f: usize| {
            if f == 1 {
                Tried::Unsure
            } else {
                Tried::Inside {
                    abs_gap: 0.0,
                    value: (),
                }
            }
        };
        assert_eq!(index.nearest_inside(slave, 0.0, &mut stats, unsure), None);
        let nowhere = |_: usize| Tried::<()>::Elsewhere;
        assert_eq!(index.nearest_inside(slave, 0.0, &mut stats, nowhere), None);
    }

    /// A candidate at a large gap: the second query at `|g| + slack`
    /// settles it, and a segment the first query missed wins there.
    #[test]
    fn a_far_best_is_settled_by_a_second_query() {
        // Segment 0 far above, segment 1 close below the point (at x = 50).
        let segments = [[[0.0, 10.0], [1.0, 10.0]], [[60.0, -3.0], [40.0, -3.0]]];
        let index = MasterIndex::build(&segments).unwrap();
        let slave = [[51.0, 0.0], [49.0, 0.0]];
        let mut calls = Vec::new();
        let gaps = [50.0_f64.hypot(10.0), 3.0];
        let got = index.nearest_inside(slave, 0.0, &mut QueryStats::default(), |f| {
            calls.push(f);
            Tried::Inside {
                abs_gap: gaps[f],
                value: f,
            }
        });
        assert_eq!(got, Some((1, 1)));
        assert_eq!(calls, [1]);
        // Only the far one projects: the first query (radius 20) finds
        // nothing and declines.
        let mut calls = Vec::new();
        let got = index.nearest_inside(slave, 0.0, &mut QueryStats::default(), |f| {
            calls.push(f);
            if f == 0 {
                Tried::Inside {
                    abs_gap: gaps[0],
                    value: f,
                }
            } else {
                Tried::Elsewhere
            }
        });
        assert_eq!((got, calls), (None, vec![1]));
        // Both project, the near one at a larger gap than the radius:
        // the second query tries segment 0 too, and the tie goes to it.
        let mut calls = Vec::new();
        let got = index.nearest_inside(slave, 0.0, &mut QueryStats::default(), |f| {
            calls.push(f);
            Tried::Inside {
                abs_gap: gaps[0],
                value: f,
            }
        });
        assert_eq!((got, calls), (Some((0, 0)), vec![1, 0]));
    }

    /// Random chains and points, both formulations, with the real
    /// projection kernel: the index chooses what the scan chooses.
    #[test]
    fn random_choices_match_the_scan() {
        let mut rng = Lcg::new(2024);
        let (mut decided, mut scanned) = (0, 0);
        for case in 0..300 {
            let n = 1 + (rng.uniform(0.0, 80.0) as usize);
            let segments = random_master(&mut rng, n, case % 3 == 0);
            let index = MasterIndex::build(&segments).unwrap();
            for formulation in [Formulation::SlaveNormal, Formulation::ClosestPoint] {
                for _ in 0..20 {
                    let c = [rng.uniform(-1.0, 11.0), rng.uniform(-2.0, 2.0)];
                    let angle = rng.uniform(0.0, std::f64::consts::TAU);
                    let h = rng.uniform(0.01, 0.5);
                    let slave = [
                        [c[0] + h * angle.cos(), c[1] + h * angle.sin()],
                        [c[0] - h * angle.cos(), c[1] - h * angle.sin()],
                    ];
                    let xi_s = [-1.0, 1.0, -0.577, 0.3][rng.uniform(0.0, 4.0) as usize];
                    let try_one = |f: usize| try_segment(formulation, &segments, slave, xi_s, f);
                    let scan = scan(&segments, try_one);
                    match index.nearest_inside(slave, xi_s, &mut QueryStats::default(), try_one) {
                        Some(got) => {
                            decided += 1;
                            assert_eq!(Some(got), scan, "case {case}, {formulation}");
                        }
                        None => scanned += 1,
                    }
                }
            }
        }
        // Both ways were taken, the index's often (a point that projects
        // into no candidate goes to the scan).
        assert!(
            decided > 2000 && scanned > 0,
            "{decided} decided, {scanned} scanned"
        );
    }

    /// Ties: repeated segments (equal `|g|` on several) go to the first.
    #[test]
    fn ties_go_to_the_first_segment() {
        let mut rng = Lcg::new(7);
        let mut ties = 0;
        for _ in 0..200 {
            let mut segments = random_master(&mut rng, 30, false);
            // segments 5 and 20 become copies of 12 (one reversed)
            segments[5] = segments[12];
            segments[20] = [segments[12][1], segments[12][0]];
            let index = MasterIndex::build(&segments).unwrap();
            let [a, b] = segments[12];
            let m = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
            let slave = [
                [m[0] + 0.1, m[1] + rng.uniform(-0.3, 0.3)],
                [m[0] - 0.1, m[1] + rng.uniform(-0.3, 0.3)],
            ];
            for formulation in [Formulation::SlaveNormal, Formulation::ClosestPoint] {
                let try_one = |f: usize| try_segment(formulation, &segments, slave, 0.0, f);
                let scan = scan(&segments, try_one);
                if let Some(got) =
                    index.nearest_inside(slave, 0.0, &mut QueryStats::default(), try_one)
                {
                    assert_eq!(Some(got), scan);
                    if [5, 12, 20].contains(&got.0) {
                        ties += 1;
                        assert_eq!(got.0, 5);
                    }
                }
            }
        }
        assert!(ties > 50, "{ties}");
    }

    /// The index's work per point (tree nodes and face boxes tested,
    /// segments projected onto) on chains of 100, 1000 and 10000 segments
    /// of length 0.1, with slave segments lying on the chain (contact):
    /// it grows with `log n`, not `n`. Counts, no timing.
    #[test]
    fn work_per_point_grows_logarithmically() {
        let mut rng = Lcg::new(99);
        let mut mean_work = Vec::new();
        for n in [100, 1000, 10_000] {
            let node = |i: usize| {
                let x = 0.1 * (n - i) as f64;
                [x, 0.3 * x.sin()]
            };
            let segments: Vec<[[f64; 2]; 2]> = (0..n).map(|i| [node(i), node(i + 1)]).collect();
            let index = MasterIndex::build(&segments).unwrap();
            let (mut total, mut worst, points) = (0, 0, 500);
            for _ in 0..points {
                let x = rng.uniform(0.5, 0.1 * n as f64 - 0.5);
                let y = 0.3 * x.sin() + rng.uniform(-0.01, 0.01);
                let slope = 0.3 * x.cos();
                let t = [0.05, 0.05 * slope];
                let slave = [[x - t[0], y - t[1]], [x + t[0], y + t[1]]];
                let mut stats = QueryStats::default();
                let mut projected = 0;
                let chosen = index.nearest_inside(slave, 0.3, &mut stats, |f| {
                    projected += 1;
                    try_segment(Formulation::SlaveNormal, &segments, slave, 0.3, f)
                });
                assert!(chosen.is_some(), "n = {n}: {slave:?}");
                let work = stats.nodes_visited + stats.faces_tested + projected;
                total += work;
                worst = worst.max(work);
            }
            let mean = total as f64 / points as f64;
            mean_work.push((n, mean, worst));
        }
        // work / log2(n) stays within 1.5 times its value at n = 100
        let (n0, m0, w0) = mean_work[0];
        let (c_mean, c_worst) = (m0 / (n0 as f64).log2(), w0 as f64 / (n0 as f64).log2());
        for &(n, mean, worst) in &mean_work {
            let log_n = (n as f64).log2();
            assert!(mean <= 1.5 * c_mean * log_n, "{mean_work:?}");
            assert!(worst as f64 <= 1.5 * c_worst * log_n, "{mean_work:?}");
        }
        // far from a scan's n projections per point at n = 10000
        assert!(mean_work[2].2 * 50 < 10_000, "{mean_work:?}");
        // and it does grow (the tree deepens): the count is not constant
        assert!(mean_work[2].1 > mean_work[0].1, "{mean_work:?}");
    }

    /// A master chain of `n` segments along `0 <= x <= 10`: wavy, or (when
    /// `scatter`) with a third of the segments thrown anywhere.
    fn random_master(rng: &mut Lcg, n: usize, scatter: bool) -> Vec<[[f64; 2]; 2]> {
        let amplitude = rng.uniform(0.0, 1.0);
        let phase = rng.uniform(0.0, 6.0);
        let node = |i: usize| {
            let x = 10.0 - 10.0 * i as f64 / n as f64;
            [x, amplitude * (x + phase).sin()]
        };
        (0..n)
            .map(|i| {
                if scatter && rng.uniform(0.0, 1.0) < 0.33 {
                    let c = [rng.uniform(-2.0, 12.0), rng.uniform(-3.0, 3.0)];
                    let d = [rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)];
                    [[c[0] - d[0], c[1] - d[1]], [c[0] + d[0], c[1] + d[1]]]
                } else {
                    [node(i), node(i + 1)]
                }
            })
            .collect()
    }

    /// The scan's test on one segment (as `search.rs` makes it,
    /// facing check aside): the projection kernel, inside by
    /// `|xi_m| <= 1 + XI_INSIDE_TOL`.
    fn try_segment(
        formulation: Formulation,
        segments: &[[[f64; 2]; 2]],
        slave: [[f64; 2]; 2],
        xi_s: f64,
        f: usize,
    ) -> Tried<f64> {
        let [s1, s2] = slave;
        let [m1, m2] = segments[f];
        let q = [s1[0], s1[1], s2[0], s2[1], m1[0], m1[1], m2[0], m2[1]];
        match contact_kernels::project(formulation, &q, xi_s) {
            Ok(p) if p.xi_m.abs() <= 1.0 + XI_INSIDE_TOL => Tried::Inside {
                abs_gap: p.gap.abs(),
                value: p.gap,
            },
            Ok(_) => Tried::Elsewhere,
            Err(e) if crate::contact::slave_side(&e) => Tried::Unsure,
            Err(_) => Tried::Elsewhere,
        }
    }

    /// Today's scan: every segment in order, a strictly smaller `|g|`
    /// replaces the choice.
    fn scan(
        segments: &[[[f64; 2]; 2]],
        mut try_one: impl FnMut(usize) -> Tried<f64>,
    ) -> Option<(usize, f64)> {
        let mut best: Option<(usize, f64)> = None;
        for f in 0..segments.len() {
            if let Tried::Inside { abs_gap, value } = try_one(f)
                && best.is_none_or(|(_, g)| abs_gap < g.abs())
            {
                best = Some((f, value));
            }
        }
        best
    }
}
