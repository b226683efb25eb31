//! Every file or folder of the repository that the docs name exists (issue 26 §3): README.md and
//! docs/*.md are scanned for paths under the repository's top folders (`src/…`, `www/…`,
//! `scripts/…`, `tests/…`, `docs/…`, `examples/…`, `python/…`), in prose and code alike; a
//! path with `*` matches when any file does. A renamed or deleted file then fails here instead of
//! leaving a newcomer a dead pointer.

use std::path::{Path, PathBuf};

/// The repository's top folders a doc may point into.
const TOP: &[&str] = &["src", "www", "scripts", "tests", "docs", "examples", "python"];

/// Build output the docs may name although a fresh clone has none (the last: what the forces
/// table's regeneration command writes).
const GENERATED: &[&str] = &["www/pkg", "www/bench/", "test-artifacts", "target/", "docs/forces-table.md"];

fn docs() -> Vec<PathBuf> {
    let mut files = vec![PathBuf::from("README.md")];
    if let Ok(entries) = std::fs::read_dir("docs") {
        let mut md: Vec<PathBuf> = entries
            .filter_map(Result::ok)
            .map(|e| e.path())
            .filter(|p| p.extension().is_some_and(|x| x == "md"))
            .collect();
        md.sort();
        files.extend(md);
    }
    files
}

/// The paths named in `text`: a top folder's name at a word start, then path characters.
fn named_paths(text: &str) -> Vec<String> {
    let mut found = Vec::new();
    let bytes = text.as_bytes();
    for top in TOP {
        let needle = format!("{top}/");
        for (at, _) in text.match_indices(&needle) {
            // Not the tail of a longer path or word (`old-src/`, `https://…/src/`).
            if at > 0 && (bytes[at - 1].is_ascii_alphanumeric() || b"/._-".contains(&bytes[at - 1])) {
                continue;
            }
            let path: String = text[at..]
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || "/._-*".contains(*c))
                .collect();
            // Sentence punctuation is not part of the path.
            let path = path.trim_end_matches(['.', ',']).to_string();
            found.push(path);
        }
    }
    found.sort();
    found.dedup();
    found
}

/// Whether `path` (maybe with `*` in its last segment) names something in the repository.
fn exists(path: &str) -> bool {
    if !path.contains('*') {
        return Path::new(path).exists();
    }
    let (dir, pattern) = path.rsplit_once('/').unwrap_or((".", path));
    let (prefix, suffix) = pattern.split_once('*').unwrap_or((pattern, ""));
    std::fs::read_dir(dir).is_ok_and(|entries| {
        entries.filter_map(Result::ok).any(|e| {
            let name = e.file_name().to_string_lossy().to_string();
            name.starts_with(prefix) && name.ends_with(suffix) && name.len() >= prefix.len() + suffix.len()
        })
    })
}

#[test]
fn every_path_the_docs_name_exists() {
    let mut missing = Vec::new();
    let mut checked = 0;
    for doc in docs() {
        let text = std::fs::read_to_string(&doc).unwrap_or_else(|e| panic!("{}: {e}", doc.display()));
        for path in named_paths(&text) {
            if GENERATED.iter().any(|g| path.starts_with(g)) {
                continue;
            }
            checked += 1;
            if !exists(&path) {
                missing.push(format!("{}: {path}", doc.display()));
            }
        }
    }
    assert!(checked > 50, "the scan found only {checked} paths: the pattern is broken");
    assert!(missing.is_empty(), "the docs name paths that do not exist:\n{}", missing.join("\n"));
}

#[test]
fn the_scan_finds_paths_in_prose_and_code() {
    let text = "see `src/sim/world.rs`, and www/js/*.js; not https://x.org/src/a or old-src/b.\n```sh\nbash scripts/test.sh\n```";
    assert_eq!(named_paths(text), ["scripts/test.sh", "src/sim/world.rs", "www/js/*.js"]);
    assert!(exists("tests/web_*.rs"));
    assert!(!exists("tests/no_such_*.rs"));
}
