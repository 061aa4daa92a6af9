//! `gapsim generate` and `gapsim verify` on formulation files outside the
//! repository, run as the binary.
//!
//! * `generate` writes the same files as the in-tree generator (the
//!   checked-in C files for the shipped formulation), for a variant the
//!   variant's functions; a syntax error is reported at `FILE:LINE:COLUMN`
//!   with a non-zero exit and nothing written.
//! * `verify` passes on the shipped formulations and on a variant (an
//!   edited copy of slave-normal.rs), and fails with a non-zero exit and a
//!   FAIL row for exactly the type whose kernel was broken on purpose
//!   (`--flip-sign`).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use codegen::lower::Instr;
use gapsim::verify::{AdFormulation, InterpretedKernels};

fn gapsim(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_gapsim"))
        .args(args)
        .output()
        .expect("run gapsim")
}

fn repo(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(path)
}

/// A fresh scratch directory for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("gapsim-cli-gen-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

/// slave-normal.rs with the projection and the normal taken along the
/// average of the slave tangent and the reversed master tangent (a
/// different formulation, same language).
fn variant() -> String {
    let shipped =
        std::fs::read_to_string(repo("contact-kernels/formulations/slave-normal.rs")).unwrap();
    let edited = shipped.replace(
        "let t_s = xs2 - xs1;",
        "let t_s = (xs2 - xs1) * 0.5 + (xm1 - xm2) * 0.5;",
    );
    assert_ne!(shipped, edited, "the edit applies");
    edited
}

