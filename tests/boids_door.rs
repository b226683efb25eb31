//! A flock passes a door a few bodies wide (issue 23 §1): 200 Boids of radius 4 px head for a
//! goal 330 px beyond a 20 px wall whose only opening is a 24 px door (three bodies wide), with
//! either arbitration. Counted from the agents' positions, not from the metrics code, so the
//! tests keep their meaning whatever the arrival rule is.

use flockpath::model::geometry::Obstacle;
use flockpath::model::params::{Arbitration, BoidsParams};
use flockpath::{Goal, Group, PlannerConfig, Region, Scene, World};
use glam::Vec2;

const WORLD: (f32, f32) = (900.0, 600.0);
/// The wall's near and far faces (x, px); it spans the world's height but for the door.
const WALL: (f32, f32) = (440.0, 460.0);
/// The door: a 24 px gap in the wall, centred on the world's middle line.
const DOOR: (f32, f32) = (288.0, 312.0);
const AGENTS: u32 = 200;
const BODY_RADIUS: f32 = 4.0;
/// 330 px beyond the wall; a radius of 90 px holds the 200 bodies with room to spare.
const GOAL: (Vec2, f32) = (Vec2::new(WALL.1 + 330.0, 300.0), 90.0);
const STEPS: u32 = 6_000;
/// At least 95% of the flock.
const ENOUGH: usize = AGENTS as usize * 95 / 100;

fn door_scene(arbitration: Arbitration) -> Scene {
    let mut s = Scene::empty(WORLD.0, WORLD.1);
    s.name = "door three bodies wide".into();
    s.seed = 7;
    s.obstacles.push(Obstacle::Rect { min: [WALL.0, 0.0], max: [WALL.1, DOOR.0] });
    s.obstacles.push(Obstacle::Rect { min: [WALL.0, DOOR.1], max: [WALL.1, WORLD.1] });
    s.goals.push(Goal::fixed(GOAL.0.to_array(), GOAL.1));
    s.groups.push(Group {
        name: "flock".into(),
        color: "#009E73".into(),
        count: AGENTS,
        spawn: Region { min: [40.0, 150.0], max: [260.0, 450.0] },
        goal: Some(0),
        agent_radius: BODY_RADIUS,
        planner: PlannerConfig::Boids(BoidsParams { arbitration, ..BoidsParams::default() }),
    });
    s
}

/// Steps `world` in blocks of 100 until `done` holds or [`STEPS`] have run (the tests ask for
/// "by step 6,000"; stopping early keeps the debug-build test short).
fn run_until(world: &mut World, done: impl Fn(&World) -> bool) {
    while world.step_count() < STEPS && !done(world) {
        world.step_n(100);
    }
}

/// Agents whose centre lies beyond the wall's far face.
fn beyond_the_wall(world: &World) -> usize {
    world.positions().iter().filter(|p| p.x > WALL.1).count()
}

#[test]
fn the_door_scene_is_what_it_says() {
    let world = World::new(door_scene(Arbitration::Priority)).expect("valid scene");
    assert_eq!(world.agent_count(), AGENTS as usize);
    assert_eq!(beyond_the_wall(&world), 0, "the flock starts before the wall");
    // The door's middle is open, the wall beside it is not.
    let blocked = |p: Vec2| world.scene().obstacles.iter().any(|o| o.contains(p));
    assert!(!blocked(Vec2::new(450.0, 300.0)));
    assert!(blocked(Vec2::new(450.0, DOOR.0 - 1.0)) && blocked(Vec2::new(450.0, DOOR.1 + 1.0)));
    assert!(DOOR.1 - DOOR.0 < 4.0 * BODY_RADIUS * 2.0, "a door fewer than four bodies wide");
}

#[test]
fn a_flock_passes_a_door_three_bodies_wide_with_either_arbitration() {
    // Parking off: what this pins is the steering through the door, whatever happens at the
    // goal (under the arrival rule before issue 23, agents parked on touching a parked body and
    // grew a chain of them back into the door that plugged it).
    // Measured at 7ad6f04 (fixed-length whiskers): priority 0 of 200 beyond the wall at step
    // 6,000, weighted 200. With whiskers that shrink with speed: priority 138 at step 3,000
    // and 200 at 6,000, weighted 200 by step 1,000.
    for arbitration in [Arbitration::Priority, Arbitration::Weighted] {
        let mut world = World::new(door_scene(arbitration)).expect("valid scene");
        world.set_parking(false);
        run_until(&mut world, |w| beyond_the_wall(w) >= ENOUGH);
        let through = beyond_the_wall(&world);
        println!("{arbitration:?}: {through} of {AGENTS} beyond the wall at step {}", world.step_count());
        assert!(
            through >= ENOUGH,
            "{arbitration:?}: {through} of {AGENTS} beyond the wall by step {STEPS}, want >= {ENOUGH}"
        );
    }
}

/// Agents whose centre is inside the goal now.
fn inside_the_goal(world: &World) -> usize {
    world.positions().iter().filter(|p| p.distance(GOAL.0) <= GOAL.1).count()
}

#[test]
fn the_flock_fills_its_goal_beyond_the_door_with_either_arbitration() {
    // Measured: at 66da5a5 the weighted flock had 199 of 200 arrived (168 centres inside at
    // step 6,000) and the priority flock none; with parking on first touch (58a075b to
    // 7ad6f04) weighted read arrived 1.0 with 1 centre inside and 75 agents behind the wall;
    // with goals that fill and whiskers that shrink with speed, 200 of 200 inside for both.
    for arbitration in [Arbitration::Priority, Arbitration::Weighted] {
        let mut world = World::new(door_scene(arbitration)).expect("valid scene");
        run_until(&mut world, |w| inside_the_goal(w) >= ENOUGH && w.metrics().overall.arrived_share >= 0.95);
        let inside = inside_the_goal(&world);
        let arrived = world.metrics().overall.arrived_share;
        println!(
            "{arbitration:?}: {inside} of {AGENTS} inside, arrived {arrived} at step {}",
            world.step_count()
        );
        assert!(
            inside >= ENOUGH,
            "{arbitration:?}: {inside} of {AGENTS} centres inside the goal by step {STEPS}, want >= {ENOUGH} \
             ({} beyond the wall)",
            beyond_the_wall(&world)
        );
        assert!(
            arrived >= 0.95,
            "{arbitration:?}: arrived_share {arrived} by step {STEPS} ({inside} inside)"
        );
    }
}
