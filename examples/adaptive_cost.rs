//! What adaptive stepping buys on the large-sliding scenes (issue #8 §2:
//! "for a target error, the cost of adaptive Types 3/6 against
//! complete").
//!
//! ```text
//! cargo run --release --example adaptive_cost -- --out docs/adaptive
//! ```
//!
//! For `scenes/sliding.toml` and `scenes/sliding-held-out.toml` (step-end
//! re-pairing on, as the scenes set it), Types 3 and 6 are solved with
//! plain schedules of 10, 20, 40 and 80 steps and adaptively
//! (`[newton] taylor_tolerance` 1e-4 and 1e-5) from 10 and 40 scheduled
//! steps; the complete formulation with 10 steps (the fewest it converges
//! with at once; it is step-count independent) is the reference and the
//! cost unit. Per run:
//!
//! * `e_U`: the final strain energy's error, percent;
//! * `e_R`: the largest reaction error at the reference's steps, percent
//!   of its largest reaction (as `gapsim study` and the safety map);
//! * the cost: Newton iterations (accepted, discarded by re-pairing or
//!   accuracy halvings, and failed), kernel calls (evaluations,
//!   projections, step-end projections), each over the complete
//!   formulation's, and the wall time (machine dependent).
//!
//! Then, per scene, method and target error (|e_U| below 0.05 % and
//! 0.005 %, e_R below 1 %), the cheapest run in Newton iterations that
//! meets it. Writes `adaptive-cost.csv` (every run) and
//! `adaptive-cost.md` (both tables, linked from docs/benchmarks.md) into `--out`
//! (default `target/adaptive-cost`).

use std::fmt::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use contact_kernels::ApproxType;
use solver::{Method, Scene, Solution, SolveOptions, solve};

/// The scenes, by file name under `scenes/`.
const SCENES: [&str; 2] = ["sliding", "sliding-held-out"];
/// Plain schedules.
const PLAIN_STEPS: [usize; 4] = [10, 20, 40, 80];
/// Adaptive runs: (scheduled steps, tolerance).
const ADAPTIVE: [(usize, f64); 4] = [(10, 1e-4), (10, 1e-5), (40, 1e-4), (40, 1e-5)];
/// The reference's step count.
const REFERENCE_STEPS: usize = 10;
/// Target energy errors, percent.
const TARGETS_PERCENT: [f64; 2] = [0.05, 0.005];
/// Reaction tolerance of every target, percent.
const REACTION_TARGET_PERCENT: f64 = 1.0;

/// One run's measurements.
struct Row {
    scene: &'static str,
    method: Method,
    steps: usize,
    tolerance: Option<f64>,
    accepted_steps: usize,
    halvings: usize,
    energy_percent: f64,
    reaction_percent: f64,
    iterations: usize,
    kernel_calls: u64,
    seconds: f64,
}

fn iterations(s: &Solution) -> usize {
    s.newton_iterations + s.failed_iterations + s.repeated_iterations
}

fn kernel_calls(s: &Solution) -> u64 {
    s.kernel_counts.evaluate + s.kernel_counts.project + s.step_end_projections
}

/// The largest reaction difference at the ends of the reference's
/// scheduled steps (a sub-step of a cut-back, which the other run need not
/// have, is left out), percent of its largest reaction magnitude.
fn reaction_error_percent(sol: &Solution, reference: &Solution) -> Result<f64, String> {
    let scale = reference
        .step_records
        .iter()
        .flat_map(|r| r.reactions.iter())
        .map(|[x, y]| x.hypot(*y))
        .fold(0.0, f64::max);
    let mut worst: f64 = 0.0;
    let ends = (1..=reference.steps)
        .filter_map(|k| reference.step_records.iter().rev().find(|r| r.step == k));
    for b in ends {
        let a = sol
            .step_records
            .iter()
            .find(|a| a.load_factor == b.load_factor)
            .ok_or_else(|| format!("no step at load factor {}", b.load_factor))?;
        for (ra, rb) in a.reactions.iter().zip(&b.reactions) {
            worst = worst.max((ra[0] - rb[0]).abs()).max((ra[1] - rb[1]).abs());
        }
    }
    Ok(100.0 * worst / scale)
}

