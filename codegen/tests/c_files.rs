//! The checked-in C kernels (`contact-kernels/c/`) are current.
//!
//! The C99 files generated for the shipped formulations
//! ([`codegen::generate_c`]) are compared with the files in
//! `contact-kernels/c/`, and that directory holds no other `.c` or `.h`
//! file. On a mismatch the test prints a unified diff and fails; it
//! re-blesses (writes the generated files, removes stale ones) only when
//! `GAPSIM_BLESS=1` is set, as `golden.rs` does for the Rust kernels.

use std::path::{Path, PathBuf};

fn kernels_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../contact-kernels")
}

fn sources() -> Vec<codegen::Source> {
    let mut files: Vec<_> = std::fs::read_dir(kernels_dir().join("formulations"))
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

/// The `.c` and `.h` files in `dir`, sorted.
fn c_files(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .map(|rd| {
            rd.map(|e| e.expect("dir entry").file_name().into_string().unwrap())
                .filter(|n| n.ends_with(".c") || n.ends_with(".h"))
                .collect()
        })
        .unwrap_or_default();
    names.sort();
    names
}

#[test]
fn checked_in_c_files_are_current() {
    let generated = codegen::generate_c(&sources()).expect("the shipped formulations generate");
    let dir = kernels_dir().join("c");
    let bless = std::env::var("GAPSIM_BLESS").is_ok_and(|v| v == "1");
    let mut problems = Vec::new();
    for file in &generated {
        let path = dir.join(&file.name);
        let current = std::fs::read_to_string(&path).unwrap_or_default();
        if current == file.contents {
            continue;
        }
        if bless {
            std::fs::create_dir_all(&dir).expect("create contact-kernels/c");
            std::fs::write(&path, &file.contents).expect("write C file");
            eprintln!("re-blessed {}", path.display());
            continue;
        }
        let diff = similar::TextDiff::from_lines(&current, &file.contents);
        let shown: String = diff
            .unified_diff()
            .context_radius(3)
            .header(&file.name, "generated")
            .to_string();
        let shown: String = shown.lines().take(100).collect::<Vec<_>>().join("\n");
        problems.push(format!("{} differs:\n{shown}", path.display()));
    }
    for stale in c_files(&dir)
        .into_iter()
        .filter(|n| !generated.iter().any(|f| &f.name == n))
    {
        let path = dir.join(&stale);
        if bless {
            std::fs::remove_file(&path).expect("remove stale C file");
            eprintln!("removed stale {}", path.display());
        } else {
            problems.push(format!("{} is not generated any more", path.display()));
        }
    }
    assert!(
        problems.is_empty(),
        "the C kernels in {} are not current (run with GAPSIM_BLESS=1 to accept):\n{}",
        dir.display(),
        problems.join("\n")
    );
}

#[test]
fn c_generation_is_deterministic() {
    let a = codegen::generate_c(&sources()).unwrap();
    let b = codegen::generate_c(&sources()).unwrap();
    assert_eq!(a, b);
}
