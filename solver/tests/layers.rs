//! The solver's module graph points one way: the layer order written in
//! `docs/architecture.md` ("The solver's layers") is checked here against
//! the imports of `solver/src`.
//!
//! The modules are read from the source with `syn`, following the `mod`
//! declarations from `lib.rs` (items under `#[cfg(test)]` are left out: a
//! test may solve a scene to check a lower module). Every path that starts
//! at `crate::`, `super::` or `self::` (in `use` declarations and in code,
//! macro bodies included) is resolved to the module that defines its item,
//! through re-exports (`crate::Method` is `options`). Between two modules
//! that are not one inside the other, that is an edge from the importing
//! module's branch to the imported one's, taken below their common
//! ancestor. The checks:
//!
//! * between top-level modules, every edge goes to the same or a lower
//!   layer of the written order, and every top-level module is in it
//!   exactly once;
//! * the edges among the children of every module (the top level
//!   included) have no cycle;
//! * nothing outside `lib.rs` imports an item defined in the crate root.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use proc_macro2::{Delimiter, TokenStream, TokenTree};
use syn::{Attribute, Item, UseTree};

/// A module's path from the crate root (`[]` is the root).
type ModPath = Vec<String>;

/// Edges the check accepts while the import behind them is being removed
/// (`docs/architecture.md`, "The solver's layers"): (from, to,
/// what is imported), as module paths joined by `::`. Each must still
/// exist: the test fails when one is no longer needed, so the list only
/// shrinks.
const KNOWN: &[(&str, &str, &str)] = &[];

/// One module of the crate, test items removed.
struct Module {
    file: PathBuf,
    children: BTreeSet<String>,
    /// Names bound by its `use` declarations, to the absolute path they
    /// import (`None`: an external crate's item).
    bindings: BTreeMap<String, Option<Vec<String>>>,
    /// Its items, for the references.
    items: Vec<Item>,
}

/// Whether `attrs` compile their item for tests only (`#[cfg(test)]`,
/// also inside `all(..)`, not under `not(..)`).
fn is_test(attrs: &[Attribute]) -> bool {
    attrs.iter().any(|a| {
        let meta = quote::ToTokens::to_token_stream(&a.meta).to_string();
        a.path().is_ident("cfg") && meta.contains("test") && !meta.contains("not")
    })
}

/// The directory a module's `mod x;` files live in.
fn child_dir(file: &Path) -> PathBuf {
    let dir = file.parent().unwrap().to_path_buf();
    match file.file_name().unwrap().to_str().unwrap() {
        "lib.rs" | "mod.rs" => dir,
        name => dir.join(name.trim_end_matches(".rs")),
    }
}

/// Reads the module at `path` (its items `items`, declared in `file`,
/// children's files under `dir`) and its descendants into `modules`.
fn load(
    modules: &mut BTreeMap<ModPath, Module>,
    path: ModPath,
    file: &Path,
    dir: &Path,
    items: Vec<Item>,
) {
    let items: Vec<Item> = items
        .into_iter()
        .filter(|item| !is_test(item_attrs(item)))
        .collect();
    let mut children = BTreeSet::new();
    for item in &items {
        if let Item::Mod(m) = item {
            let name = m.ident.to_string();
            children.insert(name.clone());
            let mut child = path.clone();
            child.push(name.clone());
            match &m.content {
                Some((_, inner)) => load(modules, child, file, &dir.join(&name), inner.clone()),
                None => {
                    let flat = dir.join(format!("{name}.rs"));
                    let nested = dir.join(&name).join("mod.rs");
                    let f = if flat.exists() { flat } else { nested };
                    let text = std::fs::read_to_string(&f)
                        .unwrap_or_else(|e| panic!("{}: {e}", f.display()));
                    let parsed =
                        syn::parse_file(&text).unwrap_or_else(|e| panic!("{}: {e}", f.display()));
                    let d = child_dir(&f);
                    load(modules, child, &f, &d, parsed.items);
                }
            }
        }
    }
    let mut bindings = BTreeMap::new();
    for item in &items {
        if let Item::Use(u) = item {
            let mut found = Vec::new();
            use_bindings(&u.tree, Vec::new(), &mut found);
            for (name, relative) in found {
                bindings.insert(name, absolute(&path, &children, &relative));
            }
        }
    }
    modules.insert(
        path,
        Module {
            file: file.to_path_buf(),
            children,
            bindings,
            items,
        },
    );
}

