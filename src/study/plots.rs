//! Study plots (PNG and SVG, pure Rust: plotters with an embedded DejaVu
//! Sans font, so no system font library is needed).
//!
//! 1. `error-vs-steps-F`: |error %| against load steps, one line per type,
//!    log scale; filled markers for positive errors, hollow for negative;
//!    each line labelled at its end.
//! 2. `error-vs-time-F`: |error %| against wall time (left) and contact
//!    time (right), one point per (type, steps), the Pareto front drawn; the
//!    complete formulation's times as vertical lines.
//! 3. `deformed`: the final configuration, both bodies, the reference
//!    outline in grey, the contact elements (slave segments with their
//!    integration points, master segments) drawn.

use std::path::Path;

use contact_kernels::ApproxType;
use plotters::coord::Shift;
use plotters::prelude::*;
use solver::{Method, Solution};

use super::{FormulationStudy, StudyError, StudyResults};

static FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");

/// Registers the embedded font under "sans-serif" (idempotent).
pub(crate) fn register_font() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        // The embedded file is a valid TrueType font; a failure here would
        // only lose text in the plots, which the backend then reports.
        let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, FONT);
    });
}

/// One colour per type (colour-blind-friendly palette), complete in black.
fn type_color(ty: ApproxType) -> RGBColor {
    const C: [RGBColor; 6] = [
        RGBColor(230, 159, 0),
        RGBColor(86, 180, 233),
        RGBColor(0, 158, 115),
        RGBColor(213, 94, 0),
        RGBColor(0, 114, 178),
        RGBColor(204, 121, 167),
    ];
    C[ty.index() - 1]
}

type DrawResult<DB> = Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

fn plot_err(path: &Path, e: impl std::fmt::Display) -> StudyError {
    StudyError::Plot {
        path: path.display().to_string(),
        message: e.to_string(),
    }
}

/// What a plot written through [`solver::report::replace_with`] fails with.
type PlotResult = Result<(), Box<dyn std::error::Error + Send + Sync>>;

/// Draws `$draw` (an expression using the drawing area `$root`) into
/// `$stem.png` and `$stem.svg`: the body is expanded once per backend.
/// Each file is drawn at a temporary path and then renamed
/// ([`solver::report::replace_with`]), so a plot is replaced atomically.
macro_rules! both {
    ($dir:expr, $stem:expr, $size:expr, |$root:ident| $draw:expr) => {{
        register_font();
        let png = $dir.join(format!("{}.png", $stem));
        solver::report::replace_with(&png, |tmp| -> PlotResult {
            let $root = BitMapBackend::new(tmp, $size).into_drawing_area();
            $draw.map_err(|e| e.to_string())?;
            $root.present().map_err(|e| e.to_string())?;
            Ok(())
        })
        .map_err(|e| plot_err(&png, e))?;
        let svg = $dir.join(format!("{}.svg", $stem));
        solver::report::replace_with(&svg, |tmp| -> PlotResult {
            let $root = SVGBackend::new(tmp, $size).into_drawing_area();
            $draw.map_err(|e| e.to_string())?;
            $root.present().map_err(|e| e.to_string())?;
            Ok(())
        })
        .map_err(|e| plot_err(&svg, e))?;
    }};
}

/// Smallest |error| shown on log axes.
const FLOOR: f64 = 1e-10;

fn log_range(values: impl Iterator<Item = f64>) -> std::ops::Range<f64> {
    let (lo, hi) = values
        .filter(|v| v.is_finite() && *v > 0.0)
        .fold((f64::INFINITY, 0.0_f64), |(a, b), v| (a.min(v), b.max(v)));
    if !lo.is_finite() {
        return FLOOR..1.0;
    }
    let lo = 10f64.powf(lo.max(FLOOR).log10().floor());
    let hi = 10f64.powf(hi.log10().ceil()).max(lo * 10.0);
    lo..hi
}

