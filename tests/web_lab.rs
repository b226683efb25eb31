//! Browser tests of the optimizer lab and the path-editing bindings in headless Chromium
//! (`bash scripts/test-wasm.sh`): the same seed gives the same optimizer run as natively (the
//! digest pinned by `tests/igsa.rs`), the lab draws its particles, and edited IGSA paths flag
//! their crossings.
#![cfg(target_arch = "wasm32")]

use flockpath::web::lab::{lab_best_of_run, lab_options_json, lab_reference_digest, Lab};
use flockpath::web::{preset_scene_json, Sim};
use wasm_bindgen_test::{wasm_bindgen_test, wasm_bindgen_test_configure};

wasm_bindgen_test_configure!(run_in_browser);

/// Digest of the reference run (IGSA, Ackley, d = 5, N = 20, T = 100, seed 3) from a native run.
const GOLDEN_OPTIM: &str = include_str!("data/golden-optim.txt");

#[wasm_bindgen_test]
fn the_reference_optimizer_run_matches_the_native_digest() {
    assert_eq!(lab_reference_digest(), GOLDEN_OPTIM.trim());
    // Through the page's handle too: same algorithm, function, sizes and seed.
    let mut lab = Lab::new("igsa", "ackley", 5, 20, 100, 3).expect("valid run");
    lab.step(1000);
    assert_eq!(lab.iteration(), 100);
    assert_eq!(lab.digest(), GOLDEN_OPTIM.trim());
}

#[wasm_bindgen_test]
fn a_2d_run_draws_its_particles_and_moves() {
    let mut lab = Lab::new("pso", "rastrigin", 2, 25, 200, 1).expect("valid run");
    assert_eq!(lab.particles(), 25);
    assert_eq!(lab.positions().len(), 50);
    lab.render(200, 150);
    assert_eq!(lab.frame_len(), 200 * 150 * 4);
    let before = lab.positions();
    lab.step(3);
    assert_ne!(before, lab.positions());
    assert_eq!(lab.curve().len(), 4);
    assert!(Lab::new("nope", "sphere", 2, 10, 10, 1).is_err());
    assert!(Lab::new("gsa", "sphere", 0, 10, 10, 1).is_err());
}

#[wasm_bindgen_test]
fn single_runs_are_seeded_and_repeatable() {
    let a = lab_best_of_run("gsa", "sphere", 10, 20, 50, 9, 2).expect("runs");
    let b = lab_best_of_run("gsa", "sphere", 10, 20, 50, 9, 2).expect("runs");
    let c = lab_best_of_run("gsa", "sphere", 10, 20, 50, 9, 3).expect("runs");
    assert_eq!(a.to_bits(), b.to_bits());
    assert_ne!(a.to_bits(), c.to_bits());
    assert!(lab_options_json().expect("json").contains("\"igsa\""));
}

#[wasm_bindgen_test]
fn an_edited_path_that_crosses_the_wall_is_flagged() {
    let mut sim = Sim::new(&preset_scene_json("igsa-path-2").expect("preset"), 200, 120).expect("starts");
    // The page plans in slices: no path until the planning is done.
    assert_eq!(sim.group_path_json(0).expect("json"), "null");
    while sim.advance_planning(50) < 1.0 {}
    let planned = sim.group_path_json(0).expect("json");
    assert!(planned.contains("\"source\":\"igsa\""), "{planned}");
    let edited = sim.set_group_waypoints(0, "[[400, 420]]").expect("accepted");
    assert!(edited.contains("\"crossing\":[true,true]"), "{edited}");
    assert!(sim.scene_json().contains("\"waypoints\""));
    assert!(sim.pick_waypoint(401.0, 419.0, 5.0).expect("json").contains("\"index\":0"));
    assert!(sim.set_group_waypoints(0, "[[1]]").is_err());
    assert_eq!(sim.set_group_waypoints(0, "[]").expect("replans"), "null", "planning again");
    while sim.advance_planning(50) < 1.0 {}
    assert_eq!(sim.group_path_json(0).expect("json"), planned, "the same path as the first time");
}
