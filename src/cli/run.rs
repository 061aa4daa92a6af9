//! `gapsim run`: solve one scene and print a summary.
//!
//! ```text
//! gapsim run [SCENE.toml] [--type T|complete] [--steps N] [--formulation F] [--linear lu|ldlt|petsc] [--petsc-options "..."] [--out DIR] [--every-step]
//! ```
//!
//! Without `SCENE` the embedded paper scene is solved. With `--out DIR` the
//! final state (and with `--every-step` every converged step) is written as
//! `.vtu` files that ParaView opens (displacement, stresses, contact
//! pressure and gap; with `--every-step` also `steps.pvd`, the step files
//! as one time series over the load factor), and a scene with contact pairs also gets
//! `DIR/contact.csv`, the final state's contact pressure and gap at every
//! slave node (see [`solver::report::contact_csv`]); the reaction force of every
//! `[[fix]]` and `[[prescribe]]` group at every converged step goes to
//! `reactions.csv`. Types 1–6 also report the step-end checks: step repeats
//! for re-pairing, accuracy halvings and the largest Taylor remainder (with
//! `--every-step`, every step's). `DIR` is checked before the solve, and
//! holds either the whole new result set or the old one, never a mix
//! ([`super::out_dir`]); files of other names in it are left alone.
//!
//! Every converged load step prints a progress line on stderr (`step 2/4:
//! load factor 0.5, 6 iterations, 0 cut-backs, 1.2 s`), every cut-back
//! one more. On a terminal a live line shows where a step is in between
//! (`towards load factor 0.5: Newton iteration 3, residual 1.2e-3, 80.4
//! s`, rewritten in place at most twice a second and cleared before the
//! next line); piped or redirected, stderr gets only the step lines. Ctrl-C (or SIGTERM) stops the solve before its next Newton
//! iteration: the command then exits with an error, writes nothing and
//! leaves `DIR` as it was.

use std::io::{IsTerminal, Write};
use std::path::PathBuf;
use std::sync::Mutex;
use std::time::{Duration, Instant};

use clap::Args;
use contact_kernels::Formulation;
use solver::ids::NodeId;
use solver::model::{Facet, FacetOf};
use solver::scene::Dimension;
use solver::{Dim, LinearSolverKind, Method, Scene, SceneDim, Solution, SolveOptions, SurfaceDim};

use solver::monitor::{IterationProgress, Monitor, StepProgress};
use solver::report::{ContactTable, contact_csv, reactions_csv};
use solver::{Cutback, SolverError};

use super::CommandResult;
use super::interrupt::Interrupt;
use super::out_dir::OutDir;

/// Whether `name` is a file of `gapsim run`'s result set: `final.vtu`,
/// `contact.csv`, `reactions.csv`, `step-NNNN.vtu`, `steps.pvd`.
pub fn is_result_file(name: &str) -> bool {
    matches!(
        name,
        "final.vtu" | "contact.csv" | "reactions.csv" | "steps.pvd"
    ) || name
        .strip_prefix("step-")
        .and_then(|n| n.strip_suffix(".vtu"))
        .is_some_and(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()))
}

/// The shortest time between two rewrites of the live iteration line.
const LIVE_INTERVAL: Duration = Duration::from_millis(500);

/// The solve's progress lines on stderr, and Ctrl-C.
struct Progress<'a> {
    interrupt: &'a Interrupt,
    steps: usize,
    /// On a terminal, the live line inside a step (the Newton iteration,
    /// its residual and the time, rewritten in place at most every
    /// [`LIVE_INTERVAL`]): when it was last written. `None` when stderr
    /// is not a terminal (piped or redirected: only the step lines).
    live: Option<Mutex<Option<Instant>>>,
    /// Whether this process reports (not a rank other than 0 of a run
    /// across MPI ranks).
    root: bool,
}

