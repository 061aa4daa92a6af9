//! The C99 emitter: a [`KernelPlan`] to one header and one source per
//! compiled formulation, plus the shared header `gapsim.h` and the shared
//! runtime `gapsim_runtime.h`/`.c`.
//!
//! ## The emitted files
//!
//! * `gapsim.h` (verbatim, [`COMMON_HEADER`]): the status codes
//!   `enum gapsim_status` (mirroring contact-kernels' `KernelError`), the
//!   limits the wrappers apply (`GAPSIM_DEGENERATE_LENGTH`,
//!   `GAPSIM_XI_M_LIMIT`, the Newton projection's iteration count and
//!   tolerance) and `gapsim_status_name`.
//! * `gapsim_runtime.h` and `gapsim_runtime.c` (verbatim,
//!   [`RUNTIME_HEADER`], [`RUNTIME_SOURCE`]): the shared runtime every
//!   formulation's `.c` file includes and calls: the validation of segments
//!   and of faces, the Newton projections, the projection check (compiled
//!   and linked once, beside the formulations' sources).
//! * `gapsim_{ident}.h`: per formulation, `GAPSIM_{IDENT}_COORDS` and the
//!   public functions `gapsim_{ident}_project` and
//!   `gapsim_{ident}_type1` .. `_type6`, and with a slip
//!   `GAPSIM_{IDENT}_SLIP_COMPONENTS` and `gapsim_{ident}_slip_type1` ..
//!   `_type6`, declared `extern "C"` under C++.
//! * `gapsim_{ident}.c`: the generated kernels as `static` functions (the
//!   residual only when the projection is not in closed form; one
//!   `const double vN = ...;` per instruction, in order, with the same
//!   operation and operand order as the Rust emitter, so that both compute
//!   identical bits when the C compiler does not contract `a * b + c` into
//!   fused multiply-adds: compile with `-ffp-contract=off`), and the public
//!   functions, which do what contact-kernels does around the generated
//!   functions, in the same order, through the runtime: validation, the
//!   projection (closed form inside the kernels, or Newton on the
//!   residual), the kernel, the projection check (finite,
//!   `|xi_m| <= GAPSIM_XI_M_LIMIT`), finite outputs. Segments and faces
//!   differ in their parametric dimension `P` (1 or 2): `xi_s` is passed as
//!   `P` doubles and `xi_m` through `P` pointers (`wrappers`); the kernels
//!   are emitted by the same `function` (vector parameters and unknowns as
//!   `const double *` / `double *`, read by component).
//!
//! ## Invariants
//!
//! * Only `<math.h>` and the emitted headers are included (`sqrt`, `fabs`,
//!   `isfinite`); the files compile cleanly with
//!   `-std=c99 -Wall -Wextra -pedantic`.
//! * Constants are printed with Rust's shortest round-trip representation
//!   (the same text the Rust emitter writes), which a correctly rounding C
//!   compiler reads back to the same bits.
//! * `Powi(a, n)` is the binary powering of LLVM's `powi` (and of
//!   compiler-rt's `__powidf2`), written out in a helper emitted only when
//!   a program uses it.
//! * The limits in [`COMMON_HEADER`] are copies of contact-kernels'
//!   constants (codegen cannot depend on it); contact-kernels' C test
//!   checks that they agree.
//!
//! ## Layout
//!
//! This file holds the emitter and the `.c` file's assembly and comments;
//! `common_header` holds `gapsim.h`, `runtime` the shared runtime,
//! `kernels` the generated functions (one statement per instruction) and
//! `wrappers` the header and public functions of a formulation over its
//! parametric dimension.

use std::fmt::Write as _;

use super::{EmittedFile, Emitter};
use crate::lower::Instr;
use crate::plan::{FormulationPlan, FunctionPlan, InputKind, KernelPlan, KernelSetPlan};

mod common_header;
mod kernels;
mod runtime;
mod wrappers;

pub use common_header::COMMON_HEADER;
use kernels::{POWI, function};
pub use kernels::{body, float_literal};
pub use runtime::{RUNTIME_HEADER, RUNTIME_SOURCE};

/// The C99 emitter (headers and sources checked in under
/// `contact-kernels/c/`).
#[derive(Debug, Clone, Copy, Default)]
pub struct CEmitter;

