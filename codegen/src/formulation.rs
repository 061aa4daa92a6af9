//! Formulation files: a small Rust-syntax language for contact kinematics
//! (the user's reference: `docs/formulations.md`).
//!
//! A formulation file is a sequence of Rust statements, parsed with `syn`
//! and interpreted into the expression DAG. Example (the paper's
//! slave-normal formulation):
//!
//! ```text
//! //! Projection along the slave normal.
//! inputs!(xs1, xs2, xm1, xm2; xi_s);
//! let x_s = lerp(xs1, xs2, xi_s);
//! let t_s = xs2 - xs1;
//! let xi_m = implicit!(xi => dot(lerp(xm1, xm2, xi) - x_s, t_s));
//! let x_ms = entity!(lerp(xm1, xm2, xi_m) - x_s);
//! let n = entity!(perp(t_s) / norm(t_s));
//! gap!(dot(n, x_ms));
//! ```
//!
//! * `inputs!(p1, p2, p3, p4; s)` declares the nodal points (2-vectors, in
//!   kernel order: slave 1, slave 2, master 1, master 2 — the coordinates
//!   `q`; or six points for 3-node segments: the slave's end, end, mid
//!   nodes, then the master's) and the slave parameter `s` (`xi_s`); they become the kernels'
//!   [`Signature`]. [`Formulation::parse`] accepts the shape the
//!   contact-kernels run-time serves ([`Arity::SegmentPair`]);
//!   [`Formulation::parse_with`] any number of points and parameters.
//! * `implicit!(xi => r)` defines a scalar as the root of `r(q, xi) = 0`;
//!   the generator never solves it in closed form: its derivatives come from
//!   implicit differentiation and its value from a Newton solve at run time.
//! * `entity!(e)` marks a value whose dependence on `q` the approximation
//!   types truncate (see [`crate::truncation`]). The implicit variable is an
//!   entity too.
//! * `gap!(e)` gives the gap as an expression of entities only.
//! * Values are scalars or 2-vectors. Operators: `+ - * /` (vector ± vector,
//!   vector * scalar, scalar * vector, vector / scalar), unary `-`, numeric
//!   literals, `v.x`, `v.y`. Functions: `lerp(a, b, xi)` (linear shape
//!   functions `(1-xi)/2 a + (1+xi)/2 b`), `dot(a, b)`, `perp(t)` =
//!   `(t.y, -t.x)` (the outward normal direction of a counter-clockwise
//!   segment), `norm(v)`, `sqrt(x)`, `powi(x, n)`, `vec2(x, y)`.
//! * `//!` lines at the top are the formulation's documentation.
//!
//! Formulations must depend on coordinate differences only (translation
//! invariance): the kernels are evaluated relative to slave node 1.

use std::collections::HashMap;

use proc_macro2::{Span, TokenStream};
use syn::parse::Parser;
use syn::spanned::Spanned;

use crate::Error;
use crate::expr::{Dag, Id, Sym};
use crate::signature::Signature;

/// A value of the formulation language.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Value<S> {
    /// A scalar.
    Scalar(S),
    /// A 2-vector.
    Vec2([S; 2]),
}

impl<S: Copy> Value<S> {
    /// The scalar components (one or two).
    pub fn components(&self) -> Vec<S> {
        match *self {
            Value::Scalar(s) => vec![s],
            Value::Vec2([a, b]) => vec![a, b],
        }
    }
}

/// Scalar arithmetic the interpreter needs; implemented by the DAG (values)
/// and by truncated jets (derivatives of the gap).
pub trait Domain {
    /// The scalar type.
    type S: Copy;
    /// A constant.
    fn constant(&mut self, c: f64) -> Self::S;
    /// `a + b`.
    fn add(&mut self, a: Self::S, b: Self::S) -> Self::S;
    /// `a - b`.
    fn sub(&mut self, a: Self::S, b: Self::S) -> Self::S;
    /// `a * b`.
    fn mul(&mut self, a: Self::S, b: Self::S) -> Self::S;
    /// `a / b`.
    fn div(&mut self, a: Self::S, b: Self::S) -> Self::S;
    /// `-a`.
    fn neg(&mut self, a: Self::S) -> Self::S;
    /// `sqrt(a)`.
    fn sqrt(&mut self, a: Self::S) -> Self::S;
    /// `a^n`.
    fn powi(&mut self, a: Self::S, n: i32) -> Self::S;
    /// The first non-finite constant a fold produced, if the domain folds
    /// constants (the DAG does: [`Dag::non_finite`]).
    fn non_finite(&self) -> Option<f64> {
        None
    }
}

