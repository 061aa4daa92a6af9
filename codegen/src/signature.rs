//! The kernel signature: what a formulation's `inputs!` declares, and the
//! sizes that follow from it.
//!
//! `inputs!(p1, ..., pk; s1, ..., sm)` declares `k` nodal points of
//! dimension [`Signature::dim`] (their coordinates, point by point, are the
//! kernel coordinates `q`, `n = dim * k` of them) and `m` scalar parameters
//! (`xi_s`). The formulation's `implicit!` adds the implicit unknown
//! (`xi_m`). Everything downstream — jets, truncation, lowering, the kernel
//! plan and its emitters — takes its sizes from here: no other module
//! knows a coordinate count.
//!
//! ## Symbols
//!
//! The expression DAG names inputs by [`Sym`]: coordinates first
//! (`Sym(0..n)`, point-major: `x1, y1, x2, y2, ...`), then the parameters
//! (`Sym(n..n+m)`), then the implicit unknown (`Sym(n+m)`).
//!
//! ## Packed symmetric matrices
//!
//! A symmetric `n x n` matrix (a Hessian) is held as its upper triangle,
//! row-major: entry `(j, k)`, `j <= k`, at [`Signature::packed`]`(j, k)`,
//! [`Signature::packed_len`]` = n (n + 1) / 2` entries.

use crate::expr::Sym;

/// The inputs of a formulation's kernels.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Signature {
    dim: usize,
    points: Vec<String>,
    params: Vec<String>,
    implicit: String,
}

impl Signature {
    /// A signature of `points` of dimension `dim`, scalar `params` and the
    /// implicit unknown named `implicit`.
    pub fn new(dim: usize, points: Vec<String>, params: Vec<String>, implicit: String) -> Self {
        Signature {
            dim,
            points,
            params,
            implicit,
        }
    }

    /// The dimension of every point (2 for the formulation language).
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// The point names, in kernel order.
    pub fn points(&self) -> &[String] {
        &self.points
    }

    /// The scalar parameter names (e.g. `xi_s`), in declaration order.
    pub fn params(&self) -> &[String] {
        &self.params
    }

    /// The implicit unknown's name (e.g. `xi_m`).
    pub fn implicit(&self) -> &str {
        &self.implicit
    }

    /// Names the implicit unknown (known only once `implicit!` is read).
    pub(crate) fn set_implicit(&mut self, name: String) {
        self.implicit = name;
    }

    /// The coordinate count `n = dim * points`.
    pub fn coords(&self) -> usize {
        self.dim * self.points.len()
    }

    /// Entries of the packed upper triangle of an `n x n` symmetric matrix.
    pub fn packed_len(&self) -> usize {
        let n = self.coords();
        n * (n + 1) / 2
    }

    /// Index of `(j, k)`, `j <= k < n`, in the packed upper triangle
    /// (row-major).
    pub fn packed(&self, j: usize, k: usize) -> usize {
        let n = self.coords();
        debug_assert!(j <= k && k < n);
        j * n - j * (j + 1) / 2 + k
    }

    /// The symbol of coordinate `i`.
    pub fn coord_sym(&self, i: usize) -> Sym {
        debug_assert!(i < self.coords());
        Sym(i as u16)
    }

    /// The symbols of all coordinates, in kernel order.
    pub fn coord_syms(&self) -> Vec<Sym> {
        (0..self.coords()).map(|i| self.coord_sym(i)).collect()
    }

    /// The symbol of parameter `i`.
    pub fn param_sym(&self, i: usize) -> Sym {
        debug_assert!(i < self.params.len());
        Sym((self.coords() + i) as u16)
    }

    /// The symbol of the implicit unknown.
    pub fn implicit_sym(&self) -> Sym {
        Sym((self.coords() + self.params.len()) as u16)
    }

    /// The coordinates of the first point: the origin of the relative
    /// coordinates the kernels receive (they are replaced by zero).
    pub fn origin_coords(&self) -> Vec<usize> {
        (0..self.dim).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sig(points: usize, params: usize) -> Signature {
        Signature::new(
            2,
            (0..points).map(|i| format!("p{i}")).collect(),
            (0..params).map(|i| format!("s{i}")).collect(),
            "xi".into(),
        )
    }

    #[test]
    fn packed_index_is_a_bijection() {
        for points in 1..=6 {
            let s = sig(points, 1);
            let n = s.coords();
            assert_eq!(n, 2 * points);
            let mut seen = vec![false; s.packed_len()];
            for j in 0..n {
                for k in j..n {
                    assert!(!seen[s.packed(j, k)]);
                    seen[s.packed(j, k)] = true;
                }
            }
            assert!(seen.iter().all(|&s| s));
        }
    }

    #[test]
    fn symbols_follow_the_declaration() {
        let s = sig(4, 1);
        assert_eq!((s.coords(), s.packed_len()), (8, 36));
        assert_eq!(s.param_sym(0), Sym(8));
        assert_eq!(s.implicit_sym(), Sym(9));
        let s = sig(3, 0);
        assert_eq!((s.coords(), s.packed_len()), (6, 21));
        assert_eq!(s.implicit_sym(), Sym(6));
        assert_eq!(s.origin_coords(), [0, 1]);
    }
}
