//! Refusals in the user's words: for each bad input, the message names the field by its path in
//! the scene JSON, shows the value as typed, and states what is allowed. The same problems in a
//! link's compact form are named with the same paths. Also the rules for what is accepted: a
//! byte-order mark, empty scenes and empty groups, preset names.

use base64::engine::general_purpose::URL_SAFE_NO_PAD;
use base64::Engine as _;
use flockpath::model::scene::{field_limits, SceneError};
use flockpath::{presets, scene_from_any, scene_to_json, Scene, World};
use serde_json::{json, Value};

/// A small valid scene as JSON: one goal, one Boids group, one circle obstacle, one hill.
fn base() -> Value {
    json!({
        "name": "base",
        "width": 400,
        "height": 300,
        "seed": 1,
        "obstacles": [{ "shape": "circle", "center": [200, 150], "radius": 30 }],
        "goals": [{ "position": [350, 150], "radius": 20, "motion": null }],
        "groups": [{
            "name": "a",
            "color": "#ff0000",
            "count": 10,
            "spawn": { "min": [10, 10], "max": [60, 60] },
            "goal": 0,
            "agent_radius": 4,
            "planner": { "kind": "boids", "params": { "max_speed": 2, "path": 0 } }
        }],
        "view": { "trails": true, "trail_fade": 0.01 },
        "hills": [{ "center": [100, 250], "radius": 40, "height": 10 }]
    })
}

/// `base()` with the value at `pointer` (a JSON pointer) replaced.
fn with(pointer: &str, value: Value) -> String {
    let mut scene = base();
    *scene.pointer_mut(pointer).unwrap_or_else(|| panic!("no {pointer} in the base scene")) = value;
    scene.to_string()
}

/// `base()` with the number at `pointer` replaced by `word`, which JSON cannot hold (NaN, 1e999).
fn with_word(pointer: &str, word: &str) -> String {
    with(pointer, json!("@@")).replace("\"@@\"", word)
}

/// `base()` with an extra key in the object at `pointer`.
fn with_key(pointer: &str, key: &str) -> String {
    let mut scene = base();
    let object = scene.pointer_mut(pointer).and_then(Value::as_object_mut).expect("an object");
    object.insert(key.to_string(), json!(1));
    scene.to_string()
}

/// A version 2 link holding `json` as its payload.
fn fragment_of(json: &str) -> String {
    let packed = miniz_oxide::deflate::compress_to_vec(json.as_bytes(), 9);
    format!("2.{}", URL_SAFE_NO_PAD.encode(packed))
}

/// The compact (version 2) form of `base()`, with `edit` applied to its text.
fn compact(edit: impl Fn(&str) -> String) -> String {
    let text = r##"["base",400,300,1,[[200,150,30]],[[350,150,20]],[["a","#ff0000",10,[10,10,60,60],0,4,"boids",[50,14,2]]],[true,0.01],[[],[[100,250,40,10]]]]"##;
    assert!(scene_from_any(&fragment_of(text)).is_ok(), "the compact base scene loads");
    fragment_of(&edit(text))
}

/// Asserts that `input` is refused with a message holding `path`, `value` and `allowed`.
fn refused(what: &str, input: &str, path: &str, value: &str, allowed: &str) {
    let error = scene_from_any(input).expect_err(what);
    let message = error.to_string();
    for (part, expected) in [("path", path), ("value", value), ("limit", allowed)] {
        assert!(
            message.contains(expected),
            "{what}: the message should name the {part} {expected:?}: {message}"
        );
    }
    assert!(!message.contains("line 1 column"), "{what}: parser positions belong in the details: {message}");
}

