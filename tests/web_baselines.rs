//! Browser tests of the baseline planners in headless Chromium (`bash scripts/test-wasm.sh`):
//! the wasm build replays the baseline presets bit for bit as the native run
//! (`tests/data/golden-baselines.txt`, checked natively by `tests/orca.rs` and
//! `tests/social_force.rs`, `tests/collision_free_speed.rs`), lists the baseline planners with their
//! parameter tables, and switches a group to each.
#![cfg(target_arch = "wasm32")]

use flockpath::web::{planners_json, preset_scene_json, Sim};
use wasm_bindgen_test::{wasm_bindgen_test, wasm_bindgen_test_configure};

wasm_bindgen_test_configure!(run_in_browser);

const GOLDEN: &str = include_str!("data/golden-baselines.txt");

fn golden(name: &str) -> &'static str {
    GOLDEN.lines().find_map(|l| l.strip_prefix(name)).map(str::trim).expect("a golden digest")
}

#[wasm_bindgen_test]
fn the_baseline_presets_replay_the_native_golden_digests() {
    for name in ["orca-crossing", "social-force-bottleneck", "csm-bottleneck"] {
        let mut sim = Sim::new(&preset_scene_json(name).expect("preset"), 64, 64).expect("starts");
        sim.step(300);
        assert_eq!(sim.digest(), golden(name), "{name}");
        // Reloading the link the Sim writes replays the same run.
        let mut again = Sim::new(&sim.scene_string(), 64, 64).expect("its own link loads");
        again.step(300);
        assert_eq!(again.digest(), sim.digest(), "{name} from its link");
    }
}

#[wasm_bindgen_test]
fn every_baseline_is_listed_and_selectable() {
    let planners: serde_json::Value = serde_json::from_str(&planners_json().expect("json")).expect("parses");
    for name in ["orca", "social_force", "collision_free_speed"] {
        let entry = planners.as_array().and_then(|a| a.iter().find(|p| p["name"] == name)).expect("listed");
        assert!(entry["params"].as_array().is_some_and(|p| p.len() > 5), "{name} has its table");
        let mut sim = Sim::new(&preset_scene_json("open-field").expect("preset"), 64, 64).expect("starts");
        sim.set_group_planner(0, name).expect("switches");
        sim.step(30);
        assert_eq!(sim.steps(), 30);
    }
}
