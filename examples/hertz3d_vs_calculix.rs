//! gapsim against CalculiX on the 3D Hertz quarter model (issue #17 §4):
//! the gapsim half of `scripts/hertz3d-vs-calculix.sh`.
//!
//! ```text
//! cargo run --release --example hertz3d_vs_calculix -- [--calculix FILE.json] [--linear ldlt[,lu]] [--repeat N] [--out DIR]
//! ```
//!
//! Solves `scenes/hertz3d.toml` (the hexahedral mesh `hertz3d-hex.msh`,
//! linear elasticity) with the scene's own options (as `gapsim run SCENE`
//! does: one load step, the complete formulation, Lagrange-multiplier
//! contact) and each linear solver of `--linear` (default `ldlt`: the LU of
//! the 87 012 equations is much slower), `N` times each (default 1). A run's
//! time is the wall time of `Scene::from_file` (TOML and mesh reading),
//! `build_model::<3>` and `solve_model`, in this process: what a user of
//! `gapsim run` waits for, without process start-up and output. The
//! pressures are measured by [`gapsim::hertz::sphere::measure_3d`] (`P` four
//! times the bottom's z reaction, Hertz's `a` and `p0` from it, the peak
//! nodal pressure, the contact radius of the farthest node above 1e-3 of
//! the peak, current coordinates).
//!
//! `--calculix FILE.json` adds the row of `scripts/calculix-hertz3d.py`
//! (same mesh, its CPRESS and RF measured the same way) and the speed-up of
//! every gapsim row against it. With `--out DIR` the table goes to
//! `DIR/hertz3d-vs-calculix.{md,csv}`; it is always printed.

use std::error::Error;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use gapsim::timing::{load_average, median, process_cpu_seconds};

use gapsim::hertz::sphere::{Hertz3d, measure_3d};
use solver::{LinearSolverKind, Scene, SolveOptions, solve_model};

/// The scene of the comparison (relative to `scenes/`).
const SCENE: &str = "hertz3d.toml";
/// The element size near the contact (`scripts/make-hertz3d-mesh.py`).
const H: f64 = 0.1;
/// The indenter's radius.
const RADIUS: f64 = 10.0;

/// One gapsim configuration, measured.
struct GapsimRow {
    linear: LinearSolverKind,
    /// Wall time of each run.
    seconds: Vec<f64>,
    /// CPU time (user plus system, all threads) of each run, when known.
    cpu: Option<Vec<f64>>,
    measured: Hertz3d,
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

/// The CalculiX row (scripts/calculix-hertz3d.py's JSON).
struct CalculixRow {
    solver: String,
    /// The mesh file's name.
    mesh: String,
    seconds: Vec<f64>,
    cpu: Option<Vec<f64>>,
    threads: u64,
    penalty: f64,
    increment: f64,
    load: f64,
    a: f64,
    p0: f64,
    peak: f64,
    radius: f64,
    penetration: f64,
    increments: u64,
    iterations: u64,
    nodes: u64,
}

impl CalculixRow {
    fn peak_error(&self) -> f64 {
        self.peak / self.p0 - 1.0
    }

    fn radius_error(&self) -> f64 {
        (self.radius - self.a) / H
    }
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
        mesh: v["mesh"]
            .as_str()
            .and_then(|m| Path::new(m).file_name()?.to_str())
            .unwrap_or("?")
            .to_string(),
        seconds,
        cpu: v["cpu_seconds_all"]
            .as_array()
            .and_then(|a| a.iter().map(serde_json::Value::as_f64).collect()),
        threads: num("threads")? as u64,
        penalty: num("penalty")?,
        increment: num("increment")?,
        load: num("load")?,
        a: num("a")?,
        p0: num("p0")?,
        peak: num("peak")?,
        radius: num("radius")?,
        penetration: num("penetration")?,
        increments: num("increments")? as u64,
        iterations: num("iterations")? as u64,
        nodes: num("nodes")? as u64,
    })
}

