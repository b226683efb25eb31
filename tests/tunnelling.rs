//! Motion that cannot tunnel (issue 24, part 2).
//!
//! The bug: the world moved each agent to `previous + velocity` and only then pushed the end
//! position out of any obstacle, so a move longer than a wall is thick jumped over it. On main
//! 7ad6f04, with a 1 px wall across the world, 39 of 50 Boids at `max_speed` 20 crossed it,
//! 28 of 50 virtual-forces agents and all 50 social-force walkers; 27 of 50 Boids crossed a
//! 10 px wall. And the crossings were not counted: a penetration was a centre inside an
//! obstacle at the end of a step only.
//!
//! Here every planner runs at the largest speed its parameter table allows (every speed and
//! acceleration row at its maximum, the scene at its largest scale of px per metre, so the
//! planners whose speeds are in m/s move the most px per step), towards a goal behind a wall
//! 1 px and 10 px thick that spans the world: no agent may end on the far side, none may cross
//! it during the run (checked here from the positions, step by step), and the metrics must
//! count no penetration. A planner that passes through obstacles by design (the original PSO,
//! without its acceptance step) must have each of its crossings counted as a penetration.
//!
//! Before the fix these cases saw 3–20 of the 20 Boids cross (both arbitrations, both walls,
//! both radii) and 1–20 social-force walkers (all 20 with the accelerations at maximum), with
//! no penetration counted; 2 of 40 PSO agents of radius 0.5 px crossed the 1 px wall; the
//! original PSO had 5 penetrations counted for 20 agents that went through.

use flockpath::model::params::{Arbitration, BoidsParams, Guidance, PsoParams};
use flockpath::model::scene::MAX_PX_PER_METRE;
use flockpath::sim::metrics::MetricsRecorder;
use flockpath::spatial::{ObstacleIndex, SpatialGrid};
use flockpath::{Goal, Group, Obstacle, PlannerConfig, PlannerKind, Region, Scene, World};
use glam::Vec2;

const WIDTH: f32 = 400.0;
const HEIGHT: f32 = 1200.0;
/// The wall's near face (the group spawns above it, its goal lies below).
const WALL_TOP: f32 = 600.0;
const AGENTS: u32 = 20;

fn steps() -> u32 {
    if cfg!(debug_assertions) {
        150
    } else {
        600
    }
}

/// The rows of a planner's table that set its speed, set to their maximum; with `accelerate`
/// also its accelerations (the relaxation time of social force at its minimum).
fn at_largest_speed(mut config: PlannerConfig, accelerate: bool) -> PlannerConfig {
    const SPEEDS: &[&str] = &["max_speed", "max_velocity", "pref_speed", "desired_speed", "max_speed_factor"];
    const ACCELERATIONS: &[&str] = &["max_force", "max_accel"];
    for spec in config.kind().param_specs() {
        let value = if SPEEDS.contains(&spec.key) || (accelerate && ACCELERATIONS.contains(&spec.key)) {
            spec.max
        } else if accelerate && spec.key == "relaxation_time" {
            spec.min
        } else {
            continue;
        };
        config.set_param(spec.key, serde_json::json!(value)).expect("a value of the table");
    }
    config
}

/// Every planner (Boids with both arbitrations; ORCA and social force heading straight at the
/// goal, into the wall, and down the flow field), at its defaults.
fn planners() -> Vec<(String, PlannerConfig)> {
    let mut out = Vec::new();
    for kind in PlannerKind::ALL {
        match kind {
            PlannerKind::Boids => {
                for arbitration in [Arbitration::Weighted, Arbitration::Priority] {
                    let config = PlannerConfig::Boids(BoidsParams { arbitration, ..BoidsParams::default() });
                    out.push((format!("boids {arbitration:?}"), config));
                }
            }
            PlannerKind::Igsa => {
                // The smallest optimizer: planning a path that does not exist stays quick.
                let mut config = kind.default_config();
                config.set_param("population", serde_json::json!(5)).expect("in the table");
                config.set_param("iterations", serde_json::json!(10)).expect("in the table");
                out.push(("igsa".into(), config));
            }
            PlannerKind::Orca | PlannerKind::SocialForce => {
                for guidance in [Guidance::Goal, Guidance::FlowField] {
                    let mut config = kind.default_config();
                    let name = serde_json::to_value(guidance).expect("a name");
                    config.set_param("guidance", name.clone()).expect("in the table");
                    out.push((format!("{} {name}", kind.name()), config));
                }
            }
            _ => out.push((kind.name().to_string(), kind.default_config())),
        }
    }
    out
}

