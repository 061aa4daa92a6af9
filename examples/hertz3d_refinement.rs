//! The 3D Hertz refinement table: `scenes/hertz3d.toml` (complete
//! formulation, one load step, the LDLᵀ) on hexahedral and tetrahedral
//! meshes of element sizes h at the contact, measured against Hertz
//! (`gapsim::hertz::three`).
//!
//! ```text
//! cargo run --release --example hertz3d_refinement -- MESH_DIR [--out docs/hertz3d] [--max-equations N]
//! ```
//!
//! `MESH_DIR` holds `hex-{h}.msh` and `tet-{h}.msh` as
//! `scripts/make-hertz3d-mesh.py` writes them (`scripts/hertz3d-refinement.sh`
//! makes them and runs this); a mesh that is missing is skipped, and so is
//! one whose next-coarser mesh of its kind had more than `--max-equations`
//! / 4 equations (default 300000: the LDLᵀ of the next, about 4 times larger, would need over 10 GiB). Writes
//! `hertz3d-refinement.{md,csv}` to the output folder and prints the table.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use gapsim::hertz::three::{Solved3d, solve_3d};
use solver::Scene;

/// The indenter's radius.
const RADIUS: f64 = 10.0;

/// The meshes, coarse to fine: kind, its name in the table, sizes h.
const MESHES: [(&str, &str, &[&str]); 2] = [
    ("hex", "hexahedra", &["0.4", "0.2", "0.1", "0.05"]),
    ("tet", "tetrahedra", &["0.4", "0.2", "0.1", "0.07", "0.05"]),
];

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut meshes = None;
    let mut out = PathBuf::from("docs/hertz3d");
    let mut max_equations = 300_000usize;
    let mut it = args.iter();
    while let Some(a) = it.next() {
        match (a.as_str(), it.clone().next()) {
            ("--out", Some(v)) => {
                out = PathBuf::from(v);
                it.next();
            }
            ("--max-equations", Some(v)) => {
                let Ok(n) = v.parse() else {
                    eprintln!("hertz3d_refinement: --max-equations {v}: not a count");
                    return ExitCode::from(2);
                };
                max_equations = n;
                it.next();
            }
            (dir, _) if meshes.is_none() && !dir.starts_with("--") => {
                meshes = Some(PathBuf::from(dir));
            }
            _ => {
                eprintln!("usage: hertz3d_refinement MESH_DIR [--out DIR] [--max-equations N]");
                return ExitCode::from(2);
            }
        }
    }
    let Some(meshes) = meshes else {
        eprintln!("usage: hertz3d_refinement MESH_DIR [--out DIR] [--max-equations N]");
        return ExitCode::from(2);
    };
    match run(&meshes, &out, max_equations) {
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

fn run(meshes: &Path, out: &Path, max_equations: usize) -> Result<(), String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let base = Scene::from_file(root.join("scenes/hertz3d.toml")).map_err(|e| e.to_string())?;
    let mut rows = Vec::new();
    for (prefix, kind, sizes) in MESHES {
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
            let solved = solve_3d(&base, &file.to_string_lossy(), RADIUS)?;
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
    for (name, text) in [
        ("hertz3d-refinement.md", md),
        ("hertz3d-refinement.csv", csv(&rows)),
    ] {
        let path = out.join(name);
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
