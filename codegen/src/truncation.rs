//! The truncation policy: which derivative chains each approximation type
//! keeps, applied exactly as the design states.
//!
//! Each entity `E` (the projection coordinate `xi_m`, the gap vector `x_ms`,
//! the unit normal `n`) is held [`EntityOrder::Constant`] (`E' = E'' = 0`),
//! [`EntityOrder::Linear`] (`E'' = 0`) or [`EntityOrder::Quadratic`] in `q`.
//! The projection coordinate's derivatives come from implicit
//! differentiation of `r(q, xi(q)) = 0`:
//!
//! ```text
//! xi'  = -r_q / r_xi
//! xi'' = -(r_qq + r_qxi xi'^T + xi' r_qxi^T + r_xixi xi' xi'^T) / r_xi
//! ```
//!
//! For the other entities, written as `E(q, xi)` with partial derivatives at
//! fixed `xi` (per component), the kept total derivatives are
//!
//! ```text
//! E'  = E_q + [xi not constant] E_xi xi'
//! E'' = E_qq + [xi not constant] (E_qxi xi'^T + xi' E_xiq + E_xixi xi' xi'^T)
//!            + [xi quadratic]     E_xi xi''
//! ```
//!
//! and the entity's own row then zeroes `E'` and/or `E''`. The gap is the
//! formulation's expression of the entities, differentiated as a truncated
//! second-order jet (for `g = n . x`: `g' = n'^T x + x'^T n`,
//! `g'' = sum_i (x_i n_i'' + n_i' x_i'^T + x_i' n_i'^T + n_i x_i'')`).
//!
//! The six types are the six rows of [`TYPES`].

use std::collections::HashMap;

use crate::diff::{add_opt, mul_opt, neg_opt, sub_opt, sum_opt, Differentiator};
use crate::expr::{Dag, Id};
use crate::formulation::{Domain, Formulation, Value};
use crate::Error;

/// How an entity depends on the displacements within a load step.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum EntityOrder {
    /// `E' = 0`, `E'' = 0`.
    Constant,
    /// `E'' = 0`.
    Linear,
    /// Full first and second derivatives.
    Quadratic,
}

impl EntityOrder {
    /// The variant's name (as written in generated code).
    pub fn name(self) -> &'static str {
        match self {
            EntityOrder::Constant => "Constant",
            EntityOrder::Linear => "Linear",
            EntityOrder::Quadratic => "Quadratic",
        }
    }
}

/// The entity names the truncation table refers to, in column order.
pub const ENTITY_NAMES: [&str; 3] = ["xi_m", "x_ms", "n"];

/// The truncation table: row `t - 1` gives type `t`'s order for
/// `[xi_m, x_ms, n]`.
pub const TYPES: [[EntityOrder; 3]; 6] = {
    use EntityOrder::{Constant as C, Linear as L, Quadratic as Q};
    [[C, L, C], [L, L, L], [L, Q, L], [Q, Q, L], [L, Q, Q], [Q, Q, Q]]
};

/// Number of coordinates.
pub const N: usize = 8;
/// Entries of the packed upper triangle of an `N x N` symmetric matrix.
pub const NH: usize = N * (N + 1) / 2;

/// Index of `(j, k)`, `j <= k`, in the packed upper triangle (row-major).
pub fn packed(j: usize, k: usize) -> usize {
    debug_assert!(j <= k && k < N);
    j * N - j * (j + 1) / 2 + k
}

/// A scalar with its (truncated) gradient and packed upper Hessian with
/// respect to `q`; `None` entries are structural zeros.
#[derive(Debug, Clone, Copy)]
pub struct Jet {
    /// The value.
    pub v: Id,
    /// First derivatives.
    pub g: [Option<Id>; N],
    /// Second derivatives, packed upper triangle.
    pub h: [Option<Id>; NH],
}

/// Jet arithmetic over a DAG (the second-order chain rule).
struct JetDomain<'a> {
    dag: &'a mut Dag,
}

