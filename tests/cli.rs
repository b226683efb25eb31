//! The command line as scripts use it (DESIGN §5): runs the built `flockpath` binary.

#[path = "support/largest_scene.rs"]
mod largest_scene;

use std::io::Write as _;
use std::path::PathBuf;
use std::process::{Command, Output, Stdio};

/// Every metrics key DESIGN §4 promises, at the top level and per group.
const METRIC_KEYS: &[&str] = &[
    "agents",
    "arrived_share",
    "mean_time_to_goal",
    "collisions_agent_agent",
    "penetrations_agent_obstacle",
    "mean_speed",
    "mean_path_length",
    "mean_turn_deg",
    "max_turn_deg",
    "stuck_agents",
];

fn flockpath(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_flockpath")).args(args).output().expect("the binary runs")
}

fn flockpath_with_stdin(args: &[&str], stdin: &str) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_flockpath"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary starts");
    child.stdin.take().expect("stdin is piped").write_all(stdin.as_bytes()).expect("stdin accepts the scene");
    child.wait_with_output().expect("the binary finishes")
}

fn stdout(o: &Output) -> String {
    String::from_utf8(o.stdout.clone()).expect("stdout is UTF-8")
}

fn stderr(o: &Output) -> String {
    String::from_utf8(o.stderr.clone()).expect("stderr is UTF-8")
}

fn ok(o: Output) -> String {
    assert!(o.status.success(), "exit {:?}, stderr: {}", o.status, stderr(&o));
    stdout(&o)
}

/// Asserts a failure with a non-zero exit, nothing on stdout, and `needle` in the message.
fn fails_naming(o: Output, needle: &str) {
    let err = stderr(&o);
    assert!(!o.status.success(), "expected a failure naming {needle:?}, got success: {}", stdout(&o));
    assert!(err.contains(needle), "stderr should name {needle:?}: {err}");
    assert!(o.stdout.is_empty(), "stdout should be empty on failure: {}", stdout(&o));
}

/// A scratch file path unique to this call (tests run in parallel threads of one process and
/// may use the same `name`: a shared path let one test delete another's file).
fn temp_path(name: &str) -> PathBuf {
    static NEXT: std::sync::atomic::AtomicU32 = std::sync::atomic::AtomicU32::new(0);
    let n = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    std::env::temp_dir().join(format!("flockpath-cli-{}-{n}-{name}", std::process::id()))
}

fn preset_json(name: &str) -> String {
    ok(flockpath(&["preset", name]))
}

#[test]
fn presets_lists_every_preset_in_menu_order_with_its_description() {
    let text = ok(flockpath(&["presets"]));
    let lines: Vec<&str> = text.lines().collect();
    let all = flockpath::model::presets::ALL;
    assert_eq!(lines.len(), all.len(), "{text}");
    for (line, preset) in lines.iter().zip(all) {
        assert_eq!(line.split_whitespace().next(), Some(preset.name), "{line:?}");
        assert!(preset.description.len() > 10, "{} has no description", preset.name);
        assert_eq!(line[preset.name.len()..].trim(), preset.description, "{line:?}");
    }
}

#[test]
fn preset_prints_valid_json_that_run_accepts_from_stdin_and_from_a_file() {
    for p in flockpath::model::presets::ALL {
        let json = preset_json(p.name);
        let scene = flockpath::scene_from_json(&json).expect("preset JSON parses");
        assert_eq!(scene, (p.build)(), "{}", p.name);

        let piped = ok(flockpath_with_stdin(&["run", "--scene", "-", "--steps", "20"], &json));
        assert!(piped.contains("20 steps"), "{piped}");

        let file = temp_path(&format!("{}.json", p.name));
        std::fs::write(&file, &json).expect("temp file written");
        let from_file =
            ok(flockpath(&["run", "--scene", file.to_str().expect("utf-8 path"), "--steps", "20"]));
        std::fs::remove_file(&file).ok();
        assert_eq!(piped, from_file, "{}: stdin and file runs differ", p.name);
    }
    // A preset name is a scene too.
    let by_name = ok(flockpath(&["run", "--scene", "pillars", "--steps", "20"]));
    let from_json =
        ok(flockpath_with_stdin(&["run", "--scene", "-", "--steps", "20"], &preset_json("pillars")));
    assert_eq!(by_name, from_json);
}

