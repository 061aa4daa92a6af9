//! gapsim's symbolic engine: contact formulations in, specialised Rust
//! kernels for the gap and its truncated derivatives out.
//!
//! The pipeline runs in one direction:
//!
//! ```text
//! formulation file --syn--> formulation::Formulation (expressions in a hash-consed expr::Dag)
//!   --> truncation::derive (entity jets, implicit xi_m, one row of truncation::TYPES)
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
    /// `[r, r_xi]` of the projection at `xi`.
    pub residual: Program,
    /// The gap value at `xi_m`.
    pub gap: Program,
    /// Per type (1..=6): outputs `[g, grad(8), packed upper hess(36)]`, and
    /// whether any Hessian entry survives.
    pub kernels: Vec<(Program, bool)>,
}

/// Derives and lowers every program of a formulation.
pub fn programs(f: &Formulation) -> Result<FormulationPrograms, Error> {
    let lower = |dag: &expr::Dag, outs: &[Option<expr::Id>]| {
        Program::lower(dag, outs, &f.coords, &ZERO_COORDS, f.param, f.implicit.sym)
    };
    let mut dag = f.dag.clone();
    let [r, r_xi] = truncation::residual(f, &mut dag);
    let residual = lower(&dag, &[Some(r), Some(r_xi)]);
    let g = truncation::gap_value(f, &mut dag)?;
    let gap = lower(&dag, &[Some(g)]);
    let mut kernels = Vec::new();
    for row in TYPES {
        // A fresh DAG per type: nothing of another type's chains leaks in.
        let mut dag = f.dag.clone();
        let k = truncation::derive(f, &mut dag, row)?;
        let mut outs = vec![Some(k.gap)];
        outs.extend(k.grad);
        outs.extend(k.hess);
        kernels.push((lower(&dag, &outs), k.has_hessian()));
    }
    Ok(FormulationPrograms { residual, gap, kernels })
}

/// Generates the kernels source for all `sources`.
pub fn generate(sources: &[Source]) -> Result<Generated, Error> {
    let mut reports = Vec::new();
    let mut items = Vec::new();
    let mut variants = Vec::new();
    let mut names = Vec::new();
    let mut docs = Vec::new();
    let mut arms = Vec::new();
    let (d, xi_s, xi_m, xi) = (format_ident!("d"), format_ident!("xi_s"), format_ident!("xi_m"), format_ident!("xi"));
    for src in sources {
        let f = Formulation::parse(&src.name, &src.text)?;
        let variant = emit::camel(&src.name);
        let name = &src.name;
        let doc = if f.doc.is_empty() { format!(" The `{name}` formulation.") } else { format!(" {}", f.doc.replace('\n', "\n ")) };
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
        let (r, r_xi) = (emit::output(p.residual.outputs[0]), emit::output(p.residual.outputs[1]));
        let res_doc = format!(" `[r, dr/dxi]` of the `{name}` projection at `xi`.{}", emit::ops_doc(&p.residual.op_count()));
        reports.push(KernelReport { formulation: name.clone(), kernel: res_fn.to_string(), ops: p.residual.op_count() });
        items.push(quote! {
            #[doc = #res_doc]
            pub(crate) fn #res_fn(#d: &[f64; 8], #xi_s: f64, #xi: f64) -> [f64; 2] {
                #res_body
                [#r, #r_xi]
            }
        });

        let gap_fn = format_ident!("{}_gap", snake);
        let gap_body = emit::body(&p.gap, &d, &xi_s, &xi_m);
        let g = emit::output(p.gap.outputs[0]);
        let gap_doc = format!(" The `{name}` gap at `xi_m`.{}", emit::ops_doc(&p.gap.op_count()));
        reports.push(KernelReport { formulation: name.clone(), kernel: gap_fn.to_string(), ops: p.gap.op_count() });
        items.push(quote! {
            #[doc = #gap_doc]
            pub(crate) fn #gap_fn(#d: &[f64; 8], #xi_s: f64, #xi_m: f64) -> f64 {
                #gap_body
                #g
            }
        });

        let mut kernel_refs = Vec::new();
        let mut op_lits = Vec::new();
        for (t, (prog, has_hess)) in p.kernels.iter().enumerate() {
            let kfn = format_ident!("{}_type{}", snake, t + 1);
            let ops = prog.op_count();
            reports.push(KernelReport { formulation: name.clone(), kernel: kfn.to_string(), ops });
            op_lits.push(emit::ops_literal(&ops));
            let orders = TYPES[t].map(|o| o.name().to_lowercase()).join(", ");
            let kdoc = format!(
                " `{name}`, type {} (xi_m, x_ms, n: {orders}): gap, gradient{}.{}",
                t + 1,
                if *has_hess { " and Hessian" } else { " (no second-order term)" },
                emit::ops_doc(&ops)
            );
            let body = emit::body(prog, &d, &xi_s, &xi_m);
            let g = emit::output(prog.outputs[0]);
            let store = emit::store_derivatives(prog, 1, *has_hess);
            if *has_hess {
                kernel_refs.push(quote!(Kernel::Hessian(#kfn)));
                items.push(quote! {
                    #[doc = #kdoc]
                    pub(crate) fn #kfn(#d: &[f64; 8], #xi_s: f64, #xi_m: f64, grad: &mut [f64; 8], hess: &mut [[f64; 8]; 8]) -> f64 {
                        #body
                        #store
                        #g
                    }
                });
            } else {
                kernel_refs.push(quote!(Kernel::Gradient(#kfn)));
                items.push(quote! {
                    #[doc = #kdoc]
                    pub(crate) fn #kfn(#d: &[f64; 8], #xi_s: f64, #xi_m: f64, grad: &mut [f64; 8]) -> f64 {
                        #body
                        #store
                        #g
                    }
                });
            }
        }
        let mut proj_ops = p.residual.op_count();
        let gops = p.gap.op_count();
        proj_ops.add += gops.add;
        proj_ops.mul += gops.mul;
        proj_ops.div += gops.div;
        proj_ops.sqrt += gops.sqrt;
        proj_ops.neg += gops.neg;
        let proj_ops = emit::ops_literal(&proj_ops);
        let set_doc = format!(" The kernels of `{name}`.");
        items.push(quote! {
            #[doc = #set_doc]
            static #set: KernelSet = KernelSet {
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
