//! Truncated second-order jets with deferred scaling.
//!
//! A jet is a scalar `v` with its gradient and Hessian with respect to the
//! `n` coordinates `q` of a [`Signature`] (every vector is `n` long, every
//! packed matrix `n (n + 1) / 2`; the arena's signature fixes both). The second-order chain and product rules
//!
//! ```text
//! (a b)'  = a' b + a b'            (a b)'' = a'' b + a b'' + a' b'^T + b' a'^T
//! f(a)'   = f1 a'                  f(a)''  = f2 a' a'^T + f1 a''
//! ```
//!
//! are applied to a representation that keeps some terms *unexpanded*, so
//! that scaling a term costs one multiplication instead of one per matrix
//! entry, and terms with the same factor merge before they are expanded:
//!
//! ```text
//! g = dense + sum_b  c_b B_b                       (basis vectors B_b, e.g. xi')
//! H = dense + sum_m  c_m M_m                       (basis matrices M_m, e.g. r_qq)
//!           + sum_b  (u_b B_b^T + B_b u_b^T)       (symmetric rank-2 terms)
//!           + sum_st c_st (B_s B_t^T + B_t B_s^T)
//! ```
//!
//! The Hessian of the gap then contains `(n . x_xi) xi''` as one scaled
//! matrix and `sum_i n_i (x_i,qxi xi'^T + ...)` as one rank-2 term, instead
//! of a dense `n x n` block per vector component. [`JetArena::materialize`]
//! expands everything at the end.
//!
//! All entries are `Option<Id>` (`None` = structural zero).

use crate::diff::{add_opt, mul_opt, neg_opt, nonzero};
use crate::expr::{Dag, Id};
use crate::formulation::Domain;
use crate::signature::Signature;

/// A vector of structural-zero-aware entries, one per coordinate
/// ([`Signature::coords`] long).
pub type Vector = Vec<Option<Id>>;
/// A packed upper-triangular symmetric matrix
/// ([`Signature::packed_len`] long, see [`Signature::packed`]).
pub type Matrix = Vec<Option<Id>>;

/// Handle of a jet in a [`JetArena`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct JetId(usize);

/// The parts of a jet (see the module docs).
#[derive(Debug, Clone)]
struct JetData {
    v: Id,
    g: Vector,
    /// `(basis vector, coefficient)`, sorted by basis, unique.
    gl: Vec<(usize, Id)>,
    h: Matrix,
    /// `(basis matrix, coefficient)`, sorted, unique.
    hm: Vec<(usize, Id)>,
    /// `(basis vector b, u)`: `u b^T + b u^T`, sorted by `b`, unique.
    hs: Vec<(usize, Vector)>,
    /// `((s, t), c)`, `s <= t`: `c (B_s B_t^T + B_t B_s^T)`, sorted, unique.
    hp: Vec<((usize, usize), Id)>,
}

impl JetData {
    fn constant(v: Id, sig: &Signature) -> JetData {
        JetData {
            v,
            g: vec![None; sig.coords()],
            gl: Vec::new(),
            h: vec![None; sig.packed_len()],
            hm: Vec::new(),
            hs: Vec::new(),
            hp: Vec::new(),
        }
    }
}

/// The lazy parts of one entity component, as [`JetArena::entity`] takes
/// them.
#[derive(Debug, Clone, Default)]
pub struct Parts {
    /// Dense gradient.
    pub g: Option<Vector>,
    /// `(basis vector, coefficient)` gradient terms.
    pub gl: Vec<(usize, Id)>,
    /// Dense Hessian.
    pub h: Option<Matrix>,
    /// `(basis matrix, coefficient)` Hessian terms.
    pub hm: Vec<(usize, Id)>,
    /// `(basis vector, u)` rank-2 Hessian terms.
    pub hs: Vec<(usize, Vector)>,
    /// `((s, t), c)` Hessian terms.
    pub hp: Vec<((usize, usize), Id)>,
}

