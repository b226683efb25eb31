//! PSO digests: every PSO preset, the presets' obstacles with acceptance off, a jam packed at
//! the spawn's density limit and a pile whose neighbour queries reach their caps, each run for a
//! fixed number of steps, must give the digests below. They were taken before the planner's
//! neighbour lookups were made faster (phase-1 scan round, local lists of possible nearest
//! agents), which must change no float: a failure here means a speed-up changed the results.

use flockpath::{presets, Goal, Group, PlannerKind, Region, Scene, World};
use glam::Vec2;

/// `count` bodies of radius 4 packed one per 8 × 8 px place in a square, heading for its
/// centre (`examples/step_cost.rs`'s jam).
fn packed(count: u32) -> World {
    let side = (f64::from(count).sqrt().ceil() as f32) * 8.0;
    let world = side + 200.0;
    let mut s = Scene::empty(world, world);
    s.goals.push(Goal::fixed([0.5 * world, 0.5 * world], 20.0));
    s.groups.push(group(count, Region { min: [104.0, 104.0], max: [96.0 + side, 96.0 + side] }));
    World::new(s).expect("valid scene")
}

/// `count` agents piled in a `size × size` square (overlapping: some queries reach their caps).
fn pile(count: u32, size: f32) -> World {
    let mut s = Scene::empty(600.0, 400.0);
    s.goals.push(Goal::fixed([500.0, 200.0], 30.0));
    s.groups.push(group(count, Region { min: [100.0, 150.0], max: [100.0 + size, 150.0 + size] }));
    let positions = (0..count)
        .map(|i| {
            let u = (f64::from(i) + 0.5) / f64::from(count);
            let v = (f64::from(i) * 0.618_033_988_749_894_9).fract();
            Vec2::new(100.0 + size * u as f32, 150.0 + size * v as f32)
        })
        .collect();
    World::new_at(s, positions).expect("valid scene")
}

fn group(count: u32, spawn: Region) -> Group {
    Group {
        name: "pso".into(),
        color: "#336699".into(),
        count,
        spawn,
        goal: Some(0),
        agent_radius: 4.0,
        planner: PlannerKind::Pso.default_config(),
    }
}

fn preset(name: &str, seed: u32, acceptance: bool) -> World {
    let mut s = (presets::find(name).expect("preset").build)();
    s.seed = seed;
    for g in &mut s.groups {
        if !acceptance {
            let off = serde_json::json!("off");
            g.planner.set_param("acceptance", off).expect("param");
        }
    }
    World::new(s).expect("valid scene")
}

fn digest(mut world: World, steps: u32) -> String {
    world.step_n(steps);
    format!("{:016x}", world.digest())
}

#[test]
fn pso_runs_match_their_digests() {
    let steps = 120;
    let mut got = Vec::new();
    for name in [
        "pso-influx",
        "pso-stream",
        "pso-static-obstacle",
        "pso-dodge",
        "pso-crowd",
        "pso-circle-target",
        "pso-four-corners",
        "pso-hills",
    ] {
        got.push((format!("{name} seed 3"), digest(preset(name, 3, true), steps)));
    }
    got.push((
        "pso-static-obstacle acceptance off".into(),
        digest(preset("pso-static-obstacle", 5, false), steps),
    ));
    got.push(("pso-four-corners acceptance off".into(), digest(preset("pso-four-corners", 5, false), steps)));
    got.push(("packed 900".into(), digest(packed(900), steps)));
    got.push(("pile 300 in 30 px".into(), digest(pile(300, 30.0), steps / 3)));
    got.push(("pile 300 in 120 px".into(), digest(pile(300, 120.0), steps)));
    let text: String = got.iter().map(|(case, d)| format!("{case}: {d}\n")).collect();
    println!("{text}");
    assert_eq!(text, EXPECTED, "PSO digests changed");
}

const EXPECTED: &str = "\
pso-influx seed 3: f075c7ca49dfaaf8\n\
pso-stream seed 3: 66cf30a0aed3cf11\n\
pso-static-obstacle seed 3: af8039c1172e3e1a\n\
pso-dodge seed 3: 846c510ffd4f29c0\n\
pso-crowd seed 3: 7ea9ab74ba07f26d\n\
pso-circle-target seed 3: b85faa4115030002\n\
pso-four-corners seed 3: e9019d237b0b9ecc\n\
pso-hills seed 3: 3a1eef57db965580\n\
pso-static-obstacle acceptance off: 7dbb7fc1ba87c6db\n\
pso-four-corners acceptance off: 4b8970529078b9f1\n\
packed 900: 9f380e855dcf62f6\n\
pile 300 in 30 px: b757edda5c4ff77d\n\
pile 300 in 120 px: aef0cc9c174b7b6d\n\
";
