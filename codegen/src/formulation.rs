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
//! * `inputs!(dim 3; xs1, xs2, xs3; xm1, xm2, xm3, xm4; xi_s: 2)` declares
//!   3D faces: the slave face's points (3: tri3, 4: quad4), then the
//!   master face's, each a 3-vector, and the slave point `xi_s = (u, v)`, a
//!   2-vector parameter (`name: 2`).
//! * `implicit!(xi: 2 => [r1, r2])` defines a 2-vector `xi = (u, v)` as the
//!   root of two residuals (a face's projection; `xi.x`, `xi.y` are `u`,
//!   `v`); its derivatives come from implicit differentiation with the 2 x 2
//!   Jacobian (`crate::truncation`), closed form when both residuals are
//!   affine in `xi`.
//! * `implicit!(xi => r)` defines a scalar as the root of `r(q, xi) = 0`;
//!   the generator never solves it in closed form: its derivatives come from
//!   implicit differentiation and its value from a Newton solve at run time.
//! * `entity!(e)` marks a value whose dependence on `q` the approximation
//!   types truncate (see [`crate::truncation`]). The implicit variable is an
//!   entity too.
//! * `gap!(e)` gives the gap as an expression of entities only.
//! * Faces: `vec3(x, y, z)`, `cross(a, b)`, `v.z`; `dot` and `norm` take
//!   3-vectors too; `tri3_point(x1, x2, x3, xi)` (`N = (1 - u - v, u, v)`),
//!   `tri3_du(x1, x2, x3)`, `tri3_dv(x1, x2, x3)` (its tangents `dx/du`,
//!   `dx/dv`), `quad4_point(x1, x2, x3, x4, xi)` (bilinear on [-1, 1]^2,
//!   `N_a = (1 + u u_a)(1 + v v_a) / 4`, nodes at (-1,-1), (1,-1), (1,1),
//!   (-1,1)), `quad4_du(.., xi)`, `quad4_dv(.., xi)`; `xi` is a 2-vector.
//! * Values are scalars, 2-vectors or 3-vectors. Operators: `+ - * /` (vector ± vector,
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
    /// A 3-vector (points and vectors of 3D faces).
    Vec3([S; 3]),
}

impl<S: Copy> Value<S> {
    /// The scalar components (one, two or three).
    pub fn components(&self) -> Vec<S> {
        match *self {
            Value::Scalar(s) => vec![s],
            Value::Vec2([a, b]) => vec![a, b],
            Value::Vec3([a, b, c]) => vec![a, b, c],
        }
    }

    /// The value of the same kind as `self` with components `c` (as many
    /// as `self` has).
    pub fn like<T: Copy>(&self, c: &[T]) -> Value<T> {
        match self {
            Value::Scalar(_) => Value::Scalar(c[0]),
            Value::Vec2(_) => Value::Vec2([c[0], c[1]]),
            Value::Vec3(_) => Value::Vec3([c[0], c[1], c[2]]),
        }
    }

