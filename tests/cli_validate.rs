//! `flockpath validate` and `flockpath run --pedpy`: the table, the JSON report, the CSV curves,
//! the links to the scenes and PedPy's text format; the periodic corridor the fundamental
//! diagrams run in. The measurements themselves are checked on hand-placed trajectories with
//! known answers in `src/experiments/validation/measure.rs` (unit tests); here the checks are
//! about what the command writes, not whether a planner passes.

use flockpath::experiments::validation::measure::{Frame, Trajectories};
use flockpath::experiments::validation::pedpy::trajectory_text;
use flockpath::{presets, scene_from_fragment, World};
use glam::Vec2;
use serde_json::Value;
use std::process::{Command, Output};

fn flockpath(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_flockpath")).args(args).output().expect("the binary runs")
}

fn temp(name: &str) -> std::path::PathBuf {
    std::env::temp_dir().join(format!("flockpath-cli-validate-{}-{name}", std::process::id()))
}

#[test]
fn validate_writes_the_table_the_json_and_the_csv_files() {
    let json = temp("report.json");
    let dir = temp("csv");
    let out = flockpath(&[
        "validate",
        "--tests",
        "t1,juelich-head-on",
        "--planners",
        "boids,forces",
        "--json",
        json.to_str().expect("utf-8 path"),
        "--csv-dir",
        dir.to_str().expect("utf-8 path"),
    ]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{stdout}\n{}", String::from_utf8_lossy(&out.stderr));
    assert!(stdout.contains("t1-free-walking") && stdout.contains("of 4 passed"), "{stdout}");
    let report: Value =
        serde_json::from_str(&std::fs::read_to_string(&json).expect("report written")).expect("JSON");
    assert_eq!(report["px_per_metre"], 20.0);
    let rows = report["rows"].as_array().expect("rows");
    assert_eq!(rows.len(), 4);
    let tests: Vec<&str> = rows.iter().filter_map(|r| r["test"].as_str()).collect();
    assert_eq!(tests, ["t1-free-walking", "t1-free-walking", "juelich-head-on", "juelich-head-on"]);
    for r in rows {
        assert!(r["pass"].is_boolean() && r["criterion"].as_str().is_some_and(|c| !c.is_empty()), "{r}");
        // Each row links to its scene, with the row's planner in every group.
        let scene = scene_from_fragment(r["scene"].as_str().expect("scene")).expect("a valid scene link");
        assert!(scene.name.starts_with("validate-"), "{}", scene.name);
        assert!(scene.groups.iter().all(|g| g.planner.kind().name() == r["planner"]), "{r}");
    }
    // T1 with one walker alone: the value is a speed in m/s, positive, at most the desired speed.
    let t1 = &rows[0];
    assert_eq!(t1["unit"], "m/s");
    let v = t1["value"].as_f64().expect("a speed");
    assert!(v > 0.0 && v <= 1.34 * 1.001, "{v}");
    let table = std::fs::read_to_string(dir.join("table.csv")).expect("table.csv");
    assert_eq!(table.lines().count(), 5, "{table}");
    assert!(table.starts_with("test,planner,value,unit,measured,criterion,pass\n"));
    assert!(table.lines().skip(1).all(|l| l.ends_with(",pass") || l.ends_with(",fail")), "{table}");
    let _ = std::fs::remove_file(&json);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Regression (issue 25 §1): `--pedpy-dir` wrote T4's runs only (re-running T4 whatever
/// `--tests` said), so no other test could be recounted outside the project. Now every test's
/// runs are written, one file each, named by test, planner and variant.
#[test]
fn pedpy_dir_writes_every_tests_runs() {
    let dir = temp("pedpy-dir");
    let out = flockpath(&[
        "validate",
        "--tests",
        "t1,juelich-rotation,juelich-head-on",
        "--planners",
        "orca",
        "--pedpy-dir",
        dir.to_str().expect("utf-8 path"),
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .expect("the directory is written")
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "juelich-head-on-orca.txt",
            "juelich-rotation-orca-0deg.txt",
            "juelich-rotation-orca-45deg.txt",
            "t1-free-walking-orca.txt",
        ]
    );
    // The head-on file: both walkers at frame 0 where the scene starts them (m), 1 cm apart.
    let text = std::fs::read_to_string(dir.join("juelich-head-on-orca.txt")).expect("written");
    assert!(text.contains("# framerate: 60.0000"), "{text:.200}");
    let first: Vec<&str> = text.lines().filter(|l| !l.starts_with('#')).take(2).collect();
    assert_eq!(first, ["1 0 2.0000 3.0000 0", "2 0 18.0000 3.0100 0"]);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn validate_refuses_unknown_names_with_usage_errors() {
    let out = flockpath(&["validate", "--tests", "t99"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("t4-fundamental-diagram"),
        "the message lists the tests"
    );
    let out = flockpath(&["validate", "--planners", "nope", "--tests", "t1"]);
    assert_eq!(out.status.code(), Some(2));
    let help = flockpath(&["validate", "--help"]);
    assert!(help.status.success());
    let text = String::from_utf8_lossy(&help.stdout);
    assert!(text.contains("--csv-dir") && text.contains("--pedpy-dir") && text.contains("RiMEA"), "{text}");
}

#[test]
fn run_pedpy_writes_metres_and_the_frame_rate() {
    let scene = temp("scene.json");
    std::fs::write(&scene, flockpath::scene_to_json(&(presets::find("open-field").expect("preset").build)()))
        .expect("scene written");
    let file = temp("pedpy.txt");
    let out = flockpath(&[
        "run",
        "--scene",
        scene.to_str().expect("utf-8"),
        "--steps",
        "10",
        "--pedpy",
        file.to_str().expect("utf-8"),
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = std::fs::read_to_string(&file).expect("written");
    assert!(text.contains("# framerate: 60.0000") && text.contains("x/m"), "{text}");
    let data: Vec<Vec<f64>> = text
        .lines()
        .filter(|l| !l.starts_with('#'))
        .map(|l| l.split(' ').map(|x| x.parse().expect("a number")).collect())
        .collect();
    // 60 agents × 11 frames (step 0 included), 5 columns, inside the 40 m × 25 m world.
    assert_eq!(data.len(), 60 * 11);
    assert!(data
        .iter()
        .all(|r| r.len() == 5 && (0.0..=40.0).contains(&r[2]) && (0.0..=25.0).contains(&r[3])));
    assert_eq!((data[0][0], data[0][1]), (1.0, 0.0));
    assert_eq!(data.last().map(|r| (r[0], r[1])), Some((60.0, 10.0)));
    let _ = std::fs::remove_file(&scene);
    let _ = std::fs::remove_file(&file);
}

/// Regression of the periodic corridor: an agent leaving the band re-enters at the other end,
/// so a T4 crowd keeps its density.
#[test]
fn a_periodic_band_keeps_every_agent_inside_it() {
    let mut scene = flockpath::Scene::empty(800.0, 40.0);
    scene.goals.push(flockpath::Goal::fixed([790.0, 20.0], 5.0));
    let mut group = (presets::find("open-field").expect("preset").build)().groups.remove(0);
    group.count = 3;
    group.spawn = flockpath::Region { min: [300.0, 5.0], max: [390.0, 35.0] };
    scene.groups.push(group);
    let starts = vec![Vec2::new(390.0, 10.0), Vec2::new(395.0, 20.0), Vec2::new(398.0, 30.0)];
    let mut world = World::new_at(scene, starts).expect("valid");
    world.set_periodic_x(Some((0.0, 400.0)));
    let mut wrapped = false;
    for _ in 0..600 {
        let before: Vec<f32> = world.positions().iter().map(|p| p.x).collect();
        world.step();
        for (b, p) in before.iter().zip(world.positions()) {
            assert!((0.0..400.0).contains(&p.x), "left the band: {p}");
            wrapped |= b - p.x > 200.0;
        }
    }
    assert!(wrapped, "someone walked across the seam");
}

#[test]
fn pedpy_ids_change_when_a_walker_wraps() {
    let traj = Trajectories {
        frame_s: 0.5,
        group: vec![0],
        frames: [19.0, 19.8, 0.6, 1.4]
            .iter()
            .map(|&x| Frame { pos: vec![Vec2::new(x, 1.0)], vel: vec![Vec2::ZERO] })
            .collect(),
    };
    let text = trajectory_text(&traj, Some(20.0), "wrap");
    let ids: Vec<&str> = text.lines().filter(|l| !l.starts_with('#')).map(|l| &l[..1]).collect();
    assert_eq!(ids, ["1", "1", "2", "2"]);
    assert!(text.contains("# framerate: 2.0000"));
}
