//! Browser tests of the wasm API in headless Chromium (`bash scripts/test-wasm.sh`): the wasm
//! build reproduces the native golden digest bit for bit, draws obstacles in their colour, and
//! turns bad input into JS errors that leave the running scene untouched.
#![cfg(target_arch = "wasm32")]

use flockpath::render::OBSTACLE_COLOR;
use flockpath::web::{planners_json, preset_scene_json, presets_json, scene_from_text, Sim};
use flockpath::{scene_from_json, scene_to_fragment, Obstacle};
use wasm_bindgen::{JsCast, JsValue};
use wasm_bindgen_test::{wasm_bindgen_test, wasm_bindgen_test_configure};

wasm_bindgen_test_configure!(run_in_browser);

/// Digest of preset `pillars`, seed 7, after 300 steps, from a native run.
const GOLDEN_DIGEST: &str = include_str!("data/golden-digest.txt");

fn pillars() -> String {
    preset_scene_json("pillars").expect("preset exists")
}

/// The message of the JS `Error` a call threw.
fn message(e: impl Into<JsValue>) -> String {
    let value: JsValue = e.into();
    let error: &js_sys::Error = value.dyn_ref().expect("a JS Error");
    String::from(error.message())
}

/// The frame as the page sees it: a view on wasm memory at `frame_ptr`, copied out.
fn frame(sim: &Sim) -> Vec<u8> {
    // Allocate first: growing wasm memory detaches every view made before.
    let mut out = vec![0u8; sim.frame_len() as usize];
    let memory: js_sys::WebAssembly::Memory = wasm_bindgen::memory().dyn_into().expect("memory");
    let bytes = js_sys::Uint8Array::new(&memory.buffer());
    let start = sim.frame_ptr();
    bytes.subarray(start, start + sim.frame_len()).copy_to(&mut out);
    out
}

#[wasm_bindgen_test]
fn the_golden_digest_matches_the_native_run() {
    let mut sim = Sim::new(&pillars(), 64, 64).expect("starts");
    sim.set_seed(7).expect("reseeds");
    sim.step(300);
    assert_eq!(sim.steps(), 300);
    assert_eq!(sim.digest(), GOLDEN_DIGEST.trim());
}

#[wasm_bindgen_test]
fn the_golden_url_replays_the_native_digest() {
    // The same link the native test `tests/golden_url.rs` runs, loaded as the page would.
    let url = include_str!("data/golden-url.txt").trim();
    let mut sim = Sim::new(url, 64, 64).expect("the golden link loads");
    assert_eq!(sim.seed(), 7);
    sim.step(300);
    assert_eq!(sim.digest(), GOLDEN_DIGEST.trim());
    // Reloading the link the Sim writes itself replays the same run.
    let mut again = Sim::new(&sim.scene_string(), 64, 64).expect("its own link loads");
    again.step(300);
    assert_eq!(again.digest(), sim.digest());
}

#[wasm_bindgen_test]
fn the_recording_exports_the_run_and_view_options_travel_in_the_link() {
    let mut sim = Sim::new(&pillars(), 64, 64).expect("starts");
    sim.step(10);
    let csv = sim.export_paths_csv();
    assert_eq!(csv.lines().count(), 1 + 11 * 80, "header + 80 agents x steps 0..=10");
    assert!(sim.export_maya_mel(24.0, 0.01).expect("mel").contains("spaceLocator"));
    assert!(sim.export_blender_py(0.0, 0.01).is_err(), "0 fps is refused");
    sim.set_trails(false).expect("trails off");
    sim.set_trail_fade(0.05).expect("fade");
    assert!(sim.set_trail_fade(2.0).is_err(), "fade outside 0..1 is refused");
    assert_eq!(sim.steps(), 10, "view changes do not restart the run");
    let other = Sim::new(&sim.scene_string(), 64, 64).expect("link loads");
    let view = scene_from_json(&other.scene_json()).expect("valid").view;
    assert_eq!((view.trails, view.trail_fade), (false, 0.05));
    sim.reset().expect("resets");
    assert_eq!(sim.export_paths_csv().lines().count(), 1 + 80, "a reset starts a new recording");
}

