//! The automatic-differentiation reference of one formulation file,
//! independent of the generated kernels.
//!
//! The formulation is parsed into its expression DAG (codegen's parser:
//! the formulation's *meaning*), and then evaluated here by a plain
//! interpreter of that DAG generic over num-dual numbers ([`eval_nodes`]).
//! Nothing of the generator's derivative pipeline (symbolic
//! differentiation, truncation, jets, lowering) is used.
//!
//! * `xi_m(q)`: Newton's method on the residual `r(q, xi)` in `f64`
//!   (from `xi = 0`, as the kernels' projection; a 2-vector unknown with the
//!   2 x 2 Jacobian by Cramer's rule), then three more Newton
//!   steps in hyper-dual arithmetic with `r_xi` from a nested dual number:
//!   each step doubles the order of the correct derivative parts, so the
//!   result carries the exact `xi'` and `xi''` of the implicit function.
//! * Type 6 ([`AdFormulation::exact`]): `g(q) = gap(E(q, xi_m(q)))`, its
//!   gradient and full Hessian from one hyper-dual pass per Hessian entry.
//! * Types 1–5 ([`AdFormulation::truncated`]): the truncated formula of
//!   docs/conventions.md assembled from num-dual partial derivatives: of
//!   every entity `E(q, xi)` at a fixed independent `xi` (`E_q`, `E_xi`,
//!   `E_qq`, `E_qxi`, `E_xixi`), of `xi_m(q)` (`xi'`, `xi''`) and of the gap
//!   as a function `G` of the entity components (`G_a`, `G_ab`):
//!
//! ```text
//! E'  = E_q + [xi not constant] E_xi xi'
//! E'' = E_qq + [xi not constant] (E_qxi xi'^T + xi' E_xiq + E_xixi xi' xi'^T)
//!            + [xi quadratic]     E_xi xi''        (then zeroed by E's own order)
//!
//! (for a 2-vector xi = (u, v) the same with sums over its components:
//! E' = E_q + sum_b E_xi_b xi_b', E'' = E_qq + sum_b (E_qxi_b xi_b'^T +
//! xi_b' E_xi_bq + sum_c E_xi_bxi_c xi_b' xi_c'^T) + sum_b E_xi_b xi_b'')
//! g'  = sum_a G_a E_a'
//! g'' = sum_a G_a E_a'' + sum_ab G_ab E_a' E_b'^T
//! ```
//!
//! The table of orders is [`TABLE`], written here from docs/conventions.md
//! (a test checks it equals the generator's `codegen::TYPES`).

use std::collections::HashMap;
use std::marker::PhantomData;

use codegen::expr::{Id, Node, Sym};
use codegen::formulation::{Arity, Domain, Value};
use codegen::{EntityOrder, Formulation};
use num_dual::{Dual, DualNum, HyperDual64};

use super::{Reference, VerifyError};

