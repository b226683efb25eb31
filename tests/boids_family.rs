//! The Boids family (lecture, "extensions"): leader following, path following, flow field and
//! predator/prey, each measured on its preset against what it promises, plus the invariants
//! (finite state, speed limit, no penetration) over long runs.

use flockpath::model::params::FlowGuide;
use flockpath::{presets, PlannerConfig, Scene, World};
use glam::Vec2;

fn boids_params(scene: &mut Scene, group: usize) -> &mut flockpath::model::params::BoidsParams {
    match &mut scene.groups[group].planner {
        PlannerConfig::Boids(p) => p,
        other => panic!("group {group} is not Boids: {other:?}"),
    }
}

/// Distance from `p` to a polyline.
fn distance_to_polyline(points: &[[f32; 2]], p: Vec2) -> f32 {
    points
        .windows(2)
        .map(|w| {
            let (a, b) = (Vec2::from(w[0]), Vec2::from(w[1]));
            let ab = b - a;
            let t = ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0);
            p.distance(a + ab * t)
        })
        .fold(f32::INFINITY, f32::min)
}

#[test]
fn followers_stay_behind_the_leader_and_close_to_it() {
    let scene = presets::boids_leader();
    let goal = Vec2::from(scene.goals[0].position);
    let goal_radius = scene.goals[0].radius;
    let mut world = World::new(scene).expect("valid");
    // Spawned at random, followers may start ahead of the leader: give them time to fall in.
    world.step_n(150);
    let (mut worst_ahead, mut worst_distance, mut distance_sum, mut samples) = (f32::MIN, 0.0f32, 0.0f32, 0);
    let mut travelling_steps = 0;
    while world.step_count() < 1500 {
        world.step();
        let pos = world.positions();
        let leader = pos[0];
        let v = world.velocities()[0];
        if leader.distance(goal) <= goal_radius + 30.0 {
            break;
        }
        if v.length() < 0.5 {
            continue;
        }
        travelling_steps += 1;
        let heading = v.normalize();
        for &p in &pos[1..] {
            worst_ahead = worst_ahead.max((p - leader).dot(heading));
            let d = p.distance(leader);
            worst_distance = worst_distance.max(d);
            distance_sum += d;
            samples += 1;
        }
    }
    let mean_distance = distance_sum / samples as f32;
    println!(
        "leader: {travelling_steps} travelling steps; followers at most {worst_ahead:.1} px ahead of the \
         leader along its heading, mean distance {mean_distance:.1} px, farthest {worst_distance:.1} px"
    );
    assert!(travelling_steps > 200, "the leader travelled for only {travelling_steps} steps");
    assert!(worst_ahead < 10.0, "a follower got {worst_ahead:.1} px ahead of the leader");
    assert!(mean_distance < 110.0, "followers trail {mean_distance:.1} px behind on average");
    assert!(worst_distance < 200.0, "a follower fell {worst_distance:.1} px behind");
    world.step_n(1500 - world.step_count().min(1500));
    let m = world.metrics();
    println!("leader: arrived {:.2} after {} steps", m.overall.arrived_share, m.steps);
    assert!(m.overall.arrived_share > 0.95);
}

#[test]
fn without_a_leader_the_flock_spreads_ahead_of_the_first_agent() {
    // The control for the test above: the same flock seeking the goal on its own does overtake
    // the first agent, so "never ahead" is the leader rule's doing.
    let mut scene = presets::boids_leader();
    boids_params(&mut scene, 0).leader = flockpath::model::params::Leader::None;
    let mut world = World::new(scene).expect("valid");
    world.step_n(150);
    let mut worst_ahead = f32::MIN;
    for _ in 0..200 {
        world.step();
        let heading = world.velocities()[0].normalize_or_zero();
        let leader = world.positions()[0];
        for &p in &world.positions()[1..] {
            worst_ahead = worst_ahead.max((p - leader).dot(heading));
        }
    }
    println!("no leader: agents up to {worst_ahead:.1} px ahead of the first agent");
    assert!(worst_ahead > 30.0);
}

