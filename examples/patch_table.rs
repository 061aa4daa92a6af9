//! The contact patch test against the number of Gauss points: plain Gauss
//! integration on every slave segment and segmented integration (Gauss
//! points on every piece between the master nodes' projections), as
//! Markdown tables on stdout.
//!
//! ```text
//! cargo run --release --example patch_table
//! ```
//!
//! For `gauss_points` = 1..8, `scenes/patch-test.toml` (two blocks, 7
//! against 5 elements at a flat interface, uniform pressure `p = 10` on the
//! top) is solved in one load step with the complete formulation, for each
//! formulation and both integration rules. The exact solution is
//! homogeneous (the scene's comments say why); the table gives the errors
//! relative to `p`, as `solver/tests/patch.rs` measures them:
//!
//! * pressure: `max |-lambda_a - p| / p` over the slave nodes (the contact
//!   pressure per unit reference length);
//! * stress: the largest deviation of any Gauss point's second
//!   Piola–Kirchhoff or Cauchy stress component (every element) from its
//!   mean over all Gauss points, and the mean's `|S_xx|`, `|S_xy|`, over
//!   `p`.
//!
//! A run that does not converge is reported as such (its error cell reads
//! `failed` and the reason follows the table).

use std::path::Path;
use std::process::ExitCode;

use solver::element::Stress;
use solver::model::Integration;
use solver::{Formulation, Method, Scene, Solution, SolveOptions, solve};

/// The pressure of the scene (per unit reference length).
const PRESSURE: f64 = 10.0;

/// Errors of one run, relative to the pressure (see the module docs).
struct Errors {
    pressure: f64,
    stress: f64,
    points: usize,
}

fn errors(sol: &Solution) -> Result<Errors, String> {
    let pressure = sol
        .final_state
        .multipliers
        .iter()
        .map(|&lambda| (-lambda - PRESSURE).abs() / PRESSURE)
        .fold(0.0, f64::max);
    let points = sol.point_stresses().map_err(|e| e.to_string())?;
    let n = points.len() as f64;
    let mut stress: f64 = 0.0;
    let measures: [fn(&Stress) -> [f64; 3]; 2] = [|s| s.pk2, |s| s.cauchy];
    for measure in measures {
        let mean: [f64; 3] =
            std::array::from_fn(|c| points.iter().map(|p| measure(p)[c]).sum::<f64>() / n);
        for p in &points {
            for (v, m) in measure(p).iter().zip(&mean) {
                stress = stress.max((v - m).abs() / PRESSURE);
            }
        }
        stress = stress
            .max(mean[0].abs() / PRESSURE)
            .max(mean[2].abs() / PRESSURE);
    }
    Ok(Errors {
        pressure,
        stress,
        points: sol.contact_points.len(),
    })
}

/// Solves the scene with the pair set to `formulation`, `integration` and
/// `gauss_points`.
fn run(
    scene: &Scene,
    formulation: Formulation,
    integration: Integration,
    gauss_points: usize,
) -> Result<Errors, String> {
    let mut s = scene.clone();
    for c in &mut s.contacts {
        c.formulation = formulation;
        c.integration = integration;
        c.gauss_points = Some(gauss_points);
    }
    let options = SolveOptions {
        method: Method::Complete,
        steps: 1,
        ..SolveOptions::from_scene(&s)
    };
    let sol = solve(&s, &options).map_err(|e| e.to_string())?;
    errors(&sol)
}

fn cell(r: &Result<Errors, String>, pick: fn(&Errors) -> f64) -> String {
    match r {
        Ok(e) => format!("{:.1e}", pick(e)),
        Err(_) => "failed".into(),
    }
}

fn main() -> ExitCode {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/patch-test.toml");
    let scene = match Scene::from_file(&path) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::FAILURE;
        }
    };
    let mut failures = Vec::new();
    for formulation in [Formulation::SlaveNormal, Formulation::ClosestPoint] {
        println!(
            "Contact patch test ({}, complete formulation, one load step): errors relative to the pressure\n",
            formulation.name()
        );
        println!(
            "| gauss_points | points (plain / segmented) | plain Gauss: pressure | plain Gauss: stress | segmented: pressure | segmented: stress |"
        );
        println!("|---:|---:|---:|---:|---:|---:|");
        for n in 1..=8 {
            let plain = run(&scene, formulation, Integration::Gauss, n);
            let seg = run(&scene, formulation, Integration::Segmented, n);
            let count = |r: &Result<Errors, String>| {
                r.as_ref()
                    .map_or_else(|_| "-".to_string(), |e| e.points.to_string())
            };
            println!(
                "| {n} | {} / {} | {} | {} | {} | {} |",
                count(&plain),
                count(&seg),
                cell(&plain, |e| e.pressure),
                cell(&plain, |e| e.stress),
                cell(&seg, |e| e.pressure),
                cell(&seg, |e| e.stress),
            );
            for (rule, r) in [("plain Gauss", &plain), ("segmented", &seg)] {
                if let Err(e) = r {
                    failures.push(format!(
                        "{}, {rule}, gauss_points = {n}: {e}",
                        formulation.name()
                    ));
                }
            }
        }
        println!();
    }
    for f in &failures {
        println!("* failed: {f}");
    }
    ExitCode::SUCCESS
}