fn run(
    scenes: &Path,
    linear: LinearSolverKind,
    repeat: usize,
) -> Result<GapsimRow, Box<dyn Error>> {
    let (mut seconds, mut cpu, mut lin, mut sym) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut last = None;
    for _ in 0..repeat {
        let cpu_start = process_cpu_seconds();
        let start = Instant::now();
        let s = Scene::from_file(scenes.join(SCENE))?;
        let model = s.build_model::<3>()?;
        let mut options = SolveOptions::from_scene(&s);
        options.linear = linear;
        let sol = solve_model(&model, &options).map_err(|e| format!("{SCENE} ({linear}): {e}"))?;
        seconds.push(start.elapsed().as_secs_f64());
        if let (Some(a), Some(b)) = (cpu_start, process_cpu_seconds()) {
            cpu.push(b - a);
        }
        lin.push(sol.timings.linear_solve.as_secs_f64());
        sym.push(sol.timings.symbolic_factorisation.as_secs_f64());
        eprintln!(
            "gapsim {SCENE} --linear {linear}: {:.2} s (cpu {:.2} s)",
            seconds.last().copied().unwrap_or_default(),
            cpu.last().copied().unwrap_or(f64::NAN)
        );
        let material = model.mesh.bodies[0].material;
        last = Some((sol, material));
    }
    let (sol, material) = last.ok_or("--repeat must be at least 1")?;
    Ok(GapsimRow {
        linear,
        measured: measure_3d(&sol, material.young, material.poisson, RADIUS)?,
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
        .map_or_else(|| "-".to_string(), |v| format!("{:.1}", median(v)))
}

fn runs_list(v: &[f64]) -> String {
    v.iter()
        .map(|s| format!("{s:.1} s"))
        .collect::<Vec<_>>()
        .join(", ")
}

fn main() -> Result<(), Box<dyn Error>> {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let mut calculix = None;
    let mut repeat = 1usize;
    let mut linears = vec![LinearSolverKind::Ldlt];
    let mut out = None;
    let mut args = std::env::args_os().skip(1);
    while let Some(a) = args.next() {
        let mut value = || args.next().ok_or(format!("{} needs a value", a.display()));
        match a.to_str() {
            Some("--calculix") => calculix = Some(PathBuf::from(value()?)),
            Some("--out") => out = Some(PathBuf::from(value()?)),
            Some("--linear") => {
                linears = value()?
                    .to_str()
                    .ok_or("--linear needs ldlt, lu or a list of them")?
                    .split(',')
                    .map(str::parse)
                    .collect::<Result<_, _>>()
                    .map_err(|e| format!("--linear: {e}"))?
            }
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
    for &linear in &linears {
        rows.push(run(&root.join("scenes"), linear, repeat)?);
    }
    let load_after = load_average();

    let threads = std::thread::available_parallelism().map_or(0, usize::from);
    let ccx_seconds = ccx.as_ref().map(|c| median(&c.seconds));
    let first = &rows[0];

    let mut md = String::new();
    writeln!(
        md,
        "3D Hertz: the quarter model `scenes/hertz3d.toml` on `scenes/hertz3d-hex.msh` ({} nodes, \
         hexahedra, h = {H} at the contact; a sphere of radius {RADIUS} pressed 0.1 into a block, \
         E = 200, nu = 0.3, linear elasticity). Hertz from each solver's own load P (four times \
         the bottom's z reaction): E* = E / (2 (1 - nu^2)), a = (3PR/4E*)^(1/3), \
         p0 = 3P/(2 pi a^2); peak: the largest nodal pressure, its error against p0; radius: \
         the largest hypot(x, y) of a slave node with pressure above 1e-3 of the peak (current \
         coordinates), its difference from a in units of h. Time: {} on this machine \
         ({threads} cores, load average {load_before} before the gapsim runs, {load_after} \
         after); gapsim: scene and mesh reading plus `build_model::<3>` and `solve_model`, \
         in-process, rayon's pool (RAYON_NUM_THREADS, default: one thread per core), one load \
         step with the complete formulation and Lagrange multipliers, as `gapsim run SCENE`; \
         CalculiX: the whole `ccx` process. CPU: user plus system time of all threads, less \
         sensitive than wall time to other work on the machine. Speed-up: CalculiX's wall \
         time over gapsim's.",
        first.nodes,
        if repeat == 1 {
            "one run".to_string()
        } else {
            format!("median of {repeat} runs")
        }
    )?;
    if let Some(c) = &ccx {
        writeln!(
            md,
            "\nCalculiX: {}, C3D8, linear elasticity, penalty surface-to-surface contact \
             (linear pressure-overclosure, slope {:.0e}: largest penetration {:.1e}), one \
             *STATIC step with initial increment {}, OMP_NUM_THREADS={}, {} nodes, run(s) {}; \
             its pressures: CPRESS at the slave nodes (.frd) at the current coordinates, its \
             P from RF at the bottom nodes, measured like gapsim's.",
            c.solver,
            c.penalty,
            c.penetration,
            c.increment,
            c.threads,
            c.nodes,
            runs_list(&c.seconds)
        )?;
    }
    writeln!(
        md,
        "\n| solver | linear solver | equations | time (s) | CPU (s) | speed-up vs CalculiX | P | a | p0 | peak pressure | peak error (%) | contact radius | radius - a (h) | Newton iterations | linear solve (s) | symbolic (s) |"
    )?;
    writeln!(
        md,
        "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|"
    )?;
    if let (Some(c), Some(t)) = (&ccx, ccx_seconds) {
        writeln!(
            md,
            "| {} | SPOOLES | - | {t:.1} | {} | 1.0 | {:.5} | {:.4} | {:.5} | {:.5} | {:+.2} | {:.4} | {:+.2} | {} ({} increments) | - | - |",
            c.solver,
            seconds_cell(&c.cpu),
            c.load,
            c.a,
            c.p0,
            c.peak,
            100.0 * c.peak_error(),
            c.radius,
            c.radius_error(),
            c.iterations,
            c.increments
        )?;
    }
    for r in &rows {
        let t = median(&r.seconds);
        let m = &r.measured;
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
            "| gapsim | {linear} | {} | {t:.1} | {} | {} | {:.5} | {:.4} | {:.5} | {:.5} | {:+.2} | {:.4} | {:+.2} | {newton} | {:.1} | {:.2} |",
            r.equations,
            seconds_cell(&r.cpu),
            ccx_seconds.map_or("-".to_string(), |c| format!("{:.1}", c / t)),
            m.load,
            m.a,
            m.p0,
            m.peak,
            100.0 * m.peak_error(),
            m.radius,
            m.radius_error(H),
            r.linear_seconds,
            r.symbolic_seconds
        )?;
    }
    if let Some(c) = ccx_seconds {
        writeln!(
            md,
            "\nTarget (issue #17): gapsim at least 10x faster than CalculiX on the same mesh."
        )?;
        let ccx_cpu = ccx.as_ref().and_then(|c| c.cpu.as_deref()).map(median);
        for r in &rows {
            let speedup = c / median(&r.seconds);
            let cpu_ratio = match (ccx_cpu, r.cpu.as_deref()) {
                (Some(c), Some(g)) if c >= median(g) => {
                    format!("; CPU time {:.1}x less", c / median(g))
                }
                (Some(c), Some(g)) => format!("; CPU time {:.1}x more", median(g) / c),
                _ => String::new(),
            };
            writeln!(
                md,
                "- {}: wall time {speedup:.1}x ({}{cpu_ratio})",
                r.linear,
                if speedup >= 10.0 { "met" } else { "missed" },
            )?;
        }
    }

    let mut csv = String::from(
        "solver,mesh,linear,nodes,equations,seconds_median,seconds_all,cpu_seconds_median,speedup_vs_calculix,\
         load,a,p0,peak,peak_error,radius,radius_error_h,newton_iterations,failed_iterations,\
         cutbacks,increments,lu_fallbacks,linear_solve_seconds,symbolic_seconds\n",
    );
    if let (Some(c), Some(t)) = (&ccx, ccx_seconds) {
        writeln!(
            csv,
            "{},{},spooles,{},,{t:.3},{},{},1,{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{},,,{},,,",
            c.solver,
            c.mesh,
            c.nodes,
            c.seconds
                .iter()
                .map(|s| format!("{s:.3}"))
                .collect::<Vec<_>>()
                .join(";"),
            c.cpu
                .as_deref()
                .map_or(String::new(), |v| format!("{:.2}", median(v))),
            c.load,
            c.a,
            c.p0,
            c.peak,
            c.peak_error(),
            c.radius,
            c.radius_error(),
            c.iterations,
            c.increments
        )?;
    }
    for r in &rows {
        let t = median(&r.seconds);
        let m = &r.measured;
        writeln!(
            csv,
            "gapsim,hertz3d-hex.msh,{},{},{},{t:.3},{},{},{},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{},{},{},,{},{:.3},{:.3}",
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
            m.load,
            m.a,
            m.p0,
            m.peak,
            m.peak_error(),
            m.radius,
            m.radius_error(H),
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
            ("hertz3d-vs-calculix.md", &md),
            ("hertz3d-vs-calculix.csv", &csv),
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
