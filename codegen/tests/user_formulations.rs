//! A user's formulation file through the library entry points: every
//! mistake that used to panic (or to generate a wrong kernel) is an error
//! at `file:line:col`, or at the file where no line applies.

use codegen::{KernelPlan, Source};

const SN: &str = include_str!("../../contact-kernels/formulations/slave-normal.rs");

fn source(name: &str, text: &str) -> Source {
    Source {
        name: name.into(),
        text: text.into(),
        compiled: true,
    }
}

/// The generator's error for `text` named `name`, after checking that the
/// edit `from` -> `to` applied.
fn error(name: &str, from: &str, to: &str) -> String {
    assert!(SN.contains(from), "`{from}` in slave-normal.rs");
    let text = SN.replace(from, to);
    codegen::generate(&[source(name, &text)])
        .expect_err("the edited file is refused")
        .to_string()
}

/// 1-based line of the first line of the edited file containing `needle`.
fn line_of(from: &str, to: &str, needle: &str) -> usize {
    SN.replace(from, to)
        .lines()
        .position(|l| l.contains(needle))
        .expect("needle")
        + 1
}

#[test]
fn non_finite_constants_are_errors_at_their_position() {
    for (from, to, needle) in [
        ("gap!(dot(n, x_ms));", "gap!(dot(n, x_ms) / 0.0);", "inf"),
        (
            "let t_s = xs2 - xs1;",
            "let t_s = (xs2 - xs1) * sqrt(-1.0);",
            "NaN",
        ),
        (
            "let t_s = xs2 - xs1;",
            "let t_s = (xs2 - xs1) * (1e300 * 1e300);",
            "inf",
        ),
    ] {
        let e = error("bad", from, to);
        let line = line_of(from, to, to);
        assert!(
            e.starts_with(&format!("bad.rs:{line}:")) && e.contains("non-finite constant"),
            "{e}"
        );
        assert!(e.contains(needle), "{e}");
    }
}

#[test]
fn a_residual_that_does_not_depend_on_its_variable_is_an_error() {
    let from = "implicit!(xi => dot(lerp(xm1, xm2, xi) - x_s, t_s))";
    let to = "implicit!(xi => dot(xm1 - x_s, t_s))";
    let e = error("flat", from, to);
    let line = line_of(from, to, to);
    assert!(
        e.starts_with(&format!("flat.rs:{line}:")) && e.contains("does not depend on `xi`"),
        "{e}"
    );
}

#[test]
fn an_unknown_macro_is_named() {
    let from = "let n = entity!(";
    let to = "let n = entty!(";
    let e = error("typo", from, to);
    let line = line_of(from, to, to);
    assert!(
        e.starts_with(&format!("typo.rs:{line}:")) && e.contains("unknown macro `entty!`"),
        "{e}"
    );
    let e = error(
        "nested",
        "gap!(dot(n, x_ms));",
        "gap!(entity!(dot(n, x_ms)));",
    );
    assert!(
        e.contains("`entity!` must be the whole value of a `let`"),
        "{e}"
    );
}

/// The example: `t_s = xs2 - xs1 + xs1` is `xs2`, which the
/// relative-coordinate kernels would evaluate as `xs2 - xs1`.
#[test]
fn a_formulation_that_is_not_translation_invariant_is_refused() {
    let (from, to) = ("let t_s = xs2 - xs1;", "let t_s = xs2 - xs1 + xs1;");
    let e = error("moved", from, to);
    let line = line_of(from, to, "let xi_m = implicit!");
    assert!(
        e.starts_with(&format!(
            "moved.rs:{line}:5: cannot prove that the projection residual is translation invariant"
        )),
        "{e}"
    );
    // An entity at its `let`.
    let (from, to) = (
        "let n = entity!(perp(t_s) / norm(t_s));",
        "let n = entity!(perp(xs2) / norm(t_s));",
    );
    let e = error("normal", from, to);
    let line = line_of(from, to, to);
    assert!(
        e.starts_with(&format!("normal.rs:{line}:5: cannot prove that entity `n`")),
        "{e}"
    );
}

/// A keyword file name works: `self.rs` gives `self_type1` and the enum
/// variant `Self_`, a file that parses.
#[test]
fn a_file_named_self_generates() {
    let g = codegen::generate(&[source("self", SN)]).unwrap();
    assert!(g.code.contains("fn self_type6"), "kernels generated");
    assert!(g.code.contains("Self_"), "the variant");
    syn::parse_file(&g.code).expect("the generated file parses");
    for f in codegen::generate_c(&[source("self", SN)]).unwrap() {
        assert!(!f.contents.is_empty(), "{}", f.name);
    }
}

#[test]
fn names_that_generate_the_same_identifiers_are_refused() {
    for pair in [["a_b", "a-b"], ["a-b", "A-b"]] {
        let e = KernelPlan::build(&[source(pair[0], SN), source(pair[1], SN)])
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with(&format!("{}.rs:", pair[1]))
                && e.contains(&format!("`{}` and `{}`", pair[0], pair[1])),
            "{e}"
        );
    }
    for bad in ["9lives", "a b", "", "ü"] {
        let e = KernelPlan::build(&[source(bad, SN)])
            .unwrap_err()
            .to_string();
        assert!(e.contains("is not a formulation name"), "{bad:?}: {e}");
    }
}

/// The generated files name where the formulations came from.
#[test]
fn the_header_names_the_source() {
    let plan = KernelPlan::build(&[source("mine", SN)]).unwrap();
    let shipped = codegen::emit::RustEmitter.source(&plan);
    assert!(
        shipped
            .starts_with("// @generated by gapsim-codegen from contact-kernels/formulations/*.rs."),
        "the shipped build keeps its header"
    );
    let plan = plan.with_origin("/home/me/mine.rs");
    for file in [
        codegen::emit::RustEmitter.source(&plan),
        codegen::emit::LanesEmitter.source(&plan),
    ] {
        let first = file.lines().next().unwrap();
        assert!(first.contains("from /home/me/mine.rs."), "{first}");
    }
}
