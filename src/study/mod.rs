//! The paper's study: strain-energy error against load steps, and speed
//! against error, for the complete formulation and every approximation type.
//!
//! For each formulation (the scene's first, then every other compiled one)
//! and each step count `N` of the scene's schedule, the scene is solved with
//! the complete formulation and with Types 1–6. The error of a type is
//!
//! ```text
//! error % = 100 (U_type - U_complete) / U_complete
//! ```
//!
//! with both strain energies at the final load factor and the same `N`.
//! Each solve is repeated [`StudyOptions::repeats`] times; times are the
//! medians (the energies of repeats are identical: the solver is
//! deterministic).
//!
//! A contact-heavy variant of the scene ([`contact_heavy_variant`]: a finer
//! interface with more integration points, same physics) measures what each
//! type saves where contact dominates the cost.
//! If that variant's complete formulation fails (a scene other than the
//! paper's may not converge on the refined interface), the study goes on
//! without it ([`StudyResults::heavy_failure`]).
//!
//! The study runs on any scene with contact (the first pair's formulation
//! first). Besides the energy error, every type's run carries the support
//! reactions' error against the complete formulation at the same step
//! count ([`reactions`], [`Run::reaction_error_percent`]), written to
//! `study-errors.csv` with the cost ratios ([`errors`]); the paper's
//! `study.csv` keeps its columns. A type whose solve fails is recorded
//! ([`Run::failure`]), not fatal; the complete formulation failing stops
//! `gapsim study` ([`StudyError::Reference`]: there is no reference) but is
//! recorded by the safety map ([`safety_map`]), which runs several scenes
//! and classifies each type per scene.

pub mod errors;
pub mod plots;
pub mod reactions;
pub mod report;
pub mod safety_map;

use std::time::Duration;

use contact_kernels::{ApproxType, Formulation};
use solver::contact::ContactSpace;
use solver::scene::Dimension;
use solver::{
    Dim, Method, Scene, SceneDim, Solution, SolveOptions, SolverError, SpaceDim, SurfaceDim,
};

/// What the study reads of a solution of dimension `D` beyond what every
/// dimension has.
pub trait StudyDim<const D: usize>: SceneDim<D> {
    /// The largest `|gap|` over the paired integration points (`None`
    /// where the solution has no per-point report: 3D).
    fn max_abs_gap(solution: &Solution<D>) -> Option<f64>
    where
        Dim<D>: SurfaceDim<D>;
}

impl StudyDim<2> for Dim<2> {
    fn max_abs_gap(solution: &Solution) -> Option<f64> {
        Some(solution.max_abs_gap())
    }
}

impl StudyDim<3> for Dim<3> {
    fn max_abs_gap(_: &Solution<3>) -> Option<f64> {
        None
    }
}

/// The contact-heavy variant's size: solid elements and slave
/// integration points (of the contact element's layout).
fn size<const D: usize>(scene: &Scene) -> Result<(usize, usize), SolverError>
where
    Dim<D>: SceneDim<D>,
{
    let model = scene.build_model::<D>()?;
    let layout = <Dim<D> as SpaceDim<D>>::Contact::build(&model, None)?;
    Ok((model.mesh.elements.len(), layout.point_count()))
}

/// Settings of a study.
#[derive(Debug, Clone)]
pub struct StudyOptions {
    /// Solves per (formulation, method, steps); times are medians.
    pub repeats: usize,
    /// Step counts (default: the scene's `loading.steps`).
    pub steps: Option<Vec<usize>>,
    /// Also study the other compiled formulations.
    pub all_formulations: bool,
    /// Step counts of the contact-heavy variant (empty: skip it).
    pub heavy_steps: Vec<usize>,
    /// Refinement of the contact-heavy variant: elements along the
    /// interface are multiplied by this factor...
    pub heavy_refine: usize,
    /// ...and each slave segment gets this many Gauss points.
    pub heavy_gauss_points: usize,
}

impl Default for StudyOptions {
    fn default() -> Self {
        StudyOptions {
            repeats: 5,
            steps: None,
            all_formulations: true,
            heavy_steps: vec![4, 20],
            heavy_refine: 8,
            heavy_gauss_points: 8,
        }
    }
}

