//! The 3D Hertz benchmark (point contact; `scenes/hertz3d.toml`, issue
//! "The solver in 3D", section 4): a sphere on a block, its measurement
//! from a solved quarter model and the picture of its pressure.
//!
//! The scene is a quarter model (symmetry planes `x = 0` and `y = 0`) of a
//! sphere of radius `R` pressed onto a block of the same material. The
//! load `P` is four times the `bottom` support's `z` reaction at the last
//! step; Hertz's contact radius and peak pressure follow from it,
//!
//! ```text
//! E* = E / (2 (1 - nu^2)),   a = (3 P R / (4 E*))^(1/3),   p0 = 3 P / (2 pi a^2),
//! p(r) = p0 sqrt(1 - r^2 / a^2)   (r < a),
//! ```
//!
//! (`E*` is [`super::contact_modulus`], `p(r)` [`super::half_ellipse`])
//!
//! and are compared with the nodal contact table of the final state
//! ([`solver::report::ContactTable::rows`]): the peak pressure is the largest
//! nodal pressure, the contact radius the largest `hypot(x, y)` of a node
//! whose pressure exceeds `1e-3` of it (current coordinates).

use std::path::Path;

use plotters::prelude::*;
use solver::Solution;

use super::{contact_modulus, fit_half_ellipse, half_ellipse};

/// The measured benchmark.
#[derive(Debug, Clone, PartialEq)]
pub struct Hertz3d {
    /// `P`: four times the bottom's `z` reaction.
    pub load: f64,
    /// Hertz's contact radius `a`.
    pub a: f64,
    /// Hertz's peak pressure `p0`.
    pub p0: f64,
    /// The largest nodal pressure.
    pub peak: f64,
    /// The contact radius measured.
    pub radius: f64,
    /// `(p0, a)` of the least-squares fit of `p^2 = A + B r^2` over the
    /// nodes with positive pressure ([`super::fit_half_ellipse`]), less
    /// sensitive than the peak to the scatter of single nodes.
    pub fit: Option<(f64, f64)>,
    /// Slave nodes whose own projection finds no master face (their
    /// pressure counts; their gap is empty in `contact.csv`).
    pub without_projection: usize,
    /// Every slave node's `(r, pressure)`.
    pub points: Vec<(f64, f64)>,
}

impl Hertz3d {
    /// The peak pressure's error relative to `p0`.
    pub fn peak_error(&self) -> f64 {
        self.peak / self.p0 - 1.0
    }

    /// The contact radius's difference from `a` in units of `h`.
    pub fn radius_error(&self, h: f64) -> f64 {
        (self.radius - self.a) / h
    }
}

/// Measures `solution` (of the scene with the support group `bottom`)
/// against Hertz for a sphere of radius `sphere_radius` and the material
/// `(young, poisson)` of both bodies.
pub fn measure_3d(
    solution: &Solution<3>,
    young: f64,
    poisson: f64,
    sphere_radius: f64,
) -> Result<Hertz3d, String> {
    let bottom = solution
        .support_groups
        .iter()
        .position(|g| g == "bottom")
        .ok_or("the solution has no support group `bottom`")?;
    let last = solution
        .step_records
        .last()
        .ok_or("the solution has no step")?;
    let load = 4.0 * last.reactions[bottom][2].abs();
    let e_star = contact_modulus(young, poisson);
    let a = (3.0 * load * sphere_radius / (4.0 * e_star)).cbrt();
    let p0 = 3.0 * load / (2.0 * std::f64::consts::PI * a * a);
    let rows =
        <solver::Dim<3> as solver::report::ContactTable<3>>::rows(solution, &solution.final_state)
            .map_err(|e| e.to_string())?;
    let points: Vec<(f64, f64)> = rows
        .iter()
        .map(|r| (r.x[0].hypot(r.x[1]), r.pressure))
        .collect();
    let peak = points.iter().map(|p| p.1).fold(f64::NEG_INFINITY, f64::max);
    let radius = points
        .iter()
        .filter(|p| p.1 > 1e-3 * peak)
        .map(|p| p.0)
        .fold(0.0, f64::max);
    Ok(Hertz3d {
        load,
        a,
        p0,
        peak,
        radius,
        fit: fit_half_ellipse(points.iter().copied().filter(|p| p.1 > 0.0)),
        without_projection: rows.iter().filter(|r| r.gap.is_none()).count(),
        points,
    })
}

