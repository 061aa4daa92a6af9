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
//! second-order jet ([`crate::jet`], which keeps `xi'`, `xi''` and the
//! rank-2 chain terms unexpanded until the end) — for `g = n . x`:
//! `g' = n'^T x + x'^T n`,
//! `g'' = sum_i (x_i n_i'' + n_i' x_i'^T + x_i' n_i'^T + n_i x_i'')`).
//!
//! The six types are the six rows of [`TYPES`].
//!
//! A 2-vector unknown `xi = (u, v)` (3D faces, `implicit!(xi: 2 => [r1,
//! r2])`) follows the same rule with sums over its components
//! (`vector.rs`): with `A_ac = dr_a/dxi_c`,
//!
//! ```text
//! xi'    = -A^-1 r_q
//! xi_b'' = -sum_a (A^-1)_ba [ r_a,qq + sum_c (r_a,qxi_c xi_c'^T + xi_c' r_a,xi_cq)
//!                             + sum_cd r_a,xi_cxi_d xi_c' xi_d'^T ]
//! E'  = E_q + [xi not constant] sum_b E_xi_b xi_b'
//! E'' = E_qq + [xi not constant] sum_b (E_qxi_b xi_b'^T + xi_b' E_xi_bq
//!                                       + sum_c E_xi_bxi_c xi_b' xi_c'^T)
//!            + [xi quadratic] sum_b E_xi_b xi_b''
//! ```

use std::collections::HashMap;

use crate::Error;
use crate::diff::{Differentiator, add_opt, mul_opt};
use crate::expr::{Dag, Id};
use crate::formulation::{Formulation, Value};
use crate::jet::{JetArena, JetId, Matrix, Parts, Vector};
use crate::signature::Signature;

mod vector;

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

/// The slip's entity: the master point's motion `s_m = x_m(xi_m) -
/// x_m(xi_m0)` since the last converged state. It takes `x_ms`'s column
/// (it differs from `x_ms` by `x_s - x_m(xi_m0)`, which does not depend on
/// `xi`: the same kind of quantity, the same chains).
pub const SLIP_ENTITY: &str = "s_m";

/// The column of the truncation table [`SLIP_ENTITY`] follows (`x_ms`'s).
pub const SLIP_ENTITY_COLUMN: usize = 1;

/// What a kernel computes: the gap or the slip (`slip!`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// The gap `g` (one component).
    Gap,
    /// The slip: one component in 2D, three in 3D.
    Slip,
}

/// The truncation table: row `t - 1` gives type `t`'s order for
/// `[xi_m, x_ms, n]`.
pub const TYPES: [[EntityOrder; 3]; 6] = {
    use EntityOrder::{Constant as C, Linear as L, Quadratic as Q};
    [
        [C, L, C],
        [L, L, L],
        [L, Q, L],
        [Q, Q, L],
        [L, Q, Q],
        [Q, Q, Q],
    ]
};

/// The expressions of one kernel: the gap, its kept gradient and packed
/// upper Hessian (all `None` for a type without second-order term), sized
/// by the formulation's [`crate::signature::Signature`].
#[derive(Debug, Clone)]
pub struct KernelExprs {
    /// The gap value.
    pub gap: Id,
    /// Kept first derivatives (`n`).
    pub grad: Vector,
    /// Kept second derivatives (packed upper triangle, `n (n + 1) / 2`).
    pub hess: Matrix,
}

impl KernelExprs {
    /// Whether any second derivative survives.
    pub fn has_hessian(&self) -> bool {
        self.hess.iter().any(Option::is_some)
    }
}

