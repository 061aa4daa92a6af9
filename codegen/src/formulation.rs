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
//!
//! This file holds the parsed formulation and the statement loop
//! ([`Formulation::parse_with`]); `value` the language's values and the
//! [`Domain`] they are computed in, `builder` the state of one parse
//! (`inputs!`, `implicit!`), `eval` the expression interpreter.

use std::collections::HashMap;

use proc_macro2::Span;
use syn::parse::Parser;
use syn::spanned::Spanned;

use crate::Error;
use crate::expr::{Dag, Id, Sym};
use crate::signature::Signature;

mod builder;
mod eval;
mod value;

use builder::Builder;
use eval::eval_expr;
pub use value::{Domain, Value};

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
    /// The slip expression (entities only; `slip!`), if the file defines
    /// one: a scalar (2D) or a 3-vector (3D).
    pub slip: Option<syn::Expr>,
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

/// A macro where none is expected, or an unknown one.
fn misplaced_macro(m: &syn::Macro, origin: &str) -> Error {
    let path = &m.path;
    let name = quote::quote!(#path).to_string().replace(' ', "");
    let msg = match name.as_str() {
        "implicit" | "entity" | "previous" => {
            format!("`{name}!` must be the whole value of a `let`")
        }
        "inputs" | "gap" | "slip" => format!("`{name}!(..);` is a statement of its own"),
        _ => format!(
            "unknown macro `{name}!` (known: inputs!, implicit!, previous!, entity!, gap!, slip!)"
        ),
    };
    err(m.span(), origin, msg)
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
        let mut slip: Option<syn::Expr> = None;
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
                syn::Stmt::Macro(m) if m.mac.path.is_ident("slip") => {
                    if slip.is_some() {
                        return Err(err(m.span(), &origin, "`slip!` given twice"));
                    }
                    let e: syn::Expr = syn::parse2(m.mac.tokens.clone())
                        .map_err(|e| err(e.span(), &origin, e.to_string()))?;
                    slip = Some(e);
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
                        syn::Expr::Macro(m) if m.mac.path.is_ident("previous") => b.previous(
                            &m.mac.tokens,
                            m.span(),
                            implicit.as_ref().map(|i| i.name.as_str()),
                        )?,
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
                        "expected `inputs!(..)`, `let name = ...;`, `gap!(..)` or `slip!(..)`",
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
            slip,
            lets,
        })
    }

    /// The entities a derivation of `quantity` needs: all of them for the
    /// slip, all but the slip's entity ([`crate::truncation::SLIP_ENTITY`])
    /// for the gap (which may not use it).
    pub fn entities_for(
        &self,
        quantity: crate::truncation::Quantity,
    ) -> impl Iterator<Item = &Entity> {
        self.entities.iter().filter(move |e| {
            quantity == crate::truncation::Quantity::Slip
                || e.name != crate::truncation::SLIP_ENTITY
        })
    }

    /// The slip's components (1 for a scalar, 3 for a 3-vector), 0 when
    /// the file has no `slip!`.
    pub fn slip_components(&self) -> usize {
        match self.slip {
            None => 0,
            Some(_) if self.signature.dim() == 2 => 1,
            Some(_) => 3,
        }
    }

    /// Interprets the slip expression in `domain` (as [`Formulation::eval_gap`]):
    /// its components, a scalar in 2D and a 3-vector in 3D. `Ok(vec![])`
    /// without `slip!`.
    pub fn eval_slip<D: Domain>(
        &self,
        domain: &mut D,
        entity_values: &HashMap<String, Value<D::S>>,
    ) -> Result<Vec<D::S>, Error> {
        let Some(slip) = &self.slip else {
            return Ok(Vec::new());
        };
        let origin = format!("{}.rs", self.name);
        let v = eval_expr(
            domain,
            entity_values,
            slip,
            &origin,
            "the slip may only use entities",
        )?;
        match (v, self.signature.dim()) {
            (Value::Scalar(s), 2) => Ok(vec![s]),
            (Value::Vec3(c), 3) => Ok(c.to_vec()),
            (_, 2) => Err(err(
                slip.span(),
                &origin,
                "a 2D slip must be a scalar (the component along the tangent)",
            )),
            _ => Err(err(
                slip.span(),
                &origin,
                "a 3D slip must be a 3-vector (its global components)",
            )),
        }
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