fn label(method: Method) -> String {
    match method {
        Method::Complete => "complete".into(),
        Method::Approx(ty) => format!("Type {ty}"),
    }
}

fn schedule(row: &Row) -> String {
    match row.tolerance {
        None => format!("{} steps", row.steps),
        Some(t) => format!("{} steps, tolerance {t:.0e}", row.steps),
    }
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("adaptive_cost: {e}");
            ExitCode::FAILURE
        }
    }
}

fn parse_out() -> Result<PathBuf, String> {
    let mut out = PathBuf::from("target/adaptive-cost");
    let mut it = std::env::args().skip(1);
    while let Some(a) = it.next() {
        match a.as_str() {
            "--out" => out = it.next().ok_or("--out needs a directory")?.into(),
            s => return Err(format!("unknown argument `{s}`")),
        }
    }
    Ok(out)
}

fn solve_timed(
    name: &str,
    scene: &Scene,
    options: &SolveOptions,
) -> Result<(Solution, f64), String> {
    let t = Instant::now();
    let sol = solve(scene, options)
        .map_err(|e| format!("{name}, {}, {} steps: {e}", options.method, options.steps))?;
    Ok((sol, t.elapsed().as_secs_f64()))
}

fn run() -> Result<(), String> {
    let out = parse_out()?;
    let mut rows = Vec::new();
    for name in SCENES {
        let path = format!("{}/scenes/{name}.toml", env!("CARGO_MANIFEST_DIR"));
        let scene = Scene::from_file(&path).map_err(|e| e.to_string())?;
        let base = SolveOptions::from_scene(&scene);
        let (reference, seconds) = solve_timed(
            name,
            &scene,
            &SolveOptions {
                method: Method::Complete,
                steps: REFERENCE_STEPS,
                ..base.clone()
            },
        )?;
        let row = |method, steps, tolerance, sol: &Solution, seconds| -> Result<Row, String> {
            Ok(Row {
                scene: name,
                method,
                steps,
                tolerance,
                accepted_steps: sol.step_records.len(),
                halvings: sol.accuracy_halvings.len(),
                energy_percent: 100.0 * (sol.strain_energy / reference.strain_energy - 1.0),
                reaction_percent: reaction_error_percent(sol, &reference)?,
                iterations: iterations(sol),
                kernel_calls: kernel_calls(sol),
                seconds,
            })
        };
        rows.push(row(
            Method::Complete,
            REFERENCE_STEPS,
            None,
            &reference,
            seconds,
        )?);
        for ty in [ApproxType::Type3, ApproxType::Type6] {
            let method = Method::Approx(ty);
            let runs = PLAIN_STEPS
                .iter()
                .map(|&n| (n, None))
                .chain(ADAPTIVE.iter().map(|&(n, t)| (n, Some(t))));
            for (steps, tolerance) in runs {
                let options = SolveOptions {
                    method,
                    steps,
                    taylor_tolerance: tolerance,
                    ..base.clone()
                };
                let (sol, seconds) = solve_timed(name, &scene, &options)?;
                let r = row(method, steps, tolerance, &sol, seconds)?;
                println!(
                    "{name}, {}, {}: e_U {:+.2e} %, e_R {:.2e} %, {} iterations",
                    label(method),
                    schedule(&r),
                    r.energy_percent,
                    r.reaction_percent,
                    r.iterations
                );
                rows.push(r);
            }
        }
    }
    std::fs::create_dir_all(&out).map_err(|e| format!("{}: {e}", out.display()))?;
    let csv_path = out.join("adaptive-cost.csv");
    solver::report::write_atomic(&csv_path, csv(&rows).as_bytes())
        .map_err(|e| format!("{}: {e}", csv_path.display()))?;
    let md_path = out.join("adaptive-cost.md");
    solver::report::write_atomic(&md_path, markdown(&rows).as_bytes())
        .map_err(|e| format!("{}: {e}", md_path.display()))?;
    println!("wrote {} and {}", csv_path.display(), md_path.display());
    Ok(())
}

