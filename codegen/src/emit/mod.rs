//! Emitters: a [`KernelPlan`] in, source text of one target language out.
//!
//! An emitter reads only the plan (names, documentation, inputs and outputs
//! by name and length, instruction lists, op counts); it knows nothing of
//! formulations or expressions. [`rust::RustEmitter`] writes the module the
//! contact-kernels crate `include!`s. A new target (e.g. C99 for #9) is a
//! new file here implementing [`Emitter`].
//!
//! Emitters must preserve the instruction list exactly: one statement per
//! instruction, in order, with the same operation and operand order, so
//! that every target computes bit-identical results.

use crate::plan::KernelPlan;

pub mod rust;

pub use rust::RustEmitter;

/// Writes a [`KernelPlan`] as source text.
pub trait Emitter {
    /// The complete generated source for `plan`.
    fn emit(&self, plan: &KernelPlan) -> String;
}
