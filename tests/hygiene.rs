//! Boundary guards (STYLE 17, after rapier's grep deny-list): the web crates appear only in
//! the wasm boundary module `src/web/` (one file per page: playground, lab, tuner); no clock or unseeded generator in the core (the bench in `src/bin/` may time);
//! no `unwrap()` in shipped code. Files are scanned as text, comments and `#[cfg(test)]` modules
//! left out, so a doc line that *names* a banned call is not a violation.

use std::path::{Path, PathBuf};

/// Words that tie code to the browser: only the wasm boundary may name them.
const WEB_ONLY: &[&str] = &["wasm_bindgen", "js_sys", "web_sys"];
/// Clocks and unseeded or non-portable generators: they make runs unreproducible.
const NOT_IN_CORE: &[&str] =
    &["thread_rng", "Instant::now", "SystemTime", "StdRng", "OsRng", "from_entropy", "rand::random"];

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let entries = std::fs::read_dir(dir).unwrap_or_else(|e| panic!("cannot list {}: {e}", dir.display()));
    for entry in entries {
        let path = entry.expect("directory entry").path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// Every `.rs` file under `src/`, as (path relative to the crate, code without comments and
/// test modules).
fn sources() -> Vec<(String, String)> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    rust_files(&root.join("src"), &mut files);
    files.sort();
    assert!(files.len() >= 10, "expected the core's source files under src/, found {}", files.len());
    files
        .into_iter()
        .map(|path| {
            let text = std::fs::read_to_string(&path).expect("source is readable UTF-8");
            let rel = path.strip_prefix(root).expect("under the crate").to_string_lossy().replace('\\', "/");
            (rel, shipped_code(&text))
        })
        .collect()
}

/// The text without `//` comments and without `#[cfg(test)]` items (a braced block after it).
fn shipped_code(text: &str) -> String {
    let mut out = String::new();
    let mut skip_depth: Option<i32> = None;
    let mut pending_cfg_test = false;
    for line in text.lines() {
        let code = strip_line_comment(line);
        let trimmed = code.trim();
        if let Some(depth) = skip_depth.as_mut() {
            *depth += brace_balance(code);
            if *depth <= 0 {
                skip_depth = None;
            }
            continue;
        }
        if trimmed.starts_with("#[cfg(test)]") {
            pending_cfg_test = true;
            continue;
        }
        if pending_cfg_test && !trimmed.is_empty() && !trimmed.starts_with("#[") {
            pending_cfg_test = false;
            let balance = brace_balance(code);
            if balance > 0 {
                skip_depth = Some(balance);
            }
            // A one-line item (`mod tests;`, `use …;`) is skipped with this line.
            continue;
        }
        out.push_str(code);
        out.push('\n');
    }
    out
}

/// The line up to a `//` that is not inside a string literal.
fn strip_line_comment(line: &str) -> &str {
    let mut in_string = false;
    let mut prev = ' ';
    for (i, c) in line.char_indices() {
        match c {
            '"' if prev != '\\' => in_string = !in_string,
            '/' if !in_string && prev == '/' => return &line[..i - 1],
            _ => {}
        }
        prev = c;
    }
    line
}

fn brace_balance(code: &str) -> i32 {
    code.chars().map(|c| i32::from(c == '{') - i32::from(c == '}')).sum()
}

fn offending_lines(code: &str, word: &str) -> Vec<String> {
    code.lines().filter(|l| l.contains(word)).map(|l| l.trim().to_string()).collect()
}

#[test]
fn web_crates_appear_only_in_the_web_module() {
    for (path, code) in sources() {
        if path.starts_with("src/web/") {
            continue;
        }
        for word in WEB_ONLY {
            let hits = offending_lines(&code, word);
            assert!(hits.is_empty(), "{path} names {word} (only src/web/ may): {hits:?}");
        }
    }
}

#[test]
fn no_clock_or_unseeded_generator_outside_the_command_line() {
    for (path, code) in sources() {
        if path.starts_with("src/bin/") {
            continue;
        }
        for word in NOT_IN_CORE {
            let hits = offending_lines(&code, word);
            assert!(
                hits.is_empty(),
                "{path} uses {word}; draw from crate::rng::Rng, keep time fixed: {hits:?}"
            );
        }
    }
}

