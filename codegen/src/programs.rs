//! Programs: a parsed formulation derived under every truncation row and
//! lowered to instruction lists (the step between the expression DAG and
//! the kernel plan).
//!
//! Every program loads the relative coordinates, the parameters and the
//! implicit unknown of the formulation's [`crate::signature::Signature`];
//! the output layouts are documented on [`FormulationPrograms`].

use crate::truncation::{self, Quantity, TYPES};
use crate::{Error, Formulation, Program, diff, expr};

/// The programs of one formulation.
#[derive(Debug, Clone)]
pub struct FormulationPrograms {
    /// Whether the projection residual is affine in its variable. Then every
    /// kernel solves the projection itself in closed form (one exact Newton
    /// step from `xi = 0`, sharing subexpressions with the derivatives) and
    /// returns `xi_m` as its last output; otherwise the kernels take the
    /// converged `xi_m` as input.
    pub affine: bool,
    /// `[r, r_xi]` of the projection at `xi` (a 2-vector unknown:
    /// `[r_0, r_1, A_00, A_01, A_10, A_11]`, `A_ac = dr_a/dxi_c`).
    pub residual: Program,
    /// The gap value (`[g]`, or `[g, xi_m]` when affine; a 2-vector
    /// unknown: `[g, u, v]`).
    pub gap: Program,
    /// Per type (1..=6): outputs `[g, grad(n), packed upper hess(n (n + 1) / 2)]`
    /// (plus `xi_m` when affine, both components for a 2-vector unknown;
    /// `n` from the formulation's signature), and whether any Hessian entry
    /// survives.
    pub kernels: Vec<(Program, bool)>,
    /// Per type (1..=6), when the formulation has a slip (`slip!`; else
    /// empty): the slip's `c` components
    /// ([`Formulation::slip_components`]), outputs `[s_0 .. s_c-1,
    /// grad_0 (n) .. grad_c-1, hess_0 (n (n + 1) / 2) .. hess_c-1]` (all
    /// structurally zero without second-order term; `xi_m` last when
    /// affine, as the kernels), and whether any Hessian entry survives. The last converged
    /// projection `xi_m0` is loaded as the parameter components after the
    /// signature's ([`crate::signature::Signature::previous_syms`]).
    pub slips: Vec<(Program, bool)>,
}

/// Derives and lowers every program of a formulation, once its translation
/// invariance is proven ([`crate::invariance::check`]: the lowering takes
/// coordinates relative to the first point).
pub fn programs(f: &Formulation) -> Result<FormulationPrograms, Error> {
    crate::invariance::check(f)?;
    if f.implicit.is_vector() {
        return programs_vector(f);
    }
    let xi = f.implicit.sym;
    // Closed-form projection when r is affine in xi: xi_m = -r(q, 0) / r_xi(q).
    let closed_form = |dag: &mut expr::Dag| -> Option<Vec<expr::Id>> {
        let [r, r_xi] = truncation::residual(f, dag);
        if diff::Differentiator::new().d(dag, r_xi, xi).is_some() {
            return None;
        }
        let zero = dag.constant(0.0);
        let r0 = dag.replace(&[Some(r)], xi, zero)[0].expect("some");
        let inv = dag.recip(r_xi);
        let t = dag.mul(r0, inv);
        Some(vec![dag.neg(t)])
    };
    assemble(f, &[xi], closed_form, |dag| {
        truncation::residual(f, dag).to_vec()
    })
}

/// The programs of a formulation whose unknown has the components `xs`
/// (its parametric dimension `P`): `closed_form` gives the projection's
/// components when the residual is affine (then every kernel solves it and
/// returns them last), `residual` the residual program's outputs.
fn assemble(
    f: &Formulation,
    xs: &[expr::Sym],
    closed_form: impl Fn(&mut expr::Dag) -> Option<Vec<expr::Id>>,
    residual: impl Fn(&mut expr::Dag) -> Vec<expr::Id>,
) -> Result<FormulationPrograms, Error> {
    let lower = |dag: &expr::Dag, outs: &[Option<expr::Id>]| {
        finite(f, Program::lower(dag, outs, &f.signature))
    };
    // Outputs with the projection solved inside the kernel, when affine.
    let finish = |dag: &mut expr::Dag, outs: Vec<Option<expr::Id>>| -> Vec<Option<expr::Id>> {
        match closed_form(dag) {
            Some(x) => {
                let mut outs = outs;
                for (sym, val) in xs.iter().zip(&x) {
                    outs = dag.replace(&outs, *sym, *val);
                }
                outs.extend(x.into_iter().map(Some));
                outs
            }
            None => outs,
        }
    };
    let mut dag = f.dag.clone();
    let affine = closed_form(&mut dag).is_some();
    let r = residual(&mut dag);
    let residual = lower(&dag, &r.into_iter().map(Some).collect::<Vec<_>>())?;
    let g = truncation::gap_value(f, &mut dag)?;
    let outs = finish(&mut dag, vec![Some(g)]);
    let gap = lower(&dag, &outs)?;
    for (what, program) in [("projection residual", &residual), ("gap", &gap)] {
        if loads_previous(f, program) {
            return Err(Error::Truncation {
                file: format!("{}.rs", f.name),
                message: format!(
                    "the {what} depends on the last converged projection (`previous!`), which \
                     only the slip may use"
                ),
            });
        }
    }
    let mut kernels = Vec::new();
    let mut slips = Vec::new();
    for row in TYPES {
        for quantity in [Quantity::Gap, Quantity::Slip] {
            if quantity == Quantity::Slip && f.slip.is_none() {
                continue;
            }
            // A fresh DAG per type and quantity: nothing of another type's
            // chains leaks in.
            let mut dag = f.dag.clone();
            let ks = truncation::derive(f, &mut dag, row, quantity)?;
            let has_hessian = ks.iter().any(truncation::KernelExprs::has_hessian);
            let mut outs: Vec<Option<expr::Id>> = ks.iter().map(|k| Some(k.gap)).collect();
            for k in &ks {
                outs.extend(k.grad.iter().copied());
            }
            for k in &ks {
                outs.extend(k.hess.iter().copied());
            }
            let outs = finish(&mut dag, outs);
            let program = lower(&dag, &outs)?;
            match quantity {
                Quantity::Gap => kernels.push((program, has_hessian)),
                Quantity::Slip => slips.push((program, has_hessian)),
            }
        }
    }
    Ok(FormulationPrograms {
        affine,
        residual,
        gap,
        kernels,
        slips,
    })
}

