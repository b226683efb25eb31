//! PSO crowd (Chen & Lin 2009): invariants over long runs and each preset's documented outcome.
//!
//! Debug builds run fewer seeds and steps so the file stays fast; every assertion still runs.

use flockpath::model::params::PsoParams;
use flockpath::{presets, Obstacle, PlannerConfig, Scene, World};

const PSO_PRESETS: &[&str] = &[
    "pso-influx",
    "pso-stream",
    "pso-static-obstacle",
    "pso-dodge",
    "pso-crowd",
    "pso-circle-target",
    "pso-four-corners",
];

fn seeds() -> u32 {
    if cfg!(debug_assertions) {
        3
    } else {
        20
    }
}

fn preset(name: &str, seed: u32) -> Scene {
    let mut s = (presets::find(name).expect("preset").build)();
    s.seed = seed;
    s
}

fn set_acceptance(scene: &mut Scene, on: bool) {
    for g in &mut scene.groups {
        g.planner.set_param("acceptance", serde_json::json!(if on { "on" } else { "off" })).expect("param");
    }
}

/// Smallest distance from any agent centre to any obstacle surface (px).
fn clearance(world: &World) -> f32 {
    let mut min = f32::INFINITY;
    for &p in world.positions() {
        for o in world.obstacles().obstacles() {
            min = min.min(o.surface(p).signed_distance);
        }
    }
    min
}

#[test]
fn with_acceptance_no_agent_ever_enters_an_obstacle_zone_on_any_pso_preset() {
    let steps = if cfg!(debug_assertions) { 300 } else { 1500 };
    let sigma = PsoParams::default().agent_sigma;
    for name in PSO_PRESETS {
        for seed in 1..=seeds() {
            let mut world = World::new(preset(name, seed)).expect("valid");
            let has_obstacles = !world.obstacles().is_empty();
            for step in 0..steps {
                world.step();
                // σ-scaled distance > 1 from every obstacle: the shape grown by the agent's σ.
                if has_obstacles {
                    let c = clearance(&world);
                    assert!(c >= sigma - 0.01, "{name} seed {seed} step {step}: clearance {c}");
                }
                for (p, v) in world.positions().iter().zip(world.velocities()) {
                    assert!(p.is_finite() && v.is_finite(), "{name} seed {seed}: non-finite state");
                    assert!(v.length() <= PsoParams::default().max_speed + 1e-4, "{name}: overspeed {v}");
                }
            }
            let m = world.metrics();
            assert_eq!(m.overall.penetrations_agent_obstacle, 0, "{name} seed {seed}");
        }
    }
}

#[test]
fn without_acceptance_the_original_pso_walks_through_the_obstacle_at_500_15() {
    let steps = 1500;
    let mut total = 0;
    let mut with_acceptance = 0;
    for seed in 1..=3 {
        let mut scene = preset("pso-static-obstacle", seed);
        assert_eq!(scene.obstacles[0], Obstacle::Circle { center: [500.0, 15.0], radius: 30.0 });
        let mut on = World::new(scene.clone()).expect("valid");
        set_acceptance(&mut scene, false);
        let mut off = World::new(scene).expect("valid");
        off.step_n(steps);
        on.step_n(steps);
        let p = off.metrics().overall.penetrations_agent_obstacle;
        println!("pso-static-obstacle seed {seed}: penetrations without acceptance {p}");
        total += p;
        with_acceptance += on.metrics().overall.penetrations_agent_obstacle;
    }
    assert!(total > 0, "the original PSO should penetrate the obstacle in some run");
    assert_eq!(with_acceptance, 0);
}

/// Runs `name` for `steps` over seeds 1..=n and returns the smallest arrival share.
fn worst_arrival(name: &str, steps: u32, n: u32) -> f64 {
    let mut worst: f64 = 1.0;
    for seed in 1..=n {
        let mut world = World::new(preset(name, seed)).expect("valid");
        world.step_n(steps);
        let m = world.metrics();
        println!(
            "{name} seed {seed}: arrived {:.2} after {steps} steps, mean time {:?}, collisions {}",
            m.overall.arrived_share, m.overall.mean_time_to_goal, m.overall.collisions_agent_agent
        );
        worst = worst.min(m.overall.arrived_share);
    }
    worst
}