impl Progress<'_> {
    /// Clears the live line before a step or cut-back line.
    fn clear_live(&self) {
        if let Some(live) = &self.live {
            let mut last = live.lock().unwrap_or_else(|e| e.into_inner());
            if last.take().is_some() {
                eprint!("\r\x1b[K");
            }
        }
    }
}

impl Monitor for Progress<'_> {
    fn iteration(&self, p: &IterationProgress) {
        let Some(live) = &self.live else { return };
        let mut last = live.lock().unwrap_or_else(|e| e.into_inner());
        let now = Instant::now();
        if last.is_some_and(|t| now.duration_since(t) < LIVE_INTERVAL) {
            return;
        }
        *last = Some(now);
        eprint!(
            "\r\x1b[K  towards load factor {}: Newton iteration {}, residual {:.3e}, {:.1} s",
            p.target,
            p.iteration,
            p.residual,
            p.elapsed.as_secs_f64()
        );
        let _ = std::io::stderr().flush();
    }

    fn step_done(&self, p: &StepProgress) {
        self.clear_live();
        if !self.root {
            return;
        }
        eprintln!(
            "step {}/{}: load factor {}, {} iterations, {} cut-backs, {:.1} s",
            p.step,
            p.steps,
            p.load_factor,
            p.iterations,
            p.cutbacks,
            p.elapsed.as_secs_f64()
        );
    }

    fn cut_back(&self, c: &Cutback) {
        self.clear_live();
        if !self.root {
            return;
        }
        eprintln!(
            "step {}/{}: cut back, {} -> {} failed: {}",
            c.step, self.steps, c.from_load_factor, c.attempted_load_factor, c.reason
        );
    }

    fn stop_requested(&self) -> bool {
        self.interrupt.requested()
    }
}

/// Arguments of `gapsim run`.
#[derive(Debug, Clone, Args)]
pub struct RunArgs {
    /// Scene file (TOML); default: the embedded paper scene
    /// (`scenes/stacked-cantilever.toml`).
    pub scene: Option<PathBuf>,

    /// `complete` or an approximation type 1..6 (default: the scene's).
    #[arg(long = "type", value_name = "T|complete")]
    pub method: Option<Method>,

    /// Number of equal load steps (default: the scene's).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..=100_000))]
    pub steps: Option<u64>,

    /// Override every contact pair's formulation.
    #[arg(long, value_name = "F")]
    pub formulation: Option<Formulation>,

    /// The linear solver of the Newton iterations (default: the scene's
    /// `[newton] linear`, LU unless set; `petsc` in a build with the
    /// `petsc` feature, docs/petsc.md).
    #[arg(long, value_name = "lu|ldlt|petsc")]
    pub linear: Option<LinearSolverKind>,

    /// PETSc options of `--linear petsc`, in PETSc's syntax (quoted), applied
    /// after the scene's `[newton] petsc_options`.
    #[arg(long, value_name = "OPTIONS", allow_hyphen_values = true)]
    pub petsc_options: Option<String>,

    /// Types 1-6: halve a step whose largest Taylor remainder (over the
    /// slave segment's or face's size) exceeds this (default: the scene's
    /// `[newton] taylor_tolerance`, none unless set).
    #[arg(long, value_name = "TOL", value_parser = parse_tolerance)]
    pub taylor_tolerance: Option<f64>,

    /// Types 1-6: where a step's Taylor expansions are taken, the step's
    /// predictor or its start (the paper's scheme; default: the scene's
    /// `[newton] expand_at`, the predictor unless set).
    #[arg(long, value_name = "predictor|start")]
    pub expand_at: Option<solver::ExpansionPoint>,

    /// Write `.vtu` files of the result into this directory.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,

    /// With `--out`: one file per converged step (`step-0000.vtu`, ...).
    #[arg(long, requires = "out")]
    pub every_step: bool,
}

