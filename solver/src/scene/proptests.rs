//! Property tests of the scene reader: random mutations of valid scenes
//! (every `scenes/*.toml`, read from their real paths so that their mesh
//! files resolve, and the embedded paper scene) never make
//! [`Scene::from_toml_str`] panic, and every error it returns names the
//! scene file first (`ORIGIN: ...`).
//!
//! The mutations: drop one key (anywhere, also inside arrays of tables),
//! replace one value with a random TOML value (scalars including NaN,
//! infinities, the integer extremes and words the schema knows; small
//! arrays and tables), truncate the text, insert junk. Random integers are
//! small or extreme, never moderately large, so that a case never builds a
//! legitimately huge mesh; 48 cases per property keep the suite fast in the
//! dev profile.

use std::path::Path;

use proptest::prelude::*;
use toml::{Table, Value};

use super::Scene;

/// `(origin, text)` of every scene the mutations start from.
fn scenes() -> Vec<(String, String)> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
    let mut out: Vec<(String, String)> = std::fs::read_dir(&dir)
        .expect("the scenes directory")
        .map(|e| e.expect("a directory entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .map(|p| {
            let text = std::fs::read_to_string(&p).expect("a readable scene");
            (p.display().to_string(), text)
        })
        .collect();
    out.sort();
    assert!(out.len() >= 3, "scenes/*.toml: {out:?}");
    out.push((
        "stacked-cantilever.toml (embedded)".to_owned(),
        crate::scenes::STACKED_CANTILEVER.to_owned(),
    ));
    out
}

/// Reads `text` as `origin`; an error must name `origin` first.
fn check(origin: &str, text: &str) -> Result<(), TestCaseError> {
    if let Err(e) = Scene::from_toml_str(text, origin) {
        let message = e.to_string();
        prop_assert!(
            message.starts_with(&format!("{origin}:")),
            "the error does not name {origin}: {message}"
        );
    }
    Ok(())
}

/// One step of a path into a TOML document.
#[derive(Debug, Clone)]
enum Step {
    Key(String),
    Index(usize),
}

/// The path of every value in `table` (depth first).
fn paths(table: &Table) -> Vec<Vec<Step>> {
    fn walk(value: &Value, at: &mut Vec<Step>, out: &mut Vec<Vec<Step>>) {
        out.push(at.clone());
        match value {
            Value::Table(t) => {
                for (k, v) in t {
                    at.push(Step::Key(k.clone()));
                    walk(v, at, out);
                    at.pop();
                }
            }
            Value::Array(a) => {
                for (i, v) in a.iter().enumerate() {
                    at.push(Step::Index(i));
                    walk(v, at, out);
                    at.pop();
                }
            }
            _ => {}
        }
    }
    let mut out = Vec::new();
    walk(&Value::Table(table.clone()), &mut Vec::new(), &mut out);
    out.remove(0); // the document itself
    out
}

/// The value at `path` (not empty) in `table`, and a way to replace or
/// remove it.
fn edit(table: &mut Table, path: &[Step], replacement: Option<Value>) {
    let (last, parents) = path.split_last().expect("a non-empty path");
    let mut here = Value::Table(std::mem::take(table));
    {
        let mut cursor = &mut here;
        for step in parents {
            cursor = match (step, cursor) {
                (Step::Key(k), Value::Table(t)) => t.get_mut(k).expect("a path of the table"),
                (Step::Index(i), Value::Array(a)) => &mut a[*i],
                _ => unreachable!("paths follow the table"),
            };
        }
        match (last, cursor, replacement) {
            (Step::Key(k), Value::Table(t), Some(v)) => {
                t.insert(k.clone(), v);
            }
            (Step::Key(k), Value::Table(t), None) => {
                t.remove(k);
            }
            (Step::Index(i), Value::Array(a), Some(v)) => a[*i] = v,
            (Step::Index(i), Value::Array(a), None) => {
                a.remove(*i);
            }
            _ => unreachable!("paths follow the table"),
        }
    }
    let Value::Table(t) = here else {
        unreachable!("the document is a table")
    };
    *table = t;
}

/// Words the schema knows, so that replacements often reach the checks
/// behind the parser.
const WORDS: &[&str] = &[
    "",
    "x",
    "y",
    "xy",
    "top",
    "bottom",
    "left",
    "right",
    "persistent",
    "unilateral",
    "slave-normal",
    "closest-point",
    "complete",
    "3",
    "lu",
    "ldlt",
    "plane-strain",
    "plane-stress",
    "master",
    "slave",
    "base",
    "block",
    "cylinder",
    "block_top",
    "hertz.msh",
    "hertz-coarse.msh",
    "missing.msh",
    "../scenes",
];