/// Jets over a DAG, with registered basis vectors and matrices.
pub struct JetArena<'a> {
    dag: &'a mut Dag,
    sig: &'a Signature,
    jets: Vec<JetData>,
    vectors: Vec<Vector>,
    matrices: Vec<Matrix>,
}

/// Merges `(key, value)` lists sorted by key, combining equal keys.
fn merge<K: Ord + Copy, V: Clone>(
    a: &[(K, V)],
    b: &[(K, V)],
    mut both: impl FnMut(&V, &V) -> Option<V>,
) -> Vec<(K, V)> {
    let mut out = Vec::with_capacity(a.len() + b.len());
    let (mut i, mut j) = (0, 0);
    while i < a.len() || j < b.len() {
        if j == b.len() || (i < a.len() && a[i].0 < b[j].0) {
            out.push(a[i].clone());
            i += 1;
        } else if i == a.len() || b[j].0 < a[i].0 {
            out.push(b[j].clone());
            j += 1;
        } else {
            if let Some(v) = both(&a[i].1, &b[j].1) {
                out.push((a[i].0, v));
            }
            i += 1;
            j += 1;
        }
    }
    out
}

fn is_zero(v: &Vector) -> bool {
    v.iter().all(Option::is_none)
}

impl<'a> JetArena<'a> {
    /// An arena over `dag`, for jets with respect to the coordinates of
    /// `sig`.
    pub fn new(dag: &'a mut Dag, sig: &'a Signature) -> Self {
        JetArena {
            dag,
            sig,
            jets: Vec::new(),
            vectors: Vec::new(),
            matrices: Vec::new(),
        }
    }

    /// The DAG.
    pub fn dag(&mut self) -> &mut Dag {
        self.dag
    }

    /// Registers a basis vector; returns its index.
    pub fn basis_vector(&mut self, v: Vector) -> usize {
        self.vectors.push(v);
        self.vectors.len() - 1
    }

    /// Registers a basis matrix; returns its index.
    pub fn basis_matrix(&mut self, m: Matrix) -> usize {
        self.matrices.push(m);
        self.matrices.len() - 1
    }

    fn push(&mut self, j: JetData) -> JetId {
        self.jets.push(j);
        JetId(self.jets.len() - 1)
    }

    /// A jet with value `v` and the given derivative parts.
    pub fn entity(&mut self, v: Id, parts: Parts) -> JetId {
        let mut j = JetData::constant(v, self.sig);
        if let Some(g) = parts.g {
            j.g = g;
        }
        j.gl = parts.gl;
        if let Some(h) = parts.h {
            j.h = h;
        }
        j.hm = parts.hm;
        j.hs = parts.hs.into_iter().filter(|(_, u)| !is_zero(u)).collect();
        j.hp = parts.hp;
        j.gl.sort_by_key(|t| t.0);
        j.hm.sort_by_key(|t| t.0);
        j.hs.sort_by_key(|t| t.0);
        j.hp.sort_by_key(|t| t.0);
        self.push(j)
    }

    /// `-b` for the derivative parts.
    fn negated(&mut self, b: &JetData) -> JetData {
        let dag = &mut *self.dag;
        JetData {
            v: b.v,
            g: b.g.iter().map(|&x| neg_opt(dag, x)).collect(),
            gl: b.gl.iter().map(|(k, c)| (*k, dag.neg(*c))).collect(),
            h: b.h.iter().map(|&x| neg_opt(dag, x)).collect(),
            hm: b.hm.iter().map(|(k, c)| (*k, dag.neg(*c))).collect(),
            hs: b
                .hs
                .iter()
                .map(|(k, u)| (*k, u.iter().map(|&x| neg_opt(dag, x)).collect()))
                .collect(),
            hp: b.hp.iter().map(|(k, c)| (*k, dag.neg(*c))).collect(),
        }
    }

