//! The stability sweep (`gapsim::stability`): the Type 6 kernels in f64
//! against a double-double hyper-dual reference over the hard families,
//! for segment pairs and for 3D face pairs.
//!
//! ```text
//! cargo run --release --example stability_sweep [-- OUT_DIR]
//! ```
//!
//! writes `OUT_DIR` (default `docs/stability`): segments `stability.csv`
//! and `stability.md` (also printed: docs/kernels.md's `stability` table),
//! `stability.{png,svg}`; faces `stability-faces.csv`, `stability-faces.md`
//! (docs/kernels.md's `stability-faces` table), `stability-faces.{png,svg}`.

use std::path::PathBuf;

use gapsim::solver::report::write_atomic;
use gapsim::stability::faces::sweep_faces;
use gapsim::stability::{csv, markdown, markdown_faces, plot, sweep};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args_os().nth(1).map_or_else(
        || PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("docs/stability"),
        PathBuf::from,
    );
    let rows = sweep();
    std::fs::create_dir_all(&out)?;
    write_atomic(out.join("stability.csv"), csv(&rows))?;
    let md = markdown(&rows);
    write_atomic(out.join("stability.md"), &md)?;
    plot::write(&rows, &out, "stability")?;
    let faces = sweep_faces();
    write_atomic(out.join("stability-faces.csv"), csv(&faces))?;
    write_atomic(out.join("stability-faces.md"), markdown_faces(&faces))?;
    plot::write_faces(&faces, &out, "stability-faces")?;
    print!("{md}");
    Ok(())
}