#[wasm_bindgen_test]
fn obstacles_are_drawn_in_the_obstacle_colour() {
    let mut sim = Sim::new(&pillars(), 450, 280).expect("starts");
    sim.step(5);
    sim.render();
    let (w, h) = (sim.width(), sim.height());
    let pixels = frame(&sim);
    assert_eq!(pixels.len(), (w * h * 4) as usize);
    let view = sim.view();
    let scene = scene_from_json(&sim.scene_json()).expect("valid");
    assert!(!scene.obstacles.is_empty());
    for obstacle in &scene.obstacles {
        let Obstacle::Circle { center, .. } = obstacle else { panic!("pillars are circles") };
        let x = (center[0] * view[0] + view[1]) as usize;
        let y = (center[1] * view[0] + view[2]) as usize;
        let at = (y * w as usize + x) * 4;
        let [r, g, b] = OBSTACLE_COLOR;
        assert_eq!(pixels[at..at + 4], [r, g, b, 255], "obstacle at {center:?}");
    }
}

#[wasm_bindgen_test]
fn bad_scenes_are_js_errors_and_the_run_goes_on() {
    let mut sim = Sim::new(&pillars(), 120, 80).expect("starts");
    sim.step(25);
    let scene_before = sim.scene_json();
    let digest_before = sim.digest();

    let good = scene_from_json(&pillars()).expect("valid");
    let fragment = scene_to_fragment(&good);
    let mut crowd = good.clone();
    crowd.groups[0].count = 10_000_000;
    let mut blocked = good.clone();
    blocked.obstacles.push(Obstacle::Circle { center: good.goals[0].position, radius: 30.0 });
    let nan_json = pillars().replacen("\"width\": 900.0", "\"width\": NaN", 1);
    assert_ne!(nan_json, pillars(), "the NaN was put in");
    let huge_json = pillars().replacen("\"width\": 900.0", "\"width\": 1e39", 1);
    // The parser's own words ride along as `details` for the page's disclosure.
    let refused = sim.load(&nan_json).expect_err("NaN");
    let details =
        js_sys::Reflect::get(&refused, &JsValue::from_str("details")).ok().and_then(|d| d.as_string());
    assert!(details.as_deref().is_some_and(|d| d.contains("column")), "{details:?}");
    let cases: Vec<(&str, String, &str)> = vec![
        ("garbled fragment", format!("{}!!x", &fragment[..fragment.len() / 2]), "scene"),
        ("unknown version", "9.abcdef".to_string(), "version"),
        ("NaN in JSON", nan_json, "width is NaN; allowed: a number in 10…20000 px"),
        ("overflowing number", huge_json, "width is 1e39; allowed"),
        ("unknown preset", "no-such-preset".to_string(), "unknown preset 'no-such-preset' (known: pillars"),
        ("10 million agents", serde_json::to_string(&crowd).expect("json"), "10000000 agents"),
        ("obstacle over the goal", serde_json::to_string(&blocked).expect("json"), "inside obstacle"),
        ("empty text", String::new(), "empty"),
    ];
    for (what, text, expected) in &cases {
        let error = sim.load(text).err().unwrap_or_else(|| panic!("{what} was accepted"));
        let said = message(error);
        assert!(said.contains(expected), "{what}: {said:?} does not mention {expected:?}");
        assert!(Sim::new(text, 10, 10).is_err(), "{what}: the constructor throws too");
        assert!(scene_from_text(text).is_err(), "{what}: scene_from_text throws too");
    }
    assert_eq!(sim.steps(), 25, "the step count survives refused loads");
    assert_eq!(sim.scene_json(), scene_before, "the scene survives refused loads");
    assert_eq!(sim.digest(), digest_before, "the agents survive refused loads");
    sim.step(1);
    assert_eq!(sim.steps(), 26, "the run goes on");
}