#[test]
fn run_metrics_to_stdout_has_every_design_key() {
    let json = preset_json("two-groups-swap");
    let out = ok(flockpath_with_stdin(&["run", "--scene", "-", "--steps", "120", "--metrics", "-"], &json));
    let m: serde_json::Value = serde_json::from_str(&out).expect("metrics are JSON");
    assert_eq!(m["steps"], 120);
    for key in METRIC_KEYS {
        assert!(m.get(key).is_some(), "top-level key {key} missing: {out}");
    }
    assert_eq!(m["agents"], 100);
    let groups = m["groups"].as_array().expect("groups is an array");
    assert_eq!(groups.len(), 2);
    for (g, name) in groups.iter().zip(["left", "right"]) {
        assert_eq!(g["name"], name);
        assert_eq!(g["planner"], "boids");
        for key in METRIC_KEYS {
            assert!(g.get(key).is_some(), "group key {key} missing: {g}");
        }
    }
    let mean_speed = m["mean_speed"].as_f64().expect("mean_speed is a number");
    assert!(mean_speed > 0.0 && mean_speed <= 2.0 + 1e-6, "mean speed {mean_speed}");
}

#[test]
fn metrics_file_seed_and_planner_overrides() {
    let json = preset_json("open-field");
    let file = temp_path("metrics.json");
    let path = file.to_str().expect("utf-8 path");
    let seeded = |seed: &str| {
        ok(flockpath_with_stdin(&["run", "--scene", "-", "--steps", "60", "--seed", seed], &json))
    };
    let (a, b, c) = (seeded("5"), seeded("5"), seeded("6"));
    assert_eq!(a, b, "same seed, same run");
    assert_ne!(a, c, "another seed, another run");

    ok(flockpath_with_stdin(
        &["run", "--scene", "-", "--steps", "60", "--planner", "boids", "--metrics", path],
        &json,
    ));
    let written = std::fs::read_to_string(&file).expect("metrics file written");
    std::fs::remove_file(&file).ok();
    let m: serde_json::Value = serde_json::from_str(&written).expect("metrics file is JSON");
    assert_eq!(m["steps"], 60);
    assert_eq!(m["groups"][0]["planner"], "boids");
}

#[test]
fn url_and_scene_round_trip() {
    let json = preset_json("corridor");
    let file = temp_path("corridor.json");
    std::fs::write(&file, &json).expect("temp file written");
    let fragment = ok(flockpath(&["url", file.to_str().expect("utf-8 path")]));
    std::fs::remove_file(&file).ok();
    let fragment = fragment.trim();
    assert!(fragment.starts_with("2."), "{fragment}");
    assert!(!fragment.contains(['/', '+', '=', '#', ' ']), "not URL-safe: {fragment}");

    let back = ok(flockpath(&["scene", fragment]));
    assert_eq!(
        flockpath::scene_from_json(&back).expect("scene prints JSON"),
        flockpath::scene_from_json(&json).expect("preset JSON")
    );
    // A whole page URL works too, and run takes the fragment directly.
    let url = format!("https://example.org/flockpath/index.html#s={fragment}");
    assert_eq!(ok(flockpath(&["scene", &url])), back);
    let run = ok(flockpath(&["run", "--scene", fragment, "--steps", "5"]));
    assert!(run.starts_with("corridor:"), "{run}");
}

