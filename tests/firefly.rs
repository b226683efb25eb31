//! Firefly crowd (Zhang, Wei & Chen 2017): invariants, aggregation, single-file queues, arrival.

use flockpath::model::params::FireflyParams;
use flockpath::sim::metrics::MetricsRecorder;
use flockpath::spatial::{ObstacleIndex, SpatialGrid};
use flockpath::{presets, Goal, World};
use glam::Vec2;

fn seeds() -> u32 {
    if cfg!(debug_assertions) {
        2
    } else {
        10
    }
}

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
        let mut later = Vec::new();
        for step in [300, 400, 500] {
            world.step_n(step - world.step_count());
            later.push(world.metrics().overall.queue_order.expect("queue order"));
        }
        let m = world.metrics();
        let queued = later.iter().sum::<f64>() / later.len() as f64;
        world.step_n(1500 - world.step_count());
        let end = world.metrics();
        println!(
            "firefly seed {seed}: queue order step 1 {start:.2}, steps 300/400/500 {later:.2?}; arrived at 1500 {:.2}; \
             collisions to step 500 {}, to 1500 {}",
            end.overall.arrived_share, m.overall.collisions_agent_agent, end.overall.collisions_agent_agent
        );
        // The spacing-based queue order (a brighter firefly of the group within 16 px ahead,
        // ±30°): the spread-out spawn reads 0.00–0.01 at step 1 on seeds 1–10; the files read
        // 0.59–0.86 at step 300, 0.68–0.95 at 400, 0.72–0.87 at 500 (means of the three 0.69–0.91).
        assert!(start < 0.1, "seed {seed}: queue order {start} at step 1");
        assert!(queued > 0.6, "seed {seed}: queue order {later:?} at steps 300/400/500");
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

    // Known answers: ten 4 px fireflies on a line towards a goal at the right.
    let mut scene = presets::firefly_migration();
    scene.obstacles.clear();
    scene.goals[0] = Goal::fixed([780.0, 300.0], 10.0);
    scene.groups.truncate(1);
    scene.groups[0].count = 10;
    scene.groups[0].agent_radius = 4.0;
    let measure = |spacing: f32, heading: Vec2| {
        let pos: Vec<Vec2> = (0..10).map(|k| Vec2::new(100.0 + spacing * k as f32, 300.0)).collect();
        let vel = vec![heading; 10];
        let mut grid = SpatialGrid::new(scene.width, scene.height, 50.0, 10);
        grid.rebuild(&pos, &vel);
        let obstacles = ObstacleIndex::new(vec![], scene.width, scene.height);
        let mut recorder = MetricsRecorder::new(&scene, &pos);
        let goals = [Some((Vec2::new(780.0, 300.0), 10.0))];
        recorder.record(1, &pos, &vel, &[0; 10], &[4.0; 10], &goals, &grid, &obstacles, &[]);
        recorder.summary(&scene, &["firefly"], 1).overall.queue_order.expect("measured")
    };
    let towards = Vec2::new(1.5, 0.0);
    // In file 12 px apart, heading for the goal: all but the head are queued.
    assert_eq!(measure(12.0, towards), 0.9);
    // 16 px is the reach (4 radii); 17 px apart is spread out.
    assert_eq!(measure(16.0, towards), 0.9);
    assert_eq!(measure(17.0, towards), 0.0);
    // Heading away from the brighter one, or 45° off it: not queued behind it.
    assert_eq!(measure(12.0, -towards), 0.0);
    assert_eq!(measure(12.0, Vec2::new(1.0, 1.0)), 0.0);
    // 25° off: still within ±30°.
    let (s, c) = 25f32.to_radians().sin_cos();
    assert_eq!(measure(12.0, Vec2::new(c, s)), 0.9);
}