/// Builds the kernel expressions of `formulation`'s `quantity` under the
/// truncation row `orders` (for `[xi_m, x_ms, n]`, see [`TYPES`]; the slip's
/// entity [`SLIP_ENTITY`] takes `x_ms`'s), one per component (the gap: one;
/// the slip: [`Formulation::slip_components`]), adding nodes to `dag`
/// (which must be the formulation's DAG or a clone of it). The gap's
/// derivation never builds the slip entity's chains.
pub fn derive(
    formulation: &Formulation,
    dag: &mut Dag,
    orders: [EntityOrder; 3],
    quantity: Quantity,
) -> Result<Vec<KernelExprs>, Error> {
    if formulation.implicit.is_vector() {
        return vector::derive(formulation, dag, orders, quantity);
    }
    let origin = format!("{}.rs", formulation.name);
    let order_of = |name: &str| order_of(formulation, orders, name);
    check_defined(formulation, &declared(formulation))?;

    let sig = &formulation.signature;
    let (n, q) = (sig.coords(), sig.coord_syms());
    let xi = formulation.implicit.sym;
    let mut diff = Differentiator::new();
    let xi_order = order_of(&formulation.implicit.name)?;

    // Implicit derivatives of xi_m (only as far as the row needs them):
    // xi' = -r_q / r_xi and
    // xi'' = -(1/r_xi) (r_qq + r_qxi xi'^T + xi' r_qxi^T + r_xixi xi' xi'^T).
    let r = formulation.implicit.residual;
    let r_xi = diff.d(dag, r, xi).ok_or_else(|| Error::Truncation {
        file: origin.clone(),
        message: "the implicit residual does not depend on its variable".into(),
    })?;
    let inv_r_xi = dag.recip(r_xi);
    let minus_inv = dag.neg(inv_r_xi);
    let mut xi_d1: Vector = vec![None; n];
    if xi_order >= EntityOrder::Linear {
        for j in 0..n {
            let r_q = diff.d(dag, r, q[j]);
            xi_d1[j] = mul_opt(dag, r_q, Some(minus_inv));
        }
    }
    // xi'' in deferred form: -inv r_qq (a basis matrix) + sym(-inv r_qxi, xi')
    // + (-inv r_xixi / 2) sym(xi', xi').
    let mut r_qq: Matrix = vec![None; sig.packed_len()];
    let mut r_qxi: Vector = vec![None; n];
    let mut r_xixi = None;
    if xi_order == EntityOrder::Quadratic {
        for j in 0..n {
            let r_qj = diff.d(dag, r, q[j]);
            for k in j..n {
                r_qq[sig.packed(j, k)] = diff.d_opt(dag, r_qj, q[k]);
            }
            r_qxi[j] = diff.d(dag, r_xi, q[j]);
        }
        r_xixi = diff.d(dag, r_xi, xi);
    }

    let mut arena = JetArena::new(dag, sig);
    let xi_basis = (xi_order >= EntityOrder::Linear).then(|| arena.basis_vector(xi_d1));
    let rqq_basis = (xi_order == EntityOrder::Quadratic).then(|| arena.basis_matrix(r_qq));

    // `c xi''` as Hessian parts.
    let xi2_parts = |arena: &mut JetArena, c: Id, parts: &mut Parts| {
        let (Some(b), Some(m)) = (xi_basis, rqq_basis) else {
            return;
        };
        let dag = arena.dag();
        let k = dag.mul(c, minus_inv);
        parts.hm.push((m, k));
        let u: Vector = r_qxi.iter().map(|&x| mul_opt(dag, x, Some(k))).collect();
        add_rank2(dag, &mut parts.hs, b, u);
        if let Some(rxx) = r_xixi {
            let half = dag.constant(0.5);
            let t = dag.mul(half, rxx);
            let t = dag.mul(t, k);
            add_pair(dag, &mut parts.hp, (b, b), t);
        }
    };

    let mut jets: HashMap<String, Value<JetId>> = HashMap::new();
    {
        let x = arena.dag().input(xi);
        let mut parts = Parts::default();
        if let Some(b) = xi_basis {
            let one = arena.dag().constant(1.0);
            parts.gl.push((b, one));
            let one = arena.dag().constant(1.0);
            xi2_parts(&mut arena, one, &mut parts);
        }
        let jet = arena.entity(x, parts);
        jets.insert(formulation.implicit.name.clone(), Value::Scalar(jet));
    }

    // Entity jets by the truncated chain rule.
    for entity in formulation.entities_for(quantity) {
        let order = order_of(&entity.name)?;
        let mut comp = |arena: &mut JetArena, e: Id| -> JetId {
            let mut parts = Parts::default();
            if order >= EntityOrder::Linear {
                let dag = arena.dag();
                let e_xi = diff.d(dag, e, xi).filter(|_| xi_basis.is_some());
                parts.g = Some((0..n).map(|j| diff.d(dag, e, q[j])).collect());
                if let (Some(b), Some(c)) = (xi_basis, e_xi) {
                    parts.gl.push((b, c));
                }
                if order == EntityOrder::Quadratic {
                    parts.h = Some(hessian_q(dag, &mut diff, e, sig));
                    if let Some(b) = xi_basis {
                        // E_qxi xi'^T + xi' E_xiq = sym(E_qxi, xi').
                        let u: Vector = (0..n).map(|j| diff.d_opt(dag, e_xi, q[j])).collect();
                        add_rank2(dag, &mut parts.hs, b, u);
                        // E_xixi xi' xi'^T = (E_xixi / 2) sym(xi', xi').
                        if let Some(e_xixi) = diff.d_opt(dag, e_xi, xi) {
                            let half = dag.constant(0.5);
                            let t = dag.mul(half, e_xixi);
                            add_pair(dag, &mut parts.hp, (b, b), t);
                        }
                    }
                    if let Some(c) = e_xi {
                        xi2_parts(arena, c, &mut parts);
                    }
                }
            }
            arena.entity(e, parts)
        };
        let v = match entity.value {
            Value::Scalar(s) => Value::Scalar(comp(&mut arena, s)),
            Value::Vec2([a, b]) => {
                let a = comp(&mut arena, a);
                Value::Vec2([a, comp(&mut arena, b)])
            }
            Value::Vec3(c) => Value::Vec3(c.map(|x| comp(&mut arena, x))),
        };
        jets.insert(entity.name.clone(), v);
    }

    finish(formulation, &mut arena, &jets, quantity)
}

