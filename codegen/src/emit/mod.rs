//! Emitters: a [`KernelPlan`] in, the source files of one target language
//! out.
//!
//! An emitter reads only the plan (names, documentation, inputs and outputs
//! by name and length, instruction lists, op counts); it knows nothing of
//! formulations or expressions. [`rust::RustEmitter`] writes the one module
//! the contact-kernels crate `include!`s; [`c::CEmitter`] writes C99
//! headers and sources (checked in under `contact-kernels/c/`);
//! [`lanes::LanesEmitter`] writes the same kernels over 4 points at a time
//! (SIMD lanes) for the batched evaluation. A new
//! target is a new file here implementing [`Emitter`].
//!
//! Emitters must preserve the instruction list exactly: one statement per
//! instruction, in order, with the same operation and operand order, so
//! that every target computes bit-identical results.

use crate::plan::KernelPlan;

pub mod c;
mod frame;
pub mod lanes;
pub mod rust;

pub use c::CEmitter;
pub use lanes::LanesEmitter;
pub use rust::RustEmitter;

/// One generated file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct EmittedFile {
    /// Its file name (no directory), e.g. `kernels.rs`.
    pub name: String,
    /// Its complete contents.
    pub contents: String,
}

/// Writes a [`KernelPlan`] as source files.
pub trait Emitter {
    /// The complete generated files for `plan`, in a fixed order (file
    /// names are unique).
    fn emit(&self, plan: &KernelPlan) -> Vec<EmittedFile>;
}
