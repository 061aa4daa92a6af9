//! The proof of translation invariance that the relative-coordinate
//! shortcut of [`crate::lower`] relies on.
//!
//! The kernels take the coordinates relative to the first point (its own
//! coordinates are zero). That is exact only if the formulation is
//! unchanged when every point moves by the same vector `c`. [`check`]
//! proves it, exactly, for the projection residual `r(q, xi)`, every
//! entity `E(q, xi)` and the gap; then `xi_m(q)`, every truncated
//! derivative the kernels compute (polynomials in the partial derivatives
//! of invariant functions) and the gap are invariant too. The slip
//! (`slip!`) is an expression of the entities only (the language refuses
//! anything else in it), so it is invariant once they are; it is not
//! expanded itself (a 3D tangential projection `s_m - (n . s_m) n` exceeds
//! [`MAX_TERMS`]).
//!
//! ## The argument
//!
//! Every DAG node is written as a polynomial `P` with exact rational
//! coefficients (every `f64` constant is a dyadic rational, so sums and
//! products are exact, [`BigRational`]) in
//!
//! * the input symbols (coordinates, parameters, the implicit unknown), and
//! * **atoms**: `1 / a`, `sqrt(a)` and `a^n` for `n < 0`, admitted only when
//!   the operand `a` has already been proven invariant.
//!
//! For a uniform translation along axis `k`, `d/dt E(p + t e_k)` equals the
//! formal sum `D_k P` of `dP/dv` over the coordinates `v` along axis `k`
//! (an atom does not change: its operand is invariant). `D_k P = 0` for
//! every axis, as a polynomial, proves `E(p + c) = E(p)` for every `c`.
//! The argument is sound but not complete (two different atoms that are
//! equal as functions are not identified); a formulation it cannot prove is
//! refused, never lowered with the shortcut.

use std::collections::BTreeMap;
use std::collections::HashMap;

use syn::spanned::Spanned;

use num_rational::BigRational;
use num_traits::{One, Zero};

use crate::Error;
use crate::expr::{Dag, Id, Node, Sym};
use crate::formulation::Formulation;

/// More terms than this in one polynomial: the proof gives up (and the
/// formulation is refused).
pub const MAX_TERMS: usize = 20_000;

/// A monomial: `(variable, exponent)` pairs, sorted by variable (a node
/// index of the DAG: an input or an atom).
type Monomial = Vec<(u32, u32)>;

/// A polynomial with exact coefficients.
#[derive(Debug, Clone, Default, PartialEq)]
struct Poly(BTreeMap<Monomial, BigRational>);

/// Why a node has no polynomial form.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Unproven {
    /// An atom's operand is not invariant.
    Atom,
    /// The expansion exceeds [`MAX_TERMS`].
    TooLarge,
    /// A non-finite constant.
    NonFinite,
}

impl Poly {
    fn constant(c: BigRational) -> Poly {
        let mut m = BTreeMap::new();
        if !c.is_zero() {
            m.insert(Vec::new(), c);
        }
        Poly(m)
    }

    fn var(v: u32) -> Poly {
        Poly(BTreeMap::from([(vec![(v, 1)], BigRational::one())]))
    }

    fn add_scaled(&self, o: &Poly, sign: i32) -> Poly {
        let mut m = self.0.clone();
        for (k, c) in &o.0 {
            let e = m.entry(k.clone()).or_insert_with(BigRational::zero);
            if sign < 0 {
                *e -= c;
            } else {
                *e += c;
            }
            if e.is_zero() {
                m.remove(k);
            }
        }
        Poly(m)
    }

    fn neg(&self) -> Poly {
        Poly(self.0.iter().map(|(k, c)| (k.clone(), -c)).collect())
    }

    fn mul(&self, o: &Poly) -> Result<Poly, Unproven> {
        if self.0.len().saturating_mul(o.0.len()) > MAX_TERMS * 4 {
            return Err(Unproven::TooLarge);
        }
        let mut m: BTreeMap<Monomial, BigRational> = BTreeMap::new();
        for (ka, ca) in &self.0 {
            for (kb, cb) in &o.0 {
                let k = mul_monomials(ka, kb);
                let e = m.entry(k.clone()).or_insert_with(BigRational::zero);
                *e += ca * cb;
                if e.is_zero() {
                    m.remove(&k);
                }
            }
        }
        if m.len() > MAX_TERMS {
            return Err(Unproven::TooLarge);
        }
        Ok(Poly(m))
    }

    fn pow(&self, n: u32) -> Result<Poly, Unproven> {
        let mut out = Poly::constant(BigRational::one());
        for _ in 0..n {
            out = out.mul(self)?;
        }
        Ok(out)
    }

