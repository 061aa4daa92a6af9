//! The structured grid behind the block generator of both dimensions
//! ([`super::block`]: quadrilaterals in 2D, hexahedra in 3D), written once
//! over the dimension `D`.
//!
//! A grid with origin `x0`, size `s` and `n_d` cells along axis `d` has the
//! nodes `p = (p_0, .., p_{D-1})`, `0 <= p_d <= n_d`, at
//! `x0_d + s_d p_d / n_d`, numbered with axis 0 fastest:
//! `p_0 + (n_0 + 1)(p_1 + (n_1 + 1)(p_2 ..))`; and the cells `c`,
//! `0 <= c_d < n_d`, numbered the same way over `n_d`, each with the nodes
//! `c + o_a` for the corners `o_a` of the parent element (its coordinates
//! `-1` and `+1` as offsets `0` and `1`), so in the element's node order.

/// A structured grid of `D` dimensions (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Grid<const D: usize> {
    /// The corner of smallest coordinates.
    pub origin: [f64; D],
    /// The extents along each axis.
    pub size: [f64; D],
    /// Cells along each axis.
    pub cells: [usize; D],
}

impl<const D: usize> Grid<D> {
    /// The number of node `p`.
    pub fn node(&self, p: [usize; D]) -> usize {
        let mut id = 0;
        for d in (0..D).rev() {
            id = id * (self.cells[d] + 1) + p[d];
        }
        id
    }

    /// Every index `p` with `p_d < extent_d`, axis 0 fastest.
    pub fn indices(extent: [usize; D]) -> impl Iterator<Item = [usize; D]> {
        let count: usize = extent.iter().product();
        (0..count).map(move |mut r| {
            std::array::from_fn(|d| {
                let p = r % extent[d];
                r /= extent[d];
                p
            })
        })
    }

    /// The nodes' coordinates, in node order.
    pub fn nodes(&self) -> Vec<[f64; D]> {
        let extent = self.cells.map(|n| n + 1);
        Self::indices(extent)
            .map(|p| {
                std::array::from_fn(|d| {
                    self.origin[d] + self.size[d] * p[d] as f64 / self.cells[d] as f64
                })
            })
            .collect()
    }

    /// The cell `c`'s nodes, at the parent corners `corners`.
    pub fn cell<const C: usize>(&self, c: [usize; D], corners: &[[f64; D]; C]) -> [usize; C] {
        corners.map(|o| self.node(std::array::from_fn(|d| c[d] + usize::from(o[d] > 0.0))))
    }
}
