//! The 3D Hertz refinement table: `scenes/hertz3d.toml` (complete
//! formulation, one load step, the LDLᵀ) on hexahedral and tetrahedral
//! meshes of element sizes h at the contact, measured against Hertz
//! (`gapsim::hertz::sphere`).
//!
//! ```text
//! cargo run --release --example hertz3d_refinement -- MESH_DIR [--out docs/hertz3d] [--max-equations N]
//!     [--kind hex|tet|hexnm|hexnm073] [--segmented] [--gauss-points N] [--dual]
//!     [--linear ldlt|petsc]
//! ```
//!
//! `MESH_DIR` holds `hex-{h}.msh`, `tet-{h}.msh`, `hexnm-{h}.msh` and
//! `hexnm073-{h}.msh` (the script's `hex-nonmatching`: the block's spacing
//! 1.37 times the indenter's h, or with `--master-ratio 0.73` 0.73 times
//! it) as `scripts/make-hertz3d-mesh.py` writes them (`scripts/hertz3d-refinement.sh`
//! makes them and runs this); a mesh that is missing is skipped, and so is
//! one whose next-coarser mesh of its kind had more than `--max-equations`
//! / 4 equations (default 300000: the LDLᵀ of the next, about 4 times larger, would need over 10 GiB). Writes
//! `hertz3d-refinement.{md,csv}` to the output folder and prints the table.
//! `--kind` keeps one mesh kind (without it: hexahedra and tetrahedra)
//! and puts it in the files' names; `--segmented` and `--gauss-points N`
//! change the scene's contact rule (`integration = "segmented"`,
//! `gauss_points`), `--dual` its multiplier basis (`multipliers =
//! "dual"`), and the files are then named after the variant:
//! `--kind tet --segmented --dual` writes
//! `hertz3d-refinement-tet-segmented-dual.{md,csv}`, `--kind hexnm`
//! `hertz3d-refinement-hexnm.{md,csv}`, no option
//! `hertz3d-refinement.{md,csv}`. `--linear petsc` (built with `--features
//! petsc`) solves with PETSc's default Krylov solve instead of the LDLᵀ,
//! for meshes whose LDLᵀ does not fit (then raise `--max-equations`), and
//! adds `-petsc` to the names: `--kind hex --linear petsc` writes
//! `hertz3d-refinement-hex-petsc.{md,csv}`.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use gapsim::hertz::sphere::{Solved3d, solve_3d};
use solver::model::{Integration, Multipliers};
use solver::{LinearSolverKind, Scene};

/// The indenter's radius.
const RADIUS: f64 = 10.0;

/// The meshes, coarse to fine: kind, its name in the table, sizes h.
const MESHES: [(&str, &str, &[&str]); 4] = [
    ("hex", "hexahedra", &["0.4", "0.2", "0.1", "0.05"]),
    ("tet", "tetrahedra", &["0.4", "0.2", "0.1", "0.07", "0.05"]),
    (
        "hexnm",
        "non-matching hexahedra",
        &["0.4", "0.2", "0.1", "0.07", "0.05"],
    ),
    (
        "hexnm073",
        "non-matching hexahedra, finer block",
        &["0.4", "0.2", "0.1", "0.07"],
    ),
];

/// What the command line asks for.
struct Args {
    meshes: PathBuf,
    out: PathBuf,
    max_equations: usize,
    kind: Option<String>,
    segmented: bool,
    gauss_points: Option<usize>,
    dual: bool,
    linear: LinearSolverKind,
}

const USAGE: &str = "usage: hertz3d_refinement MESH_DIR [--out DIR] [--max-equations N] [--kind hex|tet|hexnm|hexnm073] [--segmented] [--gauss-points N] [--dual] [--linear ldlt|petsc]";

fn parse(args: &[String]) -> Result<Args, String> {
    let mut meshes = None;
    let mut parsed = Args {
        meshes: PathBuf::new(),
        out: PathBuf::from("docs/hertz3d"),
        max_equations: 300_000,
        kind: None,
        segmented: false,
        gauss_points: None,
        dual: false,
        linear: LinearSolverKind::Ldlt,
    };
    let mut it = args.iter();
    while let Some(a) = it.next() {
        let mut value = || it.next().ok_or_else(|| format!("{a}: needs a value"));
        match a.as_str() {
            "--out" => parsed.out = PathBuf::from(value()?),
            "--max-equations" => {
                let v = value()?;
                parsed.max_equations = v
                    .parse()
                    .map_err(|_| format!("--max-equations {v}: not a count"))?;
            }
            "--kind" => {
                let v = value()?;
                if !MESHES.iter().any(|m| m.0 == v) {
                    let kinds: Vec<&str> = MESHES.iter().map(|m| m.0).collect();
                    return Err(format!("--kind {v}: one of {}", kinds.join(", ")));
                }
                parsed.kind = Some(v.clone());
            }
            "--segmented" => parsed.segmented = true,
            "--dual" => parsed.dual = true,
            "--linear" => {
                let v = value()?;
                parsed.linear = v.parse().map_err(|e| format!("--linear {v}: {e}"))?;
            }
            "--gauss-points" => {
                let v = value()?;
                parsed.gauss_points = Some(
                    v.parse()
                        .map_err(|_| format!("--gauss-points {v}: not a count"))?,
                );
            }
            dir if meshes.is_none() && !dir.starts_with("--") => meshes = Some(PathBuf::from(dir)),
            other => return Err(format!("{other}: unexpected")),
        }
    }
    parsed.meshes = meshes.ok_or("no MESH_DIR")?;
    Ok(parsed)
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let args = match parse(&args) {
        Ok(a) => a,
        Err(e) => {
            eprintln!("hertz3d_refinement: {e}\n{USAGE}");
            return ExitCode::from(2);
        }
    };
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("hertz3d_refinement: {e}");
            ExitCode::FAILURE
        }
    }
}

