//! A user's own formulation files through `gapsim generate`, `gapsim
//! verify` and `gapsim kernel`, run as the binary: one-line edits of a
//! shipped file that used to panic or to give a wrong kernel that verifies
//! clean are errors at `FILE:LINE:COLUMN` (the file alone where no line
//! applies), with a non-zero exit and nothing written.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn gapsim(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_gapsim"))
        .args(args)
        .output()
        .expect("run gapsim")
}

fn repo(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(path)
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("gapsim-user-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

fn shipped() -> String {
    std::fs::read_to_string(repo("contact-kernels/formulations/slave-normal.rs")).unwrap()
}

/// Writes slave-normal.rs with `from` replaced by `to` as `dir/name`.
fn edited(dir: &Path, name: &str, from: &str, to: &str) -> PathBuf {
    let s = shipped();
    assert!(s.contains(from), "`{from}` in slave-normal.rs");
    let path = dir.join(name);
    std::fs::write(&path, s.replace(from, to)).unwrap();
    path
}

/// Runs generate (Rust and C) and verify on `file`: each fails without a
/// panic, its message starts with `at` and contains `needle`.
fn refused(file: &Path, at: &str, needle: &str) {
    let out = file.with_extension("out");
    for cmd in [
        vec![
            "generate",
            file.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ],
        vec![
            "generate",
            file.to_str().unwrap(),
            "--lang",
            "c",
            "--out",
            out.to_str().unwrap(),
        ],
        vec!["verify", file.to_str().unwrap()],
    ] {
        let o = gapsim(&cmd);
        let err = text(&o.stderr);
        assert!(!o.status.success(), "{cmd:?} must fail");
        assert!(!err.contains("panicked"), "{cmd:?}: {err}");
        assert!(
            err.starts_with(&format!("gapsim: error: {at}")) && err.contains(needle),
            "{cmd:?}: `{at}` ... `{needle}` in {err}"
        );
    }
    assert!(!out.exists(), "nothing written");
}

fn line_of(file: &Path, needle: &str) -> usize {
    std::fs::read_to_string(file)
        .unwrap()
        .lines()
        .position(|l| l.contains(needle))
        .unwrap()
        + 1
}

#[test]
fn division_by_zero_and_sqrt_of_a_negative_are_errors_at_their_position() {
    let dir = scratch("nonfinite");
    for (name, from, to) in [
        ("div.rs", "gap!(dot(n, x_ms));", "gap!(dot(n, x_ms) / 0.0);"),
        (
            "root.rs",
            "let t_s = xs2 - xs1;",
            "let t_s = (xs2 - xs1) * sqrt(-1.0);",
        ),
    ] {
        let file = edited(&dir, name, from, to);
        let at = format!("{}:{}:", file.display(), line_of(&file, to));
        refused(&file, &at, "non-finite constant");
    }
}

#[test]
fn a_residual_without_its_variable_is_an_error() {
    let dir = scratch("flat");
    let to = "implicit!(xi => dot(xm1 - x_s, t_s))";
    let file = edited(
        &dir,
        "flat.rs",
        "implicit!(xi => dot(lerp(xm1, xm2, xi) - x_s, t_s))",
        to,
    );
    let at = format!("{}:{}:", file.display(), line_of(&file, to));
    refused(&file, &at, "does not depend on `xi`");
}

#[test]
fn an_unknown_macro_is_named_at_its_position() {
    let dir = scratch("macro");
    let file = edited(&dir, "typo.rs", "let n = entity!(", "let n = entty!(");
    let at = format!("{}:{}:", file.display(), line_of(&file, "entty!"));
    refused(&file, &at, "unknown macro `entty!`");
}

/// The kernels take coordinates relative to the first point: a file that
/// depends on an absolute position is refused, at the statement.
#[test]
fn a_formulation_that_is_not_translation_invariant_is_refused() {
    let dir = scratch("moved");
    let file = edited(
        &dir,
        "moved.rs",
        "let t_s = xs2 - xs1;",
        "let t_s = xs2 - xs1 + xs1;",
    );
    // At the `let` of the residual's variable, `xi_m`.
    let line = line_of(&file, "let xi_m = implicit!");
    refused(
        &file,
        &format!("{}:{line}:5: cannot prove", file.display()),
        "the projection residual is translation invariant",
    );
}

#[test]
fn a_file_named_self_generates_and_verifies() {
    let dir = scratch("self");
    let file = dir.join("self.rs");
    std::fs::write(&file, shipped()).unwrap();
    let out = dir.join("out");
    for lang in ["rust", "c"] {
        let o = gapsim(&[
            "generate",
            file.to_str().unwrap(),
            "--lang",
            lang,
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{lang}: {}", text(&o.stderr));
    }
    let rust = std::fs::read_to_string(out.join("kernels.rs")).unwrap();
    assert!(rust.contains("fn self_type6"), "kernels written");
    let o = gapsim(&["verify", file.to_str().unwrap()]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    // the gap's six types, then the slip's
    assert_eq!(text(&o.stdout).matches("| ok |").count(), 12);
}

#[test]
fn two_files_with_one_kernel_name_are_refused() {
    let dir = scratch("collide");
    let (a, b) = (dir.join("a_b.rs"), dir.join("a-b.rs"));
    std::fs::write(&a, shipped()).unwrap();
    std::fs::write(&b, shipped()).unwrap();
    let out = dir.join("out");
    let o = gapsim(&[
        "generate",
        a.to_str().unwrap(),
        b.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    let err = text(&o.stderr);
    assert!(!o.status.success());
    assert!(
        err.contains(&format!("{}:", b.display()))
            && err.contains("`a_b` and `a-b` would generate the same identifiers"),
        "{err}"
    );
    assert!(!out.exists(), "nothing written");
}

/// The generated `kernels.rs` names the user's file, not the shipped
/// directory.
#[test]
fn the_generated_header_names_the_users_file() {
    let dir = scratch("header");
    let file = dir.join("mine.rs");
    std::fs::write(&file, shipped()).unwrap();
    let out = dir.join("out");
    let o = gapsim(&[
        "generate",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let rust = std::fs::read_to_string(out.join("kernels.rs")).unwrap();
    let first = rust.lines().next().unwrap();
    assert_eq!(
        first,
        format!(
            "// @generated by gapsim-codegen from {}. Do not edit.",
            file.display()
        )
    );
}

/// A residual with a double root (the square of slave-normal's): the
/// kernels' Newton solve cannot converge in 20 steps, and `verify` says so
/// instead of "g'' off by 0.0e0 (> 1e-10) at ;".
#[test]
fn verify_explains_a_projection_the_kernels_cannot_solve() {
    let dir = scratch("double");
    let file = edited(
        &dir,
        "double.rs",
        "implicit!(xi => dot(lerp(xm1, xm2, xi) - x_s, t_s))",
        "implicit!(xi => powi(dot(lerp(xm1, xm2, xi) - x_s, t_s), 2))",
    );
    let o = gapsim(&["verify", file.to_str().unwrap()]);
    let err = text(&o.stderr);
    assert!(!o.status.success());
    assert!(!err.contains("off by 0.0e0"), "{err}");
    assert!(!err.contains(" at ;"), "{err}");
    assert!(
        err.contains("the kernels' projection (Newton from xi = 0, at most 20 steps) failed on")
            && err.contains("double"),
        "{err}"
    );
}