/// Plot 1: |error| against load steps.
fn draw_error_vs_steps<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    s: &FormulationStudy,
) -> DrawResult<DB> {
    root.fill(&WHITE)?;
    let steps = s.steps();
    let (lo, hi) = (steps[0] as f64, *steps.last().expect("non-empty") as f64);
    let errors = s.runs.iter().filter_map(|r| r.error_percent.map(f64::abs));
    let yr = log_range(errors);
    let mut chart = ChartBuilder::on(root)
        .caption(
            format!("Strain-energy error against load steps ({})", s.formulation),
            ("sans-serif", 22),
        )
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .right_y_label_area_size(40)
        .build_cartesian_2d(lo - 1.0..hi + 2.5, yr.log_scale())?;
    chart
        .configure_mesh()
        .x_desc("number of load steps   (filled marker: error > 0, energy above complete; hollow: error < 0)")
        .y_desc("|error| (%)")
        .x_labels(steps.len() + 2)
        .x_label_formatter(&|v| format!("{v:.0}"))
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .draw()?;
    for ty in ApproxType::ALL {
        let color = type_color(ty);
        let pts: Vec<(f64, f64)> = steps
            .iter()
            .filter_map(|n| {
                s.run(Method::Approx(ty), *n)
                    .and_then(|r| r.error_percent)
                    .map(|e| (*n as f64, e))
            })
            .collect();
        chart
            .draw_series(LineSeries::new(
                pts.iter().map(|(n, e)| (*n, e.abs().max(FLOOR))),
                color.stroke_width(2),
            ))?
            .label(format!("Type {ty}"))
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
            });
        chart.draw_series(pts.iter().map(|(n, e)| {
            let style = if *e >= 0.0 {
                color.filled()
            } else {
                color.stroke_width(2)
            };
            Circle::new((*n, e.abs().max(FLOOR)), 5, style)
        }))?;
        if let Some((n, e)) = pts.last() {
            chart.draw_series(std::iter::once(Text::new(
                format!("T{ty}"),
                (*n + 0.5, e.abs().max(FLOOR)),
                ("sans-serif", 16).into_font().color(&color),
            )))?;
        }
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::LowerLeft)
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()?;
    Ok(())
}

/// Indices of the Pareto-optimal points (no other point is both faster and
/// more accurate), sorted by time.
pub fn pareto_front(points: &[(f64, f64)]) -> Vec<usize> {
    let mut idx: Vec<usize> = (0..points.len())
        .filter(|&i| points[i].0.is_finite() && points[i].1.is_finite())
        .collect();
    idx.sort_by(|&a, &b| {
        points[a]
            .0
            .total_cmp(&points[b].0)
            .then(points[a].1.total_cmp(&points[b].1))
    });
    let mut front = Vec::new();
    let mut best = f64::INFINITY;
    for i in idx {
        if points[i].1 < best {
            best = points[i].1;
            front.push(i);
        }
    }
    front
}

/// One speed-against-error panel; `time` picks wall or contact seconds.
fn draw_speed_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    s: &FormulationStudy,
    title: &str,
    time: fn(&super::Run) -> f64,
) -> DrawResult<DB> {
    let runs: Vec<&super::Run> = s
        .runs
        .iter()
        .filter(|r| matches!(r.method, Method::Approx(_)) && r.error_percent.is_some())
        .collect();
    let pts: Vec<(f64, f64)> = runs
        .iter()
        .map(|r| {
            (
                1e3 * time(r),
                r.error_percent.map_or(f64::NAN, |e| e.abs().max(FLOOR)),
            )
        })
        .collect();
    let complete: Vec<f64> = s
        .runs
        .iter()
        .filter(|r| r.method == Method::Complete)
        .map(|r| 1e3 * time(r))
        .collect();
    let xr = log_range(pts.iter().map(|p| p.0).chain(complete.iter().copied()));
    let yr = log_range(pts.iter().map(|p| p.1));
    // One more decade below the data: room for the legend.
    let yr = yr.start / 10.0..yr.end;
    let mut chart = ChartBuilder::on(area)
        .caption(title, ("sans-serif", 18))
        .margin(10)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d(xr.clone().log_scale(), yr.clone().log_scale())?;
    chart
        .configure_mesh()
        .x_desc("time per solve (ms)")
        .y_desc("|error| (%)")
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .draw()?;
    // The complete formulation: vertical lines at the fewest and most steps.
    let steps = s.steps();
    let (nmin, nmax) = (steps[0], *steps.last().expect("non-empty"));
    let complete_at = |n: usize| {
        s.run(Method::Complete, n)
            .map_or(f64::NAN, |r| 1e3 * time(r))
    };
    let (cmin, cmax) = (complete_at(nmin), complete_at(nmax));
    for (x, label, y) in [
        (cmin, format!("complete, {nmin} steps"), yr.end / 2.5),
        (cmax, format!("complete, {nmax} steps"), yr.end / 8.0),
    ] {
        if x.is_finite() && x > 0.0 {
            chart.draw_series(LineSeries::new(
                [(x, yr.start), (x, yr.end)],
                BLACK.mix(0.5).stroke_width(1),
            ))?;
            chart.draw_series(std::iter::once(Text::new(
                label,
                (x * 1.03, y),
                ("sans-serif", 12).into_font(),
            )))?;
        }
    }
    let front = pareto_front(&pts);
    chart
        .draw_series(LineSeries::new(
            front.iter().map(|&i| pts[i]),
            BLACK.stroke_width(2),
        ))?
        .label("Pareto front")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.stroke_width(2)));
    for ty in ApproxType::ALL {
        let color = type_color(ty);
        let mine: Vec<(f64, f64, usize)> = runs
            .iter()
            .zip(&pts)
            .filter(|(r, _)| r.method == Method::Approx(ty))
            .map(|(r, p)| (p.0, p.1, r.steps))
            .collect();
        chart
            .draw_series(
                mine.iter()
                    .map(|(x, y, _)| Circle::new((*x, *y), 5, color.filled())),
            )?
            .label(format!("Type {ty}"))
            .legend(move |(x, y)| Circle::new((x + 10, y), 5, color.filled()));
        // Label the coarsest point of each type with its step count.
        if let Some((x, y, n)) = mine.first() {
            chart.draw_series(std::iter::once(Text::new(
                format!("T{ty}, {n}"),
                (*x * 1.05, *y),
                ("sans-serif", 12).into_font().color(&color),
            )))?;
        }
    }
    chart.draw_series(
        front
            .iter()
            .map(|&i| Circle::new(pts[i], 8, BLACK.stroke_width(1))),
    )?;
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::LowerRight)
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()?;
    Ok(())
}

