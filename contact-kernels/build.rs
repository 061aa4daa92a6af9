//! Generates the contact kernels from `formulations/*.rs` with
//! `gapsim-codegen` into `OUT_DIR/kernels.rs`, and the same kernels over
//! SIMD lanes into `OUT_DIR/kernels_lanes.rs` (each rewritten only when its
//! content changes).
//!
//! A formulation `foo-bar.rs` is compiled in when the crate feature
//! `foo-bar` is enabled; its `Formulation` variant exists either way.

use std::path::{Path, PathBuf};

fn main() {
    let manifest = PathBuf::from(
        std::env::var_os("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR"),
    );
    let dir = manifest.join("formulations");
    println!("cargo:rerun-if-changed={}", dir.display());
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", dir.display()))
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "rs"))
        .collect();
    files.sort();
    let mut sources = Vec::new();
    for path in &files {
        println!("cargo:rerun-if-changed={}", path.display());
        let name = path
            .file_stem()
            .and_then(|s| s.to_str())
            .expect("formulation file names are UTF-8")
            .to_owned();
        let feature = format!("CARGO_FEATURE_{}", name.to_uppercase().replace('-', "_"));
        let text = std::fs::read_to_string(path)
            .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
        sources.push(codegen::Source {
            compiled: std::env::var_os(&feature).is_some(),
            name,
            text,
        });
    }
    let generated = match codegen::generate(&sources) {
        Ok(g) => g,
        Err(e) => {
            // A malformed formulation is a user error: report it as such.
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    };
    let out =
        PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR")).join("kernels.rs");
    write_if_changed(&out, &generated.code);
    // The same kernels over SIMD lanes (`kernels_lanes.rs`), for the batch.
    match codegen::generate_with(&sources, &codegen::emit::LanesEmitter) {
        Ok(files) => {
            for file in files {
                write_if_changed(&out.with_file_name(&file.name), &file.contents);
            }
        }
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    }
}

fn write_if_changed(path: &Path, content: &str) {
    if std::fs::read_to_string(path).is_ok_and(|old| old == content) {
        return;
    }
    std::fs::write(path, content)
        .unwrap_or_else(|e| panic!("cannot write {}: {e}", path.display()));
}
