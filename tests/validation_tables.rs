//! `scripts/validation-tables.py`, which writes docs/validation.md's measured tables from
//! `flockpath validate --json`: on a small real report (two quick tests, two planners) the
//! table between the markers holds every row's verdict and measurement, the prose round the
//! markers is kept, and `--check` tells a page that equals the report from one that does not.

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn temp(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("flockpath-validation-tables-{}-{name}", std::process::id()))
}

fn tables(report: &Path, doc: &Path, check: bool) -> Output {
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/scripts/validation-tables.py");
    let mut args = vec![script, report.to_str().expect("utf-8 path"), doc.to_str().expect("utf-8 path")];
    if check {
        args.push("--check");
    }
    Command::new("python3").args(args).output().expect("python3 runs")
}

const PAGE: &str = "intro prose\n\n<!-- validation-tables:begin main -->\nstale table\n<!-- validation-tables:end main -->\n\nclosing prose\n";

#[test]
fn the_main_table_is_the_reports_rows_and_check_tells_a_stale_page() {
    let report = temp("report.json");
    let out = Command::new(env!("CARGO_BIN_EXE_flockpath"))
        .args(["validate", "--tests", "t1,juelich-head-on", "--planners", "boids,orca", "--json"])
        .arg(&report)
        .output()
        .expect("the binary runs");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let json: Value = serde_json::from_str(&std::fs::read_to_string(&report).expect("report")).expect("json");
    let rows = json["rows"].as_array().expect("rows");
    assert_eq!(rows.len(), 4);

    let doc = temp("page.md");
    std::fs::write(&doc, PAGE).expect("write page");
    assert!(!tables(&report, &doc, true).status.success(), "a stale page fails --check");
    let out = tables(&report, &doc, false);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let page = std::fs::read_to_string(&doc).expect("page");
    assert!(
        page.starts_with("intro prose\n\n<!-- validation-tables:begin main -->\n| test | boids | orca |"),
        "{page}"
    );
    assert!(page.ends_with("<!-- validation-tables:end main -->\n\nclosing prose\n"), "{page}");
    assert!(!page.contains("stale table"), "{page}");
    for row in rows {
        let verdict = if row["pass"].as_bool().expect("pass") { "**pass**" } else { "fail" };
        let cell = format!("{verdict}: {}", row["measured"].as_str().expect("measured").replace('|', "\\|"));
        let test = format!("| `{}` |", row["test"].as_str().expect("test"));
        let line = page.lines().find(|l| l.starts_with(&test)).unwrap_or_else(|| panic!("{test} in {page}"));
        assert!(line.contains(&cell), "{cell} in {line}");
    }
    let passed = rows.iter().filter(|r| r["pass"].as_bool() == Some(true)).count();
    assert!(page.contains(&format!("**{passed} of 4 pass** (2 tests × 2 planners)")), "{page}");

    let check = tables(&report, &doc, true);
    assert!(check.status.success(), "{}", String::from_utf8_lossy(&check.stderr));
    std::fs::write(&doc, page.replacen("| boids |", "| boidz |", 1)).expect("write page");
    assert!(!tables(&report, &doc, true).status.success(), "an edited table fails --check");
    let _ = std::fs::remove_file(&report);
    let _ = std::fs::remove_file(&doc);
}

#[test]
fn the_speed_tables_show_measured_density_missing_points_and_the_reference() {
    let columns = [
        "density_nominal_persons_per_m2",
        "density_measured_persons_per_m2",
        "speed_m_s",
        "specific_flow_persons_m_s",
        "reference_speed_m_s",
        "reference_specific_flow_persons_m_s",
        "speed_deviation_m_s",
        "specific_flow_deviation_persons_m_s",
    ];
    let report = serde_json::json!({
        "px_per_metre": 20,
        "rows": [],
        "curves": [{
            "name": "t4-fundamental-diagram-fd-orca",
            "test": "t4-fundamental-diagram",
            "planner": "orca",
            "columns": columns,
            "rows": [[1.0, 1.02, 1.336, 1.36, 1.04, 1.06, 0.3, 0.3], [6.0, null, null, null, null, null, null, null]],
        }],
    });
    let file = temp("fd.json");
    std::fs::write(&file, report.to_string()).expect("write report");
    let doc = temp("fd.md");
    std::fs::write(
        &doc,
        "<!-- validation-tables:begin t4-speeds -->\n<!-- validation-tables:end t4-speeds -->\n",
    )
    .expect("write page");
    let out = tables(&file, &doc, false);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let page = std::fs::read_to_string(&doc).expect("page");
    assert!(page.contains("| planner | 1 | 6 |\n"), "{page}");
    assert!(page.contains("| orca | 1.34 (1.02) | — (—) |\n"), "{page}");
    // Weidmann at the nominal densities: 1.34 (1 − exp(−1.913 (1/ρ − 1/5.4))), 0 beyond 5.4.
    assert!(page.contains("| Weidmann | 1.06 | 0.00 |\n"), "{page}");
    let _ = std::fs::remove_file(&file);
    let _ = std::fs::remove_file(&doc);
}
