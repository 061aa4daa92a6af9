//! gapsim's symbolic engine: contact formulations in, specialised Rust
//! kernels for the gap and its truncated derivatives out.
//!
//! The pipeline runs in one direction:
//!
//! ```text
//! formulation file --syn--> formulation::Formulation (expressions in a hash-consed expr::Dag)
//!   --> truncation::derive (entity jets (jet.rs), implicit xi_m, one row of truncation::TYPES)
//!   --> closed-form projection substituted when r(q, xi) is affine in xi
//!   --> lower::Program (relative coordinates, dead-code removal, CSE, instruction list)
//!   --> emit (quote! + prettyplease) --> kernels.rs
//! ```
//!
//! ```
//! let text = std::fs::read_to_string(concat!(
//!     env!("CARGO_MANIFEST_DIR"),
//!     "/../contact-kernels/formulations/slave-normal.rs"
//! ))?;
//! let src = codegen::Source { name: "slave-normal".into(), text, compiled: true };
//! let out = codegen::generate(&[src])?;
//! assert!(out.code.contains("fn slave_normal_type6"));
//! let t6 = out.reports.iter().find(|r| r.kernel == "slave_normal_type6").unwrap();
//! assert!(t6.ops.total() > 0);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
#![warn(missing_docs)]

pub mod diff;
pub mod emit;
pub mod expr;
pub mod formulation;
pub mod jet;
pub mod lower;
pub mod truncation;

use quote::{format_ident, quote};

pub use formulation::Formulation;
pub use lower::{OpCount, Program};
pub use truncation::{EntityOrder, TYPES};

/// Errors of the generator: problems in a formulation file.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The formulation file is malformed.
    #[error("{file}:{line}:{column}: {message}")]
    Formulation {
        /// The file.
        file: String,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// What is wrong.
        message: String,
    },
    /// The formulation does not fit the truncation table.
    #[error("{file}: {message}")]
    Truncation {
        /// The file.
        file: String,
        /// What is wrong.
        message: String,
    },
}

/// One formulation file to generate from.
#[derive(Debug, Clone)]
pub struct Source {
    /// The formulation name (file stem, e.g. `slave-normal`).
    pub name: String,
    /// The file's text.
    pub text: String,
    /// Whether to emit its kernels (otherwise only its enum variant exists
    /// and looking it up at run time reports it as not compiled).
    pub compiled: bool,
}

/// The cost of one generated kernel.
#[derive(Debug, Clone)]
pub struct KernelReport {
    /// The formulation.
    pub formulation: String,
    /// The generated function's name.
    pub kernel: String,
    /// Its operation count.
    pub ops: OpCount,
}

/// The generated source and per-kernel costs.
#[derive(Debug, Clone)]
pub struct Generated {
    /// The formatted Rust source (to be `include!`d by contact-kernels).
    pub code: String,
    /// One report per generated kernel.
    pub reports: Vec<KernelReport>,
}

/// Coordinates replaced by zero: slave node 1 is the origin of the relative
/// coordinates the kernels receive.
const ZERO_COORDS: [usize; 2] = [0, 1];

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
    /// Per type (1..=6): outputs `[g, grad(8), packed upper hess(36)]` (plus
    /// `xi_m` when affine), and whether any Hessian entry survives.
    pub kernels: Vec<(Program, bool)>,
}

