//! gapsim against CalculiX on the Hertz quarter model (issue #10 §2): the
//! gapsim half of `scripts/hertz-vs-calculix.sh`.
//!
//! ```text
//! cargo run --release --example hertz_vs_calculix -- [--calculix FILE.json] [--repeat N] [--out DIR]
//! ```
//!
//! Solves `scenes/hertz.toml` (finite strain, St Venant–Kirchhoff,
//! geometrically nonlinear) and `scenes/hertz-small-strain.toml` (linear
//! elasticity) with the scenes' own options (as `gapsim run SCENE` does: one
//! load step, the complete formulation, Lagrange-multiplier contact) and each
//! linear solver (`lu`, `ldlt`), `N` times each (default 3). A run's time is
//! the wall time of `Scene::from_file` (TOML and mesh reading) plus
//! `solver::solve`, in this process: what a user of `gapsim run` waits for,
//! without process start-up and printing; the table gives the median of the
//! `N` runs. The pressures are measured by [`gapsim::hertz::measure`] (peak
//! nodal pressure; `p0` and `a` of the least-squares fit `p^2 = A + B x^2`).
//!
//! `--calculix FILE.json` adds the row of `scripts/calculix-hertz.py` (same
//! mesh, same measurement of its nodal contact pressures) and the speed-up
//! of every gapsim row against it. With `--out DIR` the table goes to
//! `DIR/hertz-vs-calculix.{md,csv}`; it is always printed.

use std::error::Error;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use gapsim::timing::{load_average, median, process_cpu_seconds};

use gapsim::hertz::{HertzMeasured, SCENES, measure, pressure_profile};
use solver::{LinearSolverKind, Scene, SolveOptions, solve};

/// The scenes of the comparison (relative to `scenes/`) and their solids.
const RUNS: [(&str, &str); 2] = [
    ("hertz.toml", "finite"),
    ("hertz-small-strain.toml", "small"),
];

/// One gapsim configuration, measured.
struct GapsimRow {
    scene: &'static str,
    solids: &'static str,
    linear: LinearSolverKind,
    /// Wall time of each run.
    seconds: Vec<f64>,
    /// CPU time (user plus system, all threads) of each run, when known.
    cpu: Option<Vec<f64>>,
    measured: HertzMeasured,
    /// Current x of the outermost slave node with positive pressure.
    a_last: f64,
    newton: usize,
    failed: usize,
    cutbacks: usize,
    fallbacks: usize,
    equations: usize,
    nodes: usize,
    /// Median over the runs of `Timings::linear_solve`.
    linear_seconds: f64,
    /// Median over the runs of `Timings::symbolic_factorisation`.
    symbolic_seconds: f64,
}

/// The CalculiX row (scripts/calculix-hertz.py's JSON).
struct CalculixRow {
    solver: String,
    seconds: Vec<f64>,
    cpu: Option<Vec<f64>>,
    threads: u64,
    penalty: f64,
    peak: f64,
    p0_fit: Option<f64>,
    a_fit: Option<f64>,
    a_last: f64,
    increments: u64,
    iterations: u64,
    nodes: u64,
}

fn read_calculix(path: &Path) -> Result<CalculixRow, Box<dyn Error>> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let v: serde_json::Value =
        serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
    let num = |key: &str| -> Result<f64, String> {
        v[key]
            .as_f64()
            .ok_or_else(|| format!("{}: no number `{key}`", path.display()))
    };
    let seconds = v["seconds_all"]
        .as_array()
        .and_then(|a| a.iter().map(serde_json::Value::as_f64).collect())
        .ok_or_else(|| format!("{}: no list `seconds_all`", path.display()))?;
    Ok(CalculixRow {
        solver: v["solver"].as_str().unwrap_or("CalculiX").to_string(),
        seconds,
        cpu: v["cpu_seconds_all"]
            .as_array()
            .and_then(|a| a.iter().map(serde_json::Value::as_f64).collect()),
        threads: num("threads")? as u64,
        penalty: num("penalty")?,
        peak: num("peak")?,
        p0_fit: v["p0_fit"].as_f64(),
        a_fit: v["a_fit"].as_f64(),
        a_last: num("a_last")?,
        increments: num("increments")? as u64,
        iterations: num("iterations")? as u64,
        nodes: num("nodes")? as u64,
    })
}

