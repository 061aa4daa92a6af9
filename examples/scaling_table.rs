//! Solver scaling: the cost of one Newton iteration (complete formulation)
//! on refined versions of the paper scene, as a Markdown table.
//!
//! ```text
//! cargo run --release --example scaling_table            # the default sizes
//! cargo run --release --example scaling_table -- 8x4 26x13   # refine factors
//! cargo run --release --example scaling_table -- --linear ldlt       # the LDL^T
//! cargo run --release --example scaling_table -- --linear lu,ldlt    # both, compared
//! cargo run --release --example scaling_table -- --linear ldlt,lu \
//!     --max-equations 1100000 --lu-max-equations 110000  # up to 10^6, LU to 10^5
//! ```
//!
//! For each refinement `(x, y)` of `scenes/stacked-cantilever.toml` (every
//! body's `nx` times `x`, `ny` times `y`; `y = x / 2` keeps the elements
//! square), the first of the scene's load steps is solved with
//! [`solver::solve_model`]; from that converged state,
//! [`solver::newton::IterationProbe`] runs the first Newton iteration of the
//! second step (the same code as a solve's iteration): once to build the
//! symbolic LU, then `REPS` more times, timed phase by phase. The table gives
//! the medians: solid assembly, contact evaluation (re-projection, Type 6
//! kernel, contact scatter) and linear solve (numeric LU with the symbolic
//! factorisation reused, plus the solve), their sum, and the one-off
//! symbolic analysis. Below the table: the least-squares exponent `p` of
//! `time ∝ equations^p` on a log-log scale per phase, and the peak resident
//! memory (`VmHWM` from `/proc/self/status`, Linux; the sizes run in
//! increasing order, so it is that of the largest size). Each row also gives
//! the peak resident memory of its probed iterations alone: `VmHWM` is reset
//! (`5` written to `/proc/self/clear_refs`) before a solver's probe and read
//! after it, so the figure holds the model, the converged state and the
//! iterations' assembly and factorisation (`n/a` where the kernel refuses
//! the reset).
//!
//! `--max-equations N` adds the larger refinements [`EXTRA_SIZES`] (about
//! 3e5 and 1e6 equations) whose nominal size is at most `N`; they use
//! [`REPS_HUGE`] timed iterations. `--lu-max-equations N` (default
//! [`LU_MAX_EQUATIONS`]) skips the LU above `N` equations (its time and
//! memory grow faster than the LDL^T's, and the machine's memory is shared);
//! the comparison table then says so. The first load step is solved with the first solver listed, so above
//! that limit LU must not come first (`--linear ldlt,lu`).
//!
//! `--linear` picks the linear solver(s) (default `lu`). With several, each
//! is probed from the same converged state (the first step is solved with
//! the first one listed), the table is that of the first, and a second table
//! compares the solve and symbolic times of each with the first's (ratios
//! `first / other`, so above 1 is faster), with the LU fallbacks counted.
//!
//! `--3d` measures the same iteration on `scenes/block3d.toml` instead: a
//! 2 x 2 x 1 block of hexahedra (St Venant-Kirchhoff, finite strain),
//! clamped at its bottom and pressed by a dead traction on its top, refined `n`-fold in
//! every direction (`2n x 2n x n` elements; sizes are integers `n`, default
//! [`SIZES_3D`], about 1e4 to 1e5 equations, and [`EXTRA_SIZES_3D`] up to
//! `--max-equations`). A 3D model has no contact pairs, so the table has no
//! contact columns; below it, the growth exponents over all sizes and
//! between the two largest, and an extrapolation to [`EXTRAPOLATE_TO`]
//! equations with the latter:
//!
//! `--fill-max-equations N` adds, above the timed sizes, the
//! [`EXTRA_SIZES_3D`] of at most `N` equations as pattern-only rows: the
//! system assembled at the reference state and its symbolic analysis (the
//! factor's nonzeros, the analysis time and the peak memory, no numeric
//! factorisation), so that the fill is measured beyond the sizes whose
//! iterations take too long to time (the pattern-only fill of the largest
//! timed size is checked against its probe's):
//!
//! ```text
//! cargo run --release --example scaling_table -- --3d --linear ldlt --fill-max-equations 310000
//! ```
//!
//! The benchmark with criterion is `cargo bench --bench solver_scaling`.

