//! `flockpath run` exports: the CLI writes paths CSV/JSON, Maya MEL, Blender Python and SVG for a
//! scene given as a shared link, and each file holds the run it claims to (one CSV row per agent
//! per step, parsing back to the same final state the digest covers).

use flockpath::{presets, scene_to_fragment, World};
use std::path::PathBuf;
use std::process::{Command, Output};

fn flockpath(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_flockpath")).args(args).output().expect("the binary runs")
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("flockpath-cli-export-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

const STEPS: u32 = 40;

#[test]
fn run_writes_every_export_for_a_shared_link() {
    let scene = presets::open_field();
    let url = format!("https://example.org/course/flockpath/index.html#s={}", scene_to_fragment(&scene));
    let dir = temp_dir("all");
    let file = |name: &str| dir.join(name).to_string_lossy().into_owned();
    let steps = STEPS.to_string();
    let output = flockpath(&[
        "run",
        "--scene",
        &url,
        "--steps",
        &steps,
        "--paths",
        &file("paths.csv"),
        "--paths-json",
        &file("paths.json"),
        "--maya",
        &file("crowd.mel"),
        "--blender",
        &file("crowd.py"),
        "--svg",
        &file("trails.svg"),
        "--fps",
        "30",
        "--scale",
        "0.5",
    ]);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));

    let mut world = World::new(scene.clone()).expect("valid");
    world.step_n(STEPS);
    let agents = world.agent_count();

    // CSV: header, then one row per agent per recorded step (0..=STEPS), parsing back.
    let csv = std::fs::read_to_string(file("paths.csv")).expect("csv written");
    let mut rows = csv.lines();
    assert_eq!(rows.next(), Some("agent,group,step,time,x,y,vx,vy"));
    let parsed: Vec<Vec<f64>> = rows
        .map(|r| r.split(',').map(|x| x.parse::<f64>().expect("every field is a number")).collect())
        .collect();
    assert_eq!(parsed.len(), agents * (STEPS as usize + 1));
    assert!(parsed.iter().all(|r| r.len() == 8));
    let last_step: Vec<&Vec<f64>> = parsed.iter().filter(|r| r[2] == f64::from(STEPS)).collect();
    assert_eq!(last_step.len(), agents);
    for (row, (p, v)) in last_step.iter().zip(world.positions().iter().zip(world.velocities())) {
        // f32 written with its shortest representation parses back to the same f32.
        assert_eq!([row[4] as f32, row[5] as f32, row[6] as f32, row[7] as f32], [p.x, p.y, v.x, v.y]);
    }

    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(file("paths.json")).expect("json written"))
            .expect("paths JSON parses");
    assert_eq!(json["agents"].as_array().map(Vec::len), Some(agents));
    assert_eq!(json["steps"].as_array().map(Vec::len), Some(STEPS as usize + 1));

    // MEL: every statement ends with `;`, 30 fps is Maya's "ntsc", one locator per agent, and
    // the scale was applied (the scene is 800 px wide: x ≤ 400 units at scale 0.5).
    let mel = std::fs::read_to_string(file("crowd.mel")).expect("mel written");
    assert!(mel.contains("currentUnit -time ntsc;"));
    assert_eq!(mel.matches("spaceLocator").count(), agents);
    assert!(mel.lines().all(|l| l.is_empty() || l.starts_with("//") || l.ends_with(';')));
    let xs: Vec<f32> = mel
        .lines()
        .filter(|l| l.contains("translateX"))
        .filter_map(|l| l.split("-value ").nth(1)?.split(' ').next()?.parse().ok())
        .collect();
    assert!(!xs.is_empty() && xs.iter().all(|&x| (0.0..=400.0).contains(&x)));

    // Python: compiles.
    let py = file("crowd.py");
    assert!(std::fs::read_to_string(&py).expect("py written").contains("scene.render.fps = 30"));
    let status = Command::new("python3").args(["-m", "py_compile", &py]).status().expect("python3 runs");
    assert!(status.success(), "py_compile rejected the Blender script");

    let svg = std::fs::read_to_string(file("trails.svg")).expect("svg written");
    assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
    assert_eq!(svg.matches("<polyline").count(), agents);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bad_export_options_and_unwritable_files_are_named() {
    let fragment = scene_to_fragment(&presets::open_field());
    let cases: [(&[&str], &str); 3] = [
        (&["--paths", "/no/such/dir/p.csv"], "--paths"),
        (&["--maya", "x.mel", "--scale", "-1"], "scale"),
        (&["--blender", "x.py", "--fps", "fast"], "--fps"),
    ];
    for (extra, needle) in cases {
        let mut args = vec!["run", "--scene", &fragment, "--steps", "3"];
        args.extend_from_slice(extra);
        let output = flockpath(&args);
        let err = String::from_utf8_lossy(&output.stderr);
        assert!(!output.status.success(), "{extra:?} should fail");
        assert!(err.contains(needle), "{extra:?}: {err}");
    }
}