    /// The vector of components `c` (one: a scalar).
    pub fn from_components(c: &[S]) -> Value<S> {
        match *c {
            [a] => Value::Scalar(a),
            [a, b] => Value::Vec2([a, b]),
            [a, b, c] => Value::Vec3([a, b, c]),
            _ => panic!("values have one to three components, not {}", c.len()),
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
    /// The symbol standing for its value (a vector unknown: its first
    /// component).
    pub sym: Sym,
    /// The residual `r(q, xi)` (a vector unknown: the first residual).
    pub residual: Id,
    /// Every component's symbol and residual `(xi_c, r_c)`: one for a
    /// scalar unknown (`(sym, residual)`), two for `implicit!(xi: 2 => ..)`.
    pub components: Vec<(Sym, Id)>,
}

impl Implicit {
    /// The unknown's component count (1 or 2).
    pub fn dim(&self) -> usize {
        self.components.len()
    }

    /// Whether the unknown is a vector (`implicit!(xi: 2 => ..)`).
    pub fn is_vector(&self) -> bool {
        self.components.len() > 1
    }

    /// The unknown as a value of the language (a scalar or a 2-vector of
    /// its symbols' inputs in `dag`).
    pub fn value(&self, dag: &mut Dag) -> Value<Id> {
        let c: Vec<Id> = self.components.iter().map(|(s, _)| dag.input(*s)).collect();
        Value::from_components(&c)
    }
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
                            let residuals = b.implicit(&m.mac.tokens, m.span())?;
                            let syms = b.implicit_syms();
                            let components: Vec<(Sym, Id)> =
                                syms.into_iter().zip(residuals).collect();
                            let imp = Implicit {
                                name: name.clone(),
                                sym: components[0].0,
                                residual: components[0].1,
                                components,
                            };
                            let v = imp.value(&mut b.dag);
                            implicit = Some(imp);
                            v
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
            Value::Vec2(_) | Value::Vec3(_) => {
                Err(err(self.gap.span(), &origin, "the gap must be a scalar"))
            }
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
    /// The implicit unknown's symbols (after `inputs!`, which `let`
    /// statements require, and `implicit!`, which sets their count).
    fn implicit_syms(&self) -> Vec<Sym> {
        self.signature
            .as_ref()
            .expect("`inputs!` precedes every `let`")
            .implicit_syms()
    }

    fn declare_inputs(&mut self, tokens: &TokenStream, span: Span) -> Result<(), Error> {
        let text = tokens.to_string();
        // `dim 3; points; params` (3D faces) or `points; params` (2D).
        let (dim, text) = match text.trim_start().strip_prefix("dim ") {
            Some(rest) => {
                let (d, rest) = rest.split_once(';').unwrap_or((rest, ""));
                match d.trim() {
                    "2" => (2, rest.to_owned()),
                    "3" => (3, rest.to_owned()),
                    other => {
                        return Err(err(
                            span,
                            &self.origin,
                            format!("`dim {other}`: the dimension is 2 or 3"),
                        ));
                    }
                }
            }
            None => (2, text),
        };
        let (points, params) = text.split_once(';').ok_or_else(|| {
            err(
                span,
                &self.origin,
                "expected `inputs!(p1, p2, p3, p4; xi_s)`",
            )
        })?;
        // Faces: `slave points; master points; params`.
        let (points, slave_points, params) = if dim == 3 {
            let (master, params) = params.split_once(';').ok_or_else(|| {
                err(
                    span,
                    &self.origin,
                    "expected `inputs!(dim 3; slave points; master points; xi_s: 2)`",
                )
            })?;
            let slave = points.split(',').count();
            (format!("{points}, {master}"), slave, params)
        } else {
            (points.to_owned(), 0, params)
        };
        let points: Vec<&str> = points.split(',').map(str::trim).collect();
        let slave_points = if dim == 3 {
            slave_points
        } else {
            points.len() / 2
        };
        // A parameter is `name` (a scalar) or `name: 2` (a 2-vector).
        let declared = params;
        let mut params: Vec<(&str, usize)> = Vec::new();
        for p in declared.split(',').map(str::trim).filter(|s| !s.is_empty()) {
            let (name, len) = match p.split_once(':') {
                None => (p, 1),
                Some((name, len)) => match len.trim() {
                    "1" => (name.trim(), 1),
                    "2" => (name.trim(), 2),
                    other => {
                        return Err(err(
                            span,
                            &self.origin,
                            format!(
                                "parameter `{}: {other}`: a parameter has 1 or 2 components",
                                name.trim()
                            ),
                        ));
                    }
                },
            };
            params.push((name, len));
        }
        let fits = match self.arity {
            Arity::SegmentPair if dim == 2 => {
                matches!(points.len(), 4 | 6) && matches!(params.as_slice(), [(_, 1)])
            }
            // Faces: slave tri3 (3 points) or quad4 (4), then the master's.
            Arity::SegmentPair => {
                matches!(slave_points, 3 | 4)
                    && matches!(points.len() - slave_points, 3 | 4)
                    && matches!(params.as_slice(), [(_, 2)])
            }
            Arity::Any => !points.is_empty() && points.iter().all(|p| !p.is_empty()),
        };
        if !fits {
            let expected = match self.arity {
                Arity::SegmentPair if dim == 3 => {
                    "a slave and a master face of 3 (tri3) or 4 (quad4) points each and the \
                     slave point `xi_s: 2`: `inputs!(dim 3; xs1, xs2, xs3; xm1, xm2, xm3; xi_s: 2)`"
                }
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
        let sig = Signature::with_param_lens(
            dim,
            points.iter().map(|p| (*p).to_owned()).collect(),
            slave_points,
            params.iter().map(|(p, _)| (*p).to_owned()).collect(),
            params.iter().map(|(_, len)| *len).collect(),
        );
        for (i, p) in points.iter().enumerate() {
            let c: Vec<Id> = (0..dim)
                .map(|k| self.dag.input(sig.coord_sym(dim * i + k)))
                .collect();
            self.bind(p, Value::from_components(&c), span)?;
        }
        for (i, (p, len)) in params.iter().enumerate() {
            let first = sig.param_offset(i);
            let c: Vec<Id> = (0..*len)
                .map(|k| self.dag.input(sig.param_sym(first + k)))
                .collect();
            self.bind(p, Value::from_components(&c), span)?;
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

    /// `implicit!(xi => r)` (a scalar unknown, one residual) or
    /// `implicit!(xi: 2 => [r1, r2])` (a 2-vector unknown `(u, v)`, two
    /// residuals); returns the residuals.
    fn implicit(&mut self, tokens: &TokenStream, span: Span) -> Result<Vec<Id>, Error> {
        let closure = syn::parse2::<ImplicitDef>(tokens.clone())
            .map_err(|e| err(e.span(), &self.origin, e.to_string()))?;
        let var = closure.var.to_string();
        let sig = self
            .signature
            .as_mut()
            .expect("`inputs!` precedes every `let`");
        sig.set_implicit_len(closure.len);
        let syms = sig.implicit_syms();
        let c: Vec<Id> = syms.iter().map(|s| self.dag.input(*s)).collect();
        let previous = self.env.insert(var.clone(), Value::from_components(&c));
        let r: Result<Vec<Value<Id>>, Error> = match (&closure.residual, closure.len) {
            (syn::Expr::Array(a), 2) if a.elems.len() == 2 => {
                a.elems.iter().map(|e| self.eval(e)).collect()
            }
            (e, 1) => self.eval(e).map(|v| vec![v]),
            (e, _) => Err(err(
                e.span(),
                &self.origin,
                "a 2-vector unknown needs two residuals: `implicit!(xi: 2 => [r1, r2])`",
            )),
        };
        match previous {
            Some(p) => self.env.insert(var.clone(), p),
            None => self.env.remove(&var),
        };
        let residuals: Vec<Id> = r?
            .into_iter()
            .map(|v| match v {
                Value::Scalar(r) => Ok(r),
                _ => Err(err(
                    span,
                    &self.origin,
                    "each implicit residual must be a scalar",
                )),
            })
            .collect::<Result<_, _>>()?;
        // Every residual must change with the unknown, and every component
        // of the unknown must enter some residual: otherwise the Jacobian
        // is singular everywhere and there is no projection to solve for.
        let reached = self.dag.reachable(residuals.iter().copied());
        let independent = residuals
            .iter()
            .any(|&r| !c.iter().any(|x| self.dag.reachable([r])[x.index()]));
        if independent || c.iter().any(|x| !reached[x.index()]) {
            return Err(err(
                closure.residual.span(),
                &self.origin,
                format!(
                    "the projection residual does not depend on `{var}`: `{var} => r` needs an \
                     r that changes with `{var}` (its zero is the projection)"
                ),
            ));
        }
        Ok(residuals)
    }

    fn eval(&mut self, e: &syn::Expr) -> Result<Value<Id>, Error> {
        eval_expr(&mut self.dag, &self.env, e, &self.origin, "unknown name")
    }
}

/// `xi => residual` or `xi: 2 => [r1, r2]`
struct ImplicitDef {
    var: syn::Ident,
    len: usize,
    residual: syn::Expr,
}

impl syn::parse::Parse for ImplicitDef {
    fn parse(input: syn::parse::ParseStream) -> syn::Result<Self> {
        let var = input.parse()?;
        let mut len = 1;
        if input.peek(syn::Token![:]) {
            input.parse::<syn::Token![:]>()?;
            let lit: syn::LitInt = input.parse()?;
            len = lit.base10_parse::<usize>()?;
            if !(1..=2).contains(&len) {
                return Err(syn::Error::new(
                    lit.span(),
                    "an implicit unknown has 1 or 2 components",
                ));
            }
        }
        input.parse::<syn::Token![=>]>()?;
        let residual = input.parse()?;
        Ok(ImplicitDef { var, len, residual })
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
    use Value::{Scalar, Vec2, Vec3};
    let ev = |d: &mut D, e: &syn::Expr| eval_expr(d, env, e, origin, unknown);
    let same_kind =
        |a: &Value<D::S>, b: &Value<D::S>| std::mem::discriminant(a) == std::mem::discriminant(b);
    // Component by component: `f(a_i, b_i)` (values of one kind).
    let zip = |d: &mut D, a: Value<D::S>, b: Value<D::S>, f: fn(&mut D, D::S, D::S) -> D::S| {
        let (a, b) = (a.components(), b.components());
        let c: Vec<D::S> = a.iter().zip(&b).map(|(x, y)| f(d, *x, *y)).collect();
        Value::from_components(&c)
    };
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
            syn::UnOp::Neg(_) => {
                let v = ev(d, &u.expr)?;
                let c: Vec<D::S> = v.components().into_iter().map(|a| d.neg(a)).collect();
                Ok(v.like(&c))
            }
            _ => Err(err(u.span(), origin, "only unary `-` is supported")),
        },
        syn::Expr::Field(f) => {
            let v = ev(d, &f.base)?;
            let syn::Member::Named(m) = &f.member else {
                return Err(err(f.span(), origin, "use `.x` or `.y`"));
            };
            match (v, m.to_string().as_str()) {
                (Vec2([x, _]) | Vec3([x, _, _]), "x") => Ok(Scalar(x)),
                (Vec2([_, y]) | Vec3([_, y, _]), "y") => Ok(Scalar(y)),
                (Vec3([_, _, z]), "z") => Ok(Scalar(z)),
                (Vec2(_), other) => Err(err(
                    m.span(),
                    origin,
                    format!("no component `{other}` (use `.x` or `.y`)"),
                )),
                (Vec3(_), other) => Err(err(
                    m.span(),
                    origin,
                    format!("no component `{other}` (use `.x`, `.y` or `.z`)"),
                )),
                (Scalar(_), _) => Err(err(f.span(), origin, "a scalar has no components")),
            }
        }
        syn::Expr::Binary(b) => {
            let (l, r) = (ev(d, &b.left)?, ev(d, &b.right)?);
            let bad = |what: &str| err(b.span(), origin, format!("cannot {what}"));
            match (&b.op, l, r) {
                (syn::BinOp::Add(_), l, r) if same_kind(&l, &r) => Ok(zip(d, l, r, D::add)),
                (syn::BinOp::Sub(_), l, r) if same_kind(&l, &r) => Ok(zip(d, l, r, D::sub)),
                (syn::BinOp::Add(_) | syn::BinOp::Sub(_), Scalar(_), _)
                | (syn::BinOp::Add(_) | syn::BinOp::Sub(_), _, Scalar(_)) => {
                    Err(bad("add or subtract a scalar and a vector"))
                }
                (syn::BinOp::Add(_) | syn::BinOp::Sub(_), _, _) => {
                    Err(bad("add or subtract vectors of different sizes"))
                }
                (syn::BinOp::Mul(_), Scalar(a), Scalar(c)) => Ok(Scalar(d.mul(a, c))),
                (syn::BinOp::Mul(_), Scalar(s), v) | (syn::BinOp::Mul(_), v, Scalar(s)) => {
                    let c: Vec<D::S> = v.components().into_iter().map(|a| d.mul(s, a)).collect();
                    Ok(v.like(&c))
                }
                (syn::BinOp::Mul(_), _, _) => Err(bad("multiply two vectors (use `dot`)")),
                (syn::BinOp::Div(_), Scalar(a), Scalar(c)) => Ok(Scalar(d.div(a, c))),
                (syn::BinOp::Div(_), v, Scalar(s)) => {
                    let c: Vec<D::S> = v.components().into_iter().map(|a| d.div(a, s)).collect();
                    Ok(v.like(&c))
                }
                (syn::BinOp::Div(_), _, _) => Err(bad("divide by a vector")),
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
                        (Vec3([ax, ay, az]), Vec3([bx, by, bz])) => {
                            Ok(Vec3([comb(d, ax, bx), comb(d, ay, by), comb(d, az, bz)]))
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
                        (Vec3(a), Vec3(b)) => {
                            let u = d.mul(a[0], b[0]);
                            let v = d.mul(a[1], b[1]);
                            let w = d.mul(a[2], b[2]);
                            let uv = d.add(u, v);
                            Ok(Scalar(d.add(uv, w)))
                        }
                        _ => Err(type_err("two vectors of one size")),
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
                        Vec3([x, y, z]) => {
                            let u = d.mul(x, x);
                            let v = d.mul(y, y);
                            let w = d.mul(z, z);
                            let uv = d.add(u, v);
                            let s = d.add(uv, w);
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
                "vec3" => {
                    arity(3)?;
                    match (ev(d, args[0])?, ev(d, args[1])?, ev(d, args[2])?) {
                        (Scalar(x), Scalar(y), Scalar(z)) => Ok(Vec3([x, y, z])),
                        _ => Err(type_err("three scalars")),
                    }
                }
                "cross" => {
                    arity(2)?;
                    match (ev(d, args[0])?, ev(d, args[1])?) {
                        (Vec3(a), Vec3(b)) => {
                            let mut c = [a[0]; 3];
                            for (i, ci) in c.iter_mut().enumerate() {
                                let (j, k) = ((i + 1) % 3, (i + 2) % 3);
                                let p = d.mul(a[j], b[k]);
                                let m = d.mul(a[k], b[j]);
                                *ci = d.sub(p, m);
                            }
                            Ok(Vec3(c))
                        }
                        _ => Err(type_err("two 3-vectors")),
                    }
                }
                "tri3_point" | "tri3_du" | "tri3_dv" | "quad4_point" | "quad4_du" | "quad4_dv" => {
                    let quad = fname.starts_with("quad4");
                    let nodes = if quad { 4 } else { 3 };
                    // tri3_du and tri3_dv are constant: no parameter.
                    let takes_xi = quad || fname == "tri3_point";
                    arity(nodes + usize::from(takes_xi))?;
                    let mut pts = Vec::with_capacity(nodes);
                    for a in &args[..nodes] {
                        match ev(d, a)? {
                            Vec3(p) => pts.push(p),
                            _ => return Err(type_err("3-vector nodes")),
                        }
                    }
                    let xi = if takes_xi {
                        match ev(d, args[nodes])? {
                            Vec2(xi) => Some(xi),
                            _ => return Err(type_err("a 2-vector `(u, v)` last")),
                        }
                    } else {
                        None
                    };
                    let w = face_weights(d, &fname, xi);
                    let mut out = [pts[0][0]; 3];
                    for (k, o) in out.iter_mut().enumerate() {
                        let mut acc: Option<D::S> = None;
                        for (p, w) in pts.iter().zip(&w) {
                            let t = match w {
                                Weight::One => p[k],
                                Weight::MinusOne => d.neg(p[k]),
                                Weight::Of(w) => d.mul(*w, p[k]),
                            };
                            acc = Some(match acc {
                                None => t,
                                Some(a) => d.add(a, t),
                            });
                        }
                        *o = acc.expect("a face has nodes");
                    }
                    Ok(Vec3(out))
                }
                other => Err(err(
                    fp.span(),
                    origin,
                    format!(
                        "unknown function `{other}` (known: lerp, dot, perp, norm, sqrt, powi, vec2, \
                         vec3, cross, tri3_point, tri3_du, tri3_dv, quad4_point, quad4_du, quad4_dv)"
                    ),
                )),
            }
        }
        syn::Expr::Macro(m) => Err(misplaced_macro(&m.mac, origin)),
        other => Err(err(other.span(), origin, "unsupported expression")),
    }
}

/// A shape-function weight: exactly one, minus one, or an expression.
enum Weight<S> {
    One,
    MinusOne,
    Of(S),
}

/// The weights of a face's nodes in `name` (`tri3_point`, `tri3_du`,
/// `tri3_dv`, `quad4_point`, `quad4_du`, `quad4_dv`) at `xi = (u, v)`:
/// tri3 `N = (1 - u - v, u, v)`, `dx/du = x2 - x1`, `dx/dv = x3 - x1`;
/// quad4 `N_a = (1 + u u_a)(1 + v v_a) / 4` with nodes at (-1,-1), (1,-1),
/// (1,1), (-1,1), and its `u` and `v` derivatives.
fn face_weights<D: Domain>(d: &mut D, name: &str, xi: Option<[D::S; 2]>) -> Vec<Weight<D::S>> {
    use Weight::{MinusOne, Of, One};
    match (name, xi) {
        ("tri3_du", _) => vec![MinusOne, One, Of(d.constant(0.0))],
        ("tri3_dv", _) => vec![MinusOne, Of(d.constant(0.0)), One],
        ("tri3_point", Some([u, v])) => {
            let one = d.constant(1.0);
            let a = d.sub(one, u);
            vec![Of(d.sub(a, v)), Of(u), Of(v)]
        }
        (_, Some([u, v])) => {
            let (one, quarter) = (d.constant(1.0), d.constant(0.25));
            let um = d.sub(one, u);
            let up = d.add(one, u);
            let vm = d.sub(one, v);
            let vp = d.add(one, v);
            // (1 + u u_a) and (1 + v v_a) per node, scaled by 1/4.
            let nodes = [(um, vm), (up, vm), (up, vp), (um, vp)];
            let signs = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
            nodes
                .iter()
                .zip(signs)
                .map(|(&(fu, fv), (su, sv))| {
                    let w = match name {
                        "quad4_point" => {
                            let p = d.mul(fu, fv);
                            d.mul(quarter, p)
                        }
                        "quad4_du" => {
                            let c = d.constant(0.25 * su);
                            d.mul(c, fv)
                        }
                        _ => {
                            let c = d.constant(0.25 * sv);
                            d.mul(c, fu)
                        }
                    };
                    Of(w)
                })
                .collect()
        }
        _ => unreachable!("every face function with a parameter has one"),
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