fn toml_value() -> impl Strategy<Value = Value> {
    let leaf = prop_oneof![
        any::<bool>().prop_map(Value::Boolean),
        prop_oneof![
            -3i64..12,
            Just(i64::MAX),
            Just(i64::MIN),
            Just(1 << 32),
            Just(1 << 53),
        ]
        .prop_map(Value::Integer),
        prop_oneof![
            -10.0f64..10.0,
            Just(f64::NAN),
            Just(f64::INFINITY),
            Just(f64::NEG_INFINITY),
            Just(0.0),
            Just(-0.0),
            Just(1e300),
            Just(-1e300),
            Just(f64::MIN_POSITIVE),
            Just(5e-324),
        ]
        .prop_map(Value::Float),
        prop_oneof![
            prop::sample::select(WORDS).prop_map(str::to_owned),
            "\\PC{0,8}",
        ]
        .prop_map(Value::String),
    ];
    leaf.prop_recursive(2, 12, 4, |inner| {
        prop_oneof![
            prop::collection::vec(inner.clone(), 0..4).prop_map(Value::Array),
            prop::collection::vec(("[a-z_]{1,8}", inner), 0..3)
                .prop_map(|kv| Value::Table(kv.into_iter().collect())),
        ]
    })
}

/// A scene (index into [`scenes`]) and its parsed table.
fn scene() -> impl Strategy<Value = (String, String)> {
    prop::sample::select(scenes())
}

/// The largest char boundary of `text` at or before `at`.
fn boundary(text: &str, mut at: usize) -> usize {
    at = at.min(text.len());
    while !text.is_char_boundary(at) {
        at -= 1;
    }
    at
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn dropping_a_key_never_panics(
        (origin, text) in scene(),
        which in any::<prop::sample::Index>(),
    ) {
        let mut table: Table = text.parse().expect("a valid scene");
        let all = paths(&table);
        edit(&mut table, &all[which.index(all.len())], None);
        let mutated = toml::to_string(&table);
        prop_assume!(mutated.is_ok());
        check(&origin, &mutated.unwrap())?;
    }

    #[test]
    fn replacing_a_value_never_panics(
        (origin, text) in scene(),
        which in any::<prop::sample::Index>(),
        value in toml_value(),
    ) {
        let mut table: Table = text.parse().expect("a valid scene");
        let all = paths(&table);
        edit(&mut table, &all[which.index(all.len())], Some(value));
        let mutated = toml::to_string(&table);
        prop_assume!(mutated.is_ok());
        check(&origin, &mutated.unwrap())?;
    }

    #[test]
    fn truncating_never_panics(
        (origin, text) in scene(),
        at in any::<prop::sample::Index>(),
    ) {
        let end = boundary(&text, at.index(text.len() + 1));
        check(&origin, &text[..end])?;
    }

    #[test]
    fn inserting_junk_never_panics(
        (origin, text) in scene(),
        at in any::<prop::sample::Index>(),
        junk in prop_oneof![
            "[\\[\\]{}=\",.#\n a-z0-9_-]{1,12}",
            "\\PC{1,6}",
            prop::sample::select(vec!["[[body]]\n", "[mesh]\n", "nx = 0\n", "= =", "\"", "[", "]]"])
                .prop_map(str::to_owned),
        ],
    ) {
        let at = boundary(&text, at.index(text.len() + 1));
        let mutated = format!("{}{junk}{}", &text[..at], &text[at..]);
        check(&origin, &mutated)?;
    }
}

/// Values that once overflowed or exhausted memory, and what the scene
/// says about them.
#[test]
fn huge_blocks_are_errors_naming_the_body() {
    let text = crate::scenes::STACKED_CANTILEVER;
    for (from, to, field) in [
        (
            "nx = 7\nny = 1\n\n[[body]]\nname = \"slave\"",
            "nx = 4294967296\nny = 4294967296\n\n[[body]]\nname = \"slave\"",
            "body[0]",
        ),
        (
            "nx = 7\nny = 1\n\n[[fix]]",
            "nx = 100000\nny = 100000\n\n[[fix]]",
            "body[1]",
        ),
    ] {
        assert!(text.contains(from));
        let msg = Scene::from_toml_str(&text.replace(from, to), "huge.toml")
            .unwrap_err()
            .to_string();
        assert!(
            msg.starts_with(&format!("huge.toml: {field}: more than")),
            "{msg}"
        );
    }
    let refined = format!("{text}\n[refine]\nx = 9223372036854775807\n");
    let msg = Scene::from_toml_str(&refined, "huge.toml")
        .unwrap_err()
        .to_string();
    assert!(msg.starts_with("huge.toml: body[0]: more than"), "{msg}");
    let far = text.replace(
        "origin = [0.0, 0.0]\nsize = [7.0, 0.5]",
        "origin = [1e308, 0.0]\nsize = [1.7e308, 0.5]",
    );
    let msg = Scene::from_toml_str(&far, "huge.toml")
        .unwrap_err()
        .to_string();
    assert!(
        msg.starts_with("huge.toml: body[0].size: the far corner"),
        "{msg}"
    );
}