/// Derives and lowers every program of a formulation.
pub fn programs(f: &Formulation) -> Result<FormulationPrograms, Error> {
    let lower = |dag: &expr::Dag, outs: &[Option<expr::Id>]| {
        Program::lower(dag, outs, &f.coords, &ZERO_COORDS, f.param, f.implicit.sym)
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
    let residual = lower(&dag, &[Some(r), Some(r_xi)]);
    let g = truncation::gap_value(f, &mut dag)?;
    let outs = finish(&mut dag, vec![Some(g)]);
    let gap = lower(&dag, &outs);
    let mut kernels = Vec::new();
    for row in TYPES {
        // A fresh DAG per type: nothing of another type's chains leaks in.
        let mut dag = f.dag.clone();
        let k = truncation::derive(f, &mut dag, row)?;
        let mut outs = vec![Some(k.gap)];
        outs.extend(k.grad);
        outs.extend(k.hess);
        let outs = finish(&mut dag, outs);
        kernels.push((lower(&dag, &outs), k.has_hessian()));
    }
    Ok(FormulationPrograms {
        affine,
        residual,
        gap,
        kernels,
    })
}

/// Generates the kernels source for all `sources`.
pub fn generate(sources: &[Source]) -> Result<Generated, Error> {
    let mut reports = Vec::new();
    let mut items = Vec::new();
    let mut variants = Vec::new();
    let mut names = Vec::new();
    let mut docs = Vec::new();
    let mut arms = Vec::new();
    let (d, xi_s, xi_m, xi, xi_in) = (
        format_ident!("d"),
        format_ident!("xi_s"),
        format_ident!("xi_m"),
        format_ident!("xi"),
        format_ident!("xi_in"),
    );
    for src in sources {
        let f = Formulation::parse(&src.name, &src.text)?;
        let variant = emit::camel(&src.name);
        let name = &src.name;
        let doc = if f.doc.is_empty() {
            format!(" The `{name}` formulation.")
        } else {
            format!(" {}", f.doc.replace('\n', "\n "))
        };
        variants.push(quote!(#[doc = #doc] #variant,));
        names.push(quote!(Formulation::#variant => #name,));
        let doc_text = f.doc.clone();
        docs.push(quote!(Formulation::#variant => #doc_text,));
        if !src.compiled {
            arms.push(quote!(Formulation::#variant => None,));
            continue;
        }
        let p = programs(&f)?;
        let snake = emit::snake(&src.name);
        let set = format_ident!("{}", snake.to_string().to_uppercase());
        arms.push(quote!(Formulation::#variant => Some(&#set),));

        let res_fn = format_ident!("{}_residual", snake);
        let res_body = emit::body(&p.residual, &d, &xi_s, &xi);
        let (r, r_xi) = (
            emit::output(p.residual.outputs[0]),
            emit::output(p.residual.outputs[1]),
        );
        let res_doc = format!(
            " `[r, dr/dxi]` of the `{name}` projection at `xi`.{}",
            emit::ops_doc(&p.residual.op_count())
        );
        reports.push(KernelReport {
            formulation: name.clone(),
            kernel: res_fn.to_string(),
            ops: p.residual.op_count(),
        });
        items.push(quote! {
            #[doc = #res_doc]
            pub(crate) fn #res_fn(#d: &[f64; 8], #xi_s: f64, #xi: f64) -> [f64; 2] {
                #res_body
                [#r, #r_xi]
            }
        });

        // Kernels take `xi_m: &mut f64`: the converged projection on input
        // (Newton formulations), the projection used on output.
        let affine = p.affine;
        let xi_io = |prog: &Program| {
            if affine {
                let x = emit::output(*prog.outputs.last().expect("xi_m output"));
                (quote!(), quote!(*#xi_m = #x;))
            } else {
                (quote!(let #xi_in = *#xi_m;), quote!())
            }
        };
        let projection_doc = if affine {
            " The projection is solved in closed form inside (the residual is affine in `xi`); `xi_m` receives it."
        } else {
            " `xi_m` holds the converged projection."
        };

        let gap_fn = format_ident!("{}_gap", snake);
        let gap_body = emit::body(&p.gap, &d, &xi_s, &xi_in);
        let g = emit::output(p.gap.outputs[0]);
        let (xi_read, xi_write) = xi_io(&p.gap);
        let gap_doc = format!(
            " The `{name}` gap.{projection_doc}{}",
            emit::ops_doc(&p.gap.op_count())
        );
        reports.push(KernelReport {
            formulation: name.clone(),
            kernel: gap_fn.to_string(),
            ops: p.gap.op_count(),
        });
        items.push(quote! {
            #[doc = #gap_doc]
            pub(crate) fn #gap_fn(#d: &[f64; 8], #xi_s: f64, #xi_m: &mut f64) -> f64 {
                #xi_read
                #gap_body
                #xi_write
                #g
            }
        });

        let mut kernel_refs = Vec::new();
        let mut op_lits = Vec::new();
        for (t, (prog, has_hess)) in p.kernels.iter().enumerate() {
            let kfn = format_ident!("{}_type{}", snake, t + 1);
            let ops = prog.op_count();
            reports.push(KernelReport {
                formulation: name.clone(),
                kernel: kfn.to_string(),
                ops,
            });
            op_lits.push(emit::ops_literal(&ops));
            let orders = TYPES[t].map(|o| o.name().to_lowercase()).join(", ");
            let kdoc = format!(
                " `{name}`, type {} (xi_m, x_ms, n: {orders}): gap, gradient{}.{}",
                t + 1,
                if *has_hess {
                    " and Hessian"
                } else {
                    " (no second-order term)"
                },
                emit::ops_doc(&ops)
            );
            let body = emit::body(prog, &d, &xi_s, &xi_in);
            let g = emit::output(prog.outputs[0]);
            let store = emit::store_derivatives(prog, 1, *has_hess);
            let (xi_read, xi_write) = xi_io(prog);
            if *has_hess {
                kernel_refs.push(quote!(Kernel::Hessian(#kfn)));
                items.push(quote! {
                    #[doc = #kdoc]
                    pub(crate) fn #kfn(#d: &[f64; 8], #xi_s: f64, #xi_m: &mut f64, grad: &mut [f64; 8], hess: &mut [[f64; 8]; 8]) -> f64 {
                        #xi_read
                        #body
                        #store
                        #xi_write
                        #g
                    }
                });
            } else {
                kernel_refs.push(quote!(Kernel::Gradient(#kfn)));
                items.push(quote! {
                    #[doc = #kdoc]
                    pub(crate) fn #kfn(#d: &[f64; 8], #xi_s: f64, #xi_m: &mut f64, grad: &mut [f64; 8]) -> f64 {
                        #xi_read
                        #body
                        #store
                        #xi_write
                        #g
                    }
                });
            }
        }
        // The projection kernel: the gap kernel, plus one residual
        // evaluation per Newton iteration when not in closed form.
        let mut proj_ops = p.gap.op_count();
        if !affine {
            let rops = p.residual.op_count();
            proj_ops.add += rops.add;
            proj_ops.mul += rops.mul;
            proj_ops.div += rops.div;
            proj_ops.sqrt += rops.sqrt;
            proj_ops.neg += rops.neg;
        }
        let proj_ops = emit::ops_literal(&proj_ops);
        let set_doc = format!(" The kernels of `{name}`.");
        items.push(quote! {
            #[doc = #set_doc]
            static #set: KernelSet = KernelSet {
                closed_form_projection: #affine,
                residual: #res_fn,
                gap: #gap_fn,
                kernels: [#(#kernel_refs),*],
                ops: [#(#op_lits),*],
                projection_ops: #proj_ops,
            };
        });
    }
    let count = proc_macro2::Literal::usize_unsuffixed(sources.len());
    let all = sources.iter().map(|s| emit::camel(&s.name));
    let rows = TYPES.iter().map(|row| {
        let r = row.map(|o| format_ident!("{}", o.name()));
        quote!([#(EntityOrder::#r),*])
    });
    let tokens = quote! {
        /// A contact formulation: one per file in `contact-kernels/formulations/`.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum Formulation { #(#variants)* }

        impl Formulation {
            /// Every formulation (compiled in or not).
            pub const ALL: [Formulation; #count] = [#(Formulation::#all),*];

            /// The formulation's name (its file stem).
            pub fn name(self) -> &'static str {
                match self { #(#names)* }
            }

            /// The formulation file's documentation.
            pub fn doc(self) -> &'static str {
                match self { #(#docs)* }
            }
        }

        /// The truncation table: `[xi_m, x_ms, n]` orders of types 1..=6.
        pub(crate) const TRUNCATION: [[EntityOrder; 3]; 6] = [#(#rows),*];

        /// The kernels of a formulation, if compiled in.
        pub(crate) fn kernel_set(f: Formulation) -> Option<&'static KernelSet> {
            match f { #(#arms)* }
        }

        #(#items)*
    };
    let code = format!(
        "// @generated by gapsim-codegen from contact-kernels/formulations/*.rs. Do not edit.\n\n{}",
        emit::format_file(tokens)
    );
    Ok(Generated { code, reports })
}