#[test]
fn path_followers_keep_to_the_corridor_and_reach_its_end() {
    let run = |follow: bool| {
        let mut scene = presets::boids_path();
        if !follow {
            boids_params(&mut scene, 0).path = 0;
        }
        let path = scene.paths[0].clone();
        let end = Vec2::from(*path.points.last().expect("points"));
        let mut world = World::new(scene).expect("valid");
        let (mut inside, mut samples) = (0u32, 0u32);
        let mut reached_end = vec![false; world.agent_count()];
        for _ in 0..1800 {
            world.step();
            for (i, &p) in world.positions().iter().enumerate() {
                reached_end[i] |= p.distance(end) <= path.radius + 20.0;
                if reached_end[i] {
                    continue;
                }
                samples += 1;
                inside += u32::from(distance_to_polyline(&path.points, p) <= path.radius + 10.0);
            }
        }
        let share_inside = f64::from(inside) / f64::from(samples.max(1));
        let share_end = reached_end.iter().filter(|&&r| r).count() as f64 / reached_end.len() as f64;
        (share_inside, share_end, world.metrics().overall.arrived_share)
    };
    let (inside, end, arrived) = run(true);
    let (inside_seek, _, _) = run(false);
    println!(
        "path: {:.1}% of agent-steps within radius + 10 px before the end ({:.1}% with plain seek), \
         {:.0}% reached the end, {:.0}% arrived",
        100.0 * inside,
        100.0 * inside_seek,
        100.0 * end,
        100.0 * arrived
    );
    assert!(inside > 0.9, "only {inside:.3} of the time inside the corridor");
    assert!(inside_seek < 0.6, "plain seek stays inside {inside_seek:.3}: the test path is too easy");
    assert_eq!(end, 1.0, "not every agent reached the end of the path");
    assert!(arrived > 0.95);
}

/// Agents of group `g` whose centre is inside the group's goal now (recounted from positions).
fn inside_goal(world: &World, g: usize) -> usize {
    let (goal, radius) = world.goal_of_group(g).expect("the group has a goal");
    let group = world.group_of();
    world
        .positions()
        .iter()
        .zip(group)
        .filter(|&(p, &k)| k as usize == g && p.distance(goal) <= radius)
        .count()
}

#[test]
fn path_followers_walk_on_to_a_goal_beyond_the_paths_end() {
    // The path ends 150 px before the goal, as when a teacher draws a path towards a new goal
    // and stops short of it. Before, an agent that stepped out of the end's circle towards the
    // goal was pulled back to the end: the group circled there for ever (0 of 30 inside).
    let mut scene = presets::boids_path();
    scene.paths[0].points = vec![[90.0, 520.0], [300.0, 490.0], [420.0, 330.0], [560.0, 300.0]];
    scene.goals[0].position = [710.0, 300.0];
    let end = Vec2::from(scene.paths[0].points[3]);
    assert_eq!(end.distance(Vec2::from(scene.goals[0].position)), 150.0);
    let mut world = World::new(scene).expect("valid");
    let agents = world.agent_count();
    let mut most_inside = (0, 0);
    for _ in 0..30 {
        world.step_n(100);
        let inside = inside_goal(&world, 0);
        if inside > most_inside.0 {
            most_inside = (inside, world.step_count());
        }
    }
    let (inside, step) = most_inside;
    println!("goal beyond the path's end: at most {inside} of {agents} inside, at step {step}");
    assert!(inside * 10 >= agents * 9, "at most {inside} of {agents} inside the goal in 3,000 steps");

    // The preset, whose goal lies at the path's end, still ends inside it.
    let mut preset = World::new(presets::boids_path()).expect("valid");
    preset.step_n(1800);
    let inside = inside_goal(&preset, 0);
    assert!(inside * 10 >= preset.agent_count() * 9, "boids-path: {inside} inside its goal at step 1,800");
}

#[test]
fn the_flow_field_gets_through_the_maze_where_plain_seek_is_trapped() {
    let run = |guide: FlowGuide| {
        let mut scene = presets::boids_flow_field();
        boids_params(&mut scene, 0).flow_field = guide;
        let mut world = World::new(scene).expect("valid");
        world.step_n(1500);
        world.metrics()
    };
    let flow = run(FlowGuide::Goal);
    let seek = run(FlowGuide::Off);
    println!(
        "flow field: arrived {:.2}, stuck {}, collisions {}; plain seek: arrived {:.2}, stuck {} of {}",
        flow.overall.arrived_share,
        flow.overall.stuck_agents,
        flow.overall.collisions_agent_agent,
        seek.overall.arrived_share,
        seek.overall.stuck_agents,
        seek.overall.agents
    );
    assert!(flow.overall.arrived_share > 0.95);
    assert_eq!(flow.overall.stuck_agents, 0);
    assert!(seek.overall.arrived_share < 0.1);
    assert!(seek.overall.stuck_agents * 2 > seek.overall.agents, "plain seek was not trapped");
}

