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