/// Why a study could not be completed.
#[derive(Debug, thiserror::Error)]
pub enum StudyError {
    /// The scene has no contact pair, so there is nothing to study.
    #[error("scene `{0}` has no contact pair: the study compares contact formulations")]
    NoContact(String),
    /// The scene lists no step counts.
    #[error("no step counts to study (scene `loading.steps` is empty)")]
    NoSteps,
    /// The complete formulation failed: there is no reference to compare to.
    #[error("the complete formulation ({formulation}, {steps} steps) failed: {source}")]
    Reference {
        /// Formulation.
        formulation: Formulation,
        /// Step count.
        steps: usize,
        /// The solver's error.
        source: SolverError,
    },
    /// Writing an output file failed.
    #[error("cannot write {path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// The cause.
        source: std::io::Error,
    },
    /// Drawing a plot failed.
    #[error("cannot draw {path}: {message}")]
    Plot {
        /// The file.
        path: String,
        /// The backend's message.
        message: String,
    },
}

/// One solve of the study (medians over repeats).
#[derive(Debug, Clone)]
pub struct Run {
    /// The formulation.
    pub formulation: Formulation,
    /// Complete or a type.
    pub method: Method,
    /// Load steps.
    pub steps: usize,
    /// `None` if the solve failed (see `failure`).
    pub strain_energy: Option<f64>,
    /// Against the complete formulation at the same step count.
    pub error_percent: Option<f64>,
    /// Newton iterations (converged attempts).
    pub newton_iterations: usize,
    /// Types 1–6: Newton iterations of converged attempts a step repeat or
    /// an accuracy halving discarded ([`Solution::repeated_iterations`]).
    pub repeated_iterations: usize,
    /// Cut-backs performed.
    pub cutbacks: usize,
    /// Median wall time of the whole solve.
    pub wall_seconds: f64,
    /// Median time in contact evaluation (kernels, Taylor expansion,
    /// scatter, pairing).
    pub contact_seconds: f64,
    /// Median time in solid assembly.
    pub solid_seconds: f64,
    /// Median time in the linear solver.
    pub solve_seconds: f64,
    /// Kernel evaluations with derivatives.
    pub kernel_evaluations: u64,
    /// Value-only projections.
    pub projections: u64,
    /// Largest |gap| at the final state (exact re-projection).
    pub max_abs_gap: Option<f64>,
    /// Operation count of the kernel the method evaluates per integration
    /// point (Type 6's for complete).
    pub kernel_ops: Option<u32>,
    /// The solver's error, if it failed or refused the method.
    pub failure: Option<String>,
    /// The solver refused the method on this scene
    /// ([`solver::SolverError::NotApplicable`]: Type 1 on a frictional
    /// pair): the type cannot mean what the scene asks, which is not a
    /// failed solve. `failure` holds the reason.
    pub refused: bool,
    /// The reaction error against the complete formulation at the same step
    /// count, in percent ([`reactions`]); `None` for the complete
    /// formulation, a failed run or a scene without support groups.
    pub reaction_error_percent: Option<f64>,
    /// The largest support reaction `max_{k,g} |R(k,g)|` over the scheduled
    /// steps ([`reactions::max_reaction`]); `None` without support groups.
    pub max_reaction: Option<f64>,
}

impl Run {
    /// Newton iterations spent: those of the converged attempts and those
    /// a step repeat or an accuracy halving discarded (the cost the
    /// study's ratios compare).
    pub fn iterations_spent(&self) -> usize {
        self.newton_iterations + self.repeated_iterations
    }

    /// The word the tables show for a run without a result: `refused` (the
    /// solver refused the method on the scene) or `failed`.
    pub fn failure_word(&self) -> &'static str {
        if self.refused { "refused" } else { "failed" }
    }
}

/// All runs of one formulation.
#[derive(Debug, Clone)]
pub struct FormulationStudy {
    /// The formulation.
    pub formulation: Formulation,
    /// Runs in order: for each step count, complete then Types 1–6.
    pub runs: Vec<Run>,
}