/// Distance from each agent of `from` to its nearest agent of `to`.
fn nearest_distances(world: &World, from: std::ops::Range<usize>, to: std::ops::Range<usize>) -> Vec<f32> {
    let pos = world.positions();
    from.map(|i| to.clone().map(|j| pos[i].distance(pos[j])).fold(f32::INFINITY, f32::min)).collect()
}

/// Runs the predator preset for 800 steps with the prey's flee weight `flee_weight` and measures:
/// the predator's starting and closest distance to any prey, and over the prey that see a
/// predator (within the flee radius) the mean change of that distance per step and the mean
/// speed away from it.
fn chase(flee_weight: f32) -> (f32, f32, f32, f32) {
    let mut scene = presets::boids_predator();
    boids_params(&mut scene, 0).flee_weight = flee_weight;
    let flee_radius = boids_params(&mut scene, 0).flee_radius;
    let prey = 0..scene.groups[0].count as usize;
    let predators = prey.end..prey.end + scene.groups[1].count as usize;
    let mut world = World::new(scene).expect("valid");
    let closest = |w: &World| {
        nearest_distances(w, predators.clone(), prey.clone()).into_iter().fold(f32::INFINITY, f32::min)
    };
    let start = closest(&world);
    let mut closest_chase = start;
    let (mut gain_sum, mut away_sum, mut samples) = (0.0f32, 0.0f32, 0u32);
    for _ in 0..800 {
        let before = nearest_distances(&world, prey.clone(), predators.clone());
        world.step();
        let now = nearest_distances(&world, prey.clone(), predators.clone());
        let pos = world.positions();
        for (k, i) in prey.clone().enumerate() {
            if before[k] >= flee_radius {
                continue;
            }
            let q = predators
                .clone()
                .map(|j| pos[j])
                .min_by(|a, b| a.distance(pos[i]).total_cmp(&b.distance(pos[i])));
            let away = q.map_or(0.0, |q| world.velocities()[i].dot((pos[i] - q).normalize_or_zero()));
            gain_sum += now[k] - before[k];
            away_sum += away;
            samples += 1;
        }
        closest_chase = closest_chase.min(closest(&world));
    }
    let n = samples.max(1) as f32;
    (start, closest_chase, gain_sum / n, away_sum / n)
}

#[test]
fn prey_flee_an_approaching_predator_which_still_catches_up() {
    let (start, closest, gain, away) = chase(3.0);
    // The control: prey that see the predator (their weights change) but do not run.
    let (_, _, gain_still, away_still) = chase(0.0);
    println!(
        "predator/prey: the predator starts {start:.0} px from the nearest prey and gets to {closest:.1} px; \
         prey within the flee radius move away from it at {away:.2} px/step and the gap changes by \
         {gain:.3} px/step (not fleeing: {away_still:.2} px/step away, gap {gain_still:.3} px/step)"
    );
    assert!(closest < 0.1 * start, "the predator never caught up");
    assert!(away > 1.0, "fleeing prey move away at only {away:.2} px/step");
    assert!(away_still < 0.5 * away, "prey move away ({away_still:.2} px/step) without fleeing");
    assert!(gain > gain_still + 0.02, "fleeing does not slow the predator's approach");
}

#[test]
fn every_family_preset_keeps_the_invariants_over_a_long_run() {
    for build in
        [presets::boids_leader, presets::boids_path, presets::boids_flow_field, presets::boids_predator]
    {
        let scene = build();
        let name = scene.name.clone();
        let limits: Vec<f32> = scene
            .groups
            .iter()
            .flat_map(|g| match &g.planner {
                PlannerConfig::Boids(p) => vec![p.max_speed; g.count as usize],
                _ => vec![f32::INFINITY; g.count as usize],
            })
            .collect();
        let mut world = World::new(scene).expect("valid");
        for _ in 0..3000 {
            world.step();
            for (i, (p, v)) in world.positions().iter().zip(world.velocities()).enumerate() {
                assert!(p.is_finite() && v.is_finite(), "{name}: agent {i} not finite");
                assert!(v.length() <= limits[i] * (1.0 + 1e-5), "{name}: agent {i} too fast");
                assert!(!world.obstacles().contains(*p), "{name}: agent {i} inside an obstacle");
            }
        }
        let m = world.metrics();
        println!(
            "{name}: 3000 steps, arrived {:.2}, collisions {}, penetrations {}",
            m.overall.arrived_share, m.overall.collisions_agent_agent, m.overall.penetrations_agent_obstacle
        );
        assert_eq!(m.overall.penetrations_agent_obstacle, 0, "{name}");
    }
}
