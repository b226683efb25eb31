//! Firefly crowd (Zhang, Wei & Chen 2017): invariants, aggregation, single-file queues, arrival.

use flockpath::model::params::FireflyParams;
use flockpath::{presets, World};

fn seeds() -> u32 {
    if cfg!(debug_assertions) {
        2
    } else {
        10
    }
}

/// Expected queue order of random headings: a ±30° cone is 1/6 of the circle.
const RANDOM_QUEUE_ORDER: f64 = 1.0 / 6.0;

#[test]
fn the_paper_setting_is_the_preset() {
    let s = presets::firefly_migration_with_seed(3);
    assert_eq!((s.width, s.height, s.groups[0].count), (800.0, 600.0, 80));
    assert!(!s.obstacles.is_empty());
    assert_ne!(s.obstacles, presets::firefly_migration_with_seed(4).obstacles, "obstacles follow the seed");
    let json = serde_json::to_value(&s.groups[0].planner).expect("json");
    assert_eq!(json["kind"], "firefly");
    let p = FireflyParams::default();
    assert_eq!(
        (p.max_velocity, p.alpha, p.gamma, p.feeler_length, p.safe_distance),
        (2.0, 0.2, 0.05, 60.0, 50.0)
    );
    assert_eq!((p.mass_min, p.mass_max), (20.0, 40.0));
}

#[test]
fn long_runs_stay_finite_within_the_speed_limit_and_out_of_obstacles() {
    let steps = if cfg!(debug_assertions) { 600 } else { 2000 };
    for seed in 1..=seeds() {
        let mut world = World::new(presets::firefly_migration_with_seed(seed)).expect("valid");
        for _ in 0..steps {
            world.step();
            for (p, v) in world.positions().iter().zip(world.velocities()) {
                assert!(p.is_finite() && v.is_finite());
                assert!(v.length() <= FireflyParams::default().max_velocity + 1e-4, "overspeed {v}");
            }
        }
        assert_eq!(world.metrics().overall.penetrations_agent_obstacle, 0, "seed {seed}");
    }
}

#[test]
fn fireflies_line_up_in_file_then_reach_the_target() {
    for seed in 1..=seeds() {
        let mut world = World::new(presets::firefly_migration_with_seed(seed)).expect("valid");
        // Step 0's velocities are the random spawn velocities.
        world.step();
        let start = world.metrics().overall.queue_order.expect("queue order at the start");
        world.step_n(299);
        let m = world.metrics();
        let queued = m.overall.queue_order.expect("queue order at step 300");
        world.step_n(1200);
        let end = world.metrics();
        println!(
            "firefly seed {seed}: queue order step 1 {start:.2}, step 300 {queued:.2}; arrived at 1500 {:.2}; \
             collisions to step 300 {}, to 1500 {}",
            end.overall.arrived_share, m.overall.collisions_agent_agent, end.overall.collisions_agent_agent
        );
        // Falling in behind a brighter firefly in contact: 0.88–0.99 at step 300 on seeds 1–10
        // (0.79–0.94 without it, so 0.85 fails on main's seeds 1, 2, 6, 7).
        assert!(queued >= 0.85, "seed {seed}: queue order {queued}");
        // The first step already turns most fireflies at their nearest brighter one: measured
        // 0.89–0.95 after one step from the spawn lattice (0.72–0.81 from the former random,
        // overlapping spawn, after which the files tightened to 0.88–0.99), 0.86–0.93 at step 300.
        assert!(start > RANDOM_QUEUE_ORDER && queued > RANDOM_QUEUE_ORDER, "seed {seed}: {start} → {queued}");
        assert!(end.overall.arrived_share >= 0.9, "seed {seed}");
    }
}

#[test]
fn fireflies_do_not_interpenetrate() {
    // The paper's "no interpenetration": after the first step no two bodies overlap (before the
    // contact rule, 3,000–5,100 pair-steps by step 300). Spawn points may overlap; a pair that
    // spawned deeper than two steps of max velocity is still overlapping at the end of step 1.
    for seed in 1..=5 {
        let mut world = World::new(presets::firefly_migration_with_seed(seed)).expect("valid");
        world.step();
        let at_spawn = world.metrics().overall.collisions_agent_agent;
        world.step_n(1499);
        let total = world.metrics().overall.collisions_agent_agent;
        assert!(at_spawn <= 2, "seed {seed}: {at_spawn} overlapping pairs at step 1");
        assert_eq!(total - at_spawn, 0, "seed {seed}: overlapping pair-steps after step 1");
    }
}

#[test]
fn the_queue_order_measure_tells_a_file_from_a_random_crowd() {
    // Zero steps: recorded velocities are zero, so nobody counts as queued.
    let world = World::new(presets::firefly_migration()).expect("valid");
    assert_eq!(world.metrics().overall.queue_order, Some(0.0));
    let json = serde_json::to_value(world.metrics()).expect("json");
    assert!(json.get("queue_order").is_some() && json["groups"][0].get("queue_order").is_some());
}