use std::process::ExitCode;
use std::time::{Duration, Instant};

use solver::newton::{IterationProbe, IterationSample};
use solver::{
    Dim, LinearSolverKind, Method, Model, Scene, SolveOptions, SpaceDim, State, solve_model,
};

/// Refine factors giving about 1e3, 3e3, 1e4, 3e4 and 1e5 equations.
const SIZES: [(usize, usize); 5] = [(8, 4), (14, 7), (26, 13), (46, 23), (84, 42)];

/// Larger refine factors for `--max-equations`, with their nominal numbers
/// of equations (measured: about 28.8 equations per unit of `x y`).
const EXTRA_SIZES: [((usize, usize), usize); 2] = [((144, 72), 299_000), ((263, 132), 1_000_000)];

/// The 3D block of `--3d`.
const BLOCK_3D: &str = include_str!("../scenes/block3d.toml");

/// `--3d` refine factors (in every direction) giving about 1e4, 3e4 and
/// 1e5 equations (`n = 20`: 40 x 40 x 20 hexahedra).
const SIZES_3D: [usize; 3] = [9, 13, 20];

/// Larger `--3d` refine factors for `--max-equations`, with their nominal
/// numbers of equations (`3 (2n + 1)^2 n`: every node above the clamped
/// bottom free).
const EXTRA_SIZES_3D: [(usize, usize); 2] = [(29, 303_000), (44, 1_046_000)];

/// The size the `--3d` table extrapolates to.
const EXTRAPOLATE_TO: usize = 1_000_000;

/// Default of `--lu-max-equations`: the LU is measured up to about 1e5
/// equations (826 MiB peak there).
const LU_MAX_EQUATIONS: usize = 200_000;

/// Timed iterations above [`HUGE`] equations, or when the first
/// iteration took longer than [`SLOW`] (the 3D sizes from about 1e5
/// equations).
const REPS_HUGE: usize = 3;
const HUGE: usize = 500_000;
const SLOW: Duration = Duration::from_secs(10);

/// Timed iterations per size (after the one building the symbolic LU);
/// fewer for sizes above [`LARGE`] equations.
const REPS: usize = 7;
const REPS_LARGE: usize = 5;
const LARGE: usize = 50_000;

/// One measured size.
struct Row {
    /// The refinement, as printed in the table's first column.
    label: String,
    equations: usize,
    contact_points: usize,
    solid: f64,
    contact: f64,
    linear: f64,
    total: f64,
    symbolic: f64,
    /// Linear solves that fell back to LU (of the `REPS` + 1).
    fallbacks: usize,
    /// Nonzeros of the factor, when the solver reports them.
    fill: Option<usize>,
    /// Peak resident memory of the probed iterations, MiB.
    peak_mib: Option<f64>,
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// Three significant digits or so.
fn fmt_ms(v: f64) -> String {
    if v < 10.0 {
        format!("{v:.2}")
    } else if v < 100.0 {
        format!("{v:.1}")
    } else {
        format!("{v:.0}")
    }
}

/// Least-squares slope of `ln y` against `ln x`.
fn exponent(x: &[f64], y: &[f64]) -> f64 {
    let lx: Vec<f64> = x.iter().map(|v| v.ln()).collect();
    let ly: Vec<f64> = y.iter().map(|v| v.ln()).collect();
    let n = lx.len() as f64;
    let (mx, my) = (lx.iter().sum::<f64>() / n, ly.iter().sum::<f64>() / n);
    let sxy: f64 = lx.iter().zip(&ly).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = lx.iter().map(|a| (a - mx) * (a - mx)).sum();
    sxy / sxx
}

/// `VmHWM` (peak resident set) from `/proc/self/status`, MiB.
fn peak_mib() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib / 1024.0)
}

/// Resets `VmHWM` to the current resident set (Linux `clear_refs` code 5);
/// whether it worked.
fn reset_peak() -> bool {
    std::fs::write("/proc/self/clear_refs", "5").is_ok()
}

fn fmt_mib(v: Option<f64>) -> String {
    v.map_or_else(|| "n/a".into(), |m| format!("{m:.0}"))
}

fn fmt_fill(v: Option<usize>) -> String {
    v.map_or_else(|| "n/a".into(), |n| format!("{n:.3e}"))
}