/// A wall `thickness` px thick across the whole world (beyond both borders) at [`WALL_TOP`],
/// the group spawned above it, its goal below.
fn walled(config: &PlannerConfig, thickness: f32, radius: f32) -> Scene {
    let mut s = Scene::empty(WIDTH, HEIGHT);
    s.px_per_metre = MAX_PX_PER_METRE;
    s.obstacles.push(Obstacle::Rect { min: [-20.0, WALL_TOP], max: [WIDTH + 20.0, WALL_TOP + thickness] });
    s.goals.push(Goal::fixed([WIDTH * 0.5, HEIGHT - 60.0], 40.0));
    s.groups.push(Group {
        name: "fast".into(),
        color: "#336699".into(),
        count: AGENTS,
        spawn: Region { min: [40.0, 20.0], max: [WIDTH - 40.0, 80.0] },
        goal: Some(0),
        agent_radius: radius,
        planner: config.clone(),
    });
    s
}

/// What a run did with the wall: agents that crossed it during the run (a step whose segment
/// from the previous centre to the new one has an end on either side of the wall: the whole
/// wall spans the world, so this is exact), the crossings, the agents on the far side at the
/// end, and the penetrations the metrics counted.
#[derive(Debug, PartialEq)]
struct WallRun {
    crossed_agents: usize,
    crossings: u32,
    beyond_at_end: usize,
    penetrations: u64,
    fastest_move: f32,
}

fn run(scene: Scene, thickness: f32, steps: u32) -> WallRun {
    let mut world = World::new(scene).expect("a valid scene");
    let (top, bottom) = (WALL_TOP, WALL_TOP + thickness);
    let side = |p: Vec2| {
        if p.y <= top {
            -1
        } else if p.y >= bottom {
            1
        } else {
            0
        }
    };
    let mut crossed = vec![false; world.agent_count()];
    let mut crossings = 0;
    let mut fastest_move = 0.0f32;
    for _ in 0..steps {
        let before = world.positions().to_vec();
        world.step();
        for (i, (&a, &b)) in before.iter().zip(world.positions()).enumerate() {
            fastest_move = fastest_move.max(a.distance(b));
            if side(a) * side(b) < 0 {
                crossed[i] = true;
                crossings += 1;
            }
        }
    }
    WallRun {
        crossed_agents: crossed.iter().filter(|&&c| c).count(),
        crossings,
        beyond_at_end: world.positions().iter().filter(|p| side(**p) > 0).count(),
        penetrations: world.metrics().overall.penetrations_agent_obstacle,
        fastest_move,
    }
}

#[test]
fn no_planner_tunnels_through_a_thin_wall_at_its_largest_speed() {
    let mut failures = Vec::new();
    for (name, config) in planners() {
        for accelerate in [false, true] {
            let config = at_largest_speed(config.clone(), accelerate);
            let name = format!("{name}{}", if accelerate { " +accel" } else { "" });
            for thickness in [1.0, 10.0] {
                for radius in [4.0, 0.5] {
                    let r = run(walled(&config, thickness, radius), thickness, steps());
                    let case = format!("{name}, wall {thickness} px, radius {radius}");
                    println!("{case:>50}: {r:?}");
                    if r.crossed_agents > 0 || r.beyond_at_end > 0 || r.penetrations > 0 {
                        failures.push(format!("{case}: {r:?}"));
                    }
                }
            }
        }
    }
    assert!(failures.is_empty(), "tunnelled:\n{}", failures.join("\n"));
}

#[test]
fn a_planner_that_passes_through_obstacles_has_each_crossing_counted() {
    // The original PSO (no acceptance step) walks through obstacles by design (its preset
    // shows the failure): its agents cross, and every crossing is a penetration, although a
    // 1 px wall never holds a centre at the end of a step.
    let config =
        at_largest_speed(PlannerConfig::Pso(PsoParams { acceptance: false, ..PsoParams::default() }), false);
    let r = run(walled(&config, 1.0, 4.0), 1.0, steps());
    println!("pso without acceptance, wall 1 px: {r:?}");
    assert!(r.crossed_agents > AGENTS as usize / 2, "{r:?}");
    assert!(r.penetrations >= u64::from(r.crossings), "{r:?}");
}

#[test]
fn a_wall_with_a_gap_still_lets_fast_agents_through_the_gap() {
    // The stop before a wall must not stop a move that passes beside it: the wall has a 120 px
    // gap in the middle, and ORCA down the flow field at its largest speed goes through it.
    let config = at_largest_speed(PlannerKind::Orca.default_config(), true);
    let mut scene = walled(&config, 1.0, 4.0);
    scene.obstacles = vec![
        Obstacle::Rect { min: [-20.0, WALL_TOP], max: [WIDTH * 0.5 - 60.0, WALL_TOP + 1.0] },
        Obstacle::Rect { min: [WIDTH * 0.5 + 60.0, WALL_TOP], max: [WIDTH + 20.0, WALL_TOP + 1.0] },
    ];
    // Long enough for the crowd to queue through the gap.
    let r = run(scene, 1.0, 3 * steps());
    println!("orca through a 120 px gap: {r:?}");
    assert!(r.beyond_at_end > AGENTS as usize / 2, "{r:?}");
    assert_eq!(r.penetrations, 0, "{r:?}");
}

