//! `docs/scenes.md`, the scene format's reference, is kept true by these
//! tests: every TOML example in it is read, built, written back and solved;
//! and every key of the format (every field of every table the parser
//! knows, found by asking the parser itself) has a row in the table of its
//! section, every row names a real key, and every value a string key takes
//! is named in its section. A third test reads a scene that leaves out
//! every optional key and holds the page's default column to what the
//! parser filled in.
//!
//! The keys are found through the scene parser's own errors: every table
//! of the schema refuses unknown keys, and serde's refusal lists the keys
//! the table has ("unknown field `zz_probe`, expected one of `a`, `b`"). A
//! key whose value is a table (or an array of tables) answers the same way
//! one level down, and a key whose value is a fixed set of strings lists
//! them ("unknown variant"). So a key added to `solver/src/scene/spec/`
//! (or to a type it holds, such as the material) fails here until the page
//! describes it.

use std::path::{Path, PathBuf};

use solver::contact::face_rules::default_points;
use solver::element::FaceKind;
use solver::scene::Dimension;
use solver::{Formulation, LinearSolverKind, Scene, SceneError, SolveOptions, solve, solve_model};

/// The page, and the path its examples are read as (so that a `[mesh] file`
/// in an example is relative to `docs/`).
fn page() -> (String, PathBuf) {
    let docs = Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs");
    let path = docs.join("scenes.md");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    (text, path)
}

/// The contents of every ```` ```toml ```` block of `text`, with the line
/// each starts on.
fn toml_blocks(text: &str) -> Vec<(usize, String)> {
    let mut blocks = Vec::new();
    let mut current: Option<(usize, String)> = None;
    for (n, line) in text.lines().enumerate() {
        match &mut current {
            None if line.trim_end() == "```toml" => current = Some((n + 2, String::new())),
            None => {}
            Some(_) if line.trim_end() == "```" => blocks.extend(current.take()),
            Some((_, body)) => {
                body.push_str(line);
                body.push('\n');
            }
        }
    }
    assert!(current.is_none(), "an unclosed ```toml block");
    blocks
}

#[test]
fn every_example_parses_builds_and_runs() {
    let (text, path) = page();
    let blocks = toml_blocks(&text);
    assert_eq!(
        blocks.len(),
        text.matches("```toml").count(),
        "every ```toml block is read"
    );
    assert!(blocks.len() >= 6, "{} examples", blocks.len());
    let origin = path.display().to_string();
    for (line, example) in &blocks {
        let at = format!("docs/scenes.md, the example at line {line}");
        let scene = Scene::from_toml_str(example, &origin).unwrap_or_else(|e| panic!("{at}: {e}"));
        // written back, it reads as the same scene
        let again = Scene::from_toml_str(&scene.to_toml_string(), &origin)
            .unwrap_or_else(|e| panic!("{at}: written back: {e}"));
        assert_eq!(again, scene, "{at}: written back");
        let options = SolveOptions::from_scene(&scene);
        let (load_factor, energy) = match scene.dimension().unwrap_or_else(|e| panic!("{at}: {e}"))
        {
            Dimension::Two => {
                let model = scene
                    .build_model::<2>()
                    .unwrap_or_else(|e| panic!("{at}: {e}"));
                assert!(model.mesh.node_count() > 0, "{at}");
                let s = solve::<2>(&scene, &options).unwrap_or_else(|e| panic!("{at}: {e}"));
                (s.load_factor, s.strain_energy)
            }
            Dimension::Three => {
                let model = scene
                    .build_model::<3>()
                    .unwrap_or_else(|e| panic!("{at}: {e}"));
                assert!(model.mesh.node_count() > 0, "{at}");
                let s = solve_model(&model, &options).unwrap_or_else(|e| panic!("{at}: {e}"));
                (s.load_factor, s.strain_energy)
            }
        };
        assert_eq!(load_factor, scene.loading.load_factor_end, "{at}");
        assert!(
            energy.is_finite() && energy > 0.0,
            "{at}: strain energy {energy}"
        );
    }
}

