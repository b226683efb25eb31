//! The command line's outputs, byte for byte: every command runs on fixed inputs and its stdout
//! and every file it writes are compared with the outputs captured from the binary and committed
//! under `tests/data/cli/`. Only wall-clock figures (seconds, evaluations per second, planning
//! time, thread count) are masked before the comparison; every other byte must match.
//!
//! `FLOCKPATH_BLESS=1 cargo test --test cli_golden` rewrites the expected files (only when an
//! output changes on purpose).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// A scene small enough for short committed outputs: two groups of three agents, one obstacle.
const SCENE: &str = "tests/data/cli/small-scene.json";

/// The crate's root, where the tests run the binary unless a case has its own directory.
fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn data_dir() -> PathBuf {
    root().join("tests/data/cli")
}

fn blessing() -> bool {
    std::env::var_os("FLOCKPATH_BLESS").is_some()
}

/// A fresh, empty working directory for one case.
fn work_dir(case: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("flockpath-cli-golden-{}-{case}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

/// Replaces what the wall clock decides with `<t>`: `"key": value` in JSON, the rest of a line
/// after a prefix in text.
fn mask_clock(text: &str) -> String {
    const JSON_KEYS: &[&str] = &["\"seconds\": ", "\"evaluations_per_second\": ", "\"planning_ms\": "];
    const LINE_PREFIXES: &[&str] = &["wall time ", "seconds (1 core)"];
    let mut out = String::with_capacity(text.len());
    for line in text.split_inclusive('\n') {
        let (body, end) = match line.strip_suffix('\n') {
            Some(body) => (body, "\n"),
            None => (line, ""),
        };
        let masked = if let Some(prefix) = LINE_PREFIXES.iter().find(|p| body.starts_with(*p)) {
            format!("{prefix}<t>")
        } else if let Some(key) = JSON_KEYS.iter().find(|k| body.trim_start().starts_with(*k)) {
            let indent = &body[..body.len() - body.trim_start().len()];
            let comma = if body.ends_with(',') { "," } else { "" };
            format!("{indent}{key}<t>{comma}")
        } else if body.starts_with("| B") && body.get(4..6) == Some("-E") && body.ends_with(" |") {
            // A `tune --table` run row (`| B1-E2 | …`): the last cell is the run's seconds.
            let cut = body[..body.len() - 2].rfind("| ").expect("a table row has cells");
            format!("{}| <t> |", &body[..cut])
        } else if body.split_whitespace().nth(1).is_some_and(|w| w == "igsa" || w == "gsa")
            && body.split_whitespace().count() == 13
        {
            // A Table 4 row: the third column is the planning time in ms; the others keep their
            // columns.
            let end_of = |field: &str| field.as_ptr() as usize - body.as_ptr() as usize + field.len();
            let mut fields = body.split_whitespace();
            let path_end = fields.nth(1).map(end_of).expect("13 columns");
            let plan_end = fields.next().map(end_of).expect("13 columns");
            format!("{}{:>10}{}", &body[..path_end], "<t>", &body[plan_end..])
        } else {
            body.to_string()
        };
        out.push_str(&masked);
        out.push_str(end);
    }
    out
}

/// Runs the binary with `args` in `dir` and collects its output.
fn flockpath<S: AsRef<std::ffi::OsStr>>(args: &[S], dir: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_flockpath"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the binary runs")
}

/// One command-line case: its arguments (`{scene}` stands for the committed scene file), the
/// files it writes (relative to its working directory) and whether wall-clock figures are masked.
struct Case {
    name: &'static str,
    args: &'static [&'static str],
    files: &'static [&'static str],
    timed: bool,
}

