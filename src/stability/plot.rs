//! The stability sweep's plots: one panel per family, the worst relative
//! error of g, g' and g'' against the family's parameter (log-log; a
//! parameter 0, the segment end `1 - xi_m = 0` or `xi_m` on a face's edge
//! or corner, is drawn at 1e-16). Segments ([`write`]): solid
//! slave-normal, dashed closest-point; faces ([`write_faces`]): one line
//! style per face formulation.

use std::path::Path;

use contact_kernels::Formulation;
use plotters::prelude::*;

use super::{Family, SweepRow, faces::face_formulations};

/// Where `1 - xi_m = 0` is drawn on the log axis.
const ZERO_AT: f64 = 1e-16;

/// What one plot shows.
struct Layout<'a> {
    title: &'a str,
    families: &'a [Family],
    values: fn(Family) -> &'static [f64],
    formulations: &'a [Formulation],
}

/// Writes `stem.png` and `stem.svg` into `dir` (the segment sweep).
pub fn write(rows: &[SweepRow], dir: &Path, stem: &str) -> Result<(), String> {
    let formulations = [Formulation::SlaveNormal, Formulation::ClosestPoint];
    let layout = Layout {
        title: "Type 6 kernels in f64 against a double-double reference: worst relative error",
        families: &Family::ALL,
        values: Family::values,
        formulations: &formulations,
    };
    write_layout(rows, dir, stem, &layout)
}

/// Writes `stem.png` and `stem.svg` into `dir` (the face sweep).
pub fn write_faces(rows: &[SweepRow], dir: &Path, stem: &str) -> Result<(), String> {
    let formulations = face_formulations();
    let layout = Layout {
        title: "3D faces: Type 6 kernels in f64 against a double-double reference: worst relative error",
        families: &Family::FACES,
        values: Family::face_values,
        formulations: &formulations,
    };
    write_layout(rows, dir, stem, &layout)
}

fn write_layout(rows: &[SweepRow], dir: &Path, stem: &str, layout: &Layout) -> Result<(), String> {
    crate::study::plots::register_font();
    let png = dir.join(format!("{stem}.png"));
    draw(
        &BitMapBackend::new(&png, (1500, 900)).into_drawing_area(),
        rows,
        layout,
    )
    .map_err(|e| format!("{}: {e}", png.display()))?;
    let svg = dir.join(format!("{stem}.svg"));
    draw(
        &SVGBackend::new(&svg, (1500, 900)).into_drawing_area(),
        rows,
        layout,
    )
    .map_err(|e| format!("{}: {e}", svg.display()))?;
    Ok(())
}

fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, plotters::coord::Shift>,
    rows: &[SweepRow],
    layout: &Layout,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    root.fill(&WHITE)?;
    let root = root.titled(layout.title, ("sans-serif", 22))?;
    let panels = root.split_evenly((2, 3));
    type Output = fn(&SweepRow) -> Option<f64>;
    let outputs: [(&str, RGBColor, Output); 3] = [
        ("g", RGBColor(213, 94, 0), |r| r.gap),
        ("g'", RGBColor(0, 114, 178), |r| r.grad),
        ("g''", RGBColor(0, 158, 115), |r| r.hess),
    ];
    let last = layout.families.last().copied();
    for (panel, &family) in panels.iter().zip(layout.families) {
        let values = (layout.values)(family);
        let x = |v: f64| if v == 0.0 { ZERO_AT } else { v };
        let (lo, hi) = values.iter().fold((f64::INFINITY, 0.0_f64), |(a, b), &v| {
            (a.min(x(v)), b.max(x(v)))
        });
        let mut chart = ChartBuilder::on(panel)
            .caption(family.name(), ("sans-serif", 18))
            .margin(10)
            .x_label_area_size(40)
            .y_label_area_size(55)
            .build_cartesian_2d((lo / 3.0..hi * 3.0).log_scale(), (1e-17..1.0).log_scale())?;
        chart
            .configure_mesh()
            .x_desc(family.parameter())
            .y_desc("relative error")
            .x_label_formatter(&|v| format!("{v:.0e}"))
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .label_style(("sans-serif", 12))
            .draw()?;
        for (name, color, output) in outputs {
            for (style, &f) in layout.formulations.iter().enumerate() {
                let points: Vec<(f64, f64)> = values
                    .iter()
                    .filter_map(|&v| {
                        let row = rows
                            .iter()
                            .find(|r| r.family == family && r.value == v && r.formulation == f)?;
                        Some((x(v), output(row)?.max(1e-17)))
                    })
                    .collect();
                let label = format!("{name}, {f}");
                if style == 0 {
                    chart
                        .draw_series(LineSeries::new(
                            points.clone(),
                            ShapeStyle::from(&color).stroke_width(2),
                        ))?
                        .label(label)
                        .legend(move |(x, y)| {
                            PathElement::new([(x, y), (x + 20, y)], color.stroke_width(2))
                        });
                } else {
                    // dashes of 5 (the second formulation), 2, 10, ...
                    let dash = [5, 2, 10, 1][(style - 1) % 4];
                    chart
                        .draw_series(DashedLineSeries::new(
                            points.clone(),
                            dash,
                            4,
                            ShapeStyle::from(&color).stroke_width(1),
                        ))?
                        .label(label)
                        .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], color));
                }
                chart.draw_series(points.iter().map(|&p| Circle::new(p, 3, color.filled())))?;
            }
        }
        if Some(family) == last {
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::UpperRight)
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .label_font(("sans-serif", 12))
                .draw()?;
        }
    }
    Ok(())
}