impl Emitter for CEmitter {
    /// `gapsim.h`, `gapsim_runtime.h` and `gapsim_runtime.c`, then
    /// `gapsim_{ident}.h` and `gapsim_{ident}.c` per compiled formulation,
    /// in plan order.
    fn emit(&self, plan: &KernelPlan) -> Vec<EmittedFile> {
        let mut files = vec![
            EmittedFile {
                name: "gapsim.h".into(),
                contents: COMMON_HEADER.into(),
            },
            EmittedFile {
                name: "gapsim_runtime.h".into(),
                contents: RUNTIME_HEADER.into(),
            },
            EmittedFile {
                name: "gapsim_runtime.c".into(),
                contents: RUNTIME_SOURCE.into(),
            },
        ];
        for f in &plan.formulations {
            let Some(set) = &f.kernels else { continue };
            let (h, c) = (
                wrappers::header(f, set),
                source(f, set, wrappers::wrappers(set)),
            );
            files.push(EmittedFile {
                name: format!("gapsim_{}.h", set.ident),
                contents: h,
            });
            files.push(EmittedFile {
                name: format!("gapsim_{}.c", set.ident),
                contents: c,
            });
        }
        files
    }
}

/// The first line of every generated file of formulation `f`.
fn generated_line(f: &FormulationPlan) -> String {
    format!(
        "/* @generated by gapsim-codegen (C99 emitter) from formulation `{}`. Do not edit. */\n",
        f.name
    )
}

/// `text` as a block comment indented by `indent`: paragraphs (separated
/// by a blank line) re-flowed at 78 columns.
fn comment(text: &str, indent: &str) -> String {
    let mut out = format!("{indent}/*\n");
    for (i, paragraph) in text.split("\n\n").enumerate() {
        if i > 0 {
            let _ = writeln!(out, "{indent} *");
        }
        // Re-flowed at 78 columns (a longer word stays whole).
        let paragraph = paragraph.replace("*/", "* /");
        let mut current = String::new();
        for word in paragraph.split_whitespace() {
            if !current.is_empty() && indent.len() + 3 + current.len() + 1 + word.len() > 78 {
                let _ = writeln!(out, "{indent} * {current}");
                current.clear();
            }
            if !current.is_empty() {
                current.push(' ');
            }
            current.push_str(word);
        }
        let _ = writeln!(out, "{indent} * {current}");
    }
    let _ = writeln!(out, "{indent} */");
    out
}

/// The name of the implicit unknown's in/out argument of `k`.
fn k_implicit(set: &KernelSetPlan, k: &FunctionPlan) -> String {
    k.inputs
        .iter()
        .find(|i| i.kind == InputKind::ImplicitInOut)
        .map_or_else(|| set.signature.implicit().to_owned(), |i| i.name.clone())
}

/// The source of one formulation: the generated kernels (static), the
/// wrapper logic (static) and the public functions.
fn source(f: &FormulationPlan, set: &KernelSetPlan, wrappers: String) -> String {
    let mut out = generated_line(f);
    out.push_str(&comment(
        &format!(
            "gapsim_{}.c: the `{}` kernels, generated from the same instruction list as \
the Rust kernels (one statement per instruction, same operations in the same \
order). Compile with -ffp-contract=off: a fused multiply-add would change the \
last bits.",
            set.ident, f.name
        ),
        "",
    ));
    let _ = write!(
        out,
        "#include <math.h>\n\n#include \"gapsim_{}.h\"\n#include \"gapsim_runtime.h\"\n\n",
        set.ident
    );
    // The residual serves only the Newton projection: with the projection
    // in closed form it would be an unused static function.
    let residual = (!set.closed_form_projection).then_some(&set.residual);
    let functions = residual
        .into_iter()
        .chain([&set.gap])
        .chain(&set.kernels)
        .chain(&set.slips)
        .collect::<Vec<_>>();
    if functions.iter().any(|k| {
        k.program
            .instrs
            .iter()
            .any(|i| matches!(i, Instr::Powi(..)))
    }) {
        out.push_str(POWI);
    }
    for k in &functions {
        out.push_str(&function(k));
        out.push('\n');
    }
    out.push_str(&wrappers);
    out
}