    /// `sum over vars of dP/dv`.
    fn derivative_sum(&self, vars: &[u32]) -> Poly {
        let mut m: BTreeMap<Monomial, BigRational> = BTreeMap::new();
        for (k, c) in &self.0 {
            for (pos, &(v, e)) in k.iter().enumerate() {
                if !vars.contains(&v) {
                    continue;
                }
                let mut d = k.clone();
                if e == 1 {
                    d.remove(pos);
                } else {
                    d[pos].1 = e - 1;
                }
                let term = m.entry(d.clone()).or_insert_with(BigRational::zero);
                *term += c * BigRational::from_integer(e.into());
                if term.is_zero() {
                    m.remove(&d);
                }
            }
        }
        Poly(m)
    }
}

fn mul_monomials(a: &Monomial, b: &Monomial) -> Monomial {
    let mut out: Monomial = Vec::with_capacity(a.len() + b.len());
    let (mut i, mut j) = (0, 0);
    while i < a.len() || j < b.len() {
        match (a.get(i), b.get(j)) {
            (Some(&(va, ea)), Some(&(vb, eb))) if va == vb => {
                out.push((va, ea + eb));
                i += 1;
                j += 1;
            }
            (Some(&(va, ea)), Some(&(vb, _))) if va < vb => {
                out.push((va, ea));
                i += 1;
            }
            (Some(&x), None) => {
                out.push(x);
                i += 1;
            }
            (_, Some(&y)) => {
                out.push(y);
                j += 1;
            }
            (None, None) => unreachable!("loop condition"),
        }
    }
    out
}

/// The polynomial forms of a DAG's nodes (computed on demand, memoised).
struct Prover<'a> {
    dag: &'a Dag,
    /// Per axis, the node indices of the coordinate inputs along it.
    axes: Vec<Vec<u32>>,
    memo: HashMap<u32, Result<Poly, Unproven>>,
}