/// One row of the table.
struct Row {
    kind: &'static str,
    h: f64,
    solved: Solved3d,
}

fn run(args: &Args) -> Result<(), String> {
    let (meshes, out, max_equations) = (&args.meshes, &args.out, args.max_equations);
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut base = Scene::from_file(root.join("scenes/hertz3d.toml")).map_err(|e| e.to_string())?;
    let mut variant = args
        .kind
        .as_ref()
        .map_or_else(String::new, |k| format!("-{k}"));
    for contact in &mut base.contacts {
        if args.segmented {
            contact.integration = Integration::Segmented;
        }
        contact.gauss_points = args.gauss_points.or(contact.gauss_points);
        if args.dual {
            contact.multipliers = Multipliers::Dual;
        }
    }
    if args.segmented {
        variant.push_str("-segmented");
    }
    if let Some(n) = args.gauss_points {
        variant.push_str(&format!("-gauss{n}"));
    }
    if args.dual {
        variant.push_str("-dual");
    }
    if args.linear != LinearSolverKind::Ldlt {
        variant.push_str(&format!("-{}", args.linear));
    }
    let mut rows = Vec::new();
    for (prefix, kind, sizes) in MESHES {
        // the non-matching hexahedra only on request: their tables are apart
        if args
            .kind
            .as_deref()
            .map_or(prefix.starts_with("hexnm"), |k| k != prefix)
        {
            continue;
        }
        let mut coarser: Option<usize> = None;
        for size in sizes {
            let path = meshes.join(format!("{prefix}-{size}.msh"));
            if !path.exists() {
                eprintln!("{}: missing, skipped", path.display());
                continue;
            }
            if coarser.is_some_and(|n| n > max_equations / 4) {
                eprintln!(
                    "{}: skipped (the coarser mesh had {} equations; --max-equations {max_equations})",
                    path.display(),
                    coarser.unwrap_or(0)
                );
                continue;
            }
            let h: f64 = size
                .parse()
                .map_err(|_| format!("{size}: not an element size"))?;
            let file = path
                .canonicalize()
                .map_err(|e| format!("{}: {e}", path.display()))?;
            let solved = solve_3d(&base, &file.to_string_lossy(), RADIUS, args.linear)?;
            let m = &solved.measured;
            eprintln!(
                "{kind} h = {size}: {} equations, {} iterations, {:.1} s, peak {:+.2} %",
                solved.equations,
                solved.newton_iterations,
                solved.seconds,
                100.0 * m.peak_error()
            );
            coarser = Some(solved.equations);
            rows.push(Row { kind, h, solved });
        }
    }
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let md = markdown(&rows);
    print!("{md}");
    for (name, text) in [("md", md), ("csv", csv(&rows))] {
        let path = out.join(format!("hertz3d-refinement{variant}.{name}"));
        solver::report::write_atomic(&path, text)
            .map_err(|e| format!("{}: {e}", path.display()))?;
    }
    Ok(())
}

/// A fitted value's error relative to `reference`, in percent, or `-`.
fn fit_error(value: Option<f64>, reference: f64) -> String {
    value.map_or_else(
        || "-".into(),
        |v| format!("{:+.2} %", 100.0 * (v / reference - 1.0)),
    )
}

fn markdown(rows: &[Row]) -> String {
    let mut s = String::from(
        "| mesh | h | equations | Newton iterations | time (s) | P | p0 | peak pressure | peak error | fit p0 error | a | contact radius | difference | fit a error |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        let m = &r.solved.measured;
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {:.1} | {:.5} | {:.5} | {:.5} | {:+.2} % | {} | {:.4} | {:.4} | {:+.2} h | {} |",
            r.kind,
            r.h,
            r.solved.equations,
            r.solved.newton_iterations,
            r.solved.seconds,
            m.load,
            m.p0,
            m.peak,
            100.0 * m.peak_error(),
            fit_error(m.fit.map(|f| f.0), m.p0),
            m.a,
            m.radius,
            m.radius_error(r.h),
            fit_error(m.fit.map(|f| f.1), m.a),
        );
    }
    s
}

fn csv(rows: &[Row]) -> String {
    let mut s = String::from(
        "mesh,h,equations,newton_iterations,seconds,load,p0,peak,peak_error,p0_fit,a,radius,radius_error_h,a_fit\n",
    );
    let opt = |v: Option<f64>| v.map_or_else(String::new, |v| format!("{v:.6e}"));
    for r in rows {
        let m = &r.solved.measured;
        let _ = writeln!(
            s,
            "{},{},{},{},{:.3},{:.6e},{:.6e},{:.6e},{:.6e},{},{:.6e},{:.6e},{:.6e},{}",
            r.kind,
            r.h,
            r.solved.equations,
            r.solved.newton_iterations,
            r.solved.seconds,
            m.load,
            m.p0,
            m.peak,
            m.peak_error(),
            opt(m.fit.map(|f| f.0)),
            m.a,
            m.radius,
            m.radius_error(r.h),
            opt(m.fit.map(|f| f.1)),
        );
    }
    s
}