#[test]
fn a_penetration_is_counted_when_one_is_forced() {
    // An agent placed inside an obstacle is inside it at the end of the step (pushed out of
    // a thick block takes more than one step if it cannot leave by the border it is pressed to).
    let mut scene = walled(&PlannerKind::Boids.default_config(), 10.0, 4.0);
    scene.groups[0].count = 1;
    let mut world =
        World::new_at(scene, vec![Vec2::new(WIDTH * 0.5, WALL_TOP + 5.0)]).expect("a valid scene");
    world.step();
    let inside = world.obstacles().contains(world.positions()[0]);
    let penetrations = world.metrics().overall.penetrations_agent_obstacle;
    assert_eq!(penetrations, u64::from(inside), "inside at the end: {inside}");

    // The recorder counts a way through an obstacle, once per agent and step, but not a wrap
    // across a periodic seam: a recorder fed positions directly.
    let wall = ObstacleIndex::new(
        vec![
            Obstacle::Rect { min: [0.0, 100.0], max: [200.0, 101.0] },
            Obstacle::Rect { min: [100.0, 0.0], max: [101.0, 90.0] },
        ],
        200.0,
        200.0,
    );
    let mut scene = Scene::empty(200.0, 200.0);
    scene
        .groups
        .push(Group { count: 1, ..walled(&PlannerKind::Boids.default_config(), 1.0, 4.0).groups[0].clone() });
    let counted = |band: Option<(f32, f32)>, way: &[[f32; 2]]| {
        let start = vec![Vec2::from(way[0])];
        let mut recorder = MetricsRecorder::new(&scene, &start);
        recorder.set_periodic_x(band);
        let mut grid = SpatialGrid::new(200.0, 200.0, 20.0, 1);
        for (step, &p) in way.iter().enumerate().skip(1) {
            let pos = [Vec2::from(p)];
            grid.rebuild(&pos, &[Vec2::ZERO]);
            recorder.record(step as u32, &pos, &[Vec2::ZERO], &[0], &[4.0], &[None], &grid, &wall, &[]);
        }
        recorder.summary(&scene, &["boids"], way.len() as u32 - 1).overall.penetrations_agent_obstacle
    };
    assert_eq!(counted(None, &[[50.0, 50.0], [50.0, 150.0]]), 1, "a jump over the 1 px wall");
    assert_eq!(counted(None, &[[50.0, 50.0], [50.0, 99.0], [50.0, 99.5]]), 0, "up to the wall");
    assert_eq!(
        counted(None, &[[50.0, 90.0], [50.0, 100.5], [50.0, 150.0]]),
        1,
        "in it at the end of a step, then out"
    );
    assert_eq!(counted(None, &[[50.0, 100.5], [50.0, 150.0]]), 0, "started inside: leaving");
    assert_eq!(counted(None, &[[95.0, 50.0], [105.0, 50.0]]), 1, "a 10 px move over a 1 px wall");
    // Wrapping from x 195 to 5 in the band [0, 200) passes no wall; the same jump outside a
    // band went through the wall at x 100.
    assert_eq!(counted(Some((0.0, 200.0)), &[[195.0, 50.0], [5.0, 50.0]]), 0);
    assert_eq!(counted(None, &[[195.0, 50.0], [5.0, 50.0]]), 1);
}

#[test]
fn a_crowd_pressed_together_at_a_goal_cut_by_a_wall_is_not_pushed_through_it() {
    // Found by the crossing count: a goal that a 1 px wall cuts in two, 60 Boids at their
    // default speed. Bodies arriving at the crowd at rest are pushed out of it, or jump to the
    // nearest free place within ten body diameters, and walkers shoulder others aside: before
    // the way was checked, 5 of them were pushed or jumped through the wall into the goal's far
    // half in 400 steps (8–45 px at once), and one more was shouldered through by step 600.
    let config =
        PlannerConfig::Boids(BoidsParams { arbitration: Arbitration::Priority, ..BoidsParams::default() });
    let mut scene = Scene::empty(600.0, 400.0);
    scene.obstacles.push(Obstacle::Rect { min: [470.0, -20.0], max: [471.0, 420.0] });
    scene.goals.push(Goal::fixed([480.0, 200.0], 40.0));
    scene.groups.push(Group {
        name: "crowd".into(),
        color: "#336699".into(),
        count: 60,
        spawn: Region { min: [20.0, 20.0], max: [250.0, 380.0] },
        goal: Some(0),
        agent_radius: 4.0,
        planner: config,
    });
    let mut world = World::new(scene).expect("a valid scene");
    let mut crossings = 0;
    for _ in 0..800 {
        let before = world.positions().to_vec();
        world.step();
        crossings +=
            before.iter().zip(world.positions()).filter(|(a, b)| (a.x <= 470.0) != (b.x <= 470.0)).count();
    }
    let m = world.metrics();
    assert!(m.overall.arrived_share > 0.2, "the crowd reached the goal: {}", m.overall.arrived_share);
    assert_eq!((crossings, m.overall.penetrations_agent_obstacle), (0, 0));
}