/// Writes the picture of `m` to `path` (PNG, or SVG when it ends in
/// `.svg`): every slave node's pressure against its distance from the
/// axis, over Hertz's `p(r)`.
pub fn plot_3d(m: &Hertz3d, title: &str, path: &Path) -> Result<(), String> {
    crate::study::plots::register_font();
    let size = (900, 600);
    let fail = |e: &dyn std::fmt::Display| format!("{}: {e}", path.display());
    if path.extension().is_some_and(|e| e == "svg") {
        draw(&SVGBackend::new(path, size).into_drawing_area(), m, title).map_err(|e| fail(&e))
    } else {
        draw(
            &BitMapBackend::new(path, size).into_drawing_area(),
            m,
            title,
        )
        .map_err(|e| fail(&e))
    }
}

fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, plotters::coord::Shift>,
    m: &Hertz3d,
    title: &str,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    root.fill(&WHITE)?;
    let r_max = 1.6 * m.a;
    let p_max = 1.25 * m.p0.max(m.peak);
    let mut chart = ChartBuilder::on(root)
        .caption(title, ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(60)
        .build_cartesian_2d(0.0..r_max, 0.0..p_max)?;
    chart
        .configure_mesh()
        .x_desc("distance from the axis r")
        .y_desc("contact pressure")
        .label_style(("sans-serif", 14))
        .draw()?;
    let hertz: Vec<(f64, f64)> = (0..=400)
        .map(|k| {
            let r = m.a * k as f64 / 400.0;
            (r, half_ellipse(m.p0, m.a, r))
        })
        .chain([(r_max, 0.0)])
        .collect();
    let black = RGBColor(0, 0, 0);
    chart
        .draw_series(LineSeries::new(
            hertz,
            ShapeStyle::from(&black).stroke_width(2),
        ))?
        .label(format!("Hertz: a = {:.4}, p0 = {:.4}", m.a, m.p0))
        .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], black.stroke_width(2)));
    let blue = RGBColor(0, 114, 178);
    chart
        .draw_series(
            m.points
                .iter()
                .filter(|p| p.0 <= r_max)
                .map(|&p| Circle::new(p, 3, blue.filled())),
        )?
        .label(format!(
            "slave nodes: peak {:.4} ({:+.2} %), radius {:.4}",
            m.peak,
            100.0 * m.peak_error(),
            m.radius
        ))
        .legend(move |(x, y)| Circle::new((x + 10, y), 3, blue.filled()));
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.8))
        .border_style(RGBColor(150, 150, 150))
        .label_font(("sans-serif", 14))
        .draw()?;
    root.present()
}

/// One solve of the 3D Hertz scene and its measurement.
#[derive(Debug, Clone)]
pub struct Solved3d {
    /// The solver's equation count.
    pub equations: usize,
    /// Newton iterations of the accepted solves.
    pub newton_iterations: usize,
    /// Wall time of the solve (not the mesh's reading).
    pub seconds: f64,
    /// The measurement against Hertz.
    pub measured: Hertz3d,
}

/// Solves `scene` (the 3D Hertz scene, `scenes/hertz3d.toml` or a copy of
/// it) with its `mesh.file` replaced by `file` (relative to the scene's
/// folder, or absolute): the complete formulation as the scene says, the
/// linear solver `linear` (the tables' LDLᵀ, or PETSc's Krylov solve for a
/// mesh whose LDLᵀ does not fit), then [`measure_3d`] with the sphere's
/// radius `sphere_radius`.
pub fn solve_3d(
    scene: &solver::Scene,
    file: &str,
    sphere_radius: f64,
    linear: solver::LinearSolverKind,
) -> Result<Solved3d, String> {
    let mut scene = scene.clone();
    scene.mesh = Some(solver::scene::MeshSpec {
        file: file.to_string(),
    });
    let model = scene.build_model::<3>().map_err(|e| e.to_string())?;
    let material = model.mesh.bodies[0].material;
    let options = solver::SolveOptions {
        linear,
        ..solver::SolveOptions::from_scene(&scene)
    };
    let start = std::time::Instant::now();
    let sol = solver::solve_model(&model, &options).map_err(|e| format!("{file}: {e}"))?;
    let seconds = start.elapsed().as_secs_f64();
    let measured = measure_3d(&sol, material.young, material.poisson, sphere_radius)?;
    Ok(Solved3d {
        equations: sol.equations,
        newton_iterations: sol.newton_iterations,
        seconds,
        measured,
    })
}