#[test]
fn bad_inputs_fail_with_a_message_naming_the_problem() {
    let json = preset_json("pillars");
    let file = temp_path("pillars-for-errors.json");
    std::fs::write(&file, &json).expect("temp file written");
    let path = file.to_str().expect("utf-8 path");

    fails_naming(flockpath(&["run", "--scene", "no/such/scene.json", "--steps", "5"]), "no/such/scene.json");
    fails_naming(flockpath(&["url", "missing-scene.json"]), "no such file");
    fails_naming(flockpath(&["run", "--scene", "1.garbled!!", "--steps", "5"]), "base64");
    fails_naming(flockpath(&["scene", "1.AAAAAAAA"]), "damaged");
    fails_naming(flockpath(&["scene", "7.abc"]), "version");
    fails_naming(flockpath(&["run", "--scene", path, "--steps", "ten"]), "--steps");
    fails_naming(flockpath(&["run", "--scene", path, "--steps", "5", "--seed", "-3"]), "--seed");
    fails_naming(flockpath(&["run", "--scene", path, "--steps", "5000000000"]), "--steps");
    fails_naming(flockpath(&["run", "--scene", path, "--steps", "2000000"]), "limit");
    fails_naming(flockpath(&["run", "--scene", path, "--steps", "5", "--planner", "ants"]), "ants");
    fails_naming(flockpath(&["run", "--scene", path, "--steps", "5", "--fast"]), "--fast");
    fails_naming(flockpath(&["run", "--scene", path]), "--steps");
    fails_naming(flockpath(&["run", "--steps", "5"]), "--scene");
    fails_naming(
        flockpath(&["run", "--scene", path, "--steps", "5", "--maya", "o.mel", "--fps", "0"]),
        "frame rate",
    );
    fails_naming(flockpath(&["optimize", "--algorithms", "nope"]), "nope");
    fails_naming(
        flockpath(&["run", "--scene", path, "--steps", "5", "--maya", "o.mel", "--fps", "NaN"]),
        "--fps",
    );
    std::fs::remove_file("o.mel").ok();
    fails_naming(
        flockpath(&["run", "--scene", path, "--steps", "5", "--blender", "o.py", "--scale", "inf"]),
        "--scale",
    );
    std::fs::remove_file("o.py").ok();
    fails_naming(flockpath(&["fly"]), "fly");
    fails_naming(flockpath(&["preset", "moon-base"]), "unknown preset 'moon-base' (known: pillars");
    fails_naming(flockpath(&["run", "--scene", "moon-base", "--steps", "5"]), "no preset has that name");
    fails_naming(flockpath(&["scene", "moon-base"]), "unknown preset 'moon-base' (known: pillars");
    fails_naming(flockpath(&[]), "no command");

    // NaN and out-of-range values inside the scene are refused by name.
    let nan = json.replacen("\"width\": 900.0", "\"width\": NaN", 1);
    assert_ne!(nan, json);
    fails_naming(flockpath_with_stdin(&["run", "--scene", "-", "--steps", "5"], &nan), "stdin");
    let mut scene: serde_json::Value = serde_json::from_str(&json).expect("preset JSON");
    scene["goals"][0]["radius"] = serde_json::json!(-1.0);
    fails_naming(
        flockpath_with_stdin(&["run", "--scene", "-", "--steps", "5"], &scene.to_string()),
        "goals[0].radius is -1",
    );
    scene["goals"][0]["radius"] = serde_json::json!(1e39);
    fails_naming(flockpath_with_stdin(&["run", "--scene", "-", "--steps", "5"], &scene.to_string()), "goal");
    std::fs::remove_file(&file).ok();
}

#[test]
fn help_is_available_for_the_tool_and_its_commands() {
    let top = ok(flockpath(&["--help"]));
    for command in ["presets", "preset", "run", "url", "scene", "bench"] {
        assert!(top.contains(command), "{command} missing from --help");
    }
    let run = ok(flockpath(&["run", "--help"]));
    for flag in ["--scene", "--planner", "--seed", "--steps", "--metrics"] {
        assert!(run.contains(flag), "{flag} missing from run --help");
    }
    assert!(ok(flockpath(&["help", "bench"])).contains("--quick"));
}

