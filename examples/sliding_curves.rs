//! Reaction forces against the slide distance on the large-sliding
//! benchmark (issue #8), for the complete formulation and every
//! approximation type, as CSV and a plot.
//!
//! ```text
//! cargo run --release --example sliding_curves                    # 20 steps into target/sliding-curves
//! cargo run --release --example sliding_curves -- --steps 40 --out DIR [SCENE]
//! cargo run --release --example sliding_curves -- --steps 40 --steady 0.5 4.5 \
//!     --out docs/ironing scenes/ironing.toml                     # the ironing benchmark
//! ```
//!
//! `SCENE` (default `scenes/sliding.toml`) must have a support group named
//! `slide` (the prescribed x displacement that drags the block) and one
//! named `press` (the prescribed y displacement that presses it); the slide
//! distance at a step is the `slide` group's prescribed x displacement
//! there (its value times its load curve). Each method is solved with the
//! given step count; a method that fails is reported and left out.
//!
//! Writes into `DIR`:
//!
//! * `sliding-reactions-N.csv` (`N` the step count): one row per method
//!   and converged step: `method,steps,step,load_factor,slide_distance,
//!   strain_energy`, then `<group>_x,<group>_y` for every support group
//!   (the force the support exerts on the body, see
//!   `solver::StepRecord::reactions`);
//! * `sliding-reactions-N.png`: the tangential reaction (`slide` x) and the
//!   normal reaction (`press` y) against the slide distance, one line per
//!   method (complete in black), in the style of the study's plots;
//! * `sliding-steady-N.md`: per method, over the converged steps whose
//!   slide distance lies in the `--steady FROM TO` window (default: every
//!   step of the slide, distance above zero): the mean normal reaction
//!   `mean(press y)`, its ripple `max |press y - mean| / |mean|` and the
//!   drag `max |slide x| / |mean|` (zero for frictionless contact on a
//!   flat, elastic strip: what is left is discretisation). Also printed.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use plotters::prelude::*;
use solver::{Method, Scene, Solution, SolveOptions, solve};

static FONT: &[u8] = include_bytes!("../assets/fonts/DejaVuSans.ttf");

/// The command line.
struct Args {
    steps: usize,
    steady: Option<(f64, f64)>,
    out: PathBuf,
    scene: PathBuf,
}

fn parse_args() -> Result<Args, String> {
    let mut args = Args {
        steps: 20,
        steady: None,
        out: PathBuf::from("target/sliding-curves"),
        scene: PathBuf::from("scenes/sliding.toml"),
    };
    let mut it = std::env::args().skip(1);
    while let Some(a) = it.next() {
        match a.as_str() {
            "--steps" => {
                let v = it.next().ok_or("--steps needs a number")?;
                args.steps = v
                    .parse()
                    .ok()
                    .filter(|n| *n >= 1)
                    .ok_or_else(|| format!("--steps: `{v}` is not a positive integer"))?;
            }
            "--steady" => {
                let mut bound = || -> Result<f64, String> {
                    let v = it.next().ok_or("--steady needs two slide distances")?;
                    v.parse::<f64>()
                        .ok()
                        .filter(|d| d.is_finite())
                        .ok_or_else(|| format!("--steady: `{v}` is not a number"))
                };
                let (from, to) = (bound()?, bound()?);
                if from >= to {
                    return Err(format!("--steady: {from} is not below {to}"));
                }
                args.steady = Some((from, to));
            }
            "--out" => args.out = it.next().ok_or("--out needs a directory")?.into(),
            s if s.starts_with("--") => return Err(format!("unknown option `{s}`")),
            s => args.scene = s.into(),
        }
    }
    Ok(args)
}

/// One method's run: the slide distance and the reactions at every
/// converged step.
struct Curve {
    method: Method,
    solution: Solution,
    slide: Vec<f64>,
}

/// One colour per type (the study's palette), complete in black.
fn color(method: Method) -> RGBColor {
    const C: [RGBColor; 6] = [
        RGBColor(230, 159, 0),
        RGBColor(86, 180, 233),
        RGBColor(0, 158, 115),
        RGBColor(213, 94, 0),
        RGBColor(0, 114, 178),
        RGBColor(204, 121, 167),
    ];
    match method {
        Method::Complete => BLACK,
        Method::Approx(ty) => C[ty.index() - 1],
    }
}