/// Speed is measured in benchmarks, never in a test: no clock in any test, the core's
/// `#[cfg(test)]` modules and `tests/` included (a timed test fails on a loaded machine and
/// passes on a fast one, and asserts nothing about the code).
#[test]
fn no_clock_in_any_test() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    rust_files(&root.join("src"), &mut files);
    rust_files(&root.join("tests"), &mut files);
    let clocks = ["Instant::now", "SystemTime", ".elapsed()"];
    let mut scanned = 0;
    for path in files {
        let rel = path.strip_prefix(root).expect("under the crate").to_string_lossy().replace('\\', "/");
        // The command line's bench may time (its tests may not); this file names the words.
        if rel == "tests/hygiene.rs" {
            continue;
        }
        let text = std::fs::read_to_string(&path).expect("source is readable UTF-8");
        let code: String = if rel.starts_with("src/bin/") {
            // Only its test modules: the text that shipped_code leaves out.
            let shipped = shipped_code(&text);
            let all: String = text.lines().map(|l| format!("{}\n", strip_line_comment(l))).collect();
            all.lines().filter(|l| !shipped.contains(l)).collect::<Vec<_>>().join("\n")
        } else {
            text.lines().map(|l| format!("{}\n", strip_line_comment(l))).collect()
        };
        for clock in clocks {
            let hits = offending_lines(&code, clock);
            assert!(
                hits.is_empty(),
                "{rel} reads the clock ({clock}) in a test; measure speed in a bench: {hits:?}"
            );
        }
        scanned += 1;
    }
    assert!(scanned >= 40, "expected the test files, scanned {scanned}");
}

/// Entropy enters only as a seed: `getrandom` is named in `src/rng.rs` alone, and
/// `rng::fresh_seed` is called only by the front-ends (`src/web/`, `src/bin/`), never inside a run.
#[test]
fn entropy_enters_only_as_a_fresh_seed_from_a_front_end() {
    for (path, code) in sources() {
        if path != "src/rng.rs" {
            let hits = offending_lines(&code, "getrandom");
            assert!(hits.is_empty(), "{path} names getrandom; use crate::rng::fresh_seed: {hits:?}");
        }
        let front_end = path == "src/rng.rs" || path.starts_with("src/web/") || path.starts_with("src/bin/");
        if !front_end {
            let hits = offending_lines(&code, "fresh_seed");
            assert!(hits.is_empty(), "{path} draws a fresh seed inside the core: {hits:?}");
        }
    }
}

#[test]
fn no_unwrap_in_shipped_code() {
    for (path, code) in sources() {
        let hits = offending_lines(&code, ".unwrap()");
        assert!(hits.is_empty(), "{path} calls unwrap() outside tests; return an error instead: {hits:?}");
    }
}

#[test]
fn the_scanner_sees_through_comments_and_test_modules_only() {
    // Guards the guard: a scanner that dropped everything would pass every test above.
    let text = "fn a() { x.unwrap(); } // y.unwrap()\n\
                /// z.unwrap()\n\
                #[cfg(test)]\n\
                mod tests {\n    fn b() { {w.unwrap();} }\n}\n\
                fn c() { let s = \"http://x\"; v.unwrap(); }\n";
    let code = shipped_code(text);
    assert_eq!(
        offending_lines(&code, ".unwrap()"),
        vec!["fn a() { x.unwrap(); }", "fn c() { let s = \"http://x\"; v.unwrap(); }"]
    );
    let sources = sources();
    assert!(sources.iter().any(|(p, c)| p == "src/sim/world.rs" && c.contains("pub fn step(")));
    assert!(sources.iter().any(|(p, c)| p.starts_with("src/bin/") && c.contains("Instant::now")));
}

/// The layers (top-level modules of `src/`) and the lower ones each may use (DESIGN §2). A
/// layer not listed here, or an import outside its row, fails `layers_import_only_downwards`:
/// the rule is written down once, here.
const LAYERS: &[(&str, &[&str])] = &[
    // A leaf: the one seeded generator every layer draws from.
    ("rng", &[]),
    // A leaf: the one fingerprint of bit patterns (run digests, cache keys).
    ("digest", &[]),
    // A leaf: CSV fields, for every CSV the project writes.
    ("csv", &[]),
    // What users draw and share.
    ("model", &["rng"]),
    // Neighbour queries: the agents' grid, the obstacle index, the flow field.
    ("spatial", &["model", "digest"]),
    // Optimizers on R^d and benchmark functions: a leaf beside the crowd.
    ("optim", &["rng", "digest"]),
    // The Planner trait at the bottom, one planner per file above it; IGSA plans with optim.
    ("planners", &["model", "spatial", "optim", "rng"]),
    // A run: the world's step calls the planners; metrics, recording, replay, comparison.
    ("sim", &["model", "spatial", "planners", "rng", "digest", "csv"]),
    // The papers' tables and validation runs as data.
    ("experiments", &["model", "spatial", "planners", "optim", "sim", "rng"]),
    // The GA over the five force weights.
    ("tune", &["model", "planners", "sim", "rng"]),
    // Pixels.
    ("render", &["model", "spatial", "planners", "sim"]),
    // Files for other tools.
    ("export", &["model", "sim"]),
    // Zips and SCORM packages for an LMS.
    ("package", &["model", "sim"]),
    // wasm32 only: conversion and errors over everything below.
    (
        "web",
        &[
            "model",
            "spatial",
            "planners",
            "optim",
            "sim",
            "experiments",
            "tune",
            "render",
            "export",
            "package",
            "rng",
        ],
    ),
];

