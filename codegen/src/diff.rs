//! Symbolic differentiation with structural zeros.
//!
//! [`Differentiator::d`] returns `Option<Id>`: `None` means the derivative is
//! structurally zero (the expression does not depend on the symbol), so the
//! chain rule never builds a dead branch. Derivatives are memoised per
//! `(node, symbol)`; second derivatives are derivatives of first ones.
//!
//! The rules (with `'` the partial derivative with respect to one symbol):
//!
//! ```text
//! (a + b)' = a' + b'          (a - b)' = a' - b'        (-a)' = -a'
//! (a b)'   = a' b + a b'      (1/a)'   = -(1/a)^2 a'
//! sqrt(a)' = a' (1/2) / sqrt(a)        (a^n)' = n a^(n-1) a'
//! ```

use std::collections::HashMap;

use crate::expr::{Dag, Id, Node, Sym};

/// Memoising differentiator over a [`Dag`].
#[derive(Debug, Default)]
pub struct Differentiator {
    memo: HashMap<(Id, Sym), Option<Id>>,
}

/// `a + b` over structural zeros.
pub fn add_opt(dag: &mut Dag, a: Option<Id>, b: Option<Id>) -> Option<Id> {
    match (a, b) {
        (None, x) | (x, None) => x,
        (Some(a), Some(b)) => {
            let s = dag.add(a, b);
            nonzero(dag, s)
        }
    }
}

/// `a - b` over structural zeros.
pub fn sub_opt(dag: &mut Dag, a: Option<Id>, b: Option<Id>) -> Option<Id> {
    match (a, b) {
        (x, None) => x,
        (None, Some(b)) => Some(dag.neg(b)),
        (Some(a), Some(b)) => {
            let s = dag.sub(a, b);
            nonzero(dag, s)
        }
    }
}

/// `a * b` over structural zeros.
pub fn mul_opt(dag: &mut Dag, a: Option<Id>, b: Option<Id>) -> Option<Id> {
    let (a, b) = (a?, b?);
    let p = dag.mul(a, b);
    nonzero(dag, p)
}

/// `-a` over structural zeros.
pub fn neg_opt(dag: &mut Dag, a: Option<Id>) -> Option<Id> {
    a.map(|a| dag.neg(a))
}

/// Sum of many terms over structural zeros.
pub fn sum_opt(dag: &mut Dag, terms: impl IntoIterator<Item = Option<Id>>) -> Option<Id> {
    terms.into_iter().fold(None, |acc, t| add_opt(dag, acc, t))
}

/// Maps a node that folded to the constant zero back to a structural zero.
pub fn nonzero(dag: &Dag, id: Id) -> Option<Id> {
    if dag.as_const(id) == Some(0.0) {
        None
    } else {
        Some(id)
    }
}

impl Differentiator {
    /// A differentiator with an empty memo.
    pub fn new() -> Self {
        Self::default()
    }

    /// The partial derivative of `id` with respect to `sym`, or `None` if it
    /// is structurally zero.
    pub fn d(&mut self, dag: &mut Dag, id: Id, sym: Sym) -> Option<Id> {
        if let Some(&r) = self.memo.get(&(id, sym)) {
            return r;
        }
        let r = match dag.node(id) {
            Node::Const(_) => None,
            Node::Input(s) => (s == sym).then(|| dag.constant(1.0)),
            Node::Add(a, b) => {
                let (da, db) = (self.d(dag, a, sym), self.d(dag, b, sym));
                add_opt(dag, da, db)
            }
            Node::Sub(a, b) => {
                let (da, db) = (self.d(dag, a, sym), self.d(dag, b, sym));
                sub_opt(dag, da, db)
            }
            Node::Mul(a, b) => {
                let (da, db) = (self.d(dag, a, sym), self.d(dag, b, sym));
                let t1 = mul_opt(dag, da, Some(b));
                let t2 = mul_opt(dag, Some(a), db);
                add_opt(dag, t1, t2)
            }
            Node::Recip(a) => {
                let da = self.d(dag, a, sym);
                let r2 = dag.powi(id, 2);
                let t = mul_opt(dag, Some(r2), da);
                neg_opt(dag, t)
            }
            Node::Neg(a) => {
                let da = self.d(dag, a, sym);
                neg_opt(dag, da)
            }
            Node::Sqrt(a) => {
                let da = self.d(dag, a, sym);
                // a' / (2 sqrt(a)) = a' * (0.5 * (1/sqrt(a)))
                let half = dag.constant(0.5);
                let inv = dag.recip(id);
                let k = dag.mul(half, inv);
                mul_opt(dag, da, Some(k))
            }
            Node::Powi(a, n) => {
                let da = self.d(dag, a, sym);
                let p = dag.powi(a, n - 1);
                let c = dag.constant(f64::from(n));
                let k = dag.mul(c, p);
                mul_opt(dag, Some(k), da)
            }
        };
        self.memo.insert((id, sym), r);
        r
    }

    /// `d` lifted to structural zeros: the derivative of zero is zero.
    pub fn d_opt(&mut self, dag: &mut Dag, id: Option<Id>, sym: Sym) -> Option<Id> {
        id.and_then(|id| self.d(dag, id, sym))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn vals(x: f64, y: f64) -> HashMap<Sym, f64> {
        HashMap::from([(Sym(0), x), (Sym(1), y)])
    }

    #[test]
    fn derivatives_match_finite_differences() {
        // f = sqrt(x^2 + y^2) / (x - 3 y) + x^3
        let mut dag = Dag::new();
        let x = dag.input(Sym(0));
        let y = dag.input(Sym(1));
        let x2 = dag.mul(x, x);
        let y2 = dag.mul(y, y);
        let s = dag.add(x2, y2);
        let r = dag.sqrt(s);
        let three = dag.constant(3.0);
        let t = dag.mul(three, y);
        let den = dag.sub(x, t);
        let q = dag.div(r, den);
        let x3 = dag.powi(x, 3);
        let f = dag.add(q, x3);
        let mut diff = Differentiator::new();
        let fx = diff.d(&mut dag, f, Sym(0)).unwrap();
        let fxy = diff.d(&mut dag, fx, Sym(1)).unwrap();
        dag.check_invariants();
        let (x0, y0, h) = (1.3, -0.4, 1e-5);
        let fd = |dag: &Dag, id, x, y| dag.eval(id, &vals(x, y));
        let fx_fd = (fd(&dag, f, x0 + h, y0) - fd(&dag, f, x0 - h, y0)) / (2.0 * h);
        let fxy_fd = (fd(&dag, fx, x0, y0 + h) - fd(&dag, fx, x0, y0 - h)) / (2.0 * h);
        // Central differences: error O(h^2) ~ 1e-10 relative.
        assert!((fd(&dag, fx, x0, y0) - fx_fd).abs() < 1e-8, "df/dx");
        assert!((fd(&dag, fxy, x0, y0) - fxy_fd).abs() < 1e-8, "d2f/dxdy");
    }

    #[test]
    fn independent_symbol_is_structural_zero() {
        let mut dag = Dag::new();
        let x = dag.input(Sym(0));
        let s = dag.sqrt(x);
        let mut diff = Differentiator::new();
        assert_eq!(diff.d(&mut dag, s, Sym(1)), None);
    }
}