fn label(method: Method) -> String {
    match method {
        Method::Complete => "complete".into(),
        Method::Approx(ty) => format!("Type {ty}"),
    }
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("sliding_curves: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run() -> Result<(), String> {
    let args = parse_args()?;
    let scene = Scene::from_file(&args.scene).map_err(|e| e.to_string())?;
    let model = scene.build_model::<2>().map_err(|e| e.to_string())?;
    let group = |name: &str| {
        model
            .supports
            .iter()
            .position(|g| g.name == name)
            .ok_or_else(|| format!("{}: no support group `{name}`", args.scene.display()))
    };
    let (press, slide) = (group("press")?, group("slide")?);
    let slide_dof = model.prescribed[model.supports[slide].prescribed.clone()]
        .iter()
        .find(|p| p.dof.component() == 0)
        .copied()
        .ok_or("the `slide` group prescribes no x displacement")?;
    let distance =
        |load_factor: f64| model.factor(slide_dof.amplitude, load_factor) * slide_dof.value;

    let mut curves = Vec::new();
    for method in Method::ALL {
        let options = SolveOptions {
            method,
            steps: args.steps,
            ..SolveOptions::from_scene(&scene)
        };
        match solve(&scene, &options) {
            Ok(solution) => {
                println!(
                    "{:>9}: strain energy {:.8}, {} Newton iterations (+{} in repeated \
                     steps, {} repeats), {} cut-backs",
                    label(method),
                    solution.strain_energy,
                    solution.newton_iterations,
                    solution.repeated_iterations,
                    solution.repeats,
                    solution.cutbacks.len()
                );
                let slide = solution
                    .step_records
                    .iter()
                    .map(|r| distance(r.load_factor))
                    .collect();
                curves.push(Curve {
                    method,
                    solution,
                    slide,
                });
            }
            Err(e) => println!("{:>9}: failed: {e}", label(method)),
        }
    }
    std::fs::create_dir_all(&args.out)
        .map_err(|e| format!("cannot create {}: {e}", args.out.display()))?;
    let csv = args
        .out
        .join(format!("sliding-reactions-{}.csv", args.steps));
    gapsim::solver::report::write_atomic(&csv, to_csv(&curves))
        .map_err(|e| format!("cannot write {}: {e}", csv.display()))?;
    let png = args
        .out
        .join(format!("sliding-reactions-{}.png", args.steps));
    plot(&png, &curves, press, slide, args.steps)
        .map_err(|e| format!("cannot draw {}: {e}", png.display()))?;
    let table = steady_table(&curves, press, slide, args.steady)?;
    print!("{table}");
    let md = args.out.join(format!("sliding-steady-{}.md", args.steps));
    gapsim::solver::report::write_atomic(&md, table)
        .map_err(|e| format!("cannot write {}: {e}", md.display()))?;
    println!(
        "wrote {}, {} and {}",
        csv.display(),
        png.display(),
        md.display()
    );
    Ok(())
}

/// The steady-sliding table (module docs): per method, the mean normal
/// reaction, its ripple and the drag over the window.
fn steady_table(
    curves: &[Curve],
    press: usize,
    slide: usize,
    window: Option<(f64, f64)>,
) -> Result<String, String> {
    let inside = |d: f64| d > 0.0 && window.is_none_or(|(a, b)| (a..=b).contains(&d));
    let mut out = match window {
        Some((a, b)) => format!("Steady sliding, slide distance {a} to {b}:\n\n"),
        None => "Steady sliding, the whole slide:\n\n".to_owned(),
    };
    out.push_str(
        "| method | steps in window | mean normal reaction | ripple | drag | cut-backs |\n\
         |---|---|---|---|---|---|\n",
    );
    for c in curves {
        let rows: Vec<[f64; 2]> = c
            .solution
            .step_records
            .iter()
            .zip(&c.slide)
            .filter(|(_, d)| inside(**d))
            .map(|(r, _)| [r.reactions[press][1], r.reactions[slide][0]])
            .collect();
        if rows.is_empty() {
            return Err("no converged step in the --steady window".to_owned());
        }
        let mean = rows.iter().map(|r| r[0]).sum::<f64>() / rows.len() as f64;
        let ripple = rows.iter().map(|r| (r[0] - mean).abs()).fold(0.0, f64::max) / mean.abs();
        let drag = rows.iter().map(|r| r[1].abs()).fold(0.0, f64::max) / mean.abs();
        out.push_str(&format!(
            "| {} | {} | {:.6} | {:.3} % | {:.3} % | {} |\n",
            label(c.method),
            rows.len(),
            mean,
            100.0 * ripple,
            100.0 * drag,
            c.solution.cutbacks.len()
        ));
    }
    Ok(out)
}

fn to_csv(curves: &[Curve]) -> String {
    let mut out = String::from("method,steps,step,load_factor,slide_distance,strain_energy");
    if let Some(c) = curves.first() {
        for g in &c.solution.support_groups {
            out.push_str(&format!(",{g}_x,{g}_y"));
        }
    }
    out.push('\n');
    for c in curves {
        for (r, s) in c.solution.step_records.iter().zip(&c.slide) {
            out.push_str(&format!(
                "{},{},{},{:?},{:?},{:?}",
                c.method, c.solution.steps, r.step, r.load_factor, s, r.strain_energy
            ));
            for v in r.reactions.iter().flatten() {
                out.push_str(&format!(",{v:?}"));
            }
            out.push('\n');
        }
    }
    out
}

/// Two panels: the tangential reaction (`slide` x) and the normal reaction
/// (`press` y) against the slide distance, over the slide phase (distance
/// above zero) and the press's last step.
fn plot(
    path: &Path,
    curves: &[Curve],
    press: usize,
    slide: usize,
    steps: usize,
) -> Result<(), Box<dyn std::error::Error>> {
    let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, FONT);
    let root = BitMapBackend::new(path, (1400, 560)).into_drawing_area();
    root.fill(&WHITE)?;
    let (left, right) = root.split_horizontally(700);
    let panels = [
        (
            left,
            slide,
            0,
            "tangential reaction on the block's top edge (x)",
        ),
        (
            right,
            press,
            1,
            "normal reaction on the block's top edge (y)",
        ),
    ];
    for (area, group, component, title) in panels {
        // the points from the end of the press on
        let series: Vec<(Method, Vec<(f64, f64)>)> = curves
            .iter()
            .map(|c| {
                let start = c.slide.iter().rposition(|s| *s == 0.0).unwrap_or(0);
                let pts = c.solution.step_records[start..]
                    .iter()
                    .zip(&c.slide[start..])
                    .map(|(r, s)| (*s, r.reactions[group][component]))
                    .collect();
                (c.method, pts)
            })
            .collect();
        let all = series.iter().flat_map(|(_, p)| p.iter());
        let (x0, x1, y0, y1) = all.fold(
            (
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
            ),
            |(a, b, c, d), (x, y)| (a.min(*x), b.max(*x), c.min(*y), d.max(*y)),
        );
        if !(x0.is_finite() && y0.is_finite()) {
            continue;
        }
        let pad = 0.05 * (y1 - y0).max(1e-9);
        let mut chart = ChartBuilder::on(&area)
            .caption(format!("{title}, {steps} steps"), ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(45)
            .y_label_area_size(70)
            .build_cartesian_2d(x0..x1.max(x0 + 1e-9), y0 - pad..y1 + pad)?;
        chart
            .configure_mesh()
            .x_desc("slide distance")
            .y_desc("reaction force")
            .draw()?;
        // the types first, the complete formulation on top
        let ordered = series
            .iter()
            .filter(|(m, _)| *m != Method::Complete)
            .chain(series.iter().filter(|(m, _)| *m == Method::Complete));
        for (method, pts) in ordered {
            let col = color(*method);
            let width = if *method == Method::Complete { 3 } else { 2 };
            chart
                .draw_series(LineSeries::new(
                    pts.iter().copied(),
                    col.stroke_width(width),
                ))?
                .label(label(*method))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], col.stroke_width(2))
                });
            chart.draw_series(pts.iter().map(|p| Circle::new(*p, 3, col.filled())))?;
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::LowerRight)
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()?;
    }
    root.present()?;
    Ok(())
}
