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
//! The benchmark with criterion is `cargo bench --bench solver_scaling`.

use std::process::ExitCode;
use std::time::{Duration, Instant};

use solver::newton::{IterationProbe, IterationSample};
use solver::{LinearSolverKind, Method, Scene, SolveOptions, solve_model};

/// Refine factors giving about 1e3, 3e3, 1e4, 3e4 and 1e5 equations.
const SIZES: [(usize, usize); 5] = [(8, 4), (14, 7), (26, 13), (46, 23), (84, 42)];

/// Larger refine factors for `--max-equations`, with their nominal numbers
/// of equations (measured: about 28.8 equations per unit of `x y`).
const EXTRA_SIZES: [((usize, usize), usize); 2] = [((144, 72), 299_000), ((263, 132), 1_000_000)];

/// Default of `--lu-max-equations`: the LU is measured up to about 1e5
/// equations (826 MiB peak there).
const LU_MAX_EQUATIONS: usize = 200_000;

/// Timed iterations above [`HUGE`] equations.
const REPS_HUGE: usize = 3;
const HUGE: usize = 500_000;

/// Timed iterations per size (after the one building the symbolic LU);
/// fewer for sizes above [`LARGE`] equations.
const REPS: usize = 7;
const REPS_LARGE: usize = 5;
const LARGE: usize = 50_000;

/// One measured size.
struct Row {
    refine: (usize, usize),
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
    let model = scene.build_model()?;
    let free_dofs = model.mesh.node_count() * 2;
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
        ..SolveOptions::from_scene(&scene)
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
        "refine {}x{}: {} equations; step 1 of {steps} solved in {:.2} s ({} Newton iterations)",
        refine.0,
        refine.1,
        solution.equations,
        t.elapsed().as_secs_f64(),
        solution.newton_iterations
    );
    let state = solution.final_state.clone();
    let equations = solution.equations;
    drop(solution);
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
            probe_row(&model, &opts, &state, 2.0 * step, refine).map(Some)
        })
        .collect()
}

/// The first iteration of the second step from `state`, timed.
fn probe_row(
    model: &solver::Model,
    opts: &SolveOptions,
    state: &solver::State,
    to: f64,
    refine: (usize, usize),
) -> Result<Row, Box<dyn std::error::Error>> {
    let reset = reset_peak();
    let mut probe = IterationProbe::new(model, opts, state, to)?;
    let warm = probe.iteration()?;
    let symbolic = ms(probe.symbolic_time());
    let reps = if probe.equations() > HUGE {
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
        refine,
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

fn main() -> ExitCode {
    let mut sizes: Vec<(usize, usize)> = Vec::new();
    let mut linear = vec![LinearSolverKind::Lu];
    let mut max_equations: Option<usize> = None;
    let mut lu_max = LU_MAX_EQUATIONS;
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
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
        if arg == "--max-equations" || arg == "--lu-max-equations" {
            let value = args.next().unwrap_or_default();
            let Ok(n) = value.trim().replace('_', "").parse::<usize>() else {
                eprintln!("{arg}: expected a number of equations, got `{value}`");
                return ExitCode::FAILURE;
            };
            if arg == "--max-equations" {
                max_equations = Some(n);
            } else {
                lu_max = n;
            }
            continue;
        }
        match parse_size(&arg) {
            Some(s) => sizes.push(s),
            None => {
                eprintln!("expected refine factors like `26x13`, got `{arg}`");
                return ExitCode::FAILURE;
            }
        }
    }
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
    let base = match Scene::from_toml_str(
        solver::scenes::STACKED_CANTILEVER,
        "stacked-cantilever.toml",
    ) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::FAILURE;
        }
    };
    let mut rows = Vec::new();
    let mut others: Vec<Vec<Option<Row>>> = Vec::new();
    for &size in &sizes {
        match measure(&base, size, &linear, lu_max) {
            Ok(mut r) => match r.remove(0) {
                Some(first) => {
                    rows.push(first);
                    others.push(r);
                }
                None => unreachable!("the first solver always runs"),
            },
            Err(e) => {
                eprintln!("refine {}x{}: {e}", size.0, size.1);
                return ExitCode::FAILURE;
            }
        }
    }
    let peak = peak_mib();

    println!(
        "One Newton iteration, complete formulation, paper scene refined \
         (first iteration of load step 2 of {}; median of {REPS} runs, {REPS_LARGE} above {LARGE} equations, \
         {REPS_HUGE} above {HUGE}; {} rayon threads):\n",
        base.default_steps(),
        rayon_threads()
    );
    if linear.len() > 1 || linear[0] != LinearSolverKind::Lu {
        println!("Linear solver: {}.\n", linear[0]);
    }
    println!(
        "| refine (x, y) | equations | contact points | assembly ms | contact ms | solve ms | total ms | symbolic ms (once) | factor nonzeros | peak MiB |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for r in &rows {
        println!(
            "| {} x {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            r.refine.0,
            r.refine.1,
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