impl Domain for Dag {
    type S = Id;
    fn constant(&mut self, c: f64) -> Id {
        Dag::constant(self, c)
    }
    fn add(&mut self, a: Id, b: Id) -> Id {
        Dag::add(self, a, b)
    }
    fn sub(&mut self, a: Id, b: Id) -> Id {
        Dag::sub(self, a, b)
    }
    fn mul(&mut self, a: Id, b: Id) -> Id {
        Dag::mul(self, a, b)
    }
    fn div(&mut self, a: Id, b: Id) -> Id {
        Dag::div(self, a, b)
    }
    fn neg(&mut self, a: Id) -> Id {
        Dag::neg(self, a)
    }
    fn sqrt(&mut self, a: Id) -> Id {
        Dag::sqrt(self, a)
    }
    fn powi(&mut self, a: Id, n: i32) -> Id {
        Dag::powi(self, a, n)
    }
    fn non_finite(&self) -> Option<f64> {
        Dag::non_finite(self)
    }
}

/// The implicit variable of a formulation.
#[derive(Debug, Clone)]
pub struct Implicit {
    /// Its name in the file (an entity name, `xi_m`).
    pub name: String,
    /// The symbol standing for its value.
    pub sym: Sym,
    /// The residual `r(q, xi)`.
    pub residual: Id,
}

/// A named entity (other than the implicit variable).
#[derive(Debug, Clone)]
pub struct Entity {
    /// Its name in the file.
    pub name: String,
    /// Its value as a function of `q` and the implicit symbol.
    pub value: Value<Id>,
}

/// A parsed formulation: its expressions in one DAG.
#[derive(Debug, Clone)]
pub struct Formulation {
    /// The name (the file stem, e.g. `slave-normal`).
    pub name: String,
    /// The `//!` documentation of the file.
    pub doc: String,
    /// The DAG holding every expression.
    pub dag: Dag,
    /// The kernel inputs `inputs!` declares (points, parameters, the
    /// implicit unknown) and the sizes and symbols that follow.
    pub signature: Signature,
    /// The implicit variable (the projection coordinate).
    pub implicit: Implicit,
    /// The entities, in file order.
    pub entities: Vec<Entity>,
    /// The gap expression (entities only).
    pub gap: syn::Expr,
    /// Where each `let` name is defined: `(name, line, column)`, 1-based,
    /// in file order (for errors found after parsing).
    pub lets: Vec<(String, usize, usize)>,
}

/// Which `inputs!` declarations a parse accepts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Arity {
    /// What the contact-kernels run-time serves: a slave and a master
    /// segment with equally many nodes — four points (two-node straight
    /// segments) or six (three-node quadratic segments, Gmsh line3 order:
    /// end, end, mid) — and one parameter (`xi_s`).
    SegmentPair,
    /// Any number of points (at least one) and of parameters: for
    /// generators and tests that do not feed the contact-kernels run-time.
    Any,
}

fn err(span: Span, origin: &str, msg: impl Into<String>) -> Error {
    let start = span.start();
    Error::Formulation {
        file: origin.to_owned(),
        line: start.line,
        column: start.column + 1,
        message: msg.into(),
    }
}

impl Formulation {
    /// Parses a formulation file. `name` is the formulation's name (the
    /// file stem), used in messages and generated identifiers. The inputs
    /// must be [`Arity::SegmentPair`]'s.
    pub fn parse(name: &str, text: &str) -> Result<Formulation, Error> {
        Self::parse_with(name, text, Arity::SegmentPair)
    }