/// Loads `path`, or the embedded paper scene.
pub fn load_scene(path: Option<&PathBuf>) -> Result<Scene, solver::SceneError> {
    match path {
        Some(p) => Scene::from_file(p),
        None => Scene::from_toml_str(
            solver::scenes::STACKED_CANTILEVER,
            "stacked-cantilever.toml (embedded)",
        ),
    }
}

/// A `--taylor-tolerance`: a positive finite number.
fn parse_tolerance(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(t) if t.is_finite() && t > 0.0 => Ok(t),
        Ok(_) => Err(format!("{s}: must be positive and finite")),
        Err(e) => Err(format!("{s}: {e}")),
    }
}

/// Runs `gapsim run`.
pub fn run(args: &RunArgs) -> CommandResult {
    let scene = load_scene(args.scene.as_ref())?;
    let mut options = SolveOptions::from_scene(&scene);
    if let Some(m) = args.method {
        options.method = m;
    }
    if let Some(n) = args.steps {
        options.steps = n as usize;
    }
    if let Some(k) = args.linear {
        options.linear = k;
    }
    if let Some(o) = &args.petsc_options {
        options.petsc_options = format!("{} {o}", options.petsc_options);
    }
    if let Some(t) = args.taylor_tolerance {
        options.taylor_tolerance = Some(t);
    }
    if let Some(e) = args.expand_at {
        options.expand_at = e;
    }
    options.formulation = args.formulation;
    options.record_steps = args.every_step;
    // across MPI ranks (mpiexec, --linear petsc) rank 0 reports and writes
    let root = solver::linear::launch_rank(options.linear).map_err(|e| e.to_string())? == 0;
    let out = match &args.out {
        Some(dir) if root => Some(OutDir::check(dir, is_result_file)?),
        _ => None,
    };
    let interrupt = Interrupt::install().map_err(|e| format!("cannot catch Ctrl-C: {e}"))?;
    let progress = Progress {
        interrupt: &interrupt,
        steps: options.steps,
        live: (root && std::io::stderr().is_terminal()).then(|| Mutex::new(None)),
        root,
    };
    let at = Outputs {
        out: out.as_ref(),
        root,
    };
    match scene.dimension()? {
        Dimension::Two => run_in::<2>(args, &scene, &options, at, &interrupt, &progress),
        Dimension::Three => run_in::<3>(args, &scene, &options, at, &interrupt, &progress),
    }
}

/// Where `gapsim run` reports: the output folder (`--out`), and whether
/// this process prints and writes at all (every process of a one-rank run;
/// rank 0 of a run across MPI ranks, whose other ranks solve silently).
#[derive(Clone, Copy)]
struct Outputs<'a> {
    out: Option<&'a OutDir>,
    root: bool,
}

/// What `gapsim run` reports of the contact of dimension `D` beyond what
/// every dimension has: the summary lines of the contact state at the end
/// of a solve with contact pairs.
trait RunDim<const D: usize>: SceneDim<D> + ContactTable<D> {
    /// Prints the contact state at the end of `sol` (a solve with contact
    /// pairs): the largest penetration and what projects nowhere.
    fn contact_summary(sol: &Solution<D>) -> CommandResult
    where
        Dim<D>: SurfaceDim<D>;
}

/// 2D: over the integration points (see [`active_penetration`]), with the
/// range of `xi_m` and the unpaired points.
impl RunDim<2> for Dim<2> {
    fn contact_summary(sol: &Solution) -> CommandResult {
        match active_penetration(sol) {
            Some(a) => println!(
                "max penetration {:.3e} (largest -gap over the {} integration points in contact: \
                 paired, on a slave segment with pressure; {} open or unpaired points left out)",
                a.penetration, a.active, a.others
            ),
            None if !sol.contact_points.is_empty() => println!(
                "max penetration none (no integration point in contact: \
                 no slave segment carries pressure)"
            ),
            None => {}
        }
        if let Some((lo, hi)) = sol.xi_m_range() {
            println!("xi_m range      [{lo:.6}, {hi:.6}]");
        }
        let unpaired = sol.unpaired_points();
        if !unpaired.is_empty() {
            println!(
                "unpaired        {} integration point(s) project into no master segment:",
                unpaired.len()
            );
            for p in &unpaired {
                println!("  {p}");
            }
        }
        Ok(())
    }
}