    /// `a + b` (or `a - b`) for the derivative parts (the value is `a`'s;
    /// callers set it).
    fn combine(&mut self, a: &JetData, b: &JetData, subtract: bool) -> JetData {
        let b = if subtract { self.negated(b) } else { b.clone() };
        let dag = &mut *self.dag;
        let sum = |dag: &mut Dag, x: &Id, y: &Id| add_opt(dag, Some(*x), Some(*y));
        JetData {
            v: a.v,
            g: (0..a.g.len())
                .map(|i| add_opt(dag, a.g[i], b.g[i]))
                .collect(),
            gl: merge(&a.gl, &b.gl, |x, y| sum(dag, x, y)),
            h: (0..a.h.len())
                .map(|i| add_opt(dag, a.h[i], b.h[i]))
                .collect(),
            hm: merge(&a.hm, &b.hm, |x, y| sum(dag, x, y)),
            hs: merge(&a.hs, &b.hs, |x, y| {
                let u: Vector = (0..x.len()).map(|i| add_opt(dag, x[i], y[i])).collect();
                (!is_zero(&u)).then_some(u)
            }),
            hp: merge(&a.hp, &b.hp, |x, y| sum(dag, x, y)),
        }
    }

    /// The derivative parts of `a` scaled by `s`.
    fn scale(&mut self, a: &JetData, s: Id) -> JetData {
        let dag = &mut *self.dag;
        let m = |dag: &mut Dag, x: Option<Id>| mul_opt(dag, x, Some(s));
        let mc = |dag: &mut Dag, c: Id| {
            let p = dag.mul(c, s);
            nonzero(dag, p)
        };
        JetData {
            v: a.v,
            g: a.g.iter().map(|&x| m(dag, x)).collect(),
            gl: a
                .gl
                .iter()
                .filter_map(|(k, c)| mc(dag, *c).map(|c| (*k, c)))
                .collect(),
            h: a.h.iter().map(|&x| m(dag, x)).collect(),
            hm: a
                .hm
                .iter()
                .filter_map(|(k, c)| mc(dag, *c).map(|c| (*k, c)))
                .collect(),
            hs: a
                .hs
                .iter()
                .map(|(k, u)| (*k, u.iter().map(|&x| m(dag, x)).collect::<Vector>()))
                .filter(|(_, u)| !is_zero(u))
                .collect(),
            hp: a
                .hp
                .iter()
                .filter_map(|(k, c)| mc(dag, *c).map(|c| (*k, c)))
                .collect(),
        }
    }

    /// `a' b'^T + b' a'^T` as Hessian parts (gradient parts empty).
    fn sym_outer(&mut self, a: &JetData, b: &JetData) -> JetData {
        let sig = self.sig;
        let dag = &mut *self.dag;
        let mut out = JetData::constant(a.v, sig);
        let n = sig.coords();
        for j in 0..n {
            for k in j..n {
                let t1 = mul_opt(dag, a.g[j], b.g[k]);
                let t2 = mul_opt(dag, b.g[j], a.g[k]);
                out.h[sig.packed(j, k)] = add_opt(dag, t1, t2);
            }
        }
        // sym(A + sum a_s B_s, C + sum b_t B_t) = sym(A, C) + sum_t sym(b_t A, B_t)
        //   + sum_s sym(a_s C, B_s) + sum_st a_s b_t sym(B_s, B_t).
        let mut hs: Vec<(usize, Vector)> = Vec::new();
        for (t, bt) in &b.gl {
            hs.push((
                *t,
                a.g.iter().map(|&x| mul_opt(dag, x, Some(*bt))).collect(),
            ));
        }
        for (s, as_) in &a.gl {
            hs.push((
                *s,
                b.g.iter().map(|&x| mul_opt(dag, x, Some(*as_))).collect(),
            ));
        }
        hs.sort_by_key(|t| t.0);
        let mut merged: Vec<(usize, Vector)> = Vec::new();
        for (k, u) in hs {
            match merged.last_mut() {
                Some((lk, lu)) if *lk == k => {
                    *lu = (0..lu.len()).map(|i| add_opt(dag, lu[i], u[i])).collect()
                }
                _ => merged.push((k, u)),
            }
        }
        out.hs = merged.into_iter().filter(|(_, u)| !is_zero(u)).collect();
        let mut hp: Vec<((usize, usize), Id)> = Vec::new();
        for (s, as_) in &a.gl {
            for (t, bt) in &b.gl {
                let c = dag.mul(*as_, *bt);
                hp.push(((*s.min(t), *s.max(t)), c));
            }
        }
        hp.sort_by_key(|t| t.0);
        let mut mhp: Vec<((usize, usize), Id)> = Vec::new();
        for (k, c) in hp {
            match mhp.last_mut() {
                Some((lk, lc)) if *lk == k => *lc = dag.add(*lc, c),
                _ => mhp.push((k, c)),
            }
        }
        out.hp = mhp;
        out
    }

