//! A 2D and 3D geometrically nonlinear finite-element solver with
//! Lagrange-multiplier contact (segment-to-segment in 2D, face-to-face in
//! 3D) whose gap derivatives come from the generated kernels of
//! `contact-kernels`.
//!
//! * Solid: total-Lagrangian 4-node quadrilaterals (2x2 Gauss) and 3-node
//!   triangles (one point) in 2D (plane stress or plane strain, unit
//!   thickness), 8-node hexahedra (2x2x2 Gauss) and 4-node tetrahedra (one
//!   point) in 3D, mixed in one mesh, St Venant–Kirchhoff or small-strain
//!   linear elasticity ([`element`], [`material`]).
//! * Contact: Gauss (or segmented) integration on the slave facets in the
//!   reference configuration, multipliers at slave nodes, persistent or
//!   unilateral ([`contact`]); one [`model::ContactPair`] over the
//!   dimension, whose facets are segments in 2D and tri3/quad4 faces in 3D
//!   ([`model::SurfaceDim`]).
//! * Approximation: Types 1–6 freeze the gap's second-order Taylor expansion
//!   at each step start; the complete formulation re-projects and evaluates
//!   the exact kernel every iteration ([`Method`]).
//! * Solution: Newton–Raphson per load step with bisection cut-backs
//!   ([`newton`]), sparse direct solvers with symbolic reuse behind the
//!   [`linear::LinearSolver`] seam ([`linear`]: faer's LU, the default, and
//!   a supernodal LDLᵀ).
//!
//! One code path serves both dimensions, generic over `const D: usize`;
//! what differs between them are traits of the type `Dim<D>`
//! ([`model::SurfaceDim`], [`dim::SpaceDim`], [`scene::SceneDim`],
//! [`report::ContactTable`]). [`solve`] takes the dimension of the scene:
//! `solve::<2>` or `solve::<3>` ([`Scene::dimension`] says which).
//!
//! The modules, bottom up (the layers of `docs/architecture.md`, which
//! `solver/tests/layers.rs` checks: a module imports nothing from a layer
//! above its own): [`ids`] (typed indices), [`amplitude`], [`meminfo`] (the
//! memory the system has free), [`linear`] (the sparse solvers) and
//! [`options`] (what a solve is asked to do; modules
//! import it from there, not from the crate root); [`element`] (the solid
//! elements, kinematics and [`material`]), [`mesh`], [`model`] (the discrete
//! problem); [`contact`] (the contact element), [`dim`] (the seam over the
//! dimension), [`assembly`] (one Newton system), [`memory`] and
//! [`solution`] (what a solve returns); [`scene`] (builds a model from
//! TOML); [`monitor`] and the error type; [`newton`] (the load schedule and
//! the iterations), which fills in the solution; [`report`] (writes a
//! solution out: `.vtu`, `contact.csv`, `reactions.csv`, atomically).
//!
//! ```no_run
//! use solver::{Scene, SolveOptions, solve};
//!
//! let scene = Scene::from_toml_str(solver::scenes::STACKED_CANTILEVER, "stacked-cantilever.toml")?;
//! let solution = solve::<2>(&scene, &SolveOptions::from_scene(&scene))?;
//! println!("strain energy {:.6}", solution.strain_energy);
//! # Ok::<(), solver::SolverError>(())
//! ```
#![warn(missing_docs)]
// Index loops mirror the component formulas; negated comparisons
// (`!(x > 0.0)`) deliberately reject NaN as well.
#![allow(clippy::needless_range_loop, clippy::neg_cmp_op_on_partial_ord)]

pub mod amplitude;
pub mod assembly;
pub mod contact;
pub mod dim;
pub mod element;
mod error;
pub mod ids;
pub mod linear;
pub use element::material;
pub mod meminfo;
pub mod memory;
pub mod mesh;
pub mod model;
pub mod monitor;
pub mod newton;
pub mod options;
mod par;
pub mod partition;
pub mod report;
pub mod scene;
pub mod solution;
pub mod system;

#[cfg(test)]
mod tests;
#[cfg(test)]
mod testutil;

pub use contact_kernels::{ApproxType, Formulation, KernelError};
pub use dim::SpaceDim;
pub use error::SolverError;
pub use linear::LinearSolverKind;
pub use material::{Kinematics, Material, PlaneModel};
pub use mesh::{Mesh, Side};
pub use model::{ContactMode, Model};
pub use model::{Dim, SurfaceDim};
pub use options::{
    DEFAULT_REGULARIZATION, ExpansionPoint, Method, ParseExpansionPointError, ParseMethodError,
    SolveOptions,
};
pub use scene::{Scene, SceneDim, SceneError};
pub use solution::{
    AccuracyHalving, ContactPointId, ContactPointReport, Cutback, CutbackReason, KernelCounts,
    Solution, State, StepRecord, Timings,
};

/// Scenes shipped with the solver.
pub mod scenes {
    /// The paper scene, `scenes/stacked-cantilever.toml` (docs/conventions.md, "The
    /// paper scene").
    pub const STACKED_CANTILEVER: &str = include_str!("../../scenes/stacked-cantilever.toml");
}

/// Solves a scene of dimension `D` (`solve::<2>` of a 2D scene,
/// `solve::<3>` of a 3D one; the other dimension is an error naming the
/// scene's first body).
pub fn solve<const D: usize>(
    scene: &Scene,
    options: &SolveOptions,
) -> Result<Solution<D>, SolverError>
where
    Dim<D>: SceneDim<D>,
{
    solve_monitored(scene, options, &monitor::Silent)
}

/// Solves a model (e.g. one built by hand from a [`Mesh`]) of 2 or 3
/// dimensions.
pub fn solve_model<const D: usize>(
    model: &Model<D>,
    options: &SolveOptions,
) -> Result<Solution<D>, SolverError>
where
    Dim<D>: SpaceDim<D>,
{
    solve_model_monitored(model, options, &monitor::Silent)
}

/// [`solve`], reporting to `monitor` and stopping when it asks
/// ([`monitor`]). A model and first factorisation that cannot fit in the
/// available memory are refused before they are allocated ([`memory`]).
pub fn solve_monitored<const D: usize>(
    scene: &Scene,
    options: &SolveOptions,
    monitor: &dyn monitor::Monitor,
) -> Result<Solution<D>, SolverError>
where
    Dim<D>: SceneDim<D>,
{
    let model = scene.build_model::<D>()?;
    solve_model_monitored(&model, options, monitor)
}

/// [`solve_model`] with a [`monitor::Monitor`] (see [`solve_monitored`]).
pub fn solve_model_monitored<const D: usize>(
    model: &Model<D>,
    options: &SolveOptions,
    monitor: &dyn monitor::Monitor,
) -> Result<Solution<D>, SolverError>
where
    Dim<D>: SpaceDim<D>,
{
    memory::check_model(model, options.linear)?;
    linear::check_launch(options.linear)?;
    newton::Run::<D, <Dim<D> as SpaceDim<D>>::Contact>::new(model, options, monitor)?.execute()
}
