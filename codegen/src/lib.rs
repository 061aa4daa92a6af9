//! gapsim's symbolic engine: contact formulations in, specialised kernels
//! for the gap and its truncated derivatives out (Rust for contact-kernels,
//! C99 for everyone else: [`generate_c`]).
//!
//! The pipeline runs in one direction:
//!
//! ```text
//! formulation file --syn--> formulation::Formulation (expressions in a hash-consed expr::Dag,
//!                           signature::Signature from `inputs!`: points, parameters, sizes)
//!   --> truncation::derive (entity jets (jet.rs), implicit xi_m, one row of truncation::TYPES)
//!   --> closed-form projection substituted when r(q, xi) is affine in xi   (programs.rs)
//!   --> lower::Program (relative coordinates, dead-code removal, CSE, instruction list)
//!   --> plan::KernelPlan (functions: inputs/outputs by name and length, programs, op counts)
//!   --> emit::Emitter (emit::rust: quote! + prettyplease) --> kernels.rs
//!                     (emit::c: C99)                        --> gapsim.h, gapsim_{formulation}.h/.c
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
pub mod invariance;
pub mod jet;
pub mod lower;
pub mod plan;
pub mod programs;
pub mod signature;
pub mod truncation;

pub use emit::{EmittedFile, Emitter};
pub use formulation::Formulation;
pub use lower::{OpCount, Program};
pub use plan::KernelPlan;
pub use programs::{FormulationPrograms, programs};
pub use signature::Signature;
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
    /// The formulation does not fit the generator (the truncation table,
    /// translation invariance, its name), or its kernels would hold a
    /// non-finite constant.
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

/// Generates the Rust kernels source for all `sources`: parse, derive and
/// lower ([`programs()`]), describe ([`KernelPlan`]), emit
/// ([`emit::RustEmitter::source`]).
pub fn generate(sources: &[Source]) -> Result<Generated, Error> {
    let plan = KernelPlan::build(sources)?;
    let code = emit::RustEmitter.source(&plan);
    Ok(Generated {
        code,
        reports: reports(&plan),
    })
}

/// Generates the files of `emitter` for all `sources`: parse, derive and
/// lower ([`programs()`]), describe ([`KernelPlan`]), emit.
pub fn generate_with(
    sources: &[Source],
    emitter: &dyn Emitter,
) -> Result<Vec<emit::EmittedFile>, Error> {
    Ok(emitter.emit(&KernelPlan::build(sources)?))
}

/// Generates the C99 kernels for all compiled `sources` ([`emit::CEmitter`]):
/// `gapsim.h`, the shared runtime (`gapsim_runtime.h`, `gapsim_runtime.c`),
/// then a header and a source per formulation.
///
/// ```
/// let text = std::fs::read_to_string(concat!(
///     env!("CARGO_MANIFEST_DIR"),
///     "/../contact-kernels/formulations/slave-normal.rs"
/// ))?;
/// let src = codegen::Source { name: "slave-normal".into(), text, compiled: true };
/// let files = codegen::generate_c(&[src])?;
/// let names: Vec<_> = files.iter().map(|f| f.name.as_str()).collect();
/// assert_eq!(
///     names,
///     [
///         "gapsim.h",
///         "gapsim_runtime.h",
///         "gapsim_runtime.c",
///         "gapsim_slave_normal.h",
///         "gapsim_slave_normal.c"
///     ]
/// );
/// assert!(files[4].contents.contains("int gapsim_slave_normal_type6("));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn generate_c(sources: &[Source]) -> Result<Vec<emit::EmittedFile>, Error> {
    generate_with(sources, &emit::CEmitter)
}

/// One report per generated function, in emission order.
pub fn reports(plan: &KernelPlan) -> Vec<KernelReport> {
    let mut out = Vec::new();
    for f in &plan.formulations {
        let Some(set) = &f.kernels else { continue };
        let functions = [&set.residual, &set.gap].into_iter().chain(&set.kernels);
        out.extend(functions.map(|k| KernelReport {
            formulation: f.name.clone(),
            kernel: k.name.clone(),
            ops: k.ops,
        }));
    }
    out
}
