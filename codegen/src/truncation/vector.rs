//! The truncation rule for a 2-vector unknown `xi = (u, v)` (3D faces):
//! the sums over components of the parent module's docs, applied exactly.
//!
//! With `A_ac = dr_a/dxi_c` and `M = -A^-1` (in the kernel: the 2 x 2
//! inverse by its adjugate over the determinant),
//!
//! * `xi_b' = sum_a M_ba r_a,q` (one basis vector per component);
//! * `c xi_b''` = `sum_a c M_ba [ r_a,qq + sum_c sym(r_a,qxi_c, xi_c')
//!   + sum_cd r_a,xi_cxi_d xi_c' xi_d'^T ]` as deferred jet parts (the
//!   basis matrices `r_a,qq`, rank-2 terms on `xi_c'`, pair terms on
//!   `(xi_c', xi_d')`; `sym(u, B) = u B^T + B u^T`);
//! * an entity component `E(q, xi)`: `E' = E_q + sum_b E_xi_b xi_b'`,
//!   `E'' = E_qq + sum_b sym(E_qxi_b, xi_b') + sum_bc E_xi_bxi_c xi_b'
//!   xi_c'^T + [xi quadratic] sum_b E_xi_b xi_b''`, each part only as far
//!   as the entity's and the unknown's orders keep it.

use std::collections::HashMap;

use super::{
    EntityOrder, KernelExprs, Quantity, add_pair, add_rank2, check_entities, finish, hessian_q,
    order_of,
};
use crate::Error;
use crate::diff::{Differentiator, add_opt, mul_opt};
use crate::expr::{Dag, Id, Sym};
use crate::formulation::{Formulation, Value};
use crate::jet::{JetArena, JetId, Matrix, Parts, Vector};