/// One wording per unknown name, whichever front-end meets it: the command line shows the
/// library's typed error (`UnknownPlanner`, `UnknownCase`, `UnknownName`) inside clap's or its own
/// line, the same text the page and the comparison show.
#[test]
fn unknown_names_are_worded_by_the_library() {
    use flockpath::model::forces_cases::Behaviour;
    use flockpath::optim::Algorithm;
    use flockpath::PlannerKind;
    let planner = PlannerKind::parse("ants").expect_err("no planner ants").to_string();
    let names: Vec<&str> = PlannerKind::ALL.iter().map(|k| k.name()).collect();
    assert_eq!(planner, format!("unknown planner \"ants\"; known: {}", names.join(", ")));
    fails_naming(flockpath(&["run", "--scene", "pillars", "--steps", "5", "--planner", "ants"]), &planner);
    let spec = flockpath::sim::compare::ComparisonSpec::parse("1.boids~ants").expect_err("no planner ants");
    assert_eq!(
        spec.to_string(),
        format!("comparison: unknown planner \"ants\"; known: scene, {}", names.join(", "))
    );

    let behaviour = Behaviour::parse("b4").expect_err("no b4").to_string();
    assert_eq!(behaviour, "unknown behaviour \"b4\"; known: b1, b2, b3");
    fails_naming(flockpath(&["tune", "--behaviour", "b4", "--environment", "e1", "--seed", "1"]), &behaviour);
    let setup = flockpath::tune::TuneSetup { behaviour: "b4".into(), ..Default::default() };
    assert_eq!(setup.task().map(|_| ()).expect_err("no b4").to_string(), behaviour);

    let algorithm = Algorithm::parse("nope").expect_err("no algorithm nope").to_string();
    assert_eq!(algorithm, "unknown algorithm \"nope\"; known: gsa, igsa, pso, firefly, ga");
    fails_naming(flockpath(&["optimize", "--algorithms", "nope"]), &algorithm);
}

/// `run` reports a scene's activity check after its summary, decided at the step the metrics of
/// an independent run meet every condition; with the metrics JSON on stdout the check goes to
/// stderr; a scene without a check prints the summary alone.
#[test]
fn run_reports_the_activity_check_after_the_summary() {
    // pillars with "arrived_share >= 0.9 and penetrations_agent_obstacle = 0 within 1500 steps".
    let file = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/fragments/v2/pillars-activity.json");
    let scene = flockpath::scene_from_json(&std::fs::read_to_string(file).expect("the scene file"))
        .expect("a valid scene");
    let mut world = flockpath::World::new(scene).expect("a valid scene");
    let met = (1..=1500u32)
        .find(|_| {
            world.step();
            let m = world.metrics();
            m.overall.arrived_share >= 0.9 && m.overall.penetrations_agent_obstacle == 0
        })
        .expect("pillars arrive within 1500 steps");

    let printed = ok(flockpath(&["run", "--scene", file, "--steps", "1500"]));
    let lines: Vec<&str> = printed.lines().collect();
    assert_eq!(lines.len(), 2, "{printed}");
    assert!(lines[0].starts_with("pillars: 80 agents, 1500 steps"), "{printed}");
    assert_eq!(lines[1], format!("activity: met at step {met} (limit 1500), 2 of 2 conditions hold"));

    let early = ok(flockpath(&["run", "--scene", file, "--steps", "10"]));
    assert!(
        early.ends_with("\nactivity: not decided by step 10 (limit 1500), 1 of 2 conditions hold\n"),
        "{early}"
    );

    let json = flockpath(&["run", "--scene", file, "--steps", "10", "--metrics", "-"]);
    assert_eq!(
        stderr(&json),
        "flockpath: activity: not decided by step 10 (limit 1500), 1 of 2 conditions hold\n"
    );
    let metrics: serde_json::Value =
        serde_json::from_str(&ok(json)).expect("stdout is the metrics JSON alone");
    assert_eq!(metrics["steps"], 10);

    let plain = ok(flockpath_with_stdin(&["run", "--scene", "-", "--steps", "10"], &preset_json("pillars")));
    assert_eq!(plain.lines().count(), 1, "no check, no activity line: {plain}");
}

