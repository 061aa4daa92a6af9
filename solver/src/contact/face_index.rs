//! A spatial index over master faces: a bounding-volume hierarchy of
//! axis-aligned boxes, generic over the dimension `D` (2D segments, 3D
//! faces).
//!
//! # What it answers
//!
//! Every master face `f` has a box `B_f = [min_f, max_f]` (its nodes' box,
//! inflated by a margin the caller chooses, [`Aabb::around`]). A query asks
//! for the faces whose box meets
//!
//! - a box `Q`: `min_f[k] <= Q.max[k]` and `Q.min[k] <= max_f[k]` on every
//!   axis `k` (closed boxes: touching counts), or
//! - a ball of centre `p` and radius `r`: `dist(p, B_f) <= r`, with
//!   `dist(p, B)^2 = sum_k max(min[k] - p[k], 0, p[k] - max[k])^2`, or
//! - a line `p + t d` (every real `t`): the line meets `B_f` inflated by `r`
//!   on every side (the slab test, [`Aabb::meets_line`]).
//!
//! The answer is the list of face indices in **ascending** order, whatever
//! the tree's shape, so a caller that tries candidates in order picks the
//! same face as a loop over all faces would. A point that projects into a
//! face at a distance of at most `margin` from it lies in the face's box
//! inflated by `margin`, so a point query with radius 0 on boxes built with
//! that margin returns a superset of the faces the point can project into.
//!
//! # The tree
//!
//! Built top down: a node's faces are split at the median of their box
//! centres along the axis where the centres spread most (ties broken by
//! the face index, so the tree depends on the input only), until at most
//! [`LEAF_SIZE`] faces remain. Every node stores the union of its faces'
//! boxes. A query descends only into nodes whose box meets the query, then
//! sorts what the leaves hold. The median split gives depth
//! `ceil(log2(n / LEAF_SIZE))`, so a query that meets `k` faces visits
//! `O(log n + k)` nodes on a mesh of well-shaped faces; [`QueryStats`]
//! counts the visits (the tests check the growth on regular grids).
//!
//! # Why hand-written
//!
//! `rstar` (an R*-tree) is the well-kept candidate and is lean to build,
//! but its queries return in tree order (the ascending order above needs a
//! sort anyway), it exposes no count of visited nodes (which the tests use
//! to prove the logarithmic cost without timing), and its envelopes would
//! be rebuilt from our boxes. The median-split tree here is about a
//! hundred lines with no dependency.
//!
//! # Errors
//!
//! A non-finite coordinate, a box with `min > max`, a negative or
//! non-finite margin or radius is an [`IndexError`]; nothing panics. An
//! empty list builds an empty index (every query answers nothing);
//! zero-size boxes (a face collapsed to a point) are valid.

use thiserror::Error;

/// Faces per leaf of the tree.
pub const LEAF_SIZE: usize = 4;

/// Bad input to the index.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum IndexError {
    /// A coordinate of face `face`'s box (or its nodes) is not finite.
    #[error("face {face}: coordinate {axis} is not finite ({value})")]
    NonFinite {
        /// The face.
        face: usize,
        /// The coordinate axis.
        axis: usize,
        /// The value found.
        value: f64,
    },
    /// Face `face`'s box has `min > max` on axis `axis`.
    #[error("face {face}: box min {min} > max {max} on axis {axis}")]
    Inverted {
        /// The face.
        face: usize,
        /// The coordinate axis.
        axis: usize,
        /// The box's lower bound.
        min: f64,
        /// The box's upper bound.
        max: f64,
    },
    /// A face given with no nodes to box.
    #[error("face {face} has no nodes")]
    NoNodes {
        /// The face.
        face: usize,
    },
    /// A margin or radius that is negative or not finite.
    #[error("{what} must be finite and non-negative (got {value})")]
    BadDistance {
        /// `margin` or `radius`.
        what: &'static str,
        /// The value given.
        value: f64,
    },
    /// A query point or box with a non-finite coordinate.
    #[error("query coordinate {axis} is not finite ({value})")]
    NonFiniteQuery {
        /// The coordinate axis.
        axis: usize,
        /// The value given.
        value: f64,
    },
}

