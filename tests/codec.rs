//! Codec properties: random scenes round-trip exactly through JSON and the URL fragment, every
//! preset does, every released fragment version still decodes to the scene it was made from,
//! and shared links stay well under 1,000 characters.
//!
//! Fixtures: `tests/data/fragments/v<N>/<name>.txt` holds a fragment written by the version-N
//! encoder and `<name>.json` the scene it must decode to. When the format changes, add a new
//! `v<N+1>/` folder and never edit the old ones: old links must keep loading.

use flockpath::model::geometry::Obstacle;
use flockpath::model::scene::{GoalMotion, ViewOptions};
use flockpath::rng::Rng;
use flockpath::{
    presets, scene_from_any, scene_from_fragment, scene_from_json, scene_to_fragment, scene_to_json, Goal,
    Group, PlannerKind, Region, Scene,
};
use std::path::Path;

/// A random valid scene: obstacles of every shape, goals, groups with random planners and
/// parameters drawn within their table ranges, a random view. Values are full-precision `f32`s
/// (harder for a text codec than the editor's 0.1 px grid).
fn random_scene(rng: &mut Rng) -> Scene {
    let width = rng.range(100.0, 3000.0);
    let height = rng.range(100.0, 3000.0);
    let mut s = Scene::empty(width, height);
    s.name = ["", "a scene", "ünïcødé \"quoted\" & <tagged>", "x"][rng.below(4) as usize].to_string();
    s.seed = rng.next_u32();
    let point = |rng: &mut Rng| [rng.range(0.0, width), rng.range(0.0, height)];
    for _ in 0..rng.below(4) {
        let mut goal = Goal::fixed(point(rng), rng.range(1.0, 100.0));
        goal.motion = match rng.below(3) {
            0 => {
                // A circle that stays inside the scene.
                let radius = rng.range(0.0, 0.25 * width.min(height));
                let center = [rng.range(radius, width - radius), rng.range(radius, height - radius)];
                Some(GoalMotion::Circle { center, radius, period_steps: rng.range(1.0, 10_000.0) })
            }
            1 => Some(GoalMotion::Polyline {
                points: (0..1 + rng.below(5)).map(|_| point(rng)).collect(),
                speed: rng.range(0.0, 5.0),
            }),
            _ => None,
        };
        s.goals.push(goal);
    }
    for _ in 0..rng.below(25) {
        let [x, y] = point(rng);
        let obstacle = match rng.below(3) {
            0 => Obstacle::Circle { center: [x, y], radius: rng.range(0.5, 80.0) },
            1 => Obstacle::Rect { min: [x, y], max: [x + rng.range(1.0, 200.0), y + rng.range(1.0, 200.0)] },
            _ => {
                // A star-shaped polygon: corners at increasing angles around (x, y) never make
                // edges cross (scenes hold simple polygons only).
                let n = 3 + rng.below(6);
                let sector = std::f32::consts::TAU / n as f32;
                Obstacle::Polygon {
                    points: (0..n)
                        .map(|k| {
                            let angle = sector * (k as f32 + rng.range(0.1, 0.9));
                            let r = rng.range(5.0, 60.0);
                            [x + r * angle.cos(), y + r * angle.sin()]
                        })
                        .collect(),
                }
            }
        };
        if !s.goals.iter().any(|g| obstacle.contains(glam::Vec2::from(g.position))) {
            s.obstacles.push(obstacle);
        }
    }
    for g in 0..rng.below(5) {
        let [x0, y0] = point(rng);
        let [x1, y1] = [rng.range(x0, width), rng.range(y0, height)];
        let kind = PlannerKind::ALL[rng.below(PlannerKind::ALL.len() as u32) as usize];
        let mut planner = kind.default_config();
        for spec in kind.param_specs() {
            // `path` names one of the scene's paths, and these scenes have none.
            if rng.below(2) == 0 || spec.key == "path" {
                continue;
            }
            let value = if spec.choices.is_empty() {
                // Snap to the slider's step, as the page does (integer parameters have step 1).
                let steps = ((spec.max - spec.min) / spec.step).floor();
                let x = spec.min + (steps * rng.unit_f64()).round() * spec.step;
                if spec.step.fract() == 0.0 {
                    serde_json::json!(x as i64)
                } else {
                    serde_json::json!(x)
                }
            } else {
                serde_json::json!(spec.choices[rng.below(spec.choices.len() as u32) as usize])
            };
            planner.set_param(spec.key, value).expect("a value inside the table range is accepted");
        }
        let goal = if s.goals.is_empty() || rng.below(4) == 0 {
            None
        } else {
            Some(rng.below(s.goals.len() as u32))
        };
        s.groups.push(Group {
            name: format!("group {g}"),
            color: format!("#{:06x}", rng.next_u32() & 0xff_ffff),
            count: rng.below(300),
            spawn: Region { min: [x0, y0], max: [x1, y1] },
            goal,
            agent_radius: rng.range(0.5, 100.0),
            planner,
        });
    }
    s.view = ViewOptions { trails: rng.below(2) == 0, trail_fade: rng.unit() };
    s
}