/// The module path of a source file: `src/model/params/boids.rs` → `model::params::boids`,
/// `src/sim/mod.rs` → `sim`, `src/lib.rs` → ``.
fn module_of(path: &str) -> Vec<String> {
    let inner = path.trim_start_matches("src/").trim_end_matches(".rs");
    let mut parts: Vec<String> = inner.split('/').map(str::to_string).collect();
    if matches!(parts.last().map(String::as_str), Some("mod" | "lib")) {
        parts.pop();
    }
    parts
}

/// Every module path a file's shipped code names: `crate::a::b…` and `super::…` (resolved against
/// the file's own module), `use` lines and inline paths alike.
fn named_paths(path: &str, code: &str) -> Vec<Vec<String>> {
    let me = module_of(path);
    let mut found = Vec::new();
    for (start, _) in code.match_indices("crate::").chain(code.match_indices("super::")) {
        if start > 0 && code[..start].ends_with(|c: char| c.is_alphanumeric() || c == '_' || c == ':') {
            continue;
        }
        let rest = &code[start..];
        // `a::b::C` ends at the first segment followed by anything but `::`.
        let mut parts: Vec<String> = Vec::new();
        for segment in rest.split("::") {
            let ident: String = segment.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
            let whole = ident.len() == segment.len();
            if !ident.is_empty() {
                parts.push(ident);
            }
            if !whole {
                break;
            }
        }
        let mut base = if parts[0] == "crate" {
            Vec::new()
        } else {
            // `super` of `a/b.rs` (module a::b) is `a`; of `a/mod.rs` (module a), the root.
            let mut b = me.clone();
            b.pop();
            b
        };
        parts.remove(0);
        while parts.first().is_some_and(|p| p == "super") {
            base.pop();
            parts.remove(0);
        }
        if parts.is_empty() && rest.split("::").nth(1).is_some_and(|p| p.starts_with('{')) {
            // `crate::{a, b::c}`: each first name is a module or a root re-export.
            let list = &rest[rest.find('{').map_or(0, |i| i + 1)..rest.find('}').unwrap_or(rest.len())];
            for item in list.split(',') {
                let first: String =
                    item.trim().chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
                if !first.is_empty() {
                    let mut p = base.clone();
                    p.push(first);
                    found.push(p);
                }
            }
            continue;
        }
        base.extend(parts);
        found.push(base);
    }
    // A folder root names its own child modules without a prefix (`pub use boids::Boids;`).
    for line in code.lines() {
        let decl = line.trim().trim_start_matches("pub ").trim_start_matches("pub(crate) ");
        let Some(child) = decl.strip_prefix("mod ").and_then(|d| d.strip_suffix(';')) else { continue };
        let needle = format!("{child}::");
        for (start, _) in code.match_indices(&needle) {
            if start > 0 && code[..start].ends_with(|c: char| c.is_alphanumeric() || c == '_' || c == ':') {
                continue;
            }
            let mut p = me.clone();
            p.push(child.to_string());
            found.push(p);
        }
    }
    found
}

/// The source file a module path lives in: the longest prefix that is a file's module.
fn file_of(modules: &std::collections::BTreeMap<Vec<String>, String>, path: &[String]) -> Option<String> {
    (1..=path.len()).rev().find_map(|n| modules.get(&path[..n]).cloned())
}

/// What `lib.rs` re-exports at the crate root (`pub use sim::world::World;` → `World` ↦ `sim`):
/// `crate::World` is a use of the layer it comes from.
fn root_reexports(lib: &str) -> Vec<(String, String)> {
    let mut out = Vec::new();
    for line in lib.lines().filter(|l| l.trim_start().starts_with("pub use ")) {
        let body = line.trim().trim_start_matches("pub use ").trim_end_matches(';');
        let layer = body.split("::").next().unwrap_or("").to_string();
        let names = match (body.find('{'), body.find('}')) {
            (Some(a), Some(b)) => body[a + 1..b].split(',').map(|s| s.trim().to_string()).collect(),
            _ => vec![body.rsplit("::").next().unwrap_or("").to_string()],
        };
        out.extend(names.into_iter().filter(|n| !n.is_empty()).map(|n| (n, layer.clone())));
    }
    out
}