    /// Parses a formulation file whose `inputs!` satisfy `arity`.
    pub fn parse_with(name: &str, text: &str, arity: Arity) -> Result<Formulation, Error> {
        let origin = format!("{name}.rs");
        let doc: String = text
            .lines()
            .map(str::trim_start)
            .filter_map(|l| l.strip_prefix("//!"))
            .map(|l| l.strip_prefix(' ').unwrap_or(l))
            .collect::<Vec<_>>()
            .join("\n");
        let body: String = text
            .lines()
            .map(|l| {
                if l.trim_start().starts_with("//!") {
                    ""
                } else {
                    l
                }
            })
            .collect::<Vec<_>>()
            .join("\n");
        let stmts = syn::Block::parse_within
            .parse_str(&body)
            .map_err(|e| err(e.span(), &origin, e.to_string()))?;

        let mut b = Builder {
            origin: origin.clone(),
            dag: Dag::new(),
            env: HashMap::new(),
            arity,
            signature: None,
        };
        let mut inputs_seen = false;
        let mut implicit: Option<Implicit> = None;
        let mut entities: Vec<Entity> = Vec::new();
        let mut gap: Option<syn::Expr> = None;
        let mut lets: Vec<(String, usize, usize)> = Vec::new();

        for stmt in &stmts {
            match stmt {
                syn::Stmt::Macro(m) if m.mac.path.is_ident("inputs") => {
                    if inputs_seen {
                        return Err(err(m.span(), &origin, "`inputs!` given twice"));
                    }
                    inputs_seen = true;
                    b.declare_inputs(&m.mac.tokens, m.span())?;
                }
                syn::Stmt::Macro(m) if m.mac.path.is_ident("gap") => {
                    if gap.is_some() {
                        return Err(err(m.span(), &origin, "`gap!` given twice"));
                    }
                    let e: syn::Expr = syn::parse2(m.mac.tokens.clone())
                        .map_err(|e| err(e.span(), &origin, e.to_string()))?;
                    gap = Some(e);
                }
                syn::Stmt::Local(local) => {
                    if !inputs_seen {
                        return Err(err(local.span(), &origin, "`inputs!(...)` must come first"));
                    }
                    let syn::Pat::Ident(pat) = &local.pat else {
                        return Err(err(local.pat.span(), &origin, "expected `let name = ...`"));
                    };
                    let name = pat.ident.to_string();
                    let at = pat.ident.span().start();
                    lets.push((name.clone(), at.line, at.column + 1));
                    let Some(init) = &local.init else {
                        return Err(err(
                            local.span(),
                            &origin,
                            format!("`let {name}` needs a value"),
                        ));
                    };
                    if b.env.contains_key(&name) {
                        return Err(err(
                            pat.ident.span(),
                            &origin,
                            format!("`{name}` is already defined"),
                        ));
                    }
                    let value = match &*init.expr {
                        syn::Expr::Macro(m) if m.mac.path.is_ident("implicit") => {
                            if implicit.is_some() {
                                return Err(err(
                                    m.span(),
                                    &origin,
                                    "only one `implicit!` variable is supported",
                                ));
                            }
                            let residual = b.implicit(&m.mac.tokens, m.span())?;
                            let sym = b.implicit_sym();
                            implicit = Some(Implicit {
                                name: name.clone(),
                                sym,
                                residual,
                            });
                            let x = b.dag.input(sym);
                            Value::Scalar(x)
                        }
                        syn::Expr::Macro(m) if m.mac.path.is_ident("entity") => {
                            let e: syn::Expr = syn::parse2(m.mac.tokens.clone())
                                .map_err(|e| err(e.span(), &origin, e.to_string()))?;
                            let v = b.eval(&e)?;
                            entities.push(Entity {
                                name: name.clone(),
                                value: v,
                            });
                            v
                        }
                        e => b.eval(e)?,
                    };
                    b.env.insert(name, value);
                }
                syn::Stmt::Macro(m) => return Err(misplaced_macro(&m.mac, &origin)),
                other => {
                    return Err(err(
                        other.span(),
                        &origin,
                        "expected `inputs!(..)`, `let name = ...;` or `gap!(..)`",
                    ));
                }
            }
        }
        let whole = Span::call_site();
        if !inputs_seen {
            return Err(err(
                whole,
                &origin,
                "missing `inputs!(p1, p2, p3, p4; xi_s)`",
            ));
        }
        let implicit = implicit.ok_or_else(|| {
            err(
                whole,
                &origin,
                "missing the projection `let xi_m = implicit!(xi => ...)`",
            )
        })?;
        let gap = gap.ok_or_else(|| err(whole, &origin, "missing `gap!(...)`"))?;
        let mut signature = b.signature.expect("`inputs!` was seen");
        signature.set_implicit(implicit.name.clone());
        Ok(Formulation {
            name: name.to_owned(),
            doc,
            dag: b.dag,
            signature,
            implicit,
            entities,
            gap,
            lets,
        })
    }

