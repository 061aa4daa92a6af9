//! The expression interpreter: a `syn` expression of the formulation
//! language evaluated over any [`Domain`] with the names bound so far
//! (operators, `.x`/`.y`/`.z`, the functions `lerp`, `dot`, `perp`, `norm`,
//! `sqrt`, `powi`, `vec2`, `vec3`, `cross` and the tri3/quad4
//! interpolation and tangents with their shape-function weights); a
//! constant folding to infinity or NaN is an error at its position.

use std::collections::HashMap;

use syn::spanned::Spanned;

use super::{Domain, Value, err, misplaced_macro};
use crate::Error;

/// Interprets `e` over `domain` with the names in `env`; an expression
/// whose constant folds to infinity or NaN (`1.0 / 0.0`, `sqrt(-1.0)`, an
/// overflow) is an error at its position.
pub(super) fn eval_expr<D: Domain>(
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