#[test]
fn type_errors_and_non_numbers_name_the_field_the_value_and_the_limit() {
    let cases: Vec<(&str, String, &str, &str, &str)> = vec![
        ("text for a number", with("/width", json!("abc")), "width", "\"abc\"", "a number in 10…20000 px"),
        ("NaN", with_word("/width", "NaN"), "width", "NaN", "10…20000 px"),
        ("Infinity", with_word("/height", "Infinity"), "height", "Infinity", "10…20000 px"),
        ("-Infinity", with_word("/height", "-Infinity"), "height", "-Infinity", "10…20000 px"),
        ("overflowing JSON", with_word("/width", "1e999"), "width", "1e999", "10…20000 px"),
        ("overflowing f32", with_word("/width", "1e39"), "width", "1e39", "10…20000 px"),
        (
            "text for a parameter",
            with("/groups/0/planner/params/max_speed", json!("fast")),
            "groups[0].planner.params.max_speed",
            "\"fast\"",
            "a number in 0.1…20 px/step",
        ),
        (
            "NaN for a parameter",
            with_word("/groups/0/planner/params/max_speed", "NaN"),
            "groups[0].planner.params.max_speed",
            "NaN",
            "0.1…20 px/step",
        ),
        (
            "a parameter past f32",
            with_word("/groups/0/planner/params/max_speed", "1e39"),
            "groups[0].planner.params.max_speed",
            "1e39",
            "0.1…20 px/step",
        ),
        (
            "text inside an obstacle",
            with("/obstacles/0/radius", json!("abc")),
            "obstacles[0].radius",
            "\"abc\"",
            "above 0 and at most 20000 px",
        ),
        (
            "null inside an obstacle",
            with("/obstacles/0/center/0", json!(null)),
            "obstacles[0].center[0]",
            "null",
            "within 20000 px of the world",
        ),
        (
            "text inside a goal's motion",
            with(
                "/goals/0/motion",
                json!({ "kind": "circle", "center": [300, "x"], "radius": 5, "period_steps": 10 }),
            ),
            "goals[0].motion.center[1]",
            "\"x\"",
            "a number",
        ),
        (
            "an unknown key in an obstacle",
            with_key("/obstacles/0", "colour"),
            "obstacles[0].colour",
            "an unknown key",
            "\"radius\"",
        ),
        ("a negative count", with("/groups/0/count", json!(-5)), "groups[0].count", "-5", "0…200000"),
        ("a fractional count", with("/groups/0/count", json!(2.5)), "groups[0].count", "2.5", "0…200000"),
        (
            "an unknown shape",
            with("/obstacles/0/shape", json!("hexagon")),
            "obstacles[0].shape",
            "\"hexagon\"",
            "\"circle\", \"rect\" or \"polygon\"",
        ),
        (
            "a list for a colour",
            with("/groups/0/color", json!([1, 2])),
            "groups[0].color",
            "[1,2]",
            "#rrggbb",
        ),
        (
            "a missing width",
            {
                let mut s = base();
                s.as_object_mut().expect("object").remove("width");
                s.to_string()
            },
            "width",
            "missing",
            "10…20000 px",
        ),
        ("an unknown top-level key", with_key("", "colour"), "colour", "an unknown key", "\"width\""),
        (
            "an unknown key in a group",
            with_key("/groups/0", "size"),
            "groups[0].size",
            "an unknown key",
            "\"agent_radius\"",
        ),
        (
            "an unknown key in planner",
            with_key("/groups/0/planner", "speed"),
            "groups[0].planner.speed",
            "an unknown key",
            "\"params\"",
        ),
        (
            "an unknown planner parameter",
            with_key("/groups/0/planner/params", "warp"),
            "groups[0].planner.params.warp",
            "an unknown key",
            "\"max_speed\"",
        ),
        (
            "an unknown planner",
            with("/groups/0/planner/kind", json!("warp")),
            "groups[0].planner.kind",
            "\"warp\"",
            "\"boids\"",
        ),
    ];
    for (what, input, path, value, allowed) in cases {
        refused(what, &input, path, value, allowed);
    }
}

