//! The options of one solve: the contact [`Method`] and [`SolveOptions`].
//!
//! This module sits low (it imports only the kernel types and
//! [`crate::linear::LinearSolverKind`]): the scene reads its defaults from
//! here (`[newton]`'s keys default to the `DEFAULT_` constants, and
//! `SolveOptions::from_scene` is written in [`crate::scene`]), and the
//! modules that read the options import them from here rather than from
//! the crate root. The defaults are part of the behaviour: changing one
//! changes every result.

use contact_kernels::{ApproxType, Formulation};

use crate::linear::LinearSolverKind;

/// Default of [`SolveOptions::regularization`] (see [`crate::newton`],
/// "Multiplier regularisation").
pub const DEFAULT_REGULARIZATION: f64 = 1e-10;

/// Default of [`SolveOptions::steps`] (a scene's own default is its
/// `[loading]`'s).
pub const DEFAULT_STEPS: usize = 4;

/// Default of [`SolveOptions::tolerance`] and `[newton] tolerance`.
pub const DEFAULT_TOLERANCE: f64 = 1e-10;

/// Default of [`SolveOptions::max_iterations`] and `[newton]
/// max_iterations`.
pub const DEFAULT_MAX_ITERATIONS: usize = 30;

/// Default of [`SolveOptions::max_cutbacks`] and `[newton] max_cutbacks`.
pub const DEFAULT_MAX_CUTBACKS: usize = 8;

/// Default of [`SolveOptions::repair`] and `[newton] repair`.
pub const DEFAULT_REPAIR: bool = true;

/// Default of [`SolveOptions::expand_at`] and `[newton] expand_at`.
pub const DEFAULT_EXPAND_AT: ExpansionPoint = ExpansionPoint::Predictor;

/// Where Types 1–6 take a load step's Taylor expansions (see
/// [`crate::newton`], "Where the expansions are taken").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum ExpansionPoint {
    /// At the converged state the step starts from (the paper's scheme).
    Start,
    /// At the step's secant predictor, where its first Newton solve starts
    /// (the converged state extrapolated along the last increment, when
    /// prescribed displacements move on as they did in the last step);
    /// at the converged state when the step has no predictor.
    #[default]
    Predictor,
}

impl std::fmt::Display for ExpansionPoint {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            ExpansionPoint::Start => "start",
            ExpansionPoint::Predictor => "predictor",
        })
    }
}

/// Error parsing an [`ExpansionPoint`].
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown expansion point `{0}` (expected `start` or `predictor`)")]
pub struct ParseExpansionPointError(pub String);

impl std::str::FromStr for ExpansionPoint {
    type Err = ParseExpansionPointError;
    /// `"start"` or `"predictor"`.
    fn from_str(s: &str) -> Result<ExpansionPoint, ParseExpansionPointError> {
        match s.trim() {
            "start" => Ok(ExpansionPoint::Start),
            "predictor" => Ok(ExpansionPoint::Predictor),
            other => Err(ParseExpansionPointError(other.to_string())),
        }
    }
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
    /// [`crate::Solution::snapshots`] (plus the initial state).
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
    /// The linear solver of the Newton iterations.
    pub linear: LinearSolverKind,
    /// PETSc options of [`LinearSolverKind::Petsc`] (PETSc's syntax, after
    /// its defaults and the `PETSC_OPTIONS` environment; `[newton]
    /// petsc_options`, `--petsc-options`); ignored by the other solvers.
    pub petsc_options: String,
    /// Types 1–6: re-pair at every converged step end and repeat the step
    /// with the new pairing's Taylor expansion when a point changed its
    /// master segment (see [`crate::newton`], "Re-pairing at the step
    /// end"; `[newton] repair`, default [`DEFAULT_REPAIR`] (`true`); the
    /// paper scene sets `false`, the paper's scheme).
    /// On the contact-heavy paper variant at 4 steps repair takes the
    /// final energy error from 3.6e-4 % to 2.0e-2 %, but the final figure
    /// without it is a cancellation: the errors along the way fall from
    /// 0.18 %, 0.15 % and 0.07 % (238 points end on the wrong segment) to
    /// 0.026 %, 0.045 % and 0.016 %.
    pub repair: bool,
    /// Types 1–6: halve a converged step whose largest relative Taylor
    /// remainder exceeds this (adaptive stepping, `[newton]
    /// taylor_tolerance`; default `None`).
    pub taylor_tolerance: Option<f64>,
    /// Types 1–6: where a step's expansions are taken (`[newton]
    /// expand_at`, default [`DEFAULT_EXPAND_AT`], the step's predictor).
    pub expand_at: ExpansionPoint,
}

impl Default for SolveOptions {
    /// The defaults of a scene without `[newton]` settings (the `DEFAULT_`
    /// constants; the linear solver's default kind, no Taylor tolerance).
    fn default() -> Self {
        SolveOptions {
            method: Method::Complete,
            steps: DEFAULT_STEPS,
            formulation: None,
            record_steps: false,
            max_iterations: DEFAULT_MAX_ITERATIONS,
            max_cutbacks: DEFAULT_MAX_CUTBACKS,
            tolerance: DEFAULT_TOLERANCE,
            regularization: DEFAULT_REGULARIZATION,
            linear: LinearSolverKind::default(),
            petsc_options: String::new(),
            repair: DEFAULT_REPAIR,
            taylor_tolerance: None,
            expand_at: DEFAULT_EXPAND_AT,
        }
    }
}

/// Why `formulation` cannot evaluate the solver's contact faces (two-node
/// segments), or `None` when it can: the one wording of the scene reader
/// and of [`crate::Run::new`].
pub fn unsupported_formulation(formulation: Formulation) -> Option<String> {
    let n = formulation.coords()?;
    if n == contact_kernels::PAIR_COORDS {
        return None;
    }
    let kind = match formulation.face_nodes() {
        Some((slave, master)) => {
            format!("3D faces ({slave}-node slave face, {master}-node master face)")
        }
        None => format!("{}-node segments", n / 4),
    };
    Some(format!(
        "formulation `{formulation}` is for {kind}; the solver's contact faces are two-node \
         segments (use slave-normal or closest-point)"
    ))
}