    /// Interprets the gap expression in `domain`, with each entity name bound
    /// to `entity_values[name]` (the implicit variable included).
    pub fn eval_gap<D: Domain>(
        &self,
        domain: &mut D,
        entity_values: &HashMap<String, Value<D::S>>,
    ) -> Result<D::S, Error> {
        let origin = format!("{}.rs", self.name);
        match eval_expr(
            domain,
            entity_values,
            &self.gap,
            &origin,
            "the gap may only use entities",
        )? {
            Value::Scalar(s) => Ok(s),
            Value::Vec2(_) => Err(err(self.gap.span(), &origin, "the gap must be a scalar")),
        }
    }
}

struct Builder {
    origin: String,
    dag: Dag,
    env: HashMap<String, Value<Id>>,
    arity: Arity,
    /// Set by `inputs!` (the implicit unknown's name is filled in last).
    signature: Option<Signature>,
}

impl Builder {
    /// The implicit unknown's symbol (after `inputs!`, which `let`
    /// statements require).
    fn implicit_sym(&self) -> Sym {
        self.signature
            .as_ref()
            .expect("`inputs!` precedes every `let`")
            .implicit_sym()
    }

    fn declare_inputs(&mut self, tokens: &TokenStream, span: Span) -> Result<(), Error> {
        let text = tokens.to_string();
        let (points, params) = text.split_once(';').ok_or_else(|| {
            err(
                span,
                &self.origin,
                "expected `inputs!(p1, p2, p3, p4; xi_s)`",
            )
        })?;
        let points: Vec<&str> = points.split(',').map(str::trim).collect();
        let params: Vec<&str> = params
            .split(',')
            .map(str::trim)
            .filter(|s| !s.is_empty())
            .collect();
        let fits = match self.arity {
            Arity::SegmentPair => matches!(points.len(), 4 | 6) && params.len() == 1,
            Arity::Any => !points.is_empty() && points.iter().all(|p| !p.is_empty()),
        };
        if !fits {
            let expected = match self.arity {
                Arity::SegmentPair => {
                    "four points and one parameter: `inputs!(xs1, xs2, xm1, xm2; xi_s)` \
                     (or six for 3-node segments: `inputs!(xs1, xs2, xs3, xm1, xm2, xm3; xi_s)`)"
                }
                Arity::Any => "at least one point: `inputs!(p1, ...; s1, ...)`",
            };
            return Err(err(
                span,
                &self.origin,
                format!(
                    "expected {expected}, got {} and {}",
                    points.len(),
                    params.len()
                ),
            ));
        }
        let sig = Signature::new(
            2,
            points.iter().map(|p| (*p).to_owned()).collect(),
            params.iter().map(|p| (*p).to_owned()).collect(),
            String::new(),
        );
        for (i, p) in points.iter().enumerate() {
            let x = self.dag.input(sig.coord_sym(2 * i));
            let y = self.dag.input(sig.coord_sym(2 * i + 1));
            self.bind(p, Value::Vec2([x, y]), span)?;
        }
        for (i, p) in params.iter().enumerate() {
            let s = self.dag.input(sig.param_sym(i));
            self.bind(p, Value::Scalar(s), span)?;
        }
        self.signature = Some(sig);
        Ok(())
    }

