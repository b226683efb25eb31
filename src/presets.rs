//! Named scenes: one name→builder table shared by the page, the CLI, the tests and the benches.

use crate::fitness::{Behaviour, Environment};
use crate::geometry::Obstacle;
use crate::planners::PlannerConfig;
use crate::scene::{Goal, GoalMotion, Group, Region, Scene};

/// A named scene builder.
#[derive(Clone, Copy, Debug)]
pub struct Preset {
    /// Stable name (URL, CLI, tests).
    pub name: &'static str,
    /// One-line description shown in the UI.
    pub description: &'static str,
    /// Builds the scene.
    pub build: fn() -> Scene,
}

/// Every preset, in menu order. The first is the page's default scene.
pub const ALL: &[Preset] = &[
    Preset {
        name: "pillars",
        description: "A flock crosses a field of circular pillars to the goal on the right.",
        build: pillars,
    },
    Preset {
        name: "open-field",
        description: "One group crosses an empty field to its goal.",
        build: open_field,
    },
    Preset {
        name: "two-groups-swap",
        description: "Two groups swap sides and pass through each other.",
        build: two_groups_swap,
    },
    Preset {
        name: "corridor",
        description: "A group squeezes through a rectangle-walled passage.",
        build: corridor,
    },
    Preset {
        name: "forces-e1-open",
        description: "Virtual forces, E1: a group follows a moving goal across open space.",
        build: forces_e1_open,
    },
    Preset {
        name: "forces-e2-narrow",
        description: "Virtual forces, E2: a group follows a moving goal through a narrow passage.",
        build: forces_e2_narrow,
    },
    Preset {
        name: "forces-e3-cluttered",
        description: "Virtual forces, E3: a group follows a moving goal among small obstacles.",
        build: forces_e3_cluttered,
    },
];

/// Looks a preset up by name.
pub fn find(name: &str) -> Option<&'static Preset> {
    ALL.iter().find(|p| p.name == name)
}

fn group(name: &str, color: &str, count: u32, spawn: ([f32; 2], [f32; 2]), goal: u32) -> Group {
    Group {
        name: name.into(),
        color: color.into(),
        count,
        spawn: Region { min: spawn.0, max: spawn.1 },
        goal: Some(goal),
        agent_radius: 4.0,
        planner: PlannerConfig::default(),
    }
}

fn base(name: &str, width: f32, height: f32) -> Scene {
    Scene { name: name.into(), ..Scene::empty(width, height) }
}

/// One group crosses an empty field.
pub fn open_field() -> Scene {
    let mut s = base("open-field", 800.0, 500.0);
    s.goals.push(Goal::fixed([700.0, 250.0], 40.0));
    s.groups.push(group("flock", "#2f6fdf", 60, ([40.0, 150.0], [160.0, 350.0]), 0));
    s
}

/// A flock crossing a staggered field of pillars.
pub fn pillars() -> Scene {
    let mut s = base("pillars", 900.0, 560.0);
    for col in 0..4 {
        for row in 0..4 {
            let x = 300.0 + col as f32 * 100.0;
            let y = 110.0 + row as f32 * 110.0 + if col % 2 == 1 { 55.0 } else { 0.0 };
            s.obstacles.push(Obstacle::Circle { center: [x, y], radius: 22.0 });
        }
    }
    s.goals.push(Goal::fixed([830.0, 280.0], 40.0));
    s.groups.push(group("flock", "#2f6fdf", 80, ([30.0, 170.0], [170.0, 390.0]), 0));
    s
}

/// Two groups swap sides.
pub fn two_groups_swap() -> Scene {
    let mut s = base("two-groups-swap", 900.0, 500.0);
    s.goals.push(Goal::fixed([820.0, 250.0], 40.0));
    s.goals.push(Goal::fixed([80.0, 250.0], 40.0));
    s.groups.push(group("left", "#2f6fdf", 50, ([30.0, 150.0], [150.0, 350.0]), 0));
    s.groups.push(group("right", "#df4f2f", 50, ([750.0, 150.0], [870.0, 350.0]), 1));
    s
}