/// 3D: from the nodal contact table (`contact.csv`'s rows: each slave node
/// taken as a point of its first slave face): the largest penetration over
/// the nodes with pressure, and the nodes whose own projection finds no
/// master face.
impl RunDim<3> for Dim<3> {
    fn contact_summary(sol: &Solution<3>) -> CommandResult {
        let rows = <Dim<3> as ContactTable<3>>::rows(sol, &sol.final_state)
            .map_err(|e| format!("cannot tabulate the contact nodes: {e}"))?;
        // every node with a projection, pressed or not: a node the active
        // set left free may still penetrate
        let projected: Vec<_> = rows.iter().filter(|r| r.gap.is_some()).collect();
        let penetration = projected
            .iter()
            .filter_map(|r| r.gap)
            .fold(None, |m: Option<f64>, g| Some(m.map_or(-g, |m| m.max(-g))));
        let pressed = projected.iter().filter(|r| r.pressure != 0.0).count();
        let free_inside = projected
            .iter()
            .filter(|r| r.pressure == 0.0 && r.gap.is_some_and(|g| g < 0.0))
            .count();
        match penetration {
            Some(p) => println!(
                "max penetration {:.3e} (largest -gap over the {} slave nodes with a projection, \
                 each a point of its first slave face, 0 when none penetrates; {pressed} of them \
                 with pressure, {free_inside} without pressure inside the master)",
                p.max(0.0),
                projected.len(),
            ),
            None => println!(
                "max penetration none (no slave node projects into a master face; {} slave nodes)",
                rows.len()
            ),
        }
        let unprojected = rows.iter().filter(|r| r.gap.is_none()).count();
        if unprojected > 0 {
            println!(
                "unprojected     {unprojected} slave node(s) project into no master face (their gap is empty in contact.csv)"
            );
        }
        Ok(())
    }
}

/// The summary line of the frictional nodes at the final state, when a
/// pair has friction: how many stick, slip and are open
/// ([`solver::State::friction`], `contact.csv`'s `state`).
fn friction_summary<const D: usize>(sol: &Solution<D>)
where
    Dim<D>: RunDim<D>,
{
    let nodes = &sol.final_state.friction;
    if nodes.is_empty() {
        return;
    }
    let count = |name: &str| nodes.iter().filter(|f| f.state.name() == name).count();
    println!(
        "friction        {} stick, {} slip, {} open node(s) of the pairs with friction (contact.csv: state, shear, slip)",
        count("stick"),
        count("slip"),
        count("open")
    );
}

/// The summary line of the slave nodes held by supports on both sides
/// (`ContactTable::clamped`, `contact.csv`'s `clamped` column), when there
/// are any: their pressure is a reaction between supports. Nothing when
/// the nodal table cannot be made (`contact.csv` reports that error).
fn clamped_summary<const D: usize>(sol: &Solution<D>)
where
    Dim<D>: RunDim<D>,
{
    let Ok(rows) = <Dim<D> as ContactTable<D>>::rows(sol, &sol.final_state) else {
        return;
    };
    let nodes: Vec<String> = rows
        .iter()
        .filter(|r| <Dim<D> as ContactTable<D>>::clamped(sol, r))
        .map(|r| {
            let (node, _) = <Dim<D> as ContactTable<D>>::node_gap(r);
            sol.mesh.node_number(node).0.to_string()
        })
        .collect();
    if !nodes.is_empty() {
        // the first ten named
        let shown = nodes.len().min(10);
        let more = if nodes.len() > shown { ", ..." } else { "" };
        println!(
            "clamped         {} slave node(s) held by supports on both sides (node {}{more}): \
             their pressure is a reaction between supports, not a contact pressure \
             (contact.csv: clamped = 1)",
            nodes.len(),
            nodes[..shown].join(", ")
        );
    }
}