#[test]
fn layers_import_only_downwards() {
    let sources = sources();
    let lib = sources.iter().find(|(p, _)| p == "src/lib.rs").map(|(_, c)| c.clone()).unwrap_or_default();
    let reexports = root_reexports(&lib);
    let mut problems = Vec::new();
    for (path, code) in &sources {
        if path.starts_with("src/bin/") || path == "src/lib.rs" {
            continue;
        }
        let me = module_of(path);
        let layer = me[0].clone();
        let Some((_, allowed)) = LAYERS.iter().find(|(name, _)| *name == layer) else {
            problems.push(format!("{path}: layer `{layer}` is not in the LAYERS table"));
            continue;
        };
        for named in named_paths(path, code) {
            let Some(first) = named.first() else { continue };
            let target = reexports.iter().find(|(n, _)| n == first).map_or(first.clone(), |(_, l)| l.clone());
            if target != layer && !allowed.contains(&target.as_str()) {
                problems.push(format!(
                    "{path} ({layer}) uses crate::{} ({target} is not below {layer})",
                    named.join("::")
                ));
            }
        }
    }
    assert!(problems.is_empty(), "imports against the layer table:\n{}", problems.join("\n"));
}

/// The import circles of a file graph, each as `a → b → … → a` (one per starting file that
/// closes one): a depth-first search for a back edge.
fn circles(edges: &std::collections::BTreeMap<String, std::collections::BTreeSet<String>>) -> Vec<String> {
    use std::collections::{BTreeMap, BTreeSet};
    fn visit(
        node: &str,
        edges: &BTreeMap<String, BTreeSet<String>>,
        stack: &mut Vec<String>,
        done: &mut BTreeSet<String>,
    ) -> Option<Vec<String>> {
        if let Some(i) = stack.iter().position(|n| n == node) {
            let mut circle = stack[i..].to_vec();
            circle.push(node.to_string());
            return Some(circle);
        }
        if done.contains(node) {
            return None;
        }
        stack.push(node.to_string());
        for next in edges.get(node).into_iter().flatten() {
            if let Some(c) = visit(next, edges, stack, done) {
                return Some(c);
            }
        }
        stack.pop();
        done.insert(node.to_string());
        None
    }
    let mut done = BTreeSet::new();
    let mut circles = Vec::new();
    for node in edges.keys() {
        if let Some(c) = visit(node, edges, &mut Vec::new(), &mut done) {
            circles.push(c.join(" → "));
            done.insert(node.clone());
        }
    }
    circles
}

#[test]
fn no_import_circle_between_source_files() {
    use std::collections::{BTreeMap, BTreeSet};
    let sources = sources();
    let modules: BTreeMap<Vec<String>, String> = sources
        .iter()
        .filter(|(p, _)| !p.starts_with("src/bin/"))
        .map(|(p, _)| (module_of(p), p.clone()))
        .collect();
    let mut edges: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (path, code) in sources.iter().filter(|(p, _)| !p.starts_with("src/bin/") && *p != "src/lib.rs") {
        for named in named_paths(path, code) {
            if let Some(target) = file_of(&modules, &named) {
                if &target != path && target != "src/lib.rs" {
                    edges.entry(path.clone()).or_default().insert(target);
                }
            }
        }
    }
    let circles = circles(&edges);
    assert!(circles.is_empty(), "import circles between source files:\n{}", circles.join("\n"));
}

#[test]
fn the_layer_scanner_resolves_paths() {
    // Guards the guard: a scanner that found no path would pass both tests above.
    let code = "mod lanes;\nuse crate::model::scene::Scene;\nuse super::{GroupView, Planner};\nlet x = crate::planners::build(c).y::z();\nuse crate::{presets, World};\nlet v = lanes::Lanes2::splat(0.0);\n";
    let found = named_paths("src/planners/boids.rs", code);
    let strs: Vec<String> = found.iter().map(|p| p.join("::")).collect();
    assert_eq!(
        strs,
        vec![
            "model::scene::Scene",
            "planners::build",
            "presets",
            "World",
            "planners::GroupView",
            "planners::Planner",
            "planners::boids::lanes"
        ]
    );
    assert_eq!(module_of("src/sim/mod.rs"), vec!["sim".to_string()]);
    let mut graph = std::collections::BTreeMap::new();
    for (from, to) in [("a", "b"), ("b", "c"), ("c", "a"), ("c", "d")] {
        graph.entry(from.to_string()).or_insert_with(std::collections::BTreeSet::new).insert(to.to_string());
    }
    assert_eq!(circles(&graph).first().map(String::as_str), Some("a → b → c → a"));
    graph.remove("c");
    assert!(circles(&graph).is_empty());
    let sources = sources();
    let world = sources.iter().find(|(p, _)| p == "src/sim/world.rs").expect("sim/world.rs exists");
    assert!(named_paths(&world.0, &world.1).iter().any(|p| p.first().is_some_and(|f| f == "planners")));
}