/// A key on the way to a table: its name and whether its value is an array
/// of tables.
#[derive(Debug, Clone)]
struct Step {
    key: String,
    array: bool,
}

const PROBE: &str = "zz_probe";

/// A scene document whose only content is `inner` inside the table at
/// `path` (inline tables, each array with one element).
fn document(path: &[Step], inner: &str) -> String {
    let mut content = inner.to_owned();
    for step in path.iter().rev() {
        let table = format!("{{ {content} }}");
        let value = if step.array {
            format!("[{table}]")
        } else {
            table
        };
        content = format!("{} = {value}", step.key);
    }
    content
}

/// The parser's message on `doc`, if it is a TOML-level error.
fn syntax_message(doc: &str) -> Option<String> {
    match Scene::from_toml_str(doc, "probe.toml") {
        Err(SceneError::Syntax { message, .. }) => Some(message),
        _ => None,
    }
}

/// The names in backticks after "expected" in serde's message.
fn expected_names(message: &str) -> Vec<String> {
    let Some((_, list)) = message.split_once("expected") else {
        return Vec::new();
    };
    list.split('`')
        .skip(1)
        .step_by(2)
        .map(str::to_owned)
        .collect()
}

/// The keys of the table at `path`, if there is a table there.
fn table_keys(path: &[Step]) -> Option<Vec<String>> {
    let message = syntax_message(&document(path, &format!("{PROBE} = 1")))?;
    message
        .starts_with(&format!("unknown field `{PROBE}`"))
        .then(|| expected_names(&message))
}

/// The strings the key `key` of the table at `path` takes, if it takes a
/// fixed set.
fn variants(path: &[Step], key: &str) -> Option<Vec<String>> {
    let message = syntax_message(&document(path, &format!("{key} = \"{PROBE}\"")))?;
    message
        .starts_with(&format!("unknown variant `{PROBE}`"))
        .then(|| expected_names(&message))
}

/// One table of the schema: where it is, its keys and the fixed strings
/// its keys take.
#[derive(Debug)]
struct Table {
    path: Vec<Step>,
    keys: Vec<String>,
    variants: Vec<(String, Vec<String>)>,
}

/// Every table of the schema under `path` (`path`'s own first).
fn walk(path: Vec<Step>, out: &mut Vec<Table>) {
    let keys = table_keys(&path).unwrap_or_else(|| panic!("no table at {path:?}"));
    let mut below = Vec::new();
    let mut fixed = Vec::new();
    for key in &keys {
        let nested = [false, true].into_iter().find_map(|array| {
            let mut p = path.clone();
            p.push(Step {
                key: key.clone(),
                array,
            });
            table_keys(&p).map(|_| p)
        });
        match nested {
            Some(p) => below.push(p),
            None => {
                if let Some(v) = variants(&path, key) {
                    fixed.push((key.clone(), v));
                }
            }
        }
    }
    out.push(Table {
        path,
        keys,
        variants: fixed,
    });
    for p in below {
        walk(p, out);
    }
}

/// The text a section heading names a table by: `Top-level keys`,
/// `` `[loading]` ``, `` `[[body]]` ``, `` `[[contact]] slave` ``.
fn needle(path: &[Step]) -> String {
    match path.split_first() {
        None => "Top-level keys".to_owned(),
        Some((first, rest)) => {
            let head = if first.array {
                format!("[[{}]]", first.key)
            } else {
                format!("[{}]", first.key)
            };
            let tail: Vec<&str> = rest.iter().map(|s| s.key.as_str()).collect();
            if tail.is_empty() {
                format!("`{head}`")
            } else {
                format!("`{head} {}`", tail.join("."))
            }
        }
    }
}

/// The text of the section whose heading contains `needle`, up to the next
/// heading (of any level).
fn section<'t>(text: &'t str, needle: &str) -> Option<&'t str> {
    let mut start = None;
    let mut offset = 0;
    for line in text.split_inclusive('\n') {
        let heading = line.starts_with('#');
        match start {
            None if heading && line.contains(needle) => start = Some(offset + line.len()),
            Some(s) if heading => return Some(&text[s..offset]),
            _ => {}
        }
        offset += line.len();
    }
    start.map(|s| &text[s..])
}