fn item_attrs(item: &Item) -> &[Attribute] {
    match item {
        Item::Const(i) => &i.attrs,
        Item::Enum(i) => &i.attrs,
        Item::ExternCrate(i) => &i.attrs,
        Item::Fn(i) => &i.attrs,
        Item::ForeignMod(i) => &i.attrs,
        Item::Impl(i) => &i.attrs,
        Item::Macro(i) => &i.attrs,
        Item::Mod(i) => &i.attrs,
        Item::Static(i) => &i.attrs,
        Item::Struct(i) => &i.attrs,
        Item::Trait(i) => &i.attrs,
        Item::TraitAlias(i) => &i.attrs,
        Item::Type(i) => &i.attrs,
        Item::Union(i) => &i.attrs,
        Item::Use(i) => &i.attrs,
        _ => &[],
    }
}

/// The names a use tree binds, with the path each imports (as written).
fn use_bindings(tree: &UseTree, prefix: Vec<String>, out: &mut Vec<(String, Vec<String>)>) {
    match tree {
        UseTree::Path(p) => {
            let mut next = prefix;
            next.push(p.ident.to_string());
            use_bindings(&p.tree, next, out);
        }
        UseTree::Name(n) if n.ident == "self" => {
            if let Some(last) = prefix.last() {
                out.push((last.clone(), prefix.clone()));
            }
        }
        UseTree::Name(n) => {
            let mut full = prefix;
            full.push(n.ident.to_string());
            out.push((n.ident.to_string(), full));
        }
        UseTree::Rename(r) => {
            let mut full = prefix;
            full.push(r.ident.to_string());
            out.push((r.rename.to_string(), full));
        }
        UseTree::Glob(_) => {}
        UseTree::Group(g) => {
            for t in &g.items {
                use_bindings(t, prefix.clone(), out);
            }
        }
    }
}

/// `relative`, written in module `at` (with children `children`), from the
/// crate root; `None` for an external crate's path.
fn absolute(
    at: &[String],
    children: &BTreeSet<String>,
    relative: &[String],
) -> Option<Vec<String>> {
    let first = relative.first()?;
    let mut base: Vec<String> = match first.as_str() {
        "crate" => Vec::new(),
        "self" => at.to_vec(),
        "super" => at[..at.len().saturating_sub(1)].to_vec(),
        name if children.contains(name) => {
            let mut p = at.to_vec();
            p.push(name.to_owned());
            p.extend(relative[1..].iter().cloned());
            return Some(p);
        }
        _ => return None,
    };
    let mut rest = &relative[1..];
    while rest.first().is_some_and(|s| s == "super") {
        base.pop();
        rest = &rest[1..];
    }
    base.extend(rest.iter().cloned());
    Some(base)
}

/// The module that defines what `path` (from the crate root) names;
/// `None` for an external item.
fn resolve(modules: &BTreeMap<ModPath, Module>, path: &[String], depth: usize) -> Option<ModPath> {
    assert!(depth < 16, "re-exports loop at {path:?}");
    let mut module: ModPath = Vec::new();
    for (k, seg) in path.iter().enumerate() {
        let m = &modules[&module];
        if m.children.contains(seg) {
            module.push(seg.clone());
            continue;
        }
        return match m.bindings.get(seg) {
            Some(Some(target)) => {
                let mut full = target.clone();
                full.extend(path[k + 1..].iter().cloned());
                resolve(modules, &full, depth + 1)
            }
            Some(None) => None,
            None => Some(module),
        };
    }
    Some(module)
}

