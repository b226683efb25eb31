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

use flockpath::model::params::{Arbitration, BoidsParams, Guidance};
use flockpath::model::scene::MAX_PX_PER_METRE;
use flockpath::{Goal, Group, Obstacle, PlannerConfig, PlannerKind, Region, Scene, World};
use glam::Vec2;

const WIDTH: f32 = 400.0;
const HEIGHT: f32 = 1200.0;
/// The wall's near face (the group spawns above it, its goal lies below).
const WALL_TOP: f32 = 600.0;
const AGENTS: u32 = 40;

fn steps() -> u32 {
    if cfg!(debug_assertions) {
        200
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

fn run(scene: Scene, thickness: f32) -> WallRun {
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
    for _ in 0..steps() {
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
                    let r = run(walled(&config, thickness, radius), thickness);
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