/// The keys of the table rows `| `key` | ...` of a section.
fn rows(section: &str) -> Vec<String> {
    section
        .lines()
        .filter_map(|l| l.strip_prefix("| `")?.split_once("` |").map(|(k, _)| k))
        .filter(|k| !k.is_empty() && k.bytes().all(|b| b.is_ascii_lowercase() || b == b'_'))
        .map(str::to_owned)
        .collect()
}

#[test]
fn every_key_of_the_format_is_documented() {
    let (text, _) = page();
    let mut tables = Vec::new();
    walk(Vec::new(), &mut tables);
    // the probe reaches what the format is known to have (so that it cannot
    // pass by finding nothing)
    let names: Vec<String> = tables.iter().map(|t| needle(&t.path)).collect();
    for known in [
        "Top-level keys",
        "`[material]`",
        "`[[body]]`",
        "`[[body]] material`",
        "`[[contact]] slave`",
        "`[[contact]] master`",
        "`[newton]`",
    ] {
        assert!(names.iter().any(|n| n == known), "{known} not in {names:?}");
    }
    let side = tables
        .iter()
        .find(|t| needle(&t.path) == "`[[contact]] slave`")
        .and_then(|t| t.variants.iter().find(|(k, _)| k == "side"));
    assert_eq!(
        side.map(|(_, v)| v.clone()),
        Some(
            ["bottom", "right", "top", "left", "front", "back"]
                .map(String::from)
                .to_vec()
        )
    );

    let mut missing = Vec::new();
    for table in &tables {
        let n = needle(&table.path);
        let Some(sec) = section(&text, &n) else {
            missing.push(format!("no section whose heading names {n}"));
            continue;
        };
        let documented = rows(sec);
        for key in &table.keys {
            if !documented.contains(key) {
                missing.push(format!("{n}: no row for `{key}`"));
            }
        }
        for key in &documented {
            if !table.keys.contains(key) {
                missing.push(format!("{n}: a row for `{key}`, which is no key of it"));
            }
        }
        for (key, values) in &table.variants {
            for v in values {
                if !sec.contains(&format!("\"{v}\"")) {
                    missing.push(format!("{n}: `{key}` takes \"{v}\", not named"));
                }
            }
        }
    }
    // strings parsed by hand rather than by serde
    let mut named = |n: &str, values: Vec<String>| {
        let sec = section(&text, n).unwrap_or_default();
        for v in values {
            if !sec.contains(&v) {
                missing.push(format!("{n}: {v} not named"));
            }
        }
    };
    named(
        "`[[contact]]`",
        Formulation::ALL
            .iter()
            .map(|f| format!("\"{}\"", f.name()))
            .collect(),
    );
    named(
        "`[newton]`",
        LinearSolverKind::ALL
            .iter()
            .map(|k| format!("\"{k}\""))
            .collect(),
    );
    named(
        "`[loading]`",
        std::iter::once("\"complete\"".to_owned())
            .chain((1..=6).map(|k| format!("`{k}`")))
            .collect(),
    );
    assert!(
        missing.is_empty(),
        "docs/scenes.md:\n{}",
        missing.join("\n")
    );
}

/// A string value as the page writes it, `` `"name"` ``, from its
/// serialised form (the name a scene file gives it).
fn quoted<T: serde::Serialize>(value: &T) -> String {
    match toml::Value::try_from(value) {
        Ok(toml::Value::String(s)) => format!("`\"{s}\"`"),
        other => panic!("not a string: {other:?}"),
    }
}

/// The default cell of the row for `key` in the section named `needle`.
fn default_cell(text: &str, needle: &str, key: &str) -> String {
    let sec = section(text, needle).unwrap_or_else(|| panic!("no section {needle}"));
    let row = sec
        .lines()
        .find(|l| l.starts_with(&format!("| `{key}` |")))
        .unwrap_or_else(|| panic!("{needle}: no row for `{key}`"));
    row.split('|').nth(3).unwrap_or_default().trim().to_owned()
}