/// Every path in `tokens` that starts at `crate`, `super` or `self` and
/// continues with `::`, as written (groups `{a::B, c}` expanded).
fn token_paths(tokens: TokenStream, out: &mut Vec<Vec<String>>) {
    let tts: Vec<TokenTree> = tokens.into_iter().collect();
    let mut i = 0;
    while i < tts.len() {
        let starts = matches!(&tts[i], TokenTree::Ident(id)
            if id == "crate" || id == "super" || id == "self")
            && is_path_sep(&tts, i + 1);
        // `$crate` and `x.self` do not occur; a path after `::` is not a start
        let after_sep = i >= 2 && is_path_sep(&tts, i - 2);
        if starts && !after_sep {
            let mut prefix = vec![tts[i].to_string()];
            i = continue_path(&tts, i + 1, &mut prefix, out);
        } else {
            if let TokenTree::Group(g) = &tts[i] {
                token_paths(g.stream(), out);
            }
            i += 1;
        }
    }
}

fn is_path_sep(tts: &[TokenTree], i: usize) -> bool {
    matches!((tts.get(i), tts.get(i + 1)),
        (Some(TokenTree::Punct(a)), Some(TokenTree::Punct(b)))
            if a.as_char() == ':' && b.as_char() == ':')
}

/// Extends `prefix` from `tts[i]` (at a `::`) and records the path(s);
/// returns the index after them.
fn continue_path(
    tts: &[TokenTree],
    mut i: usize,
    prefix: &mut Vec<String>,
    out: &mut Vec<Vec<String>>,
) -> usize {
    while is_path_sep(tts, i) {
        match tts.get(i + 2) {
            Some(TokenTree::Ident(id)) => {
                prefix.push(id.to_string());
                i += 3;
            }
            Some(TokenTree::Group(g)) if g.delimiter() == Delimiter::Brace => {
                let inner: Vec<TokenTree> = g.stream().into_iter().collect();
                for part in inner.split(|t| matches!(t, TokenTree::Punct(p) if p.as_char() == ','))
                {
                    if let Some(TokenTree::Ident(first)) = part.first() {
                        let mut p = prefix.clone();
                        if first != "self" {
                            p.push(first.to_string());
                        }
                        continue_path(part, 1, &mut p, out);
                    }
                }
                return i + 3;
            }
            // `::*`, `::<T>`
            _ => break,
        }
    }
    out.push(prefix.clone());
    i
}

fn join(path: &[String]) -> String {
    if path.is_empty() {
        "crate".to_owned()
    } else {
        path.join("::")
    }
}

/// One import between two modules.
struct Edge {
    from: ModPath,
    to: ModPath,
    file: PathBuf,
    written: String,
}

/// The layers of `docs/architecture.md`, top first: the list between
/// `<!-- layers -->` and `<!-- /layers -->`, one numbered line per layer,
/// its modules the backticked names before the first `:`.
fn written_layers(doc: &str) -> Vec<Vec<String>> {
    let start = doc
        .find("<!-- layers -->")
        .expect("docs/architecture.md: no <!-- layers -->");
    let end = doc
        .find("<!-- /layers -->")
        .expect("docs/architecture.md: no <!-- /layers -->");
    doc[start..end]
        .lines()
        .filter(|l| {
            l.trim_start()
                .chars()
                .next()
                .is_some_and(|c| c.is_ascii_digit())
        })
        .map(|l| {
            let names = l.split(':').next().unwrap();
            names
                .split('`')
                .skip(1)
                .step_by(2)
                .map(str::to_owned)
                .collect()
        })
        .collect()
}

/// The cycles among `nodes` under `edges` (one per strongly connected
/// component of more than one node), each as its nodes.
fn cycles(edges: &BTreeSet<(String, String)>) -> Vec<Vec<String>> {
    let nodes: BTreeSet<&String> = edges.iter().flat_map(|(a, b)| [a, b]).collect();
    let reach = |from: &String| -> BTreeSet<String> {
        let mut seen = BTreeSet::new();
        let mut stack = vec![from.clone()];
        while let Some(n) = stack.pop() {
            for (a, b) in edges {
                if *a == n && seen.insert(b.clone()) {
                    stack.push(b.clone());
                }
            }
        }
        seen
    };
    let mut found: Vec<Vec<String>> = Vec::new();
    for n in nodes {
        let from_n = reach(n);
        if !from_n.contains(n) || found.iter().any(|c| c.contains(n)) {
            continue;
        }
        let component: Vec<String> = from_n
            .into_iter()
            .filter(|m| reach(m).contains(n))
            .collect();
        found.push(component);
    }
    found
}