    /// The Hessian parts of `x` only (gradient parts cleared).
    fn hessian_parts(x: &JetData) -> JetData {
        JetData {
            v: x.v,
            g: vec![None; x.g.len()],
            gl: Vec::new(),
            h: x.h.clone(),
            hm: x.hm.clone(),
            hs: x.hs.clone(),
            hp: x.hp.clone(),
        }
    }

    /// The gradient parts of `x` only.
    fn gradient_parts(x: &JetData) -> JetData {
        JetData {
            v: x.v,
            g: x.g.clone(),
            gl: x.gl.clone(),
            h: vec![None; x.h.len()],
            hm: Vec::new(),
            hs: Vec::new(),
            hp: Vec::new(),
        }
    }

    /// `f(a)` from `f(a.v)`, `f'(a.v)`, `f''(a.v)`.
    fn chain(&mut self, a: JetId, f0: Id, f1: Id, f2: Option<Id>) -> JetId {
        let a = self.jets[a.0].clone();
        let first = self.scale(&a, f1);
        let mut out = first;
        if let Some(f2) = f2 {
            // f2 a' a'^T = (f2 / 2) sym(a', a').
            let s = self.sym_outer(&a, &a);
            let half = self.dag.constant(0.5);
            let k = self.dag.mul(half, f2);
            let s = self.scale(&s, k);
            out = self.combine(&out, &s, false);
        }
        out.v = f0;
        self.push(out)
    }

    /// Expands a jet into its value, dense gradient and packed Hessian.
    pub fn materialize(&mut self, id: JetId) -> (Id, Vector, Matrix) {
        let j = self.jets[id.0].clone();
        let sig = self.sig;
        let dag = &mut *self.dag;
        let mut g = j.g;
        for (b, c) in &j.gl {
            for (i, gi) in g.iter_mut().enumerate() {
                let t = mul_opt(dag, Some(*c), self.vectors[*b][i]);
                *gi = add_opt(dag, *gi, t);
            }
        }
        let mut h = j.h;
        for (m, c) in &j.hm {
            for (p, hp) in h.iter_mut().enumerate() {
                let t = mul_opt(dag, Some(*c), self.matrices[*m][p]);
                *hp = add_opt(dag, *hp, t);
            }
        }
        // Fold c (B_s B_t^T + B_t B_s^T) into the rank-2 term of B_t.
        let mut hs = j.hs.clone();
        for ((s, t), c) in &j.hp {
            let u: Vector = self.vectors[*s]
                .iter()
                .map(|&x| mul_opt(dag, x, Some(*c)))
                .collect();
            match hs.iter_mut().find(|(k, _)| k == t) {
                Some((_, w)) => *w = (0..w.len()).map(|i| add_opt(dag, w[i], u[i])).collect(),
                None => hs.push((*t, u)),
            }
        }
        for (b, u) in &hs {
            let bv = &self.vectors[*b];
            let n = sig.coords();
            for jj in 0..n {
                for k in jj..n {
                    let t1 = mul_opt(dag, u[jj], bv[k]);
                    let t2 = mul_opt(dag, bv[jj], u[k]);
                    let t = add_opt(dag, t1, t2);
                    let p = sig.packed(jj, k);
                    h[p] = add_opt(dag, h[p], t);
                }
            }
        }
        (j.v, g, h)
    }
}

