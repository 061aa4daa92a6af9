//! The kernel signature: what a formulation's `inputs!` declares, and the
//! sizes that follow from it.
//!
//! `inputs!(p1, ..., pk; s1, ..., sm)` declares `k` nodal points of
//! dimension [`Signature::dim`] (their coordinates, point by point, are the
//! kernel coordinates `q`, `n = dim * k` of them) and `m` scalar parameters
//! (`xi_s`); `inputs!(dim 3; p1, ..., pk; xi_s: 2)` points of three
//! coordinates and a parameter of two components (a face's `(u, v)`). The
//! formulation's `implicit!` adds the implicit unknown (`xi_m`: one
//! component, or two for `implicit!(xi: 2 => ..)`). Everything downstream — jets, truncation, lowering, the kernel
//! plan and its emitters — takes its sizes from here: no other module
//! knows a coordinate count.
//!
//! ## Symbols
//!
//! The expression DAG names inputs by [`Sym`]: coordinates first
//! (`Sym(0..n)`, point-major: `x1, y1, x2, y2, ...`), then the parameters'
//! components (`Sym(n..n+m)`, `m` = [`Signature::param_count`], parameter
//! after parameter), then the implicit unknown's components
//! (`Sym(n+m..n+m+k)`), then, if `previous!` declares it, the last
//! converged projection `xi_m0` (`k` more: the slip's input).
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
    /// Points of the slave face (the first ones); the rest are the
    /// master's.
    slave_points: usize,
    params: Vec<String>,
    /// Components per parameter (1 or 2).
    param_lens: Vec<usize>,
    implicit: String,
    /// Components of the implicit unknown (1 or 2).
    implicit_len: usize,
    /// Whether `previous!` declared the last converged projection `xi_m0`
    /// (as many components as the implicit unknown; the slip's input).
    previous: bool,
}

impl Signature {
    /// A signature of `points` of dimension `dim`, scalar `params` and the
    /// implicit unknown named `implicit`.
    pub fn new(dim: usize, points: Vec<String>, params: Vec<String>, implicit: String) -> Self {
        let param_lens = vec![1; params.len()];
        Signature {
            dim,
            slave_points: points.len() / 2,
            points,
            params,
            param_lens,
            implicit,
            implicit_len: 1,
            previous: false,
        }
    }

    /// A signature of `points` of dimension `dim`, the first
    /// `slave_points` of them the slave face's, and parameters of
    /// `param_lens[i]` components each (the implicit unknown named and
    /// sized later, by `implicit!`).
    pub fn with_param_lens(
        dim: usize,
        points: Vec<String>,
        slave_points: usize,
        params: Vec<String>,
        param_lens: Vec<usize>,
    ) -> Self {
        debug_assert_eq!(params.len(), param_lens.len());
        Signature {
            dim,
            slave_points,
            points,
            params,
            param_lens,
            implicit: String::new(),
            implicit_len: 1,
            previous: false,
        }
    }

    /// The dimension of every point (2 for segments, 3 for faces).
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// The point names, in kernel order.
    pub fn points(&self) -> &[String] {
        &self.points
    }

    /// How many of the points are the slave's (the first ones): half of
    /// them for segments, as declared for faces.
    pub fn slave_points(&self) -> usize {
        self.slave_points
    }

    /// The parameter names (e.g. `xi_s`), in declaration order.
    pub fn params(&self) -> &[String] {
        &self.params
    }

    /// The components of parameter `i` (1 or 2).
    pub fn param_len(&self, i: usize) -> usize {
        self.param_lens[i]
    }

    /// The index of parameter `i`'s first component among all parameter
    /// components.
    pub fn param_offset(&self, i: usize) -> usize {
        self.param_lens[..i].iter().sum()
    }

    /// All parameter components (the number of `Sym`s between the
    /// coordinates and the implicit unknown).
    pub fn param_count(&self) -> usize {
        self.param_lens.iter().sum()
    }

    /// The implicit unknown's name (e.g. `xi_m`).
    pub fn implicit(&self) -> &str {
        &self.implicit
    }

    /// The implicit unknown's components (1, or 2 for a face's `(u, v)`).
    pub fn implicit_len(&self) -> usize {
        self.implicit_len
    }

    /// Names the implicit unknown (known only once `implicit!` is read).
    pub(crate) fn set_implicit(&mut self, name: String) {
        self.implicit = name;
    }

    /// Sizes the implicit unknown (known only once `implicit!` is read).
    pub(crate) fn set_implicit_len(&mut self, len: usize) {
        self.implicit_len = len;
    }

    /// Declares the last converged projection `xi_m0` (`previous!`).
    pub(crate) fn set_previous(&mut self) {
        self.previous = true;
    }

    /// Whether the formulation declares the last converged projection
    /// `xi_m0` (`previous!`, which the slip reads).
    pub fn has_previous(&self) -> bool {
        self.previous
    }

    /// The symbols of the last converged projection `xi_m0`, one per
    /// component of the implicit unknown, after the unknown's (none
    /// without `previous!`). The slip's programs load them as parameter
    /// components `param_count()..` ([`crate::lower::Source::Param`]):
    /// they follow the parameters in a slip function's arguments.
    pub fn previous_syms(&self) -> Vec<Sym> {
        if !self.previous {
            return Vec::new();
        }
        let first = self.coords() + self.param_count() + self.implicit_len;
        (0..self.implicit_len)
            .map(|k| Sym((first + k) as u16))
            .collect()
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

    /// The symbol of parameter component `i` (for scalar parameters:
    /// parameter `i`; see [`Signature::param_offset`]).
    pub fn param_sym(&self, i: usize) -> Sym {
        debug_assert!(i < self.param_count());
        Sym((self.coords() + i) as u16)
    }

    /// The symbol of the implicit unknown (a vector's first component).
    pub fn implicit_sym(&self) -> Sym {
        Sym((self.coords() + self.param_count()) as u16)
    }

    /// The symbols of the implicit unknown's components.
    pub fn implicit_syms(&self) -> Vec<Sym> {
        let first = self.coords() + self.param_count();
        (0..self.implicit_len)
            .map(|k| Sym((first + k) as u16))
            .collect()
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
