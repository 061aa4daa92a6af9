//! The stability sweep's plot: one panel per family, the worst relative
//! error of g, g' and g'' against the family's parameter (log-log; the
//! segment end `1 - xi_m = 0` is drawn at 1e-16), solid slave-normal,
//! dashed closest-point.

use std::path::Path;

use contact_kernels::Formulation;
use plotters::prelude::*;

use super::{Family, SweepRow};

/// Where `1 - xi_m = 0` is drawn on the log axis.
const ZERO_AT: f64 = 1e-16;

/// Writes `stem.png` and `stem.svg` into `dir`.
pub fn write(rows: &[SweepRow], dir: &Path, stem: &str) -> Result<(), String> {
    crate::study::plots::register_font();
    let png = dir.join(format!("{stem}.png"));
    draw(
        &BitMapBackend::new(&png, (1500, 900)).into_drawing_area(),
        rows,
    )
    .map_err(|e| format!("{}: {e}", png.display()))?;
    let svg = dir.join(format!("{stem}.svg"));
    draw(
        &SVGBackend::new(&svg, (1500, 900)).into_drawing_area(),
        rows,
    )
    .map_err(|e| format!("{}: {e}", svg.display()))?;
    Ok(())
}

fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, plotters::coord::Shift>,
    rows: &[SweepRow],
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    root.fill(&WHITE)?;
    let root = root.titled(
        "Type 6 kernels in f64 against a double-double reference: worst relative error",
        ("sans-serif", 22),
    )?;
    let panels = root.split_evenly((2, 3));
    type Output = fn(&SweepRow) -> Option<f64>;
    let outputs: [(&str, RGBColor, Output); 3] = [
        ("g", RGBColor(213, 94, 0), |r| r.gap),
        ("g'", RGBColor(0, 114, 178), |r| r.grad),
        ("g''", RGBColor(0, 158, 115), |r| r.hess),
    ];
    for (panel, family) in panels.iter().zip(Family::ALL) {
        let values = family.values();
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
            for f in [Formulation::SlaveNormal, Formulation::ClosestPoint] {
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
                if f == Formulation::SlaveNormal {
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
                    chart
                        .draw_series(DashedLineSeries::new(
                            points.clone(),
                            5,
                            4,
                            ShapeStyle::from(&color).stroke_width(1),
                        ))?
                        .label(label)
                        .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], color));
                }
                chart.draw_series(points.iter().map(|&p| Circle::new(p, 3, color.filled())))?;
            }
        }
        if family == Family::Gap {
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
