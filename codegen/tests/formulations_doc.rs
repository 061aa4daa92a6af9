//! docs/formulations.md, the language reference: every example in it (a
//! fenced `formulation` block) parses and generates Rust and C kernels,
//! and it documents every function and macro the parser knows.

const DOC: &str = include_str!("../../docs/formulations.md");
const SN: &str = include_str!("../../contact-kernels/formulations/slave-normal.rs");

/// The fenced blocks whose info string is `formulation`.
fn examples() -> Vec<String> {
    let mut out = Vec::new();
    let mut current: Option<String> = None;
    for line in DOC.lines() {
        match (&mut current, line.trim_end()) {
            (None, "```formulation") => current = Some(String::new()),
            (Some(block), "```") => {
                out.push(std::mem::take(block));
                current = None;
            }
            (Some(block), l) => {
                block.push_str(l);
                block.push('\n');
            }
            (None, _) => {}
        }
    }
    assert!(current.is_none(), "an unclosed example");
    out
}

#[test]
fn every_example_parses_and_generates() {
    let examples = examples();
    assert!(examples.len() >= 5, "{} examples", examples.len());
    for (i, text) in examples.iter().enumerate() {
        let src = codegen::Source {
            name: format!("example-{i}"),
            text: text.clone(),
            compiled: true,
        };
        let rust = codegen::generate(std::slice::from_ref(&src))
            .unwrap_or_else(|e| panic!("example {i}: {e}\n{text}"));
        assert!(rust.code.contains(&format!("fn example_{i}_type6")));
        codegen::generate_c(std::slice::from_ref(&src))
            .unwrap_or_else(|e| panic!("example {i} (C): {e}"));
    }
    // The first example is the shipped slave-normal file, up to comments.
    let code = |t: &str| -> Vec<String> {
        t.lines()
            .map(str::trim)
            .filter(|l| !l.is_empty() && !l.starts_with("//"))
            .map(str::to_owned)
            .collect()
    };
    assert_eq!(code(&examples[0]), code(SN));
}

/// The parser's list of functions (from its own error message) and its
/// macros are all in the reference.
#[test]
fn every_function_and_macro_is_documented() {
    let bad = SN.replace("norm(t_s)", "zzz(t_s)");
    let e = codegen::Formulation::parse("x", &bad)
        .unwrap_err()
        .to_string();
    let known = e
        .split("(known: ")
        .nth(1)
        .and_then(|s| s.split(')').next())
        .unwrap_or_else(|| panic!("{e}"));
    let functions: Vec<&str> = known.split(", ").collect();
    assert!(functions.len() >= 7, "{functions:?}");
    for f in functions {
        assert!(
            DOC.contains(&format!("| `{f}(")),
            "function `{f}` documented"
        );
    }
    for m in ["inputs!(", "implicit!(", "entity!(", "gap!("] {
        assert!(
            DOC.contains(&format!("`{m}")) || DOC.contains(&format!("= {m}")),
            "{m}"
        );
    }
    let bad = SN.replace("let n = entity!(", "let n = zzz!(");
    let e = codegen::Formulation::parse("x", &bad)
        .unwrap_err()
        .to_string();
    for m in ["inputs!", "implicit!", "entity!", "gap!"] {
        assert!(e.contains(m), "the parser names {m}: {e}");
    }
}
