//! The 3D Hertz benchmark on both meshes: solves `scenes/hertz3d.toml` as
//! written (hexahedra) and with `file` naming `hertz3d-tet.msh`
//! (tetrahedra), complete formulation, one load step, the LDLᵀ; prints the
//! measurement against Hertz (`gapsim::hertz::sphere`) as a Markdown table
//! (also `hertz3d.md`) and writes the pressure pictures
//! (`pressure-hexahedra.png`, `pressure-tetrahedra.png`, and SVG).
//!
//! ```text
//! cargo run --release --example hertz3d -- [--out docs/hertz3d]
//! ```

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use gapsim::hertz::sphere::{plot_3d, solve_3d};
use solver::Scene;

/// The element size near the contact (`scripts/make-hertz3d-mesh.py`).
const H: f64 = 0.1;
/// The indenter's radius.
const RADIUS: f64 = 10.0;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let out = match args.as_slice() {
        [] => PathBuf::from("docs/hertz3d"),
        [flag, dir] if flag == "--out" => PathBuf::from(dir),
        _ => {
            eprintln!("usage: hertz3d [--out DIR]");
            return ExitCode::from(2);
        }
    };
    match run(&out) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("hertz3d: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run(out: &Path) -> Result<(), String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let base = Scene::from_file(root.join("scenes/hertz3d.toml")).map_err(|e| e.to_string())?;
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let mut table = String::from(
        "| mesh | equations | Newton iterations | time (s) | P | p0 | peak pressure | error | a | contact radius | difference | nodes without a projection |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for (name, file) in [
        ("hexahedra", "hertz3d-hex.msh"),
        ("tetrahedra", "hertz3d-tet.msh"),
    ] {
        let solved = solve_3d(&base, file, RADIUS, solver::LinearSolverKind::Ldlt)?;
        let m = &solved.measured;
        table.push_str(&format!(
            "| {name} (`{file}`) | {} | {} | {:.1} | {:.5} | {:.5} | {:.5} | {:+.2} % | {:.4} | {:.4} | {:+.2} h | {} of {} |\n",
            solved.equations,
            solved.newton_iterations,
            solved.seconds,
            m.load,
            m.p0,
            m.peak,
            100.0 * m.peak_error(),
            m.a,
            m.radius,
            m.radius_error(H),
            m.without_projection,
            m.points.len()
        ));
        let title = format!("3D Hertz, {name} (h = {H} at the contact): contact pressure");
        for ext in ["png", "svg"] {
            let path = out.join(format!("pressure-{name}.{ext}"));
            plot_3d(m, &title, &path)?;
        }
    }
    print!("{table}");
    let path = out.join("hertz3d.md");
    solver::report::write_atomic(&path, table).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(())
}
