//! The hash-consed expression DAG.
//!
//! Every scalar expression is a [`Node`] stored once in an arena
//! ([`Dag`]) and named by an [`Id`]. Building a node goes through the
//! constructors of [`Dag`] ([`Dag::add`], [`Dag::mul`], ...), which
//!
//! * fold constants and apply a small set of local identities
//!   (`x + 0 = x`, `x * 1 = x`, `x - x = 0`, `-(-x) = x`, `x * x = x^2`,
//!   negations pulled outwards, `a / b = a * (1/b)`, ...),
//! * put the operands of commutative operations in canonical order
//!   (ascending id, constants first), and
//! * look the result up in a memo map, so structurally equal expressions
//!   share one id: common subexpressions are shared by construction.
//!
//! **Invariant** (checked by `debug_assert!` on insertion and by
//! [`Dag::check_invariants`]): children precede parents, i.e. every operand
//! id of a node is smaller than the node's own id. The arena order is
//! therefore a topological order, which the lowering relies on.

use std::collections::HashMap;

/// Index of a node in a [`Dag`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Id(pub(crate) u32);

impl Id {
    /// The arena index.
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// A symbol: an independent input of the expressions (a coordinate, a
/// parameter or the implicit variable). Its meaning is the caller's.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Sym(pub u16);

/// One scalar operation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Node {
    /// A constant, stored by its bit pattern (never NaN or infinite).
    Const(u64),
    /// An input symbol.
    Input(Sym),
    /// `a + b` (canonical: `a <= b`).
    Add(Id, Id),
    /// `a - b`.
    Sub(Id, Id),
    /// `a * b` (canonical: `a <= b`).
    Mul(Id, Id),
    /// `1 / a`.
    Recip(Id),
    /// `-a`.
    Neg(Id),
    /// `sqrt(a)`.
    Sqrt(Id),
    /// `a^n` for an integer `n` other than 0 and 1.
    Powi(Id, i32),
}

impl Node {
    /// The operands of the node.
    pub fn children(&self) -> impl Iterator<Item = Id> {
        let (a, b) = match *self {
            Node::Const(_) | Node::Input(_) => (None, None),
            Node::Add(a, b) | Node::Sub(a, b) | Node::Mul(a, b) => (Some(a), Some(b)),
            Node::Recip(a) | Node::Neg(a) | Node::Sqrt(a) | Node::Powi(a, _) => (Some(a), None),
        };
        a.into_iter().chain(b)
    }
}

/// The arena of nodes with its hash-consing memo.
#[derive(Debug, Default, Clone)]
pub struct Dag {
    nodes: Vec<Node>,
    memo: HashMap<Node, Id>,
    /// The first non-finite value a constant fold produced (see
    /// [`Dag::non_finite`]).
    non_finite: Option<f64>,
}