    fn bind(&mut self, name: &str, v: Value<Id>, span: Span) -> Result<(), Error> {
        if syn::parse_str::<syn::Ident>(name).is_err() {
            return Err(err(span, &self.origin, format!("`{name}` is not a name")));
        }
        if self.env.insert(name.to_owned(), v).is_some() {
            return Err(err(span, &self.origin, format!("`{name}` declared twice")));
        }
        Ok(())
    }

    fn implicit(&mut self, tokens: &TokenStream, span: Span) -> Result<Id, Error> {
        let closure = syn::parse2::<ImplicitDef>(tokens.clone())
            .map_err(|e| err(e.span(), &self.origin, e.to_string()))?;
        let var = closure.var.to_string();
        let x = self.dag.input(self.implicit_sym());
        let previous = self.env.insert(var.clone(), Value::Scalar(x));
        let r = self.eval(&closure.residual);
        match previous {
            Some(p) => self.env.insert(var.clone(), p),
            None => self.env.remove(&var),
        };
        match r? {
            Value::Scalar(r) if !self.dag.reachable([r])[x.index()] => Err(err(
                closure.residual.span(),
                &self.origin,
                format!(
                    "the projection residual does not depend on `{var}`: `{var} => r` needs an \
                     r that changes with `{var}` (its zero is the projection)"
                ),
            )),
            Value::Scalar(r) => Ok(r),
            Value::Vec2(_) => Err(err(
                span,
                &self.origin,
                "the implicit residual must be a scalar",
            )),
        }
    }

    fn eval(&mut self, e: &syn::Expr) -> Result<Value<Id>, Error> {
        eval_expr(&mut self.dag, &self.env, e, &self.origin, "unknown name")
    }
}

/// `xi => residual`
struct ImplicitDef {
    var: syn::Ident,
    residual: syn::Expr,
}

impl syn::parse::Parse for ImplicitDef {
    fn parse(input: syn::parse::ParseStream) -> syn::Result<Self> {
        let var = input.parse()?;
        input.parse::<syn::Token![=>]>()?;
        let residual = input.parse()?;
        Ok(ImplicitDef { var, residual })
    }
}