/// A closed axis-aligned box `[min, max]` in `D` dimensions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb<const D: usize> {
    /// The lower corner.
    pub min: [f64; D],
    /// The upper corner.
    pub max: [f64; D],
}

impl<const D: usize> Aabb<D> {
    /// The box of `points` inflated by `margin` on every side. `face`
    /// names the face in errors.
    pub fn around(face: usize, points: &[[f64; D]], margin: f64) -> Result<Self, IndexError> {
        check_distance("margin", margin)?;
        let first = points.first().ok_or(IndexError::NoNodes { face })?;
        let mut b = Aabb {
            min: *first,
            max: *first,
        };
        for p in points {
            for k in 0..D {
                if !p[k].is_finite() {
                    return Err(IndexError::NonFinite {
                        face,
                        axis: k,
                        value: p[k],
                    });
                }
                b.min[k] = b.min[k].min(p[k]);
                b.max[k] = b.max[k].max(p[k]);
            }
        }
        for k in 0..D {
            b.min[k] -= margin;
            b.max[k] += margin;
        }
        Ok(b)
    }

    /// Whether the two closed boxes share a point.
    pub fn meets(&self, other: &Aabb<D>) -> bool {
        (0..D).all(|k| self.min[k] <= other.max[k] && other.min[k] <= self.max[k])
    }

    /// The length of the box's diagonal.
    pub fn diagonal(&self) -> f64 {
        (0..D)
            .map(|k| (self.max[k] - self.min[k]).powi(2))
            .sum::<f64>()
            .sqrt()
    }

    /// Whether the box, inflated by `r` on every side, meets the line
    /// `p + t d` (`t` any real): the slab test, the parameters `t` inside
    /// every axis' slab overlapping (closed: touching counts). An axis
    /// along which the line does not move needs `p` inside its slab.
    pub fn meets_line(&self, p: &[f64; D], d: &[f64; D], r: f64) -> bool {
        let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
        for k in 0..D {
            let (a, b) = (self.min[k] - r, self.max[k] + r);
            if d[k] == 0.0 {
                if p[k] < a || p[k] > b {
                    return false;
                }
                continue;
            }
            let (t0, t1) = ((a - p[k]) / d[k], (b - p[k]) / d[k]);
            lo = lo.max(t0.min(t1));
            hi = hi.min(t0.max(t1));
            if lo > hi {
                return false;
            }
        }
        true
    }

    /// The squared Euclidean distance from `p` to the box (0 inside).
    pub fn distance_squared(&self, p: &[f64; D]) -> f64 {
        (0..D)
            .map(|k| {
                let d = (self.min[k] - p[k]).max(p[k] - self.max[k]).max(0.0);
                d * d
            })
            .sum()
    }

    fn union(&self, other: &Aabb<D>) -> Aabb<D> {
        let mut u = *self;
        for k in 0..D {
            u.min[k] = u.min[k].min(other.min[k]);
            u.max[k] = u.max[k].max(other.max[k]);
        }
        u
    }

    fn centre(&self, k: usize) -> f64 {
        0.5 * (self.min[k] + self.max[k])
    }

    fn validate(&self, face: usize) -> Result<(), IndexError> {
        for k in 0..D {
            for value in [self.min[k], self.max[k]] {
                if !value.is_finite() {
                    return Err(IndexError::NonFinite {
                        face,
                        axis: k,
                        value,
                    });
                }
            }
            if self.min[k] > self.max[k] {
                return Err(IndexError::Inverted {
                    face,
                    axis: k,
                    min: self.min[k],
                    max: self.max[k],
                });
            }
        }
        Ok(())
    }
}

fn check_distance(what: &'static str, value: f64) -> Result<(), IndexError> {
    if value.is_finite() && value >= 0.0 {
        Ok(())
    } else {
        Err(IndexError::BadDistance { what, value })
    }
}

#[derive(Debug, Clone)]
enum Kids {
    /// Faces `order[start..end]`.
    Leaf { start: usize, end: usize },
    /// Node indices of the two halves.
    Inner { left: usize, right: usize },
}