fn outcome_seeds() -> u32 {
    if cfg!(debug_assertions) {
        2
    } else {
        10
    }
}

#[test]
fn influx_stream_and_crowd_reach_their_targets() {
    assert!(worst_arrival("pso-influx", 1500, outcome_seeds()) >= 0.9);
    assert!(worst_arrival("pso-stream", 1500, outcome_seeds()) >= 0.9);
    assert!(worst_arrival("pso-crowd", 1500, outcome_seeds()) >= 0.9);
}

#[test]
fn most_people_get_past_the_static_obstacle() {
    assert!(worst_arrival("pso-static-obstacle", 2400, outcome_seeds()) >= 0.8);
}

#[test]
fn two_persons_dodge_head_on_without_touching_and_both_arrive() {
    for seed in 1..=outcome_seeds() {
        let mut world = World::new(preset("pso-dodge", seed)).expect("valid");
        let mut closest = f32::INFINITY;
        for _ in 0..800 {
            world.step();
            closest = closest.min(world.positions()[0].distance(world.positions()[1]));
        }
        let m = world.metrics();
        println!(
            "pso-dodge seed {seed}: closest approach {closest:.1} px, arrived {}",
            m.overall.arrived_share
        );
        assert_eq!(m.overall.collisions_agent_agent, 0, "seed {seed}");
        // Each person tests its move against the other's *old* position, so both moving at once
        // can end slightly inside 2σ = 10 px (measured 9.8); the discs (radius 4) never touch.
        let radii = world.radii()[0] + world.radii()[1];
        assert!(closest > radii, "seed {seed}: {closest}");
        assert!(closest >= 2.0 * PsoParams::default().agent_sigma - 2.0 * PsoParams::default().max_speed);
        assert_eq!(m.overall.arrived_share, 1.0, "seed {seed}");
    }
}

#[test]
fn four_corner_groups_cross_with_almost_no_collisions_once_spawn_overlaps_are_gone() {
    // Measured over seeds 1–10: zero overlapping pairs after step 60 in 9 seeds, 8 pair-steps in
    // seed 10 (two agents moving at once, each tested against the other's old position).
    let mut clean = 0;
    for seed in 1..=outcome_seeds() {
        let mut world = World::new(preset("pso-four-corners", seed)).expect("valid");
        // Spawn points are drawn independently and may overlap; give them 60 steps to separate.
        world.step_n(60);
        let after_spawn = world.metrics().overall.collisions_agent_agent;
        world.step_n(2340);
        let m = world.metrics();
        let new = m.overall.collisions_agent_agent - after_spawn;
        println!(
            "pso-four-corners seed {seed}: arrived {:.2}, collisions after step 60: {new} (spawn overlaps {after_spawn})",
            m.overall.arrived_share
        );
        assert!(m.overall.arrived_share >= 0.9, "seed {seed}");
        assert!(new <= 10, "seed {seed}: {new} collisions");
        clean += u32::from(new == 0);
    }
    assert!(clean * 10 >= outcome_seeds() * 8, "only {clean} seeds without collisions");
}

#[test]
fn the_crowd_keeps_up_with_a_target_moving_on_a_circle() {
    let scene = preset("pso-circle-target", 1);
    assert!(matches!(PlannerConfig::Pso(PsoParams::default()), ref c if *c == scene.groups[0].planner));
    for seed in 1..=outcome_seeds() {
        let mut world = World::new(preset("pso-circle-target", seed)).expect("valid");
        world.step_n(600);
        let mut worst = 0.0f32;
        let mut start = None;
        for _ in 0..30 {
            world.step_n(100);
            let (goal, _) = world.goal_of_group(0).expect("goal");
            start.get_or_insert(goal);
            let mean =
                world.positions().iter().map(|p| p.distance(goal)).sum::<f32>() / world.agent_count() as f32;
            worst = worst.max(mean);
        }
        let (end, _) = world.goal_of_group(0).expect("goal");
        println!("pso-circle-target seed {seed}: worst mean distance to the moving target {worst:.1} px");
        assert!(start.is_some_and(|s| s.distance(end) > 100.0), "the target moved");
        assert!(worst < 90.0, "seed {seed}: the crowd fell {worst} px behind");
    }
}