/// The quantity's components from the entity jets, materialized.
fn finish(
    formulation: &Formulation,
    arena: &mut JetArena,
    jets: &HashMap<String, Value<JetId>>,
    quantity: Quantity,
) -> Result<Vec<KernelExprs>, Error> {
    let components = match quantity {
        Quantity::Gap => vec![formulation.eval_gap(arena, jets)?],
        Quantity::Slip => formulation.eval_slip(arena, jets)?,
    };
    Ok(components
        .into_iter()
        .map(|c| {
            let (gap, grad, hess) = arena.materialize(c);
            KernelExprs { gap, grad, hess }
        })
        .collect())
}

/// The order row `orders` gives entity `name`, or an error naming it.
fn order_of(
    formulation: &Formulation,
    orders: [EntityOrder; 3],
    name: &str,
) -> Result<EntityOrder, Error> {
    ENTITY_NAMES
        .iter()
        .position(|n| *n == name)
        .or((name == SLIP_ENTITY).then_some(SLIP_ENTITY_COLUMN))
        .map(|i| orders[i])
        .ok_or_else(|| Error::Truncation {
            file: format!("{}.rs", formulation.name),
            message: format!(
                "entity `{name}` has no column in the truncation table (known: {}, and the \
                 slip's `{SLIP_ENTITY}`)",
                ENTITY_NAMES.join(", ")
            ),
        })
}

/// The names a formulation defines: its entities, then its implicit
/// unknown.
fn declared(formulation: &Formulation) -> Vec<&str> {
    let mut declared: Vec<&str> = formulation
        .entities
        .iter()
        .map(|e| e.name.as_str())
        .collect();
    declared.push(&formulation.implicit.name);
    declared
}