impl<'a> Prover<'a> {
    fn new(dag: &'a Dag, f: &Formulation) -> Prover<'a> {
        let dim = f.signature.dim();
        let coords: HashMap<Sym, usize> = f
            .signature
            .coord_syms()
            .into_iter()
            .enumerate()
            .map(|(i, s)| (s, i % dim))
            .collect();
        let mut axes = vec![Vec::new(); dim];
        for i in 0..dag.len() {
            if let Node::Input(s) = dag.node(dag.id(i))
                && let Some(&axis) = coords.get(&s)
            {
                axes[axis].push(i as u32);
            }
        }
        Prover {
            dag,
            axes,
            memo: HashMap::new(),
        }
    }

    /// Whether `P` is unchanged by every uniform translation.
    fn invariant(&self, p: &Poly) -> bool {
        self.axes
            .iter()
            .all(|vars| p.derivative_sum(vars).0.is_empty())
    }

    /// The polynomial form of `id`. Children precede parents, so filling
    /// the memo in index order needs no recursion.
    fn poly(&mut self, id: Id) -> Result<Poly, Unproven> {
        let live = self.dag.reachable([id]);
        for (i, &live) in live.iter().enumerate().take(id.index() + 1) {
            if !live || self.memo.contains_key(&(i as u32)) {
                continue;
            }
            let p = self.node_poly(self.dag.id(i));
            self.memo.insert(i as u32, p);
        }
        self.memo[&(id.index() as u32)].clone()
    }

    fn get(&self, id: Id) -> Result<&Poly, Unproven> {
        self.memo[&(id.index() as u32)].as_ref().map_err(|e| *e)
    }

    /// An atom: a variable of its own if `a` is invariant.
    fn atom(&self, node: Id, a: Id) -> Result<Poly, Unproven> {
        if self.invariant(self.get(a)?) {
            Ok(Poly::var(node.index() as u32))
        } else {
            Err(Unproven::Atom)
        }
    }

    fn node_poly(&self, id: Id) -> Result<Poly, Unproven> {
        let index = id.index() as u32;
        Ok(match self.dag.node(id) {
            Node::Const(bits) => Poly::constant(
                BigRational::from_float(f64::from_bits(bits)).ok_or(Unproven::NonFinite)?,
            ),
            Node::Input(_) => Poly::var(index),
            Node::Add(a, b) => self.get(a)?.add_scaled(self.get(b)?, 1),
            Node::Sub(a, b) => self.get(a)?.add_scaled(self.get(b)?, -1),
            Node::Mul(a, b) => self.get(a)?.mul(self.get(b)?)?,
            Node::Neg(a) => self.get(a)?.neg(),
            Node::Powi(a, n) if n >= 0 => self.get(a)?.pow(n.unsigned_abs())?,
            Node::Powi(a, _) | Node::Recip(a) | Node::Sqrt(a) => self.atom(id, a)?,
        })
    }
}

/// A 1-based `(line, column)`.
type Position = (usize, usize);

/// Proves that `f`'s projection residual, every entity and the gap are
/// translation invariant (module documentation), or says which is not, at
/// the `let` that defines it (the `gap!` for the gap).
pub fn check(f: &Formulation) -> Result<(), Error> {
    let mut dag = f.dag.clone();
    let gap = crate::truncation::gap_value(f, &mut dag)?;

    let at = |name: &str| {
        f.lets
            .iter()
            .find(|(n, ..)| n == name)
            .map(|&(_, line, column)| (line, column))
    };
    let start = f.gap.span().start();
    let mut targets: Vec<(String, Id, Option<Position>)> = f
        .implicit
        .components
        .iter()
        .map(|&(_, r)| {
            (
                "the projection residual".to_owned(),
                r,
                at(&f.implicit.name),
            )
        })
        .collect();
    for e in &f.entities {
        for id in e.value.components() {
            targets.push((format!("entity `{}`", e.name), id, at(&e.name)));
        }
    }
    targets.push((
        "the gap".to_owned(),
        gap,
        Some((start.line, start.column + 1)),
    ));

    let mut prover = Prover::new(&dag, f);
    for (what, id, position) in targets {
        let why = match prover.poly(id) {
            Ok(p) if prover.invariant(&p) => continue,
            Ok(_) => "moving every point by the same vector changes it",
            Err(Unproven::Atom) => {
                "it takes a square root, reciprocal or negative power of a value that \
                 changes when every point moves by the same vector"
            }
            Err(Unproven::TooLarge) => "its expansion exceeds the prover's size limit",
            Err(Unproven::NonFinite) => "it holds a non-finite constant",
        };
        let file = format!("{}.rs", f.name);
        let message = format!(
            "cannot prove that {what} is translation invariant ({why}); the kernels take \
             coordinates relative to the first point, so a formulation must depend on \
             coordinate differences only (e.g. `xs2 - xs1`, `lerp(xm1, xm2, xi) - x_s`)"
        );
        return Err(match position {
            Some((line, column)) => Error::Formulation {
                file,
                line,
                column,
                message,
            },
            None => Error::Truncation { file, message },
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    const SN: &str = include_str!("../../contact-kernels/formulations/slave-normal.rs");

    #[test]
    fn the_shipped_formulations_are_proven_invariant() {
        for (name, text) in [
            ("slave-normal", SN),
            (
                "closest-point",
                include_str!("../../contact-kernels/formulations/closest-point.rs"),
            ),
            (
                "quadratic-slave-normal",
                include_str!("../../contact-kernels/formulations/quadratic-slave-normal.rs"),
            ),
        ] {
            let f = Formulation::parse(name, text).unwrap();
            check(&f).unwrap_or_else(|e| panic!("{name}: {e}"));
        }
    }

    #[test]
    fn an_absolute_position_is_refused_with_its_statement() {
        for (from, to, what) in [
            (
                "let t_s = xs2 - xs1;",
                "let t_s = xs2 - xs1 + xs1;",
                "residual",
            ),
            (
                "entity!(lerp(xm1, xm2, xi_m) - x_s)",
                "entity!(lerp(xm1, xm2, xi_m) - x_s + 0.5 * xm1)",
                "entity `x_ms`",
            ),
        ] {
            assert!(SN.contains(from), "{from}");
            let f = Formulation::parse("bad", &SN.replace(from, to)).unwrap();
            let e = check(&f).unwrap_err().to_string();
            assert!(
                e.starts_with("bad.rs:") && e.contains(": cannot prove that") && e.contains(what),
                "{e}"
            );
        }
    }

    /// Invariance that needs cancellation across terms (shape functions
    /// summing to one, expanded products) is proven; exact rationals, so a
    /// sum that rounds to zero in `f64` is not taken for zero.
    #[test]
    fn cancellation_is_exact() {
        let ok = SN.replace(
            "let t_s = xs2 - xs1;",
            "let t_s = 0.1 * xs2 + 0.2 * xs2 - 0.30000000000000004 * xs1 - 0.5 * (xs1 - xs2) \
             - 0.5 * xs1 + 0.5 * xs2;",
        );
        // 0.1 + 0.2 is 0.30000000000000004 in f64 but not exactly: the
        // coefficients of xs2 and xs1 differ in the rationals.
        let f = Formulation::parse("ok", &ok).unwrap();
        assert!(check(&f).is_err());
        let ok = SN.replace(
            "let t_s = xs2 - xs1;",
            "let t_s = 0.25 * xs2 + 0.75 * xs2 - 0.5 * xs1 - 0.5 * xs1;",
        );
        check(&Formulation::parse("ok", &ok).unwrap()).unwrap();
        // n times an expanded |xs2 - xs1|^2 - |t_s|^2 + 1 (that is, 1).
        let sq = SN.replace(
            "let n = entity!(perp(t_s) / norm(t_s));",
            "let n = entity!(perp(t_s) / norm(t_s) * (1.0 + dot(xs2, xs2) - 2.0 * dot(xs1, xs2) \
             + dot(xs1, xs1) - dot(t_s, t_s)));",
        );
        check(&Formulation::parse("sq", &sq).unwrap()).unwrap();
    }
}