impl JetDomain<'_> {
    fn constant_jet(&mut self, v: Id) -> Jet {
        Jet { v, g: [None; N], h: [None; NH] }
    }

    /// `f(a)` given `f(a.v)`, `f'(a.v)`, `f''(a.v)`:
    /// `(f o a)' = f' a'`, `(f o a)'' = f'' a' a'^T + f' a''`.
    fn chain(&mut self, a: &Jet, f0: Id, f1: Id, f2: Option<Id>) -> Jet {
        let dag = &mut *self.dag;
        let g = a.g.map(|gj| mul_opt(dag, Some(f1), gj));
        let mut h = [None; NH];
        for j in 0..N {
            for k in j..N {
                let p = mul_opt(dag, a.g[j], a.g[k]);
                let t1 = mul_opt(dag, f2, p);
                let t2 = mul_opt(dag, Some(f1), a.h[packed(j, k)]);
                h[packed(j, k)] = add_opt(dag, t1, t2);
            }
        }
        Jet { v: f0, g, h }
    }
}

impl Domain for JetDomain<'_> {
    type S = Jet;
    fn constant(&mut self, c: f64) -> Jet {
        let v = self.dag.constant(c);
        self.constant_jet(v)
    }
    fn add(&mut self, a: Jet, b: Jet) -> Jet {
        let dag = &mut *self.dag;
        Jet {
            v: dag.add(a.v, b.v),
            g: std::array::from_fn(|j| add_opt(dag, a.g[j], b.g[j])),
            h: std::array::from_fn(|k| add_opt(dag, a.h[k], b.h[k])),
        }
    }
    fn sub(&mut self, a: Jet, b: Jet) -> Jet {
        let dag = &mut *self.dag;
        Jet {
            v: dag.sub(a.v, b.v),
            g: std::array::from_fn(|j| sub_opt(dag, a.g[j], b.g[j])),
            h: std::array::from_fn(|k| sub_opt(dag, a.h[k], b.h[k])),
        }
    }
    fn mul(&mut self, a: Jet, b: Jet) -> Jet {
        let dag = &mut *self.dag;
        let v = dag.mul(a.v, b.v);
        let g = std::array::from_fn(|j| {
            let t1 = mul_opt(dag, a.g[j], Some(b.v));
            let t2 = mul_opt(dag, Some(a.v), b.g[j]);
            add_opt(dag, t1, t2)
        });
        let mut h = [None; NH];
        for j in 0..N {
            for k in j..N {
                let p = packed(j, k);
                let t = [
                    mul_opt(dag, a.h[p], Some(b.v)),
                    mul_opt(dag, a.g[j], b.g[k]),
                    mul_opt(dag, b.g[j], a.g[k]),
                    mul_opt(dag, Some(a.v), b.h[p]),
                ];
                h[p] = sum_opt(dag, t);
            }
        }
        Jet { v, g, h }
    }
    fn div(&mut self, a: Jet, b: Jet) -> Jet {
        // a / b = a * (1/b); (1/b)' = -b'/b^2, (1/b)'' = 2 b' b'^T / b^3 - b''/b^2.
        let dag = &mut *self.dag;
        let r = dag.recip(b.v);
        let r2 = dag.powi(r, 2);
        let f1 = dag.neg(r2);
        let r3 = dag.powi(r, 3);
        let two = dag.constant(2.0);
        let f2 = dag.mul(two, r3);
        let rb = self.chain(&b, r, f1, Some(f2));
        self.mul(a, rb)
    }
    fn neg(&mut self, a: Jet) -> Jet {
        let dag = &mut *self.dag;
        Jet { v: dag.neg(a.v), g: a.g.map(|x| neg_opt(dag, x)), h: a.h.map(|x| neg_opt(dag, x)) }
    }
    fn sqrt(&mut self, a: Jet) -> Jet {
        // sqrt' = 1/(2 s), sqrt'' = -1/(4 s^3).
        let dag = &mut *self.dag;
        let s = dag.sqrt(a.v);
        let r = dag.recip(s);
        let half = dag.constant(0.5);
        let f1 = dag.mul(half, r);
        let r3 = dag.powi(r, 3);
        let q = dag.constant(-0.25);
        let f2 = dag.mul(q, r3);
        self.chain(&a, s, f1, Some(f2))
    }
    fn powi(&mut self, a: Jet, n: i32) -> Jet {
        let dag = &mut *self.dag;
        let f0 = dag.powi(a.v, n);
        let p1 = dag.powi(a.v, n - 1);
        let c1 = dag.constant(f64::from(n));
        let f1 = dag.mul(c1, p1);
        let p2 = dag.powi(a.v, n - 2);
        let c2 = dag.constant(f64::from(n * (n - 1)));
        let f2 = dag.mul(c2, p2);
        let f2 = crate::diff::nonzero(dag, f2);
        self.chain(&a, f0, f1, f2)
    }
}

