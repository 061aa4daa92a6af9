//! The 3D Cattaneo–Mindlin refinement table (`gapsim::hertz::mindlin3d`):
//! the sphere of `scenes/mindlin3d.toml` (a half model) pressed and shifted
//! with Coulomb friction on two meshes refined at the contact, against
//! Mindlin's stick radius and shear.
//!
//! ```text
//! cargo run --release --example mindlin3d
//! ```
//!
//! prints the Markdown table of docs/benchmarks.md ("Cattaneo–Mindlin in
//! 3D").

use std::path::PathBuf;

use gapsim::hertz::mindlin3d::{MESHES, markdown_3d, scene_on_3d, solve_scene_3d};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let scenes = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let mut rows = Vec::new();
    for (h, file) in MESHES {
        let row = solve_scene_3d(&scene_on_3d(&scenes, file)?, h, file)?;
        eprintln!(
            "{file}: c = {:.4}, stick radius {:?}, {:.1} s",
            row.measured.c, row.measured.stick_radius, row.seconds
        );
        rows.push(row);
    }
    print!("{}", markdown_3d(&rows));
    Ok(())
}
