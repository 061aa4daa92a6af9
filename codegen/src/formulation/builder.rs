//! The state of one parse ([`Builder`]): the DAG under construction and the
//! names bound so far; `inputs!` (the points and parameters, checked
//! against the [`Arity`], into the [`Signature`] and bound names) and
//! `implicit!` (the unknown's symbols and its residuals, which must depend
//! on it).

use std::collections::HashMap;

use proc_macro2::{Span, TokenStream};
use syn::spanned::Spanned;

use super::eval::eval_expr;
use super::{Arity, Value, err};
use crate::Error;
use crate::expr::{Dag, Id, Sym};
use crate::signature::Signature;

pub(super) struct Builder {
    pub(super) origin: String,
    pub(super) dag: Dag,
    pub(super) env: HashMap<String, Value<Id>>,
    pub(super) arity: Arity,
    /// Set by `inputs!` (the implicit unknown's name is filled in last).
    pub(super) signature: Option<Signature>,
}

impl Builder {
    /// The implicit unknown's symbols (after `inputs!`, which `let`
    /// statements require, and `implicit!`, which sets their count).
    pub(super) fn implicit_syms(&self) -> Vec<Sym> {
        self.signature
            .as_ref()
            .expect("`inputs!` precedes every `let`")
            .implicit_syms()
    }

    pub(super) fn declare_inputs(&mut self, tokens: &TokenStream, span: Span) -> Result<(), Error> {
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
    pub(super) fn implicit(&mut self, tokens: &TokenStream, span: Span) -> Result<Vec<Id>, Error> {
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

    /// `previous!(xi_m)`: the last converged value of the implicit unknown
    /// `implicit` (already defined, and named by the argument), as new
    /// input symbols after the unknown's ([`Signature::previous_syms`]).
    pub(super) fn previous(
        &mut self,
        tokens: &TokenStream,
        span: Span,
        implicit: Option<&str>,
    ) -> Result<Value<Id>, Error> {
        let named = syn::parse2::<syn::Ident>(tokens.clone())
            .map_err(|e| err(e.span(), &self.origin, e.to_string()))?
            .to_string();
        let Some(implicit) = implicit else {
            return Err(err(
                span,
                &self.origin,
                "`previous!` needs the projection first: `let xi_m = implicit!(..)`",
            ));
        };
        if named != implicit {
            return Err(err(
                span,
                &self.origin,
                format!(
                    "`previous!({named})`: only the projection `{implicit}` has a previous value"
                ),
            ));
        }
        let sig = self
            .signature
            .as_mut()
            .expect("`inputs!` precedes every `let`");
        if sig.has_previous() {
            return Err(err(span, &self.origin, "`previous!` given twice"));
        }
        sig.set_previous();
        let c: Vec<Id> = sig
            .previous_syms()
            .into_iter()
            .map(|s| self.dag.input(s))
            .collect();
        Ok(Value::from_components(&c))
    }

    pub(super) fn eval(&mut self, e: &syn::Expr) -> Result<Value<Id>, Error> {
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