/// Every entity of the table is defined, and every defined one has a
/// column.
fn check_entities(formulation: &Formulation, orders: [EntityOrder; 3]) -> Result<(), Error> {
    let declared = declared(formulation);
    for name in &declared {
        order_of(formulation, orders, name)?;
    }
    check_defined(formulation, &declared)
}

/// Every entity of the table is among the `declared` names.
fn check_defined(formulation: &Formulation, declared: &[&str]) -> Result<(), Error> {
    for name in ENTITY_NAMES {
        if !declared.contains(&name) {
            return Err(Error::Truncation {
                file: format!("{}.rs", formulation.name),
                message: format!("the formulation does not define entity `{name}`"),
            });
        }
    }
    Ok(())
}

/// `E_qq` of `e` at fixed `xi`, packed upper (`sig.packed(j, k)`, `j <=
/// k`): the derivatives in coordinate order.
fn hessian_q(dag: &mut Dag, diff: &mut Differentiator, e: Id, sig: &Signature) -> Matrix {
    let (n, q) = (sig.coords(), sig.coord_syms());
    let mut h: Matrix = vec![None; sig.packed_len()];
    for j in 0..n {
        let e_qj = diff.d(dag, e, q[j]);
        for k in j..n {
            h[sig.packed(j, k)] = diff.d_opt(dag, e_qj, q[k]);
        }
    }
    h
}

/// Adds `sym(u, B_b)` to a list of rank-2 terms.
fn add_rank2(dag: &mut Dag, hs: &mut Vec<(usize, Vector)>, b: usize, u: Vector) {
    if u.iter().all(Option::is_none) {
        return;
    }
    match hs.iter_mut().find(|(k, _)| *k == b) {
        Some((_, w)) => *w = (0..w.len()).map(|i| add_opt(dag, w[i], u[i])).collect(),
        None => hs.push((b, u)),
    }
}

/// Adds `c sym(B_s, B_t)` to a list of pair terms.
fn add_pair(dag: &mut Dag, hp: &mut Vec<((usize, usize), Id)>, key: (usize, usize), c: Id) {
    match hp.iter_mut().find(|(k, _)| *k == key) {
        Some((_, w)) => *w = dag.add(*w, c),
        None => hp.push((key, c)),
    }
}

/// The value of the formulation's gap (no derivatives).
pub fn gap_value(formulation: &Formulation, dag: &mut Dag) -> Result<Id, Error> {
    let env = entity_values(formulation, dag);
    formulation.eval_gap(dag, &env)
}

/// Every entity's value and the implicit unknown's, by name.
fn entity_values(formulation: &Formulation, dag: &mut Dag) -> HashMap<String, Value<Id>> {
    let mut env: HashMap<String, Value<Id>> = formulation
        .entities
        .iter()
        .map(|e| (e.name.clone(), e.value))
        .collect();
    let x = formulation.implicit.value(dag);
    env.insert(formulation.implicit.name.clone(), x);
    env
}

/// The vector projection residual `[r_0, r_1]` and its Jacobian `A_ac =
/// dr_a/dxi_c`, row-major: `[r_0, r_1, A_00, A_01, A_10, A_11]` (a
/// structurally zero entry as the constant 0).
pub fn residual_vector(formulation: &Formulation, dag: &mut Dag) -> Vec<Id> {
    let c = &formulation.implicit.components;
    let mut out: Vec<Id> = c.iter().map(|(_, r)| *r).collect();
    let mut diff = Differentiator::new();
    for (_, r) in c {
        for (xi, _) in c {
            let a = diff.d(dag, *r, *xi).unwrap_or_else(|| dag.constant(0.0));
            out.push(a);
        }
    }
    out
}

/// The projection residual and its derivative with respect to the implicit
/// variable: `[r, r_xi]`.
pub fn residual(formulation: &Formulation, dag: &mut Dag) -> [Id; 2] {
    let r = formulation.implicit.residual;
    let r_xi = Differentiator::new()
        .d(dag, r, formulation.implicit.sym)
        .unwrap_or_else(|| dag.constant(0.0));
    [r, r_xi]
}