fn parse_size(s: &str) -> Option<(usize, usize)> {
    let (x, y) = s.split_once(['x', ','])?;
    let (x, y) = (x.trim().parse().ok()?, y.trim().parse().ok()?);
    (x > 0 && y > 0).then_some((x, y))
}

/// One row per kind in `linear`, probed from the same state (`None`: an LU
/// above `lu_max` equations, not run).
fn measure(
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
fn measure_3d(
    base: &Scene,
    n: usize,
    linear: &[LinearSolverKind],
    lu_max: usize,
) -> Result<Vec<Option<Row>>, Box<dyn std::error::Error>> {
    let (scene, model, label) = block_3d(base, n)?;
    measure_model(&scene, &model, label, linear, lu_max)
}

/// A 3D size whose pattern alone is analysed (`--fill-max-equations`).
struct FillRow {
    label: String,
    equations: usize,
    /// The symbolic analysis, ms.
    symbolic: f64,
    fill: Option<usize>,
    /// Peak resident memory of the model, its assembly and the analysis,
    /// MiB.
    peak_mib: Option<f64>,
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
fn measure_fill_3d(
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
    };
    let probe = IterationProbe::new(&model, &opts, &zero, model.load_factor_end)?;
    let equations = probe.equations();
    let mut phase = probe.contact()?;
    probe.solid(&mut phase.system);
    let mut solver = kind.build();
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

/// The rows of the first solver and those of the others, per size.
type Rows = (Vec<Row>, Vec<Vec<Option<Row>>>);

/// Splits each size's rows into the first solver's and the others'.
fn collect(
    results: impl Iterator<Item = Result<Vec<Option<Row>>, Box<dyn std::error::Error>>>,
) -> Result<Rows, Box<dyn std::error::Error>> {
    let mut rows = Vec::new();
    let mut others = Vec::new();
    for r in results {
        let mut r = r?;
        match r.remove(0) {
            Some(first) => {
                rows.push(first);
                others.push(r);
            }
            None => unreachable!("the first solver always runs"),
        }
    }
    Ok((rows, others))
}

/// The paper scene at the refinements `raw` (default [`SIZES`], plus
/// [`EXTRA_SIZES`] up to `max_equations`).
fn run_2d(
    raw: &[String],
    max_equations: Option<usize>,
    linear: &[LinearSolverKind],
    lu_max: usize,
) -> Result<Rows, Box<dyn std::error::Error>> {
    let mut sizes = raw
        .iter()
        .map(|a| {
            parse_size(a).ok_or_else(|| format!("expected refine factors like `26x13`, got `{a}`"))
        })
        .collect::<Result<Vec<_>, _>>()?;
    if sizes.is_empty() {
        sizes = SIZES.to_vec();
    }
    if let Some(max) = max_equations {
        sizes.extend(
            EXTRA_SIZES
                .iter()
                .filter(|&&(_, n)| n <= max)
                .map(|&(size, _)| size),
        );
    }
    let base = Scene::from_toml_str(
        solver::scenes::STACKED_CANTILEVER,
        "stacked-cantilever.toml",
    )?;
    collect(sizes.iter().map(|&size| {
        measure(&base, size, linear, lu_max)
            .map_err(|e| format!("refine {}x{}: {e}", size.0, size.1).into())
    }))
}

/// The 3D block at the refine factors `raw` (default [`SIZES_3D`], plus
/// [`EXTRA_SIZES_3D`] up to `max_equations`), and the pattern alone of
/// the [`EXTRA_SIZES_3D`] above those up to `fill_max` (checked against
/// the largest timed size's fill).
fn run_3d(
    raw: &[String],
    max_equations: Option<usize>,
    fill_max: Option<usize>,
    linear: &[LinearSolverKind],
    lu_max: usize,
) -> Result<(Rows, Vec<FillRow>), Box<dyn std::error::Error>> {
    let mut sizes = raw
        .iter()
        .map(|a| {
            a.parse::<usize>()
                .ok()
                .filter(|&n| n > 0)
                .ok_or_else(|| format!("--3d: expected a refine factor like `13`, got `{a}`"))
        })
        .collect::<Result<Vec<_>, _>>()?;
    if sizes.is_empty() {
        sizes = SIZES_3D.to_vec();
    }
    let timed_max = max_equations.unwrap_or(0);
    sizes.extend(
        EXTRA_SIZES_3D
            .iter()
            .filter(|&&(_, n)| n <= timed_max)
            .map(|&(size, _)| size),
    );
    let base = Scene::from_toml_str(BLOCK_3D, "block3d.toml")?;
    let rows = collect(sizes.iter().map(|&n| {
        measure_3d(&base, n, linear, lu_max).map_err(|e| format!("refine {n}: {e}").into())
    }))?;
    let pattern_only: Vec<usize> = EXTRA_SIZES_3D
        .iter()
        .filter(|&&(_, n)| n > timed_max && n <= fill_max.unwrap_or(0))
        .map(|&(size, _)| size)
        .collect();
    let mut fills = Vec::new();
    if let (Some(&last), false) = (sizes.last(), pattern_only.is_empty()) {
        // the pattern-only path gives the timed fill
        let check = measure_fill_3d(&base, last, linear[0])?;
        let timed = rows.0.last().and_then(|r| r.fill);
        if check.fill != timed {
            return Err(format!(
                "refine {last}: pattern-only fill {:?}, the probe's {timed:?}",
                check.fill
            )
            .into());
        }
        for n in pattern_only {
            fills.push(
                measure_fill_3d(&base, n, linear[0]).map_err(|e| format!("refine {n}: {e}"))?,
            );
        }
    }
    Ok((rows, fills))
}

/// The 2D table: the paper scene, with the contact columns.
fn print_2d_table(rows: &[Row], linear: &[LinearSolverKind]) {
    println!(
        "One Newton iteration, complete formulation, paper scene refined \
         (first iteration of load step 2 of {}; median of {REPS} runs, {REPS_LARGE} above {LARGE} equations, \
         {REPS_HUGE} above {HUGE}; {} rayon threads):\n",
        paper_steps(),
        rayon_threads()
    );
    if linear.len() > 1 || linear[0] != LinearSolverKind::Lu {
        println!("Linear solver: {}.\n", linear[0]);
    }
    println!(
        "| refine (x, y) | equations | contact points | assembly ms | contact ms | solve ms | total ms | symbolic ms (once) | factor nonzeros | peak MiB |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for r in rows {
        println!(
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            r.label,
            r.equations,
            r.contact_points,
            fmt_ms(r.solid),
            fmt_ms(r.contact),
            fmt_ms(r.linear),
            fmt_ms(r.total),
            fmt_ms(r.symbolic),
            fmt_fill(r.fill),
            fmt_mib(r.peak_mib)
        );
    }
    println!();
    if rows.len() >= 2 {
        let n: Vec<f64> = rows.iter().map(|r| r.equations as f64).collect();
        let cp: Vec<f64> = rows.iter().map(|r| r.contact_points as f64).collect();
        let fit = |f: fn(&Row) -> f64| exponent(&n, &rows.iter().map(f).collect::<Vec<_>>());
        println!(
            "Growth from {} to {} equations, time ∝ equations^p (least squares on log-log): assembly p = {:.2}, \
             contact p = {:.2} (contact points ∝ equations^{:.2}), solve p = {:.2}, total p = {:.2}.",
            rows[0].equations,
            rows[rows.len() - 1].equations,
            fit(|r| r.solid),
            fit(|r| r.contact),
            exponent(&n, &cp),
            fit(|r| r.linear),
            fit(|r| r.total)
        );
        if rows.iter().all(|r| r.fill.is_some()) {
            let fill: Vec<f64> = rows.iter().map(|r| r.fill.unwrap_or(0) as f64).collect();
            println!("Factor nonzeros ∝ equations^{:.2}.", exponent(&n, &fill));
        }
        println!();
    }
}

/// The paper scene's default step count.
fn paper_steps() -> usize {
    Scene::from_toml_str(
        solver::scenes::STACKED_CANTILEVER,
        "stacked-cantilever.toml",
    )
    .map_or(0, |s| s.default_steps())
}

/// The 3D table: the hexahedral block (no contact columns: a 3D model has
/// no contact pairs yet), the growth exponents over all sizes and between
/// the two largest, and the extrapolation to [`EXTRAPOLATE_TO`] equations
/// with the latter (the peak memory as the extrapolated factor plus the
/// rest of the largest size's peak grown linearly: below 1e5 equations the
/// peak is mostly the model and the assembly, which grow linearly, and the
/// factor grows faster).
fn print_3d_table(rows: &[Row], fills: &[FillRow], linear: &[LinearSolverKind]) {
    let steps = Scene::from_toml_str(BLOCK_3D, "block3d.toml").map_or(0, |s| s.default_steps());
    println!(
        "One Newton iteration, `scenes/block3d.toml` refined (hexahedra, St Venant-Kirchhoff, finite strain, \
         no contact; first iteration of load step 2 of {steps}; median of {REPS} runs, {REPS_LARGE} above {LARGE} equations, \
         {REPS_HUGE} above {HUGE} or when the first took over {} s; {} rayon threads):\n",
        SLOW.as_secs(),
        rayon_threads()
    );
    println!("Linear solver: {}.\n", linear[0]);
    println!(
        "| elements (x, y, z) | equations | assembly ms | solve ms | total ms | symbolic ms (once) | factor nonzeros | nonzeros / equation | peak MiB | LU fallbacks |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let per_equation = |fill: Option<usize>, equations: usize| {
        fill.map_or_else(
            || "n/a".into(),
            |f| format!("{:.0}", f as f64 / equations as f64),
        )
    };
    for r in rows {
        println!(
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            r.label,
            r.equations,
            fmt_ms(r.solid),
            fmt_ms(r.linear),
            fmt_ms(r.total),
            fmt_ms(r.symbolic),
            fmt_fill(r.fill),
            per_equation(r.fill, r.equations),
            fmt_mib(r.peak_mib),
            r.fallbacks
        );
    }
    println!();
    if !fills.is_empty() {
        println!(
            "Larger sizes, pattern only (assembled at the reference state, analysed by a fresh {} as a \
             solve's first iteration; no numeric factorisation; peak: the model, its assembly and the analysis):\n",
            linear[0]
        );
        println!(
            "| elements (x, y, z) | equations | symbolic ms | factor nonzeros | nonzeros / equation | peak MiB |"
        );
        println!("|---|---:|---:|---:|---:|---:|");
        for r in fills {
            println!(
                "| {} | {} | {} | {} | {} | {} |",
                r.label,
                r.equations,
                fmt_ms(r.symbolic),
                fmt_fill(r.fill),
                per_equation(r.fill, r.equations),
                fmt_mib(r.peak_mib)
            );
        }
        println!();
    }
    if rows.len() < 2 {
        return;
    }
    // (equations, value) series, and their exponents: least squares over
    // all points and between the last two
    let fit = |pts: &[(f64, f64)]| -> (f64, f64) {
        let x: Vec<f64> = pts.iter().map(|p| p.0).collect();
        let y: Vec<f64> = pts.iter().map(|p| p.1).collect();
        let [.., (x0, y0), (x1, y1)] = pts else {
            unreachable!("at least two points")
        };
        (exponent(&x, &y), (y1 / y0).ln() / (x1 / x0).ln())
    };
    let series = |f: &dyn Fn(&Row) -> f64| -> Vec<(f64, f64)> {
        rows.iter().map(|r| (r.equations as f64, f(r))).collect()
    };
    let fmt_fit = |(all, local): (f64, f64)| format!("{all:.2} ({local:.2})");
    let (first, last) = (&rows[0], &rows[rows.len() - 1]);
    let before = &rows[rows.len() - 2];
    let time_fit = fit(&series(&|r| r.total));
    println!(
        "Growth from {} to {} equations, time ∝ equations^p (least squares on log-log; in brackets between \
         the two largest sizes, {} and {}): assembly p = {}, solve p = {}, total p = {}, symbolic p = {}; \
         peak memory ∝ equations^{}.",
        first.equations,
        last.equations,
        before.equations,
        last.equations,
        fmt_fit(fit(&series(&|r| r.solid))),
        fmt_fit(fit(&series(&|r| r.linear))),
        fmt_fit(time_fit),
        fmt_fit(fit(&series(&|r| r.symbolic))),
        fmt_fit(fit(&series(&|r| r.peak_mib.unwrap_or(f64::NAN)))),
    );
    // the fill over the timed and the pattern-only sizes
    let fill_pts: Vec<(f64, f64)> = rows
        .iter()
        .map(|r| (r.equations, r.fill))
        .chain(fills.iter().map(|r| (r.equations, r.fill)))
        .filter_map(|(n, f)| Some((n as f64, f? as f64)))
        .collect();
    let fill_fit = (fill_pts.len() >= 2).then(|| fit(&fill_pts));
    if let (Some(ff), Some(&(n0, _)), Some(&(n1, _))) =
        (fill_fit, fill_pts.first(), fill_pts.last())
    {
        println!(
            "Factor nonzeros ∝ equations^{} from {n0} to {n1} equations{}.",
            fmt_fit(ff),
            if fills.is_empty() {
                ""
            } else {
                " (timed and pattern-only sizes)"
            }
        );
    }
    println!();
    // extrapolation with the exponents between the two largest sizes
    // (the steeper ones: the growth steepens with the size in 3D), to the
    // largest pattern-only size if there is one (its fill measured), else
    // to EXTRAPOLATE_TO
    let (to, measured_fill, measured_symbolic) = match fills.last() {
        Some(r) if r.equations > last.equations => (r.equations, r.fill, Some(r.symbolic)),
        _ => (EXTRAPOLATE_TO, None, None),
    };
    let scale = to as f64 / last.equations as f64;
    let total = last.total * scale.powf(time_fit.1);
    let symbolic_fit = fit(&series(&|r| r.symbolic));
    let symbolic = measured_symbolic.unwrap_or(last.symbolic * scale.powf(symbolic_fit.1));
    let nonzeros = match measured_fill {
        Some(f) => Some(f as f64),
        None => fill_fit
            .zip(fill_pts.last())
            .map(|(ff, &(n1, f1))| f1 * (to as f64 / n1).powf(ff.1)),
    };
    // the dense-column estimate of the factorisation's flops, sum of the
    // squared column counts ~ nnz(L)^2 / n, scaled from the largest timed
    // size's solve
    let by_flops = nonzeros
        .zip(last.fill)
        .map(|(nz, f)| last.linear * (nz / f as f64).powi(2) / scale + last.solid * scale);
    // the peak as the factor's values (8 bytes a nonzero) plus the rest
    // (model, assembled system, solver work), the rest grown linearly
    let factor_mib = |f: f64| f * 8.0 / (1024.0 * 1024.0);
    let mib = last
        .peak_mib
        .zip(last.fill)
        .zip(nonzeros)
        .map(|((p, f), nz)| (p - factor_mib(f as f64)).max(0.0) * scale + factor_mib(nz));
    let gib = |m: f64| format!("{:.1}", m / 1024.0);
    println!(
        "Extrapolated, not measured: at {to} equations one iteration would take about {:.0} s with the total \
         time's exponent between the two largest timed sizes ({}; {} s with the factorisation's flops taken \
         as nonzeros^2 / equations, the dense-column estimate, from the {} fill), its symbolic analysis \
         {:.1} s once{}; the factor {} nonzeros{} ({} GiB of values, 8 bytes each); the iteration's \
         peak, those values plus the rest of the largest timed size's peak grown linearly, about {} GiB.",
        total / 1e3,
        format_args!("{:.2}", time_fit.1),
        by_flops.map_or_else(|| "n/a".into(), |t| format!("{:.0}", t / 1e3)),
        if measured_fill.is_some() {
            "measured"
        } else {
            "extrapolated"
        },
        symbolic / 1e3,
        if measured_symbolic.is_some() {
            " (measured, pattern only)"
        } else {
            " (extrapolated)"
        },
        nonzeros.map_or_else(|| "n/a".into(), |f| format!("{f:.2e}")),
        if measured_fill.is_some() {
            " (measured, pattern only)"
        } else {
            " (extrapolated with the fill's last exponent)"
        },
        nonzeros.map_or_else(|| "n/a".into(), |f| gib(factor_mib(f))),
        mib.map_or_else(|| "n/a".into(), gib),
    );
    println!();
}

fn main() -> ExitCode {
    let mut raw_sizes: Vec<String> = Vec::new();
    let mut linear = vec![LinearSolverKind::Lu];
    let mut max_equations: Option<usize> = None;
    let mut lu_max = LU_MAX_EQUATIONS;
    let mut three_d = false;
    let mut fill_max: Option<usize> = None;
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        if arg == "--3d" {
            three_d = true;
            continue;
        }
        if arg == "--linear" {
            let parsed: Result<Vec<LinearSolverKind>, _> = args
                .next()
                .unwrap_or_default()
                .split(',')
                .map(str::parse)
                .collect();
            match parsed {
                Ok(kinds) if !kinds.is_empty() => linear = kinds,
                Ok(_) => unreachable!("split yields at least one item"),
                Err(e) => {
                    eprintln!("--linear: {e}");
                    return ExitCode::FAILURE;
                }
            }
            continue;
        }
        if arg == "--max-equations" || arg == "--lu-max-equations" || arg == "--fill-max-equations"
        {
            let value = args.next().unwrap_or_default();
            let Ok(n) = value.trim().replace('_', "").parse::<usize>() else {
                eprintln!("{arg}: expected a number of equations, got `{value}`");
                return ExitCode::FAILURE;
            };
            if arg == "--max-equations" {
                max_equations = Some(n);
            } else if arg == "--fill-max-equations" {
                fill_max = Some(n);
            } else {
                lu_max = n;
            }
            continue;
        }
        raw_sizes.push(arg);
    }
    let run = if three_d {
        run_3d(&raw_sizes, max_equations, fill_max, &linear, lu_max)
    } else {
        run_2d(&raw_sizes, max_equations, &linear, lu_max).map(|r| (r, Vec::new()))
    };
    let ((rows, others), fills) = match run {
        Ok(r) => r,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::FAILURE;
        }
    };
    let peak = peak_mib();
    if three_d {
        print_3d_table(&rows, &fills, &linear);
    } else {
        print_2d_table(&rows, &linear);
    }
    for (k, &kind) in linear.iter().enumerate().skip(1) {
        // LU in the first columns, so a ratio above 1 is the other's gain
        let swap = kind == LinearSolverKind::Lu;
        let (a, b) = if swap {
            (kind, linear[0])
        } else {
            (linear[0], kind)
        };
        println!("{b} against {a} (same state; ratio = {a} time / {b} time):\n");
        println!(
            "| equations | solve ms ({a}) | solve ms ({b}) | ratio | total ms ({a}) | total ms ({b}) | ratio | symbolic ms ({a}) | symbolic ms ({b}) | ratio | peak MiB ({a}) | peak MiB ({b}) | {b} fallbacks |"
        );
        println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
        let mut skipped = Vec::new();
        for (first, o) in rows.iter().zip(&others) {
            let Some(other) = &o[k - 1] else {
                skipped.push(first.equations);
                continue;
            };
            let (r, o) = if swap { (other, first) } else { (first, other) };
            println!(
                "| {} | {} | {} | {:.2} | {} | {} | {:.2} | {} | {} | {:.2} | {} | {} | {} |",
                r.equations,
                fmt_ms(r.linear),
                fmt_ms(o.linear),
                r.linear / o.linear,
                fmt_ms(r.total),
                fmt_ms(o.total),
                r.total / o.total,
                fmt_ms(r.symbolic),
                fmt_ms(o.symbolic),
                r.symbolic / o.symbolic,
                fmt_mib(r.peak_mib),
                fmt_mib(o.peak_mib),
                o.fallbacks
            );
        }
        println!();
        if !skipped.is_empty() {
            let list: Vec<String> = skipped.iter().map(usize::to_string).collect();
            println!(
                "LU not run at {} equations (above --lu-max-equations {lu_max}).\n",
                list.join(", ")
            );
        }
    }
    if let Some(last) = rows.last() {
        println!(
            "Peak memory (VmHWM) of the whole run, after the largest size ({} equations): {} MiB.",
            last.equations,
            fmt_mib(peak)
        );
    }
    ExitCode::SUCCESS
}

/// The size of rayon's global pool (assembly and contact run on it).
fn rayon_threads() -> usize {
    std::thread::available_parallelism()
        .map(|n| n.get())
        .unwrap_or(1)
        .min(
            std::env::var("RAYON_NUM_THREADS")
                .ok()
                .and_then(|v| v.parse().ok())
                .filter(|&n: &usize| n > 0)
                .unwrap_or(usize::MAX),
        )
}
