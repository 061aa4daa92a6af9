//! The solver's error type.
//!
//! [`SolverError`] is the one error a solve returns: data-dependent
//! failures (invalid scene, model or options, no convergence, a singular
//! system, a kernel failure) are values of it, never panics. Indices in it
//! are the plain `usize` of the reports ([`ContactPointId`]).

use contact_kernels::KernelError;

use crate::memory::MemoryError;
use crate::model::ModelError;
use crate::scene::SceneError;
use crate::solution::{ContactPointId, CutbackReason};

/// Why [`crate::solve`] failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SolverError {
    /// The scene could not be read or is invalid.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// The 3D contact pairs cannot be laid out (a `gauss_points` without a
    /// rule, a degenerate slave face, a clipping failure).
    #[error(transparent)]
    FaceLayout(#[from] crate::contact::FaceLayoutError),
    /// The model built from the scene is inconsistent.
    #[error("invalid model: {0}")]
    Model(#[from] ModelError),
    /// An element's reference geometry cannot be computed (its nodes were
    /// moved after its body was added, [`crate::mesh::Mesh::geometry`]).
    #[error("invalid mesh: {0}")]
    Mesh(#[from] crate::mesh::MeshError),
    /// Invalid [`crate::SolveOptions`].
    #[error("invalid solve options: {0}")]
    Options(String),
    /// The method cannot mean what the scene asks (Type 1 on a frictional
    /// pair: its slip is zero within a step). Not a failure of the solve:
    /// the study and the safety map record the run as refused.
    #[error("refused: {0}")]
    NotApplicable(String),
    /// Newton did not converge even after the maximum number of cut-backs.
    #[error(
        "step {step}: no convergence from load factor {load_factor} towards {attempted} after {cutbacks} cut-backs; last failure: {reason}"
    )]
    Diverged {
        /// The scheduled step (1-based).
        step: usize,
        /// The last converged load factor.
        load_factor: f64,
        /// The smallest increment's target that still failed.
        attempted: f64,
        /// Cut-backs performed in this step.
        cutbacks: usize,
        /// The last attempt's failure.
        reason: CutbackReason,
    },
    /// The linear solve still failed after the maximum number of
    /// cut-backs: the system is singular (e.g. a body without enough
    /// supports), or a fallback factorisation did not fit in memory
    /// ([`crate::linear::LinearError`] says which).
    #[error(
        "the linear solve failed at load factor {load_factor} (towards {attempted}, after {cutbacks} cut-backs): {message}"
    )]
    Singular {
        /// The last converged load factor.
        load_factor: f64,
        /// The target of the failing attempt.
        attempted: f64,
        /// Cut-backs performed in this step.
        cutbacks: usize,
        /// faer's message or the non-finite component.
        message: String,
    },
    /// A contact kernel failed at a converged state (where a cut-back cannot
    /// help) or at every cut-back.
    #[error("contact kernel failed at {point} (load factor {load_factor}): {error}")]
    Kernel {
        /// The integration point.
        point: ContactPointId,
        /// The load factor of the state evaluated.
        load_factor: f64,
        /// The kernel's error.
        error: KernelError,
    },
    /// The Newton system would have more equations than its 32-bit triplet
    /// indices hold ([`crate::system::MAX_EQUATIONS`]).
    #[error(
        "the model has {equations} equations (with the node ties it may have), more than the {} a Newton system holds",
        crate::system::MAX_EQUATIONS
    )]
    TooManyEquations {
        /// The free dofs and multipliers, and a bound on the node ties.
        equations: usize,
    },
    /// The model and its first factorisation would need more memory than
    /// is available ([`crate::memory`]: the estimate is a lower bound).
    #[error(transparent)]
    Memory(#[from] MemoryError),
    /// The linear solver cannot run in this process (the `petsc` solver
    /// launched across several MPI ranks, [`crate::linear::check_launch`]),
    /// or refuses its options whatever the step
    /// ([`crate::linear::LinearError::Refused`]: Newton stops at once).
    #[error("linear solver: {0}")]
    Linear(#[from] crate::linear::LinearError),
    /// The [`crate::monitor::Monitor`] asked the solve to stop (Ctrl-C in
    /// `gapsim run`); there is no solution.
    #[error("interrupted at load factor {load_factor} (the last converged state)")]
    Interrupted {
        /// The last converged load factor.
        load_factor: f64,
    },
}
