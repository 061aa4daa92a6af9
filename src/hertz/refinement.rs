//! The Hertz refinement study: the Hertz scene on a sequence of meshes
//! refined at the contact, with small-strain (Hertz's assumptions) and
//! finite-strain solids, against Hertz's solution.
//!
//! [`run`] solves `scenes/hertz-small-strain.toml` (one load step, the
//! complete formulation) with its mesh replaced by each of [`MESHES`] and
//! with `kinematics` = `small` and `finite`; [`write`] writes
//! `hertz-refinement.csv`, `hertz-refinement.md` and the plot
//! `hertz-refinement.{png,svg}` (the errors against the element size at the
//! contact, log-log). `cargo run --release --example hertz_refinement`
//! regenerates `docs/hertz/`.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use plotters::prelude::*;
use solver::material::Kinematics;
use solver::scene::MeshSpec;
use solver::{Scene, SceneError, SolveOptions, SolverError, solve};

use super::cylinder::{HertzMeasured, HertzProblem, SCENES, measure};

/// The meshes of the study (relative to `scenes/`), coarse to fine: the
/// `h` argument of `scripts/make-hertz-mesh.py` (the element size at the
/// contact is half of it: the script subdivides once).
pub const MESHES: [(f64, &str); 5] = [
    (0.8, "hertz-refinement/h0.8.msh"),
    (0.4, "hertz-refinement/h0.4.msh"),
    (0.2, "hertz-refinement/h0.2.msh"),
    (0.1, "hertz.msh"),
    (0.05, "hertz-refinement/h0.05.msh"),
];

/// Why the study failed.
#[derive(Debug, thiserror::Error)]
pub enum RefinementError {
    /// The scene file.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// A solve.
    #[error("{mesh} ({kinematics:?}): {source}")]
    Solve {
        /// The mesh file.
        mesh: String,
        /// The kinematics.
        kinematics: Kinematics,
        /// The solver's error (boxed: it is large).
        source: Box<SolverError>,
    },
    /// Writing an output file.
    #[error("{path}: {message}")]
    Write {
        /// The file.
        path: String,
        /// What went wrong.
        message: String,
    },
}

/// One run of the study.
#[derive(Debug, Clone)]
pub struct RefinementRow {
    /// The mesh file (relative to `scenes/`).
    pub mesh: &'static str,
    /// The script's `h`.
    pub h_script: f64,
    /// The solids' kinematics.
    pub kinematics: Kinematics,
    /// What it measured.
    pub measured: HertzMeasured,
    /// Nodes of the mesh.
    pub nodes: usize,
    /// Newton iterations (all attempts).
    pub newton_iterations: usize,
    /// Wall time of the solve, seconds.
    pub seconds: f64,
}

/// Solves the scene `scenes_dir/hertz-small-strain.toml` on every mesh of
/// [`MESHES`] with both kinematics; `progress` is called after each run.
pub fn run(
    scenes_dir: &Path,
    mut progress: impl FnMut(&RefinementRow),
) -> Result<Vec<RefinementRow>, RefinementError> {
    let base = Scene::from_file(scenes_dir.join("hertz-small-strain.toml"))?;
    let mut rows = Vec::new();
    for kinematics in [Kinematics::Small, Kinematics::Finite] {
        for (h_script, mesh) in MESHES {
            let mut scene = base.clone();
            scene.mesh = Some(MeshSpec {
                file: mesh.to_string(),
            });
            if let Some(material) = scene.material.as_mut() {
                material.kinematics = kinematics;
            }
            let mut options = SolveOptions::from_scene(&scene);
            options.steps = 1;
            let start = Instant::now();
            let sol = solve(&scene, &options).map_err(|source| RefinementError::Solve {
                mesh: mesh.to_string(),
                kinematics,
                source: Box::new(source),
            })?;
            let row = RefinementRow {
                mesh,
                h_script,
                kinematics,
                measured: measure(&sol, &SCENES),
                nodes: sol.mesh.nodes_ref.len(),
                newton_iterations: sol.newton_iterations,
                seconds: start.elapsed().as_secs_f64(),
            };
            progress(&row);
            rows.push(row);
        }
    }
    Ok(rows)
}