fn run(
    scenes: &Path,
    scene: &'static str,
    solids: &'static str,
    linear: LinearSolverKind,
    repeat: usize,
) -> Result<GapsimRow, Box<dyn Error>> {
    let (mut seconds, mut cpu, mut lin, mut sym) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut last = None;
    for _ in 0..repeat {
        let cpu_start = process_cpu_seconds();
        let start = Instant::now();
        let s = Scene::from_file(scenes.join(scene))?;
        let mut options = SolveOptions::from_scene(&s);
        options.linear = linear;
        let sol = solve(&s, &options).map_err(|e| format!("{scene} ({linear}): {e}"))?;
        seconds.push(start.elapsed().as_secs_f64());
        if let (Some(a), Some(b)) = (cpu_start, process_cpu_seconds()) {
            cpu.push(b - a);
        }
        lin.push(sol.timings.linear_solve.as_secs_f64());
        sym.push(sol.timings.symbolic_factorisation.as_secs_f64());
        eprintln!(
            "gapsim {scene} --linear {linear}: {:.3} s (cpu {:.2} s)",
            seconds.last().copied().unwrap_or_default(),
            cpu.last().copied().unwrap_or(f64::NAN)
        );
        last = Some(sol);
    }
    let sol = last.ok_or("--repeat must be at least 1")?;
    Ok(GapsimRow {
        scene,
        solids,
        linear,
        measured: measure(&sol, &SCENES),
        a_last: pressure_profile(&sol)
            .iter()
            .filter(|n| n.pressure > 0.0)
            .fold(0.0, |m, n| f64::max(m, n.x)),
        newton: sol.newton_iterations,
        failed: sol.failed_iterations,
        cutbacks: sol.cutbacks.len(),
        fallbacks: sol.linear_fallbacks,
        equations: sol.equations,
        nodes: sol.mesh.nodes_ref.len(),
        linear_seconds: median(&lin),
        symbolic_seconds: median(&sym),
        cpu: (cpu.len() == seconds.len()).then_some(cpu),
        seconds,
    })
}

fn seconds_cell(v: &Option<Vec<f64>>) -> String {
    v.as_deref()
        .map_or_else(|| "-".to_string(), |v| format!("{:.2}", median(v)))
}

fn percent(v: Option<f64>) -> String {
    v.map_or_else(|| "-".to_string(), |v| format!("{:+.2}", 100.0 * v))
}

fn csv_opt(v: Option<f64>) -> String {
    v.map_or_else(String::new, |v| format!("{v:.6e}"))
}