/// The expressions of one kernel: the gap, its kept gradient and packed
/// upper Hessian (all `None` for a type without second-order term).
#[derive(Debug, Clone)]
pub struct KernelExprs {
    /// The gap value.
    pub gap: Id,
    /// Kept first derivatives.
    pub grad: [Option<Id>; N],
    /// Kept second derivatives (packed upper triangle).
    pub hess: [Option<Id>; NH],
}

impl KernelExprs {
    /// Whether any second derivative survives.
    pub fn has_hessian(&self) -> bool {
        self.hess.iter().any(Option::is_some)
    }
}

/// Builds the kernel expressions of `formulation` under the truncation row
/// `orders` (for `[xi_m, x_ms, n]`, see [`TYPES`]), adding nodes to `dag`
/// (which must be the formulation's DAG or a clone of it).
pub fn derive(formulation: &Formulation, dag: &mut Dag, orders: [EntityOrder; 3]) -> Result<KernelExprs, Error> {
    let origin = format!("{}.rs", formulation.name);
    let order_of = |name: &str| -> Result<EntityOrder, Error> {
        ENTITY_NAMES.iter().position(|n| *n == name).map(|i| orders[i]).ok_or_else(|| Error::Truncation {
            file: origin.clone(),
            message: format!("entity `{name}` has no column in the truncation table (known: {})", ENTITY_NAMES.join(", ")),
        })
    };
    let mut declared: Vec<&str> = formulation.entities.iter().map(|e| e.name.as_str()).collect();
    declared.push(&formulation.implicit.name);
    for name in ENTITY_NAMES {
        if !declared.contains(&name) {
            return Err(Error::Truncation { file: origin.clone(), message: format!("the formulation does not define entity `{name}`") });
        }
    }

    let q = formulation.coords;
    let xi = formulation.implicit.sym;
    let mut diff = Differentiator::new();
    let xi_order = order_of(&formulation.implicit.name)?;

    // Implicit derivatives of xi_m (only as far as the row needs them).
    let r = formulation.implicit.residual;
    let r_xi = diff.d(dag, r, xi).ok_or_else(|| Error::Truncation {
        file: origin.clone(),
        message: "the implicit residual does not depend on its variable".into(),
    })?;
    let inv_r_xi = dag.recip(r_xi);
    let mut xi_d1 = [None; N];
    let mut xi_d2 = [None; NH];
    if xi_order >= EntityOrder::Linear {
        for j in 0..N {
            let r_q = diff.d(dag, r, q[j]);
            let t = mul_opt(dag, r_q, Some(inv_r_xi));
            xi_d1[j] = neg_opt(dag, t);
        }
    }
    if xi_order == EntityOrder::Quadratic {
        let r_qxi: Vec<Option<Id>> = (0..N).map(|j| diff.d(dag, r_xi, q[j])).collect();
        let r_xixi = diff.d(dag, r_xi, xi);
        for j in 0..N {
            let r_qj = diff.d(dag, r, q[j]);
            for k in j..N {
                let r_qq = diff.d_opt(dag, r_qj, q[k]);
                let t = [
                    r_qq,
                    mul_opt(dag, r_qxi[j], xi_d1[k]),
                    mul_opt(dag, xi_d1[j], r_qxi[k]),
                    {
                        let p = mul_opt(dag, xi_d1[j], xi_d1[k]);
                        mul_opt(dag, r_xixi, p)
                    },
                ];
                let s = sum_opt(dag, t);
                let s = mul_opt(dag, s, Some(inv_r_xi));
                xi_d2[packed(j, k)] = neg_opt(dag, s);
            }
        }
    }
    let xi_jet = Jet { v: dag.input(xi), g: xi_d1, h: xi_d2 };

    // Entity jets by the truncated chain rule.
    let mut jets: HashMap<String, Value<Jet>> = HashMap::new();
    jets.insert(formulation.implicit.name.clone(), Value::Scalar(xi_jet));
    for entity in &formulation.entities {
        let order = order_of(&entity.name)?;
        let mut comp = |e: Id| -> Jet {
            let mut g = [None; N];
            let mut h = [None; NH];
            if order >= EntityOrder::Linear {
                let e_xi = diff.d(dag, e, xi);
                for j in 0..N {
                    let e_q = diff.d(dag, e, q[j]);
                    let chain = mul_opt(dag, e_xi, xi_d1[j]);
                    g[j] = add_opt(dag, e_q, chain);
                }
                if order == EntityOrder::Quadratic {
                    let e_xixi = diff.d_opt(dag, e_xi, xi);
                    let e_qxi: Vec<Option<Id>> = (0..N).map(|j| diff.d_opt(dag, e_xi, q[j])).collect();
                    for j in 0..N {
                        let e_qj = diff.d(dag, e, q[j]);
                        for k in j..N {
                            let e_qq = diff.d_opt(dag, e_qj, q[k]);
                            let p = mul_opt(dag, xi_d1[j], xi_d1[k]);
                            let t = [
                                e_qq,
                                mul_opt(dag, e_qxi[j], xi_d1[k]),
                                mul_opt(dag, xi_d1[j], e_qxi[k]),
                                mul_opt(dag, e_xixi, p),
                                mul_opt(dag, e_xi, xi_d2[packed(j, k)]),
                            ];
                            h[packed(j, k)] = sum_opt(dag, t);
                        }
                    }
                }
            }
            Jet { v: e, g, h }
        };
        let v = match entity.value {
            Value::Scalar(s) => Value::Scalar(comp(s)),
            Value::Vec2([a, b]) => Value::Vec2([comp(a), comp(b)]),
        };
        jets.insert(entity.name.clone(), v);
    }

    let mut domain = JetDomain { dag };
    let gap = formulation.eval_gap(&mut domain, &jets)?;
    Ok(KernelExprs { gap: gap.v, grad: gap.g, hess: gap.h })
}

/// The value of the formulation's gap (no derivatives).
pub fn gap_value(formulation: &Formulation, dag: &mut Dag) -> Result<Id, Error> {
    let mut env: HashMap<String, Value<Id>> = formulation.entities.iter().map(|e| (e.name.clone(), e.value)).collect();
    let x = dag.input(formulation.implicit.sym);
    env.insert(formulation.implicit.name.clone(), Value::Scalar(x));
    formulation.eval_gap(dag, &env)
}

/// The projection residual and its derivative with respect to the implicit
/// variable: `[r, r_xi]`.
pub fn residual(formulation: &Formulation, dag: &mut Dag) -> [Id; 2] {
    let r = formulation.implicit.residual;
    let r_xi = Differentiator::new().d(dag, r, formulation.implicit.sym).unwrap_or_else(|| dag.constant(0.0));
    [r, r_xi]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn packed_index_is_a_bijection() {
        let mut seen = [false; NH];
        for j in 0..N {
            for k in j..N {
                assert!(!seen[packed(j, k)]);
                seen[packed(j, k)] = true;
            }
        }
        assert!(seen.iter().all(|&s| s));
    }
}