/// The page's defaults are the parser's: a scene that leaves out every key
/// with a default is read, and each value it gets is what the row's
/// default column says.
#[test]
fn the_documented_defaults_are_the_parsers() {
    let (text, _) = page();
    let scene = Scene::from_toml_str(
        r#"
[material]
young = 1.0
poisson = 0.0
[[body]]
name = "a"
origin = [0.0, 0.0]
size = [1.0, 1.0]
nx = 1
ny = 1
[[body]]
name = "b"
origin = [0.0, 1.0]
size = [1.0, 1.0]
nx = 1
ny = 1
[[fix]]
y = 0.0
[[contact]]
slave = { body = "b", side = "bottom" }
master = { body = "a", side = "top" }
[loading]
load_factor_end = 1.0
steps = [3, 5]
"#,
        "defaults.toml",
    )
    .unwrap();
    let material = scene.material.unwrap().material();
    let contact = &scene.contacts[0];
    // absent `gauss_points` is the face kind's default: the 2D pair's
    // count, and face_rules' for the 3D faces
    assert_eq!(contact.gauss_points, None);
    // the model keeps it absent; the layout takes the segment's default
    assert_eq!(
        scene.build_model::<2>().unwrap().contacts[0].gauss_points,
        None
    );
    let segment = default_points(FaceKind::Segment);
    let (quad4, tri3) = (
        default_points(FaceKind::Quad4),
        default_points(FaceKind::Tri3),
    );
    let gauss_points_default =
        format!("{segment} on a segment, {quad4} x {quad4} on a quad4, {tri3} on a tri3");
    let n = &scene.newton;
    let cases: Vec<(&str, &str, String)> = vec![
        ("`[material]`", "model", quoted(&material.model)),
        ("`[material]`", "kinematics", quoted(&material.kinematics)),
        ("`[[fix]]`", "dofs", "every component".to_owned()),
        (
            "`[[contact]]`",
            "formulation",
            format!("`\"{}\"`", contact.formulation),
        ),
        ("`[[contact]]`", "mode", quoted(&contact.mode)),
        ("`[[contact]]`", "integration", quoted(&contact.integration)),
        ("`[[contact]]`", "multipliers", quoted(&contact.multipliers)),
        ("`[[contact]]`", "gauss_points", gauss_points_default),
        (
            "`[loading]`",
            "method",
            format!("`\"{}\"`", scene.loading.method),
        ),
        ("`[refine]`", "x", scene.refine.x.to_string()),
        ("`[refine]`", "y", scene.refine.y.to_string()),
        ("`[newton]`", "tolerance", format!("`{:e}`", n.tolerance)),
        ("`[newton]`", "max_iterations", n.max_iterations.to_string()),
        ("`[newton]`", "max_cutbacks", n.max_cutbacks.to_string()),
        ("`[newton]`", "linear", format!("`\"{}\"`", n.linear)),
        ("`[newton]`", "repair", format!("`{}`", n.repair)),
    ];
    let mut wrong = Vec::new();
    for (needle, key, value) in cases {
        let cell = default_cell(&text, needle, key);
        if cell != value {
            wrong.push(format!(
                "{needle} `{key}`: the page says {cell}, the parser gives {value}"
            ));
        }
    }
    // `default_steps` is the first of `steps`, `taylor_tolerance` none
    assert_eq!(scene.default_steps(), 3);
    assert_eq!(
        default_cell(&text, "`[loading]`", "default_steps"),
        "the first of `steps`"
    );
    assert_eq!(n.taylor_tolerance, None);
    assert_eq!(
        default_cell(&text, "`[newton]`", "taylor_tolerance"),
        "none"
    );
    assert!(wrong.is_empty(), "docs/scenes.md:\n{}", wrong.join("\n"));
}