impl Dag {
    /// An empty DAG.
    pub fn new() -> Self {
        Self::default()
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether the DAG is empty.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// The node behind `id`.
    ///
    /// # Panics
    /// If `id` does not belong to this DAG.
    pub fn node(&self, id: Id) -> Node {
        self.nodes[id.index()]
    }

    /// The id of arena index `index` (ids are arena indices; children
    /// precede parents, so `0..len()` is a topological order).
    ///
    /// # Panics
    /// If `index >= len()`.
    pub fn id(&self, index: usize) -> Id {
        assert!(index < self.len(), "node index {index} out of range");
        Id(index as u32)
    }

    /// The constant value of `id`, if it is a constant.
    pub fn as_const(&self, id: Id) -> Option<f64> {
        match self.node(id) {
            Node::Const(bits) => Some(f64::from_bits(bits)),
            _ => None,
        }
    }

    /// Inserts `node` (already simplified and canonical) or returns the id of
    /// its existing copy.
    fn intern(&mut self, node: Node) -> Id {
        if let Some(&id) = self.memo.get(&node) {
            return id;
        }
        let id = Id(u32::try_from(self.nodes.len()).expect("expression DAG exceeds u32 ids"));
        debug_assert!(
            node.children().all(|c| c < id),
            "children must precede parents"
        );
        self.nodes.push(node);
        self.memo.insert(node, id);
        id
    }

    /// A constant. A non-finite `value` (a fold such as `1 / 0`,
    /// `sqrt(-1)` or an overflow) is stored as it is and recorded: the DAG
    /// is then poisoned ([`Dag::non_finite`]) and its expressions must not
    /// be emitted.
    pub fn constant(&mut self, value: f64) -> Id {
        // One zero: -0.0 and 0.0 are the same constant; one NaN.
        let value = if value == 0.0 {
            0.0
        } else if value.is_nan() {
            f64::NAN
        } else {
            value
        };
        if !value.is_finite() && self.non_finite.is_none() {
            self.non_finite = Some(value);
        }
        self.intern(Node::Const(value.to_bits()))
    }

    /// The first non-finite value a constant fold produced in this DAG
    /// (`None` for a DAG whose constants are all finite).
    pub fn non_finite(&self) -> Option<f64> {
        self.non_finite
    }

    /// An input symbol.
    pub fn input(&mut self, sym: Sym) -> Id {
        self.intern(Node::Input(sym))
    }

    /// `a + b`.
    pub fn add(&mut self, a: Id, b: Id) -> Id {
        match (self.as_const(a), self.as_const(b)) {
            (Some(x), Some(y)) => return self.constant(x + y),
            (Some(0.0), None) => return b,
            (None, Some(0.0)) => return a,
            _ => {}
        }
        match (self.node(a), self.node(b)) {
            (Node::Neg(x), Node::Neg(y)) => {
                let s = self.add(x, y);
                return self.neg(s);
            }
            (Node::Neg(x), _) => return self.sub(b, x),
            (_, Node::Neg(y)) => return self.sub(a, y),
            _ => {}
        }
        if a == b {
            let two = self.constant(2.0);
            return self.mul(two, a);
        }
        if let Some((c, x, y)) = self.common_factor(a, b) {
            let s = self.add(x, y);
            return self.mul(c, s);
        }
        let (a, b) = self.order(a, b);
        self.intern(Node::Add(a, b))
    }

    /// `a - b`.
    pub fn sub(&mut self, a: Id, b: Id) -> Id {
        if a == b {
            return self.constant(0.0);
        }
        match (self.as_const(a), self.as_const(b)) {
            (Some(x), Some(y)) => return self.constant(x - y),
            (Some(0.0), None) => return self.neg(b),
            (None, Some(0.0)) => return a,
            _ => {}
        }
        match (self.node(a), self.node(b)) {
            (_, Node::Neg(y)) => return self.add(a, y),
            (Node::Neg(x), _) => {
                let s = self.add(x, b);
                return self.neg(s);
            }
            _ => {}
        }
        if let Some((c, x, y)) = self.common_factor(a, b) {
            let s = self.sub(x, y);
            return self.mul(c, s);
        }
        // `a - b` and `b - a` share one node: the one with `a < b`.
        if a > b && self.as_const(b).is_none() && self.as_const(a).is_none() {
            let s = self.sub(b, a);
            return self.neg(s);
        }
        self.intern(Node::Sub(a, b))
    }

    /// `a * b`.
    pub fn mul(&mut self, a: Id, b: Id) -> Id {
        match (self.as_const(a), self.as_const(b)) {
            (Some(x), Some(y)) => return self.constant(x * y),
            (Some(c), None) | (None, Some(c)) => {
                let other = if self.as_const(a).is_some() { b } else { a };
                if c == 0.0 {
                    return self.constant(0.0);
                }
                if c == 1.0 {
                    return other;
                }
                if c == -1.0 {
                    return self.neg(other);
                }
                if c < 0.0 {
                    let m = self.constant(-c);
                    let p = self.mul(m, other);
                    return self.neg(p);
                }
                // c1 * (c2 * x) = (c1 c2) * x
                if let Node::Mul(x, y) = self.node(other)
                    && let Some(c2) = self.as_const(x)
                {
                    let k = self.constant(c * c2);
                    return self.mul(k, y);
                }
            }
            (None, None) => {}
        }
        match (self.node(a), self.node(b)) {
            (Node::Neg(x), Node::Neg(y)) => return self.mul(x, y),
            (Node::Neg(x), _) => {
                let p = self.mul(x, b);
                return self.neg(p);
            }
            (_, Node::Neg(y)) => {
                let p = self.mul(a, y);
                return self.neg(p);
            }
            _ => {}
        }
        if a == b {
            return self.powi(a, 2);
        }
        let (a, b) = self.order(a, b);
        self.intern(Node::Mul(a, b))
    }

    /// `a / b`, written as `a * (1/b)` so that one reciprocal serves every
    /// quotient with the same denominator.
    pub fn div(&mut self, a: Id, b: Id) -> Id {
        let r = self.recip(b);
        self.mul(a, r)
    }

    /// `1 / a`.
    pub fn recip(&mut self, a: Id) -> Id {
        if let Some(x) = self.as_const(a) {
            return self.constant(1.0 / x);
        }
        match self.node(a) {
            Node::Recip(x) => x,
            Node::Neg(x) => {
                let r = self.recip(x);
                self.neg(r)
            }
            _ => self.intern(Node::Recip(a)),
        }
    }

    /// `-a`.
    pub fn neg(&mut self, a: Id) -> Id {
        if let Some(x) = self.as_const(a) {
            return self.constant(-x);
        }
        match self.node(a) {
            Node::Neg(x) => x,
            Node::Sub(x, y) if x > y => self.sub(y, x),
            _ => self.intern(Node::Neg(a)),
        }
    }

    /// `sqrt(a)`.
    pub fn sqrt(&mut self, a: Id) -> Id {
        if let Some(x) = self.as_const(a) {
            return self.constant(x.sqrt());
        }
        self.intern(Node::Sqrt(a))
    }

    /// `a^n`.
    pub fn powi(&mut self, a: Id, n: i32) -> Id {
        match n {
            0 => return self.constant(1.0),
            1 => return a,
            -1 => return self.recip(a),
            _ => {}
        }
        if let Some(x) = self.as_const(a) {
            return self.constant(x.powi(n));
        }
        match self.node(a) {
            Node::Neg(x) if n % 2 == 0 => self.powi(x, n),
            Node::Neg(x) => {
                let p = self.powi(x, n);
                self.neg(p)
            }
            Node::Powi(x, m) => self.powi(x, m * n),
            _ if n < 0 => {
                let p = self.powi(a, -n);
                self.recip(p)
            }
            _ => self.intern(Node::Powi(a, n)),
        }
    }

    /// Rewrites an output `-(x - y)` as `y - x` and `-(c x)` as `(-c) x`,
    /// so a negated result costs no negation. Returns `id` unchanged
    /// otherwise. The nodes built here bypass the canonical sign rules; they
    /// are meant for outputs only, just before lowering.
    pub fn absorb_negation(&mut self, id: Id) -> Id {
        let Node::Neg(z) = self.node(id) else {
            return id;
        };
        match self.node(z) {
            Node::Sub(x, y) => self.intern(Node::Sub(y, x)),
            Node::Mul(c, x) if self.as_const(c).is_some() => {
                let c = self.as_const(c).expect("checked");
                let m = self.constant(-c);
                self.intern(Node::Mul(m, x))
            }
            _ => id,
        }
    }

    /// `(c, x, y)` when `a = c * x` and `b = c * y` for one constant `c`:
    /// `c x ± c y` is rewritten `c (x ± y)`, one multiplication fewer.
    fn common_factor(&self, a: Id, b: Id) -> Option<(Id, Id, Id)> {
        match (self.node(a), self.node(b)) {
            (Node::Mul(c1, x), Node::Mul(c2, y)) if c1 == c2 && self.as_const(c1).is_some() => {
                Some((c1, x, y))
            }
            _ => None,
        }
    }

    /// Canonical operand order for commutative operations: constants first,
    /// then ascending id.
    fn order(&self, a: Id, b: Id) -> (Id, Id) {
        let key = |id: Id| (self.as_const(id).is_none(), id);
        if key(a) <= key(b) { (a, b) } else { (b, a) }
    }

    /// Rebuilds the expressions `roots` with some symbols replaced by
    /// constants, simplifying on the way. Returns the new ids (in a new DAG).
    pub fn substitute(
        &self,
        roots: &[Option<Id>],
        values: &HashMap<Sym, f64>,
    ) -> (Dag, Vec<Option<Id>>) {
        let mut out = Dag::new();
        let mut map: Vec<Option<Id>> = vec![None; self.len()];
        let live = self.reachable(roots.iter().flatten().copied());
        for (i, &node) in self.nodes.iter().enumerate() {
            if !live[i] {
                continue;
            }
            let m = |id: Id| map[id.index()].expect("children precede parents");
            let new = match node {
                Node::Const(bits) => out.constant(f64::from_bits(bits)),
                Node::Input(s) => match values.get(&s) {
                    Some(&v) => out.constant(v),
                    None => out.input(s),
                },
                Node::Add(a, b) => out.add(m(a), m(b)),
                Node::Sub(a, b) => out.sub(m(a), m(b)),
                Node::Mul(a, b) => out.mul(m(a), m(b)),
                Node::Recip(a) => out.recip(m(a)),
                Node::Neg(a) => out.neg(m(a)),
                Node::Sqrt(a) => out.sqrt(m(a)),
                Node::Powi(a, n) => out.powi(m(a), n),
            };
            map[i] = Some(new);
        }
        let roots = roots
            .iter()
            .map(|r| r.map(|id| map[id.index()].expect("root is live")))
            .collect();
        (out, roots)
    }

    /// Rebuilds the expressions `roots` in this DAG with the symbol `sym`
    /// replaced by the expression `with` (which must not contain `sym`),
    /// simplifying on the way. Nodes that do not depend on `sym` keep their
    /// ids.
    pub fn replace(&mut self, roots: &[Option<Id>], sym: Sym, with: Id) -> Vec<Option<Id>> {
        let live = self.reachable(roots.iter().flatten().copied());
        let mut map: Vec<Id> = (0..live.len()).map(|i| Id(i as u32)).collect();
        for i in 0..live.len() {
            if !live[i] {
                continue;
            }
            let node = self.nodes[i];
            let m = |id: Id| map[id.index()];
            let new = match node {
                Node::Input(s) if s == sym => with,
                Node::Const(_) | Node::Input(_) => Id(i as u32),
                _ if node.children().all(|c| m(c) == c) => Id(i as u32),
                Node::Add(a, b) => self.add(m(a), m(b)),
                Node::Sub(a, b) => self.sub(m(a), m(b)),
                Node::Mul(a, b) => self.mul(m(a), m(b)),
                Node::Recip(a) => self.recip(m(a)),
                Node::Neg(a) => self.neg(m(a)),
                Node::Sqrt(a) => self.sqrt(m(a)),
                Node::Powi(a, n) => self.powi(m(a), n),
            };
            map[i] = new;
        }
        roots.iter().map(|r| r.map(|id| map[id.index()])).collect()
    }

    /// Marks the nodes reachable from `roots`.
    pub fn reachable(&self, roots: impl IntoIterator<Item = Id>) -> Vec<bool> {
        let mut live = vec![false; self.len()];
        for r in roots {
            live[r.index()] = true;
        }
        // Children precede parents: one backward sweep propagates liveness.
        for i in (0..self.len()).rev() {
            if live[i] {
                for c in self.nodes[i].children() {
                    live[c.index()] = true;
                }
            }
        }
        live
    }

    /// Evaluates `id` numerically with the given symbol values (for tests
    /// and diagnostics).
    ///
    /// # Panics
    /// If a symbol reached by `id` has no value.
    pub fn eval(&self, id: Id, values: &HashMap<Sym, f64>) -> f64 {
        let live = self.reachable([id]);
        let mut v = vec![0.0; id.index() + 1];
        for i in 0..=id.index() {
            if !live[i] {
                continue;
            }
            v[i] = match self.nodes[i] {
                Node::Const(bits) => f64::from_bits(bits),
                Node::Input(s) => *values
                    .get(&s)
                    .unwrap_or_else(|| panic!("no value for symbol {s:?}")),
                Node::Add(a, b) => v[a.index()] + v[b.index()],
                Node::Sub(a, b) => v[a.index()] - v[b.index()],
                Node::Mul(a, b) => v[a.index()] * v[b.index()],
                Node::Recip(a) => 1.0 / v[a.index()],
                Node::Neg(a) => -v[a.index()],
                Node::Sqrt(a) => v[a.index()].sqrt(),
                Node::Powi(a, n) => v[a.index()].powi(n),
            };
        }
        v[id.index()]
    }

    /// [`Dag::check_invariants`] in debug builds only.
    pub fn check_invariants_debug(&self) {
        if cfg!(debug_assertions) {
            self.check_invariants();
        }
    }

    /// Checks the structural invariants: children precede parents, the memo
    /// maps every node to its own id, commutative operands are canonical and
    /// constants are finite (unless recorded by [`Dag::non_finite`]).
    ///
    /// # Panics
    /// On the first violated invariant, with a description.
    pub fn check_invariants(&self) {
        assert_eq!(
            self.memo.len(),
            self.nodes.len(),
            "memo and arena disagree in size"
        );
        for (i, node) in self.nodes.iter().enumerate() {
            let id = Id(i as u32);
            for c in node.children() {
                assert!(
                    c < id,
                    "node {i} ({node:?}) has child {c:?} not preceding it"
                );
            }
            assert_eq!(
                self.memo.get(node),
                Some(&id),
                "memo does not map node {i} to itself"
            );
            match *node {
                Node::Const(bits) => assert!(
                    self.non_finite.is_some() || f64::from_bits(bits).is_finite(),
                    "non-finite constant not recorded"
                ),
                Node::Add(a, b) | Node::Mul(a, b) => {
                    assert_eq!(
                        self.order(a, b),
                        (a, b),
                        "node {i}: commutative operands not canonical"
                    )
                }
                _ => {}
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hash_consing_shares_commuted_expressions() {
        let mut d = Dag::new();
        let x = d.input(Sym(0));
        let y = d.input(Sym(1));
        let a = d.mul(x, y);
        let b = d.mul(y, x);
        assert_eq!(a, b);
        let s1 = d.add(a, x);
        let s2 = d.add(x, b);
        assert_eq!(s1, s2);
        d.check_invariants();
    }

    #[test]
    fn identities_fold() {
        let mut d = Dag::new();
        let x = d.input(Sym(0));
        let zero = d.constant(0.0);
        let one = d.constant(1.0);
        assert_eq!(d.add(x, zero), x);
        assert_eq!(d.mul(x, one), x);
        assert_eq!(d.sub(x, x), zero);
        let nx = d.neg(x);
        assert_eq!(d.neg(nx), x);
        let xx = d.mul(x, x);
        assert_eq!(d.node(xx), Node::Powi(x, 2));
        let two = d.constant(2.0);
        let three = d.constant(3.0);
        let six = d.mul(two, three);
        assert_eq!(d.as_const(six), Some(6.0));
        d.check_invariants();
    }

    #[test]
    fn substitute_folds_zero_inputs() {
        let mut d = Dag::new();
        let x = d.input(Sym(0));
        let y = d.input(Sym(1));
        let p = d.mul(x, y);
        let s = d.add(p, y);
        let (out, roots) = d.substitute(&[Some(s)], &HashMap::from([(Sym(0), 0.0)]));
        out.check_invariants();
        assert_eq!(out.node(roots[0].unwrap()), Node::Input(Sym(1)));
    }
}
