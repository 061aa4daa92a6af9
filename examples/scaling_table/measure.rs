//! One size measured: the first load step solved, then one Newton
//! iteration of the second probed and timed phase by phase for each
//! linear solver ([`Row`]); in 3D also the pattern alone analysed
//! ([`FillRow`]).

use std::time::{Duration, Instant};

use solver::newton::{IterationProbe, IterationSample};
use solver::{
    Dim, LinearSolverKind, Method, Model, Scene, SolveOptions, SpaceDim, State, solve_model,
};

use crate::stats::{fmt_fill, fmt_mib, median, ms, peak_mib, reset_peak};
use crate::{HUGE, LARGE, REPS, REPS_HUGE, REPS_LARGE, SLOW};

/// One measured size.
pub(crate) struct Row {
    /// The refinement, as printed in the table's first column.
    pub(crate) label: String,
    pub(crate) equations: usize,
    pub(crate) contact_points: usize,
    pub(crate) solid: f64,
    pub(crate) contact: f64,
    pub(crate) linear: f64,
    pub(crate) total: f64,
    pub(crate) symbolic: f64,
    /// Linear solves that fell back to LU (of the `REPS` + 1).
    pub(crate) fallbacks: usize,
    /// Nonzeros of the factor, when the solver reports them.
    pub(crate) fill: Option<usize>,
    /// Peak resident memory of the probed iterations, MiB.
    pub(crate) peak_mib: Option<f64>,
}

/// One row per kind in `linear`, probed from the same state (`None`: an LU
/// above `lu_max` equations, not run).
pub(crate) fn measure(
    base: &Scene,
    refine: (usize, usize),
    linear: &[LinearSolverKind],
    lu_max: usize,
) -> Result<Vec<Option<Row>>, Box<dyn std::error::Error>> {
    let scene = base.refined(refine.0, refine.1);
    let model = scene.build_model::<2>()?;
    let label = format!("{} x {}", refine.0, refine.1);
    measure_model(&scene, &model, label, linear, lu_max)
}

/// [`measure`] on the 3D block: `scenes/block3d.toml` refined `n`-fold in
/// every direction.
pub(crate) fn measure_3d(
    base: &Scene,
    n: usize,
    linear: &[LinearSolverKind],
    lu_max: usize,
) -> Result<Vec<Option<Row>>, Box<dyn std::error::Error>> {
    let (scene, model, label) = block_3d(base, n)?;
    measure_model(&scene, &model, label, linear, lu_max)
}

/// A 3D size whose pattern alone is analysed (`--fill-max-equations`).
pub(crate) struct FillRow {
    pub(crate) label: String,
    pub(crate) equations: usize,
    /// The symbolic analysis, ms.
    pub(crate) symbolic: f64,
    pub(crate) fill: Option<usize>,
    /// Peak resident memory of the model, its assembly and the analysis,
    /// MiB.
    pub(crate) peak_mib: Option<f64>,
}

/// `scenes/block3d.toml` refined `n`-fold in every direction.
fn block_3d(
    base: &Scene,
    n: usize,
) -> Result<(Scene, Model<3>, String), Box<dyn std::error::Error>> {
    let mut scene = base.clone();
    scene.refine.x *= n;
    scene.refine.y *= n;
    scene.refine.z = Some(scene.refine.z.unwrap_or(1) * n);
    let model = scene.build_model::<3>()?;
    let body = &scene.bodies[0];
    let (nx, ny, nz) = (
        body.nx.unwrap_or(1) * scene.refine.x,
        body.ny.unwrap_or(1) * scene.refine.y,
        body.nz.unwrap_or(1) * scene.refine.z.unwrap_or(1),
    );
    if model.mesh.element_count() != nx * ny * nz {
        return Err(format!(
            "{} elements, expected {nx} x {ny} x {nz}",
            model.mesh.element_count()
        )
        .into());
    }
    Ok((scene, model, format!("{nx} x {ny} x {nz}")))
}

/// The pattern of the 3D block refined `n`-fold (assembled at the
/// reference state: the pattern does not depend on the state), analysed
/// by a fresh `kind` solver as a solve's first iteration analyses it; no
/// numeric factorisation.
pub(crate) fn measure_fill_3d(
    base: &Scene,
    n: usize,
    kind: LinearSolverKind,
) -> Result<FillRow, Box<dyn std::error::Error>> {
    let reset = reset_peak();
    let (scene, model, label) = block_3d(base, n)?;
    let opts = SolveOptions {
        method: Method::Complete,
        linear: kind,
        ..SolveOptions::from_scene(&scene)
    };
    let zero = State::<3> {
        load_factor: 0.0,
        displacements: vec![[0.0; 3]; model.mesh.node_count()],
        multipliers: Vec::new(),
        friction: Vec::new(),
    };
    let probe = IterationProbe::new(&model, &opts, &zero, model.load_factor_end)?;
    let equations = probe.equations();
    let mut phase = probe.contact()?;
    probe.solid(&mut phase.system);
    let mut solver = kind.build("");
    solver.set_constraints_from(equations);
    let t = Instant::now();
    solver.analyse(equations, &phase.system.rows, &phase.system.cols)?;
    let row = FillRow {
        label,
        equations,
        symbolic: ms(t.elapsed()),
        fill: solver.factor_nonzeros(),
        peak_mib: peak_mib().filter(|_| reset),
    };
    eprintln!(
        "{}: {} equations, pattern only: symbolic {:.0} ms, factor nonzeros {}, peak {} MiB",
        row.label,
        row.equations,
        row.symbolic,
        fmt_fill(row.fill),
        fmt_mib(row.peak_mib)
    );
    Ok(row)
}