impl FormulationStudy {
    /// The run of `method` at `steps`.
    pub fn run(&self, method: Method, steps: usize) -> Option<&Run> {
        self.runs
            .iter()
            .find(|r| r.method == method && r.steps == steps)
    }

    /// The step counts studied, ascending.
    pub fn steps(&self) -> Vec<usize> {
        let mut s: Vec<usize> = self.runs.iter().map(|r| r.steps).collect();
        s.sort_unstable();
        s.dedup();
        s
    }
}

/// The contact-heavy variant's runs, as ratios to the complete formulation
/// measured in the same study.
#[derive(Debug, Clone)]
pub struct HeavyStudy {
    /// Solid elements of the variant.
    pub solid_elements: usize,
    /// Slave integration points of the variant.
    pub contact_points: usize,
    /// Its runs (same layout as [`FormulationStudy::runs`]).
    pub study: FormulationStudy,
}

/// Everything a study computed.
#[derive(Debug, Clone)]
pub struct StudyResults {
    /// The scene's name.
    pub scene_name: String,
    /// Solves per configuration.
    pub repeats: usize,
    /// The linear solver of every solve (the scene's `[newton] linear`).
    pub linear: solver::LinearSolverKind,
    /// One study per formulation, the scene's first.
    pub formulations: Vec<FormulationStudy>,
    /// The contact-heavy variant, if run.
    pub heavy: Option<HeavyStudy>,
    /// Why the contact-heavy variant was left out, if it was asked for but
    /// its complete formulation failed (the study goes on without it).
    pub heavy_failure: Option<String>,
    /// The complete solution at the scene's default step count (for the
    /// deformed-configuration plot; `None` for a 3D scene, which has no
    /// such plot).
    pub deformed: Option<Solution>,
}

/// The contact-heavy variant of a scene: every body refined `refine` times
/// along x and every contact pair integrated with `gauss_points` points per
/// slave segment. Geometry, material, supports, loads and contact law are
/// unchanged.
pub fn contact_heavy_variant(scene: &Scene, refine: usize, gauss_points: usize) -> Scene {
    let mut s = scene.refined(refine, 1);
    for c in &mut s.contacts {
        c.gauss_points = Some(gauss_points);
    }
    s.name = Some(format!(
        "{} (contact-heavy: x{refine} along the interface, {gauss_points} Gauss points per segment)",
        scene_name(scene)
    ));
    s
}

/// The scene's display name.
pub fn scene_name(scene: &Scene) -> String {
    scene.name.clone().unwrap_or_else(|| scene.origin.clone())
}

/// The kernel operation count a method evaluates per integration point.
pub fn kernel_ops(formulation: Formulation, method: Method) -> Option<u32> {
    let ty = match method {
        Method::Complete => ApproxType::Type6,
        Method::Approx(t) => t,
    };
    contact_kernels::op_count(formulation, Some(ty)).map(|o| o.total())
}

fn secs(d: Duration) -> f64 {
    d.as_secs_f64()
}

/// Progress reporting: called once per finished solve configuration.
pub trait Progress {
    /// Total number of configurations is known.
    fn start(&self, total: u64);
    /// One configuration finished.
    fn advance(&self, what: &str);
}

impl Progress for indicatif::ProgressBar {
    fn start(&self, total: u64) {
        self.set_length(total);
    }
    fn advance(&self, what: &str) {
        self.set_message(what.to_owned());
        self.inc(1);
    }
}

/// A progress sink that reports nothing.
pub struct Silent;

impl Progress for Silent {
    fn start(&self, _: u64) {}
    fn advance(&self, _: &str) {}
}