fn csv(rows: &[Row]) -> String {
    let mut s = String::from(
        "scene,method,steps,taylor_tolerance,accepted_steps,accuracy_halvings,\
         energy_error_percent,reaction_error_percent,newton_iterations,kernel_calls,wall_seconds\n",
    );
    for r in rows {
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{:e},{:e},{},{},{:.4}",
            r.scene,
            r.method,
            r.steps,
            r.tolerance.map(|t| format!("{t:e}")).unwrap_or_default(),
            r.accepted_steps,
            r.halvings,
            r.energy_percent,
            r.reaction_percent,
            r.iterations,
            r.kernel_calls,
            r.seconds
        );
    }
    s
}

/// The reference row of `scene` (the complete formulation).
fn reference<'a>(rows: &'a [Row], scene: &str) -> &'a Row {
    rows.iter()
        .find(|r| r.scene == scene && r.method == Method::Complete)
        .expect("every scene has its reference row")
}

fn markdown(rows: &[Row]) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "Errors against the complete formulation ({REFERENCE_STEPS} steps; step-count \
         independent), cost over its cost (Newton iterations including discarded ones; kernel \
         calls). Generated by `cargo run --release --example adaptive_cost -- --out \
         docs/adaptive`.\n"
    );
    let _ = writeln!(
        s,
        "| scene | method | schedule | steps taken | halvings | e_U % | e_R % | iterations (x complete) | kernel calls (x complete) |"
    );
    let _ = writeln!(s, "|---|---|---|---:|---:|---:|---:|---:|---:|");
    for r in rows {
        let c = reference(rows, r.scene);
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {:+.1e} | {:.1e} | {} ({:.2}) | {} ({:.2}) |",
            r.scene,
            label(r.method),
            schedule(r),
            r.accepted_steps,
            r.halvings,
            r.energy_percent,
            r.reaction_percent,
            r.iterations,
            r.iterations as f64 / c.iterations as f64,
            r.kernel_calls,
            r.kernel_calls as f64 / c.kernel_calls as f64,
        );
    }
    let _ = writeln!(
        s,
        "\nThe cheapest run (Newton iterations) that meets a target: |e_U| below the target and \
         e_R below {REACTION_TARGET_PERCENT} %.\n"
    );
    let _ = writeln!(
        s,
        "| scene | method | target e_U | cheapest run | iterations (x complete) | kernel calls (x complete) |"
    );
    let _ = writeln!(s, "|---|---|---:|---|---:|---:|");
    for scene in SCENES {
        let c = reference(rows, scene);
        for ty in [ApproxType::Type3, ApproxType::Type6] {
            for target in TARGETS_PERCENT {
                let best = rows
                    .iter()
                    .filter(|r| r.scene == scene && r.method == Method::Approx(ty))
                    .filter(|r| {
                        r.energy_percent.abs() < target
                            && r.reaction_percent < REACTION_TARGET_PERCENT
                    })
                    .min_by_key(|r| r.iterations);
                let cells = match best {
                    Some(r) => format!(
                        "{} | {} ({:.2}) | {} ({:.2})",
                        schedule(r),
                        r.iterations,
                        r.iterations as f64 / c.iterations as f64,
                        r.kernel_calls,
                        r.kernel_calls as f64 / c.kernel_calls as f64
                    ),
                    None => "none of the runs | | ".into(),
                };
                let _ = writeln!(s, "| {scene} | Type {ty} | {target} % | {cells} |");
            }
        }
    }
    s
}
