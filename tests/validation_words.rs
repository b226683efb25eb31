//! The validation suite's words match docs/validation.md: each test's set-up and measurement,
//! which the Validation page shows as its "how it is measured" paragraphs, are the cells of the
//! test's row in the docs' table, word for word. A docs edit without the core (or the reverse)
//! fails here, so the page and the docs cannot drift apart.

use flockpath::experiments::validation::TESTS;

/// The cells of the docs table row for `id` (`| \`id\` | set-up | measurement | criterion |`),
/// with the Markdown escape `\|` undone.
fn docs_row(docs: &str, id: &str) -> Option<Vec<String>> {
    let start = format!("| `{id}` |");
    let line = docs.lines().find(|l| l.starts_with(&start))?;
    let body = line.strip_prefix(&start)?.replace("\\|", "\u{1}");
    Some(body.split('|').map(|c| c.trim().replace('\u{1}', "|")).filter(|c| !c.is_empty()).collect())
}

#[test]
fn every_test_s_setup_and_measurement_are_the_docs_words() {
    let docs = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/validation.md"))
        .expect("docs/validation.md is in the repository");
    assert_eq!(TESTS.len(), 12, "the docs table has a row per test");
    for spec in TESTS {
        let cells = docs_row(&docs, spec.id)
            .unwrap_or_else(|| panic!("docs/validation.md has no row for {}", spec.id));
        assert_eq!(cells.len(), 3, "{}: set-up, measurement, criterion: {cells:?}", spec.id);
        assert_eq!(cells[0], spec.setup, "{}: set-up", spec.id);
        assert_eq!(cells[1], spec.measurement, "{}: measurement", spec.id);
        assert!(!spec.measurement.is_empty() && !spec.setup.is_empty());
    }
}