/// Plot 2: |error| against wall time and against contact time.
fn draw_error_vs_time<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    s: &FormulationStudy,
    what: &str,
) -> DrawResult<DB> {
    root.fill(&WHITE)?;
    let (title, body) = root.split_vertically(40);
    title.draw(&Text::new(
        format!(
            "Speed against error, {what} ({}); circled: Pareto front",
            s.formulation
        ),
        (20, 10),
        ("sans-serif", 20).into_font(),
    ))?;
    let (left, right) = body.split_horizontally(body.dim_in_pixel().0 / 2);
    draw_speed_panel(&left, s, "against wall time", |r| r.wall_seconds)?;
    draw_speed_panel(&right, s, "against contact time", |r| r.contact_seconds)?;
    Ok(())
}

/// Plot 3: the deformed configuration with the contact elements.
fn draw_deformed<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    sol: &Solution,
) -> DrawResult<DB> {
    root.fill(&WHITE)?;
    let mesh = &sol.mesh;
    let u = &sol.final_state.displacements;
    let cur: Vec<(f64, f64)> = mesh
        .nodes_ref
        .iter()
        .zip(u)
        .map(|(x, d)| (x[0] + d[0], x[1] + d[1]))
        .collect();
    let refp: Vec<(f64, f64)> = mesh.nodes_ref.iter().map(|x| (x[0], x[1])).collect();
    let all = cur.iter().chain(&refp);
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for p in all {
        x0 = x0.min(p.0);
        x1 = x1.max(p.0);
        y0 = y0.min(p.1);
        y1 = y1.max(p.1);
    }
    let pad = 0.05 * (x1 - x0).max(y1 - y0);
    let (w, h) = root.dim_in_pixel();
    // Equal scales on both axes.
    let (sx, sy) = ((x1 - x0 + 2.0 * pad), (y1 - y0 + 2.0 * pad));
    let scale = ((w as f64 - 80.0) / sx).min((h as f64 - 100.0) / sy);
    let xr = x0 - pad..x0 - pad + (w as f64 - 80.0) / scale;
    let yr = y1 + pad - (h as f64 - 100.0) / scale..y1 + pad;
    let mut chart = ChartBuilder::on(root)
        .caption(
            format!(
                "Deformed configuration at load factor {:.3} ({}, {} steps); grey: reference",
                sol.load_factor, sol.method, sol.steps
            ),
            ("sans-serif", 20),
        )
        .margin(10)
        .x_label_area_size(35)
        .y_label_area_size(45)
        .build_cartesian_2d(xr, yr)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc("x")
        .y_desc("y")
        .draw()?;
    let body_colors = [
        RGBColor(0, 114, 178),
        RGBColor(213, 94, 0),
        RGBColor(0, 158, 115),
        RGBColor(204, 121, 167),
    ];
    for (e, conn) in mesh.elements.iter().enumerate() {
        let outline = |p: &[(f64, f64)]| {
            let mut v: Vec<(f64, f64)> = conn.iter().map(|&n| p[n.index()]).collect();
            v.push(v[0]);
            v
        };
        chart.draw_series(std::iter::once(PathElement::new(
            outline(&refp),
            RGBColor(190, 190, 190).stroke_width(1),
        )))?;
        let color = body_colors[mesh.element_body[e] % body_colors.len()];
        chart.draw_series(std::iter::once(Polygon::new(
            outline(&cur),
            color.mix(0.15),
        )))?;
        chart.draw_series(std::iter::once(PathElement::new(
            outline(&cur),
            color.stroke_width(1),
        )))?;
    }
    // Contact elements: master segments, slave segments, integration points
    // joined to their projections, labelled C1, C2, ...
    let mut seen_slave = Vec::new();
    for p in &sol.contact_points {
        if let Some(m) = p.master_nodes {
            chart.draw_series(std::iter::once(PathElement::new(
                vec![cur[m[0]], cur[m[1]]],
                BLACK.stroke_width(3),
            )))?;
        }
        chart.draw_series(std::iter::once(PathElement::new(
            vec![cur[p.slave_nodes[0]], cur[p.slave_nodes[1]]],
            RGBColor(200, 0, 0).stroke_width(2),
        )))?;
        let n1 = 0.5 * (1.0 - p.xi_s);
        let n2 = 0.5 * (1.0 + p.xi_s);
        let [a, b] = p.slave_nodes;
        let xs = (n1 * cur[a].0 + n2 * cur[b].0, n1 * cur[a].1 + n2 * cur[b].1);
        chart.draw_series(std::iter::once(Circle::new(
            xs,
            3,
            RGBColor(200, 0, 0).filled(),
        )))?;
        if let (Some(m), Some(xi)) = (p.master_nodes, p.xi_m) {
            let (m1, m2) = (0.5 * (1.0 - xi), 0.5 * (1.0 + xi));
            let xm = (
                m1 * cur[m[0]].0 + m2 * cur[m[1]].0,
                m1 * cur[m[0]].1 + m2 * cur[m[1]].1,
            );
            chart.draw_series(std::iter::once(PathElement::new(
                vec![xs, xm],
                RGBColor(200, 0, 0).stroke_width(1),
            )))?;
        }
        if !seen_slave.contains(&(p.pair, p.slave_segment)) {
            seen_slave.push((p.pair, p.slave_segment));
            let mid = (0.5 * (cur[a].0 + cur[b].0), 0.5 * (cur[a].1 + cur[b].1));
            if sol.contact_points.len() <= 64 {
                chart.draw_series(std::iter::once(Text::new(
                    format!("C{}", seen_slave.len()),
                    mid,
                    ("sans-serif", 13).into_font().color(&RGBColor(120, 0, 0)),
                )))?;
            }
        }
    }
    Ok(())
}

/// Writes every plot of `results` into `dir`.
pub fn write_all(results: &StudyResults, dir: &Path) -> Result<(), StudyError> {
    for s in &results.formulations {
        let f = s.formulation;
        both!(dir, format!("error-vs-steps-{f}"), (900, 620), |root| {
            draw_error_vs_steps(&root, s)
        });
        both!(dir, format!("error-vs-time-{f}"), (1300, 600), |root| {
            draw_error_vs_time(&root, s, "paper scene")
        });
    }
    if let Some(h) = &results.heavy {
        both!(dir, "error-vs-time-contact-heavy", (1300, 600), |root| {
            draw_error_vs_time(&root, &h.study, "contact-heavy variant")
        });
    }
    if let Some(deformed) = &results.deformed {
        both!(dir, "deformed", (1300, 520), |root| draw_deformed(
            &root, deformed
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::pareto_front;

    #[test]
    fn pareto_front_keeps_only_nondominated_points() {
        let pts = [(1.0, 5.0), (2.0, 1.0), (1.5, 6.0), (3.0, 0.5), (2.5, 2.0)];
        assert_eq!(pareto_front(&pts), vec![0, 1, 3]);
    }
}
