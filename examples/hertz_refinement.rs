//! The Hertz refinement study (`gapsim::hertz::refinement`): the Hertz
//! quarter model on five meshes refined at the contact, with small-strain
//! and finite-strain solids, against Hertz's solution.
//!
//! ```text
//! cargo run --release --example hertz_refinement [-- OUT_DIR]
//! ```
//!
//! writes `OUT_DIR` (default `docs/hertz`): `hertz-refinement.csv`,
//! `hertz-refinement.md` (also printed) and `hertz-refinement.{png,svg}`.

use std::path::PathBuf;

use gapsim::hertz::{SCENES, refinement};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let out = std::env::args_os()
        .nth(1)
        .map_or_else(|| root.join("docs/hertz"), PathBuf::from);
    let rows = refinement::run(&root.join("scenes"), |row| {
        eprintln!(
            "{} ({:?}): peak {:.4} ({:+.2} %), {} Newton iterations, {:.2} s",
            row.mesh,
            row.kinematics,
            row.measured.peak,
            100.0 * row.measured.peak_error(&SCENES),
            row.newton_iterations,
            row.seconds
        );
    })?;
    for path in refinement::write(&rows, &SCENES, &out)? {
        eprintln!("wrote {}", path.display());
    }
    print!("{}", refinement::markdown(&rows, &SCENES));
    Ok(())
}
