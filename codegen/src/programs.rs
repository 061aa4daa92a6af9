//! Programs: a parsed formulation derived under every truncation row and
//! lowered to instruction lists (the step between the expression DAG and
//! the kernel plan).
//!
//! Every program loads the relative coordinates, the parameters and the
//! implicit unknown of the formulation's [`crate::signature::Signature`];
//! the output layouts are documented on [`FormulationPrograms`].

use crate::truncation::{self, TYPES};
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
    /// `[r, r_xi]` of the projection at `xi`.
    pub residual: Program,
    /// The gap value (`[g]`, or `[g, xi_m]` when affine).
    pub gap: Program,
    /// Per type (1..=6): outputs `[g, grad(n), packed upper hess(n (n + 1) / 2)]`
    /// (plus `xi_m` when affine; `n` from the formulation's signature), and
    /// whether any Hessian entry survives.
    pub kernels: Vec<(Program, bool)>,
}

/// Derives and lowers every program of a formulation, once its translation
/// invariance is proven ([`crate::invariance::check`]: the lowering takes
/// coordinates relative to the first point).
pub fn programs(f: &Formulation) -> Result<FormulationPrograms, Error> {
    crate::invariance::check(f)?;
    let lower = |dag: &expr::Dag, outs: &[Option<expr::Id>]| {
        finite(f, Program::lower(dag, outs, &f.signature))
    };
    let xi = f.implicit.sym;
    // Closed-form projection when r is affine in xi: xi_m = -r(q, 0) / r_xi(q).
    let closed_form = |dag: &mut expr::Dag| -> Option<expr::Id> {
        let [r, r_xi] = truncation::residual(f, dag);
        if diff::Differentiator::new().d(dag, r_xi, xi).is_some() {
            return None;
        }
        let zero = dag.constant(0.0);
        let r0 = dag.replace(&[Some(r)], xi, zero)[0].expect("some");
        let inv = dag.recip(r_xi);
        let t = dag.mul(r0, inv);
        Some(dag.neg(t))
    };
    // Outputs with the projection solved inside the kernel, when affine.
    let finish = |dag: &mut expr::Dag, outs: Vec<Option<expr::Id>>| -> Vec<Option<expr::Id>> {
        match closed_form(dag) {
            Some(x) => {
                let mut outs = dag.replace(&outs, xi, x);
                outs.push(Some(x));
                outs
            }
            None => outs,
        }
    };
    let mut dag = f.dag.clone();
    let affine = closed_form(&mut dag).is_some();
    let [r, r_xi] = truncation::residual(f, &mut dag);
    let residual = lower(&dag, &[Some(r), Some(r_xi)])?;
    let g = truncation::gap_value(f, &mut dag)?;
    let outs = finish(&mut dag, vec![Some(g)]);
    let gap = lower(&dag, &outs)?;
    let mut kernels = Vec::new();
    for row in TYPES {
        // A fresh DAG per type: nothing of another type's chains leaks in.
        let mut dag = f.dag.clone();
        let k = truncation::derive(f, &mut dag, row)?;
        let has_hessian = k.has_hessian();
        let mut outs = vec![Some(k.gap)];
        outs.extend(k.grad);
        outs.extend(k.hess);
        let outs = finish(&mut dag, outs);
        kernels.push((lower(&dag, &outs)?, has_hessian));
    }
    Ok(FormulationPrograms {
        affine,
        residual,
        gap,
        kernels,
    })
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