/// The truncation table of docs/conventions.md: the orders kept for
/// `[xi_m, x_ms, n]`, row `t - 1` for type `t`.
pub const TABLE: [[EntityOrder; 3]; 6] = {
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

/// The entity names the table's columns refer to.
pub const TABLE_ENTITIES: [&str; 3] = ["xi_m", "x_ms", "n"];

/// The slip's entity (the master point's motion `s_m = x_m(xi_m) -
/// x_m(xi_m0)`) and the column it takes: `x_ms`'s (docs/conventions.md,
/// "The slip").
pub const SLIP_ENTITY: (&str, usize) = ("s_m", 1);

/// What a reference is computed for: the gap, or the slip's components
/// (codegen's enum: the reference filters the parsed entities by it, and
/// uses none of codegen's derivative pipeline).
pub use codegen::truncation::Quantity;

/// Newton iterations of the `f64` projection solve.
const ITERATIONS: usize = 50;
/// A Newton correction below this (relative to `1 + |xi|`) ends the solve.
const NEWTON_TOL: f64 = 1e-14;
/// Newton steps in dual arithmetic after the `f64` solve.
const DUAL_STEPS: usize = 3;

/// A parsed formulation ready for AD evaluation.
#[derive(Debug, Clone)]
pub struct AdFormulation {
    f: Formulation,
    n: usize,
    /// Parameter components.
    params: usize,
    /// Components of the implicit unknown.
    k: usize,
}

/// A scalar the interpreter can evaluate the DAG in.
pub trait Scalar: DualNum<Primitive = f64> + Copy {}
impl<D: DualNum<Primitive = f64> + Copy> Scalar for D {}

/// The formulation language's arithmetic over a [`Scalar`] (for the gap
/// expression, which is interpreted over entity values).
struct AdDomain<D>(PhantomData<D>);

impl<D: Scalar> Domain for AdDomain<D> {
    type S = D;
    fn constant(&mut self, c: f64) -> D {
        D::from(c)
    }
    fn add(&mut self, a: D, b: D) -> D {
        a + b
    }
    fn sub(&mut self, a: D, b: D) -> D {
        a - b
    }
    fn mul(&mut self, a: D, b: D) -> D {
        a * b
    }
    fn div(&mut self, a: D, b: D) -> D {
        a / b
    }
    fn neg(&mut self, a: D) -> D {
        -a
    }
    fn sqrt(&mut self, a: D) -> D {
        a.sqrt()
    }
    fn powi(&mut self, a: D, n: i32) -> D {
        a.powi(n)
    }
}

/// Evaluates the nodes `roots` of `f`'s DAG with the input symbols given by
/// `input` (a plain interpreter: children precede parents in the arena).
pub fn eval_nodes<D: Scalar>(f: &Formulation, roots: &[Id], input: &dyn Fn(Sym) -> D) -> Vec<D> {
    let Some(last) = roots.iter().map(|r| r.index()).max() else {
        return Vec::new();
    };
    let dag = &f.dag;
    let live = dag.reachable(roots.iter().copied());
    let mut v: Vec<D> = Vec::with_capacity(last + 1);
    for (i, live) in live.iter().enumerate().take(last + 1) {
        let x = if !*live {
            D::from(0.0)
        } else {
            match dag.node(id_of(f, i)) {
                Node::Const(bits) => D::from(f64::from_bits(bits)),
                Node::Input(s) => input(s),
                Node::Add(a, b) => v[a.index()] + v[b.index()],
                Node::Sub(a, b) => v[a.index()] - v[b.index()],
                Node::Mul(a, b) => v[a.index()] * v[b.index()],
                Node::Recip(a) => v[a.index()].recip(),
                Node::Neg(a) => -v[a.index()],
                Node::Sqrt(a) => v[a.index()].sqrt(),
                Node::Powi(a, k) => v[a.index()].powi(k),
            }
        };
        v.push(x);
    }
    roots.iter().map(|r| v[r.index()]).collect()
}

/// The id of arena index `i` (ids are arena indices).
fn id_of(f: &Formulation, i: usize) -> Id {
    f.dag.id(i)
}

/// A hyper-dual number seeded with `eps1` along direction `j` and `eps2`
/// along `k`.
fn seeded(value: f64, index: usize, j: usize, k: usize) -> HyperDual64 {
    HyperDual64::new(
        value,
        if index == j { 1.0 } else { 0.0 },
        if index == k { 1.0 } else { 0.0 },
        0.0,
    )
}

impl AdFormulation {
    /// Parses a formulation file (any number of points and parameters).
    /// `name` is used in messages (`name.rs:line:col`).
    pub fn parse(name: &str, text: &str) -> Result<AdFormulation, codegen::Error> {
        let f = Formulation::parse_with(name, text, Arity::Any)?;
        Ok(Self::new(f))
    }

    /// Wraps a parsed formulation.
    pub fn new(f: Formulation) -> AdFormulation {
        let n = f.signature.coords();
        let params = f.signature.param_count();
        let k = f.implicit.dim();
        AdFormulation { f, n, params, k }
    }

    /// The parsed formulation.
    pub fn formulation(&self) -> &Formulation {
        &self.f
    }

    /// The coordinate count `n`.
    pub fn coords(&self) -> usize {
        self.n
    }

    /// The table order of entity `name`, or an error naming it.
    fn order(&self, name: &str, row: [EntityOrder; 3]) -> Result<EntityOrder, VerifyError> {
        TABLE_ENTITIES
            .iter()
            .position(|e| *e == name)
            .or((name == SLIP_ENTITY.0).then_some(SLIP_ENTITY.1))
            .map(|i| row[i])
            .ok_or_else(|| VerifyError::Entity {
                file: format!("{}.rs", self.f.name),
                name: name.to_owned(),
            })
    }

    /// The implicit unknown's component count (1, or 2 for faces).
    pub fn implicit_dim(&self) -> usize {
        self.k
    }

    /// The symbol values: `q`, the parameters, the implicit unknown's
    /// components, then the last converged projection `xi_m0` (the slip's
    /// input), which `params` holds after the parameters.
    fn input<'a, D: Scalar>(
        &self,
        q: &'a [D],
        params: &'a [f64],
        xi: &'a [D],
    ) -> impl Fn(Sym) -> D + 'a {
        let (n, m, k) = (self.n, self.params, self.k);
        move |s: Sym| {
            let i = s.0 as usize;
            if i < n {
                q[i]
            } else if i < n + m {
                D::from(params[i - n])
            } else if i < n + m + k {
                xi[i - n - m]
            } else {
                D::from(params[m + i - n - m - k])
            }
        }
    }

    /// The residuals `r_a(q, xi)` and their Jacobian `A_ac = dr_a/dxi_c`
    /// (row-major) over `D`, by nested duals along each `xi_c`.
    fn residual<D: Scalar>(&self, q: &[D], params: &[f64], xi: &[D]) -> (Vec<D>, Vec<D>) {
        let k = self.k;
        let roots: Vec<Id> = self.f.implicit.components.iter().map(|c| c.1).collect();
        let qd: Vec<Dual<D>> = q.iter().map(|&v| Dual::new(v, D::from(0.0))).collect();
        let mut r = vec![D::from(0.0); k];
        let mut a = vec![D::from(0.0); k * k];
        for c in 0..k {
            let xid: Vec<Dual<D>> = (0..k)
                .map(|b| Dual::new(xi[b], D::from(if b == c { 1.0 } else { 0.0 })))
                .collect();
            let v = eval_nodes(&self.f, &roots, &self.input(&qd, params, &xid));
            for (ai, va) in v.iter().enumerate() {
                r[ai] = va.re;
                a[ai * k + c] = va.eps;
            }
        }
        (r, a)
    }

    /// The Newton step `A^-1 r` (1 x 1 or 2 x 2, by Cramer's rule).
    fn step<D: Scalar>(r: &[D], a: &[D]) -> Vec<D> {
        match r.len() {
            1 => vec![r[0] / a[0]],
            _ => {
                let det = a[0] * a[3] - a[1] * a[2];
                vec![
                    (a[3] * r[0] - a[1] * r[1]) / det,
                    (a[0] * r[1] - a[2] * r[0]) / det,
                ]
            }
        }
    }

    /// Solves `r(q, xi) = 0` in `f64` by Newton's method from `xi = 0`
    /// (every component); `None` when it does not converge or the root lies
    /// beyond `max|xi| = limit`.
    pub fn project(&self, q: &[f64], params: &[f64], limit: f64) -> Option<Vec<f64>> {
        let mut xi = vec![0.0_f64; self.k];
        let reach = |xi: &[f64]| xi.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        for _ in 0..ITERATIONS {
            let (r, a) = self.residual(q, params, &xi);
            let step = Self::step(&r, &a);
            if !step.iter().all(|s| s.is_finite()) {
                return None;
            }
            xi.iter_mut().zip(&step).for_each(|(x, s)| *x -= s);
            if reach(&xi) > limit {
                return None;
            }
            if reach(&step) <= NEWTON_TOL * (1.0 + reach(&xi)) {
                // One more step to settle the last bit.
                let (r, a) = self.residual(q, params, &xi);
                let last = Self::step(&r, &a);
                if !last.iter().all(|s| s.is_finite()) {
                    return None;
                }
                return Some(xi.iter().zip(&last).map(|(x, s)| x - s).collect());
            }
        }
        None
    }

    /// `xi_m(q)` in dual arithmetic from the converged `xi0`.
    fn xi_dual<D: Scalar>(&self, q: &[D], params: &[f64], xi0: &[f64]) -> Vec<D> {
        let mut xi: Vec<D> = xi0.iter().map(|&x| D::from(x)).collect();
        for _ in 0..DUAL_STEPS {
            let (r, a) = self.residual(q, params, &xi);
            let step = Self::step(&r, &a);
            xi.iter_mut().zip(step).for_each(|(x, s)| *x -= s);
        }
        xi
    }

    /// The entity values at `(q, xi)` that `quantity` uses, by name (the
    /// implicit one included).
    fn entities<D: Scalar>(
        &self,
        q: &[D],
        params: &[f64],
        xi: &[D],
        quantity: Quantity,
    ) -> HashMap<String, Value<D>> {
        let roots: Vec<Id> = self
            .f
            .entities_for(quantity)
            .flat_map(|e| e.value.components())
            .collect();
        let vals = eval_nodes(&self.f, &roots, &self.input(q, params, xi));
        let mut at = 0;
        let mut out = HashMap::new();
        for e in self.f.entities_for(quantity) {
            let len = e.value.components().len();
            out.insert(e.name.clone(), e.value.like(&vals[at..at + len]));
            at += len;
        }
        out.insert(self.f.implicit.name.clone(), Value::from_components(xi));
        out
    }

    /// The components of `quantity` (the gap: one) of the entity values.
    fn outputs<D: Scalar>(
        &self,
        entities: &HashMap<String, Value<D>>,
        quantity: Quantity,
    ) -> Result<Vec<D>, VerifyError> {
        let mut domain = AdDomain::<D>(PhantomData);
        Ok(match quantity {
            Quantity::Gap => vec![self.f.eval_gap(&mut domain, entities)?],
            Quantity::Slip => self.f.eval_slip(&mut domain, entities)?,
        })
    }

    /// Type 6's reference: the gap, `xi_m`, the exact gradient and Hessian
    /// (row-major `n x n`), from `xi0`, the converged projection
    /// ([`AdFormulation::project`]). `q` should be relative to the first
    /// point (the kernels' own coordinates).
    pub fn exact(&self, q: &[f64], params: &[f64], xi0: &[f64]) -> Result<Reference, VerifyError> {
        Ok(self.exact_of(q, params, xi0, Quantity::Gap)?.remove(0))
    }

    /// [`AdFormulation::exact`] of every component of `quantity` (each
    /// [`Reference::gap`] holds the component's value). For the slip,
    /// `params` ends with the last converged projection `xi_m0`.
    pub fn exact_of(
        &self,
        q: &[f64],
        params: &[f64],
        xi0: &[f64],
        quantity: Quantity,
    ) -> Result<Vec<Reference>, VerifyError> {
        let n = self.n;
        let mut out: Vec<Reference> = Vec::new();
        for j in 0..n {
            for k in j..n {
                let qd: Vec<HyperDual64> = (0..n).map(|i| seeded(q[i], i, j, k)).collect();
                let xi = self.xi_dual(&qd, params, xi0);
                let gs = self.outputs(&self.entities(&qd, params, &xi, quantity), quantity)?;
                if out.is_empty() {
                    out = vec![Reference::zeros(n); gs.len()];
                    out.iter_mut().for_each(|r| r.set_xi(xi0));
                }
                for (r, g) in out.iter_mut().zip(&gs) {
                    if j == k {
                        r.grad[j] = g.eps1;
                        r.gap = g.re;
                        r.set_xi(&xi.iter().map(|x| x.re).collect::<Vec<_>>());
                    }
                    r.hess[j * n + k] = g.eps1eps2;
                    r.hess[k * n + j] = g.eps1eps2;
                }
            }
        }
        Ok(out)
    }

    /// The references of all six types: Types 1–5 from the truncated
    /// formula, Type 6 from [`AdFormulation::exact`].
    pub fn references(
        &self,
        q: &[f64],
        params: &[f64],
        xi0: &[f64],
    ) -> Result<[Reference; 6], VerifyError> {
        let refs = self.references_of(q, params, xi0, Quantity::Gap)?;
        Ok(refs.map(|mut r| r.remove(0)))
    }

    /// [`AdFormulation::references`] of every component of `quantity`:
    /// per type, one [`Reference`] per component (the value in
    /// [`Reference::gap`]). For the slip, `params` ends with the last
    /// converged projection `xi_m0`.
    pub fn references_of(
        &self,
        q: &[f64],
        params: &[f64],
        xi0: &[f64],
        quantity: Quantity,
    ) -> Result<[Vec<Reference>; 6], VerifyError> {
        let parts = self.partials(q, params, xi0, quantity)?;
        let mut out: [Vec<Reference>; 6] = std::array::from_fn(|_| Vec::new());
        for (t, row) in TABLE.iter().enumerate().take(5) {
            out[t] = (0..parts.outputs.len())
                .map(|c| self.assemble(&parts, *row, c))
                .collect::<Result<_, _>>()?;
        }
        out[5] = self.exact_of(q, params, xi0, quantity)?;
        Ok(out)
    }

    /// The truncated reference of one table row (all six rows for tests of
    /// the reference itself: with every entity quadratic it is the exact
    /// Hessian).
    pub fn truncated(
        &self,
        q: &[f64],
        params: &[f64],
        xi0: &[f64],
        row: [EntityOrder; 3],
    ) -> Result<Reference, VerifyError> {
        let parts = self.partials(q, params, xi0, Quantity::Gap)?;
        self.assemble(&parts, row, 0)
    }

    /// Every partial derivative the truncated formula of `quantity` needs.
    fn partials(
        &self,
        q: &[f64],
        params: &[f64],
        xi0: &[f64],
        quantity: Quantity,
    ) -> Result<Partials, VerifyError> {
        let (n, kx) = (self.n, self.k);
        // xi_b' and xi_b'' of the implicit function, per component b.
        let mut xi1 = vec![vec![0.0; n]; kx];
        let mut xi2 = vec![vec![0.0; n * n]; kx];
        let mut xi_m = xi0.to_vec();
        for j in 0..n {
            for k in j..n {
                let qd: Vec<HyperDual64> = (0..n).map(|i| seeded(q[i], i, j, k)).collect();
                let xi = self.xi_dual(&qd, params, xi0);
                for (b, x) in xi.iter().enumerate() {
                    if j == k {
                        xi1[b][j] = x.eps1;
                        xi_m[b] = x.re;
                    }
                    xi2[b][j * n + k] = x.eps1eps2;
                    xi2[b][k * n + j] = x.eps1eps2;
                }
            }
        }
        // Entity components as functions of z = (q, xi) at fixed xi.
        let names: Vec<(String, usize)> = self
            .f
            .entities_for(quantity)
            .flat_map(|e| (0..e.value.components().len()).map(move |c| (e.name.clone(), c)))
            .collect();
        let m = names.len();
        let nz = n + kx;
        let mut ent = vec![Hd::zeros(nz); m];
        for j in 0..nz {
            for k in j..nz {
                let qd: Vec<HyperDual64> = (0..n).map(|i| seeded(q[i], i, j, k)).collect();
                let xi: Vec<HyperDual64> = (0..kx).map(|b| seeded(xi_m[b], n + b, j, k)).collect();
                let e = self.entities(&qd, params, &xi, quantity);
                let comps: Vec<HyperDual64> = self
                    .f
                    .entities_for(quantity)
                    .flat_map(|x| e[&x.name].components())
                    .collect();
                for (c, v) in comps.iter().enumerate() {
                    ent[c].record(v, j, k);
                }
            }
        }
        // The quantity's components as functions of [xi components, entity
        // components].
        let values: Vec<f64> = xi_m
            .iter()
            .copied()
            .chain(ent.iter().map(|h| h.value))
            .collect();
        let ng = values.len();
        let mut outputs: Vec<Hd> = Vec::new();
        for j in 0..ng {
            for k in j..ng {
                let v: Vec<HyperDual64> = (0..ng).map(|i| seeded(values[i], i, j, k)).collect();
                let mut map = HashMap::new();
                map.insert(
                    self.f.implicit.name.clone(),
                    Value::from_components(&v[..kx]),
                );
                let mut at = kx;
                for e in self.f.entities_for(quantity) {
                    let len = e.value.components().len();
                    map.insert(e.name.clone(), e.value.like(&v[at..at + len]));
                    at += len;
                }
                let gs = self.outputs(&map, quantity)?;
                if outputs.is_empty() {
                    outputs = vec![Hd::zeros(ng); gs.len()];
                }
                for (o, g) in outputs.iter_mut().zip(&gs) {
                    o.record(g, j, k);
                }
            }
        }
        Ok(Partials {
            n,
            xi_m,
            xi1,
            xi2,
            names,
            ent,
            outputs,
        })
    }

    /// The truncated `g`, `g'`, `g''` of one table row (of the quantity's
    /// component `c`):
    /// `E' = E_q + [xi not constant] sum_b E_xi_b xi_b'`,
    /// `E'' = E_qq + [xi not constant] sum_b (E_qxi_b xi_b'^T + xi_b' E_xi_bq
    /// + sum_c E_xi_bxi_c xi_b' xi_c'^T) + [xi quadratic] sum_b E_xi_b xi_b''`.
    fn assemble(
        &self,
        p: &Partials,
        row: [EntityOrder; 3],
        c: usize,
    ) -> Result<Reference, VerifyError> {
        let out = &p.outputs[c];
        let (n, kx) = (p.n, self.k);
        let xi_order = self.order(&self.f.implicit.name, row)?;
        let xi_varies = xi_order != EntityOrder::Constant;
        let xi_quadratic = xi_order == EntityOrder::Quadratic;
        // Kept (E', E'') of every gap argument: xi's components first, then
        // the entity components.
        let mut d1: Vec<Vec<f64>> = Vec::new();
        let mut d2: Vec<Vec<f64>> = Vec::new();
        for b in 0..kx {
            d1.push(if xi_varies {
                p.xi1[b].clone()
            } else {
                vec![0.0; n]
            });
            d2.push(if xi_quadratic {
                p.xi2[b].clone()
            } else {
                vec![0.0; n * n]
            });
        }
        let nz = n + kx;
        for ((name, _), e) in p.names.iter().zip(&p.ent) {
            let own = self.order(name, row)?;
            let mut a = e.grad[..n].to_vec();
            let mut h: Vec<f64> = (0..n * n).map(|i| e.hess[(i / n) * nz + i % n]).collect();
            if xi_varies {
                for b in 0..kx {
                    let e_xi = e.grad[n + b];
                    for j in 0..n {
                        a[j] += e_xi * p.xi1[b][j];
                        let e_qxi_j = e.hess[j * nz + n + b];
                        for k in 0..n {
                            let e_qxi_k = e.hess[k * nz + n + b];
                            h[j * n + k] += e_qxi_j * p.xi1[b][k] + p.xi1[b][j] * e_qxi_k;
                            for cc in 0..kx {
                                let e_bc = e.hess[(n + b) * nz + n + cc];
                                h[j * n + k] += e_bc * p.xi1[b][j] * p.xi1[cc][k];
                            }
                        }
                    }
                }
            }
            if xi_quadratic {
                for b in 0..kx {
                    let e_xi = e.grad[n + b];
                    for (hi, x2) in h.iter_mut().zip(&p.xi2[b]) {
                        *hi += e_xi * x2;
                    }
                }
            }
            match own {
                EntityOrder::Constant => {
                    a.iter_mut().for_each(|v| *v = 0.0);
                    h.iter_mut().for_each(|v| *v = 0.0);
                }
                EntityOrder::Linear => h.iter_mut().for_each(|v| *v = 0.0),
                EntityOrder::Quadratic => {}
            }
            d1.push(a);
            d2.push(h);
        }
        let mut r = Reference::zeros(n);
        r.gap = out.value;
        r.set_xi(&p.xi_m);
        let ng = d1.len();
        for a in 0..ng {
            let ga = out.grad[a];
            for (g, e1) in r.grad.iter_mut().zip(&d1[a]) {
                *g += ga * e1;
            }
            for (h, e2) in r.hess.iter_mut().zip(&d2[a]) {
                *h += ga * e2;
            }
            for b in 0..ng {
                let gab = out.hess[a * ng + b];
                if gab == 0.0 {
                    continue;
                }
                for j in 0..n {
                    for k in 0..n {
                        r.hess[j * n + k] += gab * d1[a][j] * d1[b][k];
                    }
                }
            }
        }
        Ok(r)
    }
}