/// Runs `case` and compares (or, when blessing, writes) its stdout and files.
fn check(case: &Case) {
    let dir = work_dir(case.name);
    let scene = root().join(SCENE);
    let args: Vec<String> = case
        .args
        .iter()
        .map(|a| a.replace("{scene}", scene.to_str().expect("utf-8 path")))
        .map(|a| a.replace("{fragment}", &fragment()))
        .collect();
    let output = flockpath(&args, &dir);
    assert!(
        output.status.success(),
        "{}: exit {:?}, stderr: {}",
        case.name,
        output.status,
        String::from_utf8_lossy(&output.stderr)
    );
    let mut outputs = vec![(format!("{}.stdout", case.name), output.stdout)];
    for file in case.files {
        let bytes = std::fs::read(dir.join(file))
            .unwrap_or_else(|e| panic!("{}: {file} was not written: {e}", case.name));
        outputs.push((format!("{}.{}", case.name, file.replace('/', "-")), bytes));
    }
    for (name, bytes) in outputs {
        let expected_path = data_dir().join(&name);
        let got = String::from_utf8(bytes).unwrap_or_else(|_| panic!("{name} is not UTF-8"));
        let got = if case.timed { mask_clock(&got) } else { got };
        if blessing() {
            std::fs::write(&expected_path, &got).expect("expected output written");
            continue;
        }
        let expected = std::fs::read_to_string(&expected_path)
            .unwrap_or_else(|e| panic!("{}: missing {}: {e}", case.name, expected_path.display()));
        if got != expected {
            let line = got.lines().zip(expected.lines()).position(|(g, e)| g != e);
            panic!(
                "{name} differs from {} (first differing line {:?}; {} vs {} bytes):\n--- got\n{}\n--- expected\n{}",
                expected_path.display(),
                line.map(|l| l + 1),
                got.len(),
                expected.len(),
                line.and_then(|l| got.lines().nth(l)).unwrap_or(""),
                line.and_then(|l| expected.lines().nth(l)).unwrap_or("")
            );
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// The committed `url` output: the fragment value the `scene` and `run` cases read back.
fn fragment() -> String {
    std::fs::read_to_string(data_dir().join("url.stdout")).map(|s| s.trim().to_string()).unwrap_or_default()
}

#[test]
fn presets_preset_url_and_scene_print_the_same_bytes() {
    let mut cases = vec![Case { name: "presets", args: &["presets"], files: &[], timed: false }];
    for (name, args) in [
        ("preset-pillars", &["preset", "pillars"]),
        ("preset-open-field", &["preset", "open-field"]),
        ("preset-two-groups-swap", &["preset", "two-groups-swap"]),
        ("preset-corridor", &["preset", "corridor"]),
    ] {
        cases.push(Case { name, args, files: &[], timed: false });
    }
    cases.push(Case { name: "url", args: &["url", "{scene}"], files: &[], timed: false });
    cases.push(Case { name: "scene", args: &["scene", "{fragment}"], files: &[], timed: false });
    cases.push(Case {
        name: "scene-url",
        args: &["scene", "https://example.org/flockpath/index.html#s={fragment}"],
        files: &[],
        timed: false,
    });
    cases.iter().for_each(check);
}

#[test]
fn run_prints_and_writes_the_same_bytes() {
    let cases = [
        Case {
            name: "run-summary",
            args: &["run", "--scene", "{scene}", "--steps", "30"],
            files: &[],
            timed: false,
        },
        Case {
            name: "run-metrics-stdout",
            args: &["run", "--scene", "{scene}", "--steps", "30", "--metrics", "-"],
            files: &[],
            timed: false,
        },
        Case {
            name: "run-planner-seed",
            args: &[
                "run",
                "--scene",
                "{fragment}",
                "--steps=25",
                "--planner",
                "pso",
                "--seed",
                "7",
                "--metrics",
                "metrics.json",
            ],
            files: &["metrics.json"],
            timed: false,
        },
        Case {
            name: "run-exports",
            args: &[
                "run",
                "--scene",
                "{scene}",
                "--steps",
                "12",
                "--paths",
                "paths.csv",
                "--paths-json",
                "paths.json",
                "--maya",
                "crowd.mel",
                "--blender",
                "crowd.py",
                "--svg",
                "trails.svg",
                "--metrics-history",
                "history.csv",
                "--fps",
                "30",
                "--scale=0.5",
            ],
            files: &["paths.csv", "paths.json", "crowd.mel", "crowd.py", "trails.svg", "history.csv"],
            timed: false,
        },
    ];
    cases.iter().for_each(check);
}

#[test]
fn optimize_prints_and_writes_the_same_bytes() {
    let cases = [
        Case {
            name: "optimize",
            args: &[
                "optimize",
                "--algorithms",
                "all",
                "--functions",
                "sphere,rastrigin",
                "--dim",
                "3",
                "--pop",
                "6",
                "--iters",
                "4",
                "--runs",
                "2",
                "--seed",
                "5",
                "--json",
                "cells.json",
                "--curves",
                "curves.csv",
            ],
            files: &["cells.json", "curves.csv"],
            timed: true,
        },
        Case {
            name: "optimize-curves-dir",
            args: &[
                "optimize",
                "--algorithms=gsa,igsa",
                "--functions=paper",
                "--dim=2",
                "--pop=4",
                "--iters=3",
                "--runs=1",
                "--g0",
                "50",
                "--alpha",
                "10",
                "--curves",
                "curves",
            ],
            files: &[
                "curves/curves-sphere.csv",
                "curves/curves-ackley.csv",
                "curves/curves-griewank.csv",
                "curves/curves-rastrigin.csv",
            ],
            timed: true,
        },
        Case {
            name: "optimize-paths",
            args: &[
                "optimize",
                "--paths",
                "--algorithms",
                "gsa,igsa",
                "--runs",
                "2",
                "--pop",
                "6",
                "--iters",
                "5",
                "--json",
                "paths.json",
            ],
            files: &["paths.json"],
            timed: true,
        },
        Case {
            name: "optimize-table4",
            args: &["optimize", "--table4", "--steps", "3"],
            files: &[],
            timed: true,
        },
    ];
    cases.iter().for_each(check);
}

#[test]
fn tune_prints_and_writes_the_same_bytes() {
    let cases = [
        Case {
            name: "tune",
            args: &[
                "tune",
                "--behaviour",
                "b1",
                "--environment",
                "e1",
                "--seed",
                "3",
                "--generations",
                "2",
                "--population",
                "4",
                "--frames",
                "20",
                "--json",
                "tune.json",
            ],
            files: &["tune.json"],
            timed: true,
        },
        Case {
            name: "tune-json-stdout",
            args: &[
                "tune",
                "--behavior",
                "b2",
                "--environment",
                "e2",
                "--seed",
                "1",
                "--generations",
                "1",
                "--population",
                "4",
                "--frames",
                "15",
                "--sample-every",
                "5",
                "--json",
                "-",
            ],
            files: &[],
            timed: true,
        },
        Case {
            name: "tune-score",
            args: &[
                "tune",
                "--behaviour",
                "b2",
                "--environment",
                "e3",
                "--score",
                "0.4,0.1,0.2,0.8,0.4",
                "--frames",
                "20",
            ],
            files: &[],
            timed: false,
        },
        Case {
            name: "tune-table",
            args: &[
                "tune",
                "--table",
                "--seeds",
                "2",
                "--generations",
                "1",
                "--population",
                "4",
                "--frames",
                "10",
                "--markdown",
                "table.md",
                "--json",
                "table.json",
            ],
            files: &["table.md", "table.json"],
            timed: true,
        },
        Case {
            name: "tune-table-stdout",
            args: &[
                "tune",
                "--table",
                "--seeds",
                "1",
                "--generations",
                "1",
                "--population",
                "4",
                "--frames",
                "8",
            ],
            files: &[],
            timed: true,
        },
    ];
    cases.iter().for_each(check);
}

/// Exit codes: 2 for a usage mistake, 1 for a failure, for every command.
#[test]
fn usage_mistakes_exit_2_and_failures_exit_1() {
    let usage: &[&[&str]] = &[
        &[],
        &["fly"],
        &["presets", "extra"],
        &["preset"],
        &["preset", "moon-base"],
        &["url"],
        &["scene"],
        &["run", "--steps", "5"],
        &["run", "--scene", SCENE, "--steps", "ten"],
        &["run", "--scene", SCENE, "--steps", "5", "--fast"],
        &["optimize", "--dim", "0"],
        &["optimize", "--what", "1"],
        &["tune", "--behaviour", "b4", "--environment", "e1", "--seed", "1"],
        &["tune", "--behaviour", "b1", "--environment", "e1"],
        &["bench", "--only", "disk"],
        &["bench", "--slow"],
    ];
    let failure: &[&[&str]] = &[
        &["url", "missing-scene.json"],
        &["scene", "7.abc"],
        &["run", "--scene", "no/such/scene.json", "--steps", "5"],
        &["run", "--scene", SCENE, "--steps", "3", "--paths", "/no/such/dir/p.csv"],
    ];
    for (args, code) in usage.iter().map(|a| (a, 2)).chain(failure.iter().map(|a| (a, 1))) {
        let output = flockpath(args, root());
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(code), "{args:?}: stderr {stderr}");
        assert!(
            output.stdout.is_empty(),
            "{args:?} printed on stdout: {}",
            String::from_utf8_lossy(&output.stdout)
        );
        assert!(!stderr.trim().is_empty(), "{args:?} failed without a message");
    }
}

/// Every command has `--help`, and `flockpath help COMMAND` prints the same text (tune included).
#[test]
fn every_command_has_help() {
    let run = |args: &[&str]| {
        let output = flockpath(args, root());
        assert!(output.status.success(), "{args:?}: {}", String::from_utf8_lossy(&output.stderr));
        String::from_utf8(output.stdout).expect("UTF-8 help")
    };
    let top = run(&["--help"]);
    assert!(
        top.contains("Exit codes") && top.contains("2 usage mistake") && top.contains("1 failure"),
        "{top}"
    );
    for command in ["presets", "preset", "run", "url", "scene", "bench", "optimize", "tune"] {
        assert!(top.contains(command), "{command} missing from --help:\n{top}");
        let help = run(&["help", command]);
        assert!(help.contains(&format!("flockpath {command}")), "help {command}:\n{help}");
        assert_eq!(run(&[command, "--help"]), help, "{command} --help differs from help {command}");
    }
}

/// stderr is not a terminal here: no progress bar is drawn, while tune's log lines stay.
#[test]
fn no_progress_bar_off_a_terminal() {
    let run = |args: &[&str]| flockpath(args, root());
    let optimize = run(&[
        "optimize",
        "--functions",
        "sphere",
        "--dim",
        "2",
        "--pop",
        "4",
        "--iters",
        "2",
        "--runs",
        "3",
    ]);
    assert!(optimize.status.success());
    assert!(
        optimize.stderr.is_empty(),
        "optimize drew on stderr: {:?}",
        String::from_utf8_lossy(&optimize.stderr)
    );
    let tune = run(&[
        "tune",
        "--behaviour",
        "b1",
        "--environment",
        "e1",
        "--seed",
        "1",
        "--generations",
        "2",
        "--population",
        "4",
        "--frames",
        "10",
    ]);
    let stderr = String::from_utf8_lossy(&tune.stderr);
    assert!(tune.status.success(), "{stderr}");
    assert_eq!(stderr.lines().filter(|l| l.starts_with("gen ")).count(), 2, "{stderr}");
    assert!(!stderr.contains('\r') && !stderr.contains("\u{1b}["), "a bar was drawn: {stderr:?}");
}