/// Solves `scene` with `method` `repeats` times.
fn measure<const D: usize>(
    scene: &Scene,
    formulation: Formulation,
    method: Method,
    steps: usize,
    repeats: usize,
) -> Result<(Solution<D>, [f64; 4]), SolverError>
where
    Dim<D>: StudyDim<D> + SpaceDim<D>,
{
    let mut options = SolveOptions::from_scene(scene);
    options.method = method;
    options.steps = steps;
    options.formulation = Some(formulation);
    let mut times: [Vec<f64>; 4] = Default::default();
    let mut first = None;
    for _ in 0..repeats.max(1) {
        let sol = solver::solve::<D>(scene, &options)?;
        let t = &sol.timings;
        for (v, d) in times.iter_mut().zip([
            t.total,
            t.contact_evaluation,
            t.solid_assembly,
            t.linear_solve,
        ]) {
            v.push(secs(d));
        }
        first.get_or_insert(sol);
    }
    let med = times.map(|v| crate::timing::median(&v));
    Ok((first.expect("at least one repeat"), med))
}

/// What [`study_formulation`] does when the complete formulation fails at a
/// step count.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum OnReferenceFailure {
    /// Stop the study with [`StudyError::Reference`].
    Abort,
    /// Record the failed complete run, run the types anyway (their errors
    /// are then undefined) and go on.
    Record,
}

/// Runs the complete formulation and every type at every step count of
/// `steps` (in that order), with their energy and reaction errors, on a
/// scene of dimension `D` (the study's, and on 2D scenes the safety
/// map's).
pub(crate) fn study_formulation<const D: usize>(
    scene: &Scene,
    formulation: Formulation,
    steps: &[usize],
    repeats: usize,
    progress: &dyn Progress,
    on_reference_failure: OnReferenceFailure,
) -> Result<FormulationStudy, StudyError>
where
    Dim<D>: StudyDim<D> + SpaceDim<D>,
{
    let mut runs = Vec::new();
    for &n in steps {
        let mut reference: Option<f64> = None;
        let mut reference_reactions: Option<Vec<Vec<[f64; D]>>> = None;
        for method in Method::ALL {
            let label = format!("{formulation}, {n} steps, {method}");
            let result = measure::<D>(scene, formulation, method, n, repeats);
            progress.advance(&label);
            let run = match result {
                Ok((sol, [wall, contact, solid, solve])) => {
                    let u = sol.strain_energy;
                    let history = reactions::scheduled_reactions(&sol);
                    if method == Method::Complete {
                        reference = Some(u);
                        reference_reactions = Some(history.clone());
                    }
                    let error_percent = match (method, reference) {
                        (Method::Approx(_), Some(r)) => Some(100.0 * (u - r) / r),
                        _ => None,
                    };
                    let reaction_error_percent = match (method, &reference_reactions) {
                        (Method::Approx(_), Some(r)) => {
                            reactions::reaction_error_percent(&history, r)
                        }
                        _ => None,
                    };
                    Run {
                        formulation,
                        method,
                        steps: n,
                        strain_energy: Some(u),
                        error_percent,
                        newton_iterations: sol.newton_iterations,
                        repeated_iterations: sol.repeated_iterations,
                        cutbacks: sol.cutbacks.len(),
                        wall_seconds: wall,
                        contact_seconds: contact,
                        solid_seconds: solid,
                        solve_seconds: solve,
                        kernel_evaluations: sol.kernel_counts.evaluate,
                        projections: sol.kernel_counts.project,
                        max_abs_gap: Dim::<D>::max_abs_gap(&sol),
                        kernel_ops: kernel_ops(formulation, method),
                        failure: None,
                        refused: false,
                        reaction_error_percent,
                        max_reaction: reactions::max_reaction(&history),
                    }
                }
                Err(source)
                    if method == Method::Complete
                        && on_reference_failure == OnReferenceFailure::Abort =>
                {
                    return Err(StudyError::Reference {
                        formulation,
                        steps: n,
                        source,
                    });
                }
                Err(e) => Run {
                    formulation,
                    method,
                    steps: n,
                    strain_energy: None,
                    error_percent: None,
                    newton_iterations: 0,
                    repeated_iterations: 0,
                    cutbacks: 0,
                    wall_seconds: f64::NAN,
                    contact_seconds: f64::NAN,
                    solid_seconds: f64::NAN,
                    solve_seconds: f64::NAN,
                    kernel_evaluations: 0,
                    projections: 0,
                    max_abs_gap: None,
                    kernel_ops: kernel_ops(formulation, method),
                    refused: matches!(e, SolverError::NotApplicable(_)),
                    failure: Some(e.to_string()),
                    reaction_error_percent: None,
                    max_reaction: None,
                },
            };
            runs.push(run);
        }
    }
    Ok(FormulationStudy { formulation, runs })
}