/// Value, gradient and Hessian (row-major) of one scalar, filled pass by
/// pass from hyper-dual numbers.
#[derive(Debug, Clone)]
struct Hd {
    value: f64,
    grad: Vec<f64>,
    hess: Vec<f64>,
}

impl Hd {
    fn zeros(n: usize) -> Hd {
        Hd {
            value: 0.0,
            grad: vec![0.0; n],
            hess: vec![0.0; n * n],
        }
    }

    fn record(&mut self, v: &HyperDual64, j: usize, k: usize) {
        let n = self.grad.len();
        if j == k {
            self.value = v.re;
            self.grad[j] = v.eps1;
        }
        self.hess[j * n + k] = v.eps1eps2;
        self.hess[k * n + j] = v.eps1eps2;
    }
}

/// The partial derivatives of one configuration.
#[derive(Debug, Clone)]
struct Partials {
    n: usize,
    /// The projection's components.
    xi_m: Vec<f64>,
    /// `xi_b'` per component `b`.
    xi1: Vec<Vec<f64>>,
    /// `xi_b''` per component `b` (row-major `n x n`).
    xi2: Vec<Vec<f64>>,
    /// Entity component names (entity, component).
    names: Vec<(String, usize)>,
    /// Per component, over `(q, xi)`.
    ent: Vec<Hd>,
    /// The quantity's components (the gap: one), each over `[xi,
    /// entity components...]`.
    outputs: Vec<Hd>,
}