impl Domain for JetArena<'_> {
    type S = JetId;
    fn constant(&mut self, c: f64) -> JetId {
        let v = self.dag.constant(c);
        let j = JetData::constant(v, self.sig);
        self.push(j)
    }
    fn add(&mut self, a: JetId, b: JetId) -> JetId {
        let (x, y) = (self.jets[a.0].clone(), self.jets[b.0].clone());
        let mut s = self.combine(&x, &y, false);
        s.v = self.dag.add(x.v, y.v);
        self.push(s)
    }
    fn sub(&mut self, a: JetId, b: JetId) -> JetId {
        let (x, y) = (self.jets[a.0].clone(), self.jets[b.0].clone());
        let mut s = self.combine(&x, &y, true);
        s.v = self.dag.sub(x.v, y.v);
        self.push(s)
    }
    fn mul(&mut self, a: JetId, b: JetId) -> JetId {
        let (x, y) = (self.jets[a.0].clone(), self.jets[b.0].clone());
        // Gradient: a' b + a b'.  Hessian: a'' b + a b'' + sym(a', b').
        let xg = Self::gradient_parts(&x);
        let yg = Self::gradient_parts(&y);
        let t1 = self.scale(&xg, y.v);
        let t2 = self.scale(&yg, x.v);
        let xh = Self::hessian_parts(&x);
        let yh = Self::hessian_parts(&y);
        let t3 = self.scale(&xh, y.v);
        let t4 = self.scale(&yh, x.v);
        let t5 = self.sym_outer(&x, &y);
        let mut s = self.combine(&t1, &t2, false);
        s = self.combine(&s, &t3, false);
        s = self.combine(&s, &t4, false);
        s = self.combine(&s, &t5, false);
        s.v = self.dag.mul(x.v, y.v);
        self.push(s)
    }
    fn div(&mut self, a: JetId, b: JetId) -> JetId {
        // a / b = a * (1/b); (1/b)' = -b'/b^2, (1/b)'' = 2 b' b'^T / b^3 - b''/b^2.
        let bv = self.jets[b.0].v;
        let dag = &mut *self.dag;
        let r = dag.recip(bv);
        let r2 = dag.powi(r, 2);
        let f1 = dag.neg(r2);
        let r3 = dag.powi(r, 3);
        let two = dag.constant(2.0);
        let f2 = dag.mul(two, r3);
        let rb = self.chain(b, r, f1, Some(f2));
        self.mul(a, rb)
    }
    fn neg(&mut self, a: JetId) -> JetId {
        let x = self.jets[a.0].clone();
        let zero = JetData::constant(x.v, self.sig);
        let mut s = self.combine(&zero, &x, true);
        s.v = self.dag.neg(x.v);
        self.push(s)
    }
    fn sqrt(&mut self, a: JetId) -> JetId {
        // sqrt' = 1/(2 s), sqrt'' = -1/(4 s^3).
        let av = self.jets[a.0].v;
        let dag = &mut *self.dag;
        let s = dag.sqrt(av);
        let r = dag.recip(s);
        let half = dag.constant(0.5);
        let f1 = dag.mul(half, r);
        let r3 = dag.powi(r, 3);
        let q = dag.constant(-0.25);
        let f2 = dag.mul(q, r3);
        self.chain(a, s, f1, Some(f2))
    }
    fn powi(&mut self, a: JetId, n: i32) -> JetId {
        let av = self.jets[a.0].v;
        let dag = &mut *self.dag;
        let f0 = dag.powi(av, n);
        let p1 = dag.powi(av, n - 1);
        let c1 = dag.constant(f64::from(n));
        let f1 = dag.mul(c1, p1);
        let p2 = dag.powi(av, n - 2);
        let c2 = dag.constant(f64::from(n * (n - 1)));
        let f2 = dag.mul(c2, p2);
        let f2 = nonzero(dag, f2);
        self.chain(a, f0, f1, f2)
    }
}
