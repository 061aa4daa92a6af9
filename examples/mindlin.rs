//! The Cattaneo–Mindlin refinement table (`gapsim::hertz::mindlin`): the
//! plane-strain cylinder of `scenes/mindlin.toml` pressed and shifted with
//! Coulomb friction on three meshes refined at the contact, against
//! Mindlin's stick zone and shear.
//!
//! ```text
//! cargo run --release --example mindlin
//! ```
//!
//! prints the Markdown table of docs/benchmarks.md ("Cattaneo–Mindlin").

use std::path::PathBuf;

use gapsim::hertz::mindlin::{MESHES, markdown, solve_on};

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
    Ok(())
}