/// A group squeezes through a passage between two rectangular walls.
pub fn corridor() -> Scene {
    let mut s = base("corridor", 900.0, 500.0);
    s.obstacles.push(Obstacle::Rect { min: [350.0, 0.0], max: [550.0, 205.0] });
    s.obstacles.push(Obstacle::Rect { min: [350.0, 295.0], max: [550.0, 500.0] });
    s.goals.push(Goal::fixed([820.0, 250.0], 40.0));
    s.groups.push(group("flock", "#2f9f5f", 60, ([30.0, 100.0], [200.0, 400.0]), 0));
    s
}

/// E1 with the following behaviour (B2).
pub fn forces_e1_open() -> Scene {
    forces_scene(Behaviour::Following, Environment::Open)
}

/// E2 with the following behaviour (B2).
pub fn forces_e2_narrow() -> Scene {
    forces_scene(Behaviour::Following, Environment::Narrow)
}

/// E3 with the following behaviour (B2).
pub fn forces_e3_cluttered() -> Scene {
    forces_scene(Behaviour::Following, Environment::Cluttered)
}

/// Agents in every scene of the virtual-force experiment.
pub const FORCES_AGENTS: u32 = 30;

/// A scene of the virtual-force experiment (DESIGN §3.5): an 800×400 world, 30 agents with the
/// `forces` planner on the left, heading right. B1 heads for a fixed goal on the right; B2 and
/// B3 go with a goal that moves along the middle line (1.2 and 0.8 px/step).
pub fn forces_scene(behaviour: Behaviour, environment: Environment) -> Scene {
    let name = format!("forces-{}-{}", behaviour.code(), environment.code());
    let mut s = base(&name, 800.0, 400.0);
    match environment {
        Environment::Open => {}
        Environment::Narrow => {
            // A wall across the world with one 50 px gap (about six bodies wide).
            s.obstacles.push(Obstacle::Rect { min: [370.0, 0.0], max: [430.0, 175.0] });
            s.obstacles.push(Obstacle::Rect { min: [370.0, 225.0], max: [430.0, 400.0] });
        }
        Environment::Cluttered => {
            // Small pillars (radius 8 px) on a staggered 50 px lattice.
            for col in 0..9 {
                let x = 230.0 + col as f32 * 50.0;
                let offset = if col % 2 == 1 { 25.0 } else { 0.0 };
                for row in 0..8 {
                    let y = 30.0 + offset + row as f32 * 50.0;
                    if y < 390.0 {
                        s.obstacles.push(Obstacle::Circle { center: [x, y], radius: 8.0 });
                    }
                }
            }
        }
    }
    let mut flock = group("flock", "#8f3fbf", FORCES_AGENTS, ([40.0, 140.0], [160.0, 260.0]), 0);
    flock.planner = PlannerConfig::Forces(crate::planners::ForcesParams::default());
    match behaviour {
        Behaviour::GroupMoving => s.goals.push(Goal::fixed([730.0, 200.0], 40.0)),
        Behaviour::Following | Behaviour::Guarding => {
            let speed = if behaviour == Behaviour::Following { 1.2 } else { 0.8 };
            s.goals.push(Goal {
                position: [180.0, 200.0],
                radius: 20.0,
                motion: Some(GoalMotion::Polyline { points: vec![[180.0, 200.0], [740.0, 200.0]], speed }),
            });
            flock.spawn = Region { min: [60.0, 140.0], max: [170.0, 260.0] };
        }
    }
    s.groups.push(flock);
    s
}

/// A square world of `n` wandering agents at constant density, about `neighbours` agents inside
/// each agent's perception radius (benchmarks: per-agent cost should not grow with `n`).
pub fn constant_density(n: u32, neighbours: f32) -> Scene {
    let perception = crate::planners::BoidsParams::default().perception_radius;
    let density = neighbours / (std::f32::consts::PI * perception * perception);
    let side = (n as f32 / density).sqrt().max(100.0);
    let mut s = base(&format!("density-{n}"), side, side);
    let mut g = group("crowd", "#2f6fdf", n, ([0.0, 0.0], [side, side]), 0);
    g.goal = None;
    s.groups.push(g);
    s
}
