//! # gapsim
//!
//! Approximate contact constraint formulations for large-displacement
//! structural analysis: generated gap-derivative kernels and a 2D
//! finite-element solver that uses them.
//!
//! This crate is a thin facade over the workspace's libraries, so that a
//! user depends on one crate:
//!
//! * [`contact_kernels`] — the generated gap, gradient and Hessian kernels
//!   for 2D segment-to-segment contact (both formulations, approximation
//!   Types 1–6, a value-only projection kernel), behind a small typed API.
//! * [`solver`] — the geometrically nonlinear finite-element solver
//!   (total-Lagrangian quadrilaterals, Lagrange-multiplier contact, Newton
//!   per load step) that calls the kernels.
//!
//! The `gapsim` binary built from this package is the command-line front
//! end (`gapsim kernel ...` evaluates one kernel and prints JSON).
//!
//! ```
//! use gapsim::contact_kernels::{evaluate, ApproxType, Formulation};
//!
//! let q = [0.0, 1.0, 2.0, 1.1, 2.1, 0.9, -0.1, 1.0];
//! let out = evaluate(Formulation::SlaveNormal, ApproxType::Type6, &q, 0.3)?;
//! assert!((out.gap - 0.129090446096668).abs() < 1e-12);
//! # Ok::<(), gapsim::contact_kernels::KernelError>(())
//! ```
#![warn(missing_docs)]

pub use contact_kernels;
pub use solver;

pub mod hertz;
pub mod stability;
pub mod study;
pub mod timing;
pub mod verify;
