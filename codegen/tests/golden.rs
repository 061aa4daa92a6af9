//! Golden files for the generated kernels.
//!
//! The generated source for the shipped formulations is compared with
//! `tests/golden/kernels.rs`, the lane kernels with
//! `tests/golden/kernels_lanes.rs`. On a mismatch the test prints a unified diff
//! and fails; it re-blesses the file only when `GAPSIM_BLESS=1` is set, so
//! nothing is overwritten silently.

use std::path::Path;

fn formulations_dir() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../contact-kernels/formulations")
}

/// The shipped formulations of segments (2D): `kernels.rs` and
/// `kernels_lanes.rs` are theirs.
fn sources() -> Vec<codegen::Source> {
    sources_of_dim(2)
}

/// The shipped formulations whose points have `dim` coordinates.
fn sources_of_dim(dim: usize) -> Vec<codegen::Source> {
    all_sources()
        .into_iter()
        .filter(|s| {
            codegen::Formulation::parse(&s.name, &s.text)
                .expect("the shipped formulations parse")
                .signature
                .dim()
                == dim
        })
        .collect()
}

fn all_sources() -> Vec<codegen::Source> {
    let mut files: Vec<_> = std::fs::read_dir(formulations_dir())
        .expect("formulations directory")
        .map(|e| e.expect("dir entry").path())
        .filter(|p| p.extension().is_some_and(|x| x == "rs"))
        .collect();
    files.sort();
    files
        .iter()
        .map(|p| codegen::Source {
            name: p.file_stem().unwrap().to_str().unwrap().to_owned(),
            text: std::fs::read_to_string(p).unwrap(),
            compiled: true,
        })
        .collect()
}

#[test]
fn generated_kernels_match_golden_file() {
    let generated = codegen::generate(&sources()).expect("the shipped formulations generate");
    check_golden("kernels.rs", &generated.code);
}

#[test]
fn generated_lane_kernels_match_golden_file() {
    let files = codegen::generate_with(&sources(), &codegen::emit::LanesEmitter)
        .expect("the shipped formulations generate");
    let [file] = files.as_slice() else {
        panic!("the lane emitter writes one file")
    };
    assert_eq!(file.name, codegen::emit::lanes::LANES_FILE);
    check_golden(&file.name, &file.contents);
}

/// Compares `generated` with `tests/golden/{name}`; re-blesses it with
/// `GAPSIM_BLESS=1`, otherwise fails with a unified diff.
fn check_golden(name: &str, generated: &str) {
    let golden_path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/golden")
        .join(name);
    let bless = std::env::var("GAPSIM_BLESS").is_ok_and(|v| v == "1");
    let golden = std::fs::read_to_string(&golden_path).unwrap_or_default();
    if golden == generated {
        return;
    }
    if bless {
        std::fs::write(&golden_path, generated).expect("write golden file");
        eprintln!("re-blessed {}", golden_path.display());
        return;
    }
    let diff = similar::TextDiff::from_lines(&golden, generated);
    let shown: String = diff
        .unified_diff()
        .context_radius(3)
        .header("golden", "generated")
        .to_string();
    let shown: String = shown.lines().take(200).collect::<Vec<_>>().join("\n");
    panic!(
        "generated kernels differ from {} (run with GAPSIM_BLESS=1 to accept):\n{shown}",
        golden_path.display()
    );
}

#[test]
fn generation_is_deterministic() {
    let a = codegen::generate(&sources()).unwrap();
    let b = codegen::generate(&sources()).unwrap();
    assert_eq!(a.code, b.code);
}
