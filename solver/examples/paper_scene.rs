//! Solve the paper scene from code: the complete formulation and one
//! approximation type, compared.
//!
//! ```text
//! cargo run --release -p gapsim-solver --example paper_scene
//! ```
use solver::{ApproxType, Method, Scene, SolveOptions, solve};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let scene = Scene::from_toml_str(
        solver::scenes::STACKED_CANTILEVER,
        "stacked-cantilever.toml",
    )?;
    let mut options = SolveOptions::from_scene(&scene);
    options.steps = 4;
    for method in [Method::Complete, Method::Approx(ApproxType::Type3)] {
        options.method = method;
        let sol = solve(&scene, &options)?;
        let tip = sol
            .node_at("slave", [7.0, 1.0])
            .map(|n| sol.displacement(n));
        println!(
            "{:>8}: strain energy {:.10}, {} Newton iterations, loaded node moves by {tip:?}",
            method.to_string(),
            sol.strain_energy,
            sol.newton_iterations
        );
    }
    Ok(())
}
