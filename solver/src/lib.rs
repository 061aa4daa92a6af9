//! A 2D geometrically nonlinear finite-element solver with
//! Lagrange-multiplier, segment-to-segment contact whose gap derivatives come
//! from the generated kernels of `contact-kernels`.
//!
//! * Solid: total-Lagrangian 4-node quadrilaterals, St Venant–Kirchhoff,
//!   2x2 Gauss, plane stress or plane strain, unit thickness
//!   ([`quad`], [`material`]).
//! * Contact: 2-point (or `n`-point) Gauss on the slave segments in the
//!   reference configuration, multipliers at slave nodes, persistent or
//!   unilateral ([`contact`]).
//! * Approximation: Types 1–6 freeze the gap's second-order Taylor expansion
//!   at each step start; the complete formulation re-projects and evaluates
//!   the exact kernel every iteration ([`Method`]).
//! * Solution: Newton–Raphson per load step with bisection cut-backs
//!   ([`newton`]), sparse LU from faer with symbolic reuse ([`linear`]).
//!
//! ```no_run
//! use solver::{Scene, SolveOptions, solve};
//!
//! let scene = Scene::from_toml_str(solver::scenes::STACKED_CANTILEVER, "stacked-cantilever.toml")?;
//! let solution = solve(&scene, &SolveOptions::from_scene(&scene))?;
//! println!("strain energy {:.6}", solution.strain_energy);
//! # Ok::<(), solver::SolverError>(())
//! ```
#![warn(missing_docs)]
// Index loops mirror the component formulas; negated comparisons
// (`!(x > 0.0)`) deliberately reject NaN as well.
#![allow(clippy::needless_range_loop, clippy::neg_cmp_op_on_partial_ord)]

pub mod assembly;
pub mod contact;
mod error;
pub mod linear;
pub mod material;
pub mod mesh;
pub mod model;
pub mod newton;
pub mod quad;
pub mod scene;
pub mod solution;
pub mod vtk;

#[cfg(test)]
mod tests;
#[cfg(test)]
mod testutil;

pub use contact_kernels::{ApproxType, Formulation, KernelError};
pub use error::SolverError;
pub use material::{Material, PlaneModel};
pub use mesh::{Mesh, Side};
pub use model::{ContactMode, Model};
pub use scene::{Scene, SceneError};
pub use solution::{
    ContactPointId, ContactPointReport, Cutback, CutbackReason, KernelCounts, Solution, State,
    StepRecord, Timings,
};

/// Scenes shipped with the solver.
pub mod scenes {
    /// The paper scene, `scenes/stacked-cantilever.toml` (design.md, "The
    /// paper scene").
    pub const STACKED_CANTILEVER: &str = include_str!("../../scenes/stacked-cantilever.toml");
}

/// How the contact gap is treated within a load step.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Method {
    /// Re-projection and the exact (Type 6) kernel at every Newton
    /// iteration.
    Complete,
    /// The type's Taylor expansion frozen at each step start.
    Approx(ApproxType),
}

impl Method {
    /// The complete formulation followed by the six types.
    pub const ALL: [Method; 7] = [
        Method::Complete,
        Method::Approx(ApproxType::Type1),
        Method::Approx(ApproxType::Type2),
        Method::Approx(ApproxType::Type3),
        Method::Approx(ApproxType::Type4),
        Method::Approx(ApproxType::Type5),
        Method::Approx(ApproxType::Type6),
    ];
}

impl std::fmt::Display for Method {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Method::Complete => f.write_str("complete"),
            Method::Approx(t) => write!(f, "{}", t.index()),
        }
    }
}

/// Error parsing a [`Method`].
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown method `{0}` (expected `complete` or an approximation type 1..6)")]
pub struct ParseMethodError(pub String);

impl std::str::FromStr for Method {
    type Err = ParseMethodError;
    /// `"complete"`, or `"1"`..`"6"` (also `"type3"`).
    fn from_str(s: &str) -> Result<Method, ParseMethodError> {
        let t = s.trim();
        if t.eq_ignore_ascii_case("complete") {
            return Ok(Method::Complete);
        }
        t.parse::<ApproxType>()
            .map(Method::Approx)
            .map_err(|_| ParseMethodError(s.to_owned()))
    }
}

/// Options of one solve.
#[derive(Debug, Clone, PartialEq)]
pub struct SolveOptions {
    /// Complete or an approximation type.
    pub method: Method,
    /// Number of equal load steps from 0 to the scene's final load factor.
    pub steps: usize,
    /// Replace every contact pair's formulation.
    pub formulation: Option<Formulation>,
    /// Keep the state after every converged (sub)step in
    /// [`Solution::snapshots`] (plus the initial state).
    pub record_steps: bool,
    /// Newton iterations per attempt.
    pub max_iterations: usize,
    /// Cut-backs (bisections) allowed per scheduled step.
    pub max_cutbacks: usize,
    /// Converged when `|r| <= tolerance * max(1, |f_ext|)`.
    pub tolerance: f64,
    /// Tangent-only multiplier regularisation `delta` (see
    /// [`crate::newton`]); 0 disables it.
    pub regularization: f64,
}

impl Default for SolveOptions {
    fn default() -> Self {
        SolveOptions {
            method: Method::Complete,
            steps: 4,
            formulation: None,
            record_steps: false,
            max_iterations: 30,
            max_cutbacks: 8,
            tolerance: 1e-10,
            regularization: newton::DEFAULT_REGULARIZATION,
        }
    }
}

impl SolveOptions {
    /// The scene's defaults: its method, default step count and Newton
    /// settings.
    pub fn from_scene(scene: &Scene) -> SolveOptions {
        SolveOptions {
            method: scene.loading.method,
            steps: scene.default_steps(),
            formulation: None,
            record_steps: false,
            max_iterations: scene.newton.max_iterations,
            max_cutbacks: scene.newton.max_cutbacks,
            tolerance: scene.newton.tolerance,
            regularization: newton::DEFAULT_REGULARIZATION,
        }
    }
}

/// Solves a scene.
pub fn solve(scene: &Scene, options: &SolveOptions) -> Result<Solution, SolverError> {
    let model = scene.build_model()?;
    solve_model(&model, options)
}

/// Solves a model (e.g. one built by hand from a [`Mesh`]).
pub fn solve_model(model: &Model, options: &SolveOptions) -> Result<Solution, SolverError> {
    newton::Run::new(model, options)?.execute()
}