/// Regression (issue 24): `flockpath optimize --g0 NaN --alpha NaN` ran (GSA's best then 23,103
/// instead of 99.3), because the range check `x < lo || x > hi` is false for NaN; and
/// `flockpath tune --sample-every 1000000` (or 0) ran the GA on fitness that was 0 for every
/// chromosome, because no frame was ever sampled. Every float option now refuses a non-finite
/// value naming the option and its range, and the sample interval must lie in 1…--frames.
#[test]
fn non_finite_numbers_and_empty_sample_intervals_are_refused_by_option() {
    for (option, value, range) in [
        ("--g0", "NaN", "0…1000000000000"),
        ("--alpha", "NaN", "0…1000000"),
        ("--g0", "inf", "0…1000000000000"),
        ("--alpha", "-infinity", "0…1000000"),
    ] {
        let flag = format!("{option}={value}");
        let o =
            flockpath(&["optimize", "--algorithms", "gsa", "--functions", "sphere", "--runs", "1", &flag]);
        assert_eq!(o.status.code(), Some(2), "{flag} is a usage mistake: {}", stderr(&o));
        let err = stderr(&o);
        assert!(err.contains(option) && err.contains(range), "{flag}: names the option and its range: {err}");
        fails_naming(o, value);
    }
    for every in ["0", "1000000", "401"] {
        let o = flockpath(&[
            "tune",
            "--behaviour",
            "b1",
            "--environment",
            "e1",
            "--seed",
            "1",
            "--sample-every",
            every,
        ]);
        assert_eq!(o.status.code(), Some(2), "--sample-every {every}: {}", stderr(&o));
        fails_naming(o, &format!("--sample-every {every} is outside 1…400"));
    }
    let o = flockpath(&["tune", "--table", "--frames", "20", "--sample-every", "21"]);
    fails_naming(o, "--sample-every 21 is outside 1…20");
}

/// Regression (issue 24): `flockpath url` wrote a link `flockpath run` refused (a scene JSON
/// with a 7 MiB group name loaded, its link unpacked past the reader's limit). Now a scene that
/// loads has a link that loads: at the largest sizes a scene may have, url → run round-trips,
/// and the 7 MiB name is refused by `url` itself, naming the field and the limit.
#[test]
fn url_writes_only_links_that_run_reads_even_at_the_largest_sizes() {
    let (largest, _) = largest_scene::largest_scene();
    let json = temp_path("largest.json");
    std::fs::write(&json, serde_json::to_string(&largest).expect("JSON")).expect("temp file written");
    let link = ok(flockpath(&["url", json.to_str().expect("utf-8 path")]));
    std::fs::remove_file(&json).ok();
    let link = link.trim();
    assert!(link.len() > flockpath::model::codec::MAX_LINK_CHARS * 99 / 100, "{} characters", link.len());
    // A link this long does not fit in one command-line argument (128 KiB): run reads it from a file.
    let link_file = temp_path("largest-link.txt");
    std::fs::write(&link_file, link).expect("temp file written");
    let run = ok(flockpath(&["run", "--scene", link_file.to_str().expect("utf-8 path"), "--steps", "1"]));
    assert!(run.starts_with(&format!("{}:", largest.name)), "{}", run.chars().take(200).collect::<String>());
    std::fs::remove_file(&link_file).ok();

    let mut scene: serde_json::Value = serde_json::from_str(&preset_json("pillars")).expect("preset JSON");
    scene["groups"][0]["name"] = serde_json::json!("x".repeat(7 << 20));
    let file = temp_path("long-name.json");
    std::fs::write(&file, scene.to_string()).expect("temp file written");
    let o = flockpath(&["url", file.to_str().expect("utf-8 path")]);
    std::fs::remove_file(&file).ok();
    fails_naming(o, "groups[0].name is text of 7340032 character(s)");
}
