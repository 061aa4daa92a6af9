//! A body that falls apart at unmerged nodes: two nodes of one body at the
//! same point whose elements are not connected to each other. A mesh
//! generator leaves such nodes where surfaces or volumes were meshed apart
//! and not merged (Gmsh without `Coherence`), and the body then comes
//! apart into pieces held by nothing across the seam; the reader refuses
//! it instead of solving it.
//!
//! Two nodes coincide when they are within `COINCIDENT_TOL` times the
//! diagonal of the body's bounding box of each other (the tolerance of a
//! node selection by coordinates). A pair of coincident nodes in one
//! connected piece of the body (a crack that does not cut through, drawn
//! with doubled nodes) is not reported: the body still holds together.
//!
//! Invariant: the search is a hash grid of cells of the tolerance's size
//! (each node compared with the nodes of its `3^D` neighbouring cells), so
//! it takes time linear in the nodes; the pair reported is the first in
//! node order.

use std::collections::HashMap;

/// Coincidence tolerance, relative to the bounding box's diagonal.
pub const COINCIDENT_TOL: f64 = 1e-9;

/// Two coincident nodes (body-local indices) in different connected
/// pieces of a body, and how many pieces it has.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FallsApart {
    /// The first node of the pair.
    pub a: usize,
    /// The second node of the pair.
    pub b: usize,
    /// The connected pieces of the body's elements.
    pub pieces: usize,
}

/// The representative of `i`'s set (path halving).
fn find(parent: &mut [usize], mut i: usize) -> usize {
    while parent[i] != i {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    i
}

/// Whether the body with node coordinates `nodes` and elements
/// `elements` (body-local node indices) falls apart at coincident nodes
/// (module docs): the first such pair, or `None`. Nodes of no element
/// take no part.
pub fn falls_apart<const D: usize>(
    nodes: &[[f64; D]],
    elements: &[&[usize]],
) -> Option<FallsApart> {
    if nodes.len() < 2 {
        return None;
    }
    let mut parent: Vec<usize> = (0..nodes.len()).collect();
    let mut used = vec![false; nodes.len()];
    for &n in elements.iter().flat_map(|e| e.iter()) {
        used[n] = true;
    }
    for el in elements {
        for w in el.windows(2) {
            let (ra, rb) = (find(&mut parent, w[0]), find(&mut parent, w[1]));
            if ra != rb {
                parent[ra.max(rb)] = ra.min(rb);
            }
        }
    }
    let mut lo = [f64::INFINITY; D];
    let mut hi = [f64::NEG_INFINITY; D];
    for p in nodes {
        for d in 0..D {
            lo[d] = lo[d].min(p[d]);
            hi[d] = hi[d].max(p[d]);
        }
    }
    let diagonal = (0..D).map(|d| (hi[d] - lo[d]).powi(2)).sum::<f64>().sqrt();
    let tol = COINCIDENT_TOL * diagonal;
    if !(tol > 0.0 && tol.is_finite()) {
        return None;
    }
    let cell = |p: &[f64; D]| -> [i64; D] {
        std::array::from_fn(|d| ((p[d] - lo[d]) / tol).floor() as i64)
    };
    let mut grid: HashMap<[i64; D], Vec<usize>> = HashMap::new();
    for (i, p) in nodes.iter().enumerate() {
        grid.entry(cell(p)).or_default().push(i);
    }
    let offsets = 3_usize.pow(D as u32);
    for (i, p) in nodes.iter().enumerate() {
        let c = cell(p);
        for k in 0..offsets {
            let mut r = k;
            let neighbour: [i64; D] = std::array::from_fn(|d| {
                let o = (r % 3) as i64 - 1;
                r /= 3;
                c[d] + o
            });
            let Some(candidates) = grid.get(&neighbour) else {
                continue;
            };
            for &j in candidates.iter().filter(|&&j| j > i && used[i] && used[j]) {
                let dist = (0..D)
                    .map(|d| (nodes[j][d] - p[d]).powi(2))
                    .sum::<f64>()
                    .sqrt();
                if dist <= tol && find(&mut parent, i) != find(&mut parent, j) {
                    let pieces = (0..nodes.len())
                        .filter(|&n| used[n] && find(&mut parent, n) == n)
                        .count();
                    return Some(FallsApart { a: i, b: j, pieces });
                }
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two unit squares side by side, their shared edge's nodes doubled
    /// (4, 5 at the same points as 1, 3): two pieces, the pair (1, 4)
    /// reported; merged, or with only one node doubled (a crack that does
    /// not cut through), nothing.
    #[test]
    fn doubled_nodes_between_pieces_are_found() {
        let nodes = [
            [0.0, 0.0],
            [1.0, 0.0],
            [0.0, 1.0],
            [1.0, 1.0],
            [1.0, 0.0],
            [1.0, 1.0],
            [2.0, 0.0],
            [2.0, 1.0],
        ];
        let left: &[usize] = &[0, 1, 3, 2];
        let right: &[usize] = &[4, 6, 7, 5];
        assert_eq!(
            falls_apart(&nodes, &[left, right]),
            Some(FallsApart {
                a: 1,
                b: 4,
                pieces: 2
            })
        );
        // merged: the right square on nodes 1 and 3
        let merged: &[usize] = &[1, 6, 7, 3];
        assert_eq!(falls_apart(&nodes, &[left, merged]), None);
        // a crack: only the bottom node doubled, the top one shared
        let cracked: &[usize] = &[4, 6, 7, 3];
        assert_eq!(falls_apart(&nodes, &[left, cracked]), None);
        // far apart but within the tolerance of the diagonal
        let mut near = nodes;
        near[4][0] += 1e-12;
        assert_eq!(
            falls_apart(&near, &[left, right]).map(|f| (f.a, f.b)),
            Some((1, 4))
        );
        near[4][0] += 1e-6;
        near[5][0] += 1e-6;
        assert_eq!(falls_apart(&near, &[left, right]), None);
    }
}