/// `gapsim run` on a scene of dimension `D`: the solve, the summary, each
/// loaded node's displacement, and with `--out` the `.vtu` files,
/// `reactions.csv` and, with contact pairs, `contact.csv`.
fn run_in<const D: usize>(
    args: &RunArgs,
    scene: &Scene,
    options: &SolveOptions,
    at: Outputs,
    interrupt: &Interrupt,
    progress: &Progress,
) -> CommandResult
where
    Dim<D>: RunDim<D>,
{
    let result = solver::solve_monitored::<D>(scene, options, progress);
    progress.clear_live();
    let sol = match result {
        Err(SolverError::Interrupted { load_factor }) => {
            return Err(interrupted(args, load_factor));
        }
        result => result?,
    };
    if !at.root {
        return Ok(());
    }
    let out = at.out;
    let name = scene.name.clone().unwrap_or_else(|| scene.origin.clone());
    print_header(&name, &sol);
    let facet = FacetOf::<D>::NAME;
    for r in &sol.step_records {
        for p in &r.node_ties {
            println!(
                "node tie        load factor {}: {p} is held at a master node",
                r.load_factor
            );
        }
        for p in &r.kept_outside {
            println!(
                "kept outside    load factor {}: {p} misses its master {facet} slightly",
                r.load_factor
            );
        }
    }
    let contact = !sol.contact_pairs.is_empty();
    if let Method::Approx(_) = sol.method
        && contact
    {
        taylor_summary(&sol, args.every_step);
    }
    if contact {
        Dim::<D>::contact_summary(&sol)?;
        clamped_summary::<D>(&sol);
        friction_summary::<D>(&sol);
    }
    for load in &scene.loads {
        // a load on a physical group has no position to report
        let Some(at) = load.at.and_then(|c| c.point::<D>()) else {
            continue;
        };
        let bodies: Vec<&str> = match &load.body {
            Some(b) => vec![b.as_str()],
            None => sol.mesh.bodies.iter().map(|b| b.name.as_str()).collect(),
        };
        let distance = |n: NodeId| {
            let p = sol.mesh.node_ref(n);
            solver::mesh::length(&std::array::from_fn::<f64, D, _>(|c| p[c] - at[c]))
        };
        let nearest = bodies
            .iter()
            .filter_map(|b| sol.node_at(b, at))
            .min_by(|a, b| distance(*a).total_cmp(&distance(*b)));
        if let Some(node) = nearest {
            let u = sol.displacement(node);
            let at: Vec<String> = at.iter().map(|v| v.to_string()).collect();
            let u: Vec<String> = u.iter().map(|v| format!("{v:.6}")).collect();
            println!(
                "loaded node     ({}) moves by ({})",
                at.join(", "),
                u.join(", ")
            );
        }
    }
    print_costs(&sol, options);
    if let Some(out) = out {
        write_outputs(args, &sol, out, interrupt, |at, wrote| {
            if contact {
                let (path, shown) = at("contact.csv");
                let text = contact_csv(&sol, &sol.final_state)
                    .map_err(|e| format!("cannot write {}: {e}", shown.display()))?;
                solver::report::write_atomic(&path, text)
                    .map_err(|e| format!("cannot write {}: {e}", shown.display()))?;
                wrote.push(format!("wrote           {}", shown.display()));
            }
            Ok(())
        })?;
    }
    Ok(())
}

/// Where a result file goes: its staging path and the path it will have.
type At<'a> = &'a dyn Fn(&str) -> (PathBuf, PathBuf);