#[test]
fn generate_c_of_the_shipped_formulation_is_the_checked_in_file() {
    let out = scratch("shipped");
    let o = gapsim(&[
        "generate",
        repo("contact-kernels/formulations/slave-normal.rs")
            .to_str()
            .unwrap(),
        "--lang",
        "c",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    for name in [
        "gapsim.h",
        "gapsim_runtime.h",
        "gapsim_runtime.c",
        "gapsim_slave_normal.h",
        "gapsim_slave_normal.c",
    ] {
        let written = std::fs::read_to_string(out.join(name)).unwrap();
        let checked_in =
            std::fs::read_to_string(repo(&format!("contact-kernels/c/{name}"))).unwrap();
        assert_eq!(
            written, checked_in,
            "{name} differs from the checked-in file"
        );
        assert!(text(&o.stdout).contains(name), "{name} listed on stdout");
    }
}

#[test]
fn generate_a_variant_outside_the_repository() {
    let dir = scratch("variant");
    let file = dir.join("my-normal.rs");
    std::fs::write(&file, variant()).unwrap();
    let out = dir.join("out");
    for (lang, files, needle) in [
        ("rust", &["kernels.rs"][..], "fn my_normal_type6"),
        (
            "c",
            &[
                "gapsim.h",
                "gapsim_runtime.h",
                "gapsim_runtime.c",
                "gapsim_my_normal.h",
                "gapsim_my_normal.c",
            ][..],
            "int gapsim_my_normal_type6(",
        ),
    ] {
        let o = gapsim(&[
            "generate",
            file.to_str().unwrap(),
            "--lang",
            lang,
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{lang}: {}", text(&o.stderr));
        let mut all = String::new();
        for f in files {
            all += &std::fs::read_to_string(out.join(f)).unwrap();
        }
        assert!(all.contains(needle), "{lang}: `{needle}` generated");
    }
}

#[test]
fn a_syntax_error_points_at_file_line_column() {
    let dir = scratch("syntax");
    let file = dir.join("broken.rs");
    // Line 4, column 21: the `)` where an operand is expected.
    let broken = variant().replacen(
        "let x_s = lerp(xs1, xs2, xi_s);",
        "let x_s = lerp(xs1, +);",
        1,
    );
    let line = broken
        .lines()
        .position(|l| l.contains("lerp(xs1, +)"))
        .unwrap()
        + 1;
    std::fs::write(&file, &broken).unwrap();
    let out = dir.join("out");
    for cmd in [
        vec![
            "generate",
            file.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ],
        vec!["verify", file.to_str().unwrap()],
    ] {
        let o = gapsim(&cmd);
        let err = text(&o.stderr);
        assert!(!o.status.success(), "{cmd:?} must fail");
        let at = format!("{}:{line}:", file.display());
        assert!(err.contains(&at), "{cmd:?}: `{at}` in {err}");
        // The column follows the line number.
        let col: String = err[err.find(&at).unwrap() + at.len()..]
            .chars()
            .take_while(char::is_ascii_digit)
            .collect();
        assert!(
            col.parse::<usize>().unwrap() > 1,
            "{cmd:?}: column in {err}"
        );
        assert!(!err.contains("panicked"), "{err}");
    }
    assert!(!out.exists(), "nothing written on error");
}

#[test]
fn bad_file_names_and_missing_files_are_errors() {
    let dir = scratch("names");
    let o = gapsim(&[
        "generate",
        dir.join("absent.rs").to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    assert!(
        text(&o.stderr).contains("cannot read"),
        "{}",
        text(&o.stderr)
    );
    let odd = dir.join("9lives.rs");
    std::fs::write(&odd, variant()).unwrap();
    let o = gapsim(&["verify", odd.to_str().unwrap()]);
    assert!(!o.status.success());
    assert!(
        text(&o.stderr).contains("file name must be NAME.rs"),
        "{}",
        text(&o.stderr)
    );
}

#[test]
fn verify_passes_on_the_shipped_formulations_and_a_variant() {
    let dir = scratch("verify");
    let file = dir.join("my-normal.rs");
    std::fs::write(&file, variant()).unwrap();
    for path in [
        repo("contact-kernels/formulations/slave-normal.rs"),
        repo("contact-kernels/formulations/closest-point.rs"),
        file,
    ] {
        let o = gapsim(&["verify", path.to_str().unwrap()]);
        let table = text(&o.stdout);
        assert!(
            o.status.success(),
            "{}: {table}{}",
            path.display(),
            text(&o.stderr)
        );
        for ty in 1..=6 {
            let row = table
                .lines()
                .find(|l| l.starts_with(&format!("| {ty} |")))
                .unwrap_or_else(|| panic!("row {ty} in {table}"));
            assert!(row.ends_with("| ok |"), "{row}");
        }
        // Most configurations are compared, not skipped.
        let checked: usize = table.split_whitespace().nth(1).unwrap().parse().unwrap();
        assert!(checked >= 1000, "{table}");
    }
}

/// A residual that is not affine in `xi` (slave-normal's times the
/// positive `2 + xi^2`: the same root, so the same gap and derivatives):
/// the kernels take the converged `xi_m` (Newton on the residual program),
/// the reference solves it in dual arithmetic. Verifies clean.
#[test]
fn verify_a_formulation_whose_projection_needs_newton() {
    let dir = scratch("newton");
    let file = dir.join("curved-residual.rs");
    let shipped =
        std::fs::read_to_string(repo("contact-kernels/formulations/slave-normal.rs")).unwrap();
    let edited = shipped.replace(
        "implicit!(xi => dot(lerp(xm1, xm2, xi) - x_s, t_s))",
        "implicit!(xi => dot(lerp(xm1, xm2, xi) - x_s, t_s) * (2.0 + xi * xi))",
    );
    assert_ne!(shipped, edited, "the edit applies");
    std::fs::write(&file, &edited).unwrap();
    let f = AdFormulation::parse("curved-residual", &edited).unwrap();
    assert!(
        !codegen::programs(f.formulation()).unwrap().affine,
        "the residual is not affine"
    );
    let o = gapsim(&["verify", file.to_str().unwrap()]);
    let table = text(&o.stdout);
    assert!(o.status.success(), "{table}{}", text(&o.stderr));
    // Six gap kernels, then the file's six slip kernels.
    assert_eq!(table.matches("| ok |").count(), 12, "{table}");
    assert!(table.contains("curved-residual (slip): "), "{table}");
}

#[test]
fn verify_catches_a_kernel_broken_on_purpose() {
    let dir = scratch("flip");
    let file = dir.join("my-normal.rs");
    std::fs::write(&file, variant()).unwrap();
    // The middle addition or subtraction of Type 3's instruction list.
    let f = AdFormulation::parse("my-normal", &variant()).unwrap();
    let kernels = InterpretedKernels::new(f.formulation()).unwrap();
    let adds: Vec<usize> = (kernels.program(3).instrs.iter().enumerate())
        .filter(|(_, i)| matches!(i, Instr::Add(..) | Instr::Sub(..)))
        .map(|(k, _)| k)
        .collect();
    let k = adds[adds.len() / 2];
    let flip = format!("3:{k}");
    let o = gapsim(&["verify", file.to_str().unwrap(), "--flip-sign", &flip]);
    let (table, err) = (text(&o.stdout), text(&o.stderr));
    assert!(!o.status.success(), "a broken kernel must fail: {table}");
    assert!(
        table.contains(&format!("mutated on purpose: type 3 instruction {k}")),
        "{table}"
    );
    for ty in 1..=6 {
        let row = table
            .lines()
            .find(|l| l.starts_with(&format!("| {ty} |")))
            .unwrap();
        let expect = if ty == 3 { "| FAIL |" } else { "| ok |" };
        assert!(row.ends_with(expect), "type {ty}: {row}");
    }
    assert!(err.contains("verification failed: type 3:"), "{err}");
    // Not an addition: a clear error, no table.
    let o = gapsim(&["verify", file.to_str().unwrap(), "--flip-sign", "3:0"]);
    assert!(!o.status.success());
    assert!(
        text(&o.stderr).contains("not an addition or subtraction"),
        "{}",
        text(&o.stderr)
    );
}

/// A 3D face formulation outside the repository: `gapsim verify` checks
/// every type on the face families, `gapsim generate --lang rust` writes
/// its face kernels, `--lang c` its C99 files (`xi_s` as two doubles,
/// `xi_m` through two pointers).
#[test]
fn generate_and_verify_take_face_formulations() {
    let dir = scratch("faces");
    let file = dir.join("my-face.rs");
    let shipped = std::fs::read_to_string(repo(
        "contact-kernels/formulations/tri3-quad4-slave-normal.rs",
    ))
    .unwrap();
    std::fs::write(&file, shipped).unwrap();
    let path = file.to_str().unwrap();
    let out = gapsim(&["verify", path]);
    let stdout = text(&out.stdout);
    assert!(out.status.success(), "{stdout}{}", text(&out.stderr));
    assert!(stdout.contains("my-face: 1"), "{stdout}");
    assert!(stdout.contains("my-face (slip): 1"), "{stdout}");
    assert_eq!(stdout.matches("| ok |").count(), 12, "{stdout}");
    let gen_dir = dir.join("out");
    let out = gapsim(&[
        "generate",
        path,
        "--lang",
        "rust",
        "--out",
        gen_dir.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let code = std::fs::read_to_string(gen_dir.join("kernels.rs")).unwrap();
    assert!(code.contains("static MY_FACE: FaceKernelSet"));
    assert!(code.contains("fn my_face_type6(") && code.contains("xi_s: &[f64]"));
    let out = gapsim(&[
        "generate",
        path,
        "--lang",
        "c",
        "--out",
        gen_dir.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let header = std::fs::read_to_string(gen_dir.join("gapsim_my_face.h")).unwrap();
    assert!(
        header.contains(
            "int gapsim_my_face_type6(const double q[21], double xi_s_u, double xi_s_v, \
             double *gap, double *xi_m_u, double *xi_m_v, double grad[21], double hess[441]);"
        ),
        "{header}"
    );
    let source = std::fs::read_to_string(gen_dir.join("gapsim_my_face.c")).unwrap();
    assert!(
        source.contains("#include \"gapsim_runtime.h\"")
            && source.contains("gapsim_validate_faces(q, s, 3, 4, d)")
    );
    let runtime = std::fs::read_to_string(gen_dir.join("gapsim_runtime.c")).unwrap();
    assert!(runtime.contains("static int check_face("));
    let common = std::fs::read_to_string(gen_dir.join("gapsim.h")).unwrap();
    assert!(common.contains("GAPSIM_SLAVE_POINT_OUTSIDE = 16"));
}