#[test]
fn random_scenes_round_trip_exactly_through_json_and_fragment() {
    let mut rng = Rng::new(2024, 0);
    for case in 0..500 {
        let scene = random_scene(&mut rng);
        scene.validate().unwrap_or_else(|e| panic!("case {case}: generator made an invalid scene: {e}"));
        assert_eq!(scene_from_json(&scene_to_json(&scene)).as_ref(), Ok(&scene), "case {case} (JSON)");
        let fragment = scene_to_fragment(&scene);
        assert!(fragment.starts_with("2."), "case {case}: {fragment}");
        assert!(fragment[2..].bytes().all(|b| b.is_ascii_alphanumeric() || b == b'-' || b == b'_'));
        assert_eq!(scene_from_fragment(&fragment).as_ref(), Ok(&scene), "case {case} (fragment)");
        let url = format!("https://example.org/notes/flockpath/index.html#s={fragment}&autoplay=1");
        assert_eq!(scene_from_any(&url).as_ref(), Ok(&scene), "case {case} (URL)");
    }
}

#[test]
fn every_preset_round_trips_and_its_link_is_short() {
    for p in presets::ALL {
        let scene = (p.build)();
        let fragment = scene_to_fragment(&scene);
        assert_eq!(scene_from_fragment(&fragment).as_ref(), Ok(&scene), "{}", p.name);
        // Presets with random clutter (forces-e3-cluttered) are the longest; the issue's bar is
        // 1,000 characters for 20 obstacles and 4 groups, tested below.
        assert!(fragment.len() < 600, "{}: {} characters", p.name, fragment.len());
        println!("preset {:16} fragment {:4} characters", p.name, fragment.len());
    }
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

#[test]
fn a_scene_with_20_obstacles_and_4_groups_fits_well_under_1000_characters() {
    let text = read(Path::new("tests/data/scenes/twenty-obstacles-four-groups.json"));
    let scene = scene_from_json(&text).expect("valid scene");
    assert_eq!((scene.obstacles.len(), scene.groups.len()), (20, 4));
    let fragment = scene_to_fragment(&scene);
    println!("20 obstacles, 4 groups: fragment {} characters", fragment.len());
    assert!(fragment.len() < 800, "{} characters", fragment.len());
    assert_eq!(scene_from_fragment(&fragment).as_ref(), Ok(&scene));
}

#[test]
fn every_released_fragment_version_still_decodes() {
    let root = Path::new("tests/data/fragments");
    let mut versions = 0;
    let mut checked = 0;
    let mut dirs: Vec<_> = std::fs::read_dir(root).expect("fixture folder").flatten().collect();
    dirs.sort_by_key(|d| d.file_name());
    for dir in dirs {
        let version = dir.file_name().to_string_lossy().trim_start_matches('v').to_string();
        versions += 1;
        for entry in std::fs::read_dir(dir.path()).expect("version folder").flatten() {
            let path = entry.path();
            if path.extension().is_none_or(|e| e != "txt") {
                continue;
            }
            let fragment = read(&path);
            assert!(fragment.starts_with(&format!("{version}.")), "{}: wrong version prefix", path.display());
            let expected = scene_from_json(&read(&path.with_extension("json")))
                .unwrap_or_else(|e| panic!("{}: expected scene invalid: {e}", path.display()));
            let decoded = scene_from_fragment(&fragment)
                .unwrap_or_else(|e| panic!("{}: no longer decodes: {e}", path.display()));
            assert_eq!(decoded, expected, "{}", path.display());
            checked += 1;
        }
    }
    assert!(versions >= 2, "fixtures of v1 and v2 expected, found {versions} folder(s)");
    assert!(checked >= 10, "only {checked} fixtures checked");
}

#[test]
fn the_current_encoder_still_writes_the_latest_fixtures() {
    // If this fails the format changed: add a new fixture folder instead of editing this one.
    let dir = Path::new("tests/data/fragments/v2");
    for entry in std::fs::read_dir(dir).expect("v2 fixtures").flatten() {
        let path = entry.path();
        if path.extension().is_some_and(|e| e == "txt") {
            let scene = scene_from_json(&read(&path.with_extension("json"))).expect("valid");
            assert_eq!(scene_to_fragment(&scene), read(&path).trim(), "{}", path.display());
        }
    }
}

#[test]
fn problems_are_named_in_the_message() {
    let scene = presets::corridor();
    let good = scene_to_fragment(&scene);
    let mut far_goal = scene.clone();
    far_goal.goals[0].position = [5000.0, 5000.0];
    let mut bad_fade = scene.clone();
    bad_fade.view.trail_fade = 3.0;
    let cases: Vec<(String, &[&str])> = vec![
        (good[..good.len() / 2].to_string(), &["truncated", "cut short"]),
        (format!("7.{}", &good[2..]), &["version"]),
        ("2.!!!!".into(), &["base64"]),
        ("Xno-prefix".into(), &["version prefix"]),
        ("no-such-preset".into(), &["unknown preset 'no-such-preset' (known: pillars, open-field"]),
        (scene_to_fragment(&far_goal), &["goals[0].position[0] is 5000; allowed: a number in 0…900 px"]),
        (scene_to_fragment(&bad_fade), &["view.trail_fade is 3; allowed: a number in 0…1"]),
    ];
    for (input, expected) in cases {
        let e = scene_from_any(&input).expect_err(&input).to_string();
        assert!(
            expected.iter().any(|x| e.contains(x)),
            "{input:?}: message {e:?} should mention {expected:?}"
        );
    }
}

#[test]
fn out_of_range_planner_parameters_in_a_link_are_refused_by_name() {
    // A hand-edited v2 payload with max_speed (the third Boids parameter) far outside its range.
    let json = r##"["x",400,300,1,[],[[350,150,20]],[["a","#ff0000",5,[10,10,60,60],0,4,"boids",[50,20,1e9]]],[true,0.01]]"##;
    let fragment = fragment_of(json);
    let e = scene_from_fragment(&fragment).expect_err("out of range").to_string();
    assert_eq!(e, "groups[0].planner.params.max_speed is 1e9; allowed: a number in 0.1…20 px/step");
    let unknown = fragment_of(&json.replace("\"boids\"", "\"warp\""));
    assert_eq!(
        scene_from_fragment(&unknown).expect_err("unknown").to_string(),
        "groups[0].planner.kind is \"warp\"; allowed: one of \"boids\", \"pso\", \"firefly\", \"forces\", \"igsa\", \"orca\", \"social_force\", \"collision_free_speed\""
    );
}

fn fragment_of(json: &str) -> String {
    use base64::Engine as _;
    let packed = miniz_oxide::deflate::compress_to_vec(json.as_bytes(), 9);
    format!("2.{}", base64::engine::general_purpose::URL_SAFE_NO_PAD.encode(packed))
}

/// A garbled scene of each shape fault is refused as a `scene.field` message whose typed
/// arguments name the field, its value as written and what is allowed, worded from what the
/// scene's types report (`model::shape`), not from the JSON parser's English; and the typed
/// check itself reports each fault as data.
#[test]
fn each_kind_of_garbled_scene_gives_its_code_and_arguments() {
    use flockpath::model::refusal::{Arg, Code, Message, Refusal};
    use flockpath::model::shape::{check, Expected, Fault};

    let base: serde_json::Value = serde_json::from_str(&scene_to_json(&presets::corridor())).expect("json");
    let garbled = |edit: &dyn Fn(&mut serde_json::Value)| {
        let mut json = base.clone();
        edit(&mut json);
        json
    };
    let unknown_key = garbled(&|j| j["widht"] = 800.into());
    let wrong_kind = garbled(&|j| j["width"] = "abc".into());
    let missing = garbled(&|j| {
        j.as_object_mut().expect("object").remove("height");
    });
    let bad_tag = garbled(&|j| j["obstacles"][0]["shape"] = "hexagon".into());
    let short_tuple = garbled(&|j| j["groups"][0]["spawn"]["min"] = serde_json::json!([1]));
    let negative_seed = garbled(&|j| j["seed"] = (-1).into());
    let unknown: Message = Message::new(Code::ValueUnknownKey);
    let missing_value: Message = Message::new(Code::ValueMissing);
    // `None`: the value is the refused object as written, not pinned here.
    let cases: Vec<(String, &str, Option<Arg>, &str)> = vec![
        (unknown_key.to_string(), "widht", Some(unknown.into()), "one of the keys \"name\", \"width\""),
        (wrong_kind.to_string(), "width", Some("\"abc\"".into()), "a number in 10…20000 px"),
        (missing.to_string(), "height", Some(missing_value.into()), "a number in 10…20000 px"),
        (
            bad_tag.to_string(),
            "obstacles[0].shape",
            Some("\"hexagon\"".into()),
            "\"circle\", \"rect\" or \"polygon\"",
        ),
        (short_tuple.to_string(), "groups[0].spawn.min", Some("[1]".into()), "a list of 2 numbers"),
        (negative_seed.to_string(), "seed", Some("-1".into()), "a whole number 0…4294967295"),
        // Words JSON does not have, found in the text where the parser stopped.
        (
            base.to_string().replacen("\"width\":900.0", "\"width\":NaN", 1),
            "width",
            Some("NaN".into()),
            "a number in 10…20000 px",
        ),
        (
            base.to_string().replacen("\"height\":500.0", "\"height\":1e999", 1),
            "height",
            Some("1e999".into()),
            "a number in 10…20000 px",
        ),
    ];
    for (text, path, value, allowed) in cases {
        let error = scene_from_json(&text).expect_err(path);
        let message = error.message();
        assert_eq!(message.code, Code::SceneField, "{error}");
        assert_eq!(message.arg("path"), Some(&Arg::from(path)), "{error}");
        if let Some(value) = value {
            assert_eq!(message.arg("value"), Some(&value), "{error}");
        }
        let words = message.arg_text("allowed").expect("allowed");
        assert!(
            words.starts_with(allowed),
            "{path}: allowed {words:?}, expected it to start with {allowed:?}"
        );
    }

    // The typed check reports the fault and what the type asked for as data.
    let fault = |json: &serde_json::Value| check::<Scene>(json).expect_err("garbled");
    let (_, e) = fault(&unknown_key);
    assert!(
        matches!(&e.fault, Fault::UnknownKey { name, known } if name == "widht" && known.contains(&"width")),
        "{e}"
    );
    let (_, e) = fault(&wrong_kind);
    assert_eq!((e.fault, e.expected), (Fault::WrongKind, Some(Expected::Number)));
    let (_, e) = fault(&missing);
    assert_eq!(e.fault, Fault::MissingKey { name: "height" });
    let (_, e) = fault(&bad_tag);
    assert!(
        matches!(&e.fault, Fault::UnknownVariant { name, known } if name == "hexagon" && known.contains(&"rect")),
        "{e}"
    );
    let (_, e) = fault(&short_tuple);
    assert_eq!((e.fault, e.expected), (Fault::Length { len: 1 }, Some(Expected::ListOf(2))));
    let (_, e) = fault(&negative_seed);
    assert_eq!(
        (e.fault, e.expected),
        (Fault::BadValue { text: None }, Some(Expected::Whole { max: u32::MAX.into() }))
    );
}