/// With `--out`: the `.vtu` files (every step's with `--every-step`, and
/// their `steps.pvd`; `final.vtu`), `reactions.csv` when the scene reports supports, then
/// what `more` adds (`contact.csv`), staged and committed at once; then
/// the list of what was written.
fn write_outputs<const D: usize>(
    args: &RunArgs,
    sol: &solver::Solution<D>,
    out: &OutDir,
    interrupt: &Interrupt,
    more: impl FnOnce(At<'_>, &mut Vec<String>) -> Result<(), String>,
) -> CommandResult
where
    Dim<D>: ContactTable<D>,
{
    let dir = out.path();
    let staging = out.stage()?;
    let at = |name: &str| (staging.path().join(name), dir.join(name));
    let mut vtu_files = 0;
    let mut series = None;
    if args.every_step {
        let mut steps = Vec::with_capacity(sol.snapshots.len());
        for (i, state) in sol.snapshots.iter().enumerate() {
            let name = format!("step-{i:04}.vtu");
            let (path, shown) = at(&name);
            solver::report::write_vtu_state(&path, sol, state)
                .map_err(|e| format!("cannot write {}: {e}", shown.display()))?;
            vtu_files += 1;
            steps.push((state.load_factor, name));
        }
        let files: Vec<(f64, &str)> = steps.iter().map(|(f, n)| (*f, n.as_str())).collect();
        let (path, shown) = at("steps.pvd");
        solver::report::write_atomic(&path, solver::report::pvd_string(&files))
            .map_err(|e| format!("cannot write {}: {e}", shown.display()))?;
        series = Some(shown);
    }
    let (path, shown) = at("final.vtu");
    solver::report::write_vtu(&path, sol)
        .map_err(|e| format!("cannot write {}: {e}", shown.display()))?;
    vtu_files += 1;
    let mut wrote = vec![format!(
        "wrote           {vtu_files} .vtu file(s) to {}",
        dir.display()
    )];
    if let Some(shown) = series {
        wrote.push(format!(
            "wrote           {} (the steps as a ParaView time series)",
            shown.display()
        ));
    }
    if !sol.support_groups.is_empty() {
        let (path, shown) = at("reactions.csv");
        solver::report::write_atomic(&path, reactions_csv(sol))
            .map_err(|e| format!("cannot write {}: {e}", shown.display()))?;
        wrote.push(format!("wrote           {}", shown.display()));
    }
    more(&at, &mut wrote)?;
    staging.commit(Some(interrupt))?;
    for line in wrote {
        println!("{line}");
    }
    Ok(())
}

/// The error of a solve stopped by Ctrl-C at `load_factor`.
fn interrupted(args: &RunArgs, load_factor: f64) -> Box<dyn std::error::Error + Send + Sync> {
    let kept = match &args.out {
        Some(dir) => format!(", {} left as it was", dir.display()),
        None => String::new(),
    };
    format!(
        "interrupted at load factor {load_factor} (the last converged state): \
         no solution, nothing written{kept}"
    )
    .into()
}

/// The worst penetration of the contact set at the end of a solve.
struct ActivePenetration {
    /// `max(0, max -gap)` over the active points.
    penetration: f64,
    /// The active points: paired, of a persistent pair or on a slave
    /// segment with a non-zero multiplier at either node.
    active: usize,
    /// The other integration points (open or unpaired).
    others: usize,
}

/// The largest penetration `-gap` (0 when none penetrates) over the
/// integration points in contact at the final state: paired points of a
/// persistent pair, and paired points of a unilateral pair whose slave
/// segment has a node with a non-zero multiplier (pressure); `None` when
/// no point is in contact. Open points (positive gaps far from the
/// contact zone) do not count: their gaps say nothing of the constraint.
fn active_penetration(sol: &solver::Solution) -> Option<ActivePenetration> {
    use std::collections::HashMap;
    let multiplier: HashMap<(usize, usize), f64> = sol
        .multiplier_dofs
        .iter()
        .zip(&sol.final_state.multipliers)
        .map(|(d, &l)| ((d.pair, d.node), l))
        .collect();
    let mut active = 0;
    let mut penetration = 0.0_f64;
    for p in &sol.contact_points {
        let Some(gap) = p.gap else { continue };
        let persistent = sol.contact_pairs[p.pair].mode == solver::ContactMode::Persistent;
        let pressed = p
            .slave_nodes
            .iter()
            .any(|&n| multiplier.get(&(p.pair, n)).is_some_and(|&l| l != 0.0));
        if persistent || pressed {
            active += 1;
            penetration = penetration.max(-gap);
        }
    }
    (active > 0).then_some(ActivePenetration {
        penetration,
        active,
        others: sol.contact_points.len() - active,
    })
}

/// Types 1–6: the step-end checks (see `solver::newton`, "Re-pairing at
/// the step end"): step repeats, unsettled points, accuracy halvings and
/// the largest Taylor remainder (every step's with `every_step`).
fn taylor_summary<const D: usize>(sol: &solver::Solution<D>, every_step: bool)
where
    Dim<D>: SurfaceDim<D>,
{
    let master = FacetOf::<D>::NAME;
    println!(
        "step repeats    {} (steps solved again with re-paired expansions; {} iterations discarded)",
        sol.repeats, sol.repeated_iterations
    );
    for r in &sol.step_records {
        for p in &r.unsettled {
            println!(
                "unsettled       load factor {}: {p} ends on another master {master}",
                r.load_factor
            );
        }
    }
    if !sol.accuracy_halvings.is_empty() {
        println!(
            "accuracy        {} step(s) halved for the Taylor remainder",
            sol.accuracy_halvings.len()
        );
        for h in &sol.accuracy_halvings {
            println!(
                "  step {}: {} -> {} remainder {:.3e}",
                h.step, h.from_load_factor, h.attempted_load_factor, h.remainder
            );
        }
    }
    let worst = sol
        .step_records
        .iter()
        .filter_map(|r| r.taylor_remainder.map(|t| (t, r.load_factor)))
        .max_by(|a, b| a.0.total_cmp(&b.0));
    if let Some((t, lf)) = worst {
        println!("Taylor remainder max {t:.3e} x element size (load factor {lf})");
    }
    if every_step {
        for r in &sol.step_records {
            if let Some(t) = r.taylor_remainder {
                println!(
                    "  load factor {}: remainder {t:.3e}, {} repeat(s)",
                    r.load_factor, r.repeats
                );
            }
        }
    }
}

/// The summary's first lines: the scene, the method, the size, the result
/// and Newton's effort (cut-backs included).
fn print_header<const D: usize>(name: &str, sol: &solver::Solution<D>)
where
    Dim<D>: SurfaceDim<D>,
{
    let forms: Vec<String> = sol.formulations.iter().map(|f| f.to_string()).collect();
    let contact = if forms.is_empty() {
        "no contact".to_owned()
    } else {
        format!("formulation {}", forms.join(", "))
    };
    println!("scene           {name}");
    println!(
        "method          {} ({} load steps, {contact})",
        sol.method, sol.steps
    );
    println!(
        "equations       {} (free dofs and multipliers)",
        sol.equations
    );
    println!("load factor     {}", sol.load_factor);
    println!("strain energy   {:.10}", sol.strain_energy);
    println!(
        "Newton          {} iterations ({:?} per step)",
        sol.newton_iterations,
        sol.iterations_per_step()
    );
    if sol.repeated_iterations > 0 {
        // a repeated step's accepted solve starts at the end of the
        // discarded one and may need no iteration: the work is here
        println!(
            "                (+ {} iterations of discarded solves: {} step repeats after re-pairing, {} accuracy halvings)",
            sol.repeated_iterations,
            sol.repeats,
            sol.accuracy_halvings.len()
        );
    }
    if !sol.cutbacks.is_empty() {
        println!("cut-backs       {}", sol.cutbacks.len());
        for c in &sol.cutbacks {
            println!(
                "  step {}: {} -> {} failed: {}",
                c.step, c.from_load_factor, c.attempted_load_factor, c.reason
            );
        }
        println!(
            "                ({} iterations spent in failed attempts)",
            sol.failed_iterations
        );
    }
}

/// The most solves the summary lists one by one under a line.
const SOLVES_LISTED: usize = 5;

/// The first [`SOLVES_LISTED`] of `items`, one per line under the
/// summary's line above, then how many more: each solve the LDLᵀ gave up
/// (why, and what the LU did), or each solve without the expected inertia.
fn print_listed<T: std::fmt::Display>(items: &[T]) {
    for item in items.iter().take(SOLVES_LISTED) {
        println!("                {item}");
    }
    if items.len() > SOLVES_LISTED {
        println!(
            "                ... and {} more",
            items.len() - SOLVES_LISTED
        );
    }
}

/// The solves whose stiffness was indefinite where the active constraints
/// leave it free, after a line that says so.
fn print_indefinite(log: &[solver::linear::IndefiniteSolve]) {
    if log.is_empty() {
        return;
    }
    println!(
        "indefinite      {} solves without the expected inertia (the stiffness not positive definite where the active constraints leave it free)",
        log.len()
    );
    print_listed(log);
}

/// The summary's cost lines: time, factorisation, fill, the linear
/// solver's fallbacks, kernel calls.
fn print_costs<const D: usize>(sol: &solver::Solution<D>, options: &SolveOptions)
where
    Dim<D>: SurfaceDim<D>,
{
    let t = &sol.timings;
    println!(
        "time            {:.2} ms (solid {:.2}, contact {:.2}, linear solve {:.2})",
        1e3 * t.total.as_secs_f64(),
        1e3 * t.solid_assembly.as_secs_f64(),
        1e3 * t.contact_evaluation.as_secs_f64(),
        1e3 * t.linear_solve.as_secs_f64()
    );
    println!(
        "factorisation   {} (symbolic {:.2} ms in {} analyses, numeric + solve {:.2} ms)",
        options.linear,
        1e3 * t.symbolic_factorisation.as_secs_f64(),
        sol.symbolic_factorisations,
        1e3 * t
            .linear_solve
            .saturating_sub(t.symbolic_factorisation)
            .as_secs_f64()
    );
    match (&sol.krylov, sol.factor_nonzeros) {
        (Some(k), _) => println!(
            "krylov          {}{} ({} solves, {} iterations, {:.1} per solve, at most {}){}",
            k.method,
            if k.ranks > 1 {
                format!(" on {} MPI ranks", k.ranks)
            } else {
                String::new()
            },
            k.solves,
            k.iterations,
            k.iterations as f64 / k.solves.max(1) as f64,
            k.max_iterations,
            k.switched_at.map_or(String::new(), |n| format!(
                "; solve {n} did not converge with GAMG, retried and continued with BoomerAMG"
            )) + &k.direct_at.map_or(String::new(), |n| format!(
                "; solve {n} did not converge with BoomerAMG, retried and continued with MUMPS's LU"
            ))
        ),
        (None, Some(nnz)) => println!(
            "fill            {nnz} nonzeros in L ({:.1} per equation, {} equations)",
            nnz as f64 / sol.equations.max(1) as f64,
            sol.equations
        ),
        (None, None) => println!(
            "fill            not reported for {} (faer's sparse LU does not expose its factors)",
            options.linear
        ),
    }
    if options.linear == LinearSolverKind::Ldlt {
        println!(
            "linear solver   {} ({} symbolic analyses, {} solves fell back to LU)",
            options.linear, sol.symbolic_factorisations, sol.linear_fallbacks
        );
        print_listed(&sol.linear_fallback_log);
        print_indefinite(&sol.linear_indefinite_log);
    }
    println!(
        "kernel calls    {} evaluations, {} projections",
        sol.kernel_counts.evaluate, sol.kernel_counts.project
    );
    if sol.step_end_projections > 0 {
        println!(
            "                (+ {} projections in the step-end checks)",
            sol.step_end_projections
        );
    }
}