#[derive(Debug, Clone)]
struct Node<const D: usize> {
    bounds: Aabb<D>,
    kids: Kids,
}

/// Work done by one query.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct QueryStats {
    /// Tree nodes whose box was tested against the query.
    pub nodes_visited: usize,
    /// Face boxes tested against the query (in the leaves reached).
    pub faces_tested: usize,
}

/// The bounding-volume hierarchy over the faces' boxes.
#[derive(Debug, Clone)]
pub struct FaceIndex<const D: usize> {
    boxes: Vec<Aabb<D>>,
    /// Face indices, grouped so that every leaf is a contiguous range.
    order: Vec<usize>,
    /// Node 0 is the root (absent for an empty index).
    nodes: Vec<Node<D>>,
}

impl<const D: usize> FaceIndex<D> {
    /// Builds the index over `boxes` (face `i` has box `boxes[i]`).
    pub fn build(boxes: Vec<Aabb<D>>) -> Result<Self, IndexError> {
        for (face, b) in boxes.iter().enumerate() {
            b.validate(face)?;
        }
        let mut index = FaceIndex {
            order: (0..boxes.len()).collect(),
            boxes,
            nodes: Vec::new(),
        };
        if !index.boxes.is_empty() {
            index.split(0, index.boxes.len());
        }
        Ok(index)
    }

    /// Builds the index over faces given by their nodes, each face's box
    /// inflated by `margin`.
    pub fn from_faces<F: AsRef<[[f64; D]]>>(faces: &[F], margin: f64) -> Result<Self, IndexError> {
        let boxes = faces
            .iter()
            .enumerate()
            .map(|(face, nodes)| Aabb::around(face, nodes.as_ref(), margin))
            .collect::<Result<Vec<_>, _>>()?;
        Self::build(boxes)
    }

    /// The number of faces.
    pub fn len(&self) -> usize {
        self.boxes.len()
    }

    /// Whether the index holds no face.
    pub fn is_empty(&self) -> bool {
        self.boxes.is_empty()
    }

    /// The depth of the tree (0 when empty, 1 for a single leaf).
    pub fn depth(&self) -> usize {
        fn depth_of<const D: usize>(nodes: &[Node<D>], i: usize) -> usize {
            match nodes[i].kids {
                Kids::Leaf { .. } => 1,
                Kids::Inner { left, right } => {
                    1 + depth_of(nodes, left).max(depth_of(nodes, right))
                }
            }
        }
        if self.nodes.is_empty() {
            0
        } else {
            depth_of(&self.nodes, 0)
        }
    }