#[test]
fn out_of_range_values_name_the_field_the_value_and_the_limit() {
    let cases: Vec<(&str, String, &str, &str, &str)> = vec![
        (
            "a huge radius",
            with("/obstacles/0/radius", json!(1e30)),
            "obstacles[0].radius",
            "1e30",
            "at most 20000 px",
        ),
        ("a zero radius", with("/obstacles/0/radius", json!(0)), "obstacles[0].radius", "is 0;", "above 0"),
        (
            "a far obstacle",
            with("/obstacles/0/center/0", json!(1e30)),
            "obstacles[0].center[0]",
            "1e30",
            "within 20000 px of the world",
        ),
        (
            "a far hill",
            with("/hills/0/center/1", json!(-1e30)),
            "hills[0].center[1]",
            "-1e30",
            "within 20000 px of the world",
        ),
        ("a hill too high", with("/hills/0/height", json!(20000)), "hills[0].height", "20000", "0…10000 px"),
        (
            "a parameter too large",
            with("/groups/0/planner/params/max_speed", json!(1e9)),
            "groups[0].planner.params.max_speed",
            "1e9",
            "0.1…20 px/step",
        ),
        (
            "a tiny agent",
            with("/groups/0/agent_radius", json!(0.1)),
            "groups[0].agent_radius",
            "0.1",
            "0.5…100 px",
        ),
        (
            "a goal out of the world",
            with("/goals/0/position/0", json!(5000)),
            "goals[0].position[0]",
            "5000",
            "0…400 px",
        ),
        ("a negative goal radius", with("/goals/0/radius", json!(-1)), "goals[0].radius", "-1", "above 0"),
        (
            "a goal that does not exist",
            with("/groups/0/goal", json!(3)),
            "groups[0].goal",
            "3",
            "goal index 0…0",
        ),
        (
            "a path that does not exist",
            with("/groups/0/planner/params/path", json!(2)),
            "groups[0].planner.params.path",
            "2",
            "the scene has no paths",
        ),
        (
            "a spawn region outside",
            with("/groups/0/spawn/max/1", json!(301)),
            "groups[0].spawn.max[1]",
            "301",
            "0…300 px",
        ),
        ("a bad colour", with("/groups/0/color", json!("red")), "groups[0].color", "\"red\"", "#rrggbb"),
        (
            "too many agents",
            with("/groups/0/count", json!(300_000)),
            "groups[0].count",
            "300000",
            "at most 200000",
        ),
        ("a world too wide", with("/width", json!(50_000)), "width", "50000", "10…20000 px"),
        ("a trail fade above 1", with("/view/trail_fade", json!(3)), "view.trail_fade", "3", "0…1"),
        (
            "a crossing polygon",
            with(
                "/obstacles/0",
                json!({ "shape": "polygon", "points": [[100, 100], [200, 200], [200, 100], [100, 200]] }),
            ),
            "obstacles[0].points",
            "edges 0→1 and 2→3 cross",
            "a simple polygon",
        ),
        (
            "a polygon with no area",
            with(
                "/obstacles/0",
                json!({ "shape": "polygon", "points": [[100, 100], [150, 100], [200, 100]] }),
            ),
            "obstacles[0].points",
            "no area",
            "non-zero area",
        ),
        (
            "a polygon folding back",
            with(
                "/obstacles/0",
                json!({ "shape": "polygon", "points": [[100, 100], [200, 100], [150, 100], [150, 50]] }),
            ),
            "obstacles[0].points",
            "fold back",
            "a simple polygon",
        ),
        (
            "a polygon of two points",
            with("/obstacles/0", json!({ "shape": "polygon", "points": [[100, 100], [200, 100]] })),
            "obstacles[0].points",
            "a list of 2",
            "3…1000 points",
        ),
        (
            "a flat rectangle",
            with("/obstacles/0", json!({ "shape": "rect", "min": [100, 100], "max": [100, 200] })),
            "obstacles[0].min[0]",
            "100",
            "below max[0]",
        ),
    ];
    for (what, input, path, value, allowed) in cases {
        refused(what, &input, path, value, allowed);
    }
}

#[test]
fn a_link_names_the_same_fields_as_the_json() {
    let cases: Vec<(&str, String, &str, &str, &str)> = vec![
        (
            "a parameter too large",
            compact(|t| t.replace("[50,14,2]", "[50,14,1e9]")),
            "groups[0].planner.params.max_speed",
            "1e9",
            "0.1…20 px/step",
        ),
        (
            "text for a parameter",
            compact(|t| t.replace("[50,14,2]", "[50,\"x\",2]")),
            "groups[0].planner.params.separation_radius",
            "\"x\"",
            "px",
        ),
        (
            "NaN for a radius",
            compact(|t| t.replace("[200,150,30]", "[200,150,NaN]")),
            "obstacles[0].radius",
            "NaN",
            "above 0",
        ),
        (
            "a huge radius",
            compact(|t| t.replace("[200,150,30]", "[200,150,1e30]")),
            "obstacles[0].radius",
            "1e30",
            "at most 20000 px",
        ),
        (
            "text for a count",
            compact(|t| t.replace("\"#ff0000\",10", "\"#ff0000\",\"x\"")),
            "groups[0].count",
            "\"x\"",
            "0…200000",
        ),
        ("a width of 1e999", compact(|t| t.replacen("400", "1e999", 1)), "width", "1e999", "10…20000 px"),
        (
            "a malformed obstacle",
            compact(|t| t.replace("[200,150,30]", "[200,150]")),
            "obstacles[0]",
            "[200,150]",
            "a circle [x, y, radius]",
        ),
        (
            "a spawn corner outside",
            compact(|t| t.replace("[10,10,60,60]", "[10,10,60,900]")),
            "groups[0].spawn.max[1]",
            "900",
            "0…300 px",
        ),
        (
            "a far hill",
            compact(|t| t.replace("[100,250,40,10]", "[1e30,250,40,10]")),
            "hills[0].center[0]",
            "1e30",
            "within 20000 px",
        ),
        (
            "an unknown planner",
            compact(|t| t.replace("\"boids\"", "\"warp\"")),
            "groups[0].planner.kind",
            "\"warp\"",
            "\"boids\"",
        ),
        (
            "an unknown extra parameter",
            compact(|t| t.replace("[50,14,2]", "[50,14,2,{\"warp\":1}]")),
            "groups[0].planner.params.warp",
            "an unknown key",
            "\"max_speed\"",
        ),
        (
            "a trail fade of 3",
            compact(|t| t.replace("[true,0.01]", "[true,3]")),
            "view.trail_fade",
            "3",
            "0…1",
        ),
        (
            "a goal that does not exist",
            compact(|t| t.replace("60,60],0,4", "60,60],5,4")),
            "groups[0].goal",
            "5",
            "goal index 0…0",
        ),
    ];
    for (what, input, path, value, allowed) in cases {
        refused(what, &input, path, value, allowed);
    }
}

