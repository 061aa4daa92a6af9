//! The shipped formulation files mutated at random (operators swapped,
//! constants replaced by awkward values, names replaced by other names of
//! the file, of the language or unknown ones, up to three edits at once):
//! the library entry points of `gapsim generate` (codegen's Rust and C
//! generation) and of `gapsim verify` (the reference, the interpreted
//! kernels and the verifier on a few configurations) return `Ok` or an
//! error, never panic.

use proptest::prelude::*;

const FILES: [(&str, &str); 3] = [
    (
        "slave-normal",
        include_str!("../contact-kernels/formulations/slave-normal.rs"),
    ),
    (
        "closest-point",
        include_str!("../contact-kernels/formulations/closest-point.rs"),
    ),
    (
        "quadratic-slave-normal",
        include_str!("../contact-kernels/formulations/quadratic-slave-normal.rs"),
    ),
];

/// Replacement operators, constants and names.
const OPERATORS: [&str; 4] = ["+", "-", "*", "/"];
const CONSTANTS: [&str; 9] = [
    "0.0", "-1.0", "1e308", "1e-320", "2.0", "0.5", "1e200", "-0.0", "3",
];
const NAMES: [&str; 17] = [
    "xi", "xi_s", "xi_m", "xs1", "xs2", "xm1", "xm2", "x_s", "t_s", "n", "x_ms", "lerp", "dot",
    "sqrt", "norm", "entty", "self",
];

/// One token of a file: where it is and what kind.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    Operator,
    Constant,
    Name,
}

/// The mutable tokens of `text` (outside `//` comments): byte ranges and
/// kinds.
fn tokens(text: &str) -> Vec<(usize, usize, Kind)> {
    let mut out = Vec::new();
    let mut offset = 0;
    for line in text.split_inclusive('\n') {
        let code = line.find("//").map_or(line, |c| &line[..c]);
        let b = code.as_bytes();
        let mut i = 0;
        while i < b.len() {
            let c = b[i] as char;
            let start = i;
            if c.is_ascii_alphabetic() || c == '_' {
                while i < b.len() && ((b[i] as char).is_ascii_alphanumeric() || b[i] == b'_') {
                    i += 1;
                }
                out.push((offset + start, offset + i, Kind::Name));
            } else if c.is_ascii_digit() {
                while i < b.len() && ((b[i] as char).is_ascii_alphanumeric() || b[i] == b'.') {
                    i += 1;
                }
                out.push((offset + start, offset + i, Kind::Constant));
            } else {
                if "+-*/".contains(c) && !(c == '=' || b.get(i + 1) == Some(&b'>')) {
                    out.push((offset + start, offset + i + 1, Kind::Operator));
                }
                i += 1;
            }
        }
        offset += line.len();
    }
    out
}

/// `text` with the edits `(token index, replacement index)` applied (token
/// indices modulo the count, replacements modulo their list's length).
fn mutate(text: &str, edits: &[(usize, usize)]) -> String {
    let toks = tokens(text);
    let mut chosen: Vec<(usize, usize, String)> = edits
        .iter()
        .map(|&(t, r)| {
            let (a, b, kind) = toks[t % toks.len()];
            let with = match kind {
                Kind::Operator => OPERATORS[r % OPERATORS.len()],
                Kind::Constant => CONSTANTS[r % CONSTANTS.len()],
                // A name becomes another name or, now and then, a constant.
                Kind::Name if r % 4 == 3 => CONSTANTS[r % CONSTANTS.len()],
                Kind::Name => NAMES[r % NAMES.len()],
            };
            (a, b, with.to_owned())
        })
        .collect();
    // Apply from the end, one edit per token.
    chosen.sort_by_key(|x| std::cmp::Reverse(x.0));
    chosen.dedup_by_key(|x| x.0);
    let mut s = text.to_owned();
    for (a, b, with) in chosen {
        s.replace_range(a..b, &with);
    }
    s
}

/// Every entry point; `Ok` or `Err` both fine.
fn exercise(name: &str, text: &str) {
    let source = codegen::Source {
        name: name.into(),
        text: text.into(),
        compiled: true,
    };
    let _ = codegen::generate(std::slice::from_ref(&source));
    let _ = codegen::generate_c(std::slice::from_ref(&source));
    // `gapsim verify`'s steps (verify_source), on a few configurations.
    let Ok(reference) = gapsim::verify::AdFormulation::parse(name, text) else {
        return;
    };
    let Ok(configs) = gapsim::verify::configurations(&reference) else {
        return;
    };
    let Ok(kernels) = gapsim::verify::InterpretedKernels::new(reference.formulation()) else {
        return;
    };
    let run = |ty: usize, q: &[f64], p: &[f64]| kernels.eval(ty, &kernels.relative(q), p);
    let _ = gapsim::verify::verify(&reference, &run, &configs[..4], gapsim::verify::TOL);
}

#[test]
fn the_tokenizer_finds_every_kind() {
    let t = tokens(FILES[2].1);
    for kind in [Kind::Operator, Kind::Constant, Kind::Name] {
        assert!(t.iter().any(|x| x.2 == kind), "{kind:?}");
    }
    // Names with digits are names (`xs1`), literals are constants.
    let s = "let a = xs1 * 2.5;";
    let kinds: Vec<(&str, Kind)> = tokens(s).iter().map(|x| (&s[x.0..x.1], x.2)).collect();
    assert_eq!(
        kinds,
        [
            ("let", Kind::Name),
            ("a", Kind::Name),
            ("xs1", Kind::Name),
            ("*", Kind::Operator),
            ("2.5", Kind::Constant)
        ]
    );
    // `=>` is not an operator; a `//!` comment holds no token.
    let s = "//! a - b\nlet x = implicit!(xi => xi - 1.0);\n";
    let ops: Vec<&str> = tokens(s)
        .iter()
        .filter(|x| x.2 == Kind::Operator)
        .map(|x| &s[x.0..x.1])
        .collect();
    assert_eq!(ops, ["-"]);
    // A mutation applies.
    assert_ne!(mutate(FILES[0].1, &[(0, 1)]), FILES[0].1);
}

/// The panics, each one edit of a shipped file, as fixed cases.
#[test]
fn the_reported_edits_do_not_panic() {
    let sn = FILES[0].1;
    for (from, to) in [
        ("gap!(dot(n, x_ms));", "gap!(dot(n, x_ms) / 0.0);"),
        (
            "let t_s = xs2 - xs1;",
            "let t_s = sqrt(-1.0) * (xs2 - xs1);",
        ),
        (
            "implicit!(xi => dot(lerp(xm1, xm2, xi) - x_s, t_s))",
            "implicit!(xi => dot(xm1 - x_s, t_s))",
        ),
        ("let t_s = xs2 - xs1;", "let t_s = xs2 - xs1 + xs1;"),
    ] {
        assert!(sn.contains(from));
        exercise("slave-normal", &sn.replace(from, to));
    }
    exercise("self", sn);
}

proptest! {
    // A modest count: each case generates and interprets every type.
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn mutated_formulations_never_panic(
        file in 0..FILES.len(),
        edits in proptest::collection::vec((0usize..10_000, 0usize..100), 1..=3),
    ) {
        let (name, text) = FILES[file];
        exercise(name, &mutate(text, &edits));
    }
}