/// Whether `program` loads the last converged projection `xi_m0` (the
/// parameter components after the signature's).
fn loads_previous(f: &Formulation, program: &Program) -> bool {
    use crate::lower::{Instr, Source};
    let params = f.signature.param_count();
    program
        .instrs
        .iter()
        .any(|i| matches!(*i, Instr::Load(Source::Param(p)) if p >= params))
}

/// `program`, or an error if a constant of it is not finite (a fold such as
/// `1 / 0` that only appears once the first point's coordinates are zero,
/// or in a closed-form projection whose `dr/dxi` is zero).
fn finite(f: &Formulation, program: Program) -> Result<Program, Error> {
    use crate::lower::{Instr, Operand};
    let operands = program.instrs.iter().flat_map(|i| match *i {
        Instr::Load(_) => vec![],
        Instr::Add(a, b) | Instr::Sub(a, b) | Instr::Mul(a, b) => vec![a, b],
        Instr::Square(a) | Instr::Powi(a, _) | Instr::Recip(a) | Instr::Neg(a) | Instr::Sqrt(a) => {
            vec![a]
        }
    });
    let bad = operands
        .chain(program.outputs.iter().flatten().copied())
        .find_map(|o| match o {
            Operand::Const(c) if !c.is_finite() => Some(c),
            _ => None,
        });
    match bad {
        None => Ok(program),
        Some(c) => Err(Error::Truncation {
            file: format!("{}.rs", f.name),
            message: format!(
                "the generated kernels would hold the non-finite constant {c} (a division by an \
                 expression that is zero, e.g. a projection residual whose derivative in its \
                 variable is zero)"
            ),
        }),
    }
}

/// [`programs`] for a 2-vector unknown: closed form `xi = -A^-1 r(q, 0)`
/// when every `A_ac` is independent of `xi` (the residual is affine: a
/// tri3 master), the inverse by adjugate over determinant.
fn programs_vector(f: &Formulation) -> Result<FormulationPrograms, Error> {
    let xs: Vec<expr::Sym> = f.implicit.components.iter().map(|c| c.0).collect();
    let closed_form = |dag: &mut expr::Dag| -> Option<Vec<expr::Id>> {
        let ra = truncation::residual_vector(f, dag);
        let mut diff = diff::Differentiator::new();
        for a in &ra[2..] {
            for x in &xs {
                if diff.d(dag, *a, *x).is_some() {
                    return None;
                }
            }
        }
        let zero = dag.constant(0.0);
        let mut r0 = vec![Some(ra[0]), Some(ra[1])];
        for x in &xs {
            r0 = dag.replace(&r0, *x, zero);
        }
        let [r0, r1] = [r0[0].expect("some"), r0[1].expect("some")];
        let (a00, a01, a10, a11) = (ra[2], ra[3], ra[4], ra[5]);
        let p = dag.mul(a00, a11);
        let m = dag.mul(a01, a10);
        let det = dag.sub(p, m);
        let inv = dag.recip(det);
        // xi = -A^-1 r0 = -(adj A) r0 / det.
        let t0 = dag.mul(a11, r0);
        let t1 = dag.mul(a01, r1);
        let u = dag.sub(t0, t1);
        let u = dag.mul(u, inv);
        let t2 = dag.mul(a00, r1);
        let t3 = dag.mul(a10, r0);
        let v = dag.sub(t2, t3);
        let v = dag.mul(v, inv);
        Some(vec![dag.neg(u), dag.neg(v)])
    };
    assemble(f, &xs, closed_form, |dag| {
        truncation::residual_vector(f, dag)
    })
}