/// Runs the study on `scene` (2D or 3D).
pub fn run_study(
    scene: &Scene,
    options: &StudyOptions,
    progress: &dyn Progress,
) -> Result<StudyResults, StudyError> {
    let three = scene.dimension().is_ok_and(|d| d == Dimension::Three);
    if three {
        run_study_in::<3>(scene, options, progress, |_, _| Ok(None))
    } else {
        run_study_in::<2>(scene, options, progress, |scene, options| {
            solver::solve(scene, options).map(Some)
        })
    }
}

/// [`run_study`] on a scene of dimension `D`; `deformed` solves the
/// deformed configuration's reference (2D) or gives none (3D).
fn run_study_in<const D: usize>(
    scene: &Scene,
    options: &StudyOptions,
    progress: &dyn Progress,
    deformed: impl Fn(&Scene, &SolveOptions) -> Result<Option<Solution>, SolverError>,
) -> Result<StudyResults, StudyError>
where
    Dim<D>: StudyDim<D> + SpaceDim<D>,
{
    let name = scene_name(scene);
    let first = scene
        .contacts
        .first()
        .ok_or_else(|| StudyError::NoContact(name.clone()))?
        .formulation;
    let steps = options
        .steps
        .clone()
        .unwrap_or_else(|| scene.loading.steps.clone());
    if steps.is_empty() {
        return Err(StudyError::NoSteps);
    }
    let mut formulations = vec![first];
    if options.all_formulations {
        formulations.extend(
            contact_kernels::pair_formulations()
                .into_iter()
                .filter(|f| *f != first),
        );
    }
    let per_formulation = (steps.len() * Method::ALL.len()) as u64;
    let heavy_count = (options.heavy_steps.len() * Method::ALL.len()) as u64;
    progress.start(per_formulation * formulations.len() as u64 + heavy_count + 1);

    let mut studies = Vec::new();
    for &f in &formulations {
        studies.push(study_formulation::<D>(
            scene,
            f,
            &steps,
            options.repeats,
            progress,
            OnReferenceFailure::Abort,
        )?);
    }

    let (heavy, heavy_failure) = if options.heavy_steps.is_empty() {
        (None, None)
    } else {
        let variant =
            contact_heavy_variant(scene, options.heavy_refine, options.heavy_gauss_points);
        let heavy = study_formulation::<D>(
            &variant,
            first,
            &options.heavy_steps,
            options.repeats,
            progress,
            OnReferenceFailure::Abort,
        )
        .and_then(|study| {
            let (solid_elements, contact_points) =
                size::<D>(&variant).map_err(|source| StudyError::Reference {
                    formulation: first,
                    steps: options.heavy_steps[0],
                    source,
                })?;
            Ok(HeavyStudy {
                solid_elements,
                contact_points,
                study,
            })
        });
        match heavy {
            Ok(h) => (Some(h), None),
            // The variant is an extra of the paper's study: a scene whose
            // refined variant does not converge is still studied.
            Err(e @ StudyError::Reference { .. }) => (None, Some(e.to_string())),
            Err(e) => return Err(e),
        }
    };

    let mut options_def = SolveOptions::from_scene(scene);
    options_def.method = Method::Complete;
    options_def.formulation = Some(first);
    let deformed = deformed(scene, &options_def).map_err(|source| StudyError::Reference {
        formulation: first,
        steps: options_def.steps,
        source,
    })?;
    progress.advance("deformed configuration");

    Ok(StudyResults {
        scene_name: name,
        repeats: options.repeats,
        linear: scene.newton.linear,
        formulations: studies,
        heavy,
        heavy_failure,
        deformed,
    })
}