/// The problems of the crate whose `lib.rs` is `lib`, against the layers
/// written in `doc` and the edges `known` accepts.
fn check(lib: &Path, doc: &str, known: &[(&str, &str, &str)]) -> Vec<String> {
    let root = lib.parent().unwrap().parent().unwrap();
    let text = std::fs::read_to_string(lib).unwrap();
    let mut modules = BTreeMap::new();
    let dir = child_dir(lib);
    load(
        &mut modules,
        Vec::new(),
        lib,
        &dir,
        syn::parse_file(&text).unwrap().items,
    );

    let mut edges = Vec::new();
    for (path, module) in &modules {
        let mut written = Vec::new();
        for item in &module.items {
            // a child module's own items are its own module's
            if let Item::Mod(m) = item
                && m.content.is_some()
            {
                continue;
            }
            token_paths(quote::ToTokens::to_token_stream(item), &mut written);
        }
        for w in written {
            let Some(abs) = absolute(path, &module.children, &w) else {
                continue;
            };
            let Some(to) = resolve(&modules, &abs, 0) else {
                continue;
            };
            edges.push(Edge {
                from: path.clone(),
                to,
                file: module.file.clone(),
                written: w.join("::"),
            });
        }
    }

    let layers = written_layers(doc);
    let mut layer_of: BTreeMap<String, usize> = BTreeMap::new();
    let mut problems = Vec::new();
    // top first in the document: layer numbers count from the bottom
    for (k, names) in layers.iter().enumerate() {
        for name in names {
            if layer_of.insert(name.clone(), layers.len() - k).is_some() {
                problems.push(format!("`{name}` is in two layers of docs/architecture.md"));
            }
        }
    }
    let top: &BTreeSet<String> = &modules[&Vec::new()].children;
    for name in top {
        if !layer_of.contains_key(name) {
            problems.push(format!(
                "module `{name}` is in no layer of docs/architecture.md (\"The solver's layers\")"
            ));
        }
    }
    for name in layer_of.keys() {
        if !top.contains(name) {
            problems.push(format!(
                "docs/architecture.md's layers name `{name}`, which is no module of the solver"
            ));
        }
    }

    let known: BTreeSet<(String, String)> = known
        .iter()
        .map(|(a, b, _)| (a.to_string(), b.to_string()))
        .collect();
    let mut used_known = BTreeSet::new();
    // sibling edges, grouped by their parent
    let mut siblings: BTreeMap<ModPath, BTreeSet<(String, String)>> = BTreeMap::new();
    for e in &edges {
        let from = &e.from;
        let to = &e.to;
        let where_ = format!(
            "{}: `{}`",
            e.file.strip_prefix(root).unwrap_or(&e.file).display(),
            e.written
        );
        if to.is_empty() && !from.is_empty() {
            problems.push(format!(
                "{where_}: `{}` imports an item of the crate root",
                join(from)
            ));
            continue;
        }
        let common = from.iter().zip(to).take_while(|(a, b)| a == b).count();
        if common == from.len() || common == to.len() {
            continue;
        }
        let parent = from[..common].to_vec();
        let (a, b) = (&from[common], &to[common]);
        let mut pa = parent.clone();
        pa.push(a.clone());
        let mut pb = parent.clone();
        pb.push(b.clone());
        let pair = (join(&pa), join(&pb));
        if std::env::var("DEBUG_EDGES").is_ok() {
            eprintln!("EDGE {} -> {}   ({where_})", pair.0, pair.1);
        }
        if known.contains(&pair) {
            used_known.insert(pair);
            continue;
        }
        if parent.is_empty()
            && let (Some(&la), Some(&lb)) = (layer_of.get(a), layer_of.get(b))
            && la < lb
        {
            problems.push(format!(
                "{where_}: `{a}` (layer {la}) imports `{b}` (layer {lb}), a higher layer"
            ));
        }
        siblings
            .entry(parent)
            .or_default()
            .insert((a.clone(), b.clone()));
    }
    for (parent, edges) in &siblings {
        for cycle in cycles(edges) {
            let names: Vec<String> = cycle
                .iter()
                .map(|c| {
                    let mut p = parent.clone();
                    p.push(c.clone());
                    join(&p)
                })
                .collect();
            problems.push(format!("import cycle among {}", names.join(", ")));
        }
    }
    for pair in &known {
        if !used_known.contains(pair) {
            problems.push(format!(
                "the known edge {} -> {} is gone: remove it from KNOWN in solver/tests/layers.rs",
                pair.0, pair.1
            ));
        }
    }
    problems
}