fn kinematics_name(k: Kinematics) -> &'static str {
    match k {
        Kinematics::Small => "small",
        Kinematics::Finite => "finite",
    }
}

fn percent(v: Option<f64>) -> String {
    v.map_or_else(|| "-".to_string(), |v| format!("{:+.2}", 100.0 * v))
}

/// The CSV text (one row per run; errors relative, empty when undefined).
pub fn csv(rows: &[RefinementRow], problem: &HertzProblem) -> String {
    let mut out = String::from(
        "mesh,h_script,element_size,nodes,kinematics,peak,peak_error,p0_fit,p0_fit_error,a_fit,a_fit_error,profile_error,in_contact,newton_iterations,seconds\n",
    );
    let opt = |v: Option<f64>| v.map_or_else(String::new, |v| format!("{v:.6e}"));
    for r in rows {
        let m = &r.measured;
        let _ = writeln!(
            out,
            "{},{},{},{},{},{:.6},{:.6e},{},{},{},{},{:.6e},{},{},{:.3}",
            r.mesh,
            r.h_script,
            opt(m.element_size),
            r.nodes,
            kinematics_name(r.kinematics),
            m.peak,
            m.peak_error(problem),
            opt(m.p0_fit),
            opt(m.p0_fit_error(problem)),
            opt(m.a_fit),
            opt(m.a_fit_error(problem)),
            m.profile,
            m.in_contact,
            r.newton_iterations,
            r.seconds,
        );
    }
    out
}

/// The Markdown table (errors in percent).
pub fn markdown(rows: &[RefinementRow], problem: &HertzProblem) -> String {
    let mut out = format!(
        "Hertz: a = {:.4}, p0 = {:.4} (plane strain, E = {}, nu = {}, R = {}, P = {}); one load step, complete formulation, slave-normal.\n\n",
        problem.half_width(),
        problem.peak_pressure(),
        problem.young,
        problem.poisson,
        problem.radius,
        problem.load
    );
    out.push_str("| solids | element size at the contact | nodes | peak p (%) | fit p0 (%) | fit a (%) | profile L2 (%) | nodes in contact | Newton | time (s) |\n");
    out.push_str("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for r in rows {
        let m = &r.measured;
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} | {} | {} | {:.2} | {} | {} | {:.2} |",
            kinematics_name(r.kinematics),
            m.element_size
                .map_or_else(|| "-".to_string(), |h| format!("{h:.3}")),
            r.nodes,
            percent(Some(m.peak_error(problem))),
            percent(m.p0_fit_error(problem)),
            percent(m.a_fit_error(problem)),
            100.0 * m.profile,
            m.in_contact,
            r.newton_iterations,
            r.seconds
        );
    }
    out
}

/// Writes the CSV, the Markdown table and the plot into `dir`.
pub fn write(
    rows: &[RefinementRow],
    problem: &HertzProblem,
    dir: &Path,
) -> Result<Vec<PathBuf>, RefinementError> {
    let fail = |path: &Path, e: &dyn std::fmt::Display| RefinementError::Write {
        path: path.display().to_string(),
        message: e.to_string(),
    };
    std::fs::create_dir_all(dir).map_err(|e| fail(dir, &e))?;
    let mut written = Vec::new();
    for (name, text) in [
        ("hertz-refinement.csv", csv(rows, problem)),
        ("hertz-refinement.md", markdown(rows, problem)),
    ] {
        let path = dir.join(name);
        solver::report::write_atomic(&path, text).map_err(|e| fail(&path, &e))?;
        written.push(path);
    }
    crate::study::plots::register_font();
    let png = dir.join("hertz-refinement.png");
    draw(
        &BitMapBackend::new(&png, (900, 600)).into_drawing_area(),
        rows,
        problem,
    )
    .map_err(|e| fail(&png, &e))?;
    written.push(png);
    let svg = dir.join("hertz-refinement.svg");
    draw(
        &SVGBackend::new(&svg, (900, 600)).into_drawing_area(),
        rows,
        problem,
    )
    .map_err(|e| fail(&svg, &e))?;
    written.push(svg);
    Ok(written)
}