#[wasm_bindgen_test]
fn bad_edits_and_parameters_are_js_errors_and_change_nothing() {
    let mut sim = Sim::new(&pillars(), 120, 80).expect("starts");
    sim.step(10);
    let scene_before = sim.scene_json();
    let digest_before = sim.digest();
    let over_goal =
        r#"{"op": "add_obstacle", "obstacle": {"shape": "circle", "center": [830, 280], "radius": 25}}"#;
    assert!(message(sim.edit(over_goal).expect_err("blocked")).contains("inside obstacle"));
    assert!(sim.edit("{not json").is_err());
    assert!(sim.edit(r#"{"op": "delete", "item": {"kind": "goal", "index": 99}}"#).is_err());
    assert!(sim
        .edit(r#"{"op": "move", "item": {"kind": "obstacle", "index": 0}, "dx": 1e39, "dy": 0}"#)
        .is_err());
    assert!(sim.set_group_param(0, "max_speed", "1e9").is_err());
    assert!(sim.set_group_param(0, "no_such_key", "1").is_err());
    assert!(sim.set_group_param(7, "max_speed", "1").is_err());
    assert!(sim.set_group_param(0, "max_speed", "not json").is_err());
    assert!(sim.set_group_planner(0, "no_such_planner").is_err());
    assert!(sim.set_selection("{\"kind\": \"nothing\"}").is_err());
    assert_eq!(sim.steps(), 10);
    assert_eq!(sim.scene_json(), scene_before);
    assert_eq!(sim.digest(), digest_before);

    // A good edit applies and an obstacle edit keeps the run going.
    let aside =
        r#"{"op": "add_obstacle", "obstacle": {"shape": "rect", "min": [600, 20], "max": [640, 60]}}"#;
    sim.edit(aside).expect("a free spot");
    assert_eq!(sim.steps(), 10);
    assert_eq!(sim.pick(620.0, 40.0, 0.0).expect("json"), r#"{"kind":"obstacle","index":16}"#);
    assert_eq!(sim.pick(5.0, 5.0, 0.0).expect("json"), "null");
}

#[wasm_bindgen_test]
fn catalogues_list_presets_and_planners() {
    let presets: serde_json::Value = serde_json::from_str(&presets_json().expect("json")).expect("parses");
    let first = presets[0]["name"].as_str().expect("a name");
    assert_eq!(first, "pillars");
    assert!(message(preset_scene_json("no-such-preset").expect_err("unknown")).contains("pillars"));
    let planners: serde_json::Value = serde_json::from_str(&planners_json().expect("json")).expect("parses");
    assert_eq!(planners[0]["name"], "boids");
    assert!(planners[0]["params"].as_array().is_some_and(|p| !p.is_empty()));
}

#[wasm_bindgen_test]
fn zoom_and_pan_change_the_picture_not_the_run_and_keep_their_trails() {
    let mut sim = Sim::new(&pillars(), 900, 560).expect("starts");
    sim.set_seed(7).expect("reseeds");
    sim.step(150);
    sim.render();
    let fitted = sim.view();
    let fitted_frame = frame(&sim);
    assert_eq!(sim.view_zoom(), 1.0);
    sim.zoom_view(300.0, 250.0, 3.0);
    sim.render();
    let zoomed = sim.view();
    assert_eq!(sim.view_zoom(), 3.0);
    assert!((zoomed[0] - 3.0 * fitted[0]).abs() < 1e-4, "scale {} → {}", fitted[0], zoomed[0]);
    // The scene point under (300, 250) is still there.
    let before = ((300.0 - fitted[1]) / fitted[0], (250.0 - fitted[2]) / fitted[0]);
    let after = ((300.0 - zoomed[1]) / zoomed[0], (250.0 - zoomed[2]) / zoomed[0]);
    assert!((before.0 - after.0).abs() < 1e-2 && (before.1 - after.1).abs() < 1e-2);
    let zoomed_frame = frame(&sim);
    assert!(zoomed_frame != fitted_frame);
    // Trails are redrawn for the zoomed view from the recording: the trail layer is not empty
    // (a frame with trails off differs from it).
    sim.set_trails(false).expect("trails off");
    sim.render();
    assert!(frame(&sim) != zoomed_frame, "the zoomed frame kept its trails");
    sim.set_trails(true).expect("trails on");
    sim.pan_view(40.0, -20.0);
    sim.render();
    let panned = sim.view();
    assert!((panned[1] - zoomed[1] - 40.0).abs() < 1e-3 && (panned[2] - zoomed[2] + 20.0).abs() < 1e-3);
    sim.fit_view();
    sim.render();
    assert_eq!(sim.view(), fitted);
    // None of it changed the run.
    sim.step(150);
    assert_eq!(sim.digest(), GOLDEN_DIGEST.trim());
}