/// The first load step of `model` (built from `scene`) solved with
/// `linear[0]`, then one probed row per kind in `linear`.
fn measure_model<const D: usize>(
    scene: &Scene,
    model: &Model<D>,
    label: String,
    linear: &[LinearSolverKind],
    lu_max: usize,
) -> Result<Vec<Option<Row>>, Box<dyn std::error::Error>>
where
    Dim<D>: SpaceDim<D>,
{
    let free_dofs = model.mesh.node_count() * D;
    if linear[0] == LinearSolverKind::Lu && free_dofs > lu_max {
        return Err(format!(
            "about {free_dofs} equations: above --lu-max-equations {lu_max}, LU must not solve \
             the first step (list another solver first, e.g. --linear ldlt,lu)"
        )
        .into());
    }
    let opts = SolveOptions {
        method: Method::Complete,
        linear: linear[0],
        ..SolveOptions::from_scene(scene)
    };
    let steps = opts.steps;
    let step = model.load_factor_end / steps as f64;
    // the converged state after the first load step
    let mut first = model.clone();
    first.load_factor_end = step;
    let t = Instant::now();
    let solution = solve_model(
        &first,
        &SolveOptions {
            steps: 1,
            ..opts.clone()
        },
    )?;
    eprintln!(
        "{label}: {} equations; step 1 of {steps} solved in {:.2} s ({} Newton iterations)",
        solution.equations,
        t.elapsed().as_secs_f64(),
        solution.newton_iterations
    );
    let state = solution.final_state.clone();
    let equations = solution.equations;
    drop(solution);
    drop(first);
    linear
        .iter()
        .map(|&kind| {
            if kind == LinearSolverKind::Lu && equations > lu_max {
                eprintln!("  lu: not run ({equations} equations > --lu-max-equations {lu_max})");
                return Ok(None);
            }
            let opts = SolveOptions {
                linear: kind,
                ..opts.clone()
            };
            probe_row(model, &opts, &state, 2.0 * step, label.clone()).map(Some)
        })
        .collect()
}

/// The first iteration of the second step from `state`, timed.
fn probe_row<const D: usize>(
    model: &Model<D>,
    opts: &SolveOptions,
    state: &State<D>,
    to: f64,
    label: String,
) -> Result<Row, Box<dyn std::error::Error>>
where
    Dim<D>: SpaceDim<D>,
{
    let reset = reset_peak();
    let mut probe = IterationProbe::new(model, opts, state, to)?;
    let warm = probe.iteration()?;
    let symbolic = ms(probe.symbolic_time());
    let reps = if probe.equations() > HUGE || warm.total() > SLOW {
        REPS_HUGE
    } else if probe.equations() > LARGE {
        REPS_LARGE
    } else {
        REPS
    };
    let samples: Vec<IterationSample> = (0..reps)
        .map(|_| probe.iteration())
        .collect::<Result<_, _>>()?;
    let fallbacks = probe.linear_fallbacks();
    if probe.symbolic_factorisations() != 1 && fallbacks == 0 {
        return Err(format!(
            "{} symbolic factorisations (expected 1: the pattern must not change)",
            probe.symbolic_factorisations()
        )
        .into());
    }
    let pick =
        |f: fn(&IterationSample) -> Duration| median(samples.iter().map(|s| ms(f(s))).collect());
    let row = Row {
        label,
        equations: probe.equations(),
        contact_points: probe.contact_points(),
        solid: pick(|s| s.solid_assembly),
        contact: pick(|s| s.contact_evaluation),
        linear: pick(|s| s.linear_solve),
        total: pick(|s| s.total()),
        symbolic,
        fallbacks,
        fill: probe.factor_nonzeros(),
        peak_mib: peak_mib().filter(|_| reset),
    };
    eprintln!(
        "  {}: |r| = {:.3e}; first iteration {:.0} ms (symbolic {:.0} ms), then median {:.1} ms over {reps}; peak {} MiB",
        opts.linear,
        warm.residual_norm,
        ms(warm.total()),
        symbolic,
        row.total,
        fmt_mib(row.peak_mib)
    );
    Ok(row)
}