/// |error %| against the element size, log-log: peak pressure, fitted
/// half-width and profile; solid lines small strain, dashed finite strain;
/// the 2 % target as a grey line.
fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, plotters::coord::Shift>,
    rows: &[RefinementRow],
    problem: &HertzProblem,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    root.fill(&WHITE)?;
    type Metric = fn(&HertzMeasured, &HertzProblem) -> Option<f64>;
    let metrics: [(&str, RGBColor, Metric); 3] = [
        ("peak pressure", RGBColor(213, 94, 0), |m, p| {
            Some(m.peak_error(p))
        }),
        ("fitted half-width a", RGBColor(0, 114, 178), |m, p| {
            m.a_fit_error(p)
        }),
        ("pressure profile (L2)", RGBColor(0, 158, 115), |m, _| {
            Some(m.profile)
        }),
    ];
    let points = |k: Kinematics, metric: Metric| -> Vec<(f64, f64)> {
        rows.iter()
            .filter(|r| r.kinematics == k)
            .filter_map(|r| {
                let h = r.measured.element_size?;
                let e = 100.0 * metric(&r.measured, problem)?.abs();
                (e > 0.0).then_some((h, e.max(1e-3)))
            })
            .collect()
    };
    let all: Vec<(f64, f64)> = metrics
        .iter()
        .flat_map(|&(_, _, m)| {
            let mut v = points(Kinematics::Small, m);
            v.extend(points(Kinematics::Finite, m));
            v
        })
        .collect();
    let (hmin, hmax) = all
        .iter()
        .fold((f64::INFINITY, 0.0_f64), |(a, b), &(h, _)| {
            (a.min(h), b.max(h))
        });
    let (emin, emax) = all
        .iter()
        .fold((f64::INFINITY, 0.0_f64), |(a, b), &(_, e)| {
            (a.min(e), b.max(e))
        });
    let (hmin, hmax) = if hmin.is_finite() {
        (hmin / 1.3, hmax * 1.3)
    } else {
        (0.01, 1.0)
    };
    let (emin, emax) = if emin.is_finite() {
        (emin.min(2.0) / 2.0, emax.max(2.0) * 40.0)
    } else {
        (0.01, 100.0)
    };
    let mut chart = ChartBuilder::on(root)
        .caption(
            "Hertz (plane strain): error against element size at the contact",
            ("sans-serif", 20),
        )
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(60)
        .build_cartesian_2d((hmin..hmax).log_scale(), (emin..emax).log_scale())?;
    chart
        .configure_mesh()
        .x_desc("element size at the contact")
        .x_label_formatter(&|v| format!("{v:.2}"))
        .y_label_formatter(&|v| format!("{v}"))
        .y_desc("|error| (%)")
        .label_style(("sans-serif", 14))
        .draw()?;
    chart
        .draw_series(LineSeries::new(
            [(hmin, 2.0), (hmax, 2.0)],
            ShapeStyle::from(&RGBColor(150, 150, 150)).stroke_width(1),
        ))?
        .label("2 % target")
        .legend(|(x, y)| PathElement::new([(x, y), (x + 20, y)], RGBColor(150, 150, 150)));
    for (name, color, metric) in metrics {
        let small = points(Kinematics::Small, metric);
        chart
            .draw_series(LineSeries::new(
                small.clone(),
                ShapeStyle::from(&color).stroke_width(2),
            ))?
            .label(format!("{name}, small strain"))
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], color.stroke_width(2)));
        chart.draw_series(small.iter().map(|&p| Circle::new(p, 4, color.filled())))?;
        let finite = points(Kinematics::Finite, metric);
        chart
            .draw_series(DashedLineSeries::new(
                finite.clone(),
                6,
                4,
                ShapeStyle::from(&color).stroke_width(1),
            ))?
            .label(format!("{name}, finite strain (SVK)"))
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], color));
        chart.draw_series(finite.iter().map(|&p| Circle::new(p, 4, color)))?;
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", 13))
        .draw()?;
    Ok(())
}
