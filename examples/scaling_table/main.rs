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
//!
//! The example is laid out by concept: `main.rs` (the command line, the
//! sizes and repetition counts, the comparison table of several solvers),
//! `run.rs` (the sizes of a run, 2D or 3D), `measure.rs` (one size: the
//! first load step, the probed iterations, the pattern-only analysis),
//! `table.rs` (the 2D and 3D tables, their growth exponents and the
//! extrapolation) and `stats.rs` (medians, exponents, the peak memory, the
//! number formats).

mod measure;
mod run;
mod stats;
mod table;

use std::process::ExitCode;
use std::time::Duration;

use solver::LinearSolverKind;

use run::{run_2d, run_3d};
use stats::{fmt_mib, fmt_ms, peak_mib};
use table::{print_2d_table, print_3d_table};

/// Refine factors giving about 1e3, 3e3, 1e4, 3e4 and 1e5 equations.
const SIZES: [(usize, usize); 5] = [(8, 4), (14, 7), (26, 13), (46, 23), (84, 42)];

/// Larger refine factors for `--max-equations`, with their nominal numbers
/// of equations (measured: about 28.8 equations per unit of `x y`).
const EXTRA_SIZES: [((usize, usize), usize); 2] = [((144, 72), 299_000), ((263, 132), 1_000_000)];

/// The 3D block of `--3d`.
const BLOCK_3D: &str = include_str!("../../scenes/block3d.toml");

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
