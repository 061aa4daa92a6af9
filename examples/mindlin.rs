//! The Cattaneo–Mindlin refinement table (`gapsim::hertz::mindlin`): the
//! plane-strain cylinder of `scenes/mindlin.toml` pressed and shifted with
//! Coulomb friction on three meshes refined at the contact, against
//! Mindlin's stick zone and shear.
//!
//! ```text
//! cargo run --release --example mindlin
//! ```
//!
//! prints the Markdown tables of docs/benchmarks.md ("Cattaneo–Mindlin"):
//! the stick zone and shear against Mindlin's, then the hysteresis loop of
//! a cyclic shift on each mesh (its closure, and the work of the
//! tangential load over the cycle against the friction's dissipation).

use std::path::PathBuf;

use gapsim::hertz::mindlin::{MESHES, hysteresis, markdown, solve_on};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let scenes = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let mut rows = Vec::new();
    for (h, file) in MESHES {
        let row = solve_on(&scenes, h, file)?;
        eprintln!(
            "{file}: c = {:.4}, stick half-width {:?}, {:.2} s",
            row.measured.c,
            row.measured.stick_half_width(),
            row.seconds
        );
        rows.push(row);
    }
    print!("{}", markdown(&rows));
    // the hysteresis loop: shift +d, -d, +d with the press held
    println!(
        "\n| mesh | steps | loop points | closure | work of Q over the cycle | friction's dissipation | difference |\n|---|---|---|---|---|---|---|"
    );
    for (_, file) in MESHES {
        let steps = 80;
        let h = hysteresis(&scenes, file, steps)?;
        println!(
            "| {file} | {steps} | {} | {:.1e} | {:.5e} | {:.5e} | {:+.2} % |",
            h.points.len(),
            h.closure,
            h.external_work,
            h.friction_work,
            100.0 * (h.friction_work - h.external_work) / h.external_work
        );
    }
    Ok(())
}
