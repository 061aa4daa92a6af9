//! The configurations the verifier checks a formulation on: the
//! `gapsim-families` workspace crate (seeded random configurations and the
//! hard families of two-node and 3-node segment pairs), re-exported here so
//! that the verifier, `gapsim verify`, `tests/kernels_ad.rs` and
//! contact-kernels' C comparison test (`contact-kernels/tests/c_kernels.rs`,
//! which cannot depend on this crate) draw from one generator.

pub use gapsim_families::*;