/// [`super::derive`] for a formulation whose implicit unknown has two
/// components.
pub(super) fn derive(
    formulation: &Formulation,
    dag: &mut Dag,
    orders: [EntityOrder; 3],
    quantity: Quantity,
) -> Result<Vec<KernelExprs>, Error> {
    check_entities(formulation, orders)?;
    let origin = format!("{}.rs", formulation.name);
    let sig = &formulation.signature;
    let (n, q) = (sig.coords(), sig.coord_syms());
    let xs: Vec<Sym> = formulation
        .implicit
        .components
        .iter()
        .map(|c| c.0)
        .collect();
    let rs: Vec<Id> = formulation
        .implicit
        .components
        .iter()
        .map(|c| c.1)
        .collect();
    let xi_order = order_of(formulation, orders, &formulation.implicit.name)?;
    let mut diff = Differentiator::new();

    // A_ac = dr_a/dxi_c; the residuals must depend on the unknown.
    let mut a = [[None; 2]; 2];
    for (ra, row) in rs.iter().zip(a.iter_mut()) {
        for (xc, entry) in xs.iter().zip(row.iter_mut()) {
            *entry = diff.d(dag, *ra, *xc);
        }
    }
    if a.iter().flatten().all(Option::is_none) {
        return Err(Error::Truncation {
            file: origin,
            message: "the implicit residuals do not depend on their variable".into(),
        });
    }
    let zero = dag.constant(0.0);
    let az = a.map(|row| row.map(|x| x.unwrap_or(zero)));
    // M = -A^-1 = -adj(A) / det(A).
    let p = dag.mul(az[0][0], az[1][1]);
    let m_ = dag.mul(az[0][1], az[1][0]);
    let det = dag.sub(p, m_);
    let inv_det = dag.recip(det);
    let minus_inv_det = dag.neg(inv_det);
    let m: [[Option<Id>; 2]; 2] = [
        [
            mul_opt(dag, a[1][1], Some(minus_inv_det)),
            mul_opt(dag, a[0][1], Some(inv_det)),
        ],
        [
            mul_opt(dag, a[1][0], Some(inv_det)),
            mul_opt(dag, a[0][0], Some(minus_inv_det)),
        ],
    ];

    // xi_b' = sum_a M_ba r_a,q.
    let mut xi_d1: Vec<Vector> = vec![vec![None; n]; 2];
    if xi_order >= EntityOrder::Linear {
        for (b, d1) in xi_d1.iter_mut().enumerate() {
            for (j, e) in d1.iter_mut().enumerate() {
                let mut acc = None;
                for (ra, m_ba) in rs.iter().zip(m[b]) {
                    let r_q = diff.d(dag, *ra, q[j]);
                    let t = mul_opt(dag, r_q, m_ba);
                    acc = add_opt(dag, acc, t);
                }
                *e = acc;
            }
        }
    }
    // Second-order pieces of the residuals (only for a quadratic unknown).
    let mut r_qq: Vec<Matrix> = vec![vec![None; sig.packed_len()]; 2];
    // r_qxi[a][c][j] = d2 r_a / dq_j dxi_c.
    let mut r_qxi: Vec<Vec<Vector>> = vec![vec![vec![None; n]; 2]; 2];
    // r_xixi[a][c][d] = d2 r_a / dxi_c dxi_d.
    let mut r_xixi = [[[None; 2]; 2]; 2];
    if xi_order == EntityOrder::Quadratic {
        for (ai, ra) in rs.iter().enumerate() {
            for j in 0..n {
                let r_qj = diff.d(dag, *ra, q[j]);
                for k in j..n {
                    r_qq[ai][sig.packed(j, k)] = diff.d_opt(dag, r_qj, q[k]);
                }
                for c in 0..2 {
                    r_qxi[ai][c][j] = diff.d_opt(dag, a[ai][c], q[j]);
                }
            }
            for c in 0..2 {
                for d in 0..2 {
                    r_xixi[ai][c][d] = diff.d_opt(dag, a[ai][c], xs[d]);
                }
            }
        }
    }

    let mut arena = JetArena::new(dag, sig);
    let basis: Option<[usize; 2]> = (xi_order >= EntityOrder::Linear).then(|| {
        let [b0, b1] = [xi_d1[0].clone(), xi_d1[1].clone()];
        [arena.basis_vector(b0), arena.basis_vector(b1)]
    });
    let rqq_basis: Option<[usize; 2]> = (xi_order == EntityOrder::Quadratic).then(|| {
        let [m0, m1] = [r_qq[0].clone(), r_qq[1].clone()];
        [arena.basis_matrix(m0), arena.basis_matrix(m1)]
    });

    // `coef xi_b''` as Hessian parts.
    let xi2_parts = |arena: &mut JetArena, coef: Id, b: usize, parts: &mut Parts| {
        let (Some(bv), Some(mm)) = (basis, rqq_basis) else {
            return;
        };
        let dag = arena.dag();
        for ai in 0..2 {
            let Some(m_ba) = m[b][ai] else { continue };
            let k = dag.mul(coef, m_ba);
            parts.hm.push((mm[ai], k));
            for c in 0..2 {
                let u: Vector = r_qxi[ai][c]
                    .iter()
                    .map(|&x| mul_opt(dag, x, Some(k)))
                    .collect();
                add_rank2(dag, &mut parts.hs, bv[c], u);
            }
            // sum_cd r_cd B_c B_d^T = r_00/2 sym(B_0, B_0) + r_11/2 sym(B_1, B_1)
            //   + r_01 sym(B_0, B_1) (r_01 = r_10).
            for (c, d) in [(0, 0), (1, 1), (0, 1)] {
                let Some(r) = r_xixi[ai][c][d] else { continue };
                let t = if c == d {
                    let half = dag.constant(0.5);
                    let t = dag.mul(half, r);
                    dag.mul(t, k)
                } else {
                    dag.mul(r, k)
                };
                add_pair(dag, &mut parts.hp, (bv[c], bv[d]), t);
            }
        }
    };

    let mut jets: HashMap<String, Value<JetId>> = HashMap::new();
    {
        let mut comps = Vec::new();
        for (b, xb) in xs.iter().enumerate() {
            let x = arena.dag().input(*xb);
            let mut parts = Parts::default();
            if let Some(bv) = basis {
                let one = arena.dag().constant(1.0);
                parts.gl.push((bv[b], one));
                let one = arena.dag().constant(1.0);
                xi2_parts(&mut arena, one, b, &mut parts);
            }
            comps.push(arena.entity(x, parts));
        }
        jets.insert(
            formulation.implicit.name.clone(),
            Value::from_components(&comps),
        );
    }

    for entity in formulation.entities_for(quantity) {
        let order = order_of(formulation, orders, &entity.name)?;
        let mut comp = |arena: &mut JetArena, e: Id| -> JetId {
            let mut parts = Parts::default();
            if order >= EntityOrder::Linear {
                let dag = arena.dag();
                parts.g = Some((0..n).map(|j| diff.d(dag, e, q[j])).collect());
                let e_xi: Vec<Option<Id>> = match basis {
                    Some(_) => xs.iter().map(|x| diff.d(dag, e, *x)).collect(),
                    None => vec![None, None],
                };
                if let Some(bv) = basis {
                    for (b, c) in e_xi.iter().enumerate() {
                        if let Some(c) = c {
                            parts.gl.push((bv[b], *c));
                        }
                    }
                }
                if order == EntityOrder::Quadratic {
                    parts.h = Some(hessian_q(dag, &mut diff, e, sig));
                    if let Some(bv) = basis {
                        for b in 0..2 {
                            // E_qxi_b xi_b'^T + xi_b' E_xi_bq = sym(E_qxi_b, xi_b').
                            let u: Vector =
                                (0..n).map(|j| diff.d_opt(dag, e_xi[b], q[j])).collect();
                            add_rank2(dag, &mut parts.hs, bv[b], u);
                        }
                        // sum_bc E_xi_bxi_c xi_b' xi_c'^T.
                        for (b, c) in [(0, 0), (1, 1), (0, 1)] {
                            let Some(e2) = diff.d_opt(dag, e_xi[b], xs[c]) else {
                                continue;
                            };
                            let t = if b == c {
                                let half = dag.constant(0.5);
                                dag.mul(half, e2)
                            } else {
                                e2
                            };
                            add_pair(dag, &mut parts.hp, (bv[b], bv[c]), t);
                        }
                    }
                    for (b, c) in e_xi.iter().enumerate() {
                        if let Some(c) = c {
                            xi2_parts(arena, *c, b, &mut parts);
                        }
                    }
                }
            }
            arena.entity(e, parts)
        };
        let c: Vec<JetId> = entity
            .value
            .components()
            .into_iter()
            .map(|x| comp(&mut arena, x))
            .collect();
        jets.insert(entity.name.clone(), entity.value.like(&c));
    }

    finish(formulation, &mut arena, &jets, quantity)
}