#[test]
fn words_json_cannot_hold_are_found_after_any_text() {
    // serde_json counts columns in bytes: the word is found after multi-byte names and in files
    // with Windows line ends.
    let unicode = with("/name", json!("ünïcødé ✓")).replace("\"width\":400", "\"width\":NaN");
    refused("NaN after non-ASCII text", &unicode, "width", "NaN", "10…20000 px");
    let windows = serde_json::to_string_pretty(&base()).expect("json").replace('\n', "\r\n");
    let windows = windows.replace("\"height\": 300", "\"height\": -Infinity");
    refused("-Infinity in a CRLF file", &windows, "height", "-Infinity", "10…20000 px");
}

#[test]
fn the_parsers_own_words_are_kept_as_details() {
    let error = scene_from_any(&with("/width", json!("abc"))).expect_err("refused");
    let detail = error.detail().expect("a parser error carries its details");
    assert!(detail.contains("invalid type") && detail.contains("column"), "{detail}");
    assert!(!error.to_string().contains("invalid type"), "{error}");
}

#[test]
fn sizes_over_the_limits_are_too_large() {
    let padding = " ".repeat(8 << 20);
    let big = format!("{}{padding}", with("/width", json!(400)));
    let message = scene_from_any(&big).expect_err("too large").to_string();
    assert!(message.contains("too large") && message.contains("limit 8388608 bytes"), "{message}");
    // A link whose payload inflates past the unpacking limit (a deflate bomb).
    let bomb = fragment_of(&format!("[\"x\"{}]", " ".repeat(5 << 20)));
    assert!(bomb.len() < 20_000, "the bomb is a short link ({} characters)", bomb.len());
    let message = scene_from_any(&bomb).expect_err("too large").to_string();
    assert_eq!(message, "the unpacked scene string is too large (limit 4194304 bytes)");
}

#[test]
fn a_byte_order_mark_is_accepted() {
    let text = with("/width", json!(400));
    let plain = scene_from_any(&text).expect("loads");
    assert_eq!(scene_from_any(&format!("\u{feff}{text}")), Ok(plain.clone()));
    assert_eq!(scene_from_any(&format!("\u{feff}{}", flockpath::scene_to_fragment(&plain))), Ok(plain));
}

#[test]
fn preset_names_load_and_unknown_ones_list_the_known() {
    assert_eq!(scene_from_any("pillars"), Ok(presets::pillars()));
    let error = scene_from_any(" no-such-preset ").expect_err("unknown");
    let known: Vec<&str> = presets::ALL.iter().map(|p| p.name).collect();
    assert_eq!(error.to_string(), format!("unknown preset 'no-such-preset' (known: {})", known.join(", ")));
    assert!(matches!(error, SceneError::UnknownPreset { .. }));
    // A pasted payload without its version is not taken for a preset name.
    let message = scene_from_any("eJzT0yMAAGTvBe8").expect_err("no version").to_string();
    assert!(message.contains("version prefix"), "{message}");
}

#[test]
fn empty_scenes_and_empty_groups_are_accepted_and_run() {
    // An empty canvas is where the editor starts; a group of 0 agents spawns nothing.
    let empty = r#"{"width": 400, "height": 300}"#;
    let scene = scene_from_any(empty).expect("an empty scene loads");
    assert_eq!((scene.obstacles.len(), scene.goals.len(), scene.groups.len()), (0, 0, 0));
    let none = with("/groups/0/count", json!(0));
    let scene: Scene = scene_from_any(&none).expect("a group of 0 agents loads");
    for scene in [scene_from_any(empty).expect("loads"), scene] {
        let mut world = World::new(scene).expect("runs");
        for _ in 0..5 {
            world.step();
        }
        assert_eq!(world.agent_count(), 0);
    }
}

#[test]
fn every_preset_survives_the_stricter_checks() {
    for p in presets::ALL {
        let scene = (p.build)();
        assert_eq!(scene.validate(), Ok(()), "{}", p.name);
        assert_eq!(scene_from_any(&scene_to_json(&scene)).as_ref(), Ok(&scene), "{}", p.name);
    }
}

#[test]
fn the_readme_lists_every_limit() {
    let readme = std::fs::read_to_string("README.md").expect("README.md");
    for limit in field_limits() {
        let row = format!("| `{}` | {} | {} |", limit.field, limit.allowed, limit.why);
        assert!(readme.contains(&row), "README's limits table lacks the row\n{row}");
    }
}