    /// Builds the subtree over `order[start..end]` and returns its node.
    fn split(&mut self, start: usize, end: usize) -> usize {
        let bounds = self.order[start..end]
            .iter()
            .map(|&f| self.boxes[f])
            .reduce(|a, b| a.union(&b))
            .expect("split is called on a non-empty range");
        let node = self.nodes.len();
        self.nodes.push(Node {
            bounds,
            kids: Kids::Leaf { start, end },
        });
        if end - start <= LEAF_SIZE {
            return node;
        }
        // The axis along which the box centres spread most.
        let mut axis = 0;
        let mut widest = f64::NEG_INFINITY;
        for k in 0..D {
            let (lo, hi) = self.order[start..end]
                .iter()
                .map(|&f| self.boxes[f].centre(k))
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), c| {
                    (lo.min(c), hi.max(c))
                });
            if hi - lo > widest {
                widest = hi - lo;
                axis = k;
            }
        }
        let mid = start + (end - start) / 2;
        let boxes = &self.boxes;
        self.order[start..end].select_nth_unstable_by(mid - start, |&a, &b| {
            boxes[a]
                .centre(axis)
                .total_cmp(&boxes[b].centre(axis))
                .then(a.cmp(&b))
        });
        let left = self.split(start, mid);
        let right = self.split(mid, end);
        self.nodes[node].kids = Kids::Inner { left, right };
        node
    }

    /// The faces whose box meets `query`, ascending.
    pub fn query_box(&self, query: &Aabb<D>) -> Result<Vec<usize>, IndexError> {
        self.query_box_counted(query, &mut QueryStats::default())
    }

    /// As [`Self::query_box`], adding the work done to `stats`.
    pub fn query_box_counted(
        &self,
        query: &Aabb<D>,
        stats: &mut QueryStats,
    ) -> Result<Vec<usize>, IndexError> {
        for k in 0..D {
            for value in [query.min[k], query.max[k]] {
                if !value.is_finite() {
                    return Err(IndexError::NonFiniteQuery { axis: k, value });
                }
            }
        }
        Ok(self.collect(|b| b.meets(query), stats))
    }

    /// The faces whose box lies within distance `radius` of `point`,
    /// ascending.
    pub fn query_point(&self, point: &[f64; D], radius: f64) -> Result<Vec<usize>, IndexError> {
        self.query_point_counted(point, radius, &mut QueryStats::default())
    }

    /// As [`Self::query_point`], adding the work done to `stats`.
    pub fn query_point_counted(
        &self,
        point: &[f64; D],
        radius: f64,
        stats: &mut QueryStats,
    ) -> Result<Vec<usize>, IndexError> {
        check_distance("radius", radius)?;
        for (k, &value) in point.iter().enumerate() {
            if !value.is_finite() {
                return Err(IndexError::NonFiniteQuery { axis: k, value });
            }
        }
        let r2 = radius * radius;
        Ok(self.collect(|b| b.distance_squared(point) <= r2, stats))
    }

    /// The faces whose box, inflated by `radius` on every side, meets the
    /// line `point + t direction` (`t` any real), ascending. A zero
    /// `direction` is an error (it names no line).
    pub fn query_line(
        &self,
        point: &[f64; D],
        direction: &[f64; D],
        radius: f64,
    ) -> Result<Vec<usize>, IndexError> {
        self.query_line_counted(point, direction, radius, &mut QueryStats::default())
    }

    /// As [`Self::query_line`], adding the work done to `stats`.
    pub fn query_line_counted(
        &self,
        point: &[f64; D],
        direction: &[f64; D],
        radius: f64,
        stats: &mut QueryStats,
    ) -> Result<Vec<usize>, IndexError> {
        check_distance("radius", radius)?;
        for (k, &value) in point.iter().chain(direction).enumerate() {
            if !value.is_finite() {
                return Err(IndexError::NonFiniteQuery { axis: k % D, value });
            }
        }
        if direction.iter().all(|&d| d == 0.0) {
            return Err(IndexError::BadDistance {
                what: "direction (its length)",
                value: 0.0,
            });
        }
        Ok(self.collect(|b| b.meets_line(point, direction, radius), stats))
    }

    fn collect(&self, hit: impl Fn(&Aabb<D>) -> bool, stats: &mut QueryStats) -> Vec<usize> {
        let mut found = Vec::new();
        if self.nodes.is_empty() {
            return found;
        }
        let mut stack = vec![0];
        while let Some(i) = stack.pop() {
            stats.nodes_visited += 1;
            let node = &self.nodes[i];
            if !hit(&node.bounds) {
                continue;
            }
            match node.kids {
                Kids::Inner { left, right } => {
                    stack.push(right);
                    stack.push(left);
                }
                Kids::Leaf { start, end } => {
                    for &f in &self.order[start..end] {
                        stats.faces_tested += 1;
                        if hit(&self.boxes[f]) {
                            found.push(f);
                        }
                    }
                }
            }
        }
        found.sort_unstable();
        found
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testutil::Lcg;

    fn random_boxes<const D: usize>(rng: &mut Lcg, n: usize) -> Vec<Aabb<D>> {
        (0..n)
            .map(|_| {
                let mut b = Aabb {
                    min: [0.0; D],
                    max: [0.0; D],
                };
                for k in 0..D {
                    let c = rng.uniform(-10.0, 10.0);
                    // Some boxes are flat or collapsed to a point.
                    let h = if rng.uniform(0.0, 1.0) < 0.2 {
                        0.0
                    } else {
                        rng.uniform(0.0, 1.5)
                    };
                    b.min[k] = c - h;
                    b.max[k] = c + h;
                }
                b
            })
            .collect()
    }

    fn brute_box<const D: usize>(boxes: &[Aabb<D>], q: &Aabb<D>) -> Vec<usize> {
        (0..boxes.len()).filter(|&f| boxes[f].meets(q)).collect()
    }

    fn brute_point<const D: usize>(boxes: &[Aabb<D>], p: &[f64; D], r: f64) -> Vec<usize> {
        (0..boxes.len())
            .filter(|&f| boxes[f].distance_squared(p) <= r * r)
            .collect()
    }

    /// Whether the line `p + t d` meets box `b` inflated by `r`, from the
    /// other side than the slab test: the distance from `p + t d` to the
    /// box is convex in `t`, so a golden-section search finds its minimum.
    fn line_meets_by_distance<const D: usize>(
        b: &Aabb<D>,
        p: &[f64; D],
        d: &[f64; D],
        r: f64,
    ) -> bool {
        let inflated: Aabb<D> = Aabb {
            min: std::array::from_fn(|k| b.min[k] - r),
            max: std::array::from_fn(|k| b.max[k] + r),
        };
        let at = |t: f64| -> f64 {
            inflated.distance_squared(&std::array::from_fn(|k| p[k] + t * d[k]))
        };
        // golden-section search of the convex distance over a wide range
        let (mut lo, mut hi) = (-1e3, 1e3);
        let g = (5f64.sqrt() - 1.0) / 2.0;
        for _ in 0..200 {
            let (a, c) = (hi - g * (hi - lo), lo + g * (hi - lo));
            if at(a) <= at(c) {
                hi = c;
            } else {
                lo = a;
            }
        }
        at(0.5 * (lo + hi)) <= 1e-18
    }

    fn brute_line<const D: usize>(
        boxes: &[Aabb<D>],
        p: &[f64; D],
        d: &[f64; D],
        r: f64,
    ) -> Vec<usize> {
        (0..boxes.len())
            .filter(|&f| line_meets_by_distance(&boxes[f], p, d, r))
            .collect()
    }

    fn check_random<const D: usize>(seed: u64) {
        let mut rng = Lcg::new(seed);
        let mut nonempty = 0;
        for n in [0, 1, 3, 4, 5, 17, 100, 613] {
            let boxes = random_boxes::<D>(&mut rng, n);
            let index = FaceIndex::build(boxes.clone()).unwrap();
            assert_eq!(index.len(), n);
            for _ in 0..200 {
                let q = random_boxes::<D>(&mut rng, 1)[0];
                let got = index.query_box(&q).unwrap();
                assert_eq!(got, brute_box(&boxes, &q), "n = {n}, box {q:?}");
                let mut p = [0.0; D];
                for x in &mut p {
                    *x = rng.uniform(-11.0, 11.0);
                }
                let r = if rng.uniform(0.0, 1.0) < 0.25 {
                    0.0
                } else {
                    rng.uniform(0.0, 3.0)
                };
                let got_p = index.query_point(&p, r).unwrap();
                assert_eq!(got_p, brute_point(&boxes, &p, r), "n = {n}, {p:?}, r = {r}");
                // a line through p, one direction component zero at times
                let mut d = [0.0; D];
                for x in &mut d {
                    *x = if rng.uniform(0.0, 1.0) < 0.2 {
                        0.0
                    } else {
                        rng.uniform(-1.0, 1.0)
                    };
                }
                d[0] += 0.1;
                let got_l = index.query_line(&p, &d, r).unwrap();
                assert_eq!(
                    got_l,
                    brute_line(&boxes, &p, &d, r),
                    "n = {n}, {p:?} + t {d:?}"
                );
                nonempty += usize::from(!got.is_empty())
                    + usize::from(!got_p.is_empty())
                    + usize::from(!got_l.is_empty() && got_l.len() < n);
            }
        }
        // The comparison means something only if queries find faces.
        assert!(nonempty > 200, "only {nonempty} queries found a face");
    }

    #[test]
    fn random_queries_match_brute_force_in_2d_and_3d() {
        check_random::<2>(17);
        check_random::<3>(18);
    }

    #[test]
    fn query_on_a_face_box_corner_counts_touching() {
        let boxes = vec![
            Aabb {
                min: [0.0, 0.0],
                max: [1.0, 1.0],
            },
            Aabb {
                min: [1.0, 1.0],
                max: [1.0, 1.0],
            },
        ];
        let index = FaceIndex::build(boxes).unwrap();
        assert_eq!(index.query_point(&[1.0, 1.0], 0.0).unwrap(), vec![0, 1]);
        assert_eq!(index.query_point(&[1.0, 1.0 + 1e-9], 0.0).unwrap(), vec![]);
        assert_eq!(index.query_point(&[1.0, 1.5], 0.5).unwrap(), vec![0, 1]);
    }

    #[test]
    fn empty_and_degenerate_input() {
        let empty = FaceIndex::<3>::build(Vec::new()).unwrap();
        assert!(empty.is_empty());
        assert_eq!(empty.depth(), 0);
        assert_eq!(empty.query_point(&[0.0; 3], 1.0).unwrap(), vec![]);
        // All faces collapsed onto one point: one answer holding them all.
        let same = FaceIndex::<2>::from_faces(&[[[2.0, 3.0]]; 9], 0.0).unwrap();
        assert_eq!(
            same.query_point(&[2.0, 3.0], 0.0).unwrap(),
            (0..9).collect::<Vec<_>>()
        );
        assert_eq!(same.query_point(&[2.0, 3.5], 0.4).unwrap(), vec![]);

        let nan = [[0.0, 0.0], [f64::NAN, 1.0]];
        let err = FaceIndex::<2>::from_faces(&[vec![[0.0, 0.0]], nan.to_vec()], 0.1).unwrap_err();
        assert!(
            matches!(
                err,
                IndexError::NonFinite {
                    face: 1,
                    axis: 0,
                    ..
                }
            ),
            "{err}"
        );
        let inf = Aabb {
            min: [0.0, f64::NEG_INFINITY],
            max: [1.0, 1.0],
        };
        let err = FaceIndex::build(vec![inf]).unwrap_err();
        assert!(
            matches!(
                err,
                IndexError::NonFinite {
                    face: 0,
                    axis: 1,
                    ..
                }
            ),
            "{err}"
        );
        let inverted = Aabb {
            min: [0.0, 2.0],
            max: [1.0, 1.0],
        };
        let err = FaceIndex::build(vec![inverted]).unwrap_err();
        assert!(
            matches!(
                err,
                IndexError::Inverted {
                    face: 0,
                    axis: 1,
                    ..
                }
            ),
            "{err}"
        );
        let err = FaceIndex::<2>::from_faces(&[Vec::<[f64; 2]>::new()], 0.1).unwrap_err();
        assert_eq!(err, IndexError::NoNodes { face: 0 });
        for margin in [-1.0, f64::NAN, f64::INFINITY] {
            let err = FaceIndex::<2>::from_faces(&[[[0.0, 0.0]]], margin).unwrap_err();
            assert!(
                matches!(err, IndexError::BadDistance { what: "margin", .. }),
                "{err}"
            );
        }
        let index = FaceIndex::<2>::from_faces(&[[[0.0, 0.0], [1.0, 0.0]]], 0.1).unwrap();
        let err = index.query_point(&[0.0, 0.0], -0.5).unwrap_err();
        assert!(
            matches!(err, IndexError::BadDistance { what: "radius", .. }),
            "{err}"
        );
        let err = index.query_point(&[f64::NAN, 0.0], 0.5).unwrap_err();
        assert!(
            matches!(err, IndexError::NonFiniteQuery { axis: 0, .. }),
            "{err}"
        );
        let q = Aabb {
            min: [0.0, 0.0],
            max: [f64::INFINITY, 1.0],
        };
        let err = index.query_box(&q).unwrap_err();
        assert!(
            matches!(err, IndexError::NonFiniteQuery { axis: 0, .. }),
            "{err}"
        );
    }

    #[test]
    fn candidates_hold_every_segment_a_point_projects_into_within_the_margin() {
        // A wavy master chain of 2D segments, as the 2D pairing walks it.
        let nodes: Vec<[f64; 2]> = (0..=200)
            .map(|i| {
                let x = i as f64 * 0.05;
                [x, 0.3 * (2.0 * x).sin()]
            })
            .collect();
        let segments: Vec<[[f64; 2]; 2]> = nodes.windows(2).map(|w| [w[0], w[1]]).collect();
        let margin = 0.08;
        let index = FaceIndex::from_faces(&segments, margin).unwrap();
        let mut rng = Lcg::new(11);
        let mut paired = 0;
        for _ in 0..2000 {
            let p = [rng.uniform(-0.2, 10.2), rng.uniform(-0.5, 0.5)];
            let found = index.query_point(&p, 0.0).unwrap();
            for (s, [a, b]) in segments.iter().enumerate() {
                let t = [b[0] - a[0], b[1] - a[1]];
                let xi =
                    ((p[0] - a[0]) * t[0] + (p[1] - a[1]) * t[1]) / (t[0] * t[0] + t[1] * t[1]);
                let q = [a[0] + xi * t[0], a[1] + xi * t[1]];
                let gap = (p[0] - q[0]).hypot(p[1] - q[1]);
                if (0.0..=1.0).contains(&xi) && gap <= margin {
                    paired += 1;
                    assert!(
                        found.contains(&s),
                        "{p:?} projects into {s} ({gap}): {found:?}"
                    );
                }
            }
            assert!(found.windows(2).all(|w| w[0] < w[1]));
        }
        assert!(paired > 200, "{paired}");
    }

    /// The unit quads of an `n x n` grid in the plane z = 0, as 3D faces.
    fn grid_faces(n: usize) -> Vec<[[f64; 3]; 4]> {
        let mut faces = Vec::new();
        for j in 0..n {
            for i in 0..n {
                let (x, y) = (i as f64, j as f64);
                faces.push([
                    [x, y, 0.0],
                    [x + 1.0, y, 0.0],
                    [x + 1.0, y + 1.0, 0.0],
                    [x, y + 1.0, 0.0],
                ]);
            }
        }
        faces
    }

    #[test]
    fn visits_grow_logarithmically_on_a_regular_grid() {
        let mut rng = Lcg::new(5);
        let mut worst = Vec::new();
        for n in [8, 16, 32, 64, 128] {
            let faces = grid_faces(n);
            let index = FaceIndex::from_faces(&faces, 0.05).unwrap();
            let mut max_visits = 0;
            for _ in 0..200 {
                let p = [
                    rng.uniform(0.0, n as f64),
                    rng.uniform(0.0, n as f64),
                    rng.uniform(-0.04, 0.04),
                ];
                let mut stats = QueryStats::default();
                let found = index.query_point_counted(&p, 0.0, &mut stats).unwrap();
                // The face the point lies over is always a candidate.
                let own =
                    (p[1].floor() as usize).min(n - 1) * n + (p[0].floor() as usize).min(n - 1);
                assert!(found.contains(&own), "{p:?}: {found:?}");
                assert!(found.len() <= 4);
                max_visits = max_visits.max(stats.nodes_visited);
            }
            let faces_n = n * n;
            let depth = index.depth();
            assert!(depth <= (faces_n.div_ceil(LEAF_SIZE) as f64).log2().ceil() as usize + 1);
            worst.push((faces_n, max_visits));
        }
        // From 64 to 16384 faces (256 times more) the work grows by a
        // constant per doubling, far from the 256 a linear scan would take:
        // visits <= c log2(faces) with c fixed by the smallest grid.
        let (n0, v0) = worst[0];
        let c = v0 as f64 / (n0 as f64).log2();
        for &(faces_n, visits) in &worst {
            let bound = 3.0 * c * (faces_n as f64).log2();
            assert!(
                (visits as f64) <= bound,
                "{faces_n} faces: {visits} visits, bound {bound:.1} ({worst:?})"
            );
        }
        let (n_last, v_last) = *worst.last().unwrap();
        assert!(v_last * 20 < n_last, "{worst:?}");
    }
}