/// Interprets `e` over `domain` with the names in `env`; an expression
/// whose constant folds to infinity or NaN (`1.0 / 0.0`, `sqrt(-1.0)`, an
/// overflow) is an error at its position.
fn eval_expr<D: Domain>(
    d: &mut D,
    env: &HashMap<String, Value<D::S>>,
    e: &syn::Expr,
    origin: &str,
    unknown: &str,
) -> Result<Value<D::S>, Error> {
    let v = eval_expr_inner(d, env, e, origin, unknown)?;
    match d.non_finite() {
        None => Ok(v),
        Some(c) => Err(err(
            e.span(),
            origin,
            format!(
                "`{}` gives the non-finite constant {c} (a division by zero, the square root \
                 of a negative number or an overflow)",
                e.span()
                    .source_text()
                    .unwrap_or_else(|| quote::quote!(#e).to_string())
            ),
        )),
    }
}

/// A macro where none is expected, or an unknown one.
fn misplaced_macro(m: &syn::Macro, origin: &str) -> Error {
    let path = &m.path;
    let name = quote::quote!(#path).to_string().replace(' ', "");
    let msg = match name.as_str() {
        "implicit" | "entity" => format!("`{name}!` must be the whole value of a `let`"),
        "inputs" | "gap" => format!("`{name}!(..);` is a statement of its own"),
        _ => format!("unknown macro `{name}!` (known: inputs!, implicit!, entity!, gap!)"),
    };
    err(m.span(), origin, msg)
}

/// [`eval_expr`] without the non-finite check.
fn eval_expr_inner<D: Domain>(
    d: &mut D,
    env: &HashMap<String, Value<D::S>>,
    e: &syn::Expr,
    origin: &str,
    unknown: &str,
) -> Result<Value<D::S>, Error> {
    use Value::{Scalar, Vec2};
    let ev = |d: &mut D, e: &syn::Expr| eval_expr(d, env, e, origin, unknown);
    match e {
        syn::Expr::Paren(p) => ev(d, &p.expr),
        syn::Expr::Group(g) => ev(d, &g.expr),
        syn::Expr::Lit(l) => Ok(Scalar(d.constant(literal(&l.lit, origin)?))),
        syn::Expr::Path(p) => {
            let name = p
                .path
                .get_ident()
                .map(|i| i.to_string())
                .unwrap_or_default();
            env.get(&name).copied().ok_or_else(|| {
                err(
                    p.span(),
                    origin,
                    format!("{unknown}: `{}`", quote::quote!(#p)),
                )
            })
        }
        syn::Expr::Unary(u) => match u.op {
            syn::UnOp::Neg(_) => Ok(match ev(d, &u.expr)? {
                Scalar(a) => Scalar(d.neg(a)),
                Vec2([a, b]) => Vec2([d.neg(a), d.neg(b)]),
            }),
            _ => Err(err(u.span(), origin, "only unary `-` is supported")),
        },
        syn::Expr::Field(f) => {
            let v = ev(d, &f.base)?;
            let syn::Member::Named(m) = &f.member else {
                return Err(err(f.span(), origin, "use `.x` or `.y`"));
            };
            match (v, m.to_string().as_str()) {
                (Vec2([x, _]), "x") => Ok(Scalar(x)),
                (Vec2([_, y]), "y") => Ok(Scalar(y)),
                (Vec2(_), other) => Err(err(
                    m.span(),
                    origin,
                    format!("no component `{other}` (use `.x` or `.y`)"),
                )),
                (Scalar(_), _) => Err(err(f.span(), origin, "a scalar has no components")),
            }
        }
        syn::Expr::Binary(b) => {
            let (l, r) = (ev(d, &b.left)?, ev(d, &b.right)?);
            let bad = |what: &str| err(b.span(), origin, format!("cannot {what}"));
            match (&b.op, l, r) {
                (syn::BinOp::Add(_), Scalar(a), Scalar(c)) => Ok(Scalar(d.add(a, c))),
                (syn::BinOp::Add(_), Vec2([a, b2]), Vec2([c, e2])) => {
                    Ok(Vec2([d.add(a, c), d.add(b2, e2)]))
                }
                (syn::BinOp::Sub(_), Scalar(a), Scalar(c)) => Ok(Scalar(d.sub(a, c))),
                (syn::BinOp::Sub(_), Vec2([a, b2]), Vec2([c, e2])) => {
                    Ok(Vec2([d.sub(a, c), d.sub(b2, e2)]))
                }
                (syn::BinOp::Add(_) | syn::BinOp::Sub(_), _, _) => {
                    Err(bad("add or subtract a scalar and a vector"))
                }
                (syn::BinOp::Mul(_), Scalar(a), Scalar(c)) => Ok(Scalar(d.mul(a, c))),
                (syn::BinOp::Mul(_), Scalar(s), Vec2([a, c]))
                | (syn::BinOp::Mul(_), Vec2([a, c]), Scalar(s)) => {
                    Ok(Vec2([d.mul(s, a), d.mul(s, c)]))
                }
                (syn::BinOp::Mul(_), Vec2(_), Vec2(_)) => {
                    Err(bad("multiply two vectors (use `dot`)"))
                }
                (syn::BinOp::Div(_), Scalar(a), Scalar(c)) => Ok(Scalar(d.div(a, c))),
                (syn::BinOp::Div(_), Vec2([a, c]), Scalar(s)) => {
                    Ok(Vec2([d.div(a, s), d.div(c, s)]))
                }
                (syn::BinOp::Div(_), _, Vec2(_)) => Err(bad("divide by a vector")),
                _ => Err(err(b.span(), origin, "only `+ - * /` are supported")),
            }
        }
        syn::Expr::Call(c) => {
            let syn::Expr::Path(fp) = &*c.func else {
                return Err(err(c.func.span(), origin, "expected a function name"));
            };
            let fname = fp
                .path
                .get_ident()
                .map(|i| i.to_string())
                .unwrap_or_default();
            let arity = |n: usize| -> Result<(), Error> {
                if c.args.len() == n {
                    Ok(())
                } else {
                    Err(err(
                        c.span(),
                        origin,
                        format!("`{fname}` takes {n} argument(s), got {}", c.args.len()),
                    ))
                }
            };
            let args: Vec<&syn::Expr> = c.args.iter().collect();
            let type_err = |what: &str| err(c.span(), origin, format!("`{fname}` expects {what}"));
            match fname.as_str() {
                "lerp" => {
                    arity(3)?;
                    let (a, b2, xi) = (ev(d, args[0])?, ev(d, args[1])?, ev(d, args[2])?);
                    let Scalar(xi) = xi else {
                        return Err(type_err("a scalar third argument"));
                    };
                    let half = d.constant(0.5);
                    let one = d.constant(1.0);
                    let m = d.sub(one, xi);
                    let n1 = d.mul(half, m);
                    let p = d.add(one, xi);
                    let n2 = d.mul(half, p);
                    let comb = |d: &mut D, a: D::S, b: D::S| {
                        let u = d.mul(n1, a);
                        let v = d.mul(n2, b);
                        d.add(u, v)
                    };
                    match (a, b2) {
                        (Scalar(a), Scalar(b)) => Ok(Scalar(comb(d, a, b))),
                        (Vec2([ax, ay]), Vec2([bx, by])) => {
                            Ok(Vec2([comb(d, ax, bx), comb(d, ay, by)]))
                        }
                        _ => Err(type_err("two values of the same kind")),
                    }
                }
                "dot" => {
                    arity(2)?;
                    match (ev(d, args[0])?, ev(d, args[1])?) {
                        (Vec2([a, b2]), Vec2([c2, e2])) => {
                            let u = d.mul(a, c2);
                            let v = d.mul(b2, e2);
                            Ok(Scalar(d.add(u, v)))
                        }
                        _ => Err(type_err("two vectors")),
                    }
                }
                "perp" => {
                    arity(1)?;
                    match ev(d, args[0])? {
                        Vec2([x, y]) => Ok(Vec2([y, d.neg(x)])),
                        _ => Err(type_err("a vector")),
                    }
                }
                "norm" => {
                    arity(1)?;
                    match ev(d, args[0])? {
                        Vec2([x, y]) => {
                            let u = d.mul(x, x);
                            let v = d.mul(y, y);
                            let s = d.add(u, v);
                            Ok(Scalar(d.sqrt(s)))
                        }
                        _ => Err(type_err("a vector")),
                    }
                }
                "sqrt" => {
                    arity(1)?;
                    match ev(d, args[0])? {
                        Scalar(x) => Ok(Scalar(d.sqrt(x))),
                        _ => Err(type_err("a scalar")),
                    }
                }
                "powi" => {
                    arity(2)?;
                    let Scalar(x) = ev(d, args[0])? else {
                        return Err(type_err("a scalar base"));
                    };
                    let n = match args[1] {
                        syn::Expr::Lit(syn::ExprLit {
                            lit: syn::Lit::Int(i),
                            ..
                        }) => i.base10_parse::<i32>().ok(),
                        syn::Expr::Unary(syn::ExprUnary {
                            op: syn::UnOp::Neg(_),
                            expr,
                            ..
                        }) => match &**expr {
                            syn::Expr::Lit(syn::ExprLit {
                                lit: syn::Lit::Int(i),
                                ..
                            }) => i.base10_parse::<i32>().ok().map(|n| -n),
                            _ => None,
                        },
                        _ => None,
                    };
                    let n = n.ok_or_else(|| type_err("an integer literal exponent"))?;
                    Ok(Scalar(d.powi(x, n)))
                }
                "vec2" => {
                    arity(2)?;
                    match (ev(d, args[0])?, ev(d, args[1])?) {
                        (Scalar(x), Scalar(y)) => Ok(Vec2([x, y])),
                        _ => Err(type_err("two scalars")),
                    }
                }
                other => Err(err(
                    fp.span(),
                    origin,
                    format!(
                        "unknown function `{other}` (known: lerp, dot, perp, norm, sqrt, powi, vec2)"
                    ),
                )),
            }
        }
        syn::Expr::Macro(m) => Err(misplaced_macro(&m.mac, origin)),
        other => Err(err(other.span(), origin, "unsupported expression")),
    }
}

fn literal(lit: &syn::Lit, origin: &str) -> Result<f64, Error> {
    let v = match lit {
        syn::Lit::Float(f) => f.base10_parse::<f64>().ok(),
        syn::Lit::Int(i) => i.base10_parse::<f64>().ok(),
        _ => None,
    };
    v.filter(|v| v.is_finite())
        .ok_or_else(|| err(lit.span(), origin, "expected a finite number"))
}

#[cfg(test)]
mod tests {
    use super::*;

    const SN: &str = "//! test\ninputs!(xs1, xs2, xm1, xm2; xi_s);\nlet x_s = lerp(xs1, xs2, xi_s);\nlet t_s = xs2 - xs1;\nlet xi_m = implicit!(xi => dot(lerp(xm1, xm2, xi) - x_s, t_s));\nlet x_ms = entity!(lerp(xm1, xm2, xi_m) - x_s);\nlet n = entity!(perp(t_s) / norm(t_s));\ngap!(dot(n, x_ms));\n";

    #[test]
    fn parses_slave_normal() {
        let f = Formulation::parse("sn", SN).unwrap();
        assert_eq!(f.doc, "test");
        assert_eq!(f.entities.len(), 2);
        f.dag.check_invariants();
    }

    /// The run-time's segment pairs: two-node (4 points) or 3-node (6
    /// points) segments and one parameter; other counts are refused.
    #[test]
    fn segment_pairs_have_four_or_six_points() {
        let six = SN
            .replace(
                "inputs!(xs1, xs2, xm1, xm2; xi_s);",
                "inputs!(xs1, xs2, xs3, xm1, xm2, xm3; xi_s);",
            )
            .replace("lerp(xs1, xs2, xi_s)", "lerp(xs1, xs3, xi_s)")
            .replace("lerp(xm1, xm2,", "lerp(xm1, xm3,");
        let f = Formulation::parse("six", &six).unwrap();
        assert_eq!(f.signature.coords(), 12);
        for points in [
            "xs1, xs2, xs3, xm1, xm2",
            "xs1, xs2, xs3, xm1, xm2, xm3, xm4",
        ] {
            let bad = six.replace("xs1, xs2, xs3, xm1, xm2, xm3;", &format!("{points};"));
            let e = Formulation::parse("bad", &bad).unwrap_err().to_string();
            assert!(e.contains("four points") && e.contains("six"), "{e}");
        }
    }

    #[test]
    fn errors_name_line_and_problem() {
        let bad = SN.replace("norm(t_s)", "nrm(t_s)");
        let e = Formulation::parse("sn", &bad).unwrap_err().to_string();
        assert!(
            e.contains("sn.rs:7:") && e.contains("unknown function `nrm`"),
            "{e}"
        );
        let bad = SN.replace("- x_s, t_s)", "- x_s, t_z)");
        let e = Formulation::parse("sn", &bad).unwrap_err().to_string();
        assert!(e.contains("unknown name") && e.contains("t_z"), "{e}");
        let bad = SN.replace("dot(n, x_ms)", "n");
        let f = Formulation::parse("sn", &bad).unwrap();
        let mut dag = f.dag.clone();
        let env: HashMap<String, Value<Id>> = f
            .entities
            .iter()
            .map(|e| (e.name.clone(), e.value))
            .collect();
        assert!(
            f.eval_gap(&mut dag, &env)
                .unwrap_err()
                .to_string()
                .contains("scalar")
        );
    }
}