#[test]
fn the_module_graph_follows_the_written_layers() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let doc = std::fs::read_to_string(root.join("../docs/architecture.md")).unwrap();
    let problems = check(&root.join("src/lib.rs"), &doc, KNOWN);
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// A crate written to a scratch directory: `files` are (path under
/// `src/`, contents).
fn scratch_crate(name: &str, files: &[(&str, &str)]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("gapsim-layers-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    for (path, text) in files {
        let file = dir.join("src").join(path);
        std::fs::create_dir_all(file.parent().unwrap()).unwrap();
        std::fs::write(file, text).unwrap();
    }
    dir.join("src/lib.rs")
}

const TWO_LAYERS: &str =
    "<!-- layers -->\n1. `high`: above\n2. `low`, `base`: below\n<!-- /layers -->\n";

/// The checker finds what it is for, on small crates: a clean one passes;
/// an upward import, a cycle among the children of a module, an import
/// from the crate root, a module in no layer and a stale known edge are
/// each reported; test items do not count.
#[test]
fn the_checker_finds_each_kind_of_problem() {
    let clean = scratch_crate(
        "clean",
        &[
            (
                "lib.rs",
                "pub mod high; pub mod low; mod base; pub use low::Low;",
            ),
            ("high.rs", "use crate::Low; pub fn f(_: Low) {}"),
            (
                "low/mod.rs",
                "mod a; mod b; pub use a::Low; #[cfg(test)] mod tests { use crate::high::f; }",
            ),
            ("low/a.rs", "pub struct Low; fn g() { super::b::h() }"),
            ("low/b.rs", "pub fn h() { let _ = crate::base::B; }"),
            ("base.rs", "pub struct B;"),
        ],
    );
    assert_eq!(check(&clean, TWO_LAYERS, &[]), Vec::<String>::new());

    let bad = scratch_crate(
        "bad",
        &[
            (
                "lib.rs",
                "pub mod high; pub mod low; mod base; mod extra; pub fn top() {}",
            ),
            ("high.rs", "pub struct H;"),
            (
                "low/mod.rs",
                "mod a; mod b; pub fn l() { let _ = crate::high::H; }",
            ),
            ("low/a.rs", "use super::b::B; pub struct A;"),
            (
                "low/b.rs",
                "pub struct B; fn g() -> super::a::A { crate::top(); super::a::A }",
            ),
            ("base.rs", ""),
            ("extra.rs", ""),
        ],
    );
    let problems = check(&bad, TWO_LAYERS, &[("base", "high", "gone")]);
    let expect = [
        "module `extra` is in no layer",
        "`low::b` imports an item of the crate root",
        "`low` (layer 1) imports `high` (layer 2), a higher layer",
        "import cycle among low::a, low::b",
        "the known edge base -> high is gone",
    ];
    assert_eq!(problems.len(), expect.len(), "{problems:#?}");
    for e in expect {
        assert!(problems.iter().any(|p| p.contains(e)), "{e}: {problems:#?}");
    }
    for lib in [clean, bad] {
        std::fs::remove_dir_all(lib.parent().unwrap().parent().unwrap()).unwrap();
    }
}

#[test]
fn paths_are_read_from_code_and_groups() {
    let item: TokenStream =
        "use crate::{a::B, c::{self, d::E}}; fn f() { super::g::h(); x.self_(); crate::K }"
            .parse()
            .unwrap();
    let mut out = Vec::new();
    token_paths(item, &mut out);
    let out: Vec<String> = out.iter().map(|p| p.join("::")).collect();
    assert_eq!(
        out,
        [
            "crate::a::B",
            "crate::c",
            "crate::c::d::E",
            "super::g::h",
            "crate::K"
        ]
    );
}