fn main() -> Result<(), Box<dyn Error>> {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let mut calculix = None;
    let mut repeat = 3usize;
    let mut out = None;
    let mut args = std::env::args_os().skip(1);
    while let Some(a) = args.next() {
        let mut value = || args.next().ok_or(format!("{} needs a value", a.display()));
        match a.to_str() {
            Some("--calculix") => calculix = Some(PathBuf::from(value()?)),
            Some("--out") => out = Some(PathBuf::from(value()?)),
            Some("--repeat") => {
                repeat = value()?
                    .to_str()
                    .and_then(|s| s.parse().ok())
                    .filter(|&n: &usize| n >= 1)
                    .ok_or("--repeat needs a count of at least 1")?
            }
            _ => return Err(format!("unknown argument {}", a.display()).into()),
        }
    }
    let ccx = calculix.as_deref().map(read_calculix).transpose()?;

    let load_before = load_average();
    let mut rows = Vec::new();
    for (scene, solids) in RUNS {
        for &linear in LinearSolverKind::ALL {
            rows.push(run(&root.join("scenes"), scene, solids, linear, repeat)?);
        }
    }
    let load_after = load_average();

    let (a, p0) = (SCENES.half_width(), SCENES.peak_pressure());
    let rel = |v: f64, exact: f64| v / exact - 1.0;
    let threads = std::thread::available_parallelism().map_or(0, usize::from);
    let ccx_seconds = ccx.as_ref().map(|c| median(&c.seconds));

    let mut md = String::new();
    writeln!(
        md,
        "Hertz: a = {a:.4}, p0 = {p0:.4} (plane strain, E = 200, nu = 0.3, R = 10, P = 8.63); \
         the quarter model `scenes/hertz.msh` ({} nodes). Time: median of {repeat} runs on this \
         machine ({threads} cores, load average {load_before} before the gapsim runs, \
         {load_after} after); gapsim: scene and mesh reading plus `solve`, in-process, \
         rayon's pool (RAYON_NUM_THREADS, default: one thread per core); CalculiX: the \
         whole `ccx` process. CPU: user plus system time of all threads (median), less \
         sensitive than wall time to other work on the machine. Speed-up: CalculiX's \
         wall time over gapsim's. Errors against Hertz: peak nodal pressure and the \
         least-squares fit p^2 = A + B x^2 (`gapsim::hertz::measure`) against p0 and a; \
         last node: the current x of the outermost slave node in contact against a. \
         Solids: finite = `scenes/hertz.toml` (St Venant–Kirchhoff, geometrically \
         nonlinear: its strain scale a / 2R = {:.0} % at the contact is outside Hertz's linear \
         theory, see hertz-refinement.md), small = `scenes/hertz-small-strain.toml` \
         (linear elasticity, Hertz's assumptions, as CalculiX here); both one load step \
         with the complete formulation and Lagrange multipliers, as `gapsim run SCENE`.",
        rows[0].nodes,
        100.0 * a / (2.0 * SCENES.radius)
    )?;
    if let Some(c) = &ccx {
        writeln!(
            md,
            "\nCalculiX: {}, CPE4, linear elasticity, penalty surface-to-surface contact \
             (linear pressure-overclosure, slope {:.0e}), OMP_NUM_THREADS={}, {} nodes, \
             runs {}; its pressures: CPRESS at the slave nodes (.frd) over the current x, \
             measured like gapsim's.",
            c.solver,
            c.penalty,
            c.threads,
            c.nodes,
            c.seconds
                .iter()
                .map(|s| format!("{s:.2} s"))
                .collect::<Vec<_>>()
                .join(", ")
        )?;
    }
    writeln!(
        md,
        "\n| solver | solids | linear solver | time (s) | CPU (s) | speed-up vs CalculiX | peak p (%) | fit p0 (%) | fit a (%) | last node a (%) | Newton iterations | linear solve (s) | symbolic (s) |"
    )?;
    writeln!(
        md,
        "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|"
    )?;
    if let (Some(c), Some(t)) = (&ccx, ccx_seconds) {
        writeln!(
            md,
            "| {} | small | SPOOLES | {t:.2} | {} | 1.0 | {} | {} | {} | {} | {} ({} increments) | - | - |",
            c.solver,
            seconds_cell(&c.cpu),
            percent(Some(rel(c.peak, p0))),
            percent(c.p0_fit.map(|v| rel(v, p0))),
            percent(c.a_fit.map(|v| rel(v, a))),
            percent(Some(rel(c.a_last, a))),
            c.iterations,
            c.increments
        )?;
    }
    for r in &rows {
        let t = median(&r.seconds);
        let mut newton = r.newton.to_string();
        if r.cutbacks > 0 {
            write!(
                newton,
                " + {} in {} failed attempt(s)",
                r.failed, r.cutbacks
            )?;
        }
        let mut linear = r.linear.to_string();
        if r.fallbacks > 0 {
            write!(linear, " ({} solves fell back to LU)", r.fallbacks)?;
        }
        writeln!(
            md,
            "| gapsim | {} | {linear} | {t:.2} | {} | {} | {} | {} | {} | {} | {newton} | {:.2} | {:.3} |",
            r.solids,
            seconds_cell(&r.cpu),
            ccx_seconds.map_or("-".to_string(), |c| format!("{:.1}", c / t)),
            percent(Some(r.measured.peak_error(&SCENES))),
            percent(r.measured.p0_fit_error(&SCENES)),
            percent(r.measured.a_fit_error(&SCENES)),
            percent(Some(rel(r.a_last, a))),
            r.linear_seconds,
            r.symbolic_seconds
        )?;
    }
    if let Some(c) = ccx_seconds {
        writeln!(
            md,
            "\nTarget (issue #10): gapsim at least 10x faster than CalculiX with the peak pressure within 2 % of p0."
        )?;
        let ccx_cpu = ccx.as_ref().and_then(|c| c.cpu.as_deref()).map(median);
        for r in &rows {
            let speedup = c / median(&r.seconds);
            let err = r.measured.peak_error(&SCENES);
            let cpu_ratio = match (ccx_cpu, r.cpu.as_deref()) {
                (Some(c), Some(g)) => format!("; CPU time {:.1}x less", c / median(g)),
                _ => String::new(),
            };
            writeln!(
                md,
                "- {} solids, {}: wall time {speedup:.1}x ({}{cpu_ratio}), peak {:+.2} % ({})",
                r.solids,
                r.linear,
                if speedup >= 10.0 { "met" } else { "missed" },
                100.0 * err,
                if err.abs() <= 0.02 { "met" } else { "missed" }
            )?;
        }
    }

    let mut csv = String::from(
        "solver,scene,solids,linear,nodes,equations,seconds_median,seconds_all,cpu_seconds_median,speedup_vs_calculix,\
         peak,peak_error,p0_fit,p0_fit_error,a_fit,a_fit_error,a_last,newton_iterations,failed_iterations,\
         cutbacks,increments,lu_fallbacks,linear_solve_seconds,symbolic_seconds\n",
    );
    if let (Some(c), Some(t)) = (&ccx, ccx_seconds) {
        writeln!(
            csv,
            "{},hertz.msh,small,spooles,{},,{t:.3},{},{},1,{:.6e},{:.6e},{},{},{},{},{:.6e},{},,,{},,,",
            c.solver,
            c.nodes,
            c.seconds
                .iter()
                .map(|s| format!("{s:.3}"))
                .collect::<Vec<_>>()
                .join(";"),
            c.cpu
                .as_deref()
                .map_or(String::new(), |v| format!("{:.2}", median(v))),
            c.peak,
            rel(c.peak, p0),
            csv_opt(c.p0_fit),
            csv_opt(c.p0_fit.map(|v| rel(v, p0))),
            csv_opt(c.a_fit),
            csv_opt(c.a_fit.map(|v| rel(v, a))),
            c.a_last,
            c.iterations,
            c.increments
        )?;
    }
    for r in &rows {
        let t = median(&r.seconds);
        let m = &r.measured;
        writeln!(
            csv,
            "gapsim,{},{},{},{},{},{t:.3},{},{},{},{:.6e},{:.6e},{},{},{},{},{:.6e},{},{},{},,{},{:.3},{:.3}",
            r.scene,
            r.solids,
            r.linear,
            r.nodes,
            r.equations,
            r.seconds
                .iter()
                .map(|s| format!("{s:.3}"))
                .collect::<Vec<_>>()
                .join(";"),
            r.cpu
                .as_deref()
                .map_or(String::new(), |v| format!("{:.2}", median(v))),
            ccx_seconds.map_or(String::new(), |c| format!("{:.2}", c / t)),
            m.peak,
            m.peak_error(&SCENES),
            csv_opt(m.p0_fit),
            csv_opt(m.p0_fit_error(&SCENES)),
            csv_opt(m.a_fit),
            csv_opt(m.a_fit_error(&SCENES)),
            r.a_last,
            r.newton,
            r.failed,
            r.cutbacks,
            r.fallbacks,
            r.linear_seconds,
            r.symbolic_seconds
        )?;
    }

    if let Some(dir) = &out {
        std::fs::create_dir_all(dir)
            .map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
        for (name, text) in [
            ("hertz-vs-calculix.md", &md),
            ("hertz-vs-calculix.csv", &csv),
        ] {
            let path = dir.join(name);
            solver::report::write_atomic(&path, text)
                .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
            eprintln!("wrote {}", path.display());
        }
    }
    print!("{md}");
    Ok(())
}
