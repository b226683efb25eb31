//! Golden digest: preset `pillars`, seed 7, 300 steps must give the digest in
//! `tests/data/golden-digest.txt`, natively here and in the browser (the wasm test reads the same
//! file), so a shared URL replays the same run everywhere.
//!
//! When the digest changes on purpose (a planner, the step, the spawn or the generator changed
//! behaviour by design), `cargo test --test golden` fails with the current digest in its message:
//! copy it into `tests/data/golden-digest.txt`, and say in the commit message why every old URL
//! now replays differently. When it changes by accident (a refactor, a dependency bump, a different float
//! summation order), find the cause instead: that is exactly what this test is for.

use flockpath::{presets, World};

const STEPS: u32 = 300;
const SEED: u32 = 7;

fn run(seed: u32) -> u64 {
    let mut scene = (presets::find("pillars").expect("preset pillars exists").build)();
    scene.seed = seed;
    let mut world = World::new(scene).expect("pillars is a valid scene");
    world.step_n(STEPS);
    world.digest()
}

fn golden() -> String {
    let text = include_str!("data/golden-digest.txt");
    text.trim().to_string()
}

#[test]
fn pillars_seed_7_matches_the_golden_digest() {
    let expected = golden();
    assert_eq!(expected.len(), 16, "golden file must hold 16 hex digits, holds {expected:?}");
    let actual = format!("{:016x}", run(SEED));
    assert_eq!(
        actual, expected,
        "pillars seed {SEED} after {STEPS} steps gives {actual}; if the change is deliberate, paste it \
         into tests/data/golden-digest.txt (module docs)"
    );
}

#[test]
fn the_same_scene_and_seed_give_the_same_digest() {
    assert_eq!(run(SEED), run(SEED));
    assert_eq!(run(3), run(3));
}

#[test]
fn a_different_seed_gives_a_different_digest() {
    assert_ne!(run(SEED), run(SEED + 1));
}
